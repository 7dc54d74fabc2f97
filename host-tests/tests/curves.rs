//! Ellipse G02.1/G03.1 (2.4) and parabola G02.2/G03.2 (2.5): every cut ends on the
//! analytic curve (checked here with the curve's own equation), chords stay within
//! the chord tolerance, the last cut ends exactly on the programmed point, and the
//! curve turns the way the code says.

use host_tests::{Run, run};
use interp_core::canon::Action;

/// (Z, X radius) in mm of every linear move on `line`, after the move before it.
fn cuts(r: &Run, line: u32) -> Vec<(f64, f64)> {
    r.actions
        .iter()
        .filter(|c| c.line == line && matches!(c.action, Action::Linear(_)))
        .filter_map(host_tests::xz)
        .map(|(x, z)| (z, x / 2.0))
        .collect()
}

fn ok(text: &str) -> Run {
    let r = run(text);
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    r
}

/// Turns (Z, X) by Q counter-clockwise: the long axis (Q clockwise from +Z) onto +s.
fn turn(q_deg: f64, p: (f64, f64)) -> (f64, f64) {
    let (c, s) = (q_deg.to_radians().cos(), q_deg.to_radians().sin());
    (p.0 * c - p.1 * s, p.0 * s + p.1 * c)
}

/// Centres (s, t) of the ellipses with semi-axes a, b (along s, t) through p, q.
fn ellipse_centres(p: (f64, f64), q: (f64, f64), a: f64, b: f64) -> Vec<(f64, f64)> {
    // Stretch t by a/b: circles of radius a; intersect the circles around p and q.
    let (p, q) = ((p.0, p.1 * a / b), (q.0, q.1 * a / b));
    let d = ((q.0 - p.0).powi(2) + (q.1 - p.1).powi(2)).sqrt();
    let h = (a * a - d * d / 4.0).sqrt();
    let m = ((p.0 + q.0) / 2.0, (p.1 + q.1) / 2.0);
    let u = ((q.0 - p.0) / d, (q.1 - p.1) / d);
    [1.0, -1.0].iter().map(|k| (m.0 - k * h * u.1, (m.1 + k * h * u.0) * b / a)).collect()
}

fn cross(o: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
}

#[test]
fn figure_2_8_ellipse_from_d43_14_to_d63_82() {
    let r = ok("G00 X43.14 Z0\nG02.1 X63.82 Z-50.0 A48 B25 Q60000 F100\nM30\n");
    let pts = cuts(&r, 2);
    assert!(pts.len() > 20, "{}", pts.len());
    assert_eq!(*pts.last().unwrap(), (-50.0, 31.91), "the last cut ends on the programmed point");
    let (a, b, q) = (48.0, 25.0, 60.0);
    let (s0, s1) = (turn(q, (0.0, 21.57)), turn(q, (-50.0, 31.91)));
    let on = |c: (f64, f64), p: (f64, f64)| {
        let t = turn(q, p);
        ((t.0 - c.0) / a).powi(2) + ((t.1 - c.1) / b).powi(2) - 1.0
    };
    // The centre whose ellipse holds every cut's end point.
    let c = ellipse_centres(s0, s1, a, b)
        .into_iter()
        .find(|&c| pts.iter().all(|&p| on(c, p).abs() < 1e-7))
        .expect("all points on one ellipse A48 B25 turned 60°");
    // Chord midpoints stay within the chord tolerance (1 µm): the residual of the
    // ellipse equation near the curve is about 2·distance/B at most.
    let mut prev = (0.0, 21.57);
    for &p in &pts {
        let mid = ((prev.0 + p.0) / 2.0, (prev.1 + p.1) / 2.0);
        assert!(on(c, mid).abs() * a / 2.0 < 0.0011, "chord to {p:?} strays");
        prev = p;
    }
    // G02.1 turns clockwise.
    let mut all = vec![(0.0, 21.57)];
    all.extend(pts);
    assert!(all.windows(3).all(|w| cross(w[0], w[1], w[2]) < 0.0));
    // Q with a decimal point is in degrees.
    let r2 = ok("G00 X43.14 Z0\nG02.1 X63.82 Z-50.0 A48 B25 Q60. F100\nM30\n");
    assert_eq!(cuts(&r2, 2), cuts(&r, 2));
}

#[test]
fn g03_1_turns_counter_clockwise_on_the_other_ellipse() {
    let r = ok("G00 X43.14 Z0\nG03.1 X63.82 Z-50.0 A48 B25 Q60000 F100\nM30\n");
    let mut all = vec![(0.0, 21.57)];
    all.extend(cuts(&r, 2));
    assert!(all.windows(3).all(|w| cross(w[0], w[1], w[2]) > 0.0));
    assert_eq!(*all.last().unwrap(), (-50.0, 31.91));
}

#[test]
fn figure_2_10_parabola_p10_along_z() {
    let r = ok("G00 X120 Z100 T0101 M03 S800\nG00 X0 Z0 M08\nG01 X30 F200\nG3.2 X60 Z-40 P10\nG01 X90 Z-60\nM30\n");
    let pts = cuts(&r, 4);
    assert_eq!(*pts.last().unwrap(), (-40.0, 30.0));
    // Axis along Z: (x − x0)² = 2P·σ(z − z0); through (z0, r15) and (z-40, r30).
    let p = 10.0;
    let fit = |sigma: f64| {
        let t0 = (15.0f64.powi(2) - 30.0f64.powi(2) - 2.0 * p * sigma * (0.0 + 40.0)) / (2.0 * (15.0 - 30.0));
        let s0 = 0.0 - sigma * (15.0 - t0).powi(2) / (2.0 * p);
        move |q: (f64, f64)| q.0 - (s0 + sigma * (q.1 - t0).powi(2) / (2.0 * p))
    };
    let ccw = fit(-1.0);
    assert!(pts.iter().all(|&q| ccw(q).abs() < 2e-6), "all points on the parabola opening to -Z");
    let mut all = vec![(0.0, 15.0)];
    all.extend(pts.iter().copied());
    assert!(all.windows(3).all(|w| cross(w[0], w[1], w[2]) > 0.0), "G03.2 turns counter-clockwise");
    // Chords within 1 µm: the parabola's z at the chord midpoint's x.
    for w in all.windows(2) {
        let mid = ((w[0].0 + w[1].0) / 2.0, (w[0].1 + w[1].1) / 2.0);
        assert!(ccw(mid).abs() < 0.0011, "{mid:?}");
    }
    // G02.2 takes the parabola opening the other way.
    let r = ok("G00 X30 Z0\nG02.2 X60 Z-40 P10 F200\nM30\n");
    let cw = fit(1.0);
    assert!(cuts(&r, 2).iter().all(|&q| cw(q).abs() < 2e-6));
}

#[test]
fn end_points_off_every_curve_raise_alarm_0020_and_words_are_required() {
    let cases: &[(&str, u32, u16)] = &[
        ("G00 X0 Z0\nG02.1 X0 Z-200 A10 B5 F100\nM30\n", 2, 20),
        ("G00 X30 Z0\nG02.2 X30 Z-10 P10 F100\nM30\n", 2, 20),
        ("G00 X30 Z0\nG02.1 X40 Z-10 A10 F100\nM30\n", 2, 4006),
        ("G00 X30 Z0\nG02.2 X40 Z-10 F100\nM30\n", 2, 4006),
        ("G00 X30 Z0\nG02.2 X40 Z-10 P10 R1 F100\nM30\n", 2, 4005),
        ("G17\nG00 X30 Z0\nG02.1 X40 Z-10 A10 B5 F100\nM30\n", 3, 4031),
    ];
    for &(text, line, code) in cases {
        assert_eq!(run(text).alarm_codes().first(), Some(&(line, code)), "{text}");
    }
}

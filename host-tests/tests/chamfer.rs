//! Chamfer and corner R, `,C` / `,R` (2.23): the inserted blocks computed by hand
//! from the figures' dimensions, every note and its alarm.

use host_tests::{Run, kind_names, moves, run};
use interp_core::canon::{Action, ArcMove};

/// (Z, X radius) in mm of a point given as (X diameter, Z).
fn zr(p: (f64, f64)) -> (f64, f64) {
    (p.1, p.0 / 2.0)
}

fn dist(p: (f64, f64), q: (f64, f64)) -> f64 {
    (p.0 - q.0).hypot(p.1 - q.1)
}

fn ok(text: &str) -> Run {
    let r = run(text);
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    r
}

fn arcs(r: &Run) -> Vec<(u32, ArcMove)> {
    r.actions.iter().filter_map(|c| if let Action::Arc(a) = c.action { Some((c.line, a)) } else { None }).collect()
}

/// Centre of an arc as (Z, X radius) mm.
fn centre(a: &ArcMove) -> (f64, f64) {
    (a.center.work.0[2] as f64 / 1e6, a.center.work.0[0] as f64 / 1e6)
}

fn close(a: (f64, f64), b: (f64, f64)) -> bool {
    dist(a, b) < 2e-6
}

#[test]
fn figure_2_82_chamfer_between_two_lines() {
    // Along -Z at Ø20 to Z-20, then up to Ø40: C2 cuts 2 mm off each side of the
    // imaginary corner (Z-20, Ø20).
    let r = ok("G00 X20 Z0\nG01 Z-20 ,C2 F100\nX40\nM30\n");
    assert_eq!(moves(&r), vec![('r', 20.0, 0.0), ('l', 20.0, -18.0), ('l', 24.0, -20.0), ('l', 40.0, -20.0)]);
    // The chamfer belongs to the ,C block (single block stops at its end, note 6).
    assert_eq!(r.actions[2].line, 2);
}

#[test]
fn figure_2_83_corner_r_between_two_lines() {
    let r = ok("G00 X20 Z0\nG01 Z-20 ,R3 F100\nX40\nM30\n");
    assert_eq!(moves(&r), vec![('r', 20.0, 0.0), ('l', 20.0, -17.0), ('a', 26.0, -20.0), ('l', 40.0, -20.0)]);
    let (line, a) = arcs(&r)[0];
    assert_eq!(line, 2);
    // Centre 3 mm inside both lines: Z-17, radius 13; turning from -Z to +X is
    // clockwise in the ZX plane (G02).
    assert!(close(centre(&a), (-17.0, 13.0)));
    assert!(a.cw);
}

#[test]
fn chamfer_on_a_taper_is_measured_along_each_line() {
    // 45° taper down to the corner then along -Z: points 2 mm from the corner on each.
    let r = ok("G00 X10 Z0\nG01 X30 Z-10 ,C2 F100\nZ-30\nM30\n");
    let p = r.actions.iter().filter_map(host_tests::xz).map(zr).collect::<Vec<_>>();
    let corner = (-10.0, 15.0);
    assert!((dist(p[1], corner) - 2.0).abs() < 1e-6);
    assert!((dist(p[2], corner) - 2.0).abs() < 1e-6);
    assert!(close(p[2], (-12.0, 15.0)));
    // p[1] lies on the taper r = 5 - z.
    assert!((p[1].1 - (5.0 - p[1].0)).abs() < 1e-6);
}

/// Line along -Z at radius 10 to Z-20, then G03 to (Z-30, r20) around (Z-30, r10).
const LINE_ARC: &str = "G00 X20 Z0\nG01 Z-20 {} F100\nG03 X40 Z-30 R10\nM30\n";

#[test]
fn corner_r_between_a_line_and_an_arc_is_tangent_to_both() {
    let r = ok(&LINE_ARC.replace("{}", ",R2"));
    let a = arcs(&r);
    assert_eq!(a.len(), 2);
    let (_, fillet) = a[0];
    // Independently: the centre lies 2 mm off the line (radius 12) and 10 + 2 mm
    // from the arc centre (the fillet is outside the arc's circle).
    let c = (-30.0, 10.0);
    let f = (-30.0 + (144.0f64 - 4.0).sqrt(), 12.0);
    assert!(close(centre(&fillet), f), "{:?} vs {f:?}", centre(&fillet));
    let p = r.actions.iter().filter_map(host_tests::xz).map(zr).collect::<Vec<_>>();
    // p[1]: end of the cut-back line, foot of the centre on the line.
    assert!(close(p[1], (f.0, 10.0)));
    // p[2]: end of the fillet, on the arc's circle on the line centre→fillet centre.
    let k = 10.0 / 12.0;
    assert!(close(p[2], (c.0 + (f.0 - c.0) * k, c.1 + (f.1 - c.1) * k)));
    assert!((dist(p[2], c) - 10.0).abs() < 1e-6 && (dist(p[2], f) - 2.0).abs() < 1e-6);
    assert!(fillet.cw);
    // The programmed arc keeps its centre and end point.
    assert!(close(centre(&a[1].1), c));
    assert!(close(p[3], (-30.0, 20.0)));
}

#[test]
fn chamfer_between_a_line_and_an_arc_ends_on_the_arc_2_mm_from_the_corner() {
    let r = ok(&LINE_ARC.replace("{}", ",C2"));
    let p = r.actions.iter().filter_map(host_tests::xz).map(zr).collect::<Vec<_>>();
    let corner = (-20.0, 10.0);
    assert!(close(p[1], (-18.0, 10.0)));
    assert!((dist(p[2], corner) - 2.0).abs() < 1e-6);
    assert!((dist(p[2], (-30.0, 10.0)) - 10.0).abs() < 1e-6);
    // On the arc's side of the corner (it climbs from the corner towards -Z, +X).
    assert!(p[2].0 < -20.0 && p[2].1 > 10.0);
    assert_eq!(kind_names(&r)[1..4], ["linear", "linear", "arc"]);
}

#[test]
fn corner_r_between_an_arc_and_a_line() {
    // G02 from (Z0, r10) to (Z-10, r20) around (Z0, r20) arrives heading +X; the
    // line then runs along -Z: a left turn, so the fillet lies outside the arc's
    // circle (radius 10 + 2) and 2 mm below the line (r18).
    let r = ok("G00 X20 Z0\nG02 X40 Z-10 R10 F100 ,R2\nG01 Z-30\nM30\n");
    let a = arcs(&r);
    assert_eq!(a.len(), 2);
    let c = (0.0, 20.0);
    assert!(close(centre(&a[0].1), c));
    let (_, fillet) = a[1];
    let f = (-(144.0f64 - 4.0).sqrt(), 18.0);
    assert!(close(centre(&fillet), f), "{:?}", centre(&fillet));
    assert!(!fillet.cw);
    let p = r.actions.iter().filter_map(host_tests::xz).map(zr).collect::<Vec<_>>();
    let k = 10.0 / 12.0;
    assert!(close(p[1], (c.0 + (f.0 - c.0) * k, c.1 + (f.1 - c.1) * k)));
    assert!(close(p[2], (f.0, 20.0)));
    assert!(close(p[3], (-30.0, 20.0)));
}

#[test]
fn corner_r_between_two_arcs() {
    // G03 (Z0,r10)→(Z-10,r20) around (Z-10,r10) arrives heading -Z; G02 on to
    // (Z-20,r10) around (Z-20,r20) leaves heading -X: a left turn. The fillet R1 is
    // inside the first circle (10 - 1) and outside the second (10 + 1).
    let r = ok("G00 X20 Z0\nG03 X40 Z-10 R10 F100 ,R1\nG02 X20 Z-20 R10\nM30\n");
    let a = arcs(&r);
    assert_eq!(a.len(), 3);
    let (c1, c2) = ((-10.0, 10.0), (-20.0, 20.0));
    assert!(close(centre(&a[0].1), c1) && close(centre(&a[2].1), c2));
    let f = centre(&a[1].1);
    assert!((dist(f, c1) - 9.0).abs() < 1e-6 && (dist(f, c2) - 11.0).abs() < 1e-6, "{f:?}");
    assert!(!a[1].1.cw);
    let p = r.actions.iter().filter_map(host_tests::xz).map(zr).collect::<Vec<_>>();
    assert!((dist(p[1], c1) - 10.0).abs() < 1e-6 && (dist(p[1], f) - 1.0).abs() < 1e-6);
    assert!((dist(p[2], c2) - 10.0).abs() < 1e-6 && (dist(p[2], f) - 1.0).abs() < 1e-6);
    // Near the corner (Z-10, r20), not the other crossing of the offset circles.
    assert!(dist(p[1], (-10.0, 20.0)) < 2.0 && dist(p[2], (-10.0, 20.0)) < 2.0);
}

#[test]
fn consecutive_corners_and_a_dwell_between() {
    // Note: two or more corner blocks in a row; one G04 may stand between, and the
    // dwell comes after the inserted block.
    let r = ok("G00 X20 Z0\nG01 Z-20 ,C1 F100\nG04 P500\nX40 ,R2\nZ-40\nM30\n");
    assert_eq!(kind_names(&r), ["rapid", "linear", "linear", "dwell 500", "linear", "arc", "linear", "end true"]);
    assert_eq!(
        moves(&r),
        vec![
            ('r', 20.0, 0.0),
            ('l', 20.0, -19.0),
            ('l', 22.0, -20.0),
            ('l', 36.0, -20.0),
            ('a', 40.0, -22.0),
            ('l', 40.0, -40.0)
        ]
    );
}

#[test]
fn note_1_chamfer_on_g00_is_ignored_and_note_9_the_last_word_wins() {
    let r = ok("G00 X20 Z0 ,C2\nZ-20\nG01 X40 ,C1 ,R2 F100\nZ-40\nM30\n");
    assert_eq!(moves(&r)[..2], [('r', 20.0, 0.0), ('r', 20.0, -20.0)]);
    assert_eq!(kind_names(&r)[2..5], ["linear", "arc", "linear"]);
    let r = ok("G00 X20 Z-20\nG01 X40 ,R2 ,C1 F100\nZ-40\nM30\n");
    assert_eq!(kind_names(&r)[1..4], ["linear", "linear", "linear"]);
}

#[test]
fn note_5_lines_within_1_degree_get_no_corner() {
    // 0.5° between the lines: the corner block has no length.
    let r = ok("G00 X20 Z0\nG01 Z-20 ,C1 F100\nU0.1745 W-10\nM30\n");
    assert_eq!(moves(&r)[1..], [('l', 20.0, -20.0), ('l', 20.175, -30.0)]);
}

#[test]
fn alarms_of_the_notes() {
    let cases: &[(&str, u32, u16)] = &[
        // Note 2: the next block must move with G01/G02/G03.
        ("G00 X20 Z0\nG01 Z-20 ,C1 F100\nG00 X40\nM30\n", 3, 51),
        ("G00 X20 Z0\nG01 Z-20 ,C1 F100\nM30\n", 3, 51),
        ("G00 X20 Z0\nG01 Z-20 ,C1 F100\nM08\nX40\nM30\n", 3, 51),
        ("G00 X20 Z0\nG01 Z-20 ,C1 F100\nG04 P1\nG04 P1\nX40\nM30\n", 4, 51),
        // Note 7: group 00 in the block or between.
        ("G00 X20 Z0\nG01 Z-20 ,C1 F100\nG28 U0\nM30\n", 3, 51),
        ("G00 X20 Z0\nG28 U0 ,C1\nM30\n", 2, 51),
        // Note 3: larger than the moves.
        ("G00 X20 Z0\nG01 Z-20 ,C1 F100\nX21\nM30\n", 3, 55),
        ("G00 X20 Z0\nG01 Z-1 ,R5 F100\nX40\nM30\n", 3, 55),
        // Note 4: plane selection after.
        ("G00 X20 Z0\nG01 Z-20 ,C1 F100\nG17 X40\nM30\n", 3, 212),
        // Note 8: thread blocks.
        ("G00 X20 Z0\nM03 S500\nG32 Z-20 F1 ,C1\nM30\n", 3, 50),
        ("G00 X20 Z0\nM03 S500\nG92 X18 Z-20 F1 ,C1\nM30\n", 3, 50),
    ];
    for &(text, line, code) in cases {
        let r = run(text);
        assert_eq!(r.alarm_codes().first(), Some(&(line, code)), "{text}");
    }
}

#[test]
fn an_alarm_after_a_chamfer_block_runs_the_held_move_to_its_end_first() {
    // The held Z-20 belongs to a good block: it runs before the machine stops, to
    // its programmed end (its chamfer needed the faulty G00 block), and the failed
    // block changes nothing else: going on (as `lathe check` does), G01 is in force.
    let r = run("G00 X20 Z0\nG01 Z-20 ,C2 F100\nG00 X40\nX40\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(3, 51)]);
    assert_eq!(moves(&r)[1..], [('l', 20.0, -20.0), ('l', 40.0, -20.0)]);
    assert_eq!(r.actions.iter().filter(|c| c.action.endpoint().is_some()).nth(1).map(|c| c.line), Some(2));
}

#[test]
fn chamfers_in_a_g71_shape_are_roughed_and_finished() {
    let prog = "G00 X62 Z2\nG71 U1 R0.5 F200\nG71 P10 Q20 U0 W0\nN10 G00 X20\nG01 Z-10 ,C2\nX40 ,R3\nN20 Z-30\nG70 P10 Q20\nM30\n";
    let r = ok(prog);
    // G70 replays the shape with its corners: the last cut is the finish pass.
    let fin: Vec<_> = r.actions.iter().filter(|c| c.line == 8).filter_map(host_tests::xz).collect();
    let fin: Vec<_> =
        fin.iter().map(|&(x, z)| ((x * 1000.0).round() / 1000.0, (z * 1000.0).round() / 1000.0)).collect();
    assert_eq!(
        fin,
        vec![(20.0, 2.0), (20.0, -8.0), (24.0, -10.0), (34.0, -10.0), (40.0, -13.0), (40.0, -30.0), (62.0, 2.0)]
    );
    // Roughing never cuts into the chamfer: between Z-8 and Z-10 the shape is
    // r = 2 - z, and no end point of a roughing move lies below it.
    let rough = r.actions.iter().filter(|c| c.line == 3 && matches!(c.action, Action::Linear(_)));
    let mut on_chamfer = 0;
    for (x, z) in rough.filter_map(host_tests::xz).filter(|&(_, z)| z < -8.0 && z > -10.0) {
        assert!(x / 2.0 >= 2.0 - z - 1e-6, "({x}, {z})");
        on_chamfer += ((x / 2.0 - (2.0 - z)).abs() < 1e-6) as u32;
    }
    assert!(on_chamfer > 0, "roughing passes end on the chamfer");
}

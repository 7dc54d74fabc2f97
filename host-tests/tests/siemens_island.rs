//! SINUMERIK CYCLE73 pocket milling with islands on the mill (seed 001 lines
//! 6150-7392): CYCLE74/CYCLE75 transfer the pocket's edge and islands, CYCLE73
//! clears, finishes or pre-drills the pocket minus its islands. The document's
//! example 1 is built here from its program text (the RND fillets computed in
//! the test), the cutter's swept area rasterised and measured against it.

mod mill_common;

use mill_common::plane::*;

/// T5 radius 4 (the document's second listing), T2 radius 5, T3 radius 6.
const HEAD: &str = "$TC_DP1[5,1]=120 $TC_DP6[5,1]=4\n$TC_DP1[2,1]=120 $TC_DP6[2,1]=5\n\
    $TC_DP1[3,1]=120 $TC_DP6[3,1]=6\nT5 D1\nM6\nS500 M3 F2000\nG17 G0 G90 G94 X0 Y0 Z20\n";

/// Example 1's edge and islands (lines 6886-6901) as label sections after M02.
const CONTOURS: &str = "M02\n\
    N510 _RAND:G0 G64 X25 Y30\nN520 G1 X118 RND=5\nN530 Y96 RND=5\nN540 X40 RND=5\n\
    N545 X20 Y75 RND=5\nN550 Y35\nN560 _ENDRAND:G3 X25 Y30 CR=5\n\
    N570 _INSEL1:G0 X34 Y58\nN580 G1 X64\nN590 _ENDINSEL1:G2 X34 Y58 CR=15\n\
    N600 _INSEL2:G0 X79 Y73\nN610 G1 X99\nN620 _ENDINSEL2:G3 X79 Y73 CR=10\n";

/// The transfer of example 1's contours.
const TRANSFER: &str = "CYCLE74 (\"\", \"_RAND\", \"_ENDRAND\")\nCYCLE75 (\"\", \"_INSEL1\", \"_ENDINSEL1\")\n\
    CYCLE75 (\"\", \"_INSEL2\", \"_ENDINSEL2\")\n";

/// Example 1's clearing call (line 6913): VARI 1021, RTP 10, RFP 0, SDIS 1,
/// DP −17.5, MIDA 2, FAL 0.5, FFP1 9000, FFD 3000, CDIR 0, RAD 4, DP1 3.
const ROUGH: &str = "1021, \"\", \"BEISPIEL1_MILL1\", \"5\", 10, 0, 1, -17.5, 0, , 2, 0.5, , 9000, 3000, 0, , , 4, 3";

/// `HEAD`, then `body`, then the contours; the line of the first line of `body`.
fn program(body: &str) -> (String, u32) {
    (format!("{HEAD}{body}{CONTOURS}"), HEAD.lines().count() as u32 + 1)
}

/// The alarm of `body`'s line `k` (0: its first), and nothing moved on that line.
fn alarm_at(body: &str, k: u32) -> u16 {
    let (text, first) = program(body);
    let r = siemens(&text);
    let line = first + k;
    let codes = r.alarm_codes();
    assert_eq!(codes.len(), 1, "{body}: {codes:?}");
    assert_eq!(codes[0].0, line, "{body}: {codes:?}");
    assert!(!r.actions.iter().any(|c| c.line == line && c.action.endpoint().is_some()), "{body} moved");
    codes[0].1
}

/// The transfer's alarms, on the transferring call's line.
#[test]
fn transfer_alarms_move_nothing() {
    // CYCLE73 or CYCLE75 with no CYCLE74 before: no contour.
    assert_eq!(alarm_at(&format!("CYCLE73({ROUGH})\n"), 0), 61900);
    assert_eq!(alarm_at("CYCLE75 (\"\", \"_INSEL1\", \"_ENDINSEL1\")\n", 0), 61900);
    // Nothing named: the edge's or the island's contour wrong.
    assert_eq!(alarm_at("CYCLE74 (\"\", \"\", \"\")\n", 0), 61983);
    assert_eq!(alarm_at("CYCLE74 (\"\", \"_RAND\", \"_ENDRAND\")\nCYCLE75 (\"\", \"\", \"\")\n", 1), 61980);
    // A label that is not there (the labels' own alarm).
    let code = alarm_at("CYCLE74 (\"\", \"_RAND\", \"_NOWHERE\")\n", 0);
    assert_eq!(code, alarm_at("GOTOF _NOWHERE\n", 0));
    // The edge and 15 islands fit; a 16th island is 61906.
    let mut body = String::from("CYCLE74 (\"\", \"_RAND\", \"_ENDRAND\")\n");
    for _ in 0..15 {
        body.push_str("CYCLE75 (\"\", \"_INSEL1\", \"_ENDINSEL1\")\n");
    }
    body.push_str("CYCLE75 (\"\", \"_INSEL2\", \"_ENDINSEL2\")\n");
    assert_eq!(alarm_at(&body, 16), 61906);
}

/// CYCLE73's own checks, on its line, before anything moves.
#[test]
fn cycle73_alarms_move_nothing() {
    let call = |args: &str| format!("{TRANSFER}CYCLE73({args})\n");
    let with = |i: usize, v: &str| {
        let mut a: Vec<String> = ROUGH.split(", ").map(str::to_string).collect();
        a[i] = v.to_string();
        call(&a.join(", "))
    };
    for (body, code) in [
        (with(3, "\"\""), 61984),
        (with(2, "\"\""), 61988),
        (with(0, "1015"), 61985),
        (with(10, "7"), 61982),
        (with(0, "1023"), 61002),
        (with(0, "1041"), 61002),
        (with(0, "3021"), 61002),
        (with(0, "1026"), 61002),
        (with(18, "0"), 61909),
        (with(19, "0"), 61108),
        (with(15, "5"), 61109),
        (with(7, "5"), 61101),
        // Rest material with tool 5 (radius 4) after tool 2 (radius 5) is fine; after
        // itself it has nothing smaller to follow.
        (with(0, "1012"), 61918),
    ] {
        assert_eq!(alarm_at(&body, 3), code, "{body}");
    }
    // D2 is not D1.
    let (text, first) = program(&call(ROUGH));
    let r = siemens(&text.replace("T5 D1", "T5 D2"));
    assert_eq!(r.alarm_codes(), vec![(first + 3, 61989)]);
}

/// One element of a contour in the plane (mm): a line, or an arc about `c`.
#[derive(Clone, Copy, Debug)]
enum El {
    Line([f64; 2], [f64; 2]),
    /// Start, end, centre, clockwise.
    Arc([f64; 2], [f64; 2], [f64; 2], bool),
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn len(a: [f64; 2]) -> f64 {
    a[0].hypot(a[1])
}

fn seg_dist(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let d = sub(b, a);
    let l2 = d[0] * d[0] + d[1] * d[1];
    let t = if l2 == 0.0 { 0.0 } else { ((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / l2 };
    let t = t.clamp(0.0, 1.0);
    len(sub(p, [a[0] + t * d[0], a[1] + t * d[1]]))
}

/// Whether angle `a` lies on the arc from `a0` sweeping `sweep` (radians).
fn on_sweep(a: f64, a0: f64, sweep: f64) -> bool {
    let tau = std::f64::consts::TAU;
    let rel = if sweep >= 0.0 { (a - a0).rem_euclid(tau) } else { (a0 - a).rem_euclid(tau) };
    rel <= sweep.abs() + 1e-12
}

impl El {
    fn sweep(s: [f64; 2], e: [f64; 2], c: [f64; 2], cw: bool) -> (f64, f64) {
        let a0 = (s[1] - c[1]).atan2(s[0] - c[0]);
        let a1 = (e[1] - c[1]).atan2(e[0] - c[0]);
        let tau = std::f64::consts::TAU;
        let mut sw = a1 - a0;
        if cw {
            sw = -((a0 - a1).rem_euclid(tau));
            if sw == 0.0 {
                sw = -tau;
            }
        } else {
            sw = sw.rem_euclid(tau);
            if sw == 0.0 {
                sw = tau;
            }
        }
        (a0, sw)
    }

    fn dist(&self, p: [f64; 2]) -> f64 {
        match *self {
            El::Line(a, b) => seg_dist(p, a, b),
            El::Arc(s, e, c, cw) => {
                let (a0, sw) = El::sweep(s, e, c, cw);
                let r = len(sub(s, c));
                let a = (p[1] - c[1]).atan2(p[0] - c[0]);
                if on_sweep(a, a0, sw) { (len(sub(p, c)) - r).abs() } else { len(sub(p, s)).min(len(sub(p, e))) }
            }
        }
    }

    /// Points along the element, about every 0.05 mm.
    fn points(&self) -> Vec<[f64; 2]> {
        match *self {
            El::Line(a, b) => {
                let n = (len(sub(b, a)) / 0.05).ceil().max(1.0) as usize;
                (0..n)
                    .map(|k| [a[0] + (b[0] - a[0]) * k as f64 / n as f64, a[1] + (b[1] - a[1]) * k as f64 / n as f64])
                    .collect()
            }
            El::Arc(s, _, c, cw) => {
                let (a0, sw) = El::sweep(s, self.end(), c, cw);
                let r = len(sub(s, c));
                let n = (r * sw.abs() / 0.05).ceil().max(1.0) as usize;
                (0..n)
                    .map(|k| {
                        let a = a0 + sw * k as f64 / n as f64;
                        [c[0] + r * a.cos(), c[1] + r * a.sin()]
                    })
                    .collect()
            }
        }
    }

    fn end(&self) -> [f64; 2] {
        match *self {
            El::Line(_, b) | El::Arc(_, b, _, _) => b,
        }
    }
}

/// A closed contour of lines through `corners`, each corner with the RND fillet
/// of its radius (0: none), then `close` (an arc back to the first corner, or a
/// line).
fn filleted(corners: &[([f64; 2], f64)], close: Option<([f64; 2], bool)>) -> Vec<El> {
    let n = corners.len();
    // The points where each line starts and ends after the fillets took their part.
    let mut out = Vec::new();
    let mut start = corners[0].0;
    for i in 1..n {
        let (p, rho) = corners[i];
        if rho == 0.0 || i + 1 == n {
            out.push(El::Line(start, p));
            start = p;
            continue;
        }
        let q = corners[i + 1].0;
        let u = {
            let d = sub(p, start);
            [d[0] / len(d), d[1] / len(d)]
        };
        let v = {
            let d = sub(q, p);
            [d[0] / len(d), d[1] / len(d)]
        };
        // The turn between the lines, and the tangent length of the fillet.
        let cos = (u[0] * v[0] + u[1] * v[1]).clamp(-1.0, 1.0);
        let t = rho * (cos.acos() / 2.0).tan();
        let a = [p[0] - u[0] * t, p[1] - u[1] * t];
        let b = [p[0] + v[0] * t, p[1] + v[1] * t];
        let left = u[0] * v[1] - u[1] * v[0] > 0.0;
        let normal = if left { [-u[1], u[0]] } else { [u[1], -u[0]] };
        let c = [a[0] + normal[0] * rho, a[1] + normal[1] * rho];
        out.push(El::Line(start, a));
        out.push(El::Arc(a, b, c, !left));
        start = b;
    }
    match close {
        Some((c, cw)) => out.push(El::Arc(start, corners[0].0, c, cw)),
        None => out.push(El::Line(start, corners[0].0)),
    }
    out
}

/// Whether `p` is inside the closed polygon `pts` (even-odd).
fn inside(pts: &[[f64; 2]], p: [f64; 2]) -> bool {
    let mut inn = false;
    for i in 0..pts.len() {
        let (a, b) = (pts[i], pts[(i + 1) % pts.len()]);
        if (a[1] > p[1]) != (b[1] > p[1]) && p[0] < a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]) {
            inn = !inn;
        }
    }
    inn
}

/// Example 1's pocket: the edge (lines 6886-6892: RND=5 at four corners, the G3
/// CR=5 back to the start) and the two half-disc islands (lines 6894-6901).
struct Pocket {
    edge: Vec<El>,
    islands: Vec<Vec<El>>,
    /// Their points, for the inside test.
    polys: Vec<Vec<[f64; 2]>>,
}

impl Pocket {
    fn example1() -> Self {
        let edge = filleted(
            &[
                ([25.0, 30.0], 0.0),
                ([118.0, 30.0], 5.0),
                ([118.0, 96.0], 5.0),
                ([40.0, 96.0], 5.0),
                ([20.0, 75.0], 5.0),
                ([20.0, 35.0], 0.0),
            ],
            Some(([25.0, 35.0], false)),
        );
        let i1 = vec![El::Line([34.0, 58.0], [64.0, 58.0]), El::Arc([64.0, 58.0], [34.0, 58.0], [49.0, 58.0], true)];
        let i2 = vec![El::Line([79.0, 73.0], [99.0, 73.0]), El::Arc([99.0, 73.0], [79.0, 73.0], [89.0, 73.0], false)];
        let polys = [&edge, &i1, &i2].iter().map(|c| c.iter().flat_map(|e| e.points()).collect()).collect();
        Pocket { edge, islands: vec![i1, i2], polys }
    }

    /// Distance from the nearest wall (edge or island), and whether `p` is in the
    /// pocket (inside the edge, outside every island).
    fn at(&self, p: [f64; 2]) -> (f64, bool) {
        let d = self.edge.iter().chain(self.islands.iter().flatten()).map(|e| e.dist(p)).fold(f64::MAX, f64::min);
        let inn = inside(&self.polys[0], p) && !self.polys[1..].iter().any(|i| inside(i, p));
        (d, inn)
    }
}

/// Distance from `p` to the path of move `s` in the plane.
fn move_dist(s: &Seg, p: [f64; 2]) -> f64 {
    let (a, b) = ([s.from[0], s.from[1]], [s.to[0], s.to[1]]);
    match s.arc {
        None => seg_dist(p, a, b),
        Some((c, cw)) => El::Arc(a, b, c, cw).dist(p),
    }
}

/// The cells of a 0.1 mm grid over the pocket that the cutter of radius `r`
/// sweeps along `cuts`, and those it should: inside the pocket at least `fal`
/// (+ a cell) from every wall, and reachable by a disc of radius `r` whose
/// centre keeps `r + fal` from the walls. Returns the cells missed.
fn missed(pocket: &Pocket, cuts: &[Seg], r: f64, fal: f64) -> Vec<[f64; 2]> {
    let (x0, y0, h) = (19.0, 29.0, 0.1);
    let (nx, ny) = (1000, 680);
    let mut cut = vec![false; nx * ny];
    for s in cuts {
        let (lo_x, hi_x) = (s.from[0].min(s.to[0]) - r, s.from[0].max(s.to[0]) + r);
        let (lo_y, hi_y) = (s.from[1].min(s.to[1]) - r, s.from[1].max(s.to[1]) + r);
        // An arc's box: its whole circle's (simple, a little larger).
        let (lo_x, hi_x, lo_y, hi_y) = match s.arc {
            Some((c, _)) => {
                let rr = len(sub([s.from[0], s.from[1]], c)) + r;
                (c[0] - rr, c[0] + rr, c[1] - rr, c[1] + rr)
            }
            None => (lo_x, hi_x, lo_y, hi_y),
        };
        let ix = |x: f64| (((x - x0) / h).floor().max(0.0) as usize).min(nx - 1);
        let iy = |y: f64| (((y - y0) / h).floor().max(0.0) as usize).min(ny - 1);
        for j in iy(lo_y)..=iy(hi_y) {
            for i in ix(lo_x)..=ix(hi_x) {
                let p = [x0 + i as f64 * h, y0 + j as f64 * h];
                if !cut[j * nx + i] && move_dist(s, p) <= r + 1e-3 {
                    cut[j * nx + i] = true;
                }
            }
        }
    }
    let mut out = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let p = [x0 + i as f64 * h, y0 + j as f64 * h];
            if cut[j * nx + i] {
                continue;
            }
            let (d, inn) = pocket.at(p);
            if !inn || d < fal + h {
                continue;
            }
            // Reachable: some centre within r − h of p keeps r + fal from the walls.
            let reach = (0..72).any(|k| {
                let a = f64::from(k) * 5f64.to_radians();
                (1..=8).any(|m| {
                    let q =
                        [p[0] + (r - h) * f64::from(m) / 8.0 * a.cos(), p[1] + (r - h) * f64::from(m) / 8.0 * a.sin()];
                    let (dq, iq) = pocket.at(q);
                    iq && dq >= r + fal + 1e-3
                })
            });
            if reach {
                out.push(p);
            }
        }
    }
    out
}

/// No move below the reference plane brings the cutter's centre closer than
/// `r + fal` to a wall, or out of the pocket.
fn no_gouge(pocket: &Pocket, segs: &[Seg], r: f64, fal: f64) {
    for s in segs.iter().filter(|s| s.from[2] < 0.0 || s.to[2] < 0.0) {
        for p in samples(s) {
            let (d, inn) = pocket.at(p);
            assert!(inn && d >= r + fal - 2e-3, "{s:?} at {p:?}: {d} from a wall (inside: {inn})");
        }
    }
}

/// Example 1 cleared from solid (VARI 1021, T5 radius 4, MIDA 2, FAL 0.5): the
/// cutter never comes closer than 4.5 mm to a wall, and at the depth it leaves
/// no material but what a round cutter cannot reach.
#[test]
fn example1_clears_the_pocket_to_its_allowance() {
    let (text, first) = program(&format!("{TRANSFER}CYCLE73({ROUGH})\n"));
    let run = go(&text);
    let segs: Vec<Seg> = moves(&run.actions.iter().filter(|c| c.line == first + 3).cloned().collect::<Vec<_>>());
    let pocket = Pocket::example1();
    no_gouge(&pocket, &segs, 4.0, 0.5);
    let flat: Vec<Seg> =
        segs.iter().filter(|s| s.feed > 0.0 && near(s.from[2], -17.5) && near(s.to[2], -17.5)).copied().collect();
    assert!(!flat.is_empty());
    let left = missed(&pocket, &flat, 4.0, 0.5);
    assert!(left.is_empty(), "{} cells left, first {:?}", left.len(), &left[..left.len().min(5)]);
}

/// The test's own pocket is the document's: walls where the program puts them.
#[test]
fn the_test_pocket_is_example1() {
    let p = Pocket::example1();
    let (d, inn) = p.at([100.0, 40.0]);
    assert!(inn && (d - 10.0).abs() < 1e-9, "{d}");
    assert!(!p.at([49.0, 50.0]).1, "island 1 (lower half disc)");
    assert!(p.at([49.0, 60.0]).1, "above island 1");
    assert!(!p.at([89.0, 78.0]).1, "island 2 (upper half disc)");
    assert!(!p.at([15.0, 50.0]).1 && !p.at([119.0, 50.0]).1);
    // The RND=5 fillet at (118, 30): its centre (113, 35), the corner 5(√2 − 1) out.
    let (d, inn) = p.at([118.0, 30.0]);
    assert!(!inn && (d - 5.0 * (2f64.sqrt() - 1.0)).abs() < 1e-9, "{d}");
    // The closing G3 CR=5 from (20, 35) to (25, 30) about (25, 35).
    let (d, _) = p.at([25.0 - 5.0 / 2f64.sqrt(), 35.0 - 5.0 / 2f64.sqrt()]);
    assert!(d < 1e-9);
}

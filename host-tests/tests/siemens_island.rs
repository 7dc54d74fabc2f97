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

/// The pocket on a 0.1 mm grid: whether each cell's centre is in the pocket (a
/// scanline over the walls' points, even-odd across the edge and the islands),
/// and its distance from the nearest wall.
struct Raster {
    x0: f64,
    y0: f64,
    h: f64,
    nx: usize,
    ny: usize,
    inn: Vec<bool>,
    d: Vec<f64>,
}

impl Raster {
    fn new(pocket: &Pocket) -> Self {
        let (x0, y0, h, nx, ny) = (19.0, 29.0, 0.1, 1000, 680);
        let mut inn = vec![false; nx * ny];
        for j in 0..ny {
            let y = y0 + j as f64 * h;
            let mut xs: Vec<f64> = Vec::new();
            for poly in &pocket.polys {
                for k in 0..poly.len() {
                    let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
                    if (a[1] > y) != (b[1] > y) {
                        xs.push(a[0] + (y - a[1]) / (b[1] - a[1]) * (b[0] - a[0]));
                    }
                }
            }
            xs.sort_by(f64::total_cmp);
            for pair in xs.chunks(2) {
                if let [a, b] = pair {
                    let lo = ((a - x0) / h).ceil().max(0.0) as usize;
                    let hi = (((b - x0) / h).floor() as usize).min(nx - 1);
                    for i in lo..=hi {
                        inn[j * nx + i] = true;
                    }
                }
            }
        }
        let walls: Vec<El> = pocket.edge.iter().chain(pocket.islands.iter().flatten()).copied().collect();
        let d = (0..nx * ny)
            .map(|k| {
                let p = [x0 + (k % nx) as f64 * h, y0 + (k / nx) as f64 * h];
                walls.iter().map(|e| e.dist(p)).fold(f64::MAX, f64::min)
            })
            .collect();
        Raster { x0, y0, h, nx, ny, inn, d }
    }

    fn point(&self, k: usize) -> [f64; 2] {
        [self.x0 + (k % self.nx) as f64 * self.h, self.y0 + (k / self.nx) as f64 * self.h]
    }
}

/// Squared distance (in cells²) from every cell to the nearest cell of `mask`:
/// the exact Euclidean distance transform (Felzenszwalb and Huttenlocher), a pass
/// along the rows, then along the columns.
fn distance_transform(mask: &[bool], nx: usize, ny: usize) -> Vec<f64> {
    const INF: f64 = 1e20;
    fn pass(f: &[f64]) -> Vec<f64> {
        let n = f.len();
        let (mut v, mut z) = (vec![0usize; n], vec![0f64; n + 1]);
        let mut k = 0;
        z[0] = -INF;
        z[1] = INF;
        for q in 1..n {
            loop {
                let p = v[k];
                let s = ((f[q] + (q * q) as f64) - (f[p] + (p * p) as f64)) / (2.0 * (q as f64 - p as f64));
                if s <= z[k] && k > 0 {
                    k -= 1;
                    continue;
                }
                if s <= z[k] {
                    v[0] = q;
                    z[0] = -INF;
                    z[1] = INF;
                    break;
                }
                k += 1;
                v[k] = q;
                z[k] = s;
                z[k + 1] = INF;
                break;
            }
        }
        let mut out = vec![0.0; n];
        k = 0;
        for (q, o) in out.iter_mut().enumerate() {
            while z[k + 1] < q as f64 {
                k += 1;
            }
            let p = v[k];
            *o = (q as f64 - p as f64).powi(2) + f[p];
        }
        out
    }
    let mut g: Vec<f64> = mask.iter().map(|&m| if m { 0.0 } else { INF }).collect();
    for j in 0..ny {
        let row = pass(&g[j * nx..(j + 1) * nx]);
        g[j * nx..(j + 1) * nx].copy_from_slice(&row);
    }
    for i in 0..nx {
        let col: Vec<f64> = (0..ny).map(|j| g[j * nx + i]).collect();
        for (j, v) in pass(&col).into_iter().enumerate() {
            g[j * nx + i] = v;
        }
    }
    g
}

/// The cells of the grid that the cutters sweep along their `passes` (the
/// cuts, the cutter's radius), and those a cutter of radius `r` should: inside
/// the pocket at least `fal` (+ a cell) from every wall, and reachable by a disc
/// of radius `r` whose centre keeps `r + fal` from the walls. Returns the cells
/// missed.
fn missed_by(pocket: &Pocket, passes: &[(&[Seg], f64)], r: f64, fal: f64) -> Vec<[f64; 2]> {
    let g = Raster::new(pocket);
    let (x0, y0, h, nx, ny) = (g.x0, g.y0, g.h, g.nx, g.ny);
    let mut cut = vec![false; nx * ny];
    for (s, r) in passes.iter().flat_map(|&(cuts, r)| cuts.iter().map(move |s| (s, r))) {
        let (lo_x, hi_x, lo_y, hi_y) = match s.arc {
            // An arc's box: its whole circle's (simple, a little larger).
            Some((c, _)) => {
                let rr = len(sub([s.from[0], s.from[1]], c)) + r;
                (c[0] - rr, c[0] + rr, c[1] - rr, c[1] + rr)
            }
            None => (
                s.from[0].min(s.to[0]) - r,
                s.from[0].max(s.to[0]) + r,
                s.from[1].min(s.to[1]) - r,
                s.from[1].max(s.to[1]) + r,
            ),
        };
        let ix = |x: f64| (((x - x0) / h).floor().max(0.0) as usize).min(nx - 1);
        let iy = |y: f64| (((y - y0) / h).floor().max(0.0) as usize).min(ny - 1);
        for j in iy(lo_y)..=iy(hi_y) {
            for i in ix(lo_x)..=ix(hi_x) {
                if !cut[j * nx + i] && move_dist(s, g.point(j * nx + i)) <= r + 1e-3 {
                    cut[j * nx + i] = true;
                }
            }
        }
    }
    // Where a centre may be, and how far (cells²) each cell is from there.
    let centre: Vec<bool> = (0..nx * ny).map(|k| g.inn[k] && g.d[k] >= r + fal + 1e-3).collect();
    let far = distance_transform(&centre, nx, ny);
    let reach = ((r - h) / h).powi(2);
    (0..nx * ny).filter(|&k| !cut[k] && g.inn[k] && g.d[k] >= fal + h && far[k] <= reach).map(|k| g.point(k)).collect()
}

/// [`missed_by`] one cutter of radius `r` along `cuts`.
fn missed(pocket: &Pocket, cuts: &[Seg], r: f64, fal: f64) -> Vec<[f64; 2]> {
    missed_by(pocket, &[(cuts, r)], r, fal)
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

/// The moves of `body`'s line `k` (0: its first) in a run of `body`.
fn moves_of(body: &str, k: u32) -> Vec<Seg> {
    let (text, first) = program(body);
    let run = go(&text);
    moves(&run.actions.iter().filter(|c| c.line == first + k).cloned().collect::<Vec<_>>())
}

/// The cutting moves at depth `z`.
fn flat(segs: &[Seg], z: f64) -> Vec<Seg> {
    segs.iter().filter(|s| s.feed > 0.0 && near(s.from[2], z) && near(s.to[2], z)).copied().collect()
}

/// Angle swept by an arc move, degrees (positive).
fn swept(s: &Seg) -> f64 {
    let (c, cw) = s.arc.unwrap();
    let (_, sw) = El::sweep([s.from[0], s.from[1]], [s.to[0], s.to[1]], c, cw);
    sw.abs().to_degrees()
}

/// Example 1's helical insertion (`_RAD` 4, `_DP1` 3): from RFP + SDIS (Z1) to
/// −17.5 in whole turns of at most 3 mm — 18.5 / 3 → 7 turns of 2.643 mm — on a
/// circle of radius 4, then one flat full circle at the depth (lines 6789-6797).
#[test]
fn example1_inserts_on_a_helix_in_whole_turns() {
    let segs = moves_of(&format!("{TRANSFER}CYCLE73({ROUGH})\n"), 3);
    // The first insertion: the arcs from the first one that descends.
    let first = segs.iter().position(|s| s.arc.is_some() && s.to[2] < s.from[2]).unwrap();
    let helix: Vec<&Seg> = segs[first..].iter().take_while(|s| s.arc.is_some()).collect();
    let (c, _) = helix[0].arc.unwrap();
    for s in &helix {
        assert_eq!(s.arc.unwrap().0, c, "one axis");
        assert!(near(len(sub([s.to[0], s.to[1]], c)), 4.0), "radius 4: {s:?}");
        assert_eq!(s.feed, 3000.0, "at _FFD");
    }
    let down: Vec<&&Seg> = helix.iter().filter(|s| s.to[2] < s.from[2]).collect();
    assert!(near(down[0].from[2], 1.0), "{:?}", down[0]);
    let turns: f64 = down.iter().map(|s| swept(s)).sum::<f64>() / 360.0;
    assert!((turns - 7.0).abs() < 1e-6, "{turns} turns");
    for s in &down {
        let pitch = (s.from[2] - s.to[2]) / (swept(s) / 360.0);
        assert!((pitch - 18.5 / 7.0).abs() < 2e-3, "{pitch} mm a turn");
    }
    let flat_turn: f64 =
        helix.iter().filter(|s| near(s.from[2], -17.5) && near(s.to[2], -17.5)).map(|s| swept(s)).sum();
    assert!((flat_turn - 360.0).abs() < 1e-6, "one flat circle: {flat_turn}");
}

/// Example 1's edge finish (VARI 1113, T2 radius 5 less the example mill's wear
/// of row 2, −0.02: 4.98): the cutter's centre keeps exactly that radius from the
/// walls, and every wall point is touched (the fillets are larger than the
/// cutter: nothing out of reach).
#[test]
fn example1_edge_finish_touches_every_wall_at_the_radius() {
    let finish = "1113, \"\", \"BEISPIEL1_MILL3\", \"5\", 10, 0, 1, -17.5, 0, , 2, , , 8000, 1000, 0, , , 4, 2";
    let segs = moves_of(&format!("{TRANSFER}T2 D1\nCYCLE73({finish})\n"), 4);
    let pocket = Pocket::example1();
    let r = 4.98;
    no_gouge(&pocket, &segs, r, 0.0);
    let cuts = flat(&segs, -17.5);
    let walls = pocket.edge.iter().chain(pocket.islands.iter().flatten());
    for p in walls.flat_map(|e| e.points()).step_by(10) {
        let d = cuts.iter().map(|s| move_dist(s, p)).fold(f64::MAX, f64::min);
        assert!(d <= r + 0.002, "wall point {p:?} {d} from the nearest cut");
    }
}

/// Rest material (VARI 1012): after clearing with T3 (radius 6, VARI 1011), T5 (radius 4)
/// cuts only what T3 left; together they leave nothing T5 can reach.
#[test]
fn rest_material_after_a_larger_cutter_leaves_nothing_reachable() {
    // Straight insertion: T3's helix of radius 4 does not fit every part (61910).
    let rough = ROUGH.replacen("1021", "1011", 1).replacen("\"5\"", "\"3\"", 1);
    let rest = ROUGH.replacen("1021", "1012", 1).replacen("\"5\"", "\"3\"", 1);
    let body = format!("{TRANSFER}T3 D1\nCYCLE73({rough})\nT5 D1\nCYCLE73({rest})\n");
    let (text, first) = program(&body);
    let run = go(&text);
    let of = |k: u32| moves(&run.actions.iter().filter(|c| c.line == first + k).cloned().collect::<Vec<_>>());
    let (big, small) = (of(4), of(6));
    let pocket = Pocket::example1();
    no_gouge(&pocket, &big, 6.0, 0.5);
    no_gouge(&pocket, &small, 4.0, 0.5);
    // What T3 left at the depth: T5's cells reachable, not swept by T3.
    let before = missed(&pocket, &flat(&big, -17.5), 4.0, 0.5);
    assert!(!before.is_empty(), "T3 leaves material in the corners T5 reaches");
    let left = missed_by(&pocket, &[(&flat(&big, -17.5), 6.0), (&flat(&small, -17.5), 4.0)], 4.0, 0.5);
    assert!(left.is_empty(), "{} cells left, first {:?}", left.len(), &left[..left.len().min(5)]);
    // The rest is much less cutting than a clearing.
    let length = |v: &[Seg]| {
        v.iter().filter(|s| s.feed > 0.0).map(|s| len(sub([s.to[0], s.to[1]], [s.from[0], s.from[1]]))).sum::<f64>()
    };
    assert!(length(&small) < length(&big) / 2.0, "{} vs {}", length(&small), length(&big));
}

/// Floor finishing (VARI 1114, FALD 0.2): G0 down to DP + FALD + SDIS, at _FFD to
/// DP (line 6632), the floor cleared once keeping _FAL on the walls.
#[test]
fn floor_finish_clears_the_floor_once() {
    let floor = "1014, \"\", \"BEISPIEL1_MILL4\", \"5\", 10, 0, 1, -17.5, 0, , 2, 0.5, 0.2, 9000, 3000, 0, , , 4, 3";
    let segs = moves_of(&format!("{TRANSFER}CYCLE73({floor})\n"), 3);
    let pocket = Pocket::example1();
    no_gouge(&pocket, &segs, 4.0, 0.5);
    let cut_depths: Vec<f64> =
        segs.iter().filter(|s| s.feed > 0.0 && near(s.from[2], s.to[2])).map(|s| um(s.to[2])).collect();
    assert!(cut_depths.iter().all(|&z| z == -17.5), "only the floor: {cut_depths:?}");
    let plunge = segs.iter().position(|s| s.to[2] < s.from[2] && s.feed > 0.0).unwrap();
    assert!(near(segs[plunge].from[2], -16.3), "G0 to DP + FALD + SDIS: {:?}", segs[plunge]);
    assert!(segs[plunge - 1].feed == 0.0 && near(segs[plunge - 1].to[2], -16.3));
    assert!(missed(&pocket, &flat(&segs, -17.5), 4.0, 0.5).is_empty());
}

/// Pre-drilling (VARI 1015) under MCALL CYCLE81: the drill goes to each insertion
/// point the clearing with straight insertion (VARI 1011) uses, and drills there.
#[test]
fn predrilling_drills_where_the_clearing_inserts() {
    let drill = ROUGH.replacen("1021", "1015", 1).replacen("\"\"", "\"P_DRILL\"", 1);
    let body = format!("{TRANSFER}MCALL CYCLE81(10, 0, 1, -3)\nCYCLE73({drill})\nMCALL\n");
    let (text, first) = program(&body);
    let run = go(&text);
    // The drilling cycle's feed moves to Z−3, each from the hole's position.
    let segs = moves(&run.actions);
    let holes: Vec<[f64; 2]> =
        segs.iter().filter(|s| s.feed > 0.0 && near(s.to[2], -3.0)).map(|s| [um(s.to[0]), um(s.to[1])]).collect();
    let rough = moves_of(&format!("{TRANSFER}CYCLE73({})\n", ROUGH.replacen("1021", "1011", 1)), 3);
    let inserts: Vec<[f64; 2]> = rough
        .iter()
        .filter(|s| s.feed > 0.0 && s.to[2] < s.from[2] && near(s.to[2], -17.5))
        .map(|s| [um(s.to[0]), um(s.to[1])])
        .collect();
    assert!(!holes.is_empty());
    assert_eq!(holes, inserts);
    let _ = first;
}

/// The alarms the pocket's geometry raises, on CYCLE73's line, before anything
/// moves.
#[test]
fn geometry_alarms_move_nothing() {
    let with = |i: usize, v: &str| {
        let mut a: Vec<String> = ROUGH.split(", ").map(str::to_string).collect();
        a[i] = v.to_string();
        a.join(", ")
    };
    let edge = |labels: &str| format!("CYCLE74 (\"\", {labels})\n");
    // A contour that does not close, one too small for the cutter, one of 49
    // elements (a zigzag), a circle.
    let extra = "M02\nN700 _OPEN:G0 X25 Y30\nG1 X118\nY96\n_ENDOPEN:X25\n\
        N710 _SMALL:G0 X0 Y0\nG1 X8\nY8\nX0\n_ENDSMALL:Y0\n\
        N720 _CIRCLE:G0 X60 Y60\nG3 X100 Y60 CR=20\n_ENDCIRCLE:X60 Y60 CR=20\n";
    let zigzag: String = (1..=48).map(|k| format!("G1 X{} Y{}\n", k, if k % 2 == 0 { 0 } else { 1 })).collect();
    let extra = format!("{extra}N730 _ZIG:G0 X0 Y0\n{zigzag}_ENDZIG:G1 X0 Y0\n");
    for (body, code) in [
        (format!("{}CYCLE73({ROUGH})\n{extra}", edge("\"_OPEN\", \"_ENDOPEN\"")), 61901),
        (format!("{}CYCLE73({ROUGH})\n{extra}", edge("\"_SMALL\", \"_ENDSMALL\"")), 61912),
        (format!("{}CYCLE73({ROUGH})\n{extra}", edge("\"_ZIG\", \"_ENDZIG\"")), 61903),
        // A helix of radius 20 fits the pocket without islands, not with them.
        (format!("{TRANSFER}CYCLE73({})\n", with(18, "20")), 61910),
        (format!("{TRANSFER}CYCLE73({})\n", with(0, "2011").replacen(", , , 4, 3", ", 49, 50, 4, 3", 1)), 61908),
        (
            format!(
                "{}CYCLE73({})\n{extra}",
                edge("\"_CIRCLE\", \"_ENDCIRCLE\""),
                with(0, "1012").replacen("\"5\"", "\"3\"", 1)
            ),
            61913,
        ),
    ] {
        let k = body.lines().position(|l| l.starts_with("CYCLE73")).unwrap() as u32;
        assert_eq!(alarm_at(&body, k), code, "{body}");
    }
    // A cutter of radius 0.
    let (text, first) = program(&format!("{TRANSFER}CYCLE73({ROUGH})\n"));
    let r = siemens(&text.replace("$TC_DP6[5,1]=4", "$TC_DP6[5,1]=0"));
    assert_eq!(r.alarm_codes(), vec![(first + 3, 61905)]);
}

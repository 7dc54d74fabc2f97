//! CYCLE73's geometry against the document's example 1 and made-up pockets:
//! coverage and gouging by rasterising the cutter along the moves, with the
//! walls' distances computed here from the contours' elements.

extern crate std;

use super::*;
use std::vec;
use std::vec::Vec;

const MM: f64 = 1e6;

std::thread_local! {
    /// Links that left the tool-centre region and went up and in again instead.
    pub(super) static REINSERTED: core::cell::Cell<usize> = const { core::cell::Cell::new(0) };
}

fn mm(v: f64) -> i64 {
    libm::round(v * MM) as i64
}

fn pt(p: (f64, f64)) -> (i64, i64) {
    (mm(p.0), mm(p.1))
}

fn line(a: (f64, f64), b: (f64, f64)) -> Elem {
    Elem { from: pt(a), to: pt(b), arc: None }
}

fn arc(a: (f64, f64), b: (f64, f64), c: (f64, f64), cw: bool) -> Elem {
    Elem { from: pt(a), to: pt(b), arc: Some((pt(c), cw)) }
}

/// A closed polyline of lines (mm) with a fillet of radius `rnd[i]` at vertex
/// `i` (0: none), as CYCLE74/75 contours with RND give it.
fn filleted(v: &[(f64, f64)], rnd: &[f64]) -> Vec<Elem> {
    let n = v.len();
    // Each vertex: (where the incoming side ends, the fillet arc, where the
    // outgoing side starts).
    let mut corner = Vec::new();
    for i in 0..n {
        let (p, c, q) = (v[(i + n - 1) % n], v[i], v[(i + 1) % n]);
        if rnd[i] == 0.0 {
            corner.push((c, None, c));
            continue;
        }
        let u1 = unit_mm((c.0 - p.0, c.1 - p.1));
        let u2 = unit_mm((q.0 - c.0, q.1 - c.1));
        let turn = u1.0 * u2.1 - u1.1 * u2.0;
        let cosang = -(u1.0 * u2.0 + u1.1 * u2.1); // between −u1 and u2
        let half = libm::acos(cosang.clamp(-1.0, 1.0)) / 2.0;
        let t = rnd[i] / libm::tan(half);
        let t1 = (c.0 - u1.0 * t, c.1 - u1.1 * t);
        let t2 = (c.0 + u2.0 * t, c.1 + u2.1 * t);
        let nrm = if turn > 0.0 { (-u1.1, u1.0) } else { (u1.1, -u1.0) };
        let m = (t1.0 + nrm.0 * rnd[i], t1.1 + nrm.1 * rnd[i]);
        corner.push((t1, Some((m, turn < 0.0)), t2));
    }
    let mut e = Vec::new();
    for i in 0..n {
        let (t1, a, t2) = corner[i];
        if let Some((m, cw)) = a {
            e.push(arc(t1, t2, m, cw));
        }
        e.push(line(t2, corner[(i + 1) % n].0));
    }
    e
}

fn unit_mm(a: (f64, f64)) -> (f64, f64) {
    let l = libm::hypot(a.0, a.1);
    (a.0 / l, a.1 / l)
}

/// Example 1 (seed 001 lines 6279-6420): the edge N510-N560, islands N570-N590
/// (the lower, a half circle under a line) and N600-N620 (the upper).
fn example1() -> (Vec<Elem>, Vec<Vec<Elem>>) {
    // X25 Y30 → X118 RND=5 → Y96 RND=5 → X40 RND=5 → X20 Y75 RND=5 → Y35,
    // then G3 X25 Y30 CR=5 (centre X25 Y35, tangent to both neighbours).
    let mut edge = filleted(
        &[(25.0, 30.0), (118.0, 30.0), (118.0, 96.0), (40.0, 96.0), (20.0, 75.0), (20.0, 35.0)],
        &[0.0, 5.0, 5.0, 5.0, 5.0, 0.0],
    );
    // The closing side (20,35)→(25,30) is the arc, not a line.
    let last = edge.pop().unwrap();
    assert_eq!(last.from, pt((20.0, 35.0)));
    edge.push(arc((20.0, 35.0), (25.0, 30.0), (25.0, 35.0), false));
    let i1 = vec![line((34.0, 58.0), (64.0, 58.0)), arc((64.0, 58.0), (34.0, 58.0), (49.0, 58.0), true)];
    let i2 = vec![line((79.0, 73.0), (99.0, 73.0)), arc((99.0, 73.0), (79.0, 73.0), (89.0, 73.0), false)];
    (edge, vec![i1, i2])
}

fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<Elem> {
    vec![line((x0, y0), (x1, y0)), line((x1, y0), (x1, y1)), line((x1, y1), (x0, y1)), line((x0, y1), (x0, y0))]
}

fn spec(r: f64, fal: f64, depth: f64, mid: f64) -> IslandSpec {
    let r = mm(r);
    IslandSpec {
        job: Job::Rough,
        r,
        fal: mm(fal),
        step: crate::infeed::max_width(0, r),
        levels: Levels::new(mm(1.0), mm(-depth), mm(mid)),
        rtp: mm(10.0),
        safe: mm(1.0),
        sdis: mm(1.0),
        dir: -1,
        lift: 0,
        plunge: Plunge::Vertical,
        start: None,
        cw: false,
        feeds: [400_000_000, 2_000_000_000],
    }
}

/// Distance (mm) from `p` to element `e`.
fn elem_dist(e: &Elem, p: (f64, f64)) -> f64 {
    let f = (e.from.0 as f64 / MM, e.from.1 as f64 / MM);
    let t = (e.to.0 as f64 / MM, e.to.1 as f64 / MM);
    let end = libm::hypot(p.0 - f.0, p.1 - f.1).min(libm::hypot(p.0 - t.0, p.1 - t.1));
    match e.arc {
        None => {
            let d = (t.0 - f.0, t.1 - f.1);
            let l2 = d.0 * d.0 + d.1 * d.1;
            let s = (((p.0 - f.0) * d.0 + (p.1 - f.1) * d.1) / l2).clamp(0.0, 1.0);
            libm::hypot(p.0 - f.0 - s * d.0, p.1 - f.1 - s * d.1)
        }
        Some((c, cw)) => {
            let c = (c.0 as f64 / MM, c.1 as f64 / MM);
            let r = libm::hypot(f.0 - c.0, f.1 - c.1);
            let ang = |q: (f64, f64)| libm::atan2(q.1 - c.1, q.0 - c.0);
            let tau = 2.0 * core::f64::consts::PI;
            let norm = |a: f64| ((a % tau) + tau) % tau;
            let (a0, a1, ap) = (ang(f), ang(t), ang(p));
            // Counterclockwise sweep from the start to the point and to the end.
            let (sp, se) = if cw { (norm(a0 - ap), norm(a0 - a1)) } else { (norm(ap - a0), norm(a1 - a0)) };
            let se = if se == 0.0 { tau } else { se };
            if sp <= se { (libm::hypot(p.0 - c.0, p.1 - c.1) - r).abs() } else { end }
        }
    }
}

/// A fine polygon (mm) of a contour, for inside tests.
fn fine(k: &[Elem]) -> Vec<(f64, f64)> {
    let pts = discretise(k, None).unwrap();
    pts.iter().map(|p| (p[0] / MM, p[1] / MM)).collect()
}

fn inside_poly(c: &[(f64, f64)], p: (f64, f64)) -> bool {
    let mut inside = false;
    let n = c.len();
    for i in 0..n {
        let (a, b) = (c[i], c[(i + 1) % n]);
        if (a.1 > p.1) != (b.1 > p.1) && p.0 < a.0 + (p.1 - a.1) * (b.0 - a.0) / (b.1 - a.1) {
            inside = !inside;
        }
    }
    inside
}

/// The pocket as the test sees it: signed distance (mm) to the walls,
/// positive in the region.
struct Walls {
    elems: Vec<Elem>,
    edge: Vec<(f64, f64)>,
    islands: Vec<Vec<(f64, f64)>>,
}

impl Walls {
    fn new(edge: &[Elem], islands: &[Vec<Elem>]) -> Self {
        let mut elems = edge.to_vec();
        for i in islands {
            elems.extend_from_slice(i);
        }
        Walls { elems, edge: fine(edge), islands: islands.iter().map(|i| fine(i)).collect() }
    }

    fn dist(&self, p: (f64, f64)) -> f64 {
        let d = self.elems.iter().map(|e| elem_dist(e, p)).fold(f64::INFINITY, f64::min);
        let inside = inside_poly(&self.edge, p) && !self.islands.iter().any(|i| inside_poly(i, p));
        if inside { d } else { -d }
    }
}

/// A piece of the tool centre's path (mm).
type Seg = ((f64, f64), (f64, f64));

/// The moves' tool-centre path at applicate `z` (mm), as segments (arcs cut
/// into 0.05 mm pieces), from `start`.
fn segments(moves: &[Move], z: i64) -> Vec<Seg> {
    let mut out = Vec::new();
    let mut pos: Option<P3> = None;
    let f = |p: P3| (p.a as f64 / MM, p.o as f64 / MM);
    for m in moves {
        let Some(to) = crate::end_of(m) else { continue };
        if let Some(from) = pos {
            let cutting = !matches!(m, Move::Rapid(_)) && to.d == z;
            if cutting {
                match *m {
                    Move::Arc { centre, cw, .. } => {
                        let c = (centre.0 as f64 / MM, centre.1 as f64 / MM);
                        let (a, b) = (f(from), f(to));
                        let r = libm::hypot(a.0 - c.0, a.1 - c.1);
                        let a0 = libm::atan2(a.1 - c.1, a.0 - c.0);
                        let a1 = libm::atan2(b.1 - c.1, b.0 - c.0);
                        let tau = 2.0 * core::f64::consts::PI;
                        let mut sw = a1 - a0;
                        if cw {
                            while sw >= 0.0 {
                                sw -= tau;
                            }
                        } else {
                            while sw <= 0.0 {
                                sw += tau;
                            }
                        }
                        let n = (libm::ceil(sw.abs() * r / 0.05) as usize).max(1);
                        let mut prev = a;
                        for i in 1..=n {
                            let t = a0 + sw * i as f64 / n as f64;
                            let q = (c.0 + r * libm::cos(t), c.1 + r * libm::sin(t));
                            out.push((prev, q));
                            prev = q;
                        }
                    }
                    _ => out.push((f(from), f(to))),
                }
            }
        }
        pos = Some(to);
    }
    out
}

/// Raster of the cells (0.1 mm) the cutter of radius `r` (mm) sweeps along
/// `segs`, over the box `b` (mm).
struct Raster {
    x0: f64,
    y0: f64,
    w: usize,
    h: usize,
    cut: Vec<bool>,
}

const CELL: f64 = 0.1;

impl Raster {
    fn new(b: [f64; 4], segs: &[Seg], r: f64) -> Self {
        let w = ((b[2] - b[0]) / CELL) as usize + 1;
        let h = ((b[3] - b[1]) / CELL) as usize + 1;
        let mut ras = Raster { x0: b[0], y0: b[1], w, h, cut: vec![false; w * h] };
        for &(a, c) in segs {
            let lo = ((a.0.min(c.0) - r - b[0]) / CELL).floor().max(0.0) as usize;
            let hi = (((a.0.max(c.0) + r - b[0]) / CELL).ceil() as usize).min(w - 1);
            let lo_y = ((a.1.min(c.1) - r - b[1]) / CELL).floor().max(0.0) as usize;
            let hi_y = (((a.1.max(c.1) + r - b[1]) / CELL).ceil() as usize).min(h - 1);
            for j in lo_y..=hi_y {
                for i in lo..=hi {
                    if ras.cut[j * w + i] {
                        continue;
                    }
                    let p = ras.centre(i, j);
                    if seg_dist_mm(a, c, p) <= r {
                        ras.cut[j * w + i] = true;
                    }
                }
            }
        }
        ras
    }

    fn centre(&self, i: usize, j: usize) -> (f64, f64) {
        (self.x0 + i as f64 * CELL, self.y0 + j as f64 * CELL)
    }
}

fn seg_dist_mm(a: (f64, f64), b: (f64, f64), p: (f64, f64)) -> f64 {
    let d = (b.0 - a.0, b.1 - a.1);
    let l2 = d.0 * d.0 + d.1 * d.1;
    let s = if l2 > 0.0 { (((p.0 - a.0) * d.0 + (p.1 - a.1) * d.1) / l2).clamp(0.0, 1.0) } else { 0.0 };
    libm::hypot(p.0 - a.0 - s * d.0, p.1 - a.1 - s * d.1)
}

/// Whether a cutter of radius `r` whose centre keeps `r + fal` from the walls
/// can reach `p` (with 0.02 mm to spare): some centre within r of it.
fn reachable(w: &Walls, p: (f64, f64), r: f64, fal: f64) -> bool {
    if w.dist(p) >= r + fal + 0.02 {
        return true;
    }
    for k in 1..=8 {
        let rho = (r - 0.02) * k as f64 / 8.0;
        for i in 0..144 {
            let a = 2.0 * core::f64::consts::PI * i as f64 / 144.0;
            let c = (p.0 + rho * libm::cos(a), p.1 + rho * libm::sin(a));
            if w.dist(c) >= r + fal + 0.02 {
                return true;
            }
        }
    }
    false
}

/// (b) no tool-centre point of a cutting move at any level of `moves` comes
/// closer to a wall than r + fal (less 2 µm).
fn check_gouge(s: &IslandSpec, walls: &Walls, moves: &[Move]) {
    let (r, fal) = (s.r as f64 / MM, s.fal as f64 / MM);
    for k in 1..=s.levels.count {
        for (a, b) in segments(moves, s.levels.level(k)) {
            let n = (libm::ceil(libm::hypot(b.0 - a.0, b.1 - a.1) / 0.05) as usize).max(1);
            for i in 0..=n {
                let t = i as f64 / n as f64;
                let p = (a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t);
                let d = walls.dist(p);
                assert!(d >= r + fal - 0.002, "gouge: centre {p:?} {d} mm from a wall");
            }
        }
    }
}

/// (a) every cell at least fal + one cell inside the walls that a cutter of
/// the last spec's radius can reach is cut at the last level by one of the
/// `plans` (each with its own cutter).
fn check_cover(walls: &Walls, plans: &[(&IslandSpec, &[Move])]) {
    let e = &walls.edge;
    let b = [
        e.iter().map(|p| p.0).fold(f64::INFINITY, f64::min),
        e.iter().map(|p| p.1).fold(f64::INFINITY, f64::min),
        e.iter().map(|p| p.0).fold(f64::NEG_INFINITY, f64::max),
        e.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max),
    ];
    let mut ras: Option<Raster> = None;
    for (s, moves) in plans {
        let segs = segments(moves, s.levels.to);
        let one = Raster::new(b, &segs, s.r as f64 / MM);
        match &mut ras {
            None => ras = Some(one),
            Some(r) => r.cut.iter_mut().zip(one.cut).for_each(|(a, b)| *a |= b),
        }
    }
    let ras = ras.unwrap();
    let last = plans.last().unwrap().0;
    let (r, fal) = (last.r as f64 / MM, last.fal as f64 / MM);
    let mut missed = Vec::new();
    for j in 0..ras.h {
        for i in 0..ras.w {
            if ras.cut[j * ras.w + i] {
                continue;
            }
            let p = ras.centre(i, j);
            if walls.dist(p) >= fal + CELL && reachable(walls, p, r, fal) {
                missed.push(p);
            }
        }
    }
    assert!(missed.is_empty(), "{} cells left: {:?}", missed.len(), &missed[..missed.len().min(20)]);
}

/// Roughing `s`: no gouge, nothing reachable left.
fn check_clearing(s: &IslandSpec, edge: &[Elem], islands: &[Vec<Elem>]) -> Vec<Move> {
    let refs: Vec<&[Elem]> = islands.iter().map(|v| v.as_slice()).collect();
    REINSERTED.with(|c| c.set(0));
    let moves = plan(s, edge, &refs).unwrap();
    assert_eq!(REINSERTED.with(|c| c.get()), 0, "every link straight");
    let walls = Walls::new(edge, islands);
    check_gouge(s, &walls, &moves);
    check_cover(&walls, &[(s, &moves)]);
    moves
}

#[test]
fn example1_roughing_clears_everything_and_gouges_nothing() {
    let (edge, islands) = example1();
    // T5 of the listing that calls CYCLE73 (line 6930): $TC_DP6 = 4; the
    // first listing's 6 makes the 13 mm gaps under the lower island and over the
    // upper exactly 2·(r + fal): a tool-centre region of width 0 there.
    let s = spec(4.0, 0.5, 17.5, 6.0);
    let t = std::time::Instant::now();
    let refs: Vec<&[Elem]> = islands.iter().map(|v| v.as_slice()).collect();
    let n = plan(&s, &edge, &refs).unwrap().len();
    std::println!("example 1: plan {:?}, {n} moves", t.elapsed());
    check_clearing(&s, &edge, &islands);
}

#[test]
fn two_islands_divide_the_pocket_into_two_parts() {
    let edge = rect(0.0, 0.0, 100.0, 50.0);
    let islands = vec![rect(45.0, 3.0, 55.0, 24.0), rect(45.0, 26.0, 55.0, 47.0)];
    let s = spec(4.0, 0.5, 5.0, 0.0);
    check_clearing(&s, &edge, &islands);
    let refs: Vec<&[Elem]> = islands.iter().map(|v| v.as_slice()).collect();
    let pts = start_points(&s, &edge, &refs).unwrap();
    assert_eq!(pts.len(), 2, "{pts:?}");
    assert!(pts.iter().any(|p| p.0 < mm(45.0)) && pts.iter().any(|p| p.0 > mm(55.0)));
}

fn refs(islands: &[Vec<Elem>]) -> Vec<&[Elem]> {
    islands.iter().map(|v| v.as_slice()).collect()
}

/// The moves that go down in the material (applicate changes at feed), with
/// where they start.
fn descents(moves: &[Move]) -> Vec<(P3, Move)> {
    let mut out = Vec::new();
    let mut pos = P3::default();
    for m in moves {
        let Some(to) = crate::end_of(m) else { continue };
        if !matches!(m, Move::Rapid(_)) && to.d != pos.d {
            out.push((pos, *m));
        }
        pos = to;
    }
    out
}

#[test]
fn insertions_follow_the_levels_and_the_helix_ends_flat() {
    let (edge, islands) = example1();
    let mut s = spec(4.0, 0.5, 17.5, 6.0);
    // Vertical: each chain's insertion ends at the level, one per chain and level.
    let moves = plan(&s, &edge, &refs(&islands)).unwrap();
    let chains = start_points(&s, &edge, &refs(&islands)).unwrap().len();
    let ends: Vec<i64> = descents(&moves).iter().map(|(_, m)| crate::end_of(m).unwrap().d).collect();
    let levels: Vec<i64> = (1..=s.levels.count).map(|k| s.levels.level(k)).collect();
    assert_eq!(s.levels.count, 4);
    let mut expect = Vec::new();
    for &l in &levels {
        expect.extend(std::iter::repeat_n(l, chains));
    }
    // Re-insertions after a link that would leave the region come on top.
    for l in &levels {
        assert!(ends.iter().filter(|&&e| e == *l).count() >= chains);
    }
    assert!(ends.iter().all(|e| levels.contains(e)), "{ends:?}");
    // The first move: in the plane at the retract plane; then down to RFP + SDIS.
    assert!(matches!(moves[0], Move::Rapid(p) if p.d == s.rtp));
    assert!(matches!(moves[1], Move::Rapid(p) if p.d == s.safe));
    assert!(matches!(moves.last(), Some(Move::Rapid(p)) if p.d == s.rtp));
    // Helix: turns of at most the pitch, the last one flat, about the start point.
    s.plunge = Plunge::Helix { rad: mm(2.5), pitch: mm(2.0) };
    let moves = plan(&s, &edge, &refs(&islands)).unwrap();
    let starts = start_points(&s, &edge, &refs(&islands)).unwrap();
    let mut flat_after = 0;
    let mut pos = P3::default();
    let mut in_helix = false;
    for m in &moves {
        let to = crate::end_of(m).unwrap();
        if let Move::Arc { centre, cw, .. } = *m {
            assert!(!cw);
            assert!(starts.contains(&centre));
            assert_eq!((to.a, to.o), (centre.0 + mm(2.5), centre.1), "a whole turn");
            assert_eq!((pos.a, pos.o), (to.a, to.o));
            assert!((pos.d - to.d).abs() <= mm(2.0));
            if to.d == pos.d {
                assert!(in_helix, "flat circle after the descent");
                assert!(levels.contains(&to.d));
                flat_after += 1;
                in_helix = false;
            } else {
                in_helix = true;
            }
        } else {
            assert!(!in_helix, "the helix ends with a flat circle");
        }
        pos = to;
    }
    assert_eq!(flat_after, chains * levels.len());
}

/// Points along the walls (every 0.5 mm of each element).
fn wall_samples(k: &[Elem]) -> Vec<(f64, f64)> {
    fine(k)
        .windows(2)
        .flat_map(|w| {
            let (a, b) = (w[0], w[1]);
            let n = (libm::ceil(libm::hypot(b.0 - a.0, b.1 - a.1) / 0.5) as usize).max(1);
            (0..n).map(move |i| (a.0 + (b.0 - a.0) * i as f64 / n as f64, a.1 + (b.1 - a.1) * i as f64 / n as f64))
        })
        .collect()
}

#[test]
fn outer_rings_keep_r_plus_fal_from_every_wall() {
    let (edge, islands) = example1();
    for (job, fal) in [(Job::Rough, 0.5), (Job::Edge, 0.0)] {
        let mut s = spec(4.0, fal, 5.0, 0.0);
        s.job = job;
        let moves = plan(&s, &edge, &refs(&islands)).unwrap();
        let segs = segments(&moves, s.levels.to);
        let walls = Walls::new(&edge, &islands);
        // Every wall point has the path at r + fal (the nearest centre point),
        // and no centre point is nearer any wall.
        let want = 4.0 + fal;
        let mut all = wall_samples(&edge);
        for i in &islands {
            all.extend(wall_samples(i));
        }
        for p in all {
            let d = segs.iter().map(|&(a, b)| seg_dist_mm(a, b, p)).fold(f64::INFINITY, f64::min);
            assert!((d - want).abs() < 0.002, "{job:?}: wall point {p:?}: path at {d} mm");
        }
        for (a, _) in segs {
            assert!(walls.dist(a) > want - 0.002);
        }
    }
}

fn code(r: Result<Vec<Move>, CycleAlarm>) -> u16 {
    match r {
        Err(CycleAlarm::IslandPocket { code }) => code,
        Err(e) => panic!("{e:?}"),
        Ok(m) => panic!("no alarm: {} moves", m.len()),
    }
}

#[test]
fn every_alarm_has_its_case() {
    let (edge, islands) = example1();
    let s = spec(4.0, 0.5, 5.0, 0.0);
    let is = refs(&islands);
    // 61900: no edge contour.
    assert_eq!(code(plan(&s, &[], &is)), 61900);
    // 61901: not closed (the last element ends 2 mm off the start).
    let mut open = edge.clone();
    open.last_mut().unwrap().to.0 += mm(2.0);
    assert_eq!(code(plan(&s, &open, &is)), 61901);
    // 61983: the edge crosses itself (a bow tie), or has no area.
    let bow = vec![
        line((0.0, 0.0), (50.0, 50.0)),
        line((50.0, 50.0), (50.0, 0.0)),
        line((50.0, 0.0), (0.0, 50.0)),
        line((0.0, 50.0), (0.0, 0.0)),
    ];
    assert_eq!(code(plan(&s, &bow, &[])), 61983);
    let flat = vec![line((0.0, 0.0), (50.0, 0.0)), line((50.0, 0.0), (0.0, 0.0))];
    assert_eq!(code(plan(&s, &flat, &[])), 61983);
    // 61980: an island across the edge, outside it, crossing itself, empty.
    let out = rect(110.0, 40.0, 130.0, 50.0);
    assert_eq!(code(plan(&s, &edge, &[&out])), 61980);
    let far = rect(200.0, 40.0, 230.0, 50.0);
    assert_eq!(code(plan(&s, &edge, &[&far])), 61980);
    let bow_i: Vec<Elem> = bow
        .iter()
        .map(|e| Elem {
            from: (e.from.0 / 10 + mm(60.0), e.from.1 / 10 + mm(40.0)),
            to: (e.to.0 / 10 + mm(60.0), e.to.1 / 10 + mm(40.0)),
            arc: None,
        })
        .collect();
    assert_eq!(code(plan(&s, &edge, &[&bow_i])), 61980);
    assert_eq!(code(plan(&s, &edge, &[&[]])), 61980);
    // 61904: beyond the integer grid (±5 m).
    let huge = rect(0.0, 0.0, 9.0e3, 9.0e3);
    assert_eq!(code(plan(&s, &huge, &[])), 61904);
    // 61905: no cutter radius.
    assert_eq!(code(plan(&IslandSpec { r: 0, ..s }, &edge, &is)), 61905);
    // 61912: nothing left for the centre (a 8 mm slot, r + fal = 4.5).
    let slot = rect(0.0, 0.0, 50.0, 8.0);
    assert_eq!(code(plan(&s, &slot, &[])), 61912);
    // 61908: a manual start outside the tool-centre region (in an island; by a wall).
    assert_eq!(code(plan(&IslandSpec { start: Some(pt((49.0, 50.0))), ..s }, &edge, &is)), 61908);
    assert_eq!(code(plan(&IslandSpec { start: Some(pt((21.0, 50.0))), ..s }, &edge, &is)), 61908);
    // 61909: a helix of diameter below the cutter radius.
    let helix = |rad: f64| Plunge::Helix { rad: mm(rad), pitch: mm(1.0) };
    assert_eq!(code(plan(&IslandSpec { plunge: helix(1.9), ..s }, &edge, &is)), 61909);
    // 61910: the helix does not fit at an automatic start point (its centre is
    // where the pocket is widest, 9 mm of room at most here).
    let narrow = rect(0.0, 0.0, 100.0, 20.0);
    assert!(plan(&IslandSpec { plunge: helix(5.0), ..s }, &narrow, &[]).is_ok());
    assert_eq!(code(plan(&IslandSpec { plunge: helix(6.0), ..s }, &narrow, &[])), 61910);
    // 61914: … at the manual start point.
    let near_wall = IslandSpec { plunge: helix(3.0), start: Some(pt((50.0, 6.0))), ..s };
    assert_eq!(code(plan(&near_wall, &narrow, &[])), 61914);
    assert!(plan(&IslandSpec { start: Some(pt((50.0, 10.0))), ..near_wall }, &narrow, &[]).is_ok());
    // 61915: no room for the edge finish's approach arc (the centre region is a
    // 0.2 mm wide strip).
    let thin = rect(0.0, 0.0, 50.0, 8.2);
    assert_eq!(code(plan(&IslandSpec { job: Job::Edge, fal: 0, ..s }, &thin, &[])), 61915);
    // 61916: too short for the oscillation (the centre region is 1 mm long).
    let small = rect(0.0, 0.0, 10.0, 10.0);
    let swing = IslandSpec { plunge: Plunge::Swing { tan: 0.1 }, ..s };
    assert_eq!(code(plan(&swing, &small, &[])), 61916);
    assert!(plan(&swing, &narrow, &[]).is_ok());
    // 61918: the rest cutter not smaller than the previous one.
    assert_eq!(code(plan(&IslandSpec { job: Job::Rest { prev_r: mm(4.0) }, ..s }, &edge, &is)), 61918);
    // 61913: no rest material (a rectangle without islands, corners sharp: the
    // rest is in the corners; with r = 4 after 4.1 almost nothing: a circle has none).
    let circle = vec![arc((0.0, 0.0), (0.0, 0.0), (20.0, 0.0), false)];
    assert_eq!(code(plan(&IslandSpec { job: Job::Rest { prev_r: mm(6.0) }, ..s }, &circle, &[])), 61913);
}

#[test]
fn rest_clears_what_the_larger_cutter_left() {
    let (edge, islands) = example1();
    let big = spec(5.0, 0.5, 5.0, 0.0);
    let rough = plan(&big, &edge, &refs(&islands)).unwrap();
    let small = IslandSpec { job: Job::Rest { prev_r: mm(5.0) }, ..spec(2.0, 0.5, 5.0, 0.0) };
    let rest = plan(&small, &edge, &refs(&islands)).unwrap();
    let walls = Walls::new(&edge, &islands);
    check_gouge(&small, &walls, &rest);
    check_cover(&walls, &[(&big, &rough), (&small, &rest)]);
    // Only the rest: far less path than roughing it all with the small cutter.
    let all = plan(&IslandSpec { job: Job::Rough, ..small }, &edge, &refs(&islands)).unwrap();
    let length =
        |m: &[Move]| segments(m, small.levels.to).iter().map(|(a, b)| libm::hypot(b.0 - a.0, b.1 - a.1)).sum::<f64>();
    assert!(length(&rest) < length(&all) / 2.0, "{} vs {}", length(&rest), length(&all));
}

#[test]
fn floor_finish_is_one_level_cleared_like_roughing() {
    let (edge, islands) = example1();
    let s = IslandSpec {
        job: Job::Floor,
        plunge: Plunge::Helix { rad: mm(3.0), pitch: mm(1.0) },
        ..spec(4.0, 0.5, 17.5, 6.0)
    };
    let moves = plan(&s, &edge, &refs(&islands)).unwrap();
    let floor = IslandSpec { levels: Levels { count: 1, ..s.levels }, ..s };
    let walls = Walls::new(&edge, &islands);
    check_gouge(&floor, &walls, &moves);
    check_cover(&walls, &[(&floor, &moves)]);
    // Straight down (G1), only to the floor.
    assert!(!moves.iter().any(|m| matches!(m, Move::Arc { to, .. } if to.d != s.levels.to)));
    let d = descents(&moves);
    assert!(d.iter().all(|(_, m)| matches!(m, Move::Line { to, .. } if to.d == s.levels.to)));
}

#[test]
fn swing_ramps_at_most_at_the_angle_and_ends_flat() {
    let (edge, islands) = example1();
    let tan = 0.1;
    let s = IslandSpec { plunge: Plunge::Swing { tan }, ..spec(4.0, 0.5, 8.0, 4.0) };
    let moves = check_clearing(&s, &edge, &islands);
    let mut pos = P3::default();
    let mut ramps = 0;
    for m in &moves {
        let to = crate::end_of(m).unwrap();
        if let Move::Line { .. } = m
            && to.d != pos.d
        {
            let run = libm::hypot((to.a - pos.a) as f64, (to.o - pos.o) as f64);
            assert!(((to.d - pos.d).abs() as f64) <= run * tan + 2.0, "{pos:?} → {to:?}");
            ramps += 1;
        }
        pos = to;
    }
    assert!(ramps > 0);
}

#[test]
fn a_manual_start_is_the_first_insertion_of_its_part() {
    let edge = rect(0.0, 0.0, 100.0, 50.0);
    let islands = vec![rect(45.0, 3.0, 55.0, 24.0), rect(45.0, 26.0, 55.0, 47.0)];
    let s = IslandSpec { start: Some(pt((80.0, 30.0))), ..spec(4.0, 0.5, 5.0, 0.0) };
    let pts = start_points(&s, &edge, &refs(&islands)).unwrap();
    assert_eq!(pts[0], pt((80.0, 30.0)));
    assert_eq!(pts.len(), 2);
    let moves = check_clearing(&s, &edge, &islands);
    assert!(matches!(moves[0], Move::Rapid(p) if (p.a, p.o) == pt((80.0, 30.0))));
}

#[test]
fn g2_cuts_the_edge_clockwise_and_islands_the_other_way() {
    let edge = rect(0.0, 0.0, 60.0, 40.0);
    let islands = vec![rect(25.0, 15.0, 35.0, 25.0)];
    for cw in [false, true] {
        let s = IslandSpec { cw, ..spec(4.0, 0.5, 5.0, 0.0) };
        let moves = check_clearing(&s, &edge, &islands);
        // The signed area swept about the pocket's centre by the cutting moves
        // of the outermost ring (the last ring before the lift), and about the
        // island by the ring nearest it.
        let segs = segments(&moves, s.levels.to);
        let turn = |c: (f64, f64), near: &dyn Fn((f64, f64)) -> bool| {
            segs.iter()
                .filter(|(a, b)| near(*a) && near(*b))
                .map(|(a, b)| (a.0 - c.0) * (b.1 - c.1) - (a.1 - c.1) * (b.0 - c.0))
                .sum::<f64>()
        };
        let walls = Walls::new(&edge, &islands);
        let w = |p: (f64, f64)| walls.dist(p);
        let outer = turn((30.0, 20.0), &|p| {
            (w(p) - 4.5).abs() < 0.01 && (p.0 < 20.0 || p.0 > 40.0 || p.1 < 10.0 || p.1 > 30.0)
        });
        let inner =
            turn((30.0, 20.0), &|p| (w(p) - 4.5).abs() < 0.01 && p.0 > 20.0 && p.0 < 40.0 && p.1 > 10.0 && p.1 < 30.0);
        assert_eq!(outer < 0.0, cw, "edge {outer}");
        assert_eq!(inner > 0.0, cw, "island {inner}");
    }
}

#[test]
fn odd_inputs_raise_alarms_or_plan_but_never_panic() {
    let (edge, islands) = example1();
    let base = spec(4.0, 0.5, 3.0, 0.0);
    let zero = line((10.0, 10.0), (10.0, 10.0));
    let mut with_zero = rect(0.0, 0.0, 40.0, 30.0);
    with_zero.insert(2, Elem { from: with_zero[1].to, to: with_zero[1].to, arc: None });
    let overlapping = vec![rect(10.0, 10.0, 20.0, 20.0), rect(15.0, 15.0, 25.0, 22.0)];
    let nested = vec![rect(10.0, 10.0, 30.0, 25.0), rect(12.0, 12.0, 14.0, 14.0)];
    let touching = vec![rect(0.0, 10.0, 10.0, 20.0)];
    let cases: Vec<(Vec<Elem>, Vec<Vec<Elem>>)> = vec![
        (vec![], vec![]),
        (vec![zero], vec![]),
        (with_zero.clone(), vec![]),
        (rect(0.0, 0.0, 40.0, 30.0), overlapping),
        (rect(0.0, 0.0, 40.0, 30.0), nested),
        (rect(0.0, 0.0, 40.0, 30.0), touching),
        (rect(0.0, 0.0, 4.0e6, 4.0e6), vec![]),
        (rect(-1.0e9, -1.0e9, 1.0e9, 1.0e9), vec![]),
        (rect(0.0, 0.0, 1e-6, 1e-6), vec![]),
        (edge.clone(), islands.clone()),
        (edge.clone(), vec![edge.clone()]),
        // (A full circle of radius 5 with r + fal = 4.5 plans, but takes 16 s in
        // a debug build: left to every_alarm_has_its_case's rest case.)
        (vec![arc((0.0, 0.0), (10.0, 0.0), (5.0, 0.0), true), arc((10.0, 0.0), (0.0, 0.0), (5.0, 3.0), true)], vec![]),
    ];
    let specs = [
        base,
        IslandSpec { r: 1, ..base },
        IslandSpec { step: 1, r: mm(0.5), ..base },
        IslandSpec { step: 0, ..base },
        IslandSpec { r: i64::MAX / 4, ..base },
        IslandSpec { fal: -5, ..base },
        IslandSpec { plunge: Plunge::Helix { rad: mm(3.0), pitch: 0 }, ..base },
        IslandSpec { plunge: Plunge::Swing { tan: 0.0 }, ..base },
        IslandSpec { job: Job::Rest { prev_r: mm(8.0) }, ..base },
        IslandSpec { job: Job::Edge, ..base },
        IslandSpec { job: Job::Floor, ..base },
        IslandSpec { start: Some((i64::MAX, i64::MIN)), ..base },
    ];
    for (e, i) in &cases {
        for s in &specs {
            let r = std::panic::catch_unwind(|| (plan(s, e, &refs(i)), start_points(s, e, &refs(i))));
            let (m, _) = r.unwrap_or_else(|_| panic!("panic: {s:?} {e:?} {i:?}"));
            if let Ok(m) = m {
                let mut pos = None;
                for x in &m {
                    let to = crate::end_of(x);
                    let full = matches!(x, Move::Arc { centre, to, .. } if *centre != (to.a, to.o));
                    assert!(full || to.is_none() || to != pos, "zero-length move");
                    pos = to;
                }
            }
        }
    }
}

//! CYCLE73 pocket milling with islands (seed 001 lines 6150-7392): the tool paths
//! of a pocket whose edge (CYCLE74) and islands (CYCLE75) are free contours of
//! lines and arcs in the working plane. A real offsetting of the pocket minus its
//! islands, not a rectangle approximation.
//!
//! The front end (`interp-siemens`' CYCLE73) reads and checks the call, the
//! engine (`interp-core`) reads the contours into [`Elem`] lists in plane nm and
//! calls [`plan`] once when the cycle starts; the moves it returns are emitted one
//! by one (dry run first, then the real run). [`start_points`] gives the insertion
//! points for pre-drilling (`_VARI` units 5): the modal drilling cycle runs at
//! each. Built only with the feature `island` (it needs `alloc`: the host and
//! boards with a heap; the F405 leaves the cycle out, alarm 4007).
//!
//! # Geometry (decisions where the document is silent; docs/SIEMENS-MILL.md)
//! - Contours → polygons: closed within 1 µm element to element (61901);
//!   zero-length elements dropped; arcs cut into steps whose deviation is at
//!   most 0.9 µm, on the side away from the material (chords where the arc's
//!   centre is on the pocket side, tangent polygons where it is on the
//!   material side), so the polygon never takes material. A contour that
//!   crosses or touches itself, or has less than 100 µm² of area: 61983 (edge),
//!   61980 (island); no edge: 61900. Either sense; islands that overlap unite
//!   (one island); an island outside the edge or across it (more than 3 µm):
//!   61980. Coordinates beyond ±5 m (i_overlay's i32 grid of 10 nm) or more than
//!   400 ring levels: 61904. Cutter radius below 10 µm: 61905.
//! - Rings: the tool-centre region at d_k = r + fal + k·s, s = the step capped
//!   at 80 % of the diameter (line 6799), offset with round joins (i_overlay,
//!   step 0.01 π; the shrink adds the joins' 1.23e-4·d chord deviation so no
//!   ring comes nearer a wall than d_k). Each connected shape at one offset is a
//!   node of a tree (parent: the shape one step out that holds it). Rings are
//!   emitted as polylines (arcs become chords within 1 µm): no G2/G3 in
//!   clearing; the helix and the edge finish's approach arcs are arcs.
//! - Sense: G3 (`cw` false) cuts the outer contour of every shape
//!   counterclockwise and every hole (around an island) clockwise: the material
//!   is on the same side of the cutter everywhere (climb stays climb around an
//!   island); G2 reverses all.
//! - Order: level by level (insert, clear, lift; lines 6781-6787); per level,
//!   part by part (a root of the tree), depth first from each leaf outwards. A
//!   chain = one insertion at a leaf, its rings, then its ancestors' rings while
//!   it is the last child cut; then lift (`lift` 0: RTP, 1: RFP + SDIS) and go
//!   to the next leaf. The first level is entered from RFP + SDIS, later ones
//!   from SDIS above the level before (already cut). Insertion point: the
//!   leaf's point farthest from its boundary (shrunk by halves to 2 µm).
//! - Links, gouge free: (1) to a node's first ring: the nearest point of the
//!   node's boundary from where the tool is (inside the node's shape): the disc
//!   about the tool through that point holds no boundary, so the segment is in
//!   the shape, which is in the tool-centre region. (2) between rings of one
//!   node: along the ring just cut (cut already) to its point closest to the
//!   next ring, then straight. (3) visits: see below. Every straight link is
//!   also checked against the tool-centre region; one that would leave it goes
//!   up, across and in again (the insertion if it fits there, else G1) —
//!   none does in the tests' pockets.
//! - Coverage: material the rings leave (s > r: in corners and on the medial
//!   axis) = (tool-centre region grown by r) − (the rings' swept area), opened
//!   by 3 µm; for each piece, a visit of the centre at its inner point (or the
//!   nearest point of the tool-centre region), repeated until nothing is left
//!   (50 rounds, else 61911). A visit is cut as an excursion from the nearest
//!   point of its node's boundary and back.
//! - Helix (`_VARI` x2x): about the insertion point, starting at +rad on the
//!   abscissa, in the pocket's sense, whole turns of at most `pitch`, one flat
//!   turn, then straight to the centre. 61909: helix diameter below the
//!   cutter radius (2·rad < r). 61910/61914: the helix circle is not inside the
//!   tool-centre region (automatic / manual start).
//! - Swing (`_VARI` x3x): along the longest of 32 directions through the
//!   insertion point, half length up to 4 r within the tool-centre region:
//!   centre → +L → centre → −L → centre …, each leg at most L·tan deep, a
//!   multiple of four legs, then one flat oscillation. 61916: 2 L < r.
//! - Manual start: must lie in the tool-centre region (61908); it replaces
//!   the insertion of the nearest leaf of its part to which a straight move
//!   from it stays in the region (none: 61908); that leaf's chain is cut first.
//! - Edge finish: each contour of the tool-centre region at r (edge and
//!   islands; where they come closer than 2 r they merge), per level; approach
//!   and departure on quarter arcs of radius r (or r/2, r/4) tangent at the
//!   middle of the ring's longest side; none fits: 61915. Vertical insertion
//!   at the approach arc's start.
//! - Floor finish: one level (the last of `levels`), cleared like roughing with
//!   `fal` on the walls, vertical insertion.
//! - Rest: the rest = (region at fal) − (the previous cutter's reach: the
//!   region at prev_r + fal grown by prev_r), within this cutter's reach, opened
//!   by 3 µm; none: 61913; r ≥ prev_r: 61918. Rings as roughing but clipped to
//!   the rest grown by r (tool centres that touch rest material).
//! - Not raised here: 61917 (a warning), 61982 (the front end's `_MIDA`
//!   check), the file alarms.

extern crate alloc;

mod poly;
#[cfg(test)]
mod tests;
#[cfg(test)]
extern crate std;

use crate::infeed::{Levels, parts};
use crate::v2;
use crate::{CycleAlarm, Elem, Move, P3};
use alloc::vec::Vec;
use i_overlay::core::overlay_rule::OverlayRule;
use poly::{Pt, Ring, Shape, Shapes, TooLarge, area, crosses, dist, nearest_on_seg};

/// How the cutter gets down to a level at an insertion point (`_VARI` tens).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Plunge {
    /// G1 straight down at `_FFD` (`_VARI` x1x; also the finishing jobs').
    Vertical,
    /// On a helix of centre-path radius `rad` (`_RAD`) in the pocket's milling
    /// direction, in whole turns of at most `pitch` (`_DP1`) per turn, then one
    /// flat full circle (`_VARI` x2x).
    Helix {
        /// Radius of the tool centre's helix.
        rad: i64,
        /// Largest depth per turn.
        pitch: i64,
    },
    /// Oscillating along a straight line at a slope of at most `tan` (the tangent
    /// of `_RAD`, the largest insertion angle), then one flat pass (`_VARI` x3x).
    Swing {
        /// Tangent of the largest insertion angle.
        tan: f64,
    },
}

/// What one CYCLE73 call cuts (`_VARI` units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Job {
    /// 1: clear the pocket from solid down to the allowances `fal`/`fald`.
    Rough,
    /// 2: clear what a previous clearing with the larger cutter radius `prev_r`
    /// left (its corners and narrow places), with this smaller cutter.
    Rest {
        /// Radius of the cutter of the previous clearing (`_TN`'s tool).
        prev_r: i64,
    },
    /// 3: finish the edge and each island once around (per level), reached and
    /// left on tangential arcs.
    Edge,
    /// 4: finish the floor in one level (the front end's `levels`).
    Floor,
}

/// A CYCLE73 call as the geometry needs it; lengths nm, work coordinates of the
/// plane (abscissa, ordinate) and the applicate (infeed axis).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IslandSpec {
    /// What is cut.
    pub job: Job,
    /// Cutter radius (> 0).
    pub r: i64,
    /// Allowance left on the edge and the islands in the plane (`_FAL`; 0 for the
    /// edge finish).
    pub fal: i64,
    /// Largest step between neighbouring paths in the plane (`_MIDA`, or 80 % of
    /// the cutter diameter).
    pub step: i64,
    /// The depth levels (from RFP + SDIS to the job's last level: `_DP` + `_FALD`
    /// roughing, `_DP` finishing; one level for the floor finish).
    pub levels: Levels,
    /// Retract plane `_RTP`.
    pub rtp: i64,
    /// RFP + SDIS.
    pub safe: i64,
    /// `_SDIS`.
    pub sdis: i64,
    /// +1 or −1: into the material along the applicate.
    pub dir: i64,
    /// `_VARI` hundreds: 0 retract to `_RTP`, 1 to RFP + SDIS, between insertion
    /// points and at the end.
    pub lift: u8,
    /// Insertion.
    pub plunge: Plunge,
    /// `_VARI` thousands 2: the manual start point (`_PA`, `_PO`); the cycle adds
    /// its own where the pocket divides. `None`: automatic.
    pub start: Option<(i64, i64)>,
    /// The pocket is cut clockwise (G2) around its edge: from `_CDIR` and the
    /// spindle direction (the front end's).
    pub cw: bool,
    /// Feeds: depth `_FFD`, plane `_FFP1`.
    pub feeds: [i64; 2],
}

/// The moves of one CYCLE73 call: from where the cycle starts (at or above the
/// retract plane) to the retract at the end; `edge` is the pocket's edge, each of
/// `islands` one island, closed contours in the plane (as CYCLE74/CYCLE75 gave
/// them: either sense). Alarms (61901, 61904, 61908-61918, 61980-61983): the
/// call moves nothing.
pub fn plan(spec: &IslandSpec, edge: &[Elem], islands: &[&[Elem]]) -> Result<Vec<Move>, CycleAlarm> {
    let g = Geometry::new(spec, edge, islands)?;
    match spec.job {
        Job::Edge => {
            let laps = g.laps()?;
            Ok(g.emit_edge(&laps))
        }
        _ => {
            let c = g.clearing()?;
            Ok(g.emit_clearing(&c))
        }
    }
}

/// The insertion points the clearing of `spec` would use (pre-drilling,
/// `_VARI` units 5: the front end runs the modal drilling cycle at each), in the
/// order they are cut.
pub fn start_points(spec: &IslandSpec, edge: &[Elem], islands: &[&[Elem]]) -> Result<Vec<(i64, i64)>, CycleAlarm> {
    let g = Geometry::new(spec, edge, islands)?;
    let pts: Vec<Pt> = match spec.job {
        Job::Edge => g.laps()?.iter().map(|l| l.q_in).collect(),
        _ => g.clearing()?.chains.iter().map(|c| c.start).collect(),
    };
    Ok(pts.iter().map(|p| (nm(p[0]), nm(p[1]))).collect())
}

fn alarm(code: u16) -> CycleAlarm {
    CycleAlarm::IslandPocket { code }
}

fn nm(v: f64) -> i64 {
    crate::rot::round(v)
}

fn too_large(_: TooLarge) -> CycleAlarm {
    alarm(61904)
}

/// Largest chord deviation of a discretised arc, nm (the brief: ≤ 1 µm).
const DEV: f64 = 900.0;
/// Points closer than this are the same point (contour closure, links), nm.
const TOL: f64 = 1000.0;
/// Uncut material thinner than twice this is not material (the polygons'
/// chords), nm.
const SLIVER: f64 = 3000.0;
/// Most ring levels of one clearing (alarm 61904 beyond).
const MAX_LEVELS: i64 = 400;

/// The polygon of one closed contour, counterclockwise. `island`: its arcs are
/// approximated from outside the island (the chords never enter the pocket
/// side of the arc farther than [`DEV`] and never cut the island); the edge's
/// from inside the pocket.
fn polygon(k: &[Elem], island: bool) -> Result<Ring, CycleAlarm> {
    let bad = alarm(if island { 61980 } else { 61983 });
    if k.is_empty() {
        return Err(if island { bad } else { alarm(61900) });
    }
    // Closed, element after element.
    for (i, e) in k.iter().enumerate() {
        let next = &k[(i + 1) % k.len()];
        if v2::len(v2::sub(v2::fv(e.to), v2::fv(next.from))) > TOL {
            return Err(alarm(61901));
        }
    }
    let first = discretise(k, None).ok_or(bad)?;
    let ccw = area(&first) > 0.0;
    let mut pts = discretise(k, Some(ccw != island)).ok_or(bad)?;
    pts.dedup_by(|a, b| dist(*a, *b) < 1.0);
    while pts.len() > 1 && dist(pts[0], pts[pts.len() - 1]) < 1.0 {
        pts.pop();
    }
    if pts.len() < 3 || area(&pts).abs() < 1e8 {
        return Err(bad);
    }
    if self_intersects(&pts) {
        return Err(bad);
    }
    if area(&pts) < 0.0 {
        pts.reverse();
    }
    Ok(pts)
}

/// The points of contour `k` (each element's start and its arc's inner points).
/// `outside_left`: the contour's left side is the side the chords must not
/// enter (arcs curving to that side are approximated by tangents); `None`:
/// chords.
fn discretise(k: &[Elem], outside_left: Option<bool>) -> Option<Ring> {
    let mut pts = Vec::new();
    for e in k {
        let (f, t) = (v2::fv(e.from), v2::fv(e.to));
        if !(f.0.is_finite() && f.1.is_finite()) {
            return None;
        }
        pts.push([f.0, f.1]);
        let Some((c, cw)) = e.arc else { continue };
        let c = v2::fv(c);
        let (r0, r1) = (v2::len(v2::sub(f, c)), v2::len(v2::sub(t, c)));
        if r0 < 1.0 || (r0 - r1).abs() > TOL {
            return None;
        }
        let a0 = libm::atan2(f.1 - c.1, f.0 - c.0);
        let a1 = libm::atan2(t.1 - c.1, t.0 - c.0);
        let tau = 2.0 * core::f64::consts::PI;
        // The sweep in the arc's sense; an arc back to its start is a full turn.
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
        if v2::len(v2::sub(f, t)) > 1.0 && sw.abs() >= tau - 1e-12 {
            sw = 0.0;
        }
        // Steps of at most the angle whose chord deviates DEV.
        let step = 2.0 * libm::acos((1.0 - DEV / r0).clamp(-1.0, 1.0));
        let n = libm::ceil(sw.abs() / step.max(1e-6)).clamp(1.0, 100_000.0) as usize;
        let h = sw / n as f64;
        // Tangents instead of chords: corners at radius r/cos(h/2), midway.
        let centre_left = !cw;
        let outside = outside_left.is_some_and(|l| l == centre_left);
        if outside {
            let k = r0 / libm::cos(h / 2.0);
            for i in 0..n {
                let a = a0 + h * (i as f64 + 0.5);
                pts.push([c.0 + k * libm::cos(a), c.1 + k * libm::sin(a)]);
            }
        } else {
            for i in 1..n {
                let a = a0 + h * i as f64;
                pts.push([c.0 + r0 * libm::cos(a), c.1 + r0 * libm::sin(a)]);
            }
        }
    }
    Some(pts)
}

/// Whether two non-neighbouring edges of the closed polygon meet (or two
/// neighbours fold back onto each other).
fn self_intersects(p: &[Pt]) -> bool {
    let n = p.len();
    let seg = |i: usize| (p[i], p[(i + 1) % n]);
    let bb = |i: usize| {
        let (a, b) = seg(i);
        [a[0].min(b[0]), a[1].min(b[1]), a[0].max(b[0]), a[1].max(b[1])]
    };
    let boxes: Vec<[f64; 4]> = (0..n).map(bb).collect();
    for i in 0..n {
        for j in i + 1..n {
            let adjacent = j == i + 1 || (i == 0 && j == n - 1);
            let (x, y) = (boxes[i], boxes[j]);
            if x[2] + 1.0 < y[0] || y[2] + 1.0 < x[0] || x[3] + 1.0 < y[1] || y[3] + 1.0 < x[1] {
                continue;
            }
            let (a, b) = seg(i);
            let (c, d) = seg(j);
            if adjacent {
                // Folding back: the far end of one lies on the other.
                let (far, (s0, s1)) = if j == i + 1 { (d, (a, b)) } else { (c, (a, b)) };
                let _ = far;
                let other = if j == i + 1 { d } else { c };
                if nearest_on_seg(s0, s1, other).0 != s1 && dist(nearest_on_seg(s0, s1, other).0, other) < 1.0 {
                    return true;
                }
                continue;
            }
            if crosses(a, b, c, d, 0.0) || seg_dist(a, b, c, d) < 1.0 {
                return true;
            }
        }
    }
    false
}

fn seg_dist(a: Pt, b: Pt, c: Pt, d: Pt) -> f64 {
    let f = |p: Pt, s: Pt, t: Pt| dist(p, nearest_on_seg(s, t, p).0);
    f(a, c, d).min(f(b, c, d)).min(f(c, a, b)).min(f(d, a, b))
}

/// The plane geometry of one call: the region to clear and the tool-centre
/// region.
struct Geometry<'a> {
    spec: &'a IslandSpec,
    /// The pocket minus its islands (the islands united).
    region: Shapes,
    /// Where the tool centre may be: `region` shrunk by r + fal (by r for the
    /// edge finish).
    a0: Shapes,
    /// Ring step (s ≤ `spec.step`).
    step: f64,
}

impl<'a> Geometry<'a> {
    fn new(spec: &'a IslandSpec, edge: &[Elem], islands: &[&[Elem]]) -> Result<Self, CycleAlarm> {
        // Below the grid's resolution a cutter is no cutter.
        if spec.r < 10_000 {
            return Err(alarm(61905));
        }
        let e = polygon(edge, false)?;
        let mut isl: Shapes = Vec::new();
        for k in islands {
            isl.push(alloc::vec![polygon(k, true)?]);
        }
        let edge_s: Shapes = alloc::vec![alloc::vec![e]];
        // An island outside the edge, or across it: 61980.
        let out = poly::boolean(&isl, &edge_s, OverlayRule::Difference).map_err(too_large)?;
        if poly::offset(&out, -SLIVER).map_err(too_large)?.iter().any(|s| !s.is_empty()) {
            return Err(alarm(61980));
        }
        let region = poly::boolean(&edge_s, &isl, OverlayRule::Difference).map_err(too_large)?;
        let fal = if spec.job == Job::Edge { 0 } else { spec.fal.max(0) };
        let a0 = poly::offset(&region, -((spec.r + fal) as f64)).map_err(too_large)?;
        if a0.is_empty() {
            return Err(alarm(61912));
        }
        let r = spec.r as f64;
        // At most 80 % of the diameter (line 6799: the plane infeed never
        // exceeds it; the front end raises 61982 for a larger `_MIDA`).
        let step = if spec.step > 0 { (spec.step as f64).min(1.6 * r) } else { 1.6 * r };
        Ok(Geometry { spec, region, a0, step: step.max(r / 16.0).max(1000.0) })
    }

    fn fal(&self) -> f64 {
        self.spec.fal.max(0) as f64
    }

    /// The tool-centre shapes of the clearing at ring offset `d` (from the
    /// walls), within `mask` if there is one.
    fn level_shapes(&self, d: f64, mask: Option<&Shapes>) -> Result<Shapes, CycleAlarm> {
        let s = poly::offset(&self.region, -d).map_err(too_large)?;
        match mask {
            Some(m) if !s.is_empty() => poly::boolean(&s, m, OverlayRule::Intersect).map_err(too_large),
            _ => Ok(s),
        }
    }

    /// The chains of the clearing (roughing, rest, floor): the ring tree,
    /// completed where rings leave material, ordered, with their insertions.
    fn clearing(&self) -> Result<Clearing, CycleAlarm> {
        let spec = self.spec;
        let r = spec.r as f64;
        let fal = self.fal();
        let d0 = r + fal;
        // Rest material: what the previous cutter's centre region, grown by its
        // radius, did not reach; only that (and the tool centres touching it).
        let (mask, target) = match spec.job {
            Job::Rest { prev_r } => {
                if spec.r >= prev_r {
                    return Err(alarm(61918));
                }
                let prev = poly::offset(&self.region, -(prev_r as f64 + fal)).map_err(too_large)?;
                let reach_prev = poly::offset(&prev, prev_r as f64).map_err(too_large)?;
                let wall = poly::offset(&self.region, -fal).map_err(too_large)?;
                let reach = poly::offset(&self.a0, r).map_err(too_large)?;
                let rest = poly::boolean(&wall, &reach_prev, OverlayRule::Difference).map_err(too_large)?;
                let rest = poly::boolean(&rest, &reach, OverlayRule::Intersect).map_err(too_large)?;
                let rest = opening(&rest)?;
                if rest.is_empty() {
                    return Err(alarm(61913));
                }
                let zone = poly::offset(&rest, r).map_err(too_large)?;
                (Some(zone), Some(rest))
            }
            _ => (None, None),
        };
        // The ring levels: d_k = r + fal + k·s until nothing is left (at most
        // half the region's smaller extent).
        let bb = bounds(&self.region);
        if ((bb[2] - bb[0]).min(bb[3] - bb[1]) / 2.0 - d0) / self.step > MAX_LEVELS as f64 {
            return Err(alarm(61904));
        }
        let mut nodes: Vec<Node> = Vec::new();
        let mut prev: Vec<usize> = Vec::new();
        let mut k = 0i64;
        loop {
            if k > MAX_LEVELS {
                return Err(alarm(61904));
            }
            let shapes = self.level_shapes(d0 + k as f64 * self.step, mask.as_ref())?;
            if shapes.is_empty() {
                break;
            }
            let mut cur = Vec::new();
            for sh in shapes {
                let p0 = sh[0][0];
                let parent = prev.iter().copied().find(|&i| poly::inside_shape(&nodes[i].shape, p0));
                let parent = parent.or_else(|| {
                    prev.iter().copied().min_by(|&a, &b| {
                        let da = poly::boundary_dist(core::slice::from_ref(&nodes[a].shape), p0);
                        let db = poly::boundary_dist(core::slice::from_ref(&nodes[b].shape), p0);
                        da.total_cmp(&db)
                    })
                });
                let id = nodes.len();
                if let Some(p) = parent {
                    nodes[p].children.push(id);
                }
                nodes.push(Node { shape: sh, parent, children: Vec::new(), visits: Vec::new() });
                cur.push(id);
            }
            prev = cur;
            k += 1;
        }
        if nodes.is_empty() {
            return Err(if mask.is_some() { alarm(61913) } else { alarm(61912) });
        }
        self.complete(&mut nodes, target.as_ref(), r)?;
        let chains = self.chains(&nodes)?;
        Ok(Clearing { nodes, chains })
    }

    /// Adds visits (points the tool centre goes to) where the rings leave
    /// material: the uncut = (the cutter's reach: a0 grown by r, or the rest
    /// material) minus the area the rings sweep, opened by [`SLIVER`].
    fn complete(&self, nodes: &mut [Node], target: Option<&Shapes>, r: f64) -> Result<(), CycleAlarm> {
        let rings: Vec<Ring> = nodes.iter().flat_map(|n| n.shape.iter().map(closed)).collect();
        let swept = poly::sweep(&rings, r).map_err(too_large)?;
        let reach = match target {
            Some(t) => t.clone(),
            None => poly::offset(&self.a0, r).map_err(too_large)?,
        };
        let mut uncut = opening(&poly::boolean(&reach, &swept, OverlayRule::Difference).map_err(too_large)?)?;
        for _ in 0..50 {
            if uncut.is_empty() {
                return Ok(());
            }
            let mut discs: Shapes = Vec::new();
            for u in &uncut {
                let mut c = poly::interior_point(u);
                if !poly::inside(&self.a0, c) {
                    c = nearest_boundary(&self.a0, c);
                }
                let at = deepest_node(nodes, c);
                nodes[at].visits.push(c);
                discs.push(alloc::vec![poly::circle(c, r * 0.999, 128)]);
            }
            // The discs' polygons lie inside the cutter's circle.
            let discs: Shapes = discs
                .into_iter()
                .map(|mut s| {
                    for ring in &mut s {
                        let c = ring_centre(ring);
                        let k = libm::cos(core::f64::consts::PI / 128.0);
                        for p in ring.iter_mut() {
                            *p = [c[0] + (p[0] - c[0]) * k, c[1] + (p[1] - c[1]) * k];
                        }
                    }
                    s
                })
                .collect();
            uncut = opening(&poly::boolean(&uncut, &discs, OverlayRule::Difference).map_err(too_large)?)?;
        }
        Err(alarm(61911))
    }

    /// The chains: per part (a connected piece of the tool-centre region, a
    /// root of the ring tree), depth first from each leaf outwards; a chain
    /// ends where its subtree's root has a later sibling.
    fn chains(&self, nodes: &[Node]) -> Result<Vec<Chain>, CycleAlarm> {
        let spec = self.spec;
        let roots: Vec<usize> = (0..nodes.len()).filter(|&i| nodes[i].parent.is_none()).collect();
        // The manual start: the part (root) that holds it, its leaf nearest.
        let mut manual: Option<(usize, Pt)> = None;
        if let Some((pa, po)) = spec.start {
            let p = [pa as f64, po as f64];
            if !poly::inside(&self.a0, p) {
                return Err(alarm(61908));
            }
            manual = Some((usize::MAX, p));
        }
        let mut leaves: Vec<(usize, Pt)> = Vec::new();
        for (i, n) in nodes.iter().enumerate() {
            if n.children.is_empty() {
                leaves.push((i, self.deepest(&n.shape)?));
            }
        }
        if let Some((_, p)) = manual {
            let root_of = |mut i: usize| {
                while let Some(q) = nodes[i].parent {
                    i = q;
                }
                i
            };
            let part = roots.iter().copied().find(|&rt| poly::inside_shape(&nodes[rt].shape, p));
            let mut cands: Vec<&(usize, Pt)> =
                leaves.iter().filter(|(l, _)| part.is_none_or(|rt| root_of(*l) == rt)).collect();
            cands.sort_by(|a, b| dist(a.1, p).total_cmp(&dist(b.1, p)));
            let pick = cands.into_iter().find(|(l, _)| {
                let q = nodes[*l].shape.iter().map(|c| poly::nearest_on_ring(c, p)).min_by(|a, b| a.2.total_cmp(&b.2));
                q.is_some_and(|q| poly::seg_inside(&self.a0, p, q.1, TOL))
            });
            match pick {
                Some(&(l, _)) => manual = Some((l, p)),
                None => return Err(alarm(61908)),
            }
        }
        // Nodes leading to the manual leaf go first.
        let mut first = alloc::vec![false; nodes.len()];
        if let Some((l, _)) = manual {
            let mut i = l;
            first[i] = true;
            while let Some(q) = nodes[i].parent {
                i = q;
                first[i] = true;
            }
        }
        let order = |v: &[usize]| {
            let mut v = v.to_vec();
            v.sort_by_key(|&i| !first[i]);
            v
        };
        let mut out: Vec<Chain> = Vec::new();
        for root in order(&roots) {
            // Iterative post order: (node, next child index).
            let mut stack: Vec<(usize, usize)> = alloc::vec![(root, 0)];
            let mut open: Vec<Vec<usize>> = Vec::new(); // chain under construction per depth
            let mut done: Vec<Vec<usize>> = Vec::new();
            while let Some(&mut (n, ref mut k)) = stack.last_mut() {
                let kids = order(&nodes[n].children);
                if *k < kids.len() {
                    let c = kids[*k];
                    *k += 1;
                    stack.push((c, 0));
                    continue;
                }
                stack.pop();
                // Children finished: the chain of the last child continues here;
                // a leaf starts one.
                let mut chain = if kids.is_empty() { Vec::new() } else { open.pop().unwrap_or_default() };
                if !kids.is_empty() {
                    // The earlier children's chains are finished.
                    for _ in 1..kids.len() {
                        if let Some(c) = open.pop() {
                            done.push(c);
                        }
                    }
                }
                chain.push(n);
                open.push(chain);
            }
            done.extend(open);
            // Chains in the order their leaves were reached.
            done.sort_by_key(|c| c.first().map(|&l| leaf_rank(nodes, root, l, &order)).unwrap_or(0));
            for c in done {
                let leaf = c[0];
                let (start, is_manual) = match manual {
                    Some((l, p)) if l == leaf => (p, true),
                    _ => (leaves.iter().find(|x| x.0 == leaf).map(|x| x.1).unwrap_or(nodes[leaf].shape[0][0]), false),
                };
                out.push(Chain { start, manual: is_manual, nodes: c });
            }
        }
        // The insertion must fit where it is.
        for c in &out {
            self.check_plunge(c.start, c.manual)?;
        }
        Ok(out)
    }

    /// The point of `shape` farthest from its boundary: shrunk by halves until
    /// (nearly) nothing is left.
    fn deepest(&self, shape: &Shape) -> Result<Pt, CycleAlarm> {
        let one: Shapes = alloc::vec![shape.clone()];
        let (mut lo, mut hi) = (0.0, self.step + self.spec.r as f64);
        let mut best = poly::interior_point(shape);
        for _ in 0..14 {
            let mid = (lo + hi) / 2.0;
            let s = poly::offset(&one, -mid).map_err(too_large)?;
            match s.iter().max_by(|a, b| poly::area(&a[0]).total_cmp(&poly::area(&b[0]))) {
                Some(big) => {
                    best = poly::interior_point(big);
                    lo = mid;
                }
                None => hi = mid,
            }
            if hi - lo < 2000.0 {
                break;
            }
        }
        Ok(best)
    }

    /// 61909/61910/61914/61916 for an insertion at `c`.
    fn check_plunge(&self, c: Pt, manual: bool) -> Result<(), CycleAlarm> {
        match self.spec.plunge {
            Plunge::Vertical => Ok(()),
            Plunge::Helix { rad, .. } => {
                if 2 * rad < self.spec.r {
                    return Err(alarm(61909));
                }
                if poly::boundary_dist(&self.a0, c) + TOL < rad as f64 || !poly::inside(&self.a0, c) {
                    return Err(alarm(if manual { 61914 } else { 61910 }));
                }
                Ok(())
            }
            Plunge::Swing { .. } => self.swing_line(c).map(|_| ()),
        }
    }

    /// The oscillation's direction and half length at `c`: the longest of 32
    /// directions both ways in the tool-centre region, at most 4 r; 61916 when
    /// it is shorter than the cutter radius.
    fn swing_line(&self, c: Pt) -> Result<(Pt, f64), CycleAlarm> {
        let mut best = ([1.0, 0.0], 0.0);
        for i in 0..32 {
            let a = core::f64::consts::PI * i as f64 / 32.0;
            let u = [libm::cos(a), libm::sin(a)];
            let l = poly::ray(&self.a0, c, u).min(poly::ray(&self.a0, c, [-u[0], -u[1]]));
            if l > best.1 {
                best = (u, l);
            }
        }
        let r = self.spec.r as f64;
        let l = (best.1 - TOL).min(4.0 * r);
        if 2.0 * l < r {
            return Err(alarm(61916));
        }
        Ok((best.0, l))
    }

    /// The edge finish: one lap per contour of the tool-centre region at r.
    fn laps(&self) -> Result<Vec<Lap>, CycleAlarm> {
        let r = self.spec.r as f64;
        let mut laps = Vec::new();
        let mut pos: Option<Pt> = None;
        let mut rings: Vec<Ring> = self.a0.iter().flatten().cloned().collect();
        while !rings.is_empty() {
            // The next contour: the nearest to the last.
            let i = match pos {
                None => 0,
                Some(p) => (0..rings.len())
                    .min_by(|&a, &b| {
                        poly::nearest_on_ring(&rings[a], p).2.total_cmp(&poly::nearest_on_ring(&rings[b], p).2)
                    })
                    .unwrap_or(0),
            };
            let ring = self.oriented(rings.swap_remove(i));
            // The approach at the middle of the longest side.
            let n = ring.len();
            let j = (0..n)
                .max_by(|&a, &b| dist(ring[a], ring[(a + 1) % n]).total_cmp(&dist(ring[b], ring[(b + 1) % n])))
                .unwrap_or(0);
            let (a, b) = (ring[j], ring[(j + 1) % n]);
            let p = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
            let t = v2::unit((b[0] - a[0], b[1] - a[1]));
            let nrm = if self.spec.cw { v2::mul(v2::left(t), -1.0) } else { v2::left(t) };
            let mut found = None;
            for rho in [r, r / 2.0, r / 4.0] {
                let m = [p[0] + nrm.0 * rho, p[1] + nrm.1 * rho];
                let q_in = [m[0] - t.0 * rho, m[1] - t.1 * rho];
                let q_out = [m[0] + t.0 * rho, m[1] + t.1 * rho];
                // Both quarter arcs inside the tool-centre region (sampled).
                let ok = (1..=16).all(|s| {
                    let ang = core::f64::consts::FRAC_PI_2 * s as f64 / 16.0;
                    let (ca, sa) = (libm::cos(ang), libm::sin(ang));
                    [-1.0, 1.0].iter().all(|&sg| {
                        // From p: p − m = −n·ρ, turning towards ±t.
                        let v = [-nrm.0 * ca + sg * t.0 * sa, -nrm.1 * ca + sg * t.1 * sa];
                        let x = [m[0] + v[0] * rho, m[1] + v[1] * rho];
                        poly::inside(&self.a0, x) || poly::boundary_dist(&self.a0, x) < 50.0
                    })
                });
                if ok {
                    found = Some((m, q_in, q_out));
                    break;
                }
            }
            let Some((m, q_in, q_out)) = found else { return Err(alarm(61915)) };
            let mut pts = Vec::with_capacity(n + 1);
            pts.push(p);
            for k in 1..=n {
                pts.push(ring[(j + k) % n]);
            }
            pts.push(p);
            pos = Some(q_out);
            laps.push(Lap { m, q_in, q_out, pts });
        }
        Ok(laps)
    }

    /// A contour of i_overlay's (outer counterclockwise, holes clockwise: the
    /// region on the left) turned for the milling direction: G2 around the
    /// edge reverses every contour.
    fn oriented(&self, mut c: Ring) -> Ring {
        if self.spec.cw {
            c.reverse();
        }
        c
    }

    fn lift_z(&self) -> i64 {
        if self.spec.lift == 1 { self.spec.safe } else { self.spec.rtp }
    }

    /// Where level `k`'s insertion starts: the safety plane for the first (or
    /// the levels' start, when deeper), then the safety distance above the
    /// level before.
    fn approach(&self, levels: &Levels, k: u32) -> i64 {
        let s = self.spec;
        let deeper = |z: i64| (z - s.safe) * s.dir.signum() > 0;
        let z = if k <= 1 { levels.from } else { levels.level(k - 1) - s.dir.signum() * s.sdis.abs() };
        if deeper(z) { z } else { s.safe }
    }

    fn levels(&self) -> Levels {
        let l = self.spec.levels;
        match self.spec.job {
            Job::Floor => Levels { count: 1, ..l },
            _ => Levels { count: l.count.max(1), ..l },
        }
    }

    fn plunge(&self) -> Plunge {
        match self.spec.job {
            Job::Floor | Job::Edge => Plunge::Vertical,
            _ => self.spec.plunge,
        }
    }

    fn emit_clearing(&self, cl: &Clearing) -> Vec<Move> {
        let mut e = Emit::new(self);
        let levels = self.levels();
        for k in 1..=levels.count {
            let z = levels.level(k);
            let from = self.approach(&levels, k);
            for c in &cl.chains {
                let how = if c.manual || self.spec.job != Job::Floor { self.plunge() } else { Plunge::Vertical };
                e.insert(how, c.start, from, z);
                for &n in &c.nodes {
                    e.node(&cl.nodes[n], z, from);
                }
                e.lift();
            }
        }
        e.out
    }

    fn emit_edge(&self, laps: &[Lap]) -> Vec<Move> {
        let mut e = Emit::new(self);
        let levels = self.levels();
        let f = self.spec.feeds[1];
        for k in 1..=levels.count {
            let z = levels.level(k);
            let from = self.approach(&levels, k);
            for l in laps {
                e.insert(Plunge::Vertical, l.q_in, from, z);
                let arc =
                    |to: Pt| Move::Arc { to: p3(to, z), centre: (nm(l.m[0]), nm(l.m[1])), cw: self.spec.cw, feed: f };
                e.push(arc(l.pts[0]));
                for &p in &l.pts[1..] {
                    e.push(Move::Line { to: p3(p, z), feed: f });
                }
                e.push(arc(l.q_out));
                e.lift();
            }
        }
        e.out
    }
}

fn p3(p: Pt, d: i64) -> P3 {
    P3::new(nm(p[0]), nm(p[1]), d)
}

/// `c` closed (its first point again at the end), as a path.
fn closed(c: &Ring) -> Ring {
    let mut v = c.clone();
    if let Some(&p) = c.first() {
        v.push(p);
    }
    v
}

/// The bounding box of `s`: min abscissa, ordinate, max abscissa, ordinate.
fn bounds(s: &Shapes) -> [f64; 4] {
    let mut b = [f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY];
    for p in s.iter().flatten().flatten() {
        b = [b[0].min(p[0]), b[1].min(p[1]), b[2].max(p[0]), b[3].max(p[1])];
    }
    b
}

fn ring_centre(r: &Ring) -> Pt {
    let n = r.len().max(1) as f64;
    let s = r.iter().fold([0.0, 0.0], |a, p| [a[0] + p[0], a[1] + p[1]]);
    [s[0] / n, s[1] / n]
}

/// The closest points of rings `a` and `b`: (segment of a, point, segment of
/// b, point, distance).
fn closest_pair(a: &Ring, b: &Ring) -> (usize, Pt, usize, Pt, f64) {
    let mut best = (0, a[0], 0, b[0], f64::INFINITY);
    let (n, m) = (a.len(), b.len());
    for (i, &p) in a.iter().enumerate() {
        let (j, q, d) = poly::nearest_on_ring(b, p);
        if d < best.4 {
            best = (i % n, p, j, q, d);
        }
    }
    for (j, &q) in b.iter().enumerate() {
        let (i, p, d) = poly::nearest_on_ring(a, q);
        if d < best.4 {
            best = (i, p, j % m, q, d);
        }
    }
    best
}

fn nearest_boundary(s: &Shapes, p: Pt) -> Pt {
    s.iter().flatten().map(|c| poly::nearest_on_ring(c, p)).min_by(|a, b| a.2.total_cmp(&b.2)).map(|x| x.1).unwrap_or(p)
}

/// The deepest node whose shape holds `c` (or is nearest it).
fn deepest_node(nodes: &[Node], c: Pt) -> usize {
    let mut best: Option<usize> = None;
    for (i, n) in nodes.iter().enumerate() {
        if poly::inside_shape(&n.shape, c) {
            best = Some(i); // later nodes are deeper
        }
    }
    best.unwrap_or_else(|| {
        (0..nodes.len())
            .min_by(|&a, &b| {
                poly::boundary_dist(core::slice::from_ref(&nodes[a].shape), c)
                    .total_cmp(&poly::boundary_dist(core::slice::from_ref(&nodes[b].shape), c))
            })
            .unwrap_or(0)
    })
}

/// The rank of leaf `l` in the depth-first order of `root`'s tree.
fn leaf_rank(nodes: &[Node], root: usize, l: usize, order: &dyn Fn(&[usize]) -> Vec<usize>) -> usize {
    let mut stack = alloc::vec![root];
    let mut rank = 0;
    while let Some(n) = stack.pop() {
        if n == l {
            return rank;
        }
        let kids = order(&nodes[n].children);
        if kids.is_empty() {
            rank += 1;
        }
        stack.extend(kids.into_iter().rev());
    }
    rank
}

/// `s` without what is thinner than 2·[`SLIVER`].
fn opening(s: &Shapes) -> Result<Shapes, CycleAlarm> {
    let t = poly::offset(s, -SLIVER).map_err(too_large)?;
    if t.is_empty() {
        return Ok(t);
    }
    poly::offset(&t, SLIVER).map_err(too_large)
}

/// One node of the ring tree: a connected shape of the tool-centre region at
/// one ring offset; its contours are rings.
struct Node {
    shape: Shape,
    parent: Option<usize>,
    children: Vec<usize>,
    /// Points the centre visits after the rings (material the rings leave).
    visits: Vec<Pt>,
}

/// The ring tree and its chains.
struct Clearing {
    nodes: Vec<Node>,
    chains: Vec<Chain>,
}

/// Nodes cut after one insertion: from a leaf outwards.
struct Chain {
    start: Pt,
    manual: bool,
    nodes: Vec<usize>,
}

/// An edge-finish lap: the approach arc's centre, its start, the lap (from
/// its first point around back to it), the departure arc's end.
struct Lap {
    m: Pt,
    q_in: Pt,
    q_out: Pt,
    pts: Vec<Pt>,
}

/// The moves as they are laid out.
struct Emit<'g, 'a> {
    g: &'g Geometry<'a>,
    out: Vec<Move>,
    pos: Option<P3>,
}

impl<'g, 'a> Emit<'g, 'a> {
    fn new(g: &'g Geometry<'a>) -> Self {
        Emit { g, out: Vec::new(), pos: None }
    }

    /// Appends `m` unless it goes nowhere (a full circle goes somewhere).
    fn push(&mut self, m: Move) {
        let Some(to) = crate::end_of(&m) else {
            self.out.push(m);
            return;
        };
        let turn = matches!(m, Move::Arc { centre, .. } if centre != (to.a, to.o));
        if self.pos == Some(to) && !turn {
            return;
        }
        self.pos = Some(to);
        self.out.push(m);
    }

    fn at(&self) -> Pt {
        self.pos.map(|p| [p.a as f64, p.o as f64]).unwrap_or([0.0, 0.0])
    }

    /// Up to the lift plane where the tool is.
    fn lift(&mut self) {
        if let Some(p) = self.pos {
            self.push(Move::Rapid(p.at(self.g.lift_z())));
        }
    }

    /// To insertion point `c` above the material (from the retract plane the
    /// first time, else from the lift plane), down to `from` at G0, then into
    /// the material to `z` by `how`.
    fn insert(&mut self, how: Plunge, c: Pt, from: i64, z: i64) {
        let g = self.g;
        let s = g.spec;
        let f = s.feeds[0];
        let (start, swing) = match how {
            Plunge::Helix { rad, .. } => ([c[0] + rad as f64, c[1]], None),
            Plunge::Swing { .. } => (c, g.swing_line(c).ok()),
            Plunge::Vertical => (c, None),
        };
        let plane = if self.pos.is_none() { s.rtp } else { g.lift_z() };
        self.lift();
        self.push(Move::Rapid(p3(start, plane)));
        self.push(Move::Rapid(p3(start, from)));
        match how {
            Plunge::Vertical => self.push(Move::Line { to: p3(c, z), feed: f }),
            Plunge::Helix { pitch, .. } => {
                let n = parts(z - from, pitch).min(100_000);
                let l = Levels { from, to: z, count: n };
                let centre = (nm(c[0]), nm(c[1]));
                for t in 1..=n {
                    self.push(Move::Arc { to: p3(start, l.level(t)), centre, cw: s.cw, feed: f });
                }
                // One flat turn, and to the centre (inside the helix's circle).
                self.push(Move::Arc { to: p3(start, z), centre, cw: s.cw, feed: f });
                self.push(Move::Line { to: p3(c, z), feed: s.feeds[1] });
            }
            Plunge::Swing { tan } => {
                let (u, len) = swing.unwrap_or(([1.0, 0.0], 0.0));
                let leg = libm::round(4.0 * len * tan) as i64;
                let n = parts(z - from, leg).min(25_000) * 4;
                let l = Levels { from, to: z, count: n };
                let pt = |i: u32| {
                    let k = [1.0, 0.0, -1.0, 0.0][(i as usize + 3) & 3];
                    [c[0] + u[0] * len * k, c[1] + u[1] * len * k]
                };
                for i in 1..=n {
                    self.push(Move::Line { to: p3(pt(i), l.level(i)), feed: f });
                }
                // One flat oscillation.
                for i in 1..=4 {
                    self.push(Move::Line { to: p3(pt(i), z), feed: f });
                }
            }
        }
    }

    /// A straight move in the plane to `q` at `z`, when it stays in the tool-
    /// centre region; else up, across and in again (vertically).
    fn link(&mut self, q: Pt, z: i64, from: i64) {
        let p = self.at();
        if poly::seg_inside(&self.g.a0, p, q, TOL) {
            self.push(Move::Line { to: p3(q, z), feed: self.g.spec.feeds[1] });
        } else {
            #[cfg(test)]
            tests::REINSERTED.with(|c| c.set(c.get() + 1));
            // In again as at a start point when the insertion fits here.
            let how = self.g.plunge();
            let how = if self.g.check_plunge(q, false).is_ok() { how } else { Plunge::Vertical };
            self.insert(how, q, from, z);
        }
    }

    /// Node `n`'s rings, each with the excursions to its visits where they are
    /// nearest: the first ring the one nearest the tool, each next one the
    /// remaining ring nearest the ring just cut, reached along that ring.
    fn node(&mut self, n: &Node, z: i64, from: i64) {
        let rings: Vec<Ring> = n.shape.iter().map(|c| self.g.oriented(c.clone())).collect();
        // Each visit on its ring: (ring, segment, parameter, foot, visit).
        let mut exc: Vec<(usize, usize, f64, Pt, Pt)> = Vec::new();
        for &v in &n.visits {
            let near =
                rings.iter().map(|c| poly::nearest_on_ring(c, v)).enumerate().min_by(|a, b| a.1.2.total_cmp(&b.1.2));
            if let Some((i, (j, q, _))) = near {
                let m = rings[i].len();
                let t = nearest_on_seg(rings[i][j], rings[i][(j + 1) % m], q).1;
                exc.push((i, j, t, q, v));
            }
        }
        let mut left: Vec<usize> = (0..rings.len()).collect();
        // The ring the tool stands on: (ring, segment, point).
        let mut on: Option<(usize, usize, Pt)> = None;
        while !left.is_empty() {
            let (k, j, q) = match on {
                None => {
                    // Nearest the tool (the disc argument: the link stays inside).
                    let p = self.at();
                    let (k, (j, q, _)) = left
                        .iter()
                        .map(|&i| (i, poly::nearest_on_ring(&rings[i], p)))
                        .min_by(|a, b| a.1.2.total_cmp(&b.1.2))
                        .unwrap_or((left[0], (0, p, 0.0)));
                    (k, j, q)
                }
                Some((c, cj, cq)) => {
                    let (k, (sa, pa, sb, pb, _)) = left
                        .iter()
                        .map(|&i| (i, closest_pair(&rings[c], &rings[i])))
                        .min_by(|a, b| a.1.4.total_cmp(&b.1.4))
                        .unwrap_or((left[0], (cj, cq, 0, rings[left[0]][0], 0.0)));
                    self.walk(&rings[c], (cj, cq), (sa, pa), z);
                    (k, sb, pb)
                }
            };
            left.retain(|&i| i != k);
            self.link(q, z, from);
            self.lap(&rings[k], j, q, exc.iter().filter(|e| e.0 == k).map(|e| (e.1, e.2, e.3, e.4)).collect(), z);
            on = Some((k, j, q));
        }
    }

    /// Along `ring` (already cut) from `a` to `b` (segment, point), forwards.
    fn walk(&mut self, ring: &Ring, a: (usize, Pt), b: (usize, Pt), z: i64) {
        let f = self.g.spec.feeds[1];
        let m = ring.len();
        let ta = nearest_on_seg(ring[a.0], ring[(a.0 + 1) % m], a.1).1;
        let tb = nearest_on_seg(ring[b.0], ring[(b.0 + 1) % m], b.1).1;
        let mut steps = (b.0 + m - a.0) % m;
        if steps == 0 && tb < ta {
            steps = m;
        }
        for k in 1..=steps {
            self.push(Move::Line { to: p3(ring[(a.0 + k) % m], z), feed: f });
        }
        self.push(Move::Line { to: p3(b.1, z), feed: f });
    }

    /// Once around `ring` from `q` on segment `j` back to `q`, with the
    /// excursions `exc` (segment, parameter, foot, visit): out to the visit and
    /// back to the foot. A visit lies in the node's shape and its foot is the
    /// nearest point of the shape's boundary: the disc about the visit through
    /// the foot holds no boundary, so the excursion stays in the shape.
    fn lap(&mut self, ring: &Ring, j: usize, q: Pt, exc: Vec<(usize, f64, Pt, Pt)>, z: i64) {
        let f = self.g.spec.feeds[1];
        let m = ring.len();
        let tq = nearest_on_seg(ring[j], ring[(j + 1) % m], q).1;
        // Positions along the lap: vertex j + k at k, the end q at m + tq.
        let at = |s: usize, t: f64| {
            let p = ((s + m - j) % m) as f64 + t;
            if s == j && t < tq { p + m as f64 } else { p }
        };
        let mut ex: Vec<(f64, Pt, Pt)> = exc.into_iter().map(|(s, t, foot, v)| (at(s, t), foot, v)).collect();
        ex.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut e = 0;
        for k in 1..=m + 1 {
            let (pos, to) = if k <= m { (k as f64, ring[(j + k) % m]) } else { (m as f64 + tq, q) };
            while e < ex.len() && ex[e].0 <= pos {
                let (_, foot, v) = ex[e];
                self.push(Move::Line { to: p3(foot, z), feed: f });
                self.push(Move::Line { to: p3(v, z), feed: f });
                self.push(Move::Line { to: p3(foot, z), feed: f });
                e += 1;
            }
            self.push(Move::Line { to: p3(to, z), feed: f });
        }
    }
}

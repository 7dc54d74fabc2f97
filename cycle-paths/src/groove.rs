//! G74 face (Z) and G75 outer (X) peck grooving, steps ① to ⑦ of 2.16.5–6.
//!
//! Written for G75 (peck along X, step along Z); G74 is the same with the axes
//! swapped. Columns A_n step by Δk from the start towards the end point's Z, the
//! last one at the end point's Z. In each column: feed Δi, rapid back e, feed
//! Δi + e, … until the next feed would reach B_n, then feed to B_n (①–③); relief Δd
//! along the step axis away from the end point (④; towards − when the end point is
//! level with the start); rapid back to the start's X (⑤); rapid to the next column
//! (⑥); after the last column rapid back to the start along the step axis (⑦).

use super::{StepQueue, sign};
use crate::alarm::{AlarmKind, CycleAlarm};
use crate::axis::Axis;
use crate::step::push;
use crate::step::{Pt, Step};

/// Where G74/G75 is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GrooveGen {
    /// Peck axis (X for G75, Z for G74).
    peck: Axis,
    /// Step axis.
    step: Axis,
    start: Pt,
    end: Pt,
    /// Peck depth per feed (Δi of G75, Δk of G74).
    peck_depth: i64,
    /// Column step (Δk of G75, Δi of G74).
    column: i64,
    relief: i64,
    retract: i64,
    /// Current column's position on the step axis.
    at: i64,
    /// Depth reached in the current column (peck axis); `None` before its first feed.
    depth: Option<i64>,
    done: bool,
    /// Dwell at the bottom of each column (CYCLE93 DTB), ms.
    dwell_ms: u32,
    /// The relief at the bottom moves at the cutting feed, towards the previous
    /// column (CYCLE93), instead of a rapid away from the end point.
    relief_feed: bool,
    /// Out of the column at the cutting feed (CYCLE93 with `_ZSD[4]` = 0).
    retract_feed: bool,
}

/// What CYCLE93 asks of one column beyond G74/G75 (see [`GrooveGen::options`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ColumnOptions {
    /// Dwell at the bottom, ms.
    pub dwell_ms: u32,
    /// Signed move along the step axis at the bottom, at the cutting feed (0: none).
    pub relief: i64,
    /// Out of the column at the cutting feed instead of rapid.
    pub retract_feed: bool,
}

impl GrooveGen {
    /// G75 (`face` false) or G74 from `start` to `end`. P/Q as written: `p` is Δi
    /// (X, radius), `q` is Δk (Z).
    pub fn new(face: bool, start: Pt, end: Pt, p: i64, q: i64, relief: i64, retract: i64) -> Result<Self, AlarmKind> {
        let (peck, step, peck_depth, column) = if face { (Axis::Z, Axis::X, q, p) } else { (Axis::X, Axis::Z, p, q) };
        if column == 0 && end.get(step) != start.get(step) {
            return Err(AlarmKind::CycleValueIllegal { what: "G74/G75 step P/Q is zero with a width to cut" });
        }
        Ok(GrooveGen {
            peck,
            step,
            start,
            end,
            peck_depth,
            column,
            relief,
            retract,
            at: start.get(step),
            depth: None,
            done: false,
            dwell_ms: 0,
            relief_feed: false,
            retract_feed: false,
        })
    }

    /// One column from `start` (the peck axis's start level) to `end` (its bottom)
    /// with the pecks of `peck` and the retract `retract` (CYCLE93's plunges: G75
    /// for a single column), and what `o` adds.
    pub fn column(face: bool, start: Pt, end: Pt, peck: i64, retract: i64, o: ColumnOptions) -> Self {
        let (peck_axis, step) = if face { (Axis::Z, Axis::X) } else { (Axis::X, Axis::Z) };
        GrooveGen {
            peck: peck_axis,
            step,
            start,
            end: end.with(step, start.get(step)),
            peck_depth: peck,
            column: 0,
            relief: o.relief,
            retract,
            at: start.get(step),
            depth: None,
            done: false,
            dwell_ms: o.dwell_ms,
            relief_feed: true,
            retract_feed: o.retract_feed,
        }
    }

    /// The point at `p` on the peck axis and `s` on the step axis (out of line: six
    /// moves).
    #[inline(never)]
    fn pt(&self, p: i64, s: i64) -> Pt {
        Pt::default().with(self.peck, p).with(self.step, s)
    }

    /// The next group of steps; `false` when finished.
    pub fn fill(&mut self, out: &mut StepQueue) -> Result<bool, AlarmKind> {
        if self.done {
            return Ok(false);
        }
        let (a0, b0) = (self.start.get(self.peck), self.end.get(self.peck));
        let dir = sign(b0 - a0);
        let reached = self.depth.unwrap_or(a0);
        if reached != b0 {
            // ①–③: feed to the next depth (or the bottom), then back e unless at the bottom.
            let next = if self.peck_depth == 0 { b0 } else { reached + dir * self.peck_depth };
            let next = if (b0 - next) * dir <= 0 { b0 } else { next };
            push(out, Step::Feed(self.pt(next, self.at)))?;
            self.depth = Some(next);
            if next != b0 {
                push(out, Step::Rapid(self.pt(next - dir * self.retract, self.at)))?;
            }
            return Ok(true);
        }
        // ④ relief, ⑤ back to the start's peck coordinate.
        let (s0, s1) = (self.start.get(self.step), self.end.get(self.step));
        let sdir = sign(s1 - s0);
        if self.dwell_ms > 0 {
            push(out, Step::Dwell(self.dwell_ms))?;
        }
        let relieved = if self.relief_feed {
            // CYCLE93: the relief is signed and cut.
            let r = self.at + self.relief;
            push(out, Step::Feed(self.pt(b0, r)))?;
            r
        } else {
            let relief_dir = if sdir == 0 { -1 } else { -sdir };
            let r = self.at + relief_dir * self.relief;
            push(out, Step::Rapid(self.pt(b0, r)))?;
            r
        };
        let up = self.pt(a0, relieved);
        push(out, if self.retract_feed { Step::Feed(up) } else { Step::Rapid(up) })?;
        if self.at == s1 {
            // ⑦ back to the start.
            push(out, Step::Rapid(self.start))?;
            self.done = true;
            return Ok(true);
        }
        // ⑥ next column (Δd + Δk from the relieved point), the last at the end's value.
        let next = self.at + sdir * self.column;
        self.at = if (s1 - next) * sdir <= 0 { s1 } else { next };
        push(out, Step::Rapid(self.pt(a0, self.at)))?;
        self.depth = None;
        Ok(true)
    }
}

use super::offset::Offsets;
use super::pass::PassGen;
use crate::geom::Seg;
use crate::geom::path::V2;
pub use crate::spec::job::GrooveSpec;

/// Where CYCLE93 is.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Phase {
    Approach,
    /// Plunge `i` (0-based), its pecks in `cut` once started.
    Column {
        i: u32,
        cut: Option<GrooveGen>,
    },
    /// Pass `j` of flank `side` (0 start side, 1 far side).
    Flank {
        side: u8,
        j: u32,
    },
    /// Finishing the side `side`.
    Finish {
        side: u8,
        cut: PassGen,
    },
    Return,
    Done,
}

/// CYCLE93 as an expansion: plunges, flanks, finishing passes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GroovingGen {
    spec: GrooveSpec,
    phase: Phase,
    /// Plunges, and the step coordinate of the first one's low side and the
    /// distance between them.
    columns: u32,
    first: i64,
    step: f64,
    /// Most a plunge or flank cut may move across (95 % of the tool width less
    /// the nose radius, line 10266).
    max_step: f64,
    /// Where the cycle starts and ends.
    home: Pt,
}

impl GroovingGen {
    /// Plans the plunges across the rough contour's opening.
    pub fn new(spec: &GrooveSpec, segs: &[Seg]) -> Result<Self, AlarmKind> {
        let (step_axis, _) = axes(spec);
        let width = spec.span.get(step_axis).abs();
        if width <= 0 {
            return Err(AlarmKind::SiemensCycle(CycleAlarm::ToolWidthWrong));
        }
        // Across the rough bottom: from one flank's foot to the other's (the flanks
        // above them are cut along their slope).
        let flanks = range(segs, spec.flanks);
        let (Some(a), Some(b)) = (flanks.first().map(|s| s.b), flanks.get(1).map(|s| s.b)) else {
            return Err(AlarmKind::SiemensCycle(CycleAlarm::GrooveFormWrong));
        };
        let (lo, hi) = (a.get(step_axis).min(b.get(step_axis)), a.get(step_axis).max(b.get(step_axis)));
        let open = hi - lo;
        let nose = spec.noses[0].0.max(spec.noses[1].0);
        let max_step = (0.95 * (width - nose) as f64).max(1.0);
        let columns = if open <= width { 1 } else { 1 + libm::ceil((open - width) as f64 / max_step) as u32 };
        let step = if columns > 1 { (open - width) as f64 / f64::from(columns - 1) } else { 0.0 };
        // The plunges go from the start side's edge towards the other.
        let from_lo = spec.edges[0].get(step_axis) <= spec.edges[1].get(step_axis);
        let first = if from_lo { lo } else { hi - width };
        let step = if from_lo { step } else { -step };
        let mut g =
            GroovingGen { spec: *spec, phase: Phase::Approach, columns, first, step, max_step, home: Pt::default() };
        let (c0, c1) = g.span_of(0);
        g.home = g.column_start(c0, c1).with(step_axis, g.reference(0));
        Ok(g)
    }

    /// The low and high side of plunge `i` along the step axis.
    #[inline(never)]
    fn span_of(&self, i: u32) -> (i64, i64) {
        let (step_axis, _) = axes(&self.spec);
        let width = self.spec.span.get(step_axis).abs();
        let lo = self.first + crate::geom::round_i64(self.step * f64::from(i));
        (lo, lo + width)
    }

    /// The step coordinate of edge D for plunge `i` (the tool covers [lo, hi]).
    fn reference(&self, i: u32) -> i64 {
        let (step_axis, _) = axes(&self.spec);
        let s = self.spec.span.get(step_axis);
        self.span_of(i).0 - s.min(0)
    }

    /// The plunge axis's start level over [c0, c1]: the surface's outermost, plus
    /// the safety distance (out of line: the set-up and each plunge).
    #[inline(never)]
    fn column_start(&self, c0: i64, c1: i64) -> Pt {
        let s = &self.spec;
        let (step_axis, plunge) = axes(s);
        let out = -s.inward;
        let (l0, l1) = (surface_level(s, step_axis, plunge, c0), surface_level(s, step_axis, plunge, c1));
        let top = if out > 0 { l0.max(l1) } else { l0.min(l1) };
        Pt::default().with(plunge, top + out * s.safety)
    }

    /// How deep the tool's flat bottom over [c0, c1] may go: where it first meets
    /// the rough contour (plunge-axis value), if the contour is under it.
    fn floor(&self, segs: &[Seg], c0: i64, c1: i64) -> Option<i64> {
        let s = &self.spec;
        let (step_axis, plunge) = axes(s);
        let mut best: Option<i64> = None;
        let mut see = |p: (f64, f64)| {
            let (x, z) = p;
            let (c, v) = if step_axis == Axis::Z { (z, x) } else { (x, z) };
            if c >= c0 as f64 - 0.5 && c <= c1 as f64 + 0.5 {
                let v = crate::geom::round_i64(v);
                // Outermost along the plunge axis: the least deep.
                best = Some(match best {
                    Some(b) if s.inward > 0 => b.min(v),
                    Some(b) => b.max(v),
                    None => v,
                });
            }
        };
        for seg in range(segs, s.rough) {
            // 17 points along the segment, then where it crosses the span's sides
            // (one loop: `see` and the point's evaluation are inlined once).
            let along = (0..=16).map(|k| f64::from(k) / 16.0);
            let sides = [c0, c1].into_iter().flat_map(|c| seg.crossings(step_axis, c as f64));
            for t in along.chain(sides) {
                see(seg.point_at(t));
            }
        }
        let _ = plunge;
        best
    }

    /// The next steps; false when the cycle is done.
    pub fn fill(&mut self, segs: &[Seg], here: Pt, out: &mut StepQueue) -> Result<bool, AlarmKind> {
        let (step_axis, plunge) = axes(&self.spec);
        match self.phase {
            Phase::Approach => {
                // Outside: along the longitudinal axis first; inside: the plane axis.
                let first = if self.spec.inward < 0 { Axis::Z } else { Axis::X };
                push(out, Step::Rapid(here.with(first, self.home.get(first))))?;
                push(out, Step::Rapid(self.home))?;
                self.phase = Phase::Column { i: 0, cut: None };
            }
            Phase::Column { i, cut } => {
                if i >= self.columns {
                    self.phase = Phase::Flank { side: 0, j: 0 };
                    return Ok(true);
                }
                let mut cut = match cut {
                    Some(g) => g,
                    None => {
                        let (c0, c1) = self.span_of(i);
                        let c = self.reference(i);
                        let start = self.column_start(c0, c1).with(step_axis, c);
                        let Some(bottom) = self.floor(segs, c0, c1) else {
                            self.phase = Phase::Column { i: i + 1, cut: None };
                            return Ok(true);
                        };
                        if (bottom - start.get(plunge)) * self.spec.inward <= 0 {
                            self.phase = Phase::Column { i: i + 1, cut: None };
                            return Ok(true);
                        }
                        // To the plunge's start parallel to the surface, then the pecks.
                        push(out, Step::Rapid(start))?;
                        let back = if i == 0 { 0 } else { -(self.step.signum() as i64) * crate::units::NM_PER_MM };
                        let o = ColumnOptions {
                            dwell_ms: self.spec.dwell_ms,
                            relief: back,
                            retract_feed: self.spec.retract_feed,
                        };
                        let end = start.with(plunge, bottom);
                        GrooveGen::column(self.spec.face, start, end, self.spec.peck, self.spec.safety, o)
                    }
                };
                let more = cut.fill(out)?;
                self.phase =
                    if more { Phase::Column { i, cut: Some(cut) } } else { Phase::Column { i: i + 1, cut: None } };
            }
            Phase::Flank { side, j } => self.flank(segs, side, j, out)?,
            Phase::Finish { side, mut cut } => {
                if cut.fill(segs, out)? {
                    self.phase = Phase::Finish { side, cut };
                } else if side == 0 {
                    self.phase = Phase::Finish { side: 1, cut: self.finishing(segs, 1)? };
                } else {
                    self.phase = Phase::Return;
                }
            }
            Phase::Return => {
                let up = here.with(plunge, self.home.get(plunge));
                push(out, Step::Rapid(up))?;
                push(out, Step::Rapid(self.home))?;
                self.phase = Phase::Done;
            }
            Phase::Done => return Ok(false),
        }
        Ok(true)
    }

    /// Pass `j` of a flank (one pass per 95 % of the tool width across it), the
    /// last on the flank's line: down along it with the edge on that side until the
    /// tool meets the rough contour, out along the plunge axis.
    fn flank(&mut self, segs: &[Seg], side: u8, j: u32, out: &mut StepQueue) -> Result<(), AlarmKind> {
        let (step_axis, plunge) = axes(&self.spec);
        let flanks = range(segs, self.spec.flanks);
        let Some(line) = flanks.get(usize::from(side)) else {
            self.phase = Phase::Finish { side: 0, cut: self.finishing(segs, 0)? };
            return Ok(());
        };
        let across = (line.b.get(step_axis) - line.a.get(step_axis)).abs();
        let passes = if across == 0 { 0 } else { libm::ceil(across as f64 / self.max_step) as u32 };
        if j >= passes {
            if side == 0 {
                self.phase = Phase::Flank { side: 1, j: 0 };
            } else {
                self.phase = Phase::Finish { side: 0, cut: self.finishing(segs, 0)? };
            }
            return Ok(());
        }
        // Towards the groove's middle by the passes still to come.
        let toward = sign(self.spec.edges[1].get(step_axis) - self.spec.edges[0].get(step_axis));
        let toward = if side == 0 { toward } else { -toward };
        let shift = crate::geom::round_i64(across as f64 * f64::from(passes - 1 - j) / f64::from(passes)) * toward;
        let (a, b) = (
            line.a.with(step_axis, line.a.get(step_axis) + shift),
            line.b.with(step_axis, line.b.get(step_axis) + shift),
        );
        // The edge on this side follows the line; the tool covers the width towards the middle.
        let w = self.spec.span.get(step_axis);
        let on_side_is_d = (w > 0) == (toward > 0);
        let edge_shift = if on_side_is_d { Pt::default() } else { Pt::new(-self.spec.span.x, -self.spec.span.z) };
        let cover = |p: Pt| {
            let c = p.get(step_axis);
            let far = c + toward * w.abs();
            (c.min(far), c.max(far))
        };
        // The deepest point along a → b the tool reaches without meeting the contour.
        let depth = |p: Pt| p.get(plunge) * self.spec.inward;
        let ok = |t: f64| {
            let p = lerp(a, b, t);
            let (c0, c1) = cover(p);
            // 2 µm: the edge is on the flank's own line, which the floor sees too.
            self.floor(segs, c0, c1).is_none_or(|f| depth(p) <= f * self.spec.inward + 2_000)
        };
        // The whole line if it is clear, else 30 halvings of [0, 1] (one call site
        // of `ok`: the floor search is inlined once).
        let (mut lo, mut hi, mut t) = (0.0, 1.0, 1.0);
        for i in 0..=30 {
            if ok(t) {
                lo = t;
                if i == 0 {
                    break;
                }
            } else {
                hi = t;
            }
            t = (lo + hi) / 2.0;
        }
        let end = lerp(a, b, lo);
        let add = |p: Pt| Pt::new(p.x + edge_shift.x, p.z + edge_shift.z);
        push(out, Step::Rapid(add(a)))?;
        push(out, Step::Feed(add(end)))?;
        push(out, Step::Rapid(add(end.with(plunge, a.get(plunge)))))?;
        self.phase = Phase::Flank { side, j: j + 1 };
        Ok(())
    }

    /// The finishing pass of side `side` with its own cutting edge.
    fn finishing(&self, segs: &[Seg], side: u8) -> Result<PassGen, AlarmKind> {
        let s = &self.spec;
        let (step_axis, plunge) = axes(s);
        let (from, to) = s.halves[usize::from(side)];
        let half = range(segs, (from, to));
        let (Some(first), Some(last)) = (half.first(), half.last()) else {
            return Err(AlarmKind::SiemensCycle(CycleAlarm::GrooveFormWrong));
        };
        // The edge on this side: D if D + 1 lies towards the middle.
        let towards_far = sign(s.edges[1].get(step_axis) - s.edges[0].get(step_axis));
        let d_on_start = sign(s.span.get(step_axis)) == towards_far;
        let use_d = (side == 0) == d_on_start;
        let shift = if use_d { Pt::default() } else { Pt::new(-s.span.x, -s.span.z) };
        let mv = |p: Pt| Pt::new(p.x + shift.x, p.z + shift.z);
        let out_level = self.home.get(plunge);
        let before = [Some(mv(first.a.with(plunge, out_level))), None, None];
        let after = [Some(mv(last.b.with(plunge, out_level))), None, None];
        let _ = step_axis;
        Ok(PassGen::new(self.offsets(side), (from, to), shift, before, 0, after))
    }

    /// The nose offsets of the edge finishing side `side`.
    fn offsets(&self, side: u8) -> Offsets {
        let s = &self.spec;
        let (step_axis, _) = axes(s);
        let towards_far = sign(s.edges[1].get(step_axis) - s.edges[0].get(step_axis));
        let d_on_start = sign(s.span.get(step_axis)) == towards_far;
        let (radius, tip) = if (side == 0) == d_on_start { s.noses[0] } else { s.noses[1] };
        let zero = V2::new(0.0, 0.0);
        let left = s.half1_left == (side == 0);
        Offsets {
            side: if left { 1.0 } else { -1.0 },
            equi: radius as f64,
            front: zero,
            back: zero,
            along: zero,
            tip: crate::geom::path::tip_vector(tip, radius),
        }
    }
}

/// The step and plunge axes.
fn axes(s: &GrooveSpec) -> (Axis, Axis) {
    if s.face { (Axis::X, Axis::Z) } else { (Axis::Z, Axis::X) }
}

/// The plunge-axis level of the groove's surface (the line through its edges) at
/// `c` on the step axis. Out of line: one copy for both ends of a column.
#[inline(never)]
fn surface_level(s: &GrooveSpec, step_axis: Axis, plunge: Axis, c: i64) -> i64 {
    let (e0, e1) = (s.edges[0], s.edges[1]);
    let d = e1.get(step_axis) - e0.get(step_axis);
    let t = if d == 0 { 0.0 } else { (c - e0.get(step_axis)) as f64 / d as f64 };
    e0.get(plunge) + crate::geom::round_i64(t * (e1.get(plunge) - e0.get(plunge)) as f64)
}

/// The segments of a range.
fn range(segs: &[Seg], (from, to): (u16, u16)) -> &[Seg] {
    segs.get(usize::from(from)..usize::from(to)).unwrap_or(&[])
}

/// The point at `t` between `a` and `b`.
#[inline(never)]
fn lerp(a: Pt, b: Pt, t: f64) -> Pt {
    let l = |p: i64, q: i64| p + crate::geom::round_i64((q - p) as f64 * t);
    Pt::new(l(a.x, b.x), l(a.z, b.z))
}

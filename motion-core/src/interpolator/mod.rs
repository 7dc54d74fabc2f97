//! The interpolator: runs the planned blocks one interpolation period at a time and
//! produces each axis's commanded position (Q16 steps) at the end of the period.
//!
//! Per period, integers only and no division: the speed profile advances the path
//! position `s` (Q8 nm); the progress `s / length` is one multiply by a reciprocal
//! taken when the block was queued; a line is `start + Δ·progress`, an arc
//! `centre + r·(cos θ, sin θ)` with the angle and radius linear in the progress
//! and cos/sin by CORDIC ([`cordic`](crate::cordic)). The end of a block is its
//! exact whole-step end point, computed from its nanometre end point, so nothing
//! accumulates from block to block.
//!
//! # Dense programs: as many blocks a period as their lengths need
//!
//! A speed is the distance of one period (Q8 nm). Each period takes the fastest of
//! accelerating by the block's acceleration `a`, keeping the speed, or braking by
//! `a` that passes the braking test, and runs that distance along the path: when a
//! block ends within the period and the next one may be blended into (G64, planned
//! entry above zero), the rest of the distance runs on the next block, and the next
//! — a chain of 0.02 mm blocks at 6 m/min runs five blocks a period. A block whose
//! end is a stop (exact stop, single block, the queue's end, a command, a rapid or
//! a spindle-locked block next) ends the period there, at rest.
//!
//! The braking test is exact for the planner's entry speeds `e` (the speed of the
//! period that reaches or crosses a block's start): a candidate speed `v` passes
//! when every boundary it crosses this period has `v ≤ e`, and for the first
//! boundary it does not reach the discrete braking distance
//! `B(v) = (v² − e² + a·(v + e)) / 2a` (this period and the braking periods after
//! it) fits the distance left, `a` being the smallest acceleration of the blocks
//! in between ([`profile::fits`]). Boundaries further on are tested too until one
//! of two things makes the rest certain: braking to rest fits before the boundary
//! (`(v + a/2)² ≤ 2a·distance`), or the rest of the queue is one run of blocks of
//! this acceleration, whose entries the planner chained so that passing the test for
//! one boundary passes it for all later ones (see
//! [`lookahead`](crate::planner::lookahead)). A speed that passed the test can
//! always brake by `a` in the next period and pass it again, so junction speeds,
//! the acceleration and every stop hold exactly; feed hold (the speed wanted drops
//! to zero) brakes by `a` a period across blocks and stops within
//! `B(v)` of where it was pressed.
pub mod profile;

use crate::axis::{AXIS_COUNT, Pos};
use crate::canon::SpindleSpeed;
use crate::cordic::{TRIG_FRAC, cos_sin};
use crate::fixed::{FRAC_BITS, PATH_FRAC, STEP_FRAC, mul_q32, mul_shr};
use crate::planner::block::Plan;
use crate::planner::{ArcGeom, AxisScale, Block, BlockKind, FeedSpec, Item, MotionParams, Planner};
use profile::{fits, next_speed};

/// What the operator and the spindle do to the speed this period.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Live {
    /// Feed override in Q8 (256 = 100 %).
    pub feed_ovr: u64,
    /// Rapid override in Q8.
    pub rapid_ovr: u64,
    /// Feed hold: brake to a stop on the path.
    pub hold: bool,
    /// End the running block at rest (single block, stopping for a reset).
    pub stop_at_end: bool,
    /// Measured spindle speed in revolutions per period, Q32 (feed per revolution).
    pub rev_per_tick: u64,
}

impl Live {
    /// 100 % overrides, no hold, spindle stopped.
    pub const NORMAL: Live = Live { feed_ovr: 256, rapid_ovr: 256, hold: false, stop_at_end: false, rev_per_tick: 0 };
}

/// How the speed of a segment is commanded, in its per-period form.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Rate {
    /// The axes' rapid rates; rapid override.
    Rapid,
    /// Q8 nm per period; feed override.
    PerMin(u64),
    /// Q8 nm per revolution × the measured revolutions per period; feed override.
    PerRev(i64),
}

/// An arc in interpolator terms.
#[derive(Clone, Copy, Debug, PartialEq)]
struct ArcPath {
    /// Indices of the plane's axes.
    ia: usize,
    ib: usize,
    /// Their scales (nm → steps).
    scale: [AxisScale; 2],
    /// Centre, nm.
    center: [i64; 2],
    /// Radius at the start and its change over the arc, nm.
    r0: i64,
    dr: i64,
    /// Start angle and signed sweep, turns × 2^32.
    theta0: i64,
    sweep: i64,
    /// An axis outside the plane moves too (a machining centre's helical
    /// interpolation): it moves linearly with the progress along the arc.
    helical: bool,
}

/// Per-axis profiles of an independent rapid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Independent {
    len: [u64; AXIS_COUNT],
    inv: [i64; AXIS_COUNT],
    accel: [u64; AXIS_COUNT],
    cap: [u64; AXIS_COUNT],
    s: [u64; AXIS_COUNT],
    v: [u64; AXIS_COUNT],
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Path {
    Line,
    Arc(ArcPath),
    Independent(Independent),
}

/// The running block, converted for per-period interpolation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    /// Source line.
    pub line: u32,
    /// Machine minus work coordinates.
    pub offset: Pos,
    /// Spindle during the block (G96 surface speed, commanded rpm).
    pub spindle: SpindleSpeed,
    /// Whether the speed is a rapid.
    pub rapid: bool,
    path: Path,
    rate: Rate,
    /// Start and displacement, Q16 steps (whole steps).
    start: [i64; AXIS_COUNT],
    delta: [i64; AXIS_COUNT],
    /// Exact end, whole steps.
    end_steps: [i64; AXIS_COUNT],
    /// Path length Q8 nm, `2^62 / length`, acceleration and axis speed cap (Q8).
    len: u64,
    inv: i64,
    accel: u64,
    cap: u64,
    exact_stop: bool,
}

/// A speed (or acceleration) per period as Q8.
fn q8(v: f32) -> u64 {
    (v * (1u32 << PATH_FRAC) as f32) as u64
}

impl Segment {
    /// Whether the feed is per spindle revolution (G99): it moves only while the
    /// encoder counts.
    pub fn per_rev(&self) -> bool {
        matches!(self.rate, Rate::PerRev(_))
    }

    /// Starts `b` at whole steps `from` (its data was computed when it was queued:
    /// nothing here divides).
    pub fn new(b: &Block, from: &[i64; AXIS_COUNT], p: &MotionParams) -> Self {
        let end_steps: [i64; AXIS_COUNT] =
            core::array::from_fn(|i| if p.limits[i].present { b.exec.end_steps[i] } else { from[i] });
        let start = from.map(|s| s << STEP_FRAC);
        let delta: [i64; AXIS_COUNT] = core::array::from_fn(|i| (end_steps[i] - from[i]) << STEP_FRAC);
        let rate = match b.feed {
            FeedSpec::Rapid => Rate::Rapid,
            FeedSpec::PerMin(_) => Rate::PerMin(b.exec.rate_q8.max(0) as u64),
            FeedSpec::PerRev(_) => Rate::PerRev(b.exec.rate_q8),
        };
        let path = match b.kind {
            BlockKind::Arc(g) => {
                let mut a = arc_path(&g, p);
                // Only a machining centre's arcs move a third axis.
                a.helical = canon::MILL && (0..AXIS_COUNT).any(|i| i != a.ia && i != a.ib && delta[i] != 0);
                Path::Arc(a)
            }
            BlockKind::Independent(inv) => Path::Independent(independent(from, &end_steps, &inv, p)),
            _ => Path::Line,
        };
        Segment {
            line: b.line,
            offset: b.offset,
            spindle: b.spindle,
            rapid: b.feed == FeedSpec::Rapid,
            path,
            rate,
            start,
            delta,
            end_steps,
            len: b.plan.len_q8,
            inv: b.exec.inv_len,
            accel: u64::from(b.plan.accel_q8),
            cap: q8(b.plan.cap),
            exact_stop: b.exact_stop,
        }
    }

    /// The exact end point, whole steps.
    pub fn end_steps(&self) -> &[i64; AXIS_COUNT] {
        &self.end_steps
    }

    /// The speed wanted now, Q8 nm per period.
    fn cap_now(&self, live: &Live) -> u64 {
        if live.hold {
            return 0;
        }
        let v = match self.rate {
            Rate::Rapid => return (self.cap.saturating_mul(live.rapid_ovr)) >> 8,
            Rate::PerMin(v) => v,
            Rate::PerRev(f) => mul_shr(f, live.rev_per_tick as i64, FRAC_BITS).max(0) as u64,
        };
        (v.saturating_mul(live.feed_ovr) >> 8).min(self.cap)
    }

    /// Progress (Q32) at path position `s`.
    fn progress(&self, s: u64) -> i64 {
        mul_shr(s as i64, self.inv, 30).min(1 << FRAC_BITS)
    }

    /// The commanded position at path position `s` (Q16 steps per axis).
    fn point(&self, s: u64, out: &mut [i64; AXIS_COUNT]) {
        let f = self.progress(s);
        match &self.path {
            Path::Line => {
                for ((o, st), d) in out.iter_mut().zip(&self.start).zip(&self.delta) {
                    *o = st + if *d == 0 { 0 } else { mul_q32(*d, f) };
                }
            }
            Path::Arc(a) => {
                let th = a.theta0 + mul_q32(a.sweep, f);
                let r = a.r0 + mul_q32(a.dr, f);
                let (c, sn) = cos_sin(th as u32);
                out[a.ia] = a.scale[0].q16(a.center[0] + mul_shr(r, i64::from(c), TRIG_FRAC));
                out[a.ib] = a.scale[1].q16(a.center[1] + mul_shr(r, i64::from(sn), TRIG_FRAC));
                if canon::MILL && a.helical {
                    let moving = out.iter_mut().zip(&self.start).zip(&self.delta).enumerate();
                    for (i, ((o, st), d)) in moving {
                        if i != a.ia && i != a.ib && *d != 0 {
                            *o = st + mul_q32(*d, f);
                        }
                    }
                }
            }
            Path::Independent(_) => {}
        }
    }
}

fn arc_path(g: &ArcGeom, p: &MotionParams) -> ArcPath {
    let (ia, ib) = (g.axes.0.index(), g.axes.1.index());
    ArcPath {
        ia,
        ib,
        scale: [p.scale[ia], p.scale[ib]],
        center: [g.center.0, g.center.1],
        r0: g.r0,
        dr: g.r1 - g.r0,
        theta0: g.theta0,
        sweep: g.sweep,
        helical: false,
    }
}

fn independent(
    from: &[i64; AXIS_COUNT],
    to: &[i64; AXIS_COUNT],
    inv: &[i64; AXIS_COUNT],
    p: &MotionParams,
) -> Independent {
    Independent {
        len: core::array::from_fn(|i| if inv[i] == 0 { 0 } else { p.scale[i].q8_nm(from[i].abs_diff(to[i])) }),
        inv: *inv,
        accel: core::array::from_fn(|i| q8(p.limits[i].accel).max(1)),
        cap: core::array::from_fn(|i| q8(p.limits[i].rapid)),
        s: [0; AXIS_COUNT],
        v: [0; AXIS_COUNT],
    }
}

/// What a period did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// No block.
    Idle,
    /// Moving.
    Moving,
    /// Stopped on the path by a feed hold or 0 % override; the block goes on when
    /// the speed comes back.
    Held,
    /// The block ended at rest at its end point in this period.
    Finished,
}

/// The interpolator state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interpolator {
    seg: Option<Segment>,
    /// Path position and speed, Q8 nm and Q8 nm per period.
    s: u64,
    v: u64,
    /// Commanded position at the end of the last period, Q16 steps.
    pos: [i64; AXIS_COUNT],
    /// Whole-step position where the next block starts.
    steps: [i64; AXIS_COUNT],
    /// Periods the braking test allowed no speed for.
    overruns: u32,
}

impl Interpolator {
    /// Idle at whole steps `steps`.
    pub fn new(steps: [i64; AXIS_COUNT]) -> Self {
        Interpolator { seg: None, s: 0, v: 0, pos: steps.map(|s| s << STEP_FRAC), steps, overruns: 0 }
    }

    /// The running block.
    pub fn segment(&self) -> Option<&Segment> {
        self.seg.as_ref()
    }

    /// Commanded position at the end of the last period, Q16 steps.
    pub fn position(&self) -> &[i64; AXIS_COUNT] {
        &self.pos
    }

    /// Where the next block starts, whole steps.
    pub fn start_steps(&self) -> &[i64; AXIS_COUNT] {
        &self.steps
    }

    /// Path speed of the last period, Q8 nm per period.
    pub fn speed(&self) -> u64 {
        self.v
    }

    /// Starts block `b` from rest at the current end position.
    pub fn start(&mut self, b: &Block, p: &MotionParams) {
        self.seg = Some(Segment::new(b, &self.steps, p));
        self.s = 0;
        self.v = 0;
    }

    /// Brakes along block `b`'s straight line from whole steps `from`, moving at
    /// `v` (Q8 nm/period) now: a thread pass that a reset releases from the spindle
    /// decelerates on its own line (2.17.1 note 5). Run it with `hold` set.
    pub fn brake_along(&mut self, b: &Block, from: &[i64; AXIS_COUNT], v: u64, p: &MotionParams) {
        let mut seg = Segment::new(b, from, p);
        let len: f64 = (0..AXIS_COUNT)
            .map(|i| {
                let d = (seg.end_steps[i] - from[i]) as f64 * p.scale[i].nm_per_step();
                d * d
            })
            .sum();
        // A reset is no interpolation period: this one division is fine.
        seg.len = (libm::sqrt(len) * 256.0) as u64 + 1;
        seg.inv = crate::fixed::inverse62(seg.len);
        seg.rate = Rate::Rapid;
        self.seg = Some(seg);
        self.steps = *from;
        self.s = 0;
        self.v = v;
    }

    /// Forgets the running block (after the axes were stopped on it): the next
    /// block starts from the nearest whole steps of the commanded position.
    pub fn abandon(&mut self) {
        self.seg = None;
        self.v = 0;
        self.s = 0;
        self.steps = self.pos.map(crate::fixed::round_steps);
    }

    /// Sets the position directly (after the spindle gearbox moved the axes).
    pub fn set_steps(&mut self, steps: [i64; AXIS_COUNT]) {
        self.steps = steps;
        self.pos = steps.map(|s| s << STEP_FRAC);
    }

    /// Periods whose speed no candidate of the braking test allowed (it then
    /// brakes by the acceleration regardless): 0 unless a block was entered too
    /// fast to brake for its end (single block switched on, a reset's brake).
    pub fn overruns(&self) -> u32 {
        self.overruns
    }

    /// One interpolation period. Blocks the running one may blend into are taken
    /// from `planner`, as many as the period's distance covers; the caller starts
    /// everything else.
    pub fn tick<const N: usize>(&mut self, planner: &mut Planner<N>, live: &Live, p: &MotionParams) -> Status {
        let Some(seg) = self.seg.as_mut() else { return Status::Idle };
        if let Path::Independent(ind) = &mut seg.path {
            if tick_independent(ind, seg.start, seg.delta, &mut self.pos, live) {
                return self.finish();
            }
            return if ind.v.iter().all(|v| *v == 0) { Status::Held } else { Status::Moving };
        }
        let mut at_rest = live.stop_at_end || seg.exact_stop;
        let cap = seg.cap_now(live);
        self.v = self.next_speed(planner, cap, at_rest);
        let mut s = self.s + self.v;
        loop {
            let Some(seg) = self.seg.as_ref() else { return Status::Idle };
            if s < seg.len {
                self.s = s;
                seg.point(s, &mut self.pos);
                return if self.v == 0 { Status::Held } else { Status::Moving };
            }
            s -= seg.len;
            self.steps = seg.end_steps;
            let next = match planner.front() {
                Some(Item::Motion(b)) if !at_rest && b.plan.entry_u > 0 => Segment::new(b, &self.steps, p),
                _ => return self.finish(),
            };
            planner.pop();
            at_rest = next.exact_stop;
            self.seg = Some(next);
        }
    }

    /// The speed of the next period: the fastest of accelerating, keeping the
    /// speed and braking that the braking test allows ([`allowed`]); from rest, a
    /// last step short of a stop creeps onto it.
    fn next_speed<const N: usize>(&mut self, planner: &Planner<N>, cap: u64, at_rest: bool) -> u64 {
        let Some(seg) = self.seg.as_ref() else { return 0 };
        let (v, a) = (self.v, seg.accel);
        let floor = v.saturating_sub(a);
        // Towards the cap, at most `a` per period either way.
        let wanted = if cap >= v { (v + a).min(cap) } else { floor.max(cap) };
        let next = match allowed(seg, self.s, planner, at_rest, [wanted, v.min(wanted), floor.min(wanted)]) {
            Some(v) => v,
            None => {
                self.overruns += 1;
                floor.min(wanted)
            }
        };
        if next > 0 || cap == 0 {
            return next;
        }
        // At rest short of the block's end (a stop, or an entry below one period of
        // this block's acceleration): creep onto it, never above the cap (with a
        // slow feed the acceleration per period can exceed it) or the entry.
        let rem = seg.len - self.s;
        let creep = rem.min(a).min(cap);
        match planner.front() {
            Some(Item::Motion(b)) if creep == rem && !at_rest && b.plan.entry_u > 0 => creep.min(b.plan.entry_q8()),
            _ => creep,
        }
    }

    fn finish(&mut self) -> Status {
        if let Some(seg) = self.seg.take() {
            self.steps = seg.end_steps;
        }
        self.pos = self.steps.map(|s| s << STEP_FRAC);
        self.s = 0;
        self.v = 0;
        Status::Finished
    }
}

/// The first of `candidates` (fastest first) that the braking test allows for a
/// period starting at path position `s` of the running block `seg` (`at_rest`:
/// the block ends at rest), or `None`.
///
/// Walks the boundaries ahead: the end of `seg`, then of each queued block the
/// path blends into. A candidate that fails at a boundary is replaced by the next
/// one and the same boundary is tested again (the test is monotone in the speed,
/// so the boundaries before still pass). The walk ends at a stop, or where the rest
/// is certain (see the module documentation); within a run of one acceleration it
/// tests the boundaries this period crosses and one more.
fn allowed<const N: usize>(
    seg: &Segment,
    s: u64,
    planner: &Planner<N>,
    at_rest: bool,
    candidates: [u64; 3],
) -> Option<u64> {
    let mut k = 0;
    let mut v = candidates[0];
    // Distance from the period's start to the boundary, and the smallest
    // acceleration of the blocks in between.
    let mut rem = seg.len - s;
    let mut a = seg.accel;
    let (run_from, run_accel) = planner.uniform_run();
    let run_accel = u64::from(run_accel);
    let mut items = planner.iter().enumerate();
    // The block after the boundary, if the path blends into it.
    let mut next = if at_rest { None } else { blended(items.next()) };
    loop {
        let ok = match next {
            None => fits(v, 0, a, rem),
            Some((_, b)) if rem <= v => below_entry(v, &b.plan),
            Some((_, b)) => below_entry(v, &b.plan) || chains(v, &b.plan, a, rem),
        };
        if !ok {
            k += 1;
            v = *candidates.get(k)?;
            continue;
        }
        let Some((i, b)) = next else { return Some(v) };
        if rem > v {
            // Braking to rest fits before this boundary: nothing after it matters.
            let twice = (2 * v).saturating_add(a);
            if twice.saturating_mul(twice) <= (8 * a).saturating_mul(rem) {
                return Some(v);
            }
            // One run of blocks of the test's acceleration from here on: braking
            // for this boundary by the distance brakes for every later one.
            if i >= run_from && a >= run_accel && chains(v, &b.plan, run_accel, rem) {
                return Some(v);
            }
        }
        rem = rem.saturating_add(b.plan.len_q8);
        a = a.min(u64::from(b.plan.accel_q8));
        next = if b.exact_stop { None } else { blended(items.next()) };
    }
}

/// The queued block `item`, if the path may blend into it (a motion block with a
/// planned entry above zero).
fn blended(item: Option<(usize, &Item)>) -> Option<(usize, &Block)> {
    match item {
        Some((i, Item::Motion(b))) if b.plan.entry_u > 0 => Some((i, b)),
        _ => None,
    }
}

/// Whether `v` is at or below the planned entry `e` of a block (`plan.entry_u`
/// is `(e − h)²` with `e ≥ 2h`): `v ≤ h` or `(v − h)² ≤ u`.
fn below_entry(v: u64, plan: &Plan) -> bool {
    let h = plan.half_q8();
    v <= h || (v - h).saturating_mul(v - h) <= plan.entry_u
}

/// Whether braking by `a` from `v` ends on a boundary `rem` ahead at the planned
/// entry `e` of the block after it by the distance itself (the braking branch of
/// [`fits`], `v² + a·v ≤ e² − a·e + 2a·rem`, which carries from one boundary of a
/// run to the next). At the block's own acceleration that is
/// `(v + h)² ≤ u + 2a·rem`: no root.
fn chains(v: u64, plan: &Plan, a: u64, rem: u64) -> bool {
    let h = plan.half_q8();
    if a == 2 * h {
        let lhs = (v + h).saturating_mul(v + h);
        return lhs <= plan.entry_u.saturating_add((2 * a).saturating_mul(rem));
    }
    // Another acceleration (where it changes along the way): the entry itself.
    let e = plan.entry_q8();
    let lhs = v.saturating_mul(v).saturating_add(a.saturating_mul(v));
    let rhs = e.saturating_mul(e).saturating_add((2 * a).saturating_mul(rem));
    a.saturating_mul(e) <= rhs && lhs <= rhs - a.saturating_mul(e)
}

/// One period of an independent rapid; true when every axis has arrived.
fn tick_independent(
    ind: &mut Independent,
    start: [i64; AXIS_COUNT],
    delta: [i64; AXIS_COUNT],
    pos: &mut [i64; AXIS_COUNT],
    live: &Live,
) -> bool {
    let mut done = true;
    for i in 0..AXIS_COUNT {
        if ind.len[i] == 0 {
            continue;
        }
        let cap = if live.hold { 0 } else { ind.cap[i].saturating_mul(live.rapid_ovr) >> 8 };
        let rem = ind.len[i] - ind.s[i];
        ind.v[i] = next_speed(ind.v[i], cap, 0, ind.accel[i], rem);
        ind.s[i] = (ind.s[i] + ind.v[i]).min(ind.len[i]);
        let arrived = ind.s[i] == ind.len[i];
        let f = if arrived { 1 << FRAC_BITS } else { mul_shr(ind.s[i] as i64, ind.inv[i], 30).min(1 << FRAC_BITS) };
        pos[i] = start[i] + mul_q32(delta[i], f);
        done &= arrived;
    }
    done
}

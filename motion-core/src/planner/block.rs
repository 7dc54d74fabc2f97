//! Block preparation: a canonical motion action becomes a queued [`Block`] with its
//! length, speed limits and the directions it starts and ends in (per-block
//! geometry in floating point, as the team rules allow; nothing here runs per tick).

use super::Item;
use super::machine::MotionParams;
use crate::alarm::AlarmKind;
use crate::axis::{AXIS_COUNT, Axis, Pos};
use crate::canon::{ArcMove, FeedMode, Move, SpindleDir, SpindleSpeed, TapMove, ThreadMove, ThreadSync};
use crate::cordic;
use crate::fixed::{PATH_FRAC, f32_of, inverse62, minf, sqrtf, u64_of};
use crate::sync::ramp_counts;
use canon::units::{f32_of_u64, f64_of_u128, sqrt_u64};

/// Unit direction of a path, per axis.
pub type Dir = [f32; AXIS_COUNT];

/// How a block's speed is commanded.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FeedSpec {
    /// At the axes' rapid rates (rapid override applies).
    Rapid,
    /// Feed per minute, nm/min (feed override applies).
    PerMin(i64),
    /// Feed per spindle revolution, nm/rev, following the measured spindle speed.
    PerRev(i64),
}

/// An arc in its plane: centre, radii at both ends, start angle and sweep.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ArcGeom {
    /// The plane's first and second axis (G18: Z, X).
    pub axes: (Axis, Axis),
    /// Centre in machine coordinates, nm.
    pub center: (i64, i64),
    /// Radius at the start, nm.
    pub r0: i64,
    /// Radius at the end (may differ from `r0` by the arc tolerance), nm.
    pub r1: i64,
    /// Start angle, turns × 2^32.
    pub theta0: i64,
    /// Signed sweep (negative = clockwise), turns × 2^32.
    pub sweep: i64,
}

/// A spindle-synchronised thread pass block.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ThreadSpec {
    /// Lead along the long axis at the block's start, nm per revolution.
    pub lead: i64,
    /// Lead change per revolution (G34 K), nm/rev per revolution; 0 for a constant lead.
    pub lead_delta: i64,
    /// Lead at the block's end, nm per revolution: `√(lead² + 2·K·length)` along the
    /// long axis (the lead after θ revolutions is `lead + K·θ`); checks only.
    pub lead_end: i64,
    /// The block continues a sequence with a G34 in it: it starts at the lead the
    /// thread has reached (`lead` is that lead, for checks; the gearbox keeps the exact
    /// one), not at its own F.
    pub keep_lead: bool,
    /// Start angle after the index, µdeg.
    pub start_udeg: u32,
    /// Wait for the index, or continue from the previous thread block.
    pub sync: ThreadSync,
    /// The axis with the longer travel (the lead is measured along it).
    pub long: Axis,
}

/// A rigid-tapping block.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TapSpec {
    /// Lead, nm per revolution.
    pub lead: i64,
    /// Spindle direction during the block.
    pub dir: SpindleDir,
    /// The tapping axis.
    pub long: Axis,
}

/// What kind of path a block is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BlockKind {
    /// A straight line, all axes interpolated together.
    Line,
    /// A rapid with each axis at its own rate (dog-leg path, G28/G30), with
    /// `2^62 / length` of each axis's own move.
    Independent([i64; AXIS_COUNT]),
    /// An arc in a plane.
    Arc(ArcGeom),
    /// A thread pass locked to the spindle.
    Thread(ThreadSpec),
    /// A rigid-tapping move locked to the spindle.
    Tap(TapSpec),
}

/// Look-ahead state of a block (speeds in nm per interpolation period).
///
/// A planned entry speed `e` is the speed of the interpolation period that
/// reaches (or crosses) the block's start. The look-ahead keeps it as
/// `u = (e − a/2)²` in Q16 (`a` the block's acceleration `accel_q8`, `a/2` its
/// `half_q8`): the interpolator's discrete profile brakes from `e` to `e'` over a
/// block of length `L` exactly when `u ≤ u' + 2a·L`, so planning is additions and
/// the interpolator's tests need no root ([`lookahead`](super::lookahead),
/// [`crate::interpolator`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plan {
    /// Path length, Q8 nm.
    pub len_q8: u64,
    /// `2·a·L` in Q16 (`accel_q8 · len_q8 · 2`, saturating).
    pub two_a_len: u64,
    /// The highest planned entry the junction allows, as `u` (0: the block starts
    /// from rest).
    pub max_u: u64,
    /// The planned entry as `u`; 0: the block starts from rest (the path does
    /// not blend into it). Speeds stay below 2^30 Q8 (4 m/period), `u` below 2^60.
    pub entry_u: u64,
    /// Path acceleration the axes allow along this block, nm/period².
    pub accel: f32,
    /// `accel` in Q8 nm/period², rounded down to an even number (what the
    /// interpolator brakes with; `half_q8` is half of it).
    pub accel_q8: u32,
    /// Highest path speed the axes allow (feed limits, arcs' normal acceleration
    /// and chord tolerance), nm/period.
    pub cap: f32,
    /// The programmed speed at 100 % override (junction speeds stay below it).
    pub nominal: f32,
    /// The smallest entry above 0 as `u`: the larger acceleration of the two
    /// blocks at the junction (a slower entry starts the block from rest).
    pub floor_u: u64,
    /// The junction's own limit, nm/period (`max_u` is the smaller of it and the
    /// chain's curvature speed, [`bend`](super::bend), which rises as the path
    /// beyond the junction arrives).
    pub pending: f32,
}

impl Plan {
    /// Half the acceleration, Q8 nm/period² (exact: `accel_q8` is even).
    #[inline]
    pub fn half_q8(&self) -> u64 {
        u64::from(self.accel_q8 / 2)
    }

    /// The planned entry speed, Q8 nm/period (0 when the block starts from rest);
    /// by a square root: the interpolator's hot path works with `entry_u`.
    pub fn entry_q8(&self) -> u64 {
        if self.entry_u == 0 { 0 } else { self.half_q8() + sqrt_u64(self.entry_u).0 }
    }
}

/// A block in the motion queue.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Block {
    /// Source line.
    pub line: u32,
    /// Path kind and its data.
    pub kind: BlockKind,
    /// Machine minus work coordinates for this block (G96 and the trace use work X).
    pub offset: Pos,
    /// Speed command.
    pub feed: FeedSpec,
    /// Spindle during the block.
    pub spindle: SpindleSpeed,
    /// Stop exactly at the end.
    pub exact_stop: bool,
    /// The planned entry is the junction's limit `√max_entry_sq` (the look-ahead
    /// pass stops here: a later block can only raise this block's exit).
    pub entry_at_max: bool,
    /// Look-ahead data.
    pub plan: Plan,
    /// What the interpolator needs, ready to run.
    pub exec: Exec,
}

/// What the interpolator needs of a block, computed when the block is queued so
/// that starting it (possibly in the middle of an interpolation period, when it is
/// blended into) divides nothing.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Exec {
    /// End point, whole steps per axis (exact: from the nanometre end point).
    pub end_steps: [i64; AXIS_COUNT],
    /// `2^62 / length` (length in Q8 nm).
    pub inv_len: i64,
    /// The programmed speed: Q8 nm per period (feed per minute) or Q8 nm per
    /// revolution (feed per revolution); 0 for rapids.
    pub rate_q8: i64,
}

impl Exec {
    /// The interpolator's data of a block of `kind`, `feed` and length `len_q8`
    /// (Q8 nm) that moves from `start` to `end` (machine, nm). Computed as the block
    /// is written into its queue slot: inlined there, the fields go straight into the
    /// slot (as a call, the result was built on the stack and copied; zeroed in the
    /// slot and filled later, it cost a `memclr` of 80 bytes and two copies).
    #[inline(always)]
    pub fn new(feed: FeedSpec, len_q8: u64, end: &Pos, p: &MotionParams) -> Self {
        let present = |i: usize| p.limits[i].present;
        let end_steps = core::array::from_fn(|i| if present(i) { p.scale[i].steps(end.0[i]) } else { 0 });
        let rate_q8 = match feed {
            FeedSpec::Rapid => 0,
            FeedSpec::PerMin(f) => p.rate_q8(f),
            FeedSpec::PerRev(f) => f.saturating_mul(1 << PATH_FRAC),
        };
        Exec { end_steps, inv_len: inverse_len(len_q8), rate_q8 }
    }

    /// [`Exec::new`] as a call (threads and taps: rare blocks, no need to grow the
    /// code by another inlined copy).
    #[inline(never)]
    fn outlined(feed: FeedSpec, len_q8: u64, end: &Pos, p: &MotionParams) -> Self {
        Self::new(feed, len_q8, end, p)
    }
}

/// `2^62 / len` to within 2^-30 relative, for `len` in `[1, 2^61]`, as
/// [`inverse62`] gives it, for a block being prepared: the reciprocal of the top
/// 32 bits of `len` seeded by the FPU (one `VDIV.F32`, good to 2^-23; per block,
/// never in an interrupt) and refined by one Newton step, where `inverse62` takes
/// three from a linear seed without dividing.
#[inline]
fn inverse_len(len: u64) -> i64 {
    let len = len.clamp(1, 1 << 61);
    let z = len.leading_zeros();
    let top = ((len << z) >> 32) as u32;
    let d = u64::from(top);
    // 2^63 / top in (2^31, 2^32] (the cast saturates 2^32 to 2^32 − 1).
    let mut x = u64::from((9_223_372_036_854_775_808.0f32 / top as f32) as u32);
    // e = 1 − x·top in Q63 (|e| ≈ 2^40): x·top stays within 2^63·(1 ± 2^-22).
    let e = (1u64 << 63).wrapping_sub(x.wrapping_mul(d)) as i64;
    x = x.wrapping_add_signed(((x as i64) * (e >> 31)) >> 32);
    // 2^62 / len = (2^63 / top) · 2^(z − 33).
    (if z >= 33 { x << (z - 33) } else { x >> (33 - z) }) as i64
}

/// `2^62 / length` of each present axis's own move from `start` to `end` (an
/// independent rapid's; a call: rare blocks, and four inlined reciprocals are large).
#[inline(never)]
fn axis_inverses(start: &Pos, end: &Pos, p: &MotionParams) -> [i64; AXIS_COUNT] {
    core::array::from_fn(|i| {
        let d = end.0[i].abs_diff(start.0[i]);
        if p.limits[i].present && d > 0 { inverse62(d << PATH_FRAC) } else { 0 }
    })
}

/// What preparing a block tells besides the block itself, which is written straight
/// into its queue slot (a block is ~250 bytes; a move of it is a memcpy on the M4):
/// the directions it starts and ends in and its end point.
#[derive(Clone, Copy, Debug)]
pub struct Prepared {
    /// Unit direction at the start.
    pub dir_in: Dir,
    /// Unit direction at the end.
    pub dir_out: Dir,
    /// End point, machine coordinates, nm (X radius).
    pub end: Pos,
    /// Path length, nm.
    pub len: f32,
}

/// Length (nm) and unit direction of a straight move. f32 on the FPU: the length
/// only times the move (to 1e-7), the end point comes from the exact nanometres.
#[inline(always)]
fn straight(start: &Pos, end: &Pos) -> (f32, Dir) {
    let mut d = [0.0f32; AXIS_COUNT];
    for ((v, e), s) in d.iter_mut().zip(&end.0).zip(&start.0) {
        *v = f32_of(e.wrapping_sub(*s));
    }
    let len = sqrtf(d.iter().map(|v| v * v).sum());
    let inv = if len > 0.0 { 1.0 / len } else { 0.0 };
    (len, d.map(|v| v * inv))
}

/// The fastest path speed and the path acceleration the axes allow along `dir`:
/// a rapid's (or a thread's) acceleration is the most the axes allow along it; a
/// cutting move's is that of the slowest axis it moves, smaller (up to √2 on a
/// diagonal) but the same for every direction of the same axes, so the blocks of a
/// blended chain share one acceleration and the look-ahead's braking test holds
/// across all of them at once (see [`lookahead`](super::lookahead)).
#[inline(always)]
fn axis_caps(dir: &Dir, p: &MotionParams, rapid: bool, along: bool) -> (f32, f32) {
    let (mut cap, mut accel) = (f32::MAX, f32::MAX);
    for (u, lim) in dir.iter().zip(&p.limits) {
        let u = u.abs();
        if u > 1e-9 && lim.present {
            cap = minf(cap, if rapid { lim.rapid } else { lim.feed } / u);
            accel = minf(accel, if along { lim.accel / u } else { lim.accel });
        }
    }
    (cap, accel)
}

fn len_q8(len: f32) -> Result<u64, AlarmKind> {
    let q = len * (1u32 << PATH_FRAC) as f32 + 0.5;
    if !(q >= 1.0 && q < (1u64 << 50) as f32) {
        return Err(AlarmKind::Overflow);
    }
    Ok(u64_of(q))
}

fn plan(len: u64, accel: f32, cap: f32, nominal: f32) -> Plan {
    let accel_q8 = ((accel * (1u32 << PATH_FRAC) as f32) as u32).max(2) & !1;
    let h = u64::from(accel_q8 / 2);
    Plan {
        len_q8: len,
        // At most 2^62: added to a `u` (below 2^60) it cannot overflow.
        two_a_len: if len < 1 << 30 {
            u64::from(accel_q8) * len * 2
        } else {
            u64::from(accel_q8).saturating_mul(len).saturating_mul(2).min(1 << 62)
        },
        max_u: 0,
        entry_u: 0,
        accel,
        accel_q8,
        cap,
        nominal: minf(nominal, cap),
        floor_u: h * h,
        pending: 0.0,
    }
}

/// The speed a feed commands, nm/period, at 100 % (per rev: at the commanded rpm).
#[inline(always)]
fn nominal(feed: FeedSpec, spindle: &SpindleSpeed, p: &MotionParams, cap: f32) -> f32 {
    match feed {
        FeedSpec::Rapid => cap,
        FeedSpec::PerMin(f) => p.per_tick(f32_of(f)),
        FeedSpec::PerRev(f) => p.per_tick(f32_of(f) * spindle.rpm.unwrap_or(0) as f32),
    }
}

/// A straight move from `start` (rapid or cutting).
pub fn line(
    start: &Pos,
    m: &Move,
    rapid: bool,
    p: &MotionParams,
    line: u32,
    slot: &mut Item,
) -> Result<Prepared, AlarmKind> {
    let (len, dir) = straight(start, &m.to.machine);
    let feed = match (rapid, m.feed.mode) {
        (true, _) => FeedSpec::Rapid,
        (false, FeedMode::PerMin) => FeedSpec::PerMin(m.feed.value),
        (false, FeedMode::PerRev) => FeedSpec::PerRev(m.feed.value),
    };
    let (mut cap, accel) = axis_caps(&dir, p, rapid, rapid);
    if !rapid {
        cap = minf(cap, p.path_feed);
    }
    let kind = if rapid && m.independent {
        BlockKind::Independent(axis_inverses(start, &m.to.machine, p))
    } else {
        BlockKind::Line
    };
    let (len_nm, len) = (len, len_q8(len)?);
    *slot = Item::Motion(Block {
        line,
        kind,
        offset: m.to.machine - m.to.work,
        feed,
        spindle: m.spindle,
        exact_stop: m.exact_stop || rapid,
        entry_at_max: false,
        plan: plan(len, accel, cap, nominal(feed, &m.spindle, p, cap)),
        exec: Exec::new(feed, len, &m.to.machine, p),
    });
    Ok(Prepared { dir_in: dir, dir_out: dir, end: m.to.machine, len: len_nm })
}

/// Start angle and signed sweep of an arc in turns × 2^32 from the radius vectors
/// `s` (start) and `e` (end), by CORDIC ([`cordic::angle`], within 16 units of the
/// exact angles). `None` when the end is within 2^12 units (~6e-6 rad) of the start
/// direction, where a tiny arc and a full turn must be told apart exactly: the
/// caller then uses f64.
fn sweep_turns(s: (i64, i64), e: (i64, i64), cw: bool, full: bool) -> Option<(i64, i64)> {
    const TURN: i64 = 1 << 32;
    let t0 = cordic::angle(s.0, s.1);
    let d = i64::from(cordic::angle(e.0, e.1).wrapping_sub(t0));
    if !(1 << 12..=TURN - (1 << 12)).contains(&d) {
        return None;
    }
    let sweep = match (full, cw) {
        (true, true) => -TURN,
        (true, false) => TURN,
        (false, true) => d - TURN,
        (false, false) => d,
    };
    // The start angle in (−½, ½] turn, as atan2 gives it.
    Some((i64::from(t0 as i32), sweep))
}

/// [`sweep_turns`] in f64 (`atan2`), for arcs ending near their start direction.
fn sweep_f64(s: (f64, f64), e: (f64, f64), cw: bool, full: bool) -> (i64, i64) {
    let (th0, th1) = (libm::atan2(s.1, s.0), libm::atan2(e.1, e.0));
    let tau = core::f64::consts::TAU;
    let mut sweep = th1 - th0;
    if cw {
        while sweep >= 0.0 {
            sweep -= tau;
        }
        if full {
            sweep = -tau;
        }
    } else {
        while sweep <= 0.0 {
            sweep += tau;
        }
        if full {
            sweep = tau;
        }
    }
    (turns(th0), turns(sweep))
}

/// Turns × 2^32 of an angle in radians.
fn turns(rad: f64) -> i64 {
    libm::round(rad / core::f64::consts::TAU * 4_294_967_296.0) as i64
}

/// Unit tangent of an arc in the direction of travel at the point `v` from the
/// centre (`r` its length): the radius turned a quarter, `(−sin θ, cos θ)` with
/// `sin θ = v_b / r`, `cos θ = v_a / r` — no trigonometry (f32 on the FPU, as the
/// directions are kept).
#[inline(always)]
fn tangent(axes: (Axis, Axis), v: (i64, i64), r: f32, ccw: bool) -> Dir {
    let mut d = [0.0; AXIS_COUNT];
    if r > 0.0 {
        let s = (if ccw { 1.0 } else { -1.0 }) / r;
        d[axes.0.index()] = -s * f32_of(v.1);
        d[axes.1.index()] = s * f32_of(v.0);
    }
    d
}

/// The length of `v` in f64 (a square root of the exact integer sum of squares)
/// and rounded to whole nanometres, exactly: `round(√(a² + b²))`.
fn radius(v: (i64, i64)) -> (f64, i64) {
    let sq = |x: u64| u128::from(x) * u128::from(x);
    let r2 = sq(v.0.unsigned_abs()) + sq(v.1.unsigned_abs());
    let r = libm::sqrt(f64_of_u128(r2));
    (r, round_sqrt(r2, r))
}

/// The length of `v` in f32 (within 2^-22 relative) and rounded to whole
/// nanometres exactly, `round(√(a² + b²))`: by integer arithmetic and f32 below
/// 2^64 nm² (radii up to 4.29 m, [`sqrt_u64`]), else as [`radius`] does.
fn radius_f32(v: (i64, i64)) -> (f32, i64) {
    // Both sides below 2^32 nm (4.29 m): 32-bit squares, one multiply each on the
    // Cortex-M4, summed in 64 bits when that does not carry.
    if let (Ok(a), Ok(b)) = (u32::try_from(v.0.unsigned_abs()), u32::try_from(v.1.unsigned_abs())) {
        let sq = |x: u32| u64::from(x) * u64::from(x);
        if let Some(x) = sq(a).checked_add(sq(b)) {
            let (nm, r) = sqrt_u64(x);
            return (r, nm as i64);
        }
    }
    let sq = |x: u64| u128::from(x) * u128::from(x);
    let r2 = sq(v.0.unsigned_abs()) + sq(v.1.unsigned_abs());
    match u64::try_from(r2) {
        Ok(x) => {
            let (nm, r) = sqrt_u64(x);
            (r, nm as i64)
        }
        Err(_) => {
            let (r, nm) = radius(v);
            (r as f32, nm)
        }
    }
}

/// The length of an arc of `sweep` (turns × 2^32) over radii `r0` and `r1` (their
/// mean), in f32: within 4·10⁻⁷ of the f64 product rounded to f32.
fn arc_len(sweep: i64, r0: f32, r1: f32) -> f32 {
    f32_of_u64(sweep.unsigned_abs()) * (core::f32::consts::TAU / 8_589_934_592.0) * (r0 + r1)
}

/// The integer nearest to `√x` (never a tie: `(f + ½)²` is not an integer), from
/// `r ≈ √x` corrected in integers: no soft-float rounding. Beyond 2^52 nm, where
/// an ulp of `r` exceeds 1, it is `round(r)` (no machine comes near).
fn round_sqrt(x: u128, r: f64) -> i64 {
    // √x ≥ 2^52 (compared in integers: a float compare is a software call).
    if x >= 1 << 104 {
        return libm::round(r) as i64;
    }
    let sq = |f: u64| u128::from(f) * u128::from(f);
    // Below 2^52 the f64 root is within 1 of √x (x rounded to 53 bits, then the
    // root to half an ulp ≤ ½): its integer part is ⌊√x⌋ or one off.
    let mut f = trunc_u64(r);
    if sq(f) > x {
        f = f.saturating_sub(1);
    } else if sq(f + 1) <= x {
        f += 1;
    }
    // √x rounds up when x ≥ (f + ½)², i.e. x − f² > f.
    let up = x.saturating_sub(sq(f)) > u128::from(f);
    (f + u64::from(up)) as i64
}

/// `r as u64` for a finite `r ≥ 0`, from the bits (the float conversion and its
/// range checks are software routines on the Cortex-M4).
fn trunc_u64(r: f64) -> u64 {
    let bits = r.to_bits();
    let e = ((bits >> 52) & 0x7ff) as i32 - 1023;
    let m = (bits & ((1 << 52) - 1)) | 1 << 52;
    match e {
        ..0 => 0,
        0..52 => m >> (52 - e),
        52..64 => m << (e - 52),
        _ => u64::MAX,
    }
}

/// A circular move from `start`.
pub fn arc(start: &Pos, a: &ArcMove, p: &MotionParams, line: u32, slot: &mut Item) -> Result<Prepared, AlarmKind> {
    let axes = a.plane.axes();
    let (ia, ib) = (axes.0.index(), axes.1.index());
    let c = (a.center.machine.0[ia], a.center.machine.0[ib]);
    let rel = |q: &Pos| (q.0[ia].saturating_sub(c.0), q.0[ib].saturating_sub(c.1));
    let (s, e) = (rel(start), rel(&a.to.machine));
    let ((r0f, r0_nm), (r1f, r1_nm)) = (radius_f32(s), radius_f32(e));
    let (theta0, sweep) = match sweep_turns(s, e, a.cw, a.full_circle) {
        Some(t) => t,
        None => {
            let f = |v: (i64, i64)| (v.0 as f64, v.1 as f64);
            sweep_f64(f(s), f(e), a.cw, a.full_circle)
        }
    };
    let len = arc_len(sweep, r0f, r1f);
    let feed = match a.feed.mode {
        FeedMode::PerMin => FeedSpec::PerMin(a.feed.value),
        FeedMode::PerRev => FeedSpec::PerRev(a.feed.value),
    };
    let (la, lb) = (&p.limits[ia], &p.limits[ib]);
    // Half the acceleration for the normal (v²/r), half along the path; the chord of
    // one period may stray from the arc by at most the chord tolerance.
    let accel = minf(la.accel, lb.accel) / 2.0;
    let r = minf(r0f, r1f);
    // The smaller of the centripetal (√(a·r)) and chord (√(8·r·tol)) caps: one
    // root of the smaller square.
    let bend = sqrtf(minf(accel * r, 8.0 * r * p.chord_tolerance));
    let cap = minf(minf(minf(la.feed, lb.feed), p.path_feed), bend);
    let geom = ArcGeom { axes, center: c, r0: r0_nm, r1: r1_nm, theta0, sweep };
    let (len_nm, len) = (len, len_q8(len)?);
    *slot = Item::Motion(Block {
        line,
        kind: BlockKind::Arc(geom),
        offset: a.to.machine - a.to.work,
        feed,
        spindle: a.spindle,
        exact_stop: a.exact_stop,
        entry_at_max: false,
        plan: plan(len, accel, cap, nominal(feed, &a.spindle, p, cap)),
        exec: Exec::new(feed, len, &a.to.machine, p),
    });
    let ccw = sweep > 0;
    Ok(Prepared {
        dir_in: tangent(axes, s, r0f, ccw),
        dir_out: tangent(axes, e, r1f, ccw),
        end: a.to.machine,
        len: len_nm,
    })
}

/// The axis that travels furthest (the thread's or tap's long axis).
fn long_axis(start: &Pos, end: &Pos) -> Axis {
    let mut best = Axis::Z;
    let mut far = -1i64;
    for a in Axis::ALL {
        let d = (end[a] - start[a]).saturating_abs();
        if d > far {
            (best, far) = (a, d);
        }
    }
    best
}

/// Checks that the path speed `v` (nm/period) along `dir` is within every axis's
/// feed limit; the first axis over it is named.
fn check_speed(dir: &Dir, v: f32, p: &MotionParams) -> Result<(), Axis> {
    for a in Axis::ALL {
        let lim = &p.limits[a.index()];
        if lim.present && v * dir[a.index()].abs() > lim.feed {
            return Err(a);
        }
    }
    Ok(())
}

/// A thread pass from `start`. Checks at the commanded speed that the largest lead
/// (at the start, or at the end of a G34 whose lead grows) × rpm fits the axes, that
/// a G34's constant acceleration K × speed² leaves room for the ramps and that the
/// acceleration ramp fits the thread (the pass re-checks at the measured speed
/// before it moves). A continuing block keeps the long axis `keep` of the block
/// before it when it moves along it (a pull-out keeps the lead on the thread's axis
/// while the other axis pulls out); otherwise its own longer axis. It continues from
/// the lead `keep_lead` the sequence has reached when that has a G34 in it.
pub fn thread(
    start: &Pos,
    t: &ThreadMove,
    keep: Option<Axis>,
    keep_lead: Option<i64>,
    p: &MotionParams,
    line: u32,
    slot: &mut Item,
) -> Result<Prepared, AlarmKind> {
    let continues = t.sync == ThreadSync::Continue;
    let keep_lead = keep_lead.filter(|_| continues);
    let lead = keep_lead.unwrap_or(t.lead);
    if lead <= 0 {
        return Err(AlarmKind::FeedZero);
    }
    let (len, dir) = straight(start, &t.to.machine);
    let long = match keep {
        Some(a) if continues && t.to.machine[a] != start[a] => a,
        _ => long_axis(start, &t.to.machine),
    };
    let lead_end = lead_after(lead, t.lead_delta, t.to.machine[long].saturating_sub(start[long]))?;
    let spec = ThreadSpec {
        lead,
        lead_delta: t.lead_delta,
        lead_end,
        keep_lead: keep_lead.is_some(),
        start_udeg: t.start_udeg,
        sync: t.sync,
        long,
    };
    let along = dir[long.index()].abs().max(1e-9);
    let rpm = t.spindle.rpm.unwrap_or(0) as f32 * p.thread_margin;
    // Path speed whose long-axis part is the largest lead × rpm.
    let v = p.per_tick(rpm * lead.max(lead_end) as f32) / along;
    check_speed(&dir, v, p).map_err(|a| AlarmKind::ThreadTooFast { letter: a.letter() })?;
    let (_, accel) = axis_caps(&dir, p, false, true);
    let cpt = p.per_tick(rpm) * p.cpr as f32;
    let ramp = thread_ramp(&spec, lead_end, cpt, p.cpr, accel * along)?;
    if t.sync == ThreadSync::Index && ramp_up_nm(&spec, ramp, p.cpr) > len * along {
        return Err(AlarmKind::ThreadRampTooLong);
    }
    let (len_nm, len) = (len, len_q8(len)?);
    *slot = Item::Motion(Block {
        line,
        kind: BlockKind::Thread(spec),
        offset: t.to.machine - t.to.work,
        feed: FeedSpec::PerRev(lead),
        spindle: t.spindle,
        exact_stop: true,
        entry_at_max: false,
        plan: plan(len, accel, v.max(1.0), v),
        exec: Exec::outlined(FeedSpec::PerRev(lead), len, &t.to.machine, p),
    });
    Ok(Prepared { dir_in: dir, dir_out: dir, end: t.to.machine, len: len_nm })
}

/// The lead after `length` nm along the long axis of a thread starting at `lead`
/// with G34 K `delta`: z(θ) = F·θ + K·θ²/2 gives a lead F + K·θ = √(F² + 2·K·z).
/// Alarm 0014 when it would reach zero before the end (the interpreter checks this
/// too; the motion core never runs a lead that is not positive).
pub fn lead_after(lead: i64, delta: i64, length: i64) -> Result<i64, AlarmKind> {
    if delta == 0 {
        return Ok(lead);
    }
    let sq = (lead as f64) * (lead as f64) + 2.0 * delta as f64 * length.unsigned_abs() as f64;
    let end = libm::sqrt(sq.max(0.0));
    if end.is_nan() || end < 1.0 || end >= i64::MAX as f64 {
        return Err(AlarmKind::IllegalLead);
    }
    Ok(libm::round(end) as i64)
}

/// The ramp length in counts of a thread pass at `cpt` counts per period that
/// decelerates from `lead_end` nm/rev at most, with `accel` nm per period² along
/// the long axis ([`ramp_counts`]). Alarm 4510 when the G34 K × speed² alone takes
/// more than half the acceleration.
pub fn thread_ramp(t: &ThreadSpec, lead_end: i64, cpt: f32, cpr: u32, accel: f32) -> Result<i64, AlarmKind> {
    let cpr = cpr as f32;
    let k = t.lead_delta as f32 / (cpr * cpr);
    ramp_counts(t.lead as f32 / cpr, lead_end.max(t.lead) as f32 / cpr, k, cpt, accel)
        .ok_or(AlarmKind::ThreadLeadChangeTooFast { letter: t.long.letter() })
}

/// Length along the long axis (nm) of the ramp-up of `ramp` counts: `F·R/2` and, for
/// a growing lead, `K·(R/2)²/2` (in counts).
fn ramp_up_nm(t: &ThreadSpec, ramp: i64, cpr: u32) -> f32 {
    let (r, cpr) = (ramp as f32, cpr as f32);
    t.lead as f32 / cpr * r / 2.0 + (t.lead_delta.max(0) as f32 / (cpr * cpr)) * r * r / 8.0
}

/// A rigid-tapping move from `start`: lead × rpm and lead × the spindle's
/// acceleration must be within the tapping axis's limits.
pub fn tap(start: &Pos, t: &TapMove, p: &MotionParams, line: u32, slot: &mut Item) -> Result<Prepared, AlarmKind> {
    if t.lead <= 0 {
        return Err(AlarmKind::FeedZero);
    }
    let (len, dir) = straight(start, &t.to.machine);
    let long = long_axis(start, &t.to.machine);
    let along = dir[long.index()].abs().max(1e-9);
    let too_fast = |a: Axis| AlarmKind::TapTooFast { letter: a.letter() };
    let rpm = t.spindle.rpm.unwrap_or(0) as f32;
    let v = p.per_tick(rpm * t.lead as f32) / along;
    check_speed(&dir, v, p).map_err(too_fast)?;
    // The axis follows the spindle's own acceleration: lead × rev/period².
    let period_s = p.tick_ns as f32 / 1e9;
    let rev_per_tick2 = p.spindle_accel_rpm_s as f32 / 60.0 * period_s * period_s;
    let (_, accel) = axis_caps(&dir, p, false, true);
    if t.lead as f32 * rev_per_tick2 / along > accel {
        return Err(too_fast(long));
    }
    let (len_nm, len) = (len, len_q8(len)?);
    *slot = Item::Motion(Block {
        line,
        kind: BlockKind::Tap(TapSpec { lead: t.lead, dir: t.dir, long }),
        offset: t.to.machine - t.to.work,
        feed: FeedSpec::PerRev(t.lead),
        spindle: t.spindle,
        exact_stop: true,
        entry_at_max: false,
        plan: plan(len, accel, v.max(1.0), v),
        exec: Exec::outlined(FeedSpec::PerRev(t.lead), len, &t.to.machine, p),
    });
    Ok(Prepared { dir_in: dir, dir_out: dir, end: t.to.machine, len: len_nm })
}

#[cfg(test)]
mod tests {
    use super::*;
    use canon::xorshift::XorShift;

    /// The FPU-seeded reciprocal is as close to `2^62 / len` as `inverse62`.
    #[test]
    fn seeded_inverse_is_within_two_to_the_minus_30() {
        let mut rng = XorShift::new(0x0123_4567_89ab_cdef);
        let fixed = [1u64, 2, 3, 255, 256, 1 << 20, (1 << 31) - 1, 1 << 31, (1 << 32) - 1, 123_456_789, 1 << 40];
        let random = (0..100_000).map(|i| (rng.next_u64() >> (3 + i % 60)).max(1));
        for len in fixed.into_iter().chain(random).chain([(1 << 61) - 1, 1 << 61]) {
            let exact = (1u128 << 62) / u128::from(len);
            let got = inverse_len(len) as u128;
            assert!(exact.abs_diff(got) <= (exact >> 30) + 1, "{len}: {got} vs {exact}");
        }
    }

    /// Radii rounded exactly from the integer square sum against the former
    /// `round(√(a² + b²))` in f64, and the new length against the former formula.
    #[test]
    fn integer_radii_match_the_f64_ones() {
        let mut rng = XorShift::new(0x9e37_79b9_7f4a_7c15);
        let mut next = |m: i64| rng.signed(m);
        let mut differ = 0;
        for i in 0..40_000 {
            let m = [1_000, 1_000_000, 100_000_000, 2_000_000_000][i % 4];
            let v = (next(m), next(m));
            let (r, nm) = radius(v);
            let old = libm::sqrt((v.0 as f64) * (v.0 as f64) + (v.1 as f64) * (v.1 as f64));
            assert!((r - old).abs() <= old * 1e-15, "{v:?}");
            let exact = libm::round(old) as i64;
            assert!((nm - exact).abs() <= 1, "{v:?}: {nm} vs {exact}");
            differ += usize::from(nm != exact);
            // √x never lies on a half: the exact rounding is the nearest integer.
            let x = |f: i64| (f as i128 * 2 - 1).pow(2);
            let four_x = 4 * (v.0 as i128 * v.0 as i128 + v.1 as i128 * v.1 as i128);
            assert!(x(nm) <= four_x && four_x < x(nm + 1), "{v:?}: {nm}");
            let sweep = next(1 << 31);
            let len = (sweep.unsigned_abs() as f64 * (core::f64::consts::TAU / 8_589_934_592.0) * (r + r)) as f32;
            let before = ((sweep as f64).abs() * (core::f64::consts::TAU / 4_294_967_296.0) * (old + old) / 2.0) as f32;
            assert!((len - before).abs() <= before * 2e-7, "{len} vs {before}");
        }
        // Up to 2 m radii: the f64 root rounded the same way in every case.
        assert_eq!(differ, 0);
        assert_eq!(radius((0, 0)), (0.0, 0));
        assert_eq!(radius((3, 4)).1, 5);
        assert_eq!(radius((1, 1)).1, 1);
        assert_eq!(radius((2, 2)).1, 3);
        for r in [0.0, 0.4, 1.0, 1.9, 2.5e7 + 0.75, 4_294_967_295.9, 4_294_967_296.0, 1e15 + 0.5, 1.8e19] {
            assert_eq!(trunc_u64(r), r as u64, "{r}");
        }
        // Vectors anywhere in the i64 range end at once (no long correction loop).
        for v in [(i64::MAX, i64::MAX), (i64::MIN, 0), (1 << 52, 1 << 52), ((1 << 52) - 1, 7), (-(1 << 40), 1 << 40)] {
            let (r, nm) = radius(v);
            assert!(nm.abs_diff(libm::round(r) as i64) <= 1, "{v:?}: {nm} vs {r}");
        }
    }

    /// The f32 radii and arc lengths against the f64 ones they replaced (the
    /// rounded radii equal exactly, the f32 radii within 2^-22, the lengths within
    /// 4·10⁻⁷), over vectors up to 2 m and beyond 2^32 nm.
    #[test]
    fn f32_radii_and_lengths_match_the_f64_ones() {
        let mut rng = XorShift::new(0x9e37_79b9_7f4a_7c15);
        let mut next = |m: i64| rng.signed(m);
        for i in 0..40_000 {
            let m = [1_000, 1_000_000, 100_000_000, 2_000_000_000, 1 << 40][i % 5];
            let (v, w) = ((next(m), next(m)), (next(m), next(m)));
            let ((r, nm), (r1, nm1)) = (radius(v), radius(w));
            let ((rf, nmf), (r1f, nm1f)) = (radius_f32(v), radius_f32(w));
            assert_eq!((nmf, nm1f), (nm, nm1), "{v:?} {w:?}");
            assert!((f64::from(rf) - r).abs() <= r * 2.4e-7, "{v:?}: {rf} vs {r}");
            let sweep = next(1 << 32);
            let before = (sweep.unsigned_abs() as f64 * (core::f64::consts::TAU / 8_589_934_592.0) * (r + r1)) as f32;
            let len = arc_len(sweep, rf, r1f);
            assert!((len - before).abs() <= before * 4e-7, "{len} vs {before}");
        }
        assert_eq!(radius_f32((0, 0)), (0.0, 0));
        let (r, nm) = radius_f32((3, 4));
        assert!(nm == 5 && (r - 5.0).abs() <= 5.0 * 2.4e-7, "{r}");
        assert_eq!(radius_f32((i64::MIN, i64::MAX)).1, radius((i64::MIN, i64::MAX)).1);
    }

    /// The CORDIC start angle and sweep against the f64 ones, over arcs of every
    /// size and direction: within 16 units of 2^-32 turn, or handed to f64.
    #[test]
    fn cordic_sweeps_match_atan2() {
        let mut rng = XorShift::new(0x2545_f491_4f6c_dd1d);
        let mut next = |m: i64| rng.signed(m);
        let mut fallbacks = 0;
        for i in 0..20_000 {
            let m = [1_000, 1_000_000, 100_000_000, 1_000_000_000][i % 4];
            let (s, e) = ((next(m), next(m)), (next(m), next(m)));
            let (cw, full) = (i % 2 == 0, i % 7 == 0);
            let f = |p: (i64, i64)| (p.0 as f64, p.1 as f64);
            let want = sweep_f64(f(s), f(e), cw, full);
            let Some(got) = sweep_turns(s, e, cw, full) else {
                fallbacks += 1;
                continue;
            };
            let wrap = |d: i64| if d.abs() > 1 << 31 { d - d.signum() * (1 << 32) } else { d };
            assert!(wrap(got.0 - want.0).abs() <= 16, "{s:?} {e:?}: {got:?} vs {want:?}");
            assert!((got.1 - want.1).abs() <= 32, "{s:?} {e:?} cw {cw}: {got:?} vs {want:?}");
        }
        assert!(fallbacks < 40, "{fallbacks} arcs fell back to f64");
        // An arc ending just past its start direction: a full turn less a little
        // (clockwise) or a tiny one (counter-clockwise), decided exactly in f64.
        let (s, e) = ((30_000_000, 0), (30_000_000, 1));
        assert_eq!(sweep_turns(s, e, true, false), None);
        assert!(sweep_f64((3e7, 0.0), (3e7, 1.0), true, false).1 < -(1 << 31));
        assert!(sweep_f64((3e7, 0.0), (3e7, 1.0), false, false).1 < 1_000);
    }
}

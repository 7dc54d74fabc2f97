//! SINUMERIK drilling cycles (seed 001 chapter 2.1, lines 1443-2995): CYCLE81,
//! CYCLE82, CYCLE83, CYCLE84, CYCLE840, CYCLE85, CYCLE86, CYCLE87, CYCLE88 and
//! CYCLE89, all on the one hole generator (`cycles::hole`) that drills FANUC's
//! G83–G89 — the drilling axis and positioning plane are its parameters.
//!
//! - **Drilling axis** (lines 528-545, 1508): the applicate of the active plane —
//!   G17 Z, G18 Y, G19 X. CYCLE83/84/840 take `_AXN` instead (lines 1865-1883):
//!   1 / 2 the first / second axis of the plane, 3 (or any other) the third; so on
//!   a lathe `G18` with `_AXN=1` drills along Z on the centre line, as does `G17`.
//!   A drilling axis the machine lacks is 61803 when `_AXN` chose it, else 61005
//!   (the document names 61005 for CYCLE86 in G18 without Y, line 2721; an 840D
//!   stops every drilling cycle whose drilling axis is missing).
//! - **Levels** (lines 1559-1591): RTP retract plane, RFP reference plane, SDIS
//!   safety distance in front of RFP (the side RTP is on), DP absolute or DPR
//!   relative depth (DPR wins when both are given). DPR with RTP = RFP, a depth on
//!   the retract plane's side, or no depth at all: 61101.
//! - **The hole**: the cycle drills where the tool is in the plane (the position
//!   was approached before the call), G0 to RFP+SDIS, the cycle's work, G0 to RTP.
//!   Under DIAMON a level along X (G19 or `_AXN` choosing X) is a diameter.
//! - **Dwells** in seconds; CYCLE83's DTB, DTS and _DTD < 0 are revolutions of the
//!   spindle speed S in force (rev × 60000 / S ms).

use super::{Engine, MM, Params};
use interp_core::alarm::{AlarmKind, CycleAlarm};
use interp_core::axis::{Axis, Pos};
use interp_core::canon::{FeedMode, Plane, SpindleDir};
use interp_core::command::Command;
use interp_core::command::hole::{DeepDrill, Degression, HoleSpec, HoleWork};
use interp_core::modal::State;

use CycleAlarm::{
    AxisNotPresent, FirstDepthWrong, MachiningTypeWrong, NoSpindleDirection, NoThirdAxis, ParameterWrong,
    ReferencePlaneWrong, TechnologyWrong, ThreadPitchWrong, WrongSpindleDirection,
};

/// The levels of a hole along its drilling axis (work, nm) and where it is.
struct Hole {
    axis: Axis,
    plane: Plane,
    rtp: i64,
    rfp: i64,
    r_level: i64,
    bottom: i64,
    /// +1 / −1: the direction from RFP into the material.
    dir: i64,
    /// Plane axes: abscissa, ordinate.
    abscissa: Axis,
    ordinate: Axis,
}

/// The axes of the plane: abscissa, ordinate, applicate (lines 530-545).
pub fn plane_axes(plane: Plane) -> [Axis; 3] {
    match plane {
        Plane::Xy => [Axis::X, Axis::Y, Axis::Z],
        Plane::Zx => [Axis::Z, Axis::X, Axis::Y],
        Plane::Yz => [Axis::Y, Axis::Z, Axis::X],
    }
}

/// An alarm of a drilling cycle's own parameters: a cycle alarm or one of the
/// three others they raise. Four bytes where the [`AlarmKind`] it stands for
/// takes 44: the cycles pass it on with `?`, and [`cycle`] turns it into the
/// alarm once.
#[derive(Clone, Copy, Debug)]
enum Fault {
    Cycle(CycleAlarm),
    /// [`AlarmKind::FeedPerRevSpindleStopped`].
    SpindleStopped,
    /// [`AlarmKind::Overflow`].
    Overflow,
    /// [`AlarmKind::FeedZero`].
    FeedZero,
}

impl From<CycleAlarm> for Fault {
    fn from(k: CycleAlarm) -> Self {
        Fault::Cycle(k)
    }
}

impl From<Fault> for AlarmKind {
    fn from(f: Fault) -> Self {
        match f {
            Fault::Cycle(k) => AlarmKind::SiemensCycle(k),
            Fault::SpindleStopped => AlarmKind::FeedPerRevSpindleStopped,
            Fault::Overflow => AlarmKind::Overflow,
            Fault::FeedZero => AlarmKind::FeedZero,
        }
    }
}

fn alarm(k: CycleAlarm) -> Fault {
    Fault::Cycle(k)
}

/// The drilling axis, levels and plane of a call; `axn` is the `_AXN` argument of
/// CYCLE83/84/840 (0 for the others: the applicate).
fn hole(p: &Params<'_, '_>, st: &State, ctx: &dyn Engine, axn: i64) -> Result<Hole, CycleAlarm> {
    let [a, o, n] = plane_axes(st.modal.plane);
    let axis = match axn {
        1 => a,
        2 => o,
        _ => n,
    };
    if !ctx.cfg().axes[axis.index()].present {
        return Err(if axn != 0 { AxisNotPresent } else { NoThirdAxis });
    }
    let (abscissa, ordinate) = match axis {
        Axis::Z => (Axis::X, Axis::Y),
        Axis::Y => (Axis::Z, Axis::X),
        _ => (Axis::Y, Axis::Z),
    };
    let plane = match axis {
        Axis::Z => Plane::Xy,
        Axis::Y => Plane::Zx,
        _ => Plane::Yz,
    };
    let level = |i: usize| {
        let v = p.len(i);
        if axis == Axis::X && p.diameter { v / 2 } else { v }
    };
    let (rtp, rfp, dp) = (level(0), level(1), level(3));
    let sdis = p.unsigned(2);
    let dpr = p.unsigned(4);
    let dpr = if axis == Axis::X && p.diameter { dpr / 2 } else { dpr };
    // The direction into the material: away from the retract plane, or towards
    // DP when the retract plane is the reference plane (lines 1559-1591).
    let dir = if rtp != rfp {
        (rfp - rtp).signum()
    } else if dpr != 0 {
        return Err(ReferencePlaneWrong);
    } else {
        (dp - rfp).signum()
    };
    let bottom = if dpr != 0 { rfp + dir * dpr } else { dp };
    if dir == 0 || (bottom - rfp) * dir < 0 {
        return Err(ReferencePlaneWrong);
    }
    Ok(Hole { axis, plane, rtp, rfp, r_level: rfp - dir * sdis, bottom, dir, abscissa, ordinate })
}

/// A dwell parameter in ms: seconds, or (`revs_allowed`, < 0) spindle revolutions.
fn dwell(p: &Params<'_, '_>, i: usize, st: &State, revs_allowed: bool) -> Result<u32, Fault> {
    let v = p.real(i);
    let ms = if v < 0.0 && revs_allowed {
        if st.spindle.rpm == 0 {
            return Err(Fault::SpindleStopped);
        }
        -v * 60_000.0 / f64::from(st.spindle.rpm)
    } else {
        libm::fabs(v) * 1000.0
    };
    if !ms.is_finite() || ms > f64::from(u32::MAX) {
        return Err(Fault::Overflow);
    }
    Ok(libm::round(ms) as u32)
}

/// The spindle direction of an M3/M4/M5 number (SDIR, SDR, SDAC).
fn direction(m: i64) -> Option<SpindleDir> {
    match m {
        3 => Some(SpindleDir::Cw),
        4 => Some(SpindleDir::Ccw),
        5 => Some(SpindleDir::Stop),
        _ => None,
    }
}

/// SDIR of CYCLE86-88: M3 or M4, else 61102 (lines 2689, 2814, 2896).
fn sdir(p: &Params<'_, '_>, i: usize) -> Result<SpindleDir, CycleAlarm> {
    match direction(p.int(i)) {
        Some(SpindleDir::Stop) | None => Err(NoSpindleDirection),
        Some(d) => Ok(d),
    }
}

/// The drilling cycles of this module (their numbers, CYCLE81 … CYCLE840).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Drill {
    /// CYCLE81 (RTP, RFP, SDIS, DP, DPR): G0 to RFP+SDIS, G1 to the depth, G0 to RTP.
    C81,
    /// CYCLE82 (RTP, RFP, SDIS, DP, DPR, DTB): CYCLE81 with a dwell at the depth.
    C82,
    /// CYCLE83, deep-hole drilling ([`cycle83`]).
    C83,
    /// CYCLE84, rigid tapping ([`cycle84`]).
    C84,
    /// CYCLE840, tapping with a compensating chuck ([`cycle840`]).
    C840,
    /// CYCLE85, boring in and out at feeds ([`cycle85`]).
    C85,
    /// CYCLE86, boring with an oriented stop ([`cycle86`]).
    C86,
    /// CYCLE87, boring with a stop ([`cycle87`]).
    C87,
    /// CYCLE88, boring with a dwell and a stop ([`cycle88`]).
    C88,
    /// CYCLE89 (RTP, RFP, SDIS, DP, DPR, DTB): in, dwell, out at the same feed to
    /// RFP+SDIS, G0 to RTP (lines 2920-2995).
    C89,
}

/// What a drilling cycle does at the hole: its work, the dwell at the bottom
/// (ms) and the spindle direction it sets on the way in.
type Work = (HoleWork, u32, Option<SpindleDir>);

/// Drilling cycle `which`: the hole's axis and levels (the checks every cycle
/// makes first), the cycle's own parameters, then the hole started.
pub(super) fn cycle(
    which: Drill,
    p: &Params<'_, '_>,
    cmd: &Command,
    st: &mut State,
    ctx: &mut dyn Engine,
) -> Result<(), AlarmKind> {
    let axn = match which {
        Drill::C83 | Drill::C84 => p.int(12),
        Drill::C840 => p.int(11),
        _ => 0,
    };
    let h = hole(p, st, ctx, axn)?;
    // The cycle's own parameters, their alarm converted once.
    let work = || -> Result<Work, Fault> {
        Ok(match which {
            Drill::C81 => (PLAIN, 0, None),
            Drill::C82 => (PLAIN, dwell(p, 5, st, false)?, None),
            Drill::C83 => cycle83(p, &h, st)?,
            Drill::C84 => cycle84(p, st)?,
            Drill::C840 => cycle840(p, st)?,
            Drill::C85 => cycle85(p, st)?,
            Drill::C86 => cycle86(p, &h, st, ctx)?,
            Drill::C87 => cycle87(p)?,
            Drill::C88 => cycle88(p, st)?,
            Drill::C89 => (HoleWork::Bore, dwell(p, 5, st, false)?, None),
        })
    };
    let (work, dwell_ms, spindle) = work()?;
    let position = st.work_pos(ctx.cfg());
    let spec = HoleSpec {
        work,
        axis: h.axis,
        plane: h.plane,
        position,
        step: Pos::ZERO,
        initial: h.rtp,
        r_level: h.r_level,
        bottom: h.bottom,
        dwell_ms,
        stay_at_r: false,
        repeat: 1,
    };
    let spindle = spindle.filter(|&d| d != st.spindle.dir);
    p.ok()?;
    ctx.hole(&spec, spindle, cmd, st)
}

const PLAIN: HoleWork = HoleWork::Drill { q: 0, deep: false, d: 0 };

/// CYCLE83 (RTP, RFP, SDIS, DP, DPR, FDEP, FDPR, DAM, DTB, DTS, FRF, VARI, _AXN,
/// _MDEP, _VRT, _DTD, _DIS1), lines 1703-1956.
fn cycle83(p: &Params<'_, '_>, h: &Hole, st: &State) -> Result<Work, Fault> {
    let chip_removal = match p.int(11) {
        0 => false,
        1 => true,
        _ => return Err(alarm(MachiningTypeWrong)),
    };
    // The first depth: FDPR relative to RFP, else FDEP absolute; deeper than the
    // hole, or not into it, is 61107 (lines 1803, 1823).
    let fdpr = p.unsigned(6);
    let first = if fdpr != 0 { fdpr } else { (p.len(5) - h.rfp) * h.dir };
    let total = (h.bottom - h.rfp) * h.dir;
    if first <= 0 || first > total {
        return Err(alarm(FirstDepthWrong));
    }
    let dam = p.real(7);
    let degression = if dam > 0.0 {
        Degression::Amount(p.nm(dam))
    } else if dam < 0.0 {
        if dam < -1.0 {
            return Err(alarm(ParameterWrong));
        }
        // Without _MDEP the strokes shrink to 1 mm at least.
        let min = match p.unsigned(13) {
            0 => MM,
            m => m,
        };
        Degression::Factor { ppm: interp_core::geom::round_i64(-dam * 1e6), min }
    } else {
        Degression::None
    };
    let feed = st.feed.get(st.modal.feed_mode);
    // FRF: 0.001-1, larger is 1, left out is 1 (line 1852).
    let frf = match libm::fabs(p.real(10)) {
        0.0 => 1.0,
        f => f.clamp(0.001, 1.0),
    };
    let dtb = dwell(p, 8, st, true)?;
    let deep = DeepDrill {
        first,
        approach: (h.rfp - h.r_level) * h.dir,
        degression,
        chip_removal,
        retract: p.or_1mm(14),
        anticipation: p.unsigned(16),
        dwell_depth_ms: dtb,
        dwell_start_ms: if chip_removal { dwell(p, 9, st, true)? } else { 0 },
        first_feed: interp_core::geom::round_i64(feed as f64 * frf),
        feed,
    };
    let dtd = match dwell(p, 15, st, true)? {
        0 => dtb,
        d => d,
    };
    Ok((HoleWork::DeepDrill(deep), dtd, None))
}

/// The lead of a tapping cycle from MPIT (M3–M48, sign = direction) and PIT (sign =
/// direction, unit by _PTAB): nm/rev and the direction into the hole. Both zero, a
/// size not in the ISO coarse series, or values that contradict: 61001.
fn tap_lead(p: &Params<'_, '_>, mpit: usize, pit: usize, ptab: usize) -> Result<(i64, SpindleDir), CycleAlarm> {
    let (m, v) = (p.real(mpit), p.real(pit));
    let pitch_mm = match p.int(ptab) {
        0 => v * p.per_unit / 1e6,
        1 => v,
        2 if v != 0.0 => 25.4 / v,
        2 => 0.0,
        3 => v * 25.4,
        _ => return Err(ThreadPitchWrong),
    };
    let mm = if m != 0.0 {
        let coarse = super::thread::coarse_pitch(libm::fabs(m), 48.0).ok_or(ThreadPitchWrong)?;
        let coarse = if m < 0.0 { -coarse } else { coarse };
        if pitch_mm != 0.0 && libm::fabs(pitch_mm - coarse) > 1e-6 {
            return Err(ThreadPitchWrong);
        }
        coarse
    } else if pitch_mm != 0.0 {
        pitch_mm
    } else {
        return Err(ThreadPitchWrong);
    };
    let nm = libm::round(libm::fabs(mm) * 1e6);
    if !(1.0..=2e9).contains(&nm) {
        return Err(ThreadPitchWrong);
    }
    Ok((nm as i64, if mm < 0.0 { SpindleDir::Ccw } else { SpindleDir::Cw }))
}

/// _TECHNO: units 0-3 (G601-G603), tens 0-2 (FFWON/FFWOF), hundreds up to
/// `hundreds` (SOFT/BRISK/DRIVE or the braking point), thousands 0-1; else 61125.
/// Accepted and otherwise without effect: our axes always stop exactly at the
/// tapping reversal and the planner has one acceleration profile.
fn techno(p: &Params<'_, '_>, i: usize, hundreds: u32) -> Result<(), CycleAlarm> {
    // In 32 bits (64-bit / and % are calls): a negative value fails the conversion.
    let ok =
        u32::try_from(p.int(i)).is_ok_and(|t| t <= 1999 && t % 10 <= 3 && t / 10 % 10 <= 2 && t / 100 % 10 <= hundreds);
    if ok { Ok(()) } else { Err(TechnologyWrong) }
}

/// CYCLE84 (RTP, RFP, SDIS, DP, DPR, DTB, SDAC, MPIT, PIT, POSS, SST, SST1, _AXN,
/// _PTAB, _TECHNO, _VARI, _DAM, _VRT), lines 1958-2204: rigid tapping, the axis
/// locked to the spindle (G331/G332), in pecks when _VARI is 1 (chip breaking:
/// back by _VRT) or 2 (chip removal: back to R).
fn cycle84(p: &Params<'_, '_>, st: &State) -> Result<Work, Fault> {
    let (lead, dir) = tap_lead(p, 7, 8, 13)?;
    techno(p, 14, 3)?;
    let restore = match p.int(6) {
        0 => st.spindle.dir,
        m => direction(m).ok_or(alarm(NoSpindleDirection))?,
    };
    let (q, deep) = match p.int(15) {
        0 => (0, false),
        1 => (p.unsigned(16), false),
        2 => (p.unsigned(16), true),
        _ => return Err(alarm(MachiningTypeWrong)),
    };
    let work = HoleWork::RigidTap { lead, q, deep, d: p.or_1mm(17), dir, dwell_r_ms: 0, restore };
    let dtb = dwell(p, 5, st, false)?;
    Ok((work, dtb, None))
}

/// CYCLE840 (RTP, RFP, SDIS, DP, DPR, DTB, SDR, SDAC, ENC, MPIT, PIT, _AXN, _PTAB,
/// _TECHNO), lines 2206-2504: tapping with a compensating chuck, the feed following
/// the spindle (G33 with an encoder, G63 without).
fn cycle840(p: &Params<'_, '_>, st: &State) -> Result<Work, Fault> {
    techno(p, 13, 1)?;
    let enc = p.int(8);
    let with_encoder = match enc {
        0 | 20 => true,
        1 | 11 => false,
        _ => return Err(alarm(ParameterWrong)),
    };
    // The spindle turns into the hole the way M3/M4 before the call set it.
    let dir = match st.spindle.dir {
        SpindleDir::Stop => return Err(alarm(NoSpindleDirection)),
        d => d,
    };
    let back = if dir == SpindleDir::Cw { SpindleDir::Ccw } else { SpindleDir::Cw };
    // SDR: 0 = reversed automatically (needs the encoder), else M3/M4 — the way
    // out must be the other way (61807, table 12281); without an encoder it must
    // be given (61102, table 12217).
    match (p.int(6), with_encoder) {
        (0, true) => {}
        (0, false) => return Err(alarm(NoSpindleDirection)),
        (m, _) => match direction(m) {
            Some(d) if d == back => {}
            Some(SpindleDir::Stop) | None => return Err(alarm(NoSpindleDirection)),
            Some(_) => return Err(alarm(WrongSpindleDirection)),
        },
    }
    let after = match p.int(7) {
        0 => dir,
        m => direction(m).ok_or(alarm(WrongSpindleDirection))?,
    };
    let lead = if enc == 1 {
        // ENC = 1: the lead is the programmed F over S (line 2328).
        let f = st.feed.get(st.modal.feed_mode);
        match st.modal.feed_mode {
            FeedMode::PerRev => f,
            FeedMode::PerMin if st.spindle.rpm > 0 => f / i64::from(st.spindle.rpm),
            FeedMode::PerMin => return Err(Fault::SpindleStopped),
        }
    } else {
        tap_lead(p, 9, 10, 12)?.0
    };
    if lead <= 0 {
        return Err(Fault::FeedZero);
    }
    let work = HoleWork::FloatTap { lead, dir, turning: true, after, stop_at_bottom: false };
    // DTB: with ENC = 20 and without an encoder (the example of line 2458 dwells
    // with ENC = 1); not with ENC = 0.
    let dtb = if enc == 0 { 0 } else { dwell(p, 5, st, false)? };
    Ok((work, dtb, None))
}

/// A feed parameter (FFR, RFF) in the feed mode in force; 0 = the feed in force.
fn feed(p: &Params<'_, '_>, i: usize, st: &State) -> i64 {
    match p.unsigned(i) {
        0 => st.feed.get(st.modal.feed_mode),
        f => f,
    }
}

/// CYCLE85 (RTP, RFP, SDIS, DP, DPR, DTB, FFR, RFF): in at FFR, dwell, out to
/// RFP+SDIS at RFF, G0 to RTP (lines 2506-2625).
fn cycle85(p: &Params<'_, '_>, st: &State) -> Result<Work, Fault> {
    let work = HoleWork::BoreFeeds { feed_in: feed(p, 6, st), feed_out: feed(p, 7, st) };
    let dtb = dwell(p, 5, st, false)?;
    Ok((work, dtb, None))
}

/// CYCLE86 (RTP, RFP, SDIS, DP, DPR, DTB, SDIR, RPA, RPO, RPAP, POSS): in with the
/// spindle turning SDIR, dwell, oriented stop, G0 off the wall by RPA/RPO in the
/// plane, G0 out, back to the hole position, spindle on (lines 2627-2751).
fn cycle86(p: &Params<'_, '_>, h: &Hole, st: &State, ctx: &dyn Engine) -> Result<Work, Fault> {
    let dir = sdir(p, 6)?;
    let mut shift = Pos::ZERO;
    for (axis, i) in [(h.abscissa, 7), (h.ordinate, 8)] {
        // A retract on an axis the machine lacks is ignored (line 2721).
        if ctx.cfg().axes[axis.index()].present {
            let v = p.len(i);
            shift[axis] = if axis == Axis::X && p.diameter { v / 2 } else { v };
        }
    }
    let dtb = dwell(p, 5, st, false)?;
    Ok((HoleWork::FineBore { shift, restart: dir }, dtb, Some(dir)))
}

/// CYCLE87 (RTP, RFP, SDIS, DP, DPR, SDIR): in with the spindle turning SDIR, M5,
/// M0, G0 out after NC start (lines 2753-2835).
fn cycle87(p: &Params<'_, '_>) -> Result<Work, Fault> {
    let dir = sdir(p, 5)?;
    Ok((HoleWork::BoreManual { restart: dir }, 0, Some(dir)))
}

/// CYCLE88 (RTP, RFP, SDIS, DP, DPR, DTB, SDIR): CYCLE87 with a dwell; M5 only
/// (no M0) when `_ZSD[5]` = 1 (lines 2837-2918).
fn cycle88(p: &Params<'_, '_>, st: &State) -> Result<Work, Fault> {
    let dir = sdir(p, 6)?;
    let work =
        if st.cycle.zsd[5] == 1 { HoleWork::BoreStop { restart: dir } } else { HoleWork::BoreManual { restart: dir } };
    let dtb = dwell(p, 5, st, false)?;
    Ok((work, dtb, Some(dir)))
}

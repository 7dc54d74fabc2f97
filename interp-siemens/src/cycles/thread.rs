//! CYCLE97 thread cutting (seed 001 4.7, lines 11065–11251) and CYCLE98 chained
//! threads (4.8, lines 11253–11437), mapped onto the thread infeed engine that
//! cuts FANUC's G76 (`interp_core::cycles::thread`).
//!
//! What the cycles ask of the engine, from the document:
//! - the cycle's start point is the run-in APP before the thread start, 1 mm above
//!   the thread's diameter (lines 11148–11152); passes end the run-out ROP after
//!   the thread end; the tool retracts by _VRT (0: 1 mm) above the thread;
//! - the depth TDEP less the allowance FAL is cut in NRC rough passes of constant
//!   infeed (VARI 1/2) or of constant chip cross-section (VARI 3/4, pass k at
//!   √(k/NRC) of the depth), then one pass takes FAL (when FAL > 0), then NID idle
//!   passes at the full depth (lines 11154–11166);
//! - IANG infeeds along a flank (> 0 always the same one, < 0 alternating, which a
//!   taper cannot do: it then uses one flank) (lines 11168–11176);
//! - the whole sequence is cut for each of NUMT starts, start i at NSP + i × 360° /
//!   NUMT (lines 11178–11212);
//! - the thread is a longitudinal one when its taper is at most 45°, a face thread
//!   otherwise (lines 11224–11228);
//! - CYCLE98 chains three segments of their own pitch PP1–PP3 through the points
//!   PO1/DM1 … PO4/DM4 without stopping (the thread moves after the first continue
//!   without waiting for the spindle index).
//!
//! Choices where the document is silent or contradicts itself (docs/SIEMENS.md):
//! - VARI outside 1–4 raises 61002 "machining type defined incorrectly": the CYCLE97
//!   section says 61102, but the alarm table lists CYCLE97 under 61002 and 61102 is
//!   "no spindle direction programmed"; CYCLE98's section says 61002 (an 840D
//!   raises 61002 for both);
//! - PIT is the lead of each start (the value G33 cuts with); NUMT spreads the
//!   starts over the circumference;
//! - without an allowance (FAL = 0) there is no separate finishing pass: the
//!   manual's example (5 rough passes, no allowance, then 2 idle passes) cuts 7;
//! - MPIT is a metric thread size M3–M60 of the ISO coarse series (DIN 13-1): its
//!   pitch; PIT and MPIT both zero, a size not in the series, or a PIT other than
//!   the size's pitch raise 61001 "thread pitch defined incorrectly".

use super::{Engine, MM, Params, need_zx};
use interp_core::alarm::{AlarmKind, CycleAlarm};
use interp_core::command::Command;
use interp_core::command::job::{CHAIN_POINTS, Depths, Flank, MultiThreadSpec, Pullout};
use interp_core::geom::Pt;
use interp_core::modal::State;

/// ISO metric coarse threads (DIN 13-1): nominal diameter and pitch, mm.
pub(super) const COARSE: &[(f64, f64)] = &[
    (3.0, 0.5),
    (3.5, 0.6),
    (4.0, 0.7),
    (4.5, 0.75),
    (5.0, 0.8),
    (6.0, 1.0),
    (7.0, 1.0),
    (8.0, 1.25),
    (9.0, 1.25),
    (10.0, 1.5),
    (11.0, 1.5),
    (12.0, 1.75),
    (14.0, 2.0),
    (16.0, 2.0),
    (18.0, 2.5),
    (20.0, 2.5),
    (22.0, 2.5),
    (24.0, 3.0),
    (27.0, 3.0),
    (30.0, 3.5),
    (33.0, 3.5),
    (36.0, 4.0),
    (39.0, 4.0),
    (42.0, 4.5),
    (45.0, 4.5),
    (48.0, 5.0),
    (52.0, 5.0),
    (56.0, 5.5),
    (60.0, 5.5),
    (64.0, 6.0),
    (68.0, 6.0),
];

/// The coarse pitch of metric size M`size`, mm, if it is one of [`COARSE`] up to `max`.
pub(super) fn coarse_pitch(size: f64, max: f64) -> Option<f64> {
    COARSE.iter().find(|(d, _)| libm::fabs(d - size) < 1e-6 && *d <= max + 1e-6).map(|&(_, p)| p)
}

/// Micro-degrees in a turn.
const TURN_UDEG: i64 = 360_000_000;

/// What CYCLE97 and CYCLE98 have in common after their points and pitches.
struct Common {
    app: i64,
    rop: i64,
    depth: i64,
    allowance: i64,
    iang: f64,
    nsp: f64,
    nrc: i64,
    nid: i64,
    vari: i64,
    numt: i64,
    vrt: i64,
}

/// CYCLE97 (PIT, MPIT, SPL, FPL, DM1, DM2, APP, ROP, TDEP, FAL, IANG, NSP, NRC, NID,
/// VARI, NUMT, _VRT).
pub(super) fn cycle97(
    p: &Params<'_, '_>,
    cmd: &Command,
    st: &mut State,
    ctx: &mut dyn Engine,
) -> Result<(), AlarmKind> {
    need_zx(st)?;
    let (pit, mpit) = (libm::fabs(p.real(0)), p.real(1));
    // Line 11138: PIT or the size MPIT (M3–M60), not contradicting each other.
    let lead = match (pit > 0.0, mpit != 0.0) {
        (_, true) => {
            let coarse = coarse_pitch(mpit, 60.0).ok_or(AlarmKind::SiemensCycle(CycleAlarm::ThreadPitchWrong))?;
            if pit > 0.0 && libm::fabs(pit * p.per_unit - coarse * 1e6) > 1.0 {
                return Err(AlarmKind::SiemensCycle(CycleAlarm::ThreadPitchWrong));
            }
            interp_core::geom::round_i64(coarse * 1e6)
        }
        (true, false) => p.nm(pit),
        (false, false) => return Err(AlarmKind::SiemensCycle(CycleAlarm::ThreadPitchWrong)),
    };
    let c = common(p, 6)?;
    let a = Pt::new(p.x(4), p.len(2));
    let b = Pt::new(p.x(5), p.len(3));
    p.ok()?;
    let spec = spec(&c, &[a, b], &[lead], st)?;
    ctx.thread(&spec, cmd, st)
}

/// CYCLE98 (PO1, DM1, PO2, DM2, PO3, DM3, PO4, DM4, APP, ROP, TDEP, FAL, IANG, NSP,
/// NRC, NID, PP1, PP2, PP3, VARI, NUMT, _VRT).
pub(super) fn cycle98(
    p: &Params<'_, '_>,
    cmd: &Command,
    st: &mut State,
    ctx: &mut dyn Engine,
) -> Result<(), AlarmKind> {
    need_zx(st)?;
    // Common parameters from APP (8) to NID (15); PP1–PP3 at 16–18, VARI 19, NUMT 20, _VRT 21.
    let mut c = common(p, 8)?;
    (c.vari, c.numt, c.vrt) = (p.int(19), p.int(20), p.or_1mm(21));
    check_vari(c.vari)?;
    let mut points = [Pt::default(); CHAIN_POINTS];
    for (i, pt) in points.iter_mut().enumerate() {
        *pt = Pt::new(p.x(2 * i + 1), p.len(2 * i));
    }
    let mut leads = [0; CHAIN_POINTS - 1];
    for (i, l) in leads.iter_mut().enumerate() {
        *l = p.unsigned(16 + i);
    }
    // A segment of no length (a point programmed twice) is left out.
    let mut pts: heapless::Vec<Pt, CHAIN_POINTS> = heapless::Vec::new();
    let mut lds: heapless::Vec<i64, CHAIN_POINTS> = heapless::Vec::new();
    let _ = pts.push(points[0]);
    for i in 0..CHAIN_POINTS - 1 {
        if points[i + 1] != points[i] {
            let _ = pts.push(points[i + 1]);
            let _ = lds.push(leads[i]);
        }
    }
    if lds.contains(&0) {
        return Err(AlarmKind::SiemensCycle(CycleAlarm::ThreadPitchWrong));
    }
    p.ok()?;
    let spec = spec(&c, &pts, &lds, st)?;
    ctx.thread(&spec, cmd, st)
}

/// APP, ROP, TDEP, FAL, IANG, NSP, NRC, NID (from parameter `at`) and, for CYCLE97
/// (`at` = 6), VARI, NUMT, _VRT after them.
fn common(p: &Params<'_, '_>, at: usize) -> Result<Common, CycleAlarm> {
    let mut c = Common {
        app: p.unsigned(at),
        rop: p.unsigned(at + 1),
        depth: p.unsigned(at + 2),
        allowance: p.unsigned(at + 3),
        iang: p.real(at + 4),
        nsp: p.real(at + 5),
        nrc: p.int(at + 6),
        nid: p.int(at + 7),
        vari: 0,
        numt: 0,
        vrt: 0,
    };
    if at == 6 {
        (c.vari, c.numt, c.vrt) = (p.int(14), p.int(15), p.or_1mm(16));
        check_vari(c.vari)?;
    }
    Ok(c)
}

/// VARI 1–4, else 61002 (see the module notes on 61102).
fn check_vari(vari: i64) -> Result<(), CycleAlarm> {
    if !(1..=4).contains(&vari) {
        return Err(CycleAlarm::MachiningTypeWrong);
    }
    Ok(())
}

/// The engine's specification of a thread through `pts` (radius X) with the lead
/// of each segment.
fn spec(c: &Common, pts: &[Pt], leads: &[i64], st: &State) -> Result<MultiThreadSpec, AlarmKind> {
    let n = pts.len();
    let (first, last) = (pts[0], pts[n - 1]);
    if n < 2 || first == last {
        return Err(AlarmKind::CycleValueIllegal { what: "thread start and end are the same point" });
    }
    if c.depth <= 0 || c.allowance > c.depth {
        return Err(AlarmKind::CycleValueIllegal { what: "TDEP must be above zero and at least FAL" });
    }
    // Lines 11224–11228: a taper of at most 45° is a longitudinal thread.
    let face = (last.x - first.x).abs() > (last.z - first.z).abs();
    let (long, feed) = if face {
        (interp_core::axis::Axis::X, interp_core::axis::Axis::Z)
    } else {
        (interp_core::axis::Axis::Z, interp_core::axis::Axis::X)
    };
    // Outside threads are cut going in the negative direction, inside ones positive.
    let internal = c.vari == 2 || c.vari == 4;
    let inward = if internal { 1 } else { -1 };
    let mut points = [last; CHAIN_POINTS];
    points[..n].copy_from_slice(pts);
    // Run-in along the first segment, run-out along the last, measured on the long axis.
    points[0] = extend(pts[1], pts[0], c.app, long);
    points[n - 1] = extend(pts[n - 2], pts[n - 1], c.rop, long);
    if points[..n]
        .windows(2)
        .any(|w| (w[1].get(long) - w[0].get(long)).signum() != (last.get(long) - first.get(long)).signum())
    {
        return Err(AlarmKind::CycleValueIllegal { what: "thread chain goes back along its long axis" });
    }
    let start = points[0].with(feed, points[0].get(feed) - inward * MM);
    let outer = points[..n].iter().map(|q| -inward * q.get(feed)).max().unwrap_or(0);
    let retract = -inward * (outer + c.vrt);
    let angle_udeg = interp_core::geom::round_i64(libm::fabs(c.iang) * 1e6);
    let cylindrical = pts.iter().all(|q| q.get(feed) == first.get(feed));
    let nsp = interp_core::geom::round_i64(c.nsp * 1e6);
    let start_udeg = match st.cycle.recut {
        Some(r) if !face => recut_start(r, &points[..n], leads)?,
        Some(_) => return Err(AlarmKind::SiemensCycle(CycleAlarm::RecutImpossible)),
        None => nsp,
    };
    let mut all_leads = [leads[n - 2]; CHAIN_POINTS - 1];
    all_leads[..n - 1].copy_from_slice(leads);
    Ok(MultiThreadSpec {
        start,
        points,
        count: n,
        leads: all_leads,
        face,
        inward,
        height: c.depth,
        allowance: c.allowance,
        depths: Depths::Split { passes: c.nrc.clamp(1, 999) as u32, constant_section: c.vari >= 3 },
        finish: u32::from(c.allowance > 0) + c.nid.clamp(0, 999) as u32,
        flank: Flank::ToFinal { angle_udeg, alternate: c.iang < 0.0 && cylindrical },
        pull: Pullout::default(),
        retract,
        starts: c.numt.clamp(1, 360) as u32,
        start_udeg: start_udeg.rem_euclid(TURN_UDEG) as u32,
    })
}

/// The start angle that makes a thread through `points` (pass start first) with
/// `leads` run through the re-cutting synchronisation point `r` (4.9): the angle
/// there less the turns the spindle makes while the tool goes from the pass start
/// to its Z. 61612 when the point is not on the thread (a face thread too: only
/// its Z is known).
fn recut_start(r: interp_core::modal::ThreadRecut, points: &[Pt], leads: &[i64]) -> Result<i64, AlarmKind> {
    let mut turns = 0.0;
    for (w, &lead) in points.windows(2).zip(leads) {
        let (a, b) = (w[0].z, w[1].z);
        let (lo, hi) = (a.min(b), a.max(b));
        let to = r.z.clamp(lo, hi);
        turns += (to - a).abs() as f64 / lead as f64;
        if to == r.z {
            let advance = interp_core::geom::round_i64(interp_core::geom::fmod(turns, 1.0) * TURN_UDEG as f64);
            return Ok(r.angle_udeg - advance);
        }
    }
    Err(AlarmKind::SiemensCycle(CycleAlarm::RecutImpossible))
}

/// `to` moved on by `by` along the long axis, away from `from`, on the line
/// `from` → `to`.
fn extend(from: Pt, to: Pt, by: i64, long: interp_core::axis::Axis) -> Pt {
    let d = to.get(long) - from.get(long);
    if by == 0 || d == 0 {
        return to;
    }
    let t = by as f64 / d.abs() as f64;
    let mv = |a: i64, b: i64| b + interp_core::geom::round_i64((b - a) as f64 * t);
    Pt::new(mv(from.x, to.x), mv(from.z, to.z))
}

//! CYCLE90 thread milling (seed 001 lines 3538-3772): an internal (TYPTH 0) or
//! external (TYPTH 1) thread of diameter DIATH, core diameter KDIAM and pitch PIT
//! about CPA/CPO, milled on a helix in the direction CDIR (2 G2, 3 G3) from the
//! reference plane RFP to the depth DP (or RFP − DPR) — or from the bottom up,
//! when RTP lies beyond DP (lines 3630-3650). The path is [`mill_paths::thread`].
//!
//! Checks, in this order: plane (61005); D offset (61000, also for a radius of
//! 0, line 3739), a negative radius 61112 (table 5.3); levels (61101); thread
//! sizes — PIT outside 0.001 … 2000, DIATH ≤ 0, KDIAM not below DIATH, an
//! internal thread without KDIAM — 61001 "thread pitch defined incorrectly"
//! (the table's "thread size or pitch contradictory"); TYPTH other than 0/1
//! 61002; an internal thread whose cutter does not fit its core hole
//! (2r ≥ KDIAM) 61105 (line 3743); FFR 0 with no feed in force 61003. A CDIR
//! other than 2/3 is G3 with the message 62101 (line 3717), the cycle goes on.

use super::{Radius, cutter, feed, levels, plane};
use crate::cycles::{Engine, Params};
use interp_core::alarm::{AlarmKind, CycleAlarm};
use interp_core::command::Command;
use interp_core::modal::State;
use mill_paths::MillGen;
use mill_paths::thread::{Thread, ThreadSpec};

/// CYCLE90: checks the call and starts its thread.
pub(in crate::cycles) fn cycle90(
    p: &Params<'_, '_>,
    cmd: &Command,
    st: &mut State,
    ctx: &mut dyn Engine,
) -> Result<(), AlarmKind> {
    let s = spec90(p, st, ctx)?;
    p.ok()?;
    ctx.mill(MillGen::Thread(Thread::new(s)), cmd, st)?;
    if !matches!(p.int(9), 2 | 3) {
        ctx.message(62101);
    }
    Ok(())
}

/// The thread of a CYCLE90 call, or its alarm.
#[inline(never)]
fn spec90(p: &Params<'_, '_>, st: &State, ctx: &mut dyn Engine) -> Result<ThreadSpec, CycleAlarm> {
    plane(st, ctx.cfg())?;
    let r = cutter(st, Radius::NotNegative)?;
    if r == 0 {
        return Err(CycleAlarm::NoToolOffset);
    }
    let (rtp, rfp, to, safe) = match levels(p, st, [0, 1, 2, 3], Some(4)) {
        Ok(l) => (l.rtp, l.rfp, l.bottom, l.safe),
        Err(e) => {
            // From the bottom up (line 3632): RTP beyond DP, DP given absolute.
            let (rtp, rfp, dp) = (p.len(0), p.len(1), p.len(3));
            let dir = (dp - rfp).signum();
            if p.unsigned(4) != 0 || dir == 0 || (rtp - dp).signum() != dir {
                return Err(e);
            }
            (rtp, rfp, dp, rfp - dir * p.unsigned(2))
        }
    };
    let (diath, kdiam, pit, internal) = (p.len(5), p.len(6), p.len(7), p.int(10) == 0);
    // PIT 0.001 … 2000 mm (in mm whatever the program's unit).
    if !(1_000..=2_000_000_000).contains(&pit) || !(i64::from(internal)..diath).contains(&kdiam) {
        return Err(CycleAlarm::ThreadPitchWrong);
    }
    if !(0..=1).contains(&p.int(10)) {
        return Err(CycleAlarm::MachiningTypeWrong);
    }
    if internal && 2 * r >= kdiam {
        return Err(CycleAlarm::CutterRadiusTooLarge);
    }
    Ok(ThreadSpec {
        centre: (p.len(11), p.len(12)),
        diath,
        kdiam,
        r,
        pit,
        internal,
        cw: p.int(9) == 2,
        rtp,
        safe,
        from: rfp,
        to,
        feed: feed(p, 8, st)?,
    })
}

//! CYCLE72 contour milling (seed 001 lines 5450-5764): along the contour of a
//! subprogram or a label section `_KNAME` (read as CYCLE95 reads `NPP`, in the
//! active plane), offset by the cutter radius to the side `_RL`, level by level
//! per `_MID` ([`mill_paths::contour_mill`]).
//!
//! - `_VARI` units 1 roughing (offset by radius + `_FAL`, down to `_DP` +
//!   `_FALD`), 2 finishing (offset by the radius, down to `_DP`); tens 0 the
//!   intermediate moves rapid, 1 at `_FF3` (0: `_FFP1`, line 5668); hundreds 0
//!   lift to `_RTP` between levels, 1 to `_RFP` + `_SDIS`, 2 by `_SDIS`. Other
//!   digits are 61002.
//! - `_RL` 40 on the contour, 41 left, 42 right; anything else 61002.
//! - `_AS1`/`_AS2` units 1 straight along the tangent, 2 quarter circle, 3
//!   semicircle; tens 1 in space. `_AS2` 0 is `_AS1` (line 5644). Under G40
//!   only straight (line 5648). `_LP1`/`_LP2` 0 is 61116 (line 5657).
//! - Alarms: 61000 no offset, 61009 T0, 61112 negative radius, 61101 levels,
//!   61003 no feed, 61606 contour errors (the reader's), 61105 an arc the
//!   offset runs through its centre.

use super::{Radius, cutter, feed, levels, plane, tool_selected};
use crate::cycles::{ContourSource, Engine, Params};
use interp_core::alarm::{AlarmKind, CycleAlarm};
use interp_core::command::Command;
use interp_core::modal::State;
use mill_paths::MillGen;
use mill_paths::contour_mill::{ContourMill, ContourSpec, Soft};
use mill_paths::infeed::Levels;

/// CYCLE72: checks the call, reads its contour and starts the milling.
pub(in crate::cycles) fn cycle72(
    p: &Params<'_, '_>,
    cmd: &Command,
    st: &mut State,
    ctx: &mut dyn Engine,
    contour: Option<ContourSource<'_>>,
) -> Result<(), AlarmKind> {
    let s = spec(p, st, ctx)?;
    p.ok()?;
    let contour = contour.ok_or(AlarmKind::SiemensCycle(CycleAlarm::ContourPreparation { cause: 10933 }))?;
    ctx.mill_contour(MillGen::Contour(ContourMill::new(s)), contour, cmd, st)
}

/// An `_AS` value: (path, in space), or 61002.
fn soft(v: i64, lp: i64, g40: bool) -> Result<Soft, CycleAlarm> {
    let (path, space) = (v % 10, v / 10);
    if !(1..=3).contains(&path) || !(0..=1).contains(&space) {
        return Err(CycleAlarm::MachiningTypeWrong);
    }
    if lp == 0 {
        return Err(CycleAlarm::ApproachPathZero);
    }
    Ok(Soft { path: if g40 { 1 } else { path as u8 }, space: space == 1, lp })
}

fn spec(p: &Params<'_, '_>, st: &State, ctx: &mut dyn Engine) -> Result<ContourSpec, CycleAlarm> {
    plane(st, ctx.cfg())?;
    let r = cutter(st, Radius::NotNegative)?;
    tool_selected(st)?;
    let l = levels(p, st, [1, 2, 3, 4], None)?;
    let vari = p.int(10);
    let (unit, tens, hund) = (vari % 10, vari / 10 % 10, vari / 100);
    if !(1..=2).contains(&unit) || !(0..=1).contains(&tens) || !(0..=2).contains(&hund) {
        return Err(CycleAlarm::MachiningTypeWrong);
    }
    let side = match p.int(11) {
        40 => 0,
        41 => 1,
        42 => -1,
        _ => return Err(CycleAlarm::MachiningTypeWrong),
    };
    let as1 = soft(p.int(12), p.unsigned(13), side == 0)?;
    let as2 = match p.int(15) {
        0 => soft(p.int(12), if p.unsigned(16) == 0 { p.unsigned(13) } else { p.unsigned(16) }, side == 0)?,
        v => soft(v, p.unsigned(16), side == 0)?,
    };
    let ffp1 = feed(p, 8, st)?;
    let ffd = feed(p, 9, st)?;
    let ff3 = if p.unsigned(14) > 0 { p.unsigned(14) } else { ffp1 };
    let rough = unit == 1;
    // Roughing stops `_FALD` above the bottom (towards the surface).
    let bottom = if rough { l.bottom.saturating_sub(l.dir.saturating_mul(p.unsigned(7))) } else { l.bottom };
    if bottom.saturating_sub(l.rfp).saturating_mul(l.dir) <= 0 {
        return Err(CycleAlarm::ReferencePlaneWrong);
    }
    Ok(ContourSpec {
        side,
        off: if side == 0 { 0 } else { r.saturating_add(if rough { p.unsigned(6) } else { 0 }) },
        r,
        levels: Levels::new(l.start, bottom, p.unsigned(5)),
        rtp: l.rtp,
        safe: l.safe,
        sdis: p.unsigned(3),
        dir: l.dir,
        g1: tens == 1,
        lift: hund as u8,
        soft: [as1, as2],
        feeds: [ffd, ffp1, ff3],
    })
}

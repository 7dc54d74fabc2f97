//! POCKET3/POCKET4 (lines 4714-5258, any cutter): see [`pocket34`] and
//! docs/SIEMENS-MILL.md.
//!
//! POCKET1 (rectangular pocket, lines 4421-4574) and POCKET2 (circular pocket,
//! lines 4576-4712): a centre-cutting cutter (DIN 844) plunges at the pocket's
//! centre and clears it ring by ring from the inside out, level by level per
//! MID, then finishes the wall per MIDF ([`mill_paths::pocket`]).
//!
//! - VARI (SLOT1's text, lines 4109-4139): 0 complete (roughing to FAL at FFP1,
//!   finishing at FFP2 and SSF), 1 roughing, 2 finishing; any other value is
//!   61002 "machining type defined incorrectly" (the tables give 0, 1, 2 only).
//! - CDIR (lines 4090-4100): 2 G2, 3 G3; 0 climb, 1 conventional milling from
//!   the spindle direction (M3: climb G3, conventional G2; M4 the other way; a
//!   stopped spindle counts as M3); other values are 61002.
//! - CRAD smaller than the cutter radius leaves corners of the cutter radius
//!   (line 4519); a cutter wider than the pocket's width (POCKET1) or a radius
//!   above PRAD (POCKET2) is 61105 "milling cutter radius too large".
//! - The width step between rings is 80 % of the cutter diameter (the document
//!   gives none for POCKET1/2; POCKET3's `_MIDA` default, line 4960).

#[cfg(feature = "mill-pockets")]
use super::width_infeed;
use super::{Radius, cutter, feed, fits, levels, plane};
use crate::cycles::{Engine, Params};
use interp_core::alarm::{AlarmKind, CycleAlarm};
use interp_core::canon::SpindleDir;
use interp_core::command::Command;
use interp_core::modal::State;
use mill_paths::MillGen;
use mill_paths::infeed::{Levels, max_width};
use mill_paths::pocket::{Insert, Pocket, PocketSpec};
use mill_paths::rot::Rot;

/// POCKET1 (`circle` false) or POCKET2: checks the call and starts its pocket.
pub(in crate::cycles) fn pocket12(
    circle: bool,
    p: &Params<'_, '_>,
    cmd: &Command,
    st: &mut State,
    ctx: &mut dyn Engine,
) -> Result<(), AlarmKind> {
    let s = spec12(circle, p, st, ctx)?;
    p.ok()?;
    ctx.mill(MillGen::Pocket(Pocket::new(s)), cmd, st)
}

/// The pocket of a POCKET1/POCKET2 call, or its alarm.
fn spec12(circle: bool, p: &Params<'_, '_>, st: &State, ctx: &mut dyn Engine) -> Result<PocketSpec, CycleAlarm> {
    plane(st, ctx.cfg())?;
    let r = cutter(st, Radius::NotNegative)?;
    let l = levels(p, st, [0, 1, 2, 3], Some(4))?;
    // Where the shape's parameters end: POCKET1 has LENG, WID, CRAD, CPA, CPO,
    // STA1; POCKET2 PRAD, CPA, CPO.
    let (c, k) = if circle { (6, 8) } else { (8, 11) };
    let vari = p.int(k + 5);
    let m4 = st.spindle.dir == SpindleDir::Ccw;
    let cw = match p.int(k + 3) {
        2 => true,
        3 => false,
        // Climb (0) is G3 under M3, conventional (1) G2 (line 4098).
        d @ 0..=1 => (d == 0) == m4,
        _ => return Err(CycleAlarm::MachiningTypeWrong),
    };
    if !(0..=2).contains(&vari) {
        return Err(CycleAlarm::MachiningTypeWrong);
    }
    let (hl, hw, cr, sta) = if circle {
        let rad = p.unsigned(5);
        (rad, rad, rad, 0.0)
    } else {
        (p.unsigned(5) / 2, p.unsigned(6) / 2, p.unsigned(7), p.real(10))
    };
    fits(2 * hl.min(hw), r)?;
    let ffd = feed(p, k, st)?;
    let ffp1 = feed(p, k + 1, st)?;
    let ffp2 = if p.unsigned(k + 7) > 0 { feed(p, k + 7, st)? } else { ffp1 };
    let none = Levels { count: 0, ..Levels::new(l.start, l.bottom, 0) };
    let depth = |mid| Levels::new(l.start, l.bottom, p.unsigned(mid));
    Ok(PocketSpec {
        rot: Rot::new((p.len(c), p.len(c + 1)), sta),
        hl,
        hw,
        cr,
        r,
        fal: p.unsigned(k + 4),
        step: max_width(0, r),
        rtp: l.rtp,
        safe: l.safe,
        rough: if vari == 2 { none } else { depth(k + 2) },
        finish: if vari == 1 { none } else { depth(k + 6) },
        floor: none,
        insert: Insert::Feed,
        arc_in: 0,
        blank: [0; 3],
        feeds: [ffd, ffp1, ffp2],
        ssf: p.int(k + 8).clamp(0, i64::from(u32::MAX)) as u32,
        cw,
    })
}

/// POCKET3 (`circle` false, lines 4714-5014) or POCKET4 (5016-5258): checks the
/// call and starts its pocket.
///
/// - `_VARI` units 1 roughing (to `_FAL` and `_FALD`), 2 finishing (the wall if
///   `_FAL` > 0, then the floor if `_FALD` > 0); tens the insertion: 0 G0, 1 G1
///   straight down, 2 helix (`_RAD1`, `_DP1`), 3 oscillating at `_RAD1` degrees
///   (POCKET3 only); else 61002.
/// - `_CDIR` 0-3 as POCKET1's, else 61109; 0/1 with the spindle stopped 61102.
/// - 61113 `_CRAD` above half a side, 61105 the cutter wider than a side (or a
///   radius above `_PRAD`), 61111 `_MIDA`, 61110 `_FALD` above `_MID`, 61108 a
///   helix or oscillation that cannot run, 61117 a radius ≤ 0.
#[cfg(feature = "mill-pockets")]
pub(in crate::cycles) fn pocket34(
    circle: bool,
    p: &Params<'_, '_>,
    cmd: &Command,
    st: &mut State,
    ctx: &mut dyn Engine,
) -> Result<(), AlarmKind> {
    let s = spec34(circle, p, st, ctx)?;
    p.ok()?;
    ctx.mill(MillGen::Pocket(Pocket::new(s)), cmd, st)
}

/// The pocket of a POCKET3/POCKET4 call, or its alarm.
#[cfg(feature = "mill-pockets")]
fn spec34(circle: bool, p: &Params<'_, '_>, st: &State, ctx: &mut dyn Engine) -> Result<PocketSpec, CycleAlarm> {
    plane(st, ctx.cfg())?;
    let r = cutter(st, Radius::Positive)?;
    let l = levels(p, st, [0, 1, 2, 3], None)?;
    // Where the parameters after the shape sit: _MID at k (POCKET3 has _LENG,
    // _WID, _CRAD, _PA, _PO, _STA; POCKET4 _PRAD, _PA, _PO), _AD at j (POCKET3
    // has _AP2 before it).
    let (k, j) = if circle { (7, 16) } else { (10, 20) };
    let vari = p.int(k + 6);
    // Units 1 roughing, 2 finishing; tens the insertion (POCKET4 has no 3x).
    let tens_max = if circle { 2 } else { 3 };
    if !(0..=tens_max * 10 + 9).contains(&vari) || !(1..=2).contains(&(vari % 10)) {
        return Err(CycleAlarm::MachiningTypeWrong);
    }
    let cw = match p.int(k + 5) {
        2 => true,
        3 => false,
        // Climb (0) is G3 under M3, conventional (1) G2 (lines 4925-4933); they need
        // the spindle's direction (61102 lists POCKET3/POCKET4).
        d @ 0..=1 => match st.spindle.dir {
            SpindleDir::Cw => d == 1,
            SpindleDir::Ccw => d == 0,
            _ => return Err(CycleAlarm::NoSpindleDirection),
        },
        _ => return Err(CycleAlarm::CdirWrong),
    };
    let (hl, hw, cr, centre) = if circle {
        let rad = p.unsigned(4);
        (rad, rad, rad, Rot::new((p.len(5), p.len(6)), 0.0))
    } else {
        let sta = p.real(9);
        let (leng, wid) = (p.len(4), p.len(5));
        let mut rot = Rot::new((p.len(7), p.len(8)), sta);
        // _ZSD[2] = 1: _PA/_PO is a corner, _LENG/_WID signed towards the centre
        // (lines 3533-3534, 4876-4884).
        if st.cycle.zsd[2] == 1 {
            rot.at = rot.point(leng as f64 / 2.0, wid as f64 / 2.0);
        }
        let (hl, hw, cr) = (leng.abs() / 2, wid.abs() / 2, p.unsigned(6));
        if cr > hl.min(hw) {
            return Err(CycleAlarm::CornerRadiusTooLarge);
        }
        (hl, hw, cr, rot)
    };
    fits(2 * hl.min(hw), r)?;
    let step = width_infeed(p.unsigned(k + 7), r)?;
    let (mid, fal, fald) = (p.unsigned(k), p.unsigned(k + 1), p.unsigned(k + 2));
    let total = (l.bottom - l.start).abs();
    if fald > 0 && (fald >= total || (mid > 0 && fald > mid)) {
        return Err(CycleAlarm::FloorAllowanceTooLarge);
    }
    let (rad1, dp1) = (p.unsigned(j + 1), p.unsigned(j + 2));
    let insert = match vari / 10 {
        0 => Insert::Rapid,
        1 => Insert::Feed,
        // The helix must fit inside the roughed pocket.
        2 if rad1 > 0 && dp1 > 0 && rad1 + r <= hl.min(hw) - fal => Insert::Helix { rad: rad1, pitch: dp1 },
        3 if rad1 > 0 && p.real(j + 1).abs() < 90.0 => {
            let (s, c) = libm::sincos(p.real(j + 1).abs().to_radians());
            Insert::Swing { tan: s / c }
        }
        _ => return Err(CycleAlarm::InsertionWrong),
    };
    let ffp1 = feed(p, k + 3, st)?;
    let ffd = feed(p, k + 4, st)?;
    // Roughing leaves _FALD on the floor; the wall is finished down to there,
    // then the floor from _DP + _FALD + _SDIS (lines 4796-4820).
    let to = l.bottom - l.dir * fald;
    let none = Levels { count: 0, ..Levels::new(l.start, to, 0) };
    let rough = vari % 10 == 1;
    let (ap1, ap2) =
        if circle { (p.unsigned(k + 8), p.unsigned(k + 8)) } else { (p.unsigned(k + 8) / 2, p.unsigned(19) / 2) };
    let ad = p.unsigned(j);
    Ok(PocketSpec {
        rot: centre,
        hl,
        hw,
        cr,
        r,
        fal: if rough { fal } else { 0 },
        step,
        rtp: l.rtp,
        safe: l.safe,
        rough: if rough { Levels::new(l.start, to, mid) } else { none },
        finish: if rough || fal == 0 { none } else { Levels::new(l.start, to, mid) },
        floor: if rough || fald == 0 {
            none
        } else {
            Levels { count: 1, ..Levels::new(to + l.safe - l.rfp, l.bottom, 0) }
        },
        insert,
        arc_in: fal.max(2_000_000),
        blank: if ap1 > 0 && ap2 > 0 && ad > 0 { [ap1, ap2, l.rfp + l.dir * ad] } else { [0; 3] },
        feeds: [ffd, ffp1, ffp1],
        ssf: 0,
        cw,
    })
}

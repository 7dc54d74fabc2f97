//! CYCLE71 face milling (lines 5260-5448) and the spigots CYCLE76 (rectangular,
//! 5766-5953) and CYCLE77 (circular, 5955-6111): the calls read and checked here,
//! the paths laid out by [`mill_paths::face`] and [`mill_paths::spigot`].
//!
//! **CYCLE71** `(_RTP, _RFP, _SDIS, _DP, _PA, _PO, _LENG, _WID, _STA, _MID, _MIDA,
//! _FDP, _FALD, _FFP1, _VARI, _FDP1)`: the rectangle from the corner `_PA`/`_PO`,
//! `_LENG`/`_WID` signed, turned by `_STA`; `_VARI` units 1 roughing to `_FALD`
//! per `_MID`, 2 finishing at `_DP` once; tens 1 parallel to the abscissa in one
//! direction, 2 to the ordinate in one direction, 3 and 4 the same alternating
//! (lines 5385-5397; anything else 61002). Alarms: 61009 no tool (T0) — 61124 instead
//! when `_MIDA` is 0 too (the width comes from the tool), 61000 no D, 61117 a
//! radius ≤ 0, 61011 a scaling in force, 61101 the levels, 61118 `_LENG` or
//! `_WID` 0, 61111 `_MIDA` above the diameter, 61003 no feed.
//!
//! **CYCLE76** `(_RTP, _RFP, _SDIS, _DP, _DPR, _LENG, _WID, _CRAD, _PA, _PO, _STA,
//! _MID, _FAL, _FALD, _FFP1, _FFD, _CDIR, _VARI, _AP1, _AP2)` and **CYCLE77**
//! `(_RTP, _RFP, _SDIS, _DP, _DPR, _PRAD, _PA, _PO, _MID, _FAL, _FALD, _FFP1, _FFD,
//! _CDIR, _VARI, _AP1)` (`_PRAD` is the diameter, line 6045): `_VARI` 1 roughing
//! to `_FAL`/`_FALD` per `_MID`, 2 finishing (the wall per `_MID` to `_DP`; the
//! floor only, one ring at `_DP`, when `_FAL` is 0 and `_FALD` not, lines
//! 5852-5854, 6031-6033); CYCLE76's reference point is the centre, or with `_ZSD[2]` = 1
//! the corner (`_LENG`/`_WID` signed, line 5868). `_CDIR` 2 G2, 3 G3; 0 climb and
//! 1 conventional milling from the spindle: round the outside of a spigot
//! climb milling under M3 is G2 (the document prints the pockets' table, M3 →
//! G3, which is conventional milling outside a contour; we mill as the names
//! say). Alarms: 61009 no tool or no offset (lines 5921, 6083), 61112 a negative
//! radius, 61012 unequal scaling of the plane's axes, 61002 `_VARI`/`_CDIR`,
//! 61101 the levels, 61605 a CYCLE76 `_LENG`/`_WID` of 0 or `_CRAD` above half
//! the smaller side, 61213 a CYCLE77 `_PRAD` of 0, 61215 a blank not larger than
//! the spigot, 61610 `_MID` 0, 61003 no feed. 61200 (too many elements in the
//! machining block) cannot happen: the path is generated, not stored.

use super::{Radius, cutter, feed, here, levels, plane, tool_selected, width_infeed};
use crate::cycles::{Engine, Params};
use interp_core::alarm::{AlarmKind, CycleAlarm};
use interp_core::canon::SpindleDir;
use interp_core::command::Command;
use interp_core::modal::State;
use interp_core::modal::mill::on;
use mill_paths::MillGen;
use mill_paths::face::{Face, FaceSpec};
use mill_paths::infeed::Levels;
use mill_paths::rot::Rot;
use mill_paths::spigot::{Spigot, SpigotSpec};

/// The scale factors (thousandths, no sign) of the plane's abscissa, ordinate
/// and applicate when a scaling is in force.
fn scales(st: &State) -> Option<[i32; 3]> {
    let f = &st.mill.frame;
    if f.active & on::SCALE == 0 {
        return None;
    }
    let axes = interp_core::cycles::mill::plane_axes(st.modal.plane);
    Some(axes.map(|x| f.scale.get(x.index()).map_or(1000, |k| k.abs())))
}

/// CYCLE71: checks the call and starts its face.
pub(in crate::cycles) fn cycle71(
    p: &Params<'_, '_>,
    cmd: &Command,
    st: &mut State,
    ctx: &mut dyn Engine,
) -> Result<(), AlarmKind> {
    let s = spec71(p, st, ctx)?;
    p.ok()?;
    ctx.mill(MillGen::Face(Face::new(s)), cmd, st)
}

/// The face of a CYCLE71 call, or its alarm.
fn spec71(p: &Params<'_, '_>, st: &State, ctx: &mut dyn Engine) -> Result<FaceSpec, CycleAlarm> {
    let at = here(st, ctx.cfg());
    plane(st, ctx.cfg())?;
    let mida = p.unsigned(10);
    if st.tool.tool == 0 && mida == 0 {
        return Err(CycleAlarm::InfeedWidthMissing);
    }
    tool_selected(st)?;
    let r = cutter(st, Radius::Positive)?;
    if scales(st).is_some_and(|k| k != [1000; 3]) {
        return Err(CycleAlarm::ScaleNotAllowed);
    }
    let vari = p.int(14);
    let (unit, tens) = (vari % 10, vari / 10);
    if !(1..=2).contains(&unit) || !(1..=4).contains(&tens) {
        return Err(CycleAlarm::MachiningTypeWrong);
    }
    let l = levels(p, st, [0, 1, 2, 3], None)?;
    let (leng, wid) = (p.len(6), p.len(7));
    if leng == 0 || wid == 0 {
        return Err(CycleAlarm::LengthOrWidthZero);
    }
    let step = width_infeed(mida, r)?;
    let finish = unit == 2;
    let fald = p.unsigned(12);
    Ok(FaceSpec {
        rot: Rot::new((p.len(4), p.len(5)), p.real(8)),
        leng,
        wid,
        along_wid: tens % 2 == 0,
        zigzag: tens >= 3,
        r,
        step,
        fdp: p.unsigned(11),
        fdp1: p.unsigned(15),
        from: at.d,
        rtp: l.rtp,
        safe: l.safe,
        sdis: p.unsigned(2),
        dir: l.dir,
        levels: if finish {
            Levels::new(l.start, l.bottom, 0)
        } else {
            Levels::new(l.start, l.bottom - l.dir * fald, p.unsigned(9))
        },
        finish,
        fald,
        feed: feed(p, 13, st)?,
    })
}

/// CYCLE76 (`circle` false) or CYCLE77: checks the call and starts its spigot.
pub(in crate::cycles) fn spigot(
    circle: bool,
    p: &Params<'_, '_>,
    cmd: &Command,
    st: &mut State,
    ctx: &mut dyn Engine,
) -> Result<(), AlarmKind> {
    let s = spec_spigot(circle, p, st, ctx)?;
    p.ok()?;
    ctx.mill(MillGen::Spigot(Spigot::new(s)), cmd, st)
}

/// The spigot of a CYCLE76/CYCLE77 call, or its alarm.
fn spec_spigot(circle: bool, p: &Params<'_, '_>, st: &State, ctx: &mut dyn Engine) -> Result<SpigotSpec, CycleAlarm> {
    let at = here(st, ctx.cfg());
    plane(st, ctx.cfg())?;
    // No tool or no offset is 61009 (lines 5921, 6083).
    tool_selected(st)?;
    let r = cutter(st, Radius::NotNegative).map_err(|e| match e {
        CycleAlarm::NoToolOffset => CycleAlarm::ToolNumberZero,
        e => e,
    })?;
    if scales(st).is_some_and(|[a, o, _]| a != o) {
        return Err(CycleAlarm::ScaleDiffers);
    }
    // Where _MID is: the parameters after it are the same in both.
    let k = if circle { 8 } else { 11 };
    let m4 = st.spindle.dir == SpindleDir::Ccw;
    let cw = match p.int(k + 5) {
        2 => true,
        3 => false,
        // Outside a contour, climb milling (0) under M3 is G2.
        d @ 0..=1 => (d == 0) != m4,
        _ => return Err(CycleAlarm::MachiningTypeWrong),
    };
    let vari = p.int(k + 6);
    if !(1..=2).contains(&vari) {
        return Err(CycleAlarm::MachiningTypeWrong);
    }
    let l = levels(p, st, [0, 1, 2, 3], Some(4))?;
    let ap1 = p.unsigned(k + 7);
    let (rot, hl, hw, cr) = if circle {
        let d = p.unsigned(5);
        if d == 0 {
            return Err(CycleAlarm::CircleRadiusTooSmall);
        }
        if ap1 <= d {
            return Err(CycleAlarm::BlankWrong);
        }
        (Rot::new((p.len(6), p.len(7)), 0.0), d / 2, d / 2, d / 2)
    } else {
        let (leng, wid, crad) = (p.len(5), p.len(6), p.unsigned(7));
        let (hl, hw) = (leng.abs() / 2, wid.abs() / 2);
        if hl == 0 || hw == 0 || crad > hl.min(hw) {
            return Err(CycleAlarm::ContourWrong);
        }
        if ap1 <= leng.abs() || p.unsigned(k + 8) <= wid.abs() {
            return Err(CycleAlarm::BlankWrong);
        }
        let mut rot = Rot::new((p.len(8), p.len(9)), p.real(10));
        if st.cycle.zsd[2] == 1 {
            // Dimensioned from a corner: the centre half the signed sides away.
            rot.at = rot.point(leng as f64 / 2.0, wid as f64 / 2.0);
        }
        (rot, hl, hw, crad)
    };
    let mid = p.unsigned(k);
    if mid == 0 {
        return Err(CycleAlarm::NoInfeedDepth);
    }
    let (fal, fald) = (p.unsigned(k + 1), p.unsigned(k + 2));
    let ffp1 = feed(p, k + 3, st)?;
    let ffd = feed(p, k + 4, st)?;
    let finish = vari == 2;
    // _ZSD[1] does not name the spigots (line 3531): their infeeds always start
    // at RFP + SDIS.
    let levels = match (finish, fal == 0 && fald > 0) {
        (true, true) => Levels::new(l.safe, l.bottom, 0),
        (true, false) => Levels::new(l.safe, l.bottom, mid),
        _ => Levels::new(l.safe, l.bottom - l.dir * fald, mid),
    };
    Ok(SpigotSpec {
        rot,
        hl,
        hw,
        cr,
        r,
        fal: if finish { 0 } else { fal },
        blank: ap1 / 2,
        here: (at.a, at.o),
        rtp: l.rtp,
        safe: l.safe,
        levels,
        feeds: [ffd, ffp1],
        cw,
    })
}

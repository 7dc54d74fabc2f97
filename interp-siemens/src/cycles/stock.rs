//! CYCLE95 stock removal with undercuts (seed 001 4.5, lines 10596–10954), mapped
//! onto G71/G72's roughing engine (`interp_core::cycles`, `rough::RoughGen` with the
//! options a [`StockSpec`] asks for): the contour `NPP` (a subprogram or a label section, read by
//! the engine in its program's language), the twelve machining types of VARI
//! (roughing / finishing / complete × longitudinal / face × outside / inside) with
//! the hundreds digit choosing how far each cut follows the contour, MID, the
//! allowances, the feeds FF1–FF3, the chip-breaking DT/DAM and _VRT.
//!
//! Choices where the document is silent or contradicts itself (docs/SIEMENS.md):
//! - MID with `_ZSD[0]` = 0 follows the diameter programming in force (the rule
//!   the document states for CYCLE950, lines 11708–11716, and what its CYCLE95
//!   example needs: the 39 mm of lines 10733–10737 are the diameters 76 − 37 of
//!   KONTUR_1): under DIAMON a longitudinal MID is a diameter; 1 = radius,
//!   2 = diameter; a face cycle's MID is a length along Z;
//! - FALX follows DIAMON like every plane-axis value of the turning cycles
//!   (line 10113): under DIAMON it is a diameter;
//! - hundreds digit 2 follows the contour after each cut up to the previous cut
//!   point, 0 (the default) one cut point further (the "overlapping" pull of
//!   lines 10617–10619);
//! - VARI outside 1–12 / 101–112 / 201–212 raises 61002.

use super::{ContourSource, Engine, Params, need_zx};
use interp_core::alarm::{AlarmKind, CycleAlarm};
use interp_core::command::Command;
use interp_core::command::job::{Blank, Pull, StockSpec};
use interp_core::geom::Pt;
use interp_core::modal::State;

/// CYCLE95 (NPP, MID, FALZ, FALX, FAL, FF1, FF2, FF3, VARI, DT, DAM, _VRT).
pub(super) fn cycle95(
    p: &Params<'_, '_>,
    cmd: &Command,
    st: &mut State,
    ctx: &mut dyn Engine,
    contour: Option<ContourSource<'_>>,
) -> Result<(), AlarmKind> {
    need_zx(st)?;
    // A negative VARI (or one beyond u32) reads as 0, whose units are wrong.
    let vari = u32::try_from(p.int(8)).unwrap_or(0);
    let (units, hundreds) = (vari % 100, vari / 100);
    if !(1..=12).contains(&units) || !(hundreds == 0 || hundreds == 2) {
        return Err(AlarmKind::SiemensCycle(CycleAlarm::MachiningTypeWrong));
    }
    let (stage, kind) = ((units - 1) / 4, (units - 1) % 4);
    let facing = kind % 2 == 1;
    let mid = p.unsigned(1);
    // _ZSD[0]: 0 by DIAMON/DIAMOF, 1 radius, 2 diameter (lines 10139–10145).
    let mid_diameter = match st.cycle.zsd[0] {
        1 => false,
        2 => true,
        _ => p.diameter,
    };
    let depth = if !facing && mid_diameter { mid / 2 } else { mid };
    let falx = p.unsigned(3);
    let spec = StockSpec {
        facing,
        internal: kind >= 2,
        rough: stage != 1,
        finish: stage != 0,
        depth,
        allow_x: if p.diameter { falx / 2 } else { falx },
        allow_z: p.unsigned(2),
        allow: p.unsigned(4),
        feeds: [p.unsigned(5), p.unsigned(6), p.unsigned(7)],
        pull: if hundreds == 0 { Pull::Overlap } else { Pull::Previous },
        equal: true,
        undercuts: true,
        parallel: false,
        blank: Blank::Contour,
        direction: 0,
        retract_angle_udeg: 45_000_000,
        arc_feed: 0,
        approach: 0,
        interrupt: p.unsigned(10),
        dwell_ms: seconds_ms(p.real(9)),
        retract: p.or_1mm(11),
    };
    let contour = contour.ok_or(AlarmKind::SiemensCycle(CycleAlarm::ContourPreparation { cause: 10933 }))?;
    p.ok()?;
    ctx.stock(&spec, contour, cmd, st)
}

/// A dwell in seconds as ms (negative or absurd values: none).
pub(super) fn seconds_ms(s: f64) -> u32 {
    if s.is_finite() && s > 0.0 { libm::round((s * 1e3).min(1e9)) as u32 } else { 0 }
}

/// CYCLE950 (_NP1, _NP2, _NP3, _NP4, _VARI, _MID, _FALZ, _FALX, _FF1, _FF2, _FF3,
/// _FF4, _VRT, _ANGB, _SDIS, _NP5, _NP6, _NP7, _NP8, _APZ, _APZA, _APX, _APXA,
/// _TOL1), the extended stock removal of seed 001 4.10 (lines 11511–12156), on the
/// same roughing engine as CYCLE95:
/// - `_VARI` digits (lines 11688–11698): units 1 longitudinal, 2 face, 3
///   contour-parallel (G73's passes); tens the infeed direction X−/X+/Z−/Z+
///   (outside/inside); hundreds rough/finish/complete; thousands with / without
///   following the contour; ten-thousands with / without the undercuts;
///   hundred-thousands the machining direction (checked against the contour's: 61721);
/// - `_MID` full steps until less than two are left, then two halves (11702–11706),
///   radius or diameter by `_ZSD[0]` as CYCLE95; contour-parallel: perpendicular;
/// - feeds: `_FF1` longitudinal and `_FF2` face roughing, `_FF3` finishing, `_FF4`
///   on the finishing contour's arcs;
/// - `_VRT` (0: 1 mm) at the angle `_ANGB` (0: 45°), `_TOL1` (0: 1 mm) where the
///   rapids stop before the blank;
/// - the blank: `_APX`/`_APZ` absolute (`_APXA`/`_APZA` 90: a cylinder) or an
///   allowance round the contour (91); none given: the cylinder through the
///   contour's highest point, as CYCLE95.
///
/// Not done (docs/SIEMENS.md): a blank *contour* (`_NP5`–`_NP7`, other than
/// "DEFAULT") raises 4007; the machining is cut directly rather than written to the
/// program `_NP4` (the HMI's way), and no updated blank `_NP8` is written; `_SDIS`
/// is not used (the retracts keep _VRT off the contour).
pub(super) fn cycle950(
    p: &Params<'_, '_>,
    cmd: &Command,
    st: &mut State,
    ctx: &mut dyn Engine,
    contour: Option<ContourSource<'_>>,
) -> Result<(), AlarmKind> {
    need_zx(st)?;
    // Six digits; a negative or longer VARI reads as 0, whose units digit is wrong.
    let vari = u32::try_from(p.int(4)).ok().filter(|&v| v < 1_000_000).unwrap_or(0);
    let digit = |k: u32| (vari / 10_u32.pow(k)) % 10;
    let (kind, infeed, stage, pull, under, dir) = (digit(0), digit(1), digit(2), digit(3), digit(4), digit(5));
    let bad = !(1..=3).contains(&kind)
        || !(1..=4).contains(&infeed)
        || !(1..=3).contains(&stage)
        || !(1..=2).contains(&pull)
        || !(1..=2).contains(&under)
        || !(1..=4).contains(&dir);
    // Longitudinal infeeds along X, face along Z; the machining direction along the other.
    let infeed_x = infeed <= 2;
    if bad || (kind == 1 && !infeed_x) || (kind == 2 && infeed_x) || ((dir <= 2) == infeed_x) {
        return Err(AlarmKind::SiemensCycle(CycleAlarm::IllegalInput));
    }
    let facing = !infeed_x;
    let internal = infeed == 2 || infeed == 4;
    let mid = p.unsigned(5);
    let mid_diameter = match st.cycle.zsd[0] {
        1 => false,
        2 => true,
        _ => p.diameter,
    };
    let depth = if kind != 3 && !facing && mid_diameter { mid / 2 } else { mid };
    let falx = p.unsigned(7);
    let half = |v: i64| if p.diameter { v / 2 } else { v };
    let feeds = if facing {
        [p.unsigned(9), p.unsigned(8), p.unsigned(10)]
    } else {
        [p.unsigned(8), p.unsigned(9), p.unsigned(10)]
    };
    let angb = if p.real(13) == 0.0 { 45.0 } else { libm::fabs(p.real(13)) };
    if angb >= 90.0 {
        return Err(AlarmKind::SiemensCycle(CycleAlarm::IllegalInput));
    }
    let blank_contour = p.text(15);
    if !blank_contour.is_empty() && !blank_contour.eq_ignore_ascii_case(b"DEFAULT") {
        return Err(AlarmKind::NotSupportedYet { what: "a CYCLE950 blank contour (_NP5-_NP7)" });
    }
    let (apza, apxa) = (p.int(20), p.int(22));
    let blank = match (apza, apxa) {
        (0, 0) => Blank::Contour,
        (91, 91) | (0, 91) | (91, 0) => Blank::Allowance(Pt::new(half(p.unsigned(21)), p.unsigned(19))),
        (90, 90) | (0, 90) | (90, 0) => Blank::At(Pt::new(half(p.len(21).abs()), p.len(19))),
        _ => return Err(AlarmKind::SiemensCycle(CycleAlarm::BlankContourWrong)),
    };
    // Along the cutting axis: X− (1) / X+ (2) for face machining, Z− (3) / Z+ (4).
    let direction = if dir % 2 == 1 { -1 } else { 1 };
    let spec = StockSpec {
        facing,
        internal,
        rough: stage != 2,
        finish: stage != 1,
        depth,
        allow_x: half(falx),
        allow_z: p.unsigned(6),
        allow: 0,
        feeds,
        pull: if pull == 1 { Pull::Previous } else { Pull::None },
        equal: false,
        undercuts: under == 1,
        parallel: kind == 3,
        blank,
        direction,
        retract_angle_udeg: interp_core::geom::round_i64(angb * 1e6),
        arc_feed: p.unsigned(11),
        interrupt: 0,
        dwell_ms: 0,
        retract: p.or_1mm(12),
        approach: p.or_1mm(23),
    };
    let contour = contour.ok_or(AlarmKind::SiemensCycle(CycleAlarm::FinishedContourWrong))?;
    p.ok()?;
    ctx.stock(&spec, contour, cmd, st)
}

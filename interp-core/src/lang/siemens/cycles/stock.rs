//! CYCLE95 stock removal with undercuts (seed 001 4.5, lines 10596–10954), mapped
//! onto the stock generator that shares G71/G72's roughing geometry
//! (`crate::cycles`): the contour `NPP` (a subprogram or a label section, read by
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
use crate::alarm::AlarmKind;
use crate::command::Command;
use crate::command::job::StockSpec;
use crate::modal::State;

/// CYCLE95 (NPP, MID, FALZ, FALX, FAL, FF1, FF2, FF3, VARI, DT, DAM, _VRT).
pub(super) fn cycle95(
    p: &Params<'_, '_>,
    cmd: &Command,
    st: &mut State,
    ctx: &mut dyn Engine,
    contour: Option<ContourSource<'_>>,
) -> Result<(), AlarmKind> {
    need_zx(st)?;
    let vari = p.int(8);
    let (units, hundreds) = (vari % 100, vari / 100);
    if !(1..=12).contains(&units) || !(hundreds == 0 || hundreds == 2) {
        return Err(AlarmKind::MachiningTypeWrong);
    }
    let (stage, kind) = ((units - 1) / 4, (units - 1) % 4);
    let facing = kind % 2 == 1;
    let mid = p.unsigned(1)?;
    // _ZSD[0]: 0 by DIAMON/DIAMOF, 1 radius, 2 diameter (lines 10139–10145).
    let mid_diameter = match st.cycle.zsd[0] {
        1 => false,
        2 => true,
        _ => p.diameter,
    };
    let depth = if !facing && mid_diameter { mid / 2 } else { mid };
    let falx = p.unsigned(3)?;
    let spec = StockSpec {
        facing,
        internal: kind >= 2,
        rough: stage != 1,
        finish: stage != 0,
        depth,
        allow_x: if p.diameter { falx / 2 } else { falx },
        allow_z: p.unsigned(2)?,
        allow: p.unsigned(4)?,
        feeds: [p.unsigned(5)?, p.unsigned(6)?, p.unsigned(7)?],
        overlap: hundreds == 0,
        interrupt: p.unsigned(10)?,
        dwell_ms: seconds_ms(p.real(9)),
        retract: p.or_1mm(11)?,
    };
    let contour = contour.ok_or(AlarmKind::ContourPreparation { cause: 10933 })?;
    ctx.stock(&spec, contour, cmd, st)
}

/// A dwell in seconds as ms (negative or absurd values: none).
pub(super) fn seconds_ms(s: f64) -> u32 {
    if s.is_finite() && s > 0.0 { libm::round((s * 1e3).min(1e9)) as u32 } else { 0 }
}

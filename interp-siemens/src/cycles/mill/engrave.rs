//! CYCLE60 engraving (seed 001 lines 9799-10068): a text cut along a line or on
//! the top or bottom of a circle in a single-stroke font ([`mill_paths::engrave`],
//! the public-domain Hershey Roman simplex for printable ASCII).
//!
//! Parameters: `_TEXT, _RTP, _RFP, _SDIS, _DP, _DPR, _PA, _PO, _STA, _CP1, _CP2,
//! _WID, _DF, _FFD, _FFP1, _VARI, _CODEP`.
//! - `_VARI` digits (no sign): units the reference point Cartesian (0) or polar
//!   (1: `_PA` radius, `_PO` angle — about the work zero on a line, about the
//!   circle's centre on a circle); tens 0 line, 1 top of a circle, 2 bottom;
//!   hundreds reserved; thousands the reference point at the text's left (0),
//!   centre (1) or right (2); ten-thousands at its bottom (0), middle (1) or top
//!   (2); hundred-thousands `_DF` the spacing (0), the total width (1, on a line
//!   only) or the opening angle (2, on a circle only); millions the centre
//!   Cartesian (0) or polar (1: `_CP1` radius, `_CP2` angle about the work zero).
//!   A digit outside its values is 61002.
//! - `_WID` the height of the capitals' tool-centre path (line 9900: the letter's
//!   height less the cutter diameter); 0 is 61019.
//! - `_CODEP` 0 or 1252, else 61178; a character the font lacks (beyond ASCII
//!   32-126 and the accented letters of code page 1252: æ, ø, ß, €, £, µ …) 61179,
//!   as is a text of more than 91 characters; characters that do not fit `_DF` 61176.
//! - A circle with the reference point on its centre (radius 0) is 61019.

use super::{Radius, cutter, feed, levels, plane};
use crate::cycles::{Engine, Params};
use core::f64::consts::PI;
use interp_core::alarm::{AlarmKind, CycleAlarm};
use interp_core::command::Command;
use interp_core::modal::State;
use mill_paths::MillGen;
use mill_paths::engrave::{Engrave, EngraveSpec, Path, Width};

/// CYCLE60: checks the call and starts the engraving.
pub(in crate::cycles) fn cycle60(
    p: &Params<'_, '_>,
    cmd: &Command,
    st: &mut State,
    ctx: &mut dyn Engine,
) -> Result<(), AlarmKind> {
    let g = engraving(p, st, ctx)?;
    p.ok()?;
    ctx.mill(MillGen::Engrave(g), cmd, st)
}

/// A point given Cartesian (`polar` false) or as radius and angle (degrees)
/// about `about`.
fn point(polar: bool, x: i64, y: i64, about: (i64, i64)) -> (i64, i64) {
    if !polar {
        return (x, y);
    }
    let (s, c) = libm::sincos(y as f64 / 1e6 * PI / 180.0);
    let r = x as f64;
    (about.0.saturating_add((r * c) as i64), about.1.saturating_add((r * s) as i64))
}

fn engraving(p: &Params<'_, '_>, st: &State, ctx: &mut dyn Engine) -> Result<Engrave, CycleAlarm> {
    plane(st, ctx.cfg())?;
    cutter(st, Radius::NotNegative)?;
    let l = levels(p, st, [1, 2, 3, 4], Some(5))?;
    let vari = p.int(15).unsigned_abs();
    let digit = |i: u32| (vari / 10u64.pow(i) % 10) as u8;
    let path = match digit(1) {
        0 => Path::Line,
        1 => Path::Top,
        2 => Path::Bottom,
        _ => return Err(CycleAlarm::MachiningTypeWrong),
    };
    let width = match (digit(5), path) {
        (0, _) => Width::Spacing,
        (1, Path::Line) => Width::Total,
        (2, Path::Top | Path::Bottom) => Width::Angle,
        _ => return Err(CycleAlarm::MachiningTypeWrong),
    };
    if digit(0) > 1 || digit(3) > 2 || digit(4) > 2 || digit(6) > 1 || vari >= 10_000_000 {
        return Err(CycleAlarm::MachiningTypeWrong);
    }
    if !matches!(p.int(16), 0 | 1252) {
        return Err(CycleAlarm::NoCodePage);
    }
    // Angles are read as lengths of a thousandth of a degree, the radius in nm.
    let ang = |i: usize| (p.real(i) * 1e6) as i64;
    let line = path == Path::Line;
    let centre = if line { (0, 0) } else { point(digit(6) == 1, p.len(9), ang(10), (0, 0)) };
    let reference = point(digit(0) == 1, p.len(6), ang(7), centre);
    let height = p.unsigned(11);
    let df = if width == Width::Angle { p.real(12) } else { p.len(12) as f64 };
    if height == 0 || (!line && reference == centre) {
        return Err(CycleAlarm::ParameterWrong);
    }
    let feeds = [feed(p, 13, st)?, feed(p, 14, st)?];
    Engrave::new(&EngraveSpec {
        text: p.text(0),
        path,
        reference,
        centre,
        sta: p.real(8),
        height,
        df,
        width,
        h_align: digit(3),
        v_align: digit(4),
        rtp: l.rtp,
        safe: l.safe,
        bottom: l.bottom,
        feeds,
    })
}

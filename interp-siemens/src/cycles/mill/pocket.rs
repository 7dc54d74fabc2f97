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

use super::{Radius, cutter, feed, fits, levels, plane};
use crate::cycles::{Engine, Params};
use interp_core::alarm::{AlarmKind, CycleAlarm};
use interp_core::canon::SpindleDir;
use interp_core::command::Command;
use interp_core::modal::State;
use mill_paths::MillGen;
use mill_paths::infeed::{Levels, max_width};
use mill_paths::pocket::{Pocket, PocketSpec};
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
        feeds: [ffd, ffp1, ffp2],
        ssf: p.int(k + 8).clamp(0, i64::from(u32::MAX)) as u32,
        cw,
    })
}

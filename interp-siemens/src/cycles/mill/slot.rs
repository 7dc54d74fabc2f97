//! LONGHOLE (elongated holes on a circle, lines 3774-3956), SLOT1 (slots on a
//! circle, 3958-4235) and SLOT2 (circumferential slots, 4237-4419): the calls
//! read and checked here, cut by one generator ([`mill_paths::slot`]).
//!
//! - NUM slots at STA1 + k·INDA on the circle CPA/CPO, RAD (INDA 0: 360/NUM);
//!   NUM ≤ 0 or (NUM − 1)·|INDA| ≥ 360° is 61106 (as HOLES2).
//! - LONGHOLE: the width is the cutter's; LENG (the overall length) below the
//!   cutter diameter is 61105 (line 3862), LENG 0 61609. SLOT1: LENG × WID about
//!   the point at RAD, its length along the radius; a cutter wider than WID is
//!   61105 (line 4054), WID 0 or LENG < WID 61609. SLOT2: WID wide along the
//!   circle over AFSL degrees between its end caps' centres; 61105 as SLOT1,
//!   a cutter diameter under WID/2 61905 (except VARI x3, line 4356).
//! - Slots that touch or cut each other (or a SLOT2 over the circle's centre) are
//!   61104 (lines 3905, 4194, 4376, table 12217).
//! - VARI: units 0 complete, 1 roughing, 2 finishing (SLOT2 also 3: the wall
//!   only, per MID); tens SLOT1 0 G0/1 G1 vertical, 3 oscillating at most
//!   `_STA2` (0 is 61128), SLOT2 0 G0 straight / 1 along the circle at `_FFCP`.
//!   Other values are 61002 — the table's number (line 12203); SLOT1's text
//!   (line 4149) prints 61102, which is the spindle-direction alarm.
//! - CDIR: SLOT1 0-3 as POCKET1 (else 61002); SLOT2 2/3, another value is the
//!   message 62101 "wrong milling direction, G3 generated" and G3.

use super::{Radius, cutter, feed, fits, here, levels, plane};
use crate::cycles::{Engine, Params};
use interp_core::alarm::{AlarmKind, CycleAlarm};
use interp_core::canon::SpindleDir;
use interp_core::command::Command;
use interp_core::modal::State;
use mill_paths::MillGen;
use mill_paths::infeed::{Levels, max_width};
use mill_paths::slot::{SlotSpec, Slots};

/// Which of the three.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(in crate::cycles) enum Kind {
    Longhole,
    Slot1,
    Slot2,
}

/// LONGHOLE, SLOT1 or SLOT2: checks the call and starts its slots.
pub(in crate::cycles) fn slots(
    kind: Kind,
    p: &Params<'_, '_>,
    cmd: &Command,
    st: &mut State,
    ctx: &mut dyn Engine,
) -> Result<(), AlarmKind> {
    let (s, message) = spec(kind, p, st, ctx)?;
    p.ok()?;
    ctx.mill(MillGen::Slots(Slots::new(s)), cmd, st)?;
    if message {
        ctx.message(62101);
    }
    Ok(())
}

/// The slots of a call and whether CDIR was replaced by G3 (62101), or its alarm.
fn spec(kind: Kind, p: &Params<'_, '_>, st: &State, ctx: &mut dyn Engine) -> Result<(SlotSpec, bool), CycleAlarm> {
    use CycleAlarm as A;
    let lh = kind == Kind::Longhole;
    plane(st, ctx.cfg())?;
    let r = cutter(st, Radius::NotNegative)?;
    let l = levels(p, st, [0, 1, 2, 3], Some(4))?;
    // LONGHOLE has no WID: from CPA on its parameters are one place earlier.
    let k = if lh { 7 } else { 8 };
    let vari = if lh { 0 } else { p.int(18) };
    let (units, tens) = (vari % 10, vari / 10);
    let m4 = st.spindle.dir == SpindleDir::Ccw;
    let mut message = false;
    let cw = match (kind, p.int(16)) {
        (Kind::Longhole, _) => false,
        (_, 2) => true,
        (_, 3) => false,
        // Climb (0) is G3 under M3, conventional (1) G2 (line 4098).
        (Kind::Slot1, d @ 0..=1) => (d == 0) == m4,
        (Kind::Slot1, _) => return Err(A::MachiningTypeWrong),
        _ => {
            message = true;
            false
        }
    };
    let ok = match kind {
        Kind::Slot2 => (0..=3).contains(&units) && (0..=1).contains(&tens),
        _ => (0..=2).contains(&units) && matches!(tens, 0 | 1 | 3) && vari >= 0,
    };
    if !ok {
        return Err(A::MachiningTypeWrong);
    }
    let sta2 = p.real(23);
    if kind == Kind::Slot1 && tens == 3 && sta2 == 0.0 {
        return Err(A::InsertionAngleZero);
    }
    // The circle: NUM slots INDA apart.
    let num = u32::try_from(p.int(5)).ok().filter(|&n| n > 0).ok_or(A::CircleElements)?;
    let mut inda = p.real(k + 4);
    if inda == 0.0 {
        inda = 360.0 / f64::from(num);
    }
    let span = f64::from(num - 1) * libm::fabs(inda);
    if span.is_nan() || span >= 360.0 {
        return Err(A::CircleElements);
    }
    // The slot: its width and the half length of its axis.
    // (SLOT2's 7th parameter is AFSL, an angle: not read as a length.)
    let arc = kind == Kind::Slot2;
    let leng = if arc { 0 } else { p.unsigned(6) };
    let wid = if lh { 2 * r } else { p.unsigned(7) };
    let rad = p.unsigned(k + 2);
    let afsl = libm::fabs(p.real(6));
    match kind {
        Kind::Longhole if leng == 0 => return Err(A::FormWrong),
        Kind::Longhole => fits(leng, r)?,
        Kind::Slot1 if wid == 0 || leng < wid => return Err(A::FormWrong),
        _ => fits(wid, r)?,
    }
    if kind == Kind::Slot2 && units != 3 && 4 * r < wid {
        return Err(A::CutterRadiusTooSmall);
    }
    let e = (leng - wid).max(0) / 2;
    // Neighbours must not touch: the closest two slots are |INDA| or the rest
    // of the circle apart — at their inner ends' centres (LONGHOLE, SLOT1), or
    // between one's end and the next one's start (SLOT2), a chord of the circle.
    let a = if num > 1 { libm::fabs(inda).min(360.0 - span) } else { 360.0 };
    let (r0, g) = if arc { (rad, a - afsl) } else { ((rad - e).max(0), a) };
    let chord = 2.0 * r0 as f64 * libm::sin(g.to_radians() / 2.0);
    let collide = g <= 0.0 || (g < 360.0 && chord < wid as f64) || (arc && rad < wid / 2);
    if collide {
        return Err(A::SlotContourViolated);
    }
    let (ffd, ffp1) = (feed(p, k + 5, st)?, feed(p, k + 6, st)?);
    let ffp2 = if !lh && p.unsigned(20) > 0 { feed(p, 20, st)? } else { ffp1 };
    let ffcp = if kind == Kind::Slot2 && tens == 1 { feed(p, 22, st)? } else { 0 };
    // Roughing leaves FAL on the wall (less if the width leaves no room, lines
    // 4107-4113) and _FALD on the floor; finishing cuts the wall per MIDF.
    let half = wid / 2 - r;
    let fal = if lh { 0 } else { p.unsigned(17) };
    let fald = if kind == Kind::Slot1 { p.unsigned(22).min((l.bottom - l.rfp).abs()) } else { 0 };
    let rough_to = l.bottom - l.dir * fald;
    let none = |to| Levels { from: l.start, to, count: 0 };
    let mid = p.unsigned(k + 7);
    let rough = if units >= 2 { none(rough_to) } else { Levels::new(l.start, rough_to, mid) };
    let finish = match units {
        1 => none(l.bottom),
        3 => Levels::new(l.start, l.bottom, mid),
        _ if lh => none(l.bottom),
        // The width is the cutter's: only the floor is finished (line 4153).
        _ if half == 0 => Levels { from: rough_to, to: l.bottom, count: 1 },
        _ => Levels::new(l.start, l.bottom, p.unsigned(19)),
    };
    let s = SlotSpec {
        centre: (p.len(k), p.len(k + 1)),
        rad,
        sta: p.real(k + 3),
        inda,
        num,
        arc,
        e,
        afsl,
        rho: (half - fal).max(0),
        rho_f: half,
        step: max_width(0, r),
        rtp: l.rtp,
        safe: l.safe,
        here: here(st, ctx.cfg()),
        rough,
        finish,
        feeds: [ffd, ffp1, ffp2, ffcp],
        ssf: if lh { 0 } else { p.int(21).clamp(0, i64::from(u32::MAX)) as u32 },
        rpm: st.spindle.rpm,
        cw,
        insert: if kind == Kind::Slot1 { tens as u8 } else { 0 },
        tan2: libm::tan(libm::fabs(sta2).min(90.0).to_radians()),
        floor: fald > 0,
    };
    Ok((s, message))
}

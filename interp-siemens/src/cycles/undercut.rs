//! CYCLE94 undercut form E/F to DIN 509 (seed 001 4.4, lines 10453–10594) and
//! CYCLE96 thread undercut form A–D to DIN 76 (4.6, lines 10956–11061): the
//! undercut's contour from the standard's dimensions, cut in one pass with the
//! nose compensated (the engine's contour pass, `interp_core::cycles`).
//!
//! The figures with the standards' tables are missing from the seed; the
//! dimensions are the standards' own:
//! - DIN 509:2006-12 table 1, undercuts for workpieces under normal stress, by
//!   the finished diameter d1 (the rows HEIDENHAIN's CNC PILOT manual lists for
//!   DIN 509 E/F as well): over 3 to 10 mm R0.4×0.2 (f 2, t2 0.1), over 10 to 18 mm
//!   R0.6×0.2 (f 2, t2 0.1), over 18 to 80 mm R0.6×0.3 (f 2.5, t2 0.2), over 80 mm
//!   R1×0.4 (f 4, t2 0.3); the cylinder-side flank at 15°, form F's face relief at 8°;
//! - DIN 76-1:2004-06 tables 1 (outside threads) and 2 (inside threads), by the
//!   pitch of the ISO coarse thread of the nominal diameter (DIN 13-1): the
//!   undercut diameter d_g = d − x (outside) or d + y (inside), the width g2 of
//!   the normal forms A/C and the short forms B/D, the radius r, the flank at 30°
//!   (cross-checked against HEIDENHAIN's tables of DIN 76 for forms A and C).
//!
//! The undercut lies in the corner of the finished diameter and the face at SPL.
//! Its position — which side of the diameter the tool is (outside for cutting
//! edge positions 3 and 4, inside for 1 and 2) and which side of the face the
//! diameter runs (towards +Z for positions 2 and 3, −Z for 1 and 4) — is the
//! active cutting edge position (_VARI = 0, 61608 unless 1–4) or _VARI 1–4
//! (61613 otherwise). The cycle's start point is 2 mm off the finished diameter
//! and 10 mm (or past the undercut) off the face (line 10522); the contour runs
//! from there at the feed in force and the tool goes back to it with G0.
//!
//! Choices (docs/SIEMENS.md): a clearance angle (P24) smaller than the flank's
//! angle flattens the flank to it (the document's "undercut form changed": the edge
//! geometry decides the contour) — the message itself is not shown; a thread
//! undercut form A/B needs an outside position, C/D an inside one (61613 / 61608).

use super::thread::coarse_pitch;
use super::{Engine, Params, need_zx};
use interp_core::alarm::{AlarmKind, CycleAlarm};
use interp_core::command::Command;
use interp_core::geom::{Pt, Seg, SegKind};
use interp_core::modal::State;

/// A DIN 509 row: finished diameter up to (mm), radius r, depth t1, width f, face
/// depth t2 (form F).
const DIN_509: &[(f64, f64, f64, f64, f64)] = &[
    (10.0, 0.4, 0.2, 2.0, 0.1),
    (18.0, 0.6, 0.2, 2.0, 0.1),
    (80.0, 0.6, 0.3, 2.5, 0.2),
    (f64::INFINITY, 1.0, 0.4, 4.0, 0.3),
];

/// A DIN 76-1 row: pitch P; outside: x (d_g = d − x), g2 of form A, g2 of form B;
/// inside: y (d_g = d + y), g2 of form C, g2 of form D; radius r (mm).
type Din76Row = (f64, f64, f64, f64, f64, f64, f64, f64);

/// DIN 76-1:2004 tables 1 and 2, the pitches of M3–M68.
const DIN_76: &[Din76Row] = &[
    (0.5, 0.8, 1.75, 1.25, 0.3, 2.7, 2.0, 0.2),
    (0.6, 1.0, 2.1, 1.5, 0.3, 3.3, 2.4, 0.4),
    (0.7, 1.1, 2.45, 1.75, 0.3, 3.8, 2.75, 0.4),
    (0.75, 1.2, 2.6, 1.9, 0.3, 4.0, 2.9, 0.4),
    (0.8, 1.3, 2.8, 2.0, 0.3, 4.2, 3.0, 0.4),
    (1.0, 1.6, 3.5, 2.5, 0.5, 5.2, 3.7, 0.6),
    (1.25, 2.0, 4.4, 3.2, 0.5, 6.7, 4.9, 0.6),
    (1.5, 2.3, 5.2, 3.8, 0.5, 7.8, 5.6, 0.8),
    (1.75, 2.6, 6.1, 4.3, 0.5, 9.1, 6.4, 1.0),
    (2.0, 3.0, 7.0, 5.0, 0.5, 10.3, 7.3, 1.0),
    (2.5, 3.6, 8.7, 6.3, 0.5, 13.0, 9.3, 1.2),
    (3.0, 4.4, 10.5, 7.5, 0.5, 15.2, 10.7, 1.6),
    (3.5, 5.0, 12.0, 9.0, 0.5, 17.7, 12.7, 1.6),
    (4.0, 5.7, 14.0, 10.0, 0.5, 20.0, 14.0, 2.0),
    (4.5, 6.4, 16.0, 11.0, 0.5, 23.0, 16.0, 2.5),
    (5.0, 7.0, 17.5, 12.5, 0.5, 26.0, 18.5, 2.5),
    (5.5, 7.7, 19.0, 14.0, 0.5, 28.0, 20.0, 3.2),
    (6.0, 8.3, 21.0, 15.0, 0.5, 30.0, 21.0, 3.2),
];

/// Where the undercut lies: `x` +1 when the tool is outside the diameter (−1
/// inside), `z` the direction the finished diameter runs from the face.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Position {
    x: i64,
    z: i64,
}

/// The undercut's position from _VARI (1–4) or the active cutting edge position.
fn position(vari: i64, st: &State) -> Result<Position, CycleAlarm> {
    let sl = match vari {
        0 => match st.tool.tip {
            t @ 1..=4 => t,
            _ => return Err(CycleAlarm::WrongEdgePosition),
        },
        1..=4 => vari as u8,
        _ => return Err(CycleAlarm::UndercutPositionWrong),
    };
    // The tip points into the corner: position 3 (−X −Z) cuts an outside corner
    // whose diameter runs towards +Z.
    let (x, z) = match sl {
        1 => (-1, -1),
        2 => (-1, 1),
        3 => (1, 1),
        _ => (1, -1),
    };
    Ok(Position { x, z })
}

/// What the contour of an undercut is made of (mm): the finished radius `rf`, the
/// depth `t` below it, the width `f` at the diameter, the flank angle (degrees
/// from the axis), the bottom radius `r`, the face relief `t2` at `relief` degrees.
struct Shape {
    rf: f64,
    t: f64,
    f: f64,
    flank: f64,
    r: f64,
    t2: f64,
    relief: f64,
}

/// CYCLE94 (SPD, SPL, FORM, _VARI).
pub(super) fn cycle94(
    p: &Params<'_, '_>,
    cmd: &Command,
    st: &mut State,
    ctx: &mut dyn Engine,
) -> Result<(), AlarmKind> {
    need_zx(st)?;
    if st.tool.offset_number == 0 {
        return Err(AlarmKind::SiemensCycle(CycleAlarm::NoToolOffset));
    }
    let rf = p.x(0).abs();
    let form = p.text(2);
    let f_form = match form {
        [b'E' | b'e'] => false,
        [b'F' | b'f'] => true,
        _ => return Err(AlarmKind::SiemensCycle(CycleAlarm::FormWrong)),
    };
    let d = 2.0 * rf as f64 / 1e6;
    if d < 3.0 {
        return Err(AlarmKind::SiemensCycle(CycleAlarm::FinishedDiameterTooSmall));
    }
    let pos = position(p.int(3), st)?;
    let &(_, r, t1, f, t2) = DIN_509.iter().find(|row| d <= row.0).unwrap_or(&DIN_509[3]);
    let shape = Shape { rf: rf as f64 / 1e6, t: t1, f, flank: 15.0, r, t2: if f_form { t2 } else { 0.0 }, relief: 8.0 };
    let spl = p.len(1);
    p.ok()?;
    start_undercut(&shape, spl, pos, cmd, st, ctx)
}

/// CYCLE96 (DIATH, SPL, FORM, _VARI).
pub(super) fn cycle96(
    p: &Params<'_, '_>,
    cmd: &Command,
    st: &mut State,
    ctx: &mut dyn Engine,
) -> Result<(), AlarmKind> {
    need_zx(st)?;
    if st.tool.offset_number == 0 {
        return Err(AlarmKind::SiemensCycle(CycleAlarm::NoToolOffset));
    }
    let form = match p.text(2) {
        [c] if (b'A'..=b'D').contains(&c.to_ascii_uppercase()) => c.to_ascii_uppercase(),
        _ => return Err(AlarmKind::SiemensCycle(CycleAlarm::FormWrong)),
    };
    // DIATH is the thread's nominal size M3–M68 (line 11003), a diameter.
    let d = libm::fabs(p.real(0)) * p.per_unit / 1e6;
    let pitch = coarse_pitch(d, 68.0).ok_or(AlarmKind::SiemensCycle(CycleAlarm::ThreadPitchWrong))?;
    let row = DIN_76
        .iter()
        .find(|row| libm::fabs(row.0 - pitch) < 1e-9)
        .ok_or(AlarmKind::SiemensCycle(CycleAlarm::ThreadPitchWrong))?;
    let outside = form <= b'B';
    let (dg, g2) = match form {
        b'A' => (d - row.1, row.2),
        b'B' => (d - row.1, row.3),
        b'C' => (d + row.4, row.5),
        _ => (d + row.4, row.6),
    };
    if dg < 3.0 {
        return Err(AlarmKind::SiemensCycle(CycleAlarm::FinishedDiameterTooSmall));
    }
    let vari = p.int(3);
    let pos = position(vari, st)?;
    if (pos.x > 0) != outside {
        return Err(if vari == 0 {
            AlarmKind::SiemensCycle(CycleAlarm::WrongEdgePosition)
        } else {
            AlarmKind::SiemensCycle(CycleAlarm::UndercutPositionWrong)
        });
    }
    let shape = Shape { rf: d / 2.0, t: libm::fabs(d - dg) / 2.0, f: g2, flank: 30.0, r: row.7, t2: 0.0, relief: 0.0 };
    let spl = p.len(1);
    p.ok()?;
    start_undercut(&shape, spl, pos, cmd, st, ctx)
}

/// The undercut `s` in the corner of the face at `spl` (nm) and the finished
/// diameter, started from the cycle's start point.
fn start_undercut(
    s: &Shape,
    spl: i64,
    pos: Position,
    cmd: &Command,
    st: &mut State,
    ctx: &mut dyn Engine,
) -> Result<(), AlarmKind> {
    // A clearance angle below the flank's makes the flank flatter (line 10531).
    let clearance = ctx.cfg().tools.get(st.tool.offset_number).map_or(0, |r| r.clearance_udeg);
    let c = f64::from(clearance) / 1e6;
    let flank = if c > 0.0 && c < s.flank { c } else { s.flank };
    let run = s.t / libm::tan(flank.to_radians());
    let extra = run - s.t / libm::tan(s.flank.to_radians());
    let (x, z) = (pos.x as f64, pos.z as f64);
    let pt = |xr: f64, zd: f64| {
        Pt::new(interp_core::geom::round_i64(xr * 1e6), spl + interp_core::geom::round_i64(zd * 1e6))
    };
    // In (radius, distance from the face along the diameter) mm.
    let f = s.f + extra;
    let bottom = s.rf - x * s.t;
    let wall = -s.t2;
    let start = pt(s.rf + x * 2.0, z * f64::max(10.0, f + 1.0));
    let q0 = pt(s.rf, z * f);
    let q1 = pt(bottom, z * (f - run));
    let q2 = pt(bottom, z * (wall + s.r));
    let center = pt(bottom + x * s.r, z * (wall + s.r));
    let q3 = pt(bottom + x * s.r, z * wall);
    // The arc turns from along the bottom (towards the face) up the wall.
    let cw = x * z > 0.0;
    let mut path: heapless::Vec<Seg, 6> = heapless::Vec::new();
    let line = |a, b| Seg { kind: SegKind::Line, a, b };
    for seg in [line(start, q0), line(q0, q1), line(q1, q2), Seg { kind: SegKind::Arc { center, cw }, a: q2, b: q3 }] {
        let _ = path.push(seg);
    }
    if s.t2 > 0.0 {
        // Form F: the face relieved by t2, back to the face at the relief angle.
        let up = s.t2 / libm::tan(s.relief.to_radians());
        let _ = path.push(line(q3, pt(bottom + x * (s.r + up), 0.0)));
    }
    // The tool is on the open side: right of the path when it runs towards the face
    // with the tool above (outside, diameter towards +Z).
    let tool_left = x * z < 0.0;
    ctx.contour_pass(&path, tool_left, start, cmd, st)
}

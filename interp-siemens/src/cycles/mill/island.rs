//! CYCLE73 pocket milling with islands (seed 001 lines 6461-7392): the pocket's
//! edge (CYCLE74) and islands (CYCLE75), kept by the driver, are read by the
//! engine in the active plane and cleared, finished or drilled by the path of
//! [`mill_paths::island`].
//!
//! - `_VARI` units 1 clearing from solid (to `_FAL`/`_FALD`), 2 rest material
//!   (what the larger cutter of tool `_TN` left), 3 edge finishing, 4 floor
//!   finishing, 5 pre-drilling positions; tens the insertion 1 G1 straight down,
//!   2 helix (`_RAD` radius, `_DP1` per turn), 3 oscillating (`_RAD` degrees);
//!   hundreds the retract 0 to `_RTP`, 1 to RFP + SDIS; thousands the start point
//!   1 automatic, 2 `_PA`/`_PO`. Other digits are 61002, as is an edge finish
//!   that does not insert straight down (line 6623).
//! - `_TN` empty 61984, `_PNAME` empty 61988, `_BNAME` empty with units 5 61985
//!   (the 840D writes its path into these programs: here they are only names).
//! - D other than D1 61989 (line 6760), a radius ≤ 0 61905 (line 6257), `_MIDA`
//!   above 80 % of the cutter diameter 61982 (line 6808), rest material with a
//!   cutter not smaller than `_TN`'s 61918.
//! - The shared checks: plane 61005, D0 61000, levels 61101, feeds 61003,
//!   `_CDIR` 61109 (0/1 need the spindle's direction, 61102).

use super::{Radius, cutter, feed, levels, plane};
use crate::cycles::{Arg, ContourSource, Engine, Params};
use interp_core::MachineConfig;
use interp_core::alarm::{AlarmKind, CycleAlarm};
use interp_core::canon::SpindleDir;
use interp_core::command::Command;
use interp_core::modal::State;
use mill_paths::infeed::Levels;
use mill_paths::island::{IslandSpec, Job, Plunge};

/// CYCLE73: checks the call and starts its path on the contours CYCLE74 and
/// CYCLE75 transferred (`edge`: the driver's; 61900 without it).
pub(in crate::cycles) fn cycle73(
    p: &Params<'_, '_>,
    cmd: &Command,
    st: &mut State,
    ctx: &mut dyn Engine,
    edge: Option<ContourSource<'_>>,
) -> Result<(), AlarmKind> {
    let s = spec(p, st, ctx.cfg())?;
    p.ok()?;
    let edge = edge.ok_or(island(61900))?;
    ctx.mill_islands(&s, edge, cmd, st)
}

/// Whether a CYCLE73 call pre-drills (`_VARI` units 5): the driver runs the
/// modal drilling cycle at the insertion points ([`predrill`]).
pub fn predrills(args: &interp_core::lang::siemens::call::CallArgs) -> bool {
    let mut buf = [Arg::Empty; interp_core::lang::siemens::call::MAX_ARGS];
    matches!(args.args(&mut buf).first(), Some(Arg::Int(v)) if v % 10 == 5)
}

/// A pre-drilling CYCLE73 call checked: the clearing whose insertion points are
/// drilled (`mill_paths::island::start_points`), or the call's alarm.
pub fn predrill(args: &[Arg<'_>], st: &State, cfg: &MachineConfig) -> Result<IslandSpec, AlarmKind> {
    let p = Params::new(args, st);
    let mut s = spec(&p, st, cfg)?;
    p.ok()?;
    s.job = Job::Rough;
    Ok(s)
}

/// A CYCLE73 alarm.
fn island(code: u16) -> CycleAlarm {
    CycleAlarm::IslandPocket { code }
}

/// The call as the path needs it, or its alarm.
fn spec(p: &Params<'_, '_>, st: &State, cfg: &MachineConfig) -> Result<IslandSpec, CycleAlarm> {
    plane(st, cfg)?;
    let vari = p.int(0);
    let (unit, tens, hund, thou) = (vari % 10, vari / 10 % 10, vari / 100 % 10, vari / 1000);
    let digits_ok = (1..=5).contains(&unit) && (1..=3).contains(&tens) && hund <= 1 && (1..=2).contains(&thou);
    if !(0..=9999).contains(&vari) || !digits_ok || (unit == 3 && tens != 1) {
        return Err(CycleAlarm::MachiningTypeWrong);
    }
    let r = cutter(st, Radius::NotNegative)?;
    // D is an offset row, `t + (d − 1) × tool count` (read::tool_row): D1's rows
    // are the first `tool count`.
    if st.mill.d > cfg.tool_count {
        return Err(island(61989));
    }
    names(p, unit)?;
    // Pre-drilling lays out the clearing of the tool `_TN` (the drill is active).
    let r = if unit == 5 { tool_radius(p, cfg)? } else { r };
    if r <= 0 {
        return Err(CycleAlarm::CutterRadiusTooSmall);
    }
    let l = levels(p, st, [4, 5, 6, 7], Some(8))?;
    let mida = p.unsigned(10);
    if mida > 2 * r * 4 / 5 {
        return Err(island(61982));
    }
    let step = mill_paths::infeed::max_width(mida, r);
    let (mid, fal, fald) = (p.unsigned(9), p.unsigned(11), p.unsigned(12));
    let total = (l.bottom - l.start).abs();
    if fald >= total {
        return Err(CycleAlarm::FloorAllowanceTooLarge);
    }
    let ffp1 = feed(p, 13, st)?;
    let ffd = feed(p, 14, st)?;
    let cw = direction(p.int(15), st)?;
    let above_floor = l.bottom - l.dir * fald;
    let (job, fal, levels) = match unit {
        2 => (Job::Rest { prev_r: previous_radius(p, st, cfg)? }, fal, Levels::new(l.start, above_floor, mid)),
        3 => (Job::Edge, 0, Levels::new(l.start, l.bottom, mid)),
        // From DP + FALD + SDIS straight down to DP, the floor once (line 6632).
        4 => (Job::Floor, fal, Levels::new(above_floor - l.dir * p.unsigned(6), l.bottom, 0)),
        _ => (Job::Rough, fal, Levels::new(l.start, above_floor, mid)),
    };
    let start = (thou == 2).then(|| (p.len(16), p.len(17)));
    Ok(IslandSpec {
        job,
        r,
        fal,
        step,
        levels,
        rtp: l.rtp,
        safe: l.safe,
        sdis: p.unsigned(6),
        dir: l.dir,
        lift: hund as u8,
        plunge: plunge(p, tens)?,
        start,
        cw,
        feeds: [ffd, ffp1],
    })
}

/// `_TN`, `_PNAME` and (pre-drilling) `_BNAME` must be given: the 840D names the
/// tool and the programs it writes with them.
fn names(p: &Params<'_, '_>, unit: i64) -> Result<(), CycleAlarm> {
    let given = |i| p.text(i).iter().any(|c| !c.is_ascii_whitespace());
    if !given(3) {
        return Err(island(61984));
    }
    if !given(2) {
        return Err(island(61988));
    }
    if unit == 5 && !given(1) {
        return Err(island(61985));
    }
    Ok(())
}

/// G2 around the edge: `_CDIR` 2 G2, 3 G3, 0 climb / 1 conventional from the
/// spindle's direction (M3: climb G3, conventional G2, line 6855).
fn direction(cdir: i64, st: &State) -> Result<bool, CycleAlarm> {
    match cdir {
        2 => Ok(true),
        3 => Ok(false),
        d @ 0..=1 => match st.spindle.dir {
            SpindleDir::Cw => Ok(d == 1),
            SpindleDir::Ccw => Ok(d == 0),
            _ => Err(CycleAlarm::NoSpindleDirection),
        },
        _ => Err(CycleAlarm::CdirWrong),
    }
}

/// The insertion of `_VARI` tens: a helix needs `_RAD` > 0 (61909) and `_DP1` > 0
/// (61108), an oscillation an angle in 0 < `_RAD` < 90° (0: 61128, else 61108).
fn plunge(p: &Params<'_, '_>, tens: i64) -> Result<Plunge, CycleAlarm> {
    match tens {
        2 => {
            let (rad, pitch) = (p.unsigned(18), p.unsigned(19));
            if rad == 0 {
                return Err(island(61909));
            }
            if pitch == 0 {
                return Err(CycleAlarm::InsertionWrong);
            }
            Ok(Plunge::Helix { rad, pitch })
        }
        3 => {
            let deg = libm::fabs(p.real(18));
            if deg == 0.0 {
                return Err(CycleAlarm::InsertionAngleZero);
            }
            if deg >= 90.0 {
                return Err(CycleAlarm::InsertionWrong);
            }
            Ok(Plunge::Swing { tan: libm::tan(deg.to_radians()) })
        }
        _ => Ok(Plunge::Vertical),
    }
}

/// The radius of the cutter that cleared before (tool `_TN`, its D1: line
/// 6744), larger than this one's, or 61918.
fn previous_radius(p: &Params<'_, '_>, st: &State, cfg: &MachineConfig) -> Result<i64, CycleAlarm> {
    let prev = tool_radius(p, cfg)?;
    if prev <= st.tool.nose_radius {
        return Err(island(61918));
    }
    Ok(prev)
}

/// The radius of tool `_TN` (a tool number without tool management, line
/// 6738), its D1; a name that is no tool of the table is 61984.
fn tool_radius(p: &Params<'_, '_>, cfg: &MachineConfig) -> Result<i64, CycleAlarm> {
    let tn = p.text(3);
    let t = core::str::from_utf8(tn).ok().and_then(|s| s.trim().parse::<i64>().ok()).ok_or(island(61984))?;
    let row = crate::read::tool_row(cfg, t, 1).ok_or(island(61984))?;
    Ok(cfg.tools.get(row).map_or(0, |o| o.radius))
}

//! A machining centre's hole cycles, G73–G89 with G98/G99 (seed 004 @6390–@10300;
//! FANUC 0i-M where it is silent): the block's words and the cycle memory made
//! into a [`HoleSpec`] for the one hole generator, drilling along Z at positions
//! in XY whatever the plane (@7190).
//!
//! - R and Z: under G90 absolute levels; under G91 R is measured from the initial
//!   level and Z from the R level (FANUC; the seed does not say). Both are kept
//!   for the following holes, with Q, P and F, until G80 or G00–G03 (@10250).
//! - The initial level is where the tool was when the mode started; it is kept
//!   for the mode, so that after G99 holes (back to R) a G98 hole returns to it
//!   (@7537).
//! - A block in the mode drills only if it has X, Y, Z or R (@10120); K repeats
//!   the hole, moving by the G91 position words each time; K0 only stores data.
//! - The transformations in force (G16, G51.1, G51, G68 in the XY plane) move the
//!   hole positions and scale the levels; Q is not scaled (FANUC).

use super::hole::{HoleGen, HoleSpec, HoleWork};
use super::single::tap_lead;
use crate::alarm::AlarmKind;
use crate::axis::{Axis, Pos};
use crate::canon::{Plane, SpindleDir};
use crate::codes::GCode;
use crate::command::{Command, CycleArgs};
use crate::config::{MachineConfig, Param};
use crate::modal::mill::{narrow, on, xyz};
use crate::modal::{RigidTap, State};
use crate::moves::frame;

/// The block of a machining centre's hole cycle `code`: `None` when it drills
/// nothing (no X, Y, Z or R, or K0).
pub fn hole_block(
    code: GCode,
    cmd: &Command,
    st: &mut State,
    cfg: &MachineConfig,
) -> Result<Option<HoleGen>, AlarmKind> {
    let CycleArgs::Hole { r, dwell_ms, q, repeat } = cmd.cycle else { return Ok(None) };
    let f = st.mill.frame;
    if f.active & on::ROTATE != 0 && f.rot_plane != Plane::Xy {
        return Err(AlarmKind::RotationPlaneChange);
    }
    let here_work = super::emit::work_pos(st, cfg);
    let here = if f.active != 0 { f.prog() } else { xyz(&here_work) };
    let initial = match st.mill.initial {
        Some(z) => i64::from(z),
        None => {
            st.mill.initial = Some(narrow(here[2])?);
            here[2]
        }
    };
    let g91 = st.modal.incremental;
    let mem = &mut st.cycle.hole;
    if let Some(r) = r {
        mem.r = if g91 { initial.checked_add(r).ok_or(AlarmKind::Overflow)? } else { r };
        mem.r_set = true;
    }
    if let Some(q) = q {
        mem.q = q;
    }
    if let Some(p) = dwell_ms {
        mem.dwell_ms = p;
    }
    let missing = |letter| AlarmKind::MissingWord { letter, context: "hole cycle" };
    if let Some(w) = cmd.axes[Axis::Z.index()] {
        if !mem.r_set {
            return Err(missing(b'R'));
        }
        let bottom = if w.incremental { mem.r.checked_add(w.value).ok_or(AlarmKind::Overflow)? } else { w.value };
        mem.bottom = Some(bottom);
    }
    if !cmd.has_axes() && r.is_none() || repeat == Some(0) {
        return Ok(None);
    }
    let mem = *mem;
    if !mem.r_set {
        return Err(missing(b'R'));
    }
    let bottom = mem.bottom.ok_or(missing(b'Z'))?;
    let (position, step) = positions(cmd, st, here)?;
    let repeat = repeat.unwrap_or(1);
    let f = st.mill.frame;
    let level = |z: i64| if f.active != 0 { f.forward([here[0], here[1], z])[2] } else { z };
    let mut pos = here_work;
    let w = if f.active != 0 { f.forward([position[0], position[1], here[2]]) } else { position };
    (pos[Axis::X], pos[Axis::Y]) = (w[0], w[1]);
    let mut step_w = Pos::ZERO;
    let s = if f.active != 0 { f.vector(step) } else { step };
    (step_w[Axis::X], step_w[Axis::Y]) = (s[0], s[1]);
    let spec = HoleSpec {
        work: work(code, st, cfg, mem.q)?,
        axis: Axis::Z,
        plane: Plane::Xy,
        position: pos,
        step: step_w,
        initial: level(initial),
        r_level: level(mem.r),
        bottom: level(bottom),
        dwell_ms: if dwells(code) { mem.dwell_ms } else { 0 },
        stay_at_r: st.modal.return_to_r,
        repeat,
    };
    Ok(Some(HoleGen::new(spec)))
}

/// The programmed hole position (X, Y; Z where the tool is) and the K step: X/Y
/// absolute under G90, added under G91 (the step of each repetition); under G16
/// radius and angle.
fn positions(cmd: &Command, st: &mut State, here: [i64; 3]) -> Result<([i64; 3], [i64; 3]), AlarmKind> {
    let mut step = [0i64; 3];
    let mut position = here;
    if st.mill.frame.active & on::POLAR != 0 {
        let polar_words = [Axis::X, Axis::Y].iter().any(|a| cmd.axes[a.index()].is_some_and(|w| w.incremental));
        if polar_words && matches!(cmd.cycle, CycleArgs::Hole { repeat: Some(2..), .. }) {
            return Err(AlarmKind::NotSupportedYet { what: "K with incremental G16 radius or angle" });
        }
        let mut words = cmd.clone();
        words.axes[Axis::Z.index()] = None;
        let t = frame::programmed_target(&words, st)?;
        position[0] = t[0];
        position[1] = t[1];
        return Ok((position, step));
    }
    for (i, a) in [Axis::X, Axis::Y].into_iter().enumerate() {
        if let Some(w) = cmd.axes[a.index()] {
            if w.incremental {
                position[i] = position[i].checked_add(w.value).ok_or(AlarmKind::Overflow)?;
                step[i] = w.value;
            } else {
                position[i] = w.value;
            }
        }
    }
    Ok((position, step))
}

/// The cycles that dwell P at the bottom: G82, G89, G88, G76, G87 and tapping
/// (FANUC 0i-M's formats; G81, G73, G83, G85, G86 keep P for the others).
fn dwells(code: GCode) -> bool {
    use GCode::*;
    matches!(code, DrillDwell | BoreDwell | BoreManual | FineBore | BackBore | Tap | LeftTap)
}

/// What is done at the hole.
fn work(code: GCode, st: &mut State, cfg: &MachineConfig, q: i64) -> Result<HoleWork, AlarmKind> {
    use GCode::*;
    let d = cfg.params.get(Param::PeckDrillClearance);
    let restart = if st.spindle.dir == SpindleDir::Stop { SpindleDir::Cw } else { st.spindle.dir };
    Ok(match code {
        Drill | DrillDwell => HoleWork::Drill { q: 0, deep: false, d },
        HighSpeedPeck | PeckDrill if q <= 0 => return Err(AlarmKind::PeckDepthMissing),
        HighSpeedPeck => HoleWork::Drill { q, deep: false, d },
        PeckDrill => HoleWork::Drill { q, deep: true, d },
        Bore | BoreDwell => HoleWork::Bore,
        BoreSpindleStop => HoleWork::BoreStop { restart },
        BoreManual => HoleWork::BoreManual { restart },
        FineBore => HoleWork::FineBore { shift: shift(cfg, q)?, restart },
        BackBore => HoleWork::BackBore { shift: shift(cfg, q)?, restart },
        _ => tap(code == LeftTap, st, cfg, q)?,
    })
}

/// G76/G87: Q along the direction of parameter 5149, in machine axis directions.
fn shift(cfg: &MachineConfig, q: i64) -> Result<Pos, AlarmKind> {
    let mut p = Pos::ZERO;
    match cfg.params.get(Param::BoreShiftDirection) {
        1 => p[Axis::X] = q,
        2 => p[Axis::X] = -q,
        3 => p[Axis::Y] = q,
        4 => p[Axis::Y] = -q,
        _ => return Err(AlarmKind::CycleValueIllegal { what: "parameter 5149 must be 1-4" }),
    }
    Ok(p)
}

/// G84 (M03 in, M04 out) or G74 (`left`: M04 in, M03 out): rigid after M29 —
/// the spindle then stays in position control (stopped) until G80 —, else
/// floating, reversing at the bottom and turning forward again at R (@8119).
fn tap(left: bool, st: &mut State, cfg: &MachineConfig, q: i64) -> Result<HoleWork, AlarmKind> {
    let dir = if left { SpindleDir::Ccw } else { SpindleDir::Cw };
    match st.cycle.rigid {
        RigidTap::Pending { rpm, before } | RigidTap::Active { rpm, before } => {
            st.cycle.rigid = RigidTap::Active { rpm, before };
            Ok(HoleWork::RigidTap {
                lead: tap_lead(st, rpm)?,
                q,
                deep: cfg.params.flag(Param::DeepPeckTapping),
                d: cfg.params.get(Param::PeckTapClearance),
                dir,
                // Seed 004 @8700: a dwell is made at the bottom and back at R.
                dwell_r_ms: st.cycle.hole.dwell_ms,
                restore: SpindleDir::Stop,
            })
        }
        RigidTap::Off => Ok(HoleWork::FloatTap {
            lead: tap_lead(st, st.spindle.rpm)?,
            dir,
            turning: st.spindle.dir == dir,
            after: dir,
            stop_at_bottom: false,
        }),
    }
}

//! Coordinate systems: G50 coordinate setting, G52 local frame, G53 machine
//! coordinates, G28/G30 reference returns (2.11, 2.12).

use crate::alarm::AlarmKind;
use crate::axis::Axis;
use crate::canon::Endpoint;
use crate::command::Command;
use crate::command::cycle::is_hole;
use crate::config::{MachineConfig, Param};
use crate::env::Environment;
use crate::modal::State;
use crate::modal::mill::{FRAME_AXES, narrow};
use crate::moves::motion::{endpoint, rapid_to, target};
use crate::stage::Staged;

/// G50 X/Z (U/W): the current point gets the given work coordinates by shifting
/// all six work frames alike (2.12.2 notes 3–4); the local frame of an axis named
/// here is cancelled (2.12.3 note 3). The axes do not move.
pub(super) fn set_coordinates(cmd: &Command, st: &mut State, cfg: &MachineConfig) -> Result<(), AlarmKind> {
    if !cmd.has_axes() {
        return Ok(()); // G50 S only: the clamp was taken with the spindle words.
    }
    if cfg.params.flag(Param::DisableCoordinateSetting) {
        return Err(AlarmKind::CoordinateSettingDisabled);
    }
    let now = st.work_pos(cfg);
    let wanted = target(cmd, st, cfg)?;
    for a in Axis::ALL {
        if cmd.axes[a.index()].is_some() {
            st.frames.shift[a] = st.frames.shift[a]
                .checked_add(st.frames.local[a])
                .and_then(|v| v.checked_add(now[a]))
                .and_then(|v| v.checked_sub(wanted[a]))
                .ok_or(AlarmKind::Overflow)?;
            st.frames.local[a] = 0;
        }
    }
    st.sum_own_offsets();
    Ok(())
}

/// G52: the local frame's origin in work coordinates. U/W mean the same as X/Z
/// here (the manual cancels with either `G52 X0 Z0` or `G52 U0 W0`).
/// On a mill G52 takes absolute words only: they are the local origin's position
/// in the work frame (seed 004 @2362), and under G91 there is none to give (4015,
/// as G53).
pub(super) fn local_frame(cmd: &Command, st: &mut State, cfg: &MachineConfig) -> Result<(), AlarmKind> {
    if crate::is_mill(cfg) && cmd.axes.iter().flatten().any(|w| w.incremental) {
        return Err(AlarmKind::LocalFrameIncremental);
    }
    for a in Axis::ALL {
        if let Some(w) = cmd.axes[a.index()] {
            st.frames.local[a] = w.value;
        }
    }
    st.sum_own_offsets();
    Ok(())
}

/// G53: rapid to machine coordinates, tool offset not applied, one block only.
pub(super) fn machine_move(
    cmd: &Command,
    st: &mut State,
    cfg: &MachineConfig,
    out: &mut Staged<'_>,
) -> Result<(), AlarmKind> {
    let mut machine = st.pos;
    for a in Axis::ALL {
        if let Some(w) = cmd.axes[a.index()] {
            machine[a] = w.value;
        }
    }
    let to = Endpoint { machine, work: machine - st.work_to_machine(cfg) };
    rapid_to(to, st, cfg, out, cfg.rapid_independent)
}

/// G28 / G30 Pn: rapid through the intermediate point to reference position n,
/// each axis at its own rapid rate (2.11.1 note 1, 2.11.2 note 4); only the axes
/// named in the block move.
pub(super) fn reference_return(
    cmd: &Command,
    st: &mut State,
    cfg: &MachineConfig,
    env: &dyn Environment,
    out: &mut Staged<'_>,
) -> Result<(), AlarmKind> {
    for a in Axis::ALL {
        if cmd.axes[a.index()].is_some() && !env.referenced(a) {
            return Err(AlarmKind::ReferenceNotEstablished { letter: a.letter() });
        }
    }
    let mill = crate::is_mill(cfg);
    if mill && is_hole(st.modal.drilling) {
        return Err(AlarmKind::ReferenceInCycle);
    }
    let middle = endpoint(target(cmd, st, cfg)?, st, cfg)?;
    if mill {
        // G29 comes back through this point: each axis named keeps it, in work
        // coordinates (seed 004 @5400: "系统对中间点有记憶功能").
        for (i, a) in FRAME_AXES.into_iter().enumerate() {
            if cmd.axes[a.index()].is_some() {
                st.mill.g28[i] = narrow(middle.work[a])?;
                st.mill.g28_axes.insert(a);
            }
        }
    }
    let reference = cfg.reference[usize::from(cmd.reference - 1)];
    let mut machine = middle.machine;
    for a in Axis::ALL {
        if cmd.axes[a.index()].is_some() {
            machine[a] = reference[a];
        }
    }
    let home = Endpoint { machine, work: machine - st.work_to_machine(cfg) };
    rapid_to(middle, st, cfg, out, true)?;
    rapid_to(home, st, cfg, out, true)
}

/// G29 (a machining centre's, seed 004 @5826): each axis named rapids to the
/// intermediate point G28 or G30 gave it, then to the point commanded — in work
/// coordinates under G90, as a displacement from the intermediate point under
/// G91. The axes move independently, as G28's do.
pub(super) fn return_from_reference(
    cmd: &Command,
    st: &mut State,
    cfg: &MachineConfig,
    env: &dyn Environment,
    out: &mut Staged<'_>,
) -> Result<(), AlarmKind> {
    if is_hole(st.modal.drilling) {
        return Err(AlarmKind::ReferenceInCycle);
    }
    let here = st.work_pos(cfg);
    let (mut middle, mut end) = (here, here);
    for a in Axis::ALL {
        let Some(w) = cmd.axes[a.index()] else { continue };
        if !env.referenced(a) {
            return Err(AlarmKind::ReferenceNotEstablished { letter: a.letter() });
        }
        let Some(i) = FRAME_AXES.iter().position(|x| *x == a).filter(|_| st.mill.g28_axes.contains(a)) else {
            return Err(AlarmKind::NoIntermediatePoint { letter: a.letter() });
        };
        middle[a] = i64::from(st.mill.g28[i]);
        end[a] = if w.incremental { middle[a].checked_add(w.value).ok_or(AlarmKind::Overflow)? } else { w.value };
    }
    let (middle, end) = (endpoint(middle, st, cfg)?, endpoint(end, st, cfg)?);
    rapid_to(middle, st, cfg, out, true)?;
    rapid_to(end, st, cfg, out, true)
}

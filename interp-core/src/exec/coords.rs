//! Coordinate systems: G50 coordinate setting, G52 local frame, G53 machine
//! coordinates, G28/G30 reference returns (2.11, 2.12).

use crate::alarm::AlarmKind;
use crate::axis::Axis;
use crate::canon::Endpoint;
use crate::command::Command;
use crate::config::{MachineConfig, Param};
use crate::env::Environment;
use crate::modal::State;
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
pub(super) fn local_frame(cmd: &Command, st: &mut State) {
    for a in Axis::ALL {
        if let Some(w) = cmd.axes[a.index()] {
            st.frames.local[a] = w.value;
        }
    }
    st.sum_own_offsets();
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
    let middle = endpoint(target(cmd, st, cfg)?, st, cfg)?;
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

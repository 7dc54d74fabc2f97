//! `$H` homing with home switches (`$22=1`): a sequence per axis, the axis that
//! takes the tool away from the work first — a lathe X then Z, a mill Z then X
//! then Y (as grbl homes a mill; [`order`]): seek toward the home switch at `$25` (toward plus unless `$23` has the axis's bit),
//! brake when the switch input is seen, redefine the axis so that the point where
//! the switch tripped is the reference position, then move to `$27` short of that
//! point at `$24`. The moves go straight to the motion port; the controller takes
//! the position when the sequence says it is done.

use interp_core::MachineConfig;
use interp_core::axis::{Axis, Pos};
use interp_core::config::MachineKind;

use crate::jog::feed_move;
use crate::port::{MotionPort, MotionStatus};
use crate::settings::Settings;

/// Where a homing sequence is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Homing {
    /// Index into [`order`] of the axis being homed.
    axis: usize,
    phase: Phase,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Phase {
    /// Waiting for the motion core to be at rest.
    Start,
    /// Moving toward the switch.
    Seek,
    /// The switch tripped at this position; braking.
    Braking { trip: Pos },
    /// Moving off the switch.
    PullOff,
}

/// What one step of the sequence came to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Homed {
    /// Still homing.
    Busy,
    /// No home switch within 1.5 × the travel.
    Failed,
    /// Every axis homed; the axes stand at this machine position.
    Done(Pos),
}

/// The axes `$H` homes, in order: the one that clears the tool from the work
/// first (a lathe's cross slide X, a mill's quill or head Z).
pub(crate) fn order(kind: MachineKind) -> &'static [Axis] {
    match kind {
        MachineKind::Lathe => &[Axis::X, Axis::Z],
        MachineKind::Mill => &[Axis::Z, Axis::X, Axis::Y],
    }
}

/// +1 or -1: the direction toward axis `a`'s home switch (`$23` bit 0 X, 1 Y, 2 Z).
fn home_dir(a: Axis, s: &Settings) -> i64 {
    if s.homing_dir_mask & (1 << a.index()) != 0 { -1 } else { 1 }
}

impl Homing {
    /// A sequence that starts with X once the motion core is at rest.
    pub const fn new() -> Self {
        Homing { axis: 0, phase: Phase::Start }
    }

    /// One poll: `st` the motion core's status, `home` the home switch inputs
    /// (X, Y, Z).
    pub fn step<M: MotionPort + ?Sized>(
        &mut self,
        st: &MotionStatus,
        home: [bool; 3],
        cfg: &MachineConfig,
        s: &Settings,
        port: &mut M,
    ) -> Homed {
        let axes = order(cfg.kind);
        let Some(&a) = axes.get(self.axis) else { return Homed::Failed };
        let switch = home.get(a.index()).copied().unwrap_or(false);
        match self.phase {
            Phase::Start if st.idle => {
                self.phase = Phase::Seek;
                seek(a, st.position, cfg, s, port);
            }
            Phase::Seek if switch => {
                port.reset();
                self.phase = Phase::Braking { trip: st.position };
            }
            Phase::Seek if st.idle => return Homed::Failed,
            Phase::Braking { trip } if st.idle => {
                let reference = cfg.reference[0][a];
                let mut pos = st.position;
                pos[a] = reference + (st.position[a] - trip[a]);
                port.set_position(pos);
                // Pull off from the switch point (the axis braked beyond it).
                let mut to = pos;
                to[a] = reference - i64::from(s.homing_pulloff_um) * 1_000 * home_dir(a, s);
                let feed = i64::from(s.homing_feed) * 1_000_000;
                let _ = port.push(feed_move(to, to, feed, cfg.spindle.max_rpm));
                self.phase = Phase::PullOff;
            }
            Phase::PullOff if st.idle => {
                if self.axis + 1 < axes.len() {
                    *self = Homing { axis: self.axis + 1, phase: Phase::Start };
                } else {
                    return Homed::Done(st.position);
                }
            }
            _ => {}
        }
        Homed::Busy
    }
}

/// Starts the seek of axis `a` from `from` toward its switch.
fn seek<M: MotionPort + ?Sized>(a: Axis, from: Pos, cfg: &MachineConfig, s: &Settings, port: &mut M) {
    let ax = cfg.axis(a);
    let travel = (ax.max - ax.min).saturating_mul(3) / 2;
    let mut to = from;
    to[a] = from[a].saturating_add(travel * home_dir(a, s));
    let feed = i64::from(s.homing_seek) * 1_000_000;
    let _ = port.push(feed_move(to, to, feed, cfg.spindle.max_rpm));
}

//! `$H` homing with home switches (`$22=1`): a sequence per axis, X first: seek
//! toward the home switch at `$25` (toward plus unless `$23` has the axis's bit),
//! brake when the switch input is seen, redefine the axis so that the point where
//! the switch tripped is the reference position, then move to `$27` short of that
//! point at `$24`. The moves go straight to the motion port; the controller takes
//! the position when the sequence says it is done.

use interp_core::MachineConfig;
use interp_core::axis::{Axis, Pos};

use crate::jog::feed_move;
use crate::port::{MotionPort, MotionStatus};
use crate::settings::Settings;

/// Where a homing sequence is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Homing {
    /// 0: X, 1: Z.
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

const AXES: [Axis; 2] = [Axis::X, Axis::Z];

/// +1 or -1: the direction toward axis `i`'s home switch.
fn home_dir(i: usize, s: &Settings) -> i64 {
    let bit = AXES[i].index();
    if s.homing_dir_mask & (1 << bit) != 0 { -1 } else { 1 }
}

impl Homing {
    /// A sequence that starts with X once the motion core is at rest.
    pub const fn new() -> Self {
        Homing { axis: 0, phase: Phase::Start }
    }

    /// One poll: `st` the motion core's status, `home` the home switch inputs
    /// (X, Z).
    pub fn step<M: MotionPort + ?Sized>(
        &mut self,
        st: &MotionStatus,
        home: [bool; 2],
        cfg: &MachineConfig,
        s: &Settings,
        port: &mut M,
    ) -> Homed {
        let switch = home[self.axis];
        match self.phase {
            Phase::Start if st.idle => {
                self.phase = Phase::Seek;
                seek(self.axis, st.position, cfg, s, port);
            }
            Phase::Seek if switch => {
                port.reset();
                self.phase = Phase::Braking { trip: st.position };
            }
            Phase::Seek if st.idle => return Homed::Failed,
            Phase::Braking { trip } if st.idle => {
                let a = AXES[self.axis];
                let reference = cfg.reference[0][a];
                let mut pos = st.position;
                pos[a] = reference + (st.position[a] - trip[a]);
                port.set_position(pos);
                // Pull off from the switch point (the axis braked beyond it).
                let mut to = pos;
                to[a] = reference - i64::from(s.homing_pulloff_um) * 1_000 * home_dir(self.axis, s);
                let feed = i64::from(s.homing_feed) * 1_000_000;
                let _ = port.push(feed_move(to, to, feed, cfg.spindle.max_rpm));
                self.phase = Phase::PullOff;
            }
            Phase::PullOff if st.idle => {
                if self.axis + 1 < AXES.len() {
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

/// Starts the seek of axis `i` from `from` toward its switch.
fn seek<M: MotionPort + ?Sized>(i: usize, from: Pos, cfg: &MachineConfig, s: &Settings, port: &mut M) {
    let a = AXES[i];
    let ax = cfg.axis(a);
    let travel = (ax.max - ax.min).saturating_mul(3) / 2;
    let mut to = from;
    to[a] = from[a].saturating_add(travel * home_dir(i, s));
    let feed = i64::from(s.homing_seek) * 1_000_000;
    let _ = port.push(feed_move(to, to, feed, cfg.spindle.max_rpm));
}

//! The controller's only way to the motion core: [`MotionPort`].
//!
//! The controller does not own the motion core. On the board the core lives in the
//! interpolation timer's interrupt and the controller runs in a lower-priority
//! task; the firmware implements this trait on a handle that takes **one short
//! critical section per call** (every method here is O(1) or bounded by the
//! planner's push). On the host the virtual board and the tests own a
//! [`MotionCore`] directly: it implements the trait as is.

use interp_core::axis::Pos;
use interp_core::canon::{Canon, CanonSink, Full};
use interp_core::{Alarm, AlarmKind, MachineConfig};
use motion_core::motion::{Event, MotionCore, State};

/// A snapshot of the motion core for status reports and job control.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MotionStatus {
    /// Where the core is.
    pub state: State,
    /// Machine position of the axes (steps issued), nm, X radius.
    pub position: Pos,
    /// Machine minus work coordinates of the block running or last run.
    pub work_offset: Pos,
    /// Path speed now, nm/min.
    pub feed: i64,
    /// Measured spindle speed, rev/min (signed: negative counting down).
    pub rpm: i32,
    /// Source line of the block running or last run.
    pub line: u32,
    /// Entries queued in the look-ahead planner.
    pub queued: usize,
    /// Capacity of the planner queue.
    pub capacity: usize,
    /// The motion alarm in force.
    pub alarm: Option<Alarm>,
    /// Nothing queued, nothing moving, every step issued.
    pub idle: bool,
    /// Times the queue ran empty while a program streamed.
    pub starvations: u32,
}

/// What the controller asks of the motion core (see the module doc for the
/// interrupt-safety contract).
pub trait MotionPort {
    /// Queues a canonical action; [`Full`] is back-pressure (offer it again later).
    fn push(&mut self, c: Canon) -> Result<(), Full>;
    /// [`MotionPort::push`] of an action the caller keeps: the motion core reads it
    /// where it is instead of taking a copy (an arc is 176 bytes).
    #[inline]
    fn push_ref(&mut self, c: &Canon) -> Result<(), Full> {
        self.push(*c)
    }
    /// Feed hold: brake on the path.
    fn feed_hold(&mut self);
    /// Cycle start: resume after feed hold or M00/M01.
    fn cycle_start(&mut self);
    /// Reset: brake, stop the spindle, drop the queue, clear a motion alarm.
    fn reset(&mut self);
    /// Emergency stop: as reset, with the e-stop alarm.
    fn emergency_stop(&mut self);
    /// Feed override 0–200 %.
    fn set_feed_override(&mut self, pct: u16);
    /// Rapid override 0–100 %.
    fn set_rapid_override(&mut self, pct: u16);
    /// Spindle override 50–200 %.
    fn set_spindle_override(&mut self, pct: u16);
    /// Declares the axes to be at machine position `pos` without moving (homing);
    /// false if the core is not at rest.
    fn set_position(&mut self, pos: Pos) -> bool;
    /// Rebuilds the core for a changed machine description (settings `$100` …),
    /// keeping the position; only at rest. The core's complaint if `cfg` is unusable.
    fn reconfigure(&mut self, cfg: &MachineConfig) -> Result<(), AlarmKind>;
    /// The next event (spindle, tool, aux, stop, end, alarm …).
    fn pop_event(&mut self) -> Option<Event>;
    /// A status snapshot.
    fn status(&self) -> MotionStatus;
}

impl<const N: usize> MotionPort for MotionCore<N> {
    fn push(&mut self, c: Canon) -> Result<(), Full> {
        CanonSink::push(self, c)
    }

    fn push_ref(&mut self, c: &Canon) -> Result<(), Full> {
        CanonSink::push_ref(self, c)
    }

    fn feed_hold(&mut self) {
        MotionCore::feed_hold(self);
    }

    fn cycle_start(&mut self) {
        MotionCore::cycle_start(self);
    }

    fn reset(&mut self) {
        MotionCore::reset(self);
    }

    fn emergency_stop(&mut self) {
        MotionCore::emergency_stop(self);
    }

    fn set_feed_override(&mut self, pct: u16) {
        MotionCore::set_feed_override(self, pct);
    }

    fn set_rapid_override(&mut self, pct: u16) {
        MotionCore::set_rapid_override(self, pct);
    }

    fn set_spindle_override(&mut self, pct: u16) {
        MotionCore::set_spindle_override(self, pct);
    }

    fn set_position(&mut self, pos: Pos) -> bool {
        MotionCore::set_position(self, pos)
    }

    fn reconfigure(&mut self, cfg: &MachineConfig) -> Result<(), AlarmKind> {
        if !self.is_idle() {
            return Err(AlarmKind::MotionConfigInvalid { what: "the machine is moving" });
        }
        self.rebuild(cfg)
    }

    fn pop_event(&mut self) -> Option<Event> {
        MotionCore::pop_event(self)
    }

    fn status(&self) -> MotionStatus {
        let rpm = self.spindle().measured_rpm();
        MotionStatus {
            state: self.state(),
            position: self.position(),
            work_offset: self.work_offset(),
            feed: self.path_speed(),
            rpm: if rpm.is_finite() { libm::roundf(rpm) as i32 } else { 0 },
            line: self.line(),
            queued: self.queued(),
            capacity: N,
            alarm: self.alarm(),
            idle: self.is_idle(),
            starvations: self.stats().starvations,
        }
    }
}

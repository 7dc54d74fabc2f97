//! The board's side of the controller (`controller` crate, docs/PROTOCOL.md): the
//! controller type the firmware runs, [`controller::MotionPort`] on the motion
//! handle (one short critical section per call), the debounced switches as the
//! controller's [`controller::Inputs`], and the spindle drive following the motion
//! core. `main.rs` drives it like the host's virtual board (`sim/src/board.rs`):
//! `receive` as bytes arrive, `poll` every millisecond, `transmit` when there is
//! output.

use core::mem::MaybeUninit;

use controller::{Mode, MotionStatus};
use interp_core::axis::Pos;
use interp_core::canon::{Canon, Full, SpindleDir};
use interp_core::{AlarmKind, MachineConfig};
use motion_core::motion::Event;
use motion_driver::io::Switch;

use crate::io::{InputLevels, Outputs, rotation};
use crate::motion::MotionPort;

/// Stream window, bytes (G70–G73 shapes, WHILE loops and GOTO targets must lie in
/// it while a program streams).
#[cfg(feature = "f405")]
pub const WINDOW: usize = 4096;
/// Program memory text, bytes (programs uploaded with `%`/`$TAPE`, M98 subprograms).
#[cfg(feature = "f405")]
pub const TEXT: usize = 16384;
/// Programs in memory.
#[cfg(feature = "f405")]
pub const PROGRAMS: usize = 32;
/// Indexed sequence numbers in program memory.
#[cfg(feature = "f405")]
pub const SEQUENCES: usize = 512;

/// Stream window, bytes: as on the F405, so a program streams the same way (its
/// G70–G73 shapes, loops and jump targets must lie in the window).
#[cfg(feature = "f446")]
pub const WINDOW: usize = 4096;
/// Program memory text, bytes: the F446RE has no CCM, so the controller shares the
/// 128 KB SRAM with the other statics and the stack (a G71 and boot take ~28-35 KB of
/// it), and program memory is half the F405's.
#[cfg(feature = "f446")]
pub const TEXT: usize = 8192;
/// Programs in memory.
#[cfg(feature = "f446")]
pub const PROGRAMS: usize = 16;
/// Indexed sequence numbers in program memory.
#[cfg(feature = "f446")]
pub const SEQUENCES: usize = 256;

/// The controller the firmware runs. `controller::Board` (8 KB window, 48 KB program
/// memory, 113 KB in all) does not fit beside the motion core in the 128 KB SRAM
/// (static RAM budget 96 KB): the same controller with a smaller window and program
/// memory (see README "Firmware sizes").
pub type Ctl = controller::Controller<WINDOW, TEXT, PROGRAMS, SEQUENCES>;

/// Builds the controller in `slot` (a static). Out of line, with `slot` a unique
/// reference, so the compiler builds it in place instead of on the stack and
/// copying it (the stack has no room for a second copy).
#[inline(never)]
pub fn build(slot: &'static mut MaybeUninit<Ctl>, cfg: MachineConfig, pos: Pos) -> &'static mut Ctl {
    let ctl = Ctl::new_in(slot, cfg, pos);
    // SINUMERIK mode: its front end plugged in (without the feature G290 and
    // `$310=1` raise alarm 4007 and none of interp-siemens is linked).
    #[cfg(feature = "siemens")]
    ctl.interpreter_mut().plug(&interp_siemens::SINUMERIK);
    ctl
}

/// The motion core behind the board's handle: every call is one critical section
/// masking the period and encoder interrupts (never the step interrupt), doing what
/// `impl MotionPort for MotionCore<N>` (controller/src/port.rs) does.
impl controller::MotionPort for MotionPort {
    fn push(&mut self, c: Canon) -> Result<(), Full> {
        self.lock(|m| motion_driver::board::push(&mut m.core, &c)).unwrap_or(Err(Full))
    }

    fn push_ref(&mut self, c: &Canon) -> Result<(), Full> {
        self.lock(|m| motion_driver::board::push(&mut m.core, c)).unwrap_or(Err(Full))
    }

    fn feed_hold(&mut self) {
        self.lock(|m| m.core.feed_hold());
    }

    fn cycle_start(&mut self) {
        self.lock(|m| m.core.cycle_start());
    }

    fn reset(&mut self) {
        self.lock(|m| m.core.reset());
    }

    fn emergency_stop(&mut self) {
        self.lock(|m| m.core.emergency_stop());
    }

    fn set_feed_override(&mut self, pct: u16) {
        self.lock(|m| m.core.set_feed_override(pct));
    }

    fn set_rapid_override(&mut self, pct: u16) {
        self.lock(|m| m.core.set_rapid_override(pct));
    }

    /// As on the host: the motion core has no spindle override yet.
    fn set_spindle_override(&mut self, pct: u16) {
        self.lock(|m| controller::MotionPort::set_spindle_override(&mut m.core, pct));
    }

    fn set_position(&mut self, pos: Pos) -> bool {
        self.lock(|m| m.core.set_position(pos)).unwrap_or(false)
    }

    /// Rebuilds the core for `cfg` keeping the position, only at rest, as the host's
    /// `MotionCore` does. The step timings the player was built with are the
    /// drives' pulse timings, which no setting changes.
    fn reconfigure(&mut self, cfg: &MachineConfig) -> Result<(), AlarmKind> {
        self.lock(|m| {
            if !m.core.is_idle() {
                return Err(AlarmKind::MotionConfigInvalid { what: "the machine is moving" });
            }
            // `$311`: the third step channel follows the machine kind (C on a
            // lathe, Y on a mill), once its last edges have been played.
            let third = crate::motion::axes(cfg.kind)[crate::motion::THIRD_CHANNEL].index();
            if !m.engine.can_set_core_axis(crate::motion::THIRD_CHANNEL, third) {
                return Err(AlarmKind::MotionConfigInvalid { what: "the machine is moving" });
            }
            // In place: no second ~21 KB core on the stack.
            m.core.rebuild(cfg)?;
            m.engine.set_core_axis(crate::motion::THIRD_CHANNEL, third);
            Ok(())
        })
        .unwrap_or(Err(AlarmKind::MotionConfigInvalid { what: "motion core not started" }))
    }

    fn pop_event(&mut self) -> Option<Event> {
        self.lock(|m| m.core.pop_event()).flatten()
    }

    fn status(&self) -> MotionStatus {
        self.peek(|m| controller::MotionPort::status(&m.core)).unwrap_or(MotionStatus {
            state: motion_core::motion::State::Stopped,
            position: Pos::default(),
            work_offset: Pos::default(),
            feed: 0,
            rpm: 0,
            line: 0,
            queued: 0,
            capacity: 0,
            alarm: None,
            idle: true,
            starvations: 0,
        })
    }
}

/// The debounced switches as the controller reads them. The board has no door
/// switch and no user inputs (M91/M92 see 0).
pub fn inputs(levels: InputLevels) -> controller::Inputs {
    controller::Inputs {
        estop: levels.active(Switch::EStop),
        limit_x: levels.active(Switch::XLimit),
        limit_y: levels.active(Switch::YLimit),
        limit_z: levels.active(Switch::ZLimit),
        home_x: levels.active(Switch::XHome),
        home_y: levels.active(Switch::YHome),
        home_z: levels.active(Switch::ZHome),
        feed_hold: levels.active(Switch::FeedHold),
        cycle_start: levels.active(Switch::CycleStart),
        door: false,
        tool_change_done: cfg!(feature = "mill") && levels.active(Switch::ToolChangeDone),
        user: 0,
    }
}

/// The spindle drive follows the motion core's commanded direction and speed
/// (spindle commands in stream order, G96 speed changes along the cut); applied
/// when it changes.
pub struct SpindleFollower {
    last: Option<(SpindleDir, u32)>,
}

impl SpindleFollower {
    /// Nothing applied yet (the drive starts stopped).
    pub const fn new() -> Self {
        SpindleFollower { last: None }
    }

    /// Sets the drive to the core's output if that changed.
    pub fn follow(&mut self, port: &MotionPort, outputs: &mut Outputs) {
        let Some(now) = port.peek(|m| m.core.spindle_output()) else { return };
        if self.last != Some(now) {
            hal::SpindleDrive::set_speed(outputs, rotation(now.0), now.1);
            self.last = Some(now);
        }
    }

    /// The drive was stopped behind the core's back (e-stop): apply again.
    pub fn forget(&mut self) {
        self.last = None;
    }
}

impl Default for SpindleFollower {
    fn default() -> Self {
        Self::new()
    }
}

/// Whether the machine is at rest with nothing to do: the controller Idle and the
/// motion core idle (when the flash may be written).
pub fn at_rest(ctl: &Ctl, port: &MotionPort) -> bool {
    ctl.mode(port) == Mode::Idle && controller::MotionPort::status(port).idle
}

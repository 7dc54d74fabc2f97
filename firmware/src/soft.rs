//! The QEMU build's motion (feature `qemu`): QEMU models neither the timers'
//! compares nor GPIO, so the control task does the motion interrupts' work on a
//! software time base (microseconds of embassy time) once a millisecond: every
//! period due is computed, its edges are played at once (counted, no pins), and a
//! simulated spindle encoder turns at the commanded speed — a count reaching one of
//! the compare values the engine gives goes to the motion core, as the encoder
//! compare interrupt hands it over on the board, and an index pulse is latched every
//! revolution. So threads (G32, G76, G92) run in QEMU too.

use interp_core::canon::SpindleDir;
use motion_driver::board;
use motion_driver::encoder::Window;
use motion_driver::engine::Sample;

use crate::motion::{self, MotionPort};

/// Periods computed per call at most (catching up after the host stalled QEMU).
const MAX_PERIODS: usize = 16;
/// Edges played per call at most.
const MAX_EDGES: usize = 1_024;
/// Microseconds per minute.
const US_PER_MIN: u64 = 60_000_000;

/// The software time base's state: the simulated encoder.
pub struct SoftMotion {
    /// Encoder counts per revolution.
    cpr: u32,
    /// Raw encoder count (wraps like TIM5's 32-bit counter).
    raw: u32,
    /// Count phase: counts × µs/min not yet made into whole counts.
    phase: u64,
    /// Time (µs) the encoder was advanced to.
    at: u32,
    /// The compare values the engine gave last (TIM5's channels 3 and 4 on the board).
    window: Window,
}

impl SoftMotion {
    /// The encoder stands at count 0 at time `now` (µs).
    pub fn new(cpr: u32, now: u32) -> Self {
        SoftMotion { cpr: cpr.max(1), raw: 0, phase: 0, at: now, window: Window::OFF }
    }

    /// Runs the motion work due at `now` (µs of embassy time).
    pub fn run(&mut self, port: &mut MotionPort, now: u32) {
        for _ in 0..MAX_PERIODS {
            let start = port.peek(|m| m.engine.base_ticks()).unwrap_or(now);
            if (now.wrapping_sub(start) as i32) < 0 {
                break;
            }
            // The spindle turns up to the period's start, then the period is computed.
            self.turn(port, start);
            let sample = Sample { now: start, raw_count: self.raw, index: motion::index_latch(), estop: false };
            port.lock(|m| board::period(&mut m.engine, &mut m.core, sample));
            self.window = self.arm(port, start);
        }
        // The encoder never runs ahead of the periods computed: after a stall its
        // counts and the core's time catch up together.
        // SAFETY: without a step interrupt, this task is the player's only user.
        let _ = unsafe {
            motion::with_player(|p| {
                for _ in 0..MAX_EDGES {
                    match board::play(p, now, false).next {
                        Some(n) if now.wrapping_sub(n) as i32 >= 0 => {}
                        _ => break,
                    }
                }
            })
        };
    }

    /// The engine's compare values, with the counts already at or past one handed
    /// over first (what the board's count interrupt does after setting them).
    fn arm(&mut self, port: &mut MotionPort, now: u32) -> Window {
        let raw = self.raw;
        port.lock(|m| {
            let mut w = board::window(&mut m.engine, &mut m.core);
            for _ in 0..8 {
                if !m.engine.reached(&w, raw) {
                    break;
                }
                board::encoder(&mut m.engine, &mut m.core, now, raw);
                w = board::window(&mut m.engine, &mut m.core);
            }
            w
        })
        .unwrap_or(Window::OFF)
    }

    /// Advances the encoder to time `to` (µs) at the commanded spindle speed (M03
    /// counts up), handing a count to the core when it reaches a compare value.
    fn turn(&mut self, port: &mut MotionPort, to: u32) {
        let dt = to.wrapping_sub(self.at);
        if dt as i32 <= 0 {
            return;
        }
        let (dir, rpm) = port.peek(|m| m.core.spindle_output()).unwrap_or((SpindleDir::Stop, 0));
        let step: u32 = match dir {
            SpindleDir::Cw => 1,
            SpindleDir::Ccw => u32::MAX,
            SpindleDir::Stop => 0,
        };
        self.phase += u64::from(dt) * u64::from(rpm) * u64::from(self.cpr);
        let counts = if step == 0 { 0 } else { self.phase / US_PER_MIN };
        self.phase = if step == 0 { 0 } else { self.phase % US_PER_MIN };
        for k in 1..=counts {
            self.raw = self.raw.wrapping_add(step);
            if self.raw.is_multiple_of(self.cpr) {
                motion::latch_index(self.raw);
            }
            if Some(self.raw) != self.window.up && Some(self.raw) != self.window.down {
                continue;
            }
            // Counts spread evenly over the interval.
            let t = self.at.wrapping_add((u64::from(dt) * k / counts) as u32);
            self.window = self.arm(port, t);
        }
        self.at = to;
    }
}

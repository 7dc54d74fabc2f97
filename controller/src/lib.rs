//! The board's controller: everything between the serial link and the motion core
//! that is the same on the real board and on the host's virtual board — the link
//! protocols (grbl 1.1 line protocol, FANUC tape mode), job control, the stream
//! window and program store, settings and persistence. `no_std`, no allocation,
//! no unsafe code; bytes in, bytes out, time and hardware readings as arguments.
//! See `docs/PROTOCOL.md` for the wire contract.
//!
//! A shell drives it like this (the firmware's serial task, `lathe board`, tests):
//!
//! ```text
//! loop {
//!     let n = ctl.receive(&mut rx_bytes, now);  // keep rx_bytes[n..] for later
//!     ctl.poll(now, &mut port, &mut io, inputs); // bounded work
//!     let m = ctl.transmit(&mut tx_buf);        // send tx_buf[..m]
//! }
//! ```
//!
//! `port` reaches the motion core ([`MotionPort`]); on the board the core runs in
//! the interpolation timer interrupt and every port call is one short critical
//! section. The controller itself never runs in an interrupt.
//!
//! What a shell must honour:
//! - `receive`, `poll` and `transmit` are called from one task (the UART
//!   interrupt or DMA only fills a byte ring the task empties into `receive`);
//!   bytes `receive` did not take are offered again later, in order, as `receive`
//!   left them in the slice (it removes the real-time bytes it acted on, which
//!   may sit behind bytes the full receive buffer cannot take yet).
//! - `poll` every millisecond or so (and soon after `receive`): real-time
//!   commands act at the next poll; one poll does bounded work (≤ 4 lines,
//!   ≤ 8 interpreter steps of ≤ 32 macro statements each, one status report).
//! - `now` is monotonic nanoseconds (the link-quiet timeout of look-aheads).
//! - Inputs are debounced, true = active; they are read once per poll (e-stop is
//!   level-sensitive; limits, buttons and the door act on their rising edge).
//! - The spindle drive follows the motion core's `spindle_output()` every period
//!   (the shell's job, not the controller's); M-code, tool and spindle events reach
//!   [`MachineIo`] from `poll`.
//! - Settings that change the motion (`$100` …) call [`MotionPort::reconfigure`]
//!   at rest; [`Controller::take_dirty`] says what to write to flash.
#![no_std]
#![forbid(unsafe_code)]

#[cfg(test)]
extern crate std;

mod controller;
pub mod crc;
mod decimal;
mod dollar;
mod framing;
mod homing;
pub mod io;
mod jog;
mod lines;
pub mod outq;
pub mod persist;
pub mod port;
pub mod report;
mod rx;
pub mod settings;
mod starve;
mod tape;
mod toolchange;
pub mod window;

pub use controller::{Controller, Counters, Dirty, LINES_PER_POLL, Mode, OUT, RX, STEPS_PER_POLL, WELCOME};
pub use framing::frame_line;
pub use io::{Inputs, MachineIo};
pub use port::{MotionPort, MotionStatus};
pub use settings::Settings;

/// The board's controller: an 8 KiB stream window, 24 KiB of program memory for
/// 64 programs with 1024 indexed sequence numbers; about 76 KB in all (the
/// STM32F405 has 128 KB of SRAM and 64 KB of CCM; the motion core takes 21 KB).
pub type Board = Controller<8192, BOARD_TEXT, 64, 1024>;

/// Program memory of [`Board`], bytes (also the longest program it can hold).
pub const BOARD_TEXT: usize = 24576;

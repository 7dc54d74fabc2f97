//! The canned cycles' tool paths: the generators of the turning, threading, grooving
//! and hole cycles (FANUC G70–G76, G83–G89, G73–G89 of a machining centre; SINUMERIK
//! CYCLE81–89, CYCLE93–97), the ellipse and parabola curves and polar interpolation's
//! virtual moves. Each is a small state machine that plans its next few [`Step`]s
//! into a [`StepQueue`] when asked: pure functions of their inputs, no language, no
//! machine state. The interpreter (`interp_core::cycles`) keeps one in its
//! expansion, dry-runs it to validate the cycle, and turns its steps into actions.
//!
//! A crate of its own so that a board builds it for size (docs/FIRMWARE-SIZES.md):
//! a generator runs once per cycle pass, not per block, and the interpreter's
//! per-block path stays at opt-level 2 beside it.

#![no_std]

#[cfg(test)]
extern crate std;

pub mod curve;
pub mod groove;
pub mod hole;
pub mod holes;
pub mod offset;
pub mod pass;
pub mod pattern;
pub mod polar;
pub mod profile;
pub mod rough;
pub mod spec;
pub mod step;
pub mod thread;

pub use ::canon;
pub use ::geom;
pub use canon::{alarm, axis, units};
pub use step::{Pt, Step};

use alarm::AlarmKind;

/// Built with SINUMERIK mode (CYCLE93–97 use the generators' extra forms).
pub const SIEMENS: bool = cfg!(feature = "siemens");
/// Built with the machining-centre profile.
pub const MILL: bool = canon::MILL;

/// Steps planned and not yet emitted.
pub type StepQueue = heapless::Deque<Step, 8>;

/// Queues a planned step (an error if the queue is full: a generator's bug, as it
/// checks for room first). One out-of-line copy for every generator: inlined, each
/// of its ~100 call sites carried its own copy of the queue's index arithmetic.
#[inline(never)]
pub fn push(out: &mut StepQueue, s: Step) -> Result<(), AlarmKind> {
    out.push_back(s).map_err(|_| AlarmKind::Overflow)
}

/// The sign of `v` (-1, 0, 1), out of line: 64-bit `signum` is ~36 B inlined
/// and the engines take it at a dozen and a half sites.
#[inline(never)]
pub fn sign(v: i64) -> i64 {
    v.signum()
}

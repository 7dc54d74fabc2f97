//! Interpreter core: part programs in, canonical machining actions out. `no_std`,
//! no allocation, no unsafe code: the same logic runs in the firmware and in the
//! host simulator. Two languages (the FANUC-style dialect of the ELESY-E3TA manual,
//! SINUMERIK 840D) on two kinds of machine (lathe, machining centre) share one
//! engine (docs/LANGUAGES.md).
//!
//! Layers, one module each (docs/STRUCTURE.md):
//! - [`program`]: program text and the cursor that cuts blocks out of it;
//! - [`modal`]: the modal state a block is read against;
//! - [`command`]: the checked block every language produces;
//! - [`lang`]: the front ends — [`lang::fanuc`] (reader, macro B, checker), each
//!   turning its language's blocks into commands, with its own variables and
//!   control flow;
//! - [`stage`], [`moves`], [`contour`], [`cycles`], [`exec`]: the engine — the
//!   command applied to the modal state, emitting [`canon`] actions: staging (all or
//!   nothing), the move helpers, the contour look-ahead and compensation, the canned
//!   cycles, and `exec` on top dispatching to them;
//! - [`codes`]: G-code meanings and the table of each machine kind;
//! - [`interpreter`]: the incremental driver, one NC block (and a bounded number of
//!   macro statements) per step, with the subprogram and loop stacks.
//!
//! Units: lengths in nanometres, angles in micro-degrees, X as a radius (see [`units`]).
#![no_std]
#![forbid(unsafe_code)]

#[cfg(test)]
extern crate std;
// CYCLE73's planned path (mill-paths' `island`): only builds with a heap.
#[cfg(feature = "mill-island")]
extern crate alloc;

pub mod codes;
pub mod command;
pub mod contour;
pub mod cycles;
pub mod env;
pub mod exec;
pub use ::geom;
mod head;
pub mod interpreter;
pub mod lang;
pub mod modal;
pub mod moves;
pub mod program;
mod sort;
pub mod stage;

// The vocabulary shared with the motion core lives in the `canon` crate; its
// modules are re-exported under their old paths (`interp_core::axis::Pos`,
// `interp_core::canon::Action`, `interp_core::config::MachineConfig` …).
pub use ::canon;

/// Whether this build carries the FANUC 0i-M machining-centre profile (cargo
/// feature `mill`, docs/FIRMWARE-SIZES.md). Without it a board refuses `$311=1`,
/// and a machine configuration of kind mill reads no block (alarm 0010 for
/// every G code: the M-series table is not in the image).
pub const MILL: bool = ::canon::MILL;

/// Whether this build carries SINUMERIK mode (cargo feature `siemens`, turned on
/// by the `interp-siemens` crate: the interpreter's SINUMERIK state in
/// `lang::siemens` and `interpreter::siemens`). Without it G290 and a power-on language of SINUMERIK raise
/// alarm 4007.
pub const SIEMENS: bool = cfg!(feature = "siemens");

/// Whether `cfg` runs as a machining centre in this build: every M-series path
/// is behind this test, so a build without the `mill` feature leaves them out.
#[inline(always)]
pub(crate) fn is_mill(cfg: &config::MachineConfig) -> bool {
    MILL && cfg.kind == config::MachineKind::Mill
}
pub use ::canon::{alarm, axis, config, units};

pub use ::canon::{Action, Canon, CanonSink};
pub use alarm::{Alarm, AlarmKind};
pub use axis::{Axis, Pos};
pub use config::MachineConfig;
pub use env::{Environment, Panel};
pub use interpreter::{Interpreter, Progress};
pub use program::{ProgramStore, SingleProgram};

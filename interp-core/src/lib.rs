//! Lathe interpreter core: FANUC-style lathe programs (ELESY-E3TA dialect, G-code
//! system A/B/C) in, canonical machining actions out. `no_std`, no allocation,
//! no unsafe code: the same logic runs in the firmware and in the host simulator.
//!
//! Layers, one module each:
//! - [`program`]: program text and the cursor that cuts blocks out of it;
//! - [`parse`]: one block of text into words (syntax), or an evaluated macro
//!   statement ([`macros`]: variables, expressions, GOTO/IF/WHILE);
//! - [`modal`]: the modal state a block is read against (below `check`);
//! - [`check`]: words into a validated command in internal units (meaning);
//! - [`stage`], [`moves`], [`contour`], [`cycles`], [`exec`]: the command applied to
//!   the modal state, emitting [`canon`] actions — staging (all or nothing), the
//!   move helpers, the contour look-ahead, the canned cycles, and `exec` on top
//!   dispatching to them (docs/STRUCTURE.md);
//! - [`interpreter`]: the incremental driver, one NC block (and a bounded number of
//!   macro statements) per step, with the subprogram and loop stacks.
//!
//! Units: lengths in nanometres, angles in micro-degrees, X as a radius (see [`units`]).
#![no_std]
#![forbid(unsafe_code)]

#[cfg(test)]
extern crate std;

pub mod check;
pub mod codes;
pub mod contour;
pub mod cycles;
pub mod env;
pub mod exec;
pub mod geom;
mod head;
pub mod interpreter;
pub mod macros;
pub mod modal;
pub mod moves;
pub mod parse;
pub mod program;
mod sort;
pub mod stage;

// The vocabulary shared with the motion core lives in the `canon` crate; its
// modules are re-exported under their old paths (`interp_core::axis::Pos`,
// `interp_core::canon::Action`, `interp_core::config::MachineConfig` …).
pub use ::canon;
pub use ::canon::{alarm, axis, config, units};

pub use ::canon::{Action, Canon, CanonSink};
pub use alarm::{Alarm, AlarmKind};
pub use axis::{Axis, Pos};
pub use config::MachineConfig;
pub use env::{Environment, Panel};
pub use interpreter::{Interpreter, Progress};
pub use program::{ProgramStore, SingleProgram};

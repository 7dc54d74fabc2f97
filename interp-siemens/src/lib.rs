//! The SINUMERIK 840D front end (seed 001): the second language of the same
//! machine. `interp-core` is the machine — the FANUC front end, the modal state,
//! the canned-cycle geometry, compensation and canon — and this crate is the
//! language: DEF statements, labels and jumps, REPEAT sections, PROC
//! subprograms called by name, MCALL and the standard-cycle calls, driving the
//! interpreter's shared call stack and block execution.
//!
//! It plugs into an interpreter through [`interp_core::lang::Front`]:
//!
//! ```
//! use interp_core::{Interpreter, MachineConfig};
//! let mut interp = Interpreter::new(MachineConfig::default());
//! interp.plug(&interp_siemens::SINUMERIK);
//! ```
//!
//! Without it an interpreter alarms 4007 ("SINUMERIK mode not in this build") at
//! G290 or a SINUMERIK power-on language, and a firmware built without the
//! `siemens` feature links none of this crate. The firmware builds it for size
//! (opt-level "z", docs/FIRMWARE-SIZES.md): it runs once per SINUMERIK
//! statement, not per FANUC block. Still in `interp_core::lang::siemens` (moving
//! here next): the reader, checker and expression evaluator, which the cycle
//! engine's contour reading shares, the variables, and the cycles' parameter
//! mapping.
#![no_std]
#![warn(missing_docs)]

mod def;
mod driver;
mod labels;

pub use driver::{SINUMERIK, Sinumerik};

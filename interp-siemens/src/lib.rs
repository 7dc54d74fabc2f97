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
//! statement, not per FANUC block. What interp-core keeps of the language is
//! the seam: the state the interpreter holds for it (`interp_core::lang::siemens`:
//! the variables, a call's bound arguments) and the traits the engine calls
//! through ([`interp_core::lang::Front`] for a cycle's start and its contour's
//! blocks, [`interp_core::lang::Engine`] for the shared generators).
//!
//! - [`lex`], [`read`], [`expr`], [`check`]: a line read into words and
//!   statements, its expressions evaluated, its NC words checked into the
//!   engine's command;
//! - [`cycles`]: the standard cycles' parameter lists, checks and 61xxx alarms,
//!   mapped onto the engine's shared generators.
#![no_std]
#![warn(missing_docs)]

#[cfg(test)]
extern crate std;

pub mod check;
pub mod cycles;
mod def;
mod driver;
pub mod expr;
mod labels;
pub mod lex;
pub mod read;

pub use driver::{SINUMERIK, Sinumerik};

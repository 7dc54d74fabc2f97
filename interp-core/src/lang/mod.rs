//! The languages programs are written in: one front end each.
//!
//! A front end reads blocks of its language, keeps the language's variables and
//! control flow, and hands every NC block to the execution layers as a checked
//! [`crate::command::Command`]. Everything below the command — the modal state,
//! the canned cycles' geometry, the contour look-ahead and compensation, the
//! canonical actions — is one engine that every language shares.
//!
//! - [`fanuc`]: the FANUC-style dialect of the ELESY-E3TA manual (G-code systems
//!   A/B/C on a lathe, the M series on a mill), with custom macro B.
//! - [`siemens`]: SINUMERIK 840D (R parameters, DEF variables, labels, PROC
//!   subprograms, MCALL and the standard cycles of seed 001): the parts the
//!   engine shares here (the reader and checker the cycles' contour reading
//!   uses, the variables, the cycle calls' parameter mapping); the language's
//!   flow is the `interp-siemens` crate, plugged in as a [`Front`].
//!
//! How a language plugs in: the FANUC front end is the interpreter's own; any
//! other is a [`Front`] given to the interpreter with
//! [`crate::Interpreter::plug`], which hands it every step while its language
//! is in force (`G290`/`G291` switch). Both hand their blocks to the same
//! execution (`Interpreter::run_cmd`) and share one call stack.

pub mod fanuc;
pub mod siemens;

use crate::lang::fanuc::macros::Variables;
use crate::program::Cursor;
use crate::units::NumberFormat;

pub use crate::config::Language;

/// A language front end beside FANUC's: it reads, checks and runs the blocks of
/// its language on the interpreter's engine, one step at a time. The FANUC step
/// stays as it is: the interpreter calls a front end only while its language is
/// in force (one test of the language per step, one call through this trait).
pub trait Front: Sync + core::fmt::Debug {
    /// One step in this language: statements up to the step budget, at most one
    /// NC block, as [`crate::Interpreter::step`] describes.
    fn step(
        &self,
        it: &mut crate::Interpreter,
        programs: &dyn crate::program::ProgramStore,
        env: &dyn crate::env::Environment,
        sink: &mut dyn crate::canon::CanonSink,
    ) -> Result<crate::Progress, crate::Alarm>;
}

/// A program as the blocks of a canned cycle's shape (G70–G73 ns–nf) are read from
/// it: the text, where the program begins, the language it is written in, and what
/// the words are evaluated against.
#[derive(Clone, Copy, Debug)]
pub struct ProgramText<'a> {
    /// The text; cursors of the program index into it.
    pub text: &'a [u8],
    /// Where the program begins: sequence numbers are searched from here.
    pub start: Cursor,
    /// The language the program is written in: its blocks are read by that front end.
    pub language: Language,
    /// The variables `#i` in words stand for (`None`: words may not use variables).
    pub vars: Option<&'a Variables>,
    /// The number format in force (ROUND in words); `None` outside a program.
    pub fmt: Option<NumberFormat>,
}

impl ProgramText<'_> {
    /// No program (MDI, tests): no blocks, no variables.
    pub const NONE: ProgramText<'static> =
        ProgramText { text: &[], start: Cursor::start(0), language: Language::Fanuc, vars: None, fmt: None };

    /// Program text without variables, starting at its beginning (tests, tools).
    pub const fn plain(text: &[u8]) -> ProgramText<'_> {
        ProgramText { text, start: Cursor::start(0), language: Language::Fanuc, vars: None, fmt: None }
    }
}

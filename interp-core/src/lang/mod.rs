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

use crate::alarm::AlarmKind;
use crate::canon::SpindleDir;
use crate::command::Command;
use crate::command::hole::HoleSpec;
use crate::command::job::{GrooveSpec, MultiThreadSpec, StockSpec};
use crate::config::MachineConfig;
use crate::geom::{Pt, Seg};
use crate::lang::fanuc::macros::Variables;
use crate::lang::siemens::call::ContourSource;
use crate::modal::State;
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

    /// M17, RET or the end of a subprogram in this language: back to the caller
    /// (the level's sections end with it; a pass still due starts the level
    /// again); in the main program the end. The interpreter calls it for a
    /// block's [`Flow::Return`](crate::stage::Flow) routed by this language.
    fn ret(&self, it: &mut crate::Interpreter);

    /// Starts the standard cycle `sig` of a cycle-call block `cmd` with `args`
    /// (bound to `sig`, padded with [`Arg::Empty`](siemens::call::Arg::Empty)):
    /// checks the parameters (the language's alarms), maps them onto the
    /// engine's specification and starts the generator on `engine`. Nothing moves
    /// when an alarm is returned. Called by the engine (`Executor::cycle_call`).
    fn cycle_start(
        &self,
        sig: &'static siemens::call::Signature,
        args: &[siemens::call::Arg<'_>],
        cmd: &Command,
        st: &mut State,
        engine: &mut dyn Engine,
        contour: Option<siemens::call::ContourSource<'_>>,
    ) -> Result<(), AlarmKind>;

    /// One block of a cycle's contour written in this language, read and checked
    /// against `vars` (a contour's blocks are NC blocks only: a statement is
    /// alarm 61606 with the NCK cause 10930); `None` for a block without words.
    /// Called by the engine's contour reading (`cycles::profile`).
    fn contour_command(
        &self,
        raw: &crate::program::RawBlock<'_>,
        vars: &siemens::vars::Vars,
        st: &State,
        cfg: &MachineConfig,
    ) -> Result<Option<Command>, AlarmKind>;
}

/// The engine's side of a cycle call: the shared generators a cycle's parameters
/// are mapped onto. Implemented by `interp_core::cycles` (which sits above the
/// languages), handed down as a trait object.
pub trait Engine {
    /// The machine.
    fn cfg(&self) -> &MachineConfig;
    /// Starts the thread infeed engine (G76's) with `spec` for the cycle block `cmd`.
    fn thread(&mut self, spec: &MultiThreadSpec, cmd: &Command, st: &mut State) -> Result<(), AlarmKind>;
    /// One pass along `path` (work, X radius) with the nose compensated, the tool
    /// left (or right) of it, from and back to `start` with G0, at the feed in force.
    fn contour_pass(
        &mut self,
        path: &[Seg],
        tool_left: bool,
        start: Pt,
        cmd: &Command,
        st: &mut State,
    ) -> Result<(), AlarmKind>;
    /// Starts the grooving generator (G74/G75's columns) with `spec` on `segs`.
    fn grooving(&mut self, spec: &GrooveSpec, segs: &[Seg], cmd: &Command, st: &mut State) -> Result<(), AlarmKind>;
    /// Starts the one hole generator (G83–G89's, the mill's G73–G89) with `spec`,
    /// the spindle turned on `spindle` at the R level first when given.
    fn hole(
        &mut self,
        spec: &HoleSpec,
        spindle: Option<SpindleDir>,
        cmd: &Command,
        st: &mut State,
    ) -> Result<(), AlarmKind>;
    /// Raises the cycle message `code` (SINUMERIK 62xxx, its text in
    /// `canon::alarm::cycle_message`: shown, the program goes on) for the cycle
    /// just started: the operator sees it once the cycle's dry run has passed.
    fn message(&mut self, code: u16);
    /// Starts a milling cycle's tool path `path` (`mill_paths`) in the active
    /// plane for the cycle block `cmd`.
    #[cfg(feature = "siemens")]
    fn mill(&mut self, path: mill_paths::MillGen, cmd: &Command, st: &mut State) -> Result<(), AlarmKind>;
    /// Reads `contour` and starts the stock-removal generator (G71's geometry) on it.
    fn stock(
        &mut self,
        spec: &StockSpec,
        contour: ContourSource<'_>,
        cmd: &Command,
        st: &mut State,
    ) -> Result<(), AlarmKind>;
    /// Stages `action` with the cycle block (a setting cycle's canonical action,
    /// such as CYCLE832's path tolerance): delivered only if the block succeeds.
    /// Last in the trait: the other methods keep their vtable slots (the stack
    /// bound, `firmware/stack-bound.py`, resolves calls through a slot to every
    /// vtable's method in it).
    fn emit(&mut self, action: crate::canon::Action) -> Result<(), AlarmKind>;
    /// Reads `contour` in the active plane (the cycle's shape store) and starts
    /// the milling tool path `path` along it (CYCLE72; a board build without it
    /// leaves the method out, `mill-contour`).
    #[cfg(feature = "mill-contour")]
    fn mill_contour(
        &mut self,
        path: mill_paths::MillGen,
        contour: ContourSource<'_>,
        cmd: &Command,
        st: &mut State,
    ) -> Result<(), AlarmKind>;
    /// CYCLE73: reads the pocket's `edge` and the islands of the call
    /// ([`siemens::call::CycleCall::island`]) in the active plane, plans the
    /// path of `spec` through them (`mill_paths::island`) and starts it (a board
    /// build without a heap leaves the method out, `mill-island`).
    #[cfg(feature = "mill-island")]
    fn mill_islands(
        &mut self,
        spec: &mill_paths::island::IslandSpec,
        edge: ContourSource<'_>,
        cmd: &Command,
        st: &mut State,
    ) -> Result<(), AlarmKind>;
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

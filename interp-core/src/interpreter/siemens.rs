//! What the interpreter keeps for the SINUMERIK front end between steps: its
//! variables, the modal call, the kinds of program level (PROC, REPEAT) its
//! frames open, and a cycle call on its way to the engine. The front end's
//! driver — what it does with these — is the `interp-siemens` crate
//! ([`crate::lang::Front`]), which steps SINUMERIK statements: one NC block, or
//! a bounded number of statements, per step, on the engine the FANUC dialect uses.
//!
//! - An NC block is read ([`read`]), checked ([`check_into`]) and run by
//!   `run_cmd`, like a FANUC block; its assignments are written when it has
//!   succeeded. A line of plain words and numbers is read and checked a short
//!   way here instead ([`Interpreter::siemens_plain`]: the shared plain reader
//!   and a check with SINUMERIK's meanings, at the interpreter's speed); the
//!   front end runs it as it runs its NC blocks (one copy of `run_cmd`, built
//!   for size with the front end).
//! - DEF defines variables of the current level (before its first NC block only,
//!   alarm 14500); IF…GOTOx and GOTOF/GOTOB/GOTO/GOTOC jump to labels or block
//!   numbers of the level; REPEAT pushes a section frame; a call by name pushes a
//!   PROC frame with the arguments bound to the PROC's parameters (12340/12330),
//!   or starts a standard cycle as a cycle-call block; M17/RET return; MCALL
//!   calls its subprogram or cycle after every block that moves an axis.
//! - The end of a subprogram's text (or the next PROC of the same text) returns;
//!   the end of the main program's text without M02/M30 is alarm 5010, which a
//!   stream reads as "wait for more text".

use super::Interpreter;
use crate::config::Language;
#[cfg(feature = "siemens")]
use crate::lang::fanuc::check::sinumerik_plain;
#[cfg(feature = "siemens")]
use crate::lang::fanuc::parse::read_plain_line;
use crate::lang::siemens::call::{CallArgs, ContourSource, CycleCall, Signature};
use crate::lang::siemens::vars::Vars;
#[cfg(feature = "siemens")]
use crate::modal::Modal;
#[cfg(feature = "siemens")]
use crate::program::ProgramStore;
#[cfg(feature = "siemens")]
use crate::program::lines::next_line;
use crate::program::{Cursor, ProgramId};

/// What a call-stack frame opened. Without the `siemens` feature only a FANUC
/// call (the type takes no room in the frames).
#[derive(Clone, Copy, Debug)]
pub enum Level {
    /// A FANUC M98/G65 call.
    Fanuc,
    /// A SINUMERIK subprogram call.
    #[cfg(feature = "siemens")]
    Proc {
        /// The level's first line (its PROC line): labels are searched from here.
        start: Cursor,
        /// Bytes of the PROC line: a pass `P` starts again after it.
        skip: u16,
        /// PROC … SAVE: the modal state at the call ([`Front::saved`]) comes back
        /// at the return.
        save: bool,
        /// Called by MCALL: no modal call inside it.
        modal_call: bool,
    },
    /// A REPEAT section: from `start` to the offset `end` (after its last line).
    #[cfg(feature = "siemens")]
    Repeat {
        /// The section's first line.
        start: Cursor,
        /// Where the section ends.
        end: usize,
    },
}

impl Level {
    /// A cursor the frame needs kept in the text (a stream window must not drop it).
    pub fn kept(&self) -> Option<Cursor> {
        match *self {
            Level::Fanuc => None,
            #[cfg(feature = "siemens")]
            Level::Proc { start, .. } | Level::Repeat { start, .. } => Some(start),
        }
    }

    /// Program `program`'s text lost its first `bytes` bytes.
    pub fn shift(&mut self, program: ProgramId, bytes: usize) {
        #[cfg(feature = "siemens")]
        let sh = |c: &mut Cursor| {
            if c.program == program {
                c.offset = c.offset.saturating_sub(bytes);
            }
        };
        #[cfg(not(feature = "siemens"))]
        let _ = (program, bytes);
        match self {
            Level::Fanuc => {}
            #[cfg(feature = "siemens")]
            Level::Proc { start, .. } => sh(start),
            #[cfg(feature = "siemens")]
            Level::Repeat { start, end } => {
                if start.program == program {
                    *end = end.saturating_sub(bytes);
                }
                sh(start);
            }
        }
    }
}

/// What a modal call (MCALL) calls.
#[derive(Clone, Copy, Debug)]
pub enum Callee {
    /// A standard cycle.
    Cycle(&'static Signature),
    /// A subprogram: where it begins.
    Proc(Cursor),
}

/// A modal call in force: the callee and its arguments, bound when MCALL was read.
#[derive(Clone, Debug)]
pub struct ModalCall {
    pub callee: Callee,
    pub args: CallArgs,
    pub list: bool,
}

/// The SINUMERIK front end's state in the interpreter: without the `siemens`
/// feature (a board without SINUMERIK mode, the F446) only the empty plug, so
/// the language's variables and modal call take no RAM there.
#[derive(Debug)]
pub struct Front {
    /// R parameters and DEF variables.
    #[cfg(feature = "siemens")]
    pub vars: Vars,
    /// MCALL in force.
    #[cfg(feature = "siemens")]
    pub mcall: Option<ModalCall>,
    /// A block that moved an axis ran under MCALL (its line): the modal call is
    /// due before the next line is read.
    #[cfg(feature = "siemens")]
    pub mcall_due: Option<core::num::NonZeroU32>,
    /// The modal state at the call of the PROC … SAVE running (one at a time).
    #[cfg(feature = "siemens")]
    pub saved: Option<Modal>,
    /// A drilling pattern (HOLES1, HOLES2, CYCLE801) being positioned: the
    /// driver moves to its next hole when the modal call of the last is done.
    #[cfg(feature = "siemens")]
    pub pattern: Option<crate::cycles::holes::HolePattern>,
    /// [`Front::general`] before a drilling pattern switched the short way off
    /// (the pattern's holes are approached between lines: no plain line may be
    /// read first; no cost on the per-block path).
    #[cfg(feature = "siemens")]
    pub general_before: bool,
    /// The call depth the pattern was called at: its holes are approached only
    /// there, not while the modal call's subprogram runs one level deeper.
    #[cfg(feature = "siemens")]
    pub pattern_depth: usize,
    /// The last message of the cycles (62xxx: shown, the program goes on at NC
    /// start) and the line that raised it, for the operator's display.
    #[cfg(feature = "siemens")]
    pub notice: Option<(u16, u32)>,
    /// The contours CYCLE74 (the edge, first) and CYCLE75 (the islands)
    /// transferred to the next CYCLE73.
    #[cfg(feature = "mill-island")]
    pub pocket: heapless::Vec<PocketContour, POCKET_CONTOURS>,
    /// The front end plugged in ([`Interpreter::plug`]): kept with the language's
    /// cold state, so the FANUC step's fields stay where they were.
    pub front: Option<&'static dyn crate::lang::Front>,
    /// Every line the front end's general way, the short way for plain lines
    /// ([`Interpreter::siemens_plain`]) off: tests compare the two.
    pub general: bool,
}

/// Most contours one CYCLE73 pocket has: its edge and 15 islands (61906 beyond).
#[cfg(feature = "mill-island")]
pub const POCKET_CONTOURS: usize = 16;

/// Where one contour of a pocket with islands is, as CYCLE74/CYCLE75 named it
/// (seed 001 lines 6172-6204: the 840D keeps the names in a temporary file for
/// CYCLE73): a program name (`_KNAME`), the start and end labels or block numbers
/// (`_LSANF`, `_LSEND`). CYCLE73 finds the contour again by these.
#[cfg(feature = "mill-island")]
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct PocketContour {
    /// `_KNAME`: the program the contour is in (empty: the calling program).
    pub name: heapless::Vec<u8, 64>,
    /// `_LSANF` (empty: the whole program `name`).
    pub start: heapless::Vec<u8, 32>,
    /// `_LSEND`.
    pub end: heapless::Vec<u8, 32>,
}

impl Default for Front {
    fn default() -> Self {
        Self::new()
    }
}

impl Front {
    pub const fn new() -> Self {
        Front {
            #[cfg(feature = "siemens")]
            vars: Vars::new(),
            #[cfg(feature = "siemens")]
            mcall: None,
            #[cfg(feature = "siemens")]
            mcall_due: None,
            #[cfg(feature = "siemens")]
            saved: None,
            #[cfg(feature = "siemens")]
            pattern: None,
            #[cfg(feature = "siemens")]
            general_before: false,
            #[cfg(feature = "siemens")]
            pattern_depth: 0,
            #[cfg(feature = "siemens")]
            notice: None,
            #[cfg(feature = "mill-island")]
            pocket: heapless::Vec::new(),
            front: None,
            general: false,
        }
    }

    /// A new run: no DEF variables, no modal call, no pocket contours
    /// transferred (R parameters stay).
    pub fn rewind(&mut self) {
        #[cfg(feature = "mill-island")]
        self.pocket.clear();
        #[cfg(feature = "siemens")]
        {
            self.vars.clear_locals();
            self.mcall = None;
            self.mcall_due = None;
            self.saved = None;
            self.end_pattern();
            self.notice = None;
        }
    }

    /// Starts running drilling pattern `p`, called at call depth `depth`: the
    /// short way for plain lines off until it ends.
    #[cfg(feature = "siemens")]
    pub fn begin_pattern(&mut self, p: crate::cycles::holes::HolePattern, depth: usize) {
        if self.pattern.is_none() {
            self.general_before = self.general;
        }
        self.pattern_depth = depth;
        self.general = true;
        self.pattern = Some(p);
    }

    /// No drilling pattern running any more: the short way as it was.
    #[cfg(feature = "siemens")]
    pub fn end_pattern(&mut self) {
        if self.pattern.take().is_some() {
            self.general = self.general_before;
        }
    }

    /// Program `program`'s text lost its first `bytes` bytes.
    pub fn shift(&mut self, program: ProgramId, bytes: usize) {
        #[cfg(feature = "siemens")]
        if let Some(ModalCall { callee: Callee::Proc(c), .. }) = &mut self.mcall
            && c.program == program
        {
            c.offset = c.offset.saturating_sub(bytes);
        }
        #[cfg(not(feature = "siemens"))]
        let _ = (program, bytes);
    }

    /// The variables.
    #[cfg(feature = "siemens")]
    pub fn vars(&self) -> &Vars {
        &self.vars
    }

    /// The variables, to set from outside (tests, the panel).
    #[cfg(feature = "siemens")]
    pub fn vars_mut(&mut self) -> &mut Vars {
        &mut self.vars
    }
}

pub use crate::lang::siemens::call::ContourAt;

/// A cycle call for `run_cmd`: the cycle, its bound arguments and its contour.
#[derive(Clone, Copy, Debug)]
pub struct CallSpec<'c> {
    pub sig: &'static Signature,
    /// The front end whose cycle it is: it starts the cycle and reads its contour.
    pub front: &'static dyn crate::lang::Front,
    pub args: &'c CallArgs,
    pub contour: Option<ContourAt<'c>>,
    /// CYCLE73's islands (`contour` is its edge).
    #[cfg(feature = "mill-island")]
    pub islands: &'c [ContourAt<'c>],
}

impl<'c> CallSpec<'c> {
    /// The call as the engine gets it, the contour reading `vars`.
    pub fn bind(&self, vars: &'c Vars) -> CycleCall<'c> {
        let front = self.front;
        let contour =
            self.contour.map(|c| ContourSource { program: c.program, start: c.start, end: c.end, vars, front });
        CycleCall {
            sig: self.sig,
            args: self.args,
            contour,
            front,
            #[cfg(feature = "mill-island")]
            islands: self.islands,
        }
    }
}

/// What the short way ([`Interpreter::siemens_plain`]) made of the line at the
/// cursor (the cursor is past it).
#[cfg(feature = "siemens")]
#[derive(Clone, Copy, Debug)]
#[doc(hidden)]
pub enum Plain {
    /// Blanks, a comment, a block number alone.
    Skipped { line: u32 },
    /// A block of plain words, checked into the interpreter's command: the front
    /// end runs it.
    Block { at: Cursor, line: u32 },
}

impl Interpreter {
    /// The short way of a SINUMERIK step (issue 19): a line of plain words and
    /// numbers (`N.. G1 X40.412 Z-0.05 F.2`: no name, `=`, bracket, label,
    /// expression or string, only words the short way reads as SINUMERIK does) is
    /// read by the shared plain reader ([`read_plain_line`]) and checked with
    /// SINUMERIK's meanings ([`sinumerik_plain`]) into the block's command, without
    /// the front end's statement reader and checker (`interp-siemens`, built for
    /// size); the front end runs it as it runs its NC blocks. `None`: the front
    /// end's step reads the line — everything else, every alarm of reading and
    /// checking included, and every line while a modal call (MCALL) or a REPEAT
    /// section's end may be due. Here (opt-level 2) the per-block reading and
    /// checking stays fast; the block's run is the front end's one copy.
    #[cfg(feature = "siemens")]
    #[inline(never)]
    #[doc(hidden)]
    pub fn siemens_plain(&mut self, programs: &dyn ProgramStore) -> Option<Plain> {
        let repeat = |f: &super::Frame| matches!(f.kind, Level::Repeat { .. });
        if self.siemens.general
            || self.siemens.mcall.is_some()
            || self.siemens.mcall_due.is_some()
            || self.calls.last().is_some_and(repeat)
        {
            return None;
        }
        let at = self.cursor;
        let text = programs.text(at.program).unwrap_or(&[]);
        let mut next = at;
        let raw = next_line(text, &mut next)?;
        let line = raw.line;
        if !read_plain_line(raw.text, line, &mut self.block) {
            return None;
        }
        if !self.block.is_empty() && !sinumerik_plain(&self.block, &self.state, &self.cfg, &mut self.cmd) {
            return None;
        }
        self.last_block = at;
        self.cursor = next;
        Some(if self.block.is_empty() {
            // Blanks, a comment, a block number alone.
            Plain::Skipped { line }
        } else {
            Plain::Block { at, line }
        })
    }

    /// M17/RET of a block the front end routed: the front end plugged in goes
    /// back to the caller (its `Front::ret`; built and run at its size).
    pub(super) fn front_return(&mut self) {
        #[cfg(feature = "siemens")]
        if let Some(front) = self.siemens.front {
            front.ret(self);
        }
    }

    /// Every SINUMERIK line the front end's general way (`true`), or plain lines
    /// the short way ([`Interpreter::siemens_plain`], the default): tests run
    /// lines both ways and compare.
    #[doc(hidden)]
    pub fn set_siemens_general(&mut self, general: bool) {
        self.siemens.general = general;
    }

    /// The SINUMERIK variables.
    #[cfg(feature = "siemens")]
    pub fn siemens_vars(&self) -> &Vars {
        self.siemens.vars()
    }

    /// The SINUMERIK variables, to set R parameters from the panel or a test.
    #[cfg(feature = "siemens")]
    pub fn siemens_vars_mut(&mut self) -> &mut Vars {
        self.siemens.vars_mut()
    }

    /// The language blocks are read in now.
    pub fn language(&self) -> Language {
        self.language
    }
}

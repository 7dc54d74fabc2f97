//! The driver's side of FANUC macro and subprogram calls (see
//! [`crate::lang::fanuc::calls`]): G65 and the calls by G and M code go into the
//! called program with a new level of local variables; G66/G67 start and end modal
//! calls, made after every block that moves an axis; M/T-code subprogram calls go
//! in like M98. Each call is checked completely (program, nesting, room for #149)
//! before anything changes, so a refused call leaves the run as it was.

use super::{Entry, Interpreter, Next};
use crate::alarm::AlarmKind;
use crate::command::CallBy;
use crate::lang::fanuc::calls::{CallCodes, Caller, MacroCall, T_CODE_VARIABLE};
use crate::lang::fanuc::macros::MAX_MACRO_LEVEL;
use crate::program::{Cursor, ProgramStore};

impl Interpreter {
    /// The macro call block just read into `self.macro_calls.read`: G65 and a call by G or M
    /// code lead into the called program (`Some`, checked); G66 and G67 change the
    /// modal calls and the step goes on (`None`).
    #[inline(never)]
    pub(super) fn macro_call<P: ProgramStore + ?Sized>(&mut self, programs: &P) -> Result<Option<Next>, AlarmKind> {
        match self.macro_calls.read.block.call {
            MacroCall::Simple { program, repeats, by } => {
                let start = self.macro_start(program, programs)?;
                Ok(Some(Next::Call { start, repeats, entry: Entry::Macro(by) }))
            }
            MacroCall::Modal { program, repeats } => {
                // The program must be there when the modal call begins (FANUC looks
                // at the first move; the alarm names the G66 block instead).
                programs.start(program).ok_or(AlarmKind::ProgramNotFound { program })?;
                self.modal.start(program, repeats, &self.macro_calls.read.args)?;
                Ok(None)
            }
            MacroCall::Cancel => {
                self.modal.cancel();
                Ok(None)
            }
        }
    }

    /// Where macro `program` starts, if a macro call may go there: the program is
    /// stored, and neither the 12 levels of calls nor the 4 of macro calls are used up.
    fn macro_start<P: ProgramStore + ?Sized>(&self, program: u32, programs: &P) -> Result<Cursor, AlarmKind> {
        if self.calls.is_full() {
            return Err(AlarmKind::CallNestingTooDeep);
        }
        if self.vars.level() >= MAX_MACRO_LEVEL {
            return Err(AlarmKind::MacroNestingTooDeep);
        }
        programs.start(program).ok_or(AlarmKind::ProgramNotFound { program })
    }

    /// After a block that goes on to the next: the G66 modal call due, if the block
    /// moved an axis ([`crate::command::Command::moves_axes`]).
    #[inline(never)]
    pub(super) fn modal_call_after_move<P: ProgramStore + ?Sized>(&self, programs: &P) -> Result<Next, AlarmKind> {
        let Some((i, program, repeats, _)) = self.modal.due() else { return Ok(Next::Go) };
        if !self.cmd.moves_axes(&self.state) {
            return Ok(Next::Go);
        }
        let start = self.macro_start(program, programs)?;
        Ok(Next::Call { start, repeats, entry: Entry::Modal(i) })
    }

    /// M98, or a subprogram call by an M or T code, checked.
    pub(super) fn subprogram_call<P: ProgramStore + ?Sized>(
        &self,
        program: u32,
        repeats: u16,
        by: CallBy,
        programs: &P,
    ) -> Result<Next, AlarmKind> {
        let caller = match by {
            CallBy::M98 => {
                if program == self.cursor.program {
                    return Err(AlarmKind::SelfCall { program });
                }
                Caller::Program
            }
            CallBy::Code => {
                let t = self.block.sub_call().and_then(|c| c.t);
                if t.is_some() && !self.vars.can_set(T_CODE_VARIABLE) {
                    return Err(AlarmKind::VariablesFull);
                }
                Caller::Subprogram
            }
        };
        if self.calls.is_full() {
            return Err(AlarmKind::CallNestingTooDeep);
        }
        let start = programs.start(program).ok_or(AlarmKind::ProgramNotFound { program })?;
        Ok(Next::Call { start, repeats, entry: Entry::Subprogram(caller) })
    }

    /// Entering a called program (its frame is pushed), right after the calling
    /// block (or its cycle's dry run): a macro's level of local variables, a T
    /// code's value in #149 (from the calling block, still in `self.block`), the
    /// code calls it switches off.
    pub(super) fn enter_call(&mut self, entry: Entry) {
        // `macro_start` made sure there is a level free, `subprogram_call` that
        // #149 has room.
        let by = match entry {
            Entry::Macro(by) => {
                let _ = self.vars.enter_level(&self.macro_calls.read.args);
                by
            }
            Entry::Modal(i) => {
                self.modal.set_busy(i, true);
                let _ = self.vars.enter_level(self.modal.args(i).unwrap_or(&self.macro_calls.read.args));
                Caller::Program
            }
            Entry::Subprogram(by) => {
                if let Some(t) = self.block.sub_call().and_then(|c| c.t) {
                    let _ = self.vars.set(T_CODE_VARIABLE, Some(f64::from(t)));
                }
                by
            }
        };
        self.set_codes_off(self.codes_off | by.switches_off());
    }

    /// Leaving a called program (M99, its frame popped): the caller's local
    /// variables and code calls again.
    pub(super) fn leave_call(&mut self, entry: Entry, off: u8) {
        match entry {
            Entry::Macro(_) => self.vars.leave_level(),
            Entry::Modal(i) => {
                self.vars.leave_level();
                self.modal.set_busy(i, false);
            }
            Entry::Subprogram(_) => {}
        }
        self.set_codes_off(off);
    }

    /// Every call dropped (rewind, reset): the main program's level, no modal call,
    /// every code call on.
    pub(super) fn drop_calls(&mut self) {
        self.vars.leave_all_levels();
        self.modal.clear();
        self.set_codes_off(0);
    }

    /// The code calls `off` switches off are off from now on.
    fn set_codes_off(&mut self, off: u8) {
        if off != self.codes_off {
            self.codes_off = off;
            self.refresh_codes();
        }
    }

    /// The table of codes that call, from the parameters and what is switched off.
    #[inline(never)]
    pub(super) fn refresh_codes(&mut self) {
        self.macro_calls.codes = CallCodes::of(&self.cfg.params, self.codes_off);
    }

    /// Macro levels now active (0 in the main program and what it calls with M98).
    pub fn macro_level(&self) -> usize {
        self.vars.level()
    }
}

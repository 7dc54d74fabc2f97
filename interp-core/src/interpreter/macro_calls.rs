//! The driver's side of FANUC macro and subprogram calls (see
//! [`crate::lang::fanuc::calls`]): G65 and the calls by G and M code go into the
//! called program with a new level of local variables; G66/G67 start and end modal
//! calls, made after every block that moves an axis; M/T-code subprogram calls go
//! in like M98. Each call is checked completely (program, nesting, room for #149)
//! before anything changes, so a refused call leaves the run as it was.

use super::{Entry, Interpreter, Next};
use crate::alarm::AlarmKind;
use crate::command::CallBy;
use crate::lang::fanuc::calls::{CallBlock, CallCodes, Caller, MacroCall, T_CODE_VARIABLE};
use crate::lang::fanuc::macros::MAX_MACRO_LEVEL;
use crate::program::{Cursor, ProgramStore};

impl Interpreter {
    /// The macro call block `c` just read (its arguments in `self.args`): G65 and
    /// a call by G or M code lead into the called program (`Some`, checked); G66
    /// and G67 change the modal calls and the step goes on (`None`).
    pub(super) fn macro_call<P: ProgramStore + ?Sized>(
        &mut self,
        c: &CallBlock,
        programs: &P,
    ) -> Result<Option<Next>, AlarmKind> {
        match c.call {
            MacroCall::Simple { program, repeats, by } => {
                let start = self.macro_start(program, programs)?;
                Ok(Some(Next::Call { start, repeats, entry: Entry::Macro { by, modal: None }, t: None }))
            }
            MacroCall::Modal { program, repeats } => {
                // The program must be there when the modal call begins (FANUC looks
                // at the first move; the alarm names the G66 block instead).
                programs.start(program).ok_or(AlarmKind::ProgramNotFound { program })?;
                self.modal.start(program, repeats, &self.args)?;
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
        Ok(Next::Call { start, repeats, entry: Entry::Macro { by: Caller::Program, modal: Some(i) }, t: None })
    }

    /// M98, or a subprogram call by an M or T code, checked.
    pub(super) fn subprogram_call<P: ProgramStore + ?Sized>(
        &self,
        program: u32,
        repeats: u16,
        by: CallBy,
        programs: &P,
    ) -> Result<Next, AlarmKind> {
        let (caller, t) = match by {
            CallBy::M98 => {
                if program == self.cursor.program {
                    return Err(AlarmKind::SelfCall { program });
                }
                (Caller::Program, None)
            }
            CallBy::Code { t } => {
                if t.is_some() && !self.vars.can_set(T_CODE_VARIABLE) {
                    return Err(AlarmKind::VariablesFull);
                }
                (Caller::Subprogram, t)
            }
        };
        if self.calls.is_full() {
            return Err(AlarmKind::CallNestingTooDeep);
        }
        let start = programs.start(program).ok_or(AlarmKind::ProgramNotFound { program })?;
        Ok(Next::Call { start, repeats, entry: Entry::Subprogram { by: caller }, t })
    }

    /// Entering a called program (its frame is pushed): a macro's level of local
    /// variables, a T code's value in #149, the code calls it switches off.
    pub(super) fn enter_call(&mut self, entry: Entry, t: Option<u32>) {
        if let Some(t) = t {
            // `subprogram_call` made sure there is room.
            let _ = self.vars.set(T_CODE_VARIABLE, Some(f64::from(t)));
        }
        let by = match entry {
            Entry::Macro { by, modal } => {
                // `macro_start` made sure there is a level free.
                let args = match modal {
                    Some(i) => {
                        self.modal.set_busy(i, true);
                        self.modal.args(i).unwrap_or(&self.args)
                    }
                    None => &self.args,
                };
                let _ = self.vars.enter_level(args);
                by
            }
            Entry::Subprogram { by } => by,
        };
        self.set_codes_off(self.codes_off | by.switches_off());
    }

    /// Leaving a called program (M99, its frame popped): the caller's local
    /// variables and code calls again.
    pub(super) fn leave_call(&mut self, entry: Entry, off: u8) {
        if let Entry::Macro { modal, .. } = entry {
            self.vars.leave_level();
            if let Some(i) = modal {
                self.modal.set_busy(i, false);
            }
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
            self.codes_stale = true;
        }
    }

    /// The table of codes that call, from the parameters and what is switched off.
    #[inline(never)]
    pub(super) fn refresh_codes(&mut self) {
        self.codes = CallCodes::of(&self.cfg.params, self.codes_off);
        self.codes_stale = false;
    }

    /// Macro levels now active (0 in the main program and what it calls with M98).
    pub fn macro_level(&self) -> usize {
        self.vars.level()
    }
}

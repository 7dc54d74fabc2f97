//! Stepping SINUMERIK statements: one NC block, or a bounded number of
//! statements, per step, on the engine the FANUC dialect uses.
//!
//! - An NC block is read ([`read`]), checked ([`check_into`]) and run by the
//!   interpreter's `run_cmd`, like a FANUC block; its assignments are written
//!   when it has succeeded.
//! - DEF defines variables of the current level (before its first NC block only,
//!   alarm 14500); IF…GOTOx and GOTOF/GOTOB/GOTO/GOTOC jump to labels or block
//!   numbers of the level; REPEAT pushes a section frame; a call by name pushes a
//!   PROC frame with the arguments bound to the PROC's parameters (12340/12330),
//!   or starts a standard cycle as a cycle-call block; M17/RET return; MCALL
//!   calls its subprogram or cycle after every block that moves an axis.
//! - The end of a subprogram's text (or the next PROC of the same text) returns;
//!   the end of the main program's text without M02/M30 is alarm 5010, which a
//!   stream reads as "wait for more text".

use crate::check::{Extras, apply, check_into, number_format};
#[cfg(feature = "mill-island")]
use crate::cycles::predrills;
use crate::def::{self, Proc, proc_params};
use crate::labels::{self, Level as Section};
use crate::read::{Dir, Jump, Pending, Scope, Stmt, Target, Words, read};
#[cfg(feature = "mill-island")]
use interp_core::alarm::CycleAlarm;
use interp_core::alarm::{Alarm, AlarmKind, SiemensAlarm as S};
use interp_core::canon::{Action, Canon, CanonSink};
use interp_core::codes::GCode;
use interp_core::command::Command;
use interp_core::config::Language;
use interp_core::env::Environment;
use interp_core::geom::round_i64;
use interp_core::interpreter::siemens::{CallSpec, Callee, ContourAt, Level, ModalCall, Plain};
#[cfg(feature = "mill-island")]
use interp_core::interpreter::siemens::{POCKET_CONTOURS, PocketContour};
use interp_core::interpreter::{Entry, Frame, Interpreter, Next, Phase, Progress};
use interp_core::lang::ProgramText;
use interp_core::lang::fanuc::calls::Caller;
use interp_core::lang::siemens::call::{Arg, CallArgs, Signature};
use interp_core::lang::siemens::vars::Value;
use interp_core::modal::Modal;
use interp_core::program::lines::{self, next_line};
use interp_core::program::{Cursor, ProgramId, ProgramStore};
use interp_core::stage::Flow;

/// The SINUMERIK front end, as an interpreter is given it
/// ([`Interpreter::plug`]): the interpreter hands it every step while the
/// language in force is SINUMERIK (after G290, or on a machine whose power-on
/// language it is).
#[derive(Debug)]
pub struct Sinumerik;

/// The SINUMERIK front end (stateless: its state is the interpreter's).
pub static SINUMERIK: Sinumerik = Sinumerik;

impl interp_core::lang::Front for Sinumerik {
    fn step(
        &self,
        it: &mut Interpreter,
        programs: &dyn ProgramStore,
        env: &dyn Environment,
        sink: &mut dyn CanonSink,
    ) -> Result<Progress, Alarm> {
        it.siemens_step(programs, env, sink)
    }

    fn ret(&self, it: &mut Interpreter) {
        it.siemens_return();
    }

    fn cycle_start(
        &self,
        sig: &'static Signature,
        args: &[Arg<'_>],
        cmd: &interp_core::command::Command,
        st: &mut interp_core::modal::State,
        engine: &mut dyn interp_core::lang::Engine,
        contour: Option<interp_core::lang::siemens::call::ContourSource<'_>>,
    ) -> Result<(), AlarmKind> {
        crate::cycles::start(sig, args, cmd, st, engine, contour)
    }

    fn contour_command(
        &self,
        raw: &interp_core::program::RawBlock<'_>,
        vars: &interp_core::lang::siemens::vars::Vars,
        st: &interp_core::modal::State,
        cfg: &interp_core::MachineConfig,
    ) -> Result<Option<interp_core::command::Command>, AlarmKind> {
        crate::check::contour_command(raw, vars, st, cfg)
    }
}

/// What a block that ran does next: write its assignments, jump (the block's
/// GOTO, when it goes on), arm MCALL if it moved an axis.
#[derive(Clone, Copy)]
struct After<'p, 't> {
    pending: Option<&'p Pending<'t>>,
    to: Option<Cursor>,
    moves: bool,
}

/// The SINUMERIK driver's steps, on the interpreter they drive (an extension
/// trait: the interpreter is interp-core's type, the steps are this crate's).
#[allow(clippy::too_many_arguments)]
trait Driver {
    fn siemens_step(
        &mut self,
        programs: &dyn ProgramStore,
        env: &dyn Environment,
        sink: &mut dyn CanonSink,
    ) -> Result<Progress, Alarm>;

    fn siemens_level_ran<P: ProgramStore + ?Sized>(&self, at: Cursor, programs: &P) -> bool;

    fn level_start<P: ProgramStore + ?Sized>(&self, programs: &P) -> Cursor;

    fn section<'t, P: ProgramStore + ?Sized>(&self, text: &'t [u8], programs: &P) -> Section<'t>;

    fn section_end(&mut self);

    fn siemens_return(&mut self);

    fn text_end<K: CanonSink + ?Sized>(&mut self, at: Cursor, sink: &mut K) -> Result<Progress, Alarm>;

    fn siemens_nc<P, E, K>(
        &mut self,
        at: Cursor,
        text: &[u8],
        words: &Words,
        pending: &Pending<'_>,
        jump: Option<Jump<'_>>,
        programs: &P,
        env: &E,
        sink: &mut K,
    ) -> Result<Progress, Alarm>
    where
        P: ProgramStore + ?Sized,
        E: Environment,
        K: CanonSink + ?Sized;

    fn run_block<P, E, K>(
        &mut self,
        at: Cursor,
        line: u32,
        spec: Option<CallSpec<'_>>,
        extras: Extras,
        then: After<'_, '_>,
        programs: &P,
        env: &E,
        sink: &mut K,
    ) -> Result<Progress, Alarm>
    where
        P: ProgramStore + ?Sized,
        E: Environment,
        K: CanonSink + ?Sized;

    fn program_text<'p, P: ProgramStore + ?Sized>(&self, id: ProgramId, programs: &'p P) -> ProgramText<'p>;

    fn siemens_route(&self, flow: Flow) -> Result<Next, AlarmKind>;

    fn commit(&mut self, pending: &Pending<'_>);

    fn write_tool(&mut self, row: u16, param: u8, v: Value<'_>);

    fn assignments<P: ProgramStore + ?Sized>(
        &mut self,
        pending: &Pending<'_>,
        jump: Option<Jump<'_>>,
        at: Cursor,
        text: &[u8],
        programs: &P,
    ) -> Result<(), AlarmKind>;

    fn find_jump<P: ProgramStore + ?Sized>(
        &self,
        jump: Jump<'_>,
        at: Cursor,
        text: &[u8],
        programs: &P,
    ) -> Result<Option<Cursor>, AlarmKind>;

    fn jump_to<P: ProgramStore + ?Sized>(
        &mut self,
        jump: Jump<'_>,
        at: Cursor,
        text: &[u8],
        programs: &P,
    ) -> Result<(), AlarmKind>;

    fn repeat<P: ProgramStore + ?Sized>(
        &mut self,
        start: &[u8],
        end: Option<&[u8]>,
        count: u32,
        single: bool,
        at: Cursor,
        text: &[u8],
        programs: &P,
    ) -> Result<(), AlarmKind>;

    fn in_modal_call(&self) -> bool;

    fn call<P, E, K>(
        &mut self,
        name: &[u8],
        list: bool,
        passes: u32,
        args: &mut CallArgs,
        at: Cursor,
        programs: &P,
        env: &E,
        sink: &mut K,
    ) -> Result<Progress, Alarm>
    where
        P: ProgramStore + ?Sized,
        E: Environment,
        K: CanonSink + ?Sized;

    fn enter_proc<P: ProgramStore + ?Sized>(
        &mut self,
        entry: Cursor,
        args: &mut CallArgs,
        list: bool,
        passes: u32,
        modal_call: bool,
        programs: &P,
    ) -> Result<(), AlarmKind>;

    fn set_mcall<P: ProgramStore + ?Sized>(
        &mut self,
        name: Option<&[u8]>,
        list: bool,
        args: &mut CallArgs,
        programs: &P,
    ) -> Result<(), AlarmKind>;

    fn modal_call<P, E, K>(&mut self, line: u32, programs: &P, env: &E, sink: &mut K) -> Result<Progress, Alarm>
    where
        P: ProgramStore + ?Sized,
        E: Environment,
        K: CanonSink + ?Sized;

    fn start_pattern<K: CanonSink + ?Sized>(
        &mut self,
        sig: &'static Signature,
        args: &CallArgs,
        at: Cursor,
        sink: &mut K,
    ) -> Result<Progress, Alarm>;

    fn pattern_hole<P, E, K>(&mut self, programs: &P, env: &E, sink: &mut K) -> Option<Result<Progress, Alarm>>
    where
        P: ProgramStore + ?Sized,
        E: Environment,
        K: CanonSink + ?Sized;

    fn notice(&mut self, n: crate::cycles::Notice, line: u32) -> Progress;

    fn cycle<P, E, K>(
        &mut self,
        sig: &'static Signature,
        args: &CallArgs,
        at: Cursor,
        line: u32,
        programs: &P,
        env: &E,
        sink: &mut K,
    ) -> Result<Progress, Alarm>
    where
        P: ProgramStore + ?Sized,
        E: Environment,
        K: CanonSink + ?Sized;

    fn contour_of<'p, P: ProgramStore + ?Sized>(
        &self,
        sig: &Signature,
        args: &CallArgs,
        at: Cursor,
        programs: &'p P,
    ) -> Result<Option<ContourAt<'p>>, AlarmKind>;

    fn contour_at<'p, P: ProgramStore + ?Sized>(
        &self,
        prog: &[u8],
        start: &[u8],
        end: &[u8],
        at: Cursor,
        programs: &'p P,
    ) -> Result<ContourAt<'p>, AlarmKind>;

    #[cfg(feature = "mill-island")]
    fn pocket_contour<P: ProgramStore + ?Sized>(
        &mut self,
        sig: &Signature,
        args: &CallArgs,
        at: Cursor,
        programs: &P,
    ) -> Result<(), AlarmKind>;

    #[cfg(feature = "mill-island")]
    fn pocket_contours<'p, P: ProgramStore + ?Sized>(
        &self,
        at: Cursor,
        programs: &'p P,
        islands: &mut Islands<'p>,
    ) -> Result<ContourAt<'p>, AlarmKind>;

    #[cfg(feature = "mill-island")]
    fn start_predrill<P, E, K>(
        &mut self,
        args: &CallArgs,
        at: Cursor,
        programs: &P,
        env: &E,
        sink: &mut K,
    ) -> Result<Progress, Alarm>
    where
        P: ProgramStore + ?Sized,
        E: Environment,
        K: CanonSink + ?Sized;

    #[cfg(feature = "mill-island")]
    fn insertion_points<P, E>(
        &self,
        args: &CallArgs,
        at: Cursor,
        programs: &P,
        env: &E,
    ) -> Result<interp_core::cycles::holes::HolePattern, AlarmKind>
    where
        P: ProgramStore + ?Sized,
        E: Environment;
}

/// CYCLE73's islands, resolved for its call.
#[cfg(feature = "mill-island")]
type Islands<'p> = heapless::Vec<ContourAt<'p>, { POCKET_CONTOURS - 1 }>;

impl Driver for Interpreter {
    /// Steps SINUMERIK lines: statements up to the step budget, at most one NC
    /// block. On trait objects: one copy of the SINUMERIK path whatever the store,
    /// machine and sink, and the FANUC step that calls it stays as it was.
    #[inline(never)]
    fn siemens_step(
        &mut self,
        programs: &dyn ProgramStore,
        env: &dyn Environment,
        sink: &mut dyn CanonSink,
    ) -> Result<Progress, Alarm> {
        let env = &env;
        // A line of plain words and numbers: read and checked the short way
        // (interp-core's `siemens_plain`), run here as every NC block.
        match self.siemens_plain(programs) {
            Some(Plain::Skipped { line }) => return Ok(Progress::Skipped { line }),
            Some(Plain::Block { at, line }) => {
                let then = After { pending: None, to: None, moves: false };
                return self.run_block(at, line, None, Extras::default(), then, programs, env, sink);
            }
            None => {}
        }
        let mut budget = self.budget;
        loop {
            if let Some(line) = self.siemens.mcall_due.take().map(core::num::NonZeroU32::get) {
                return self.modal_call(line, programs, env, sink);
            }
            if let Some(r) = self.pattern_hole(programs, env, sink) {
                return r;
            }
            self.section_end();
            let at = self.cursor;
            self.last_block = at;
            let text = programs.text(at.program).unwrap_or(&[]);
            let Some(raw) = next_line(text, &mut self.cursor) else {
                return self.text_end(at, sink);
            };
            let line = raw.line;
            if raw.percent {
                return Ok(Progress::Skipped { line });
            }
            if lines::proc_name(raw.text).is_some() {
                if !self.started && !self.siemens_level_ran(at, programs) {
                    // The PROC statement that opens this level: its parameters were bound by the call.
                    if let Err(k) = proc_params(proc_body(raw.text)) {
                        return Err(self.alarm_stop(sink, at.program, line, k));
                    }
                    return Ok(Progress::Skipped { line });
                }
                // The next PROC of the same text: this program has ended.
                self.cursor = at;
                return self.text_end(at, sink);
            }
            if interp_core::lang::fanuc::parse::skip_level(raw.text).is_some_and(|l| env.block_skip(l)) {
                return Ok(Progress::Skipped { line });
            }
            let mut pending = Pending::new();
            let mut args = CallArgs::new();
            let mut words = Words::EMPTY;
            let stmt = {
                let scope = Scope { vars: &self.siemens.vars, state: &self.state, cfg: &self.cfg };
                read(raw.text, line, &scope, &mut words, &mut pending, &mut args)
            };
            let stmt = match stmt {
                Ok(s) => s,
                Err(k) => return Err(self.alarm_stop(sink, at.program, line, k)),
            };
            let done = match stmt {
                Stmt::Nc { jump } if !words.is_empty() => {
                    return self.siemens_nc(at, text, &words, &pending, jump, programs, env, sink);
                }
                Stmt::Nc { jump: None } if pending.is_empty() => return Ok(Progress::Skipped { line }),
                Stmt::Nc { jump } => self.assignments(&pending, jump, at, text, programs),
                Stmt::Def(body) => {
                    if self.started {
                        Err(S::DefNotAtStart.into())
                    } else {
                        def::define(body, &mut self.siemens.vars, &self.state, &self.cfg)
                    }
                }
                Stmt::If { holds, jump } => {
                    if holds {
                        self.jump_to(jump, at, text, programs)
                    } else {
                        Ok(())
                    }
                }
                Stmt::Goto(jump) => self.jump_to(jump, at, text, programs),
                Stmt::Repeat { start, end, count, single } => {
                    self.repeat(start, end, count, single, at, text, programs)
                }
                Stmt::Call { name, list, passes } => {
                    return self.call(name, list, passes, &mut args, at, programs, env, sink);
                }
                Stmt::MCall { name, list } => self.set_mcall(name, list, &mut args, programs),
                Stmt::Proc(_) => Err(S::DefNotAtStart.into()),
                Stmt::Ret => {
                    self.siemens_return();
                    return Ok(Progress::Executed { line });
                }
            };
            if let Err(k) = done {
                return Err(self.alarm_stop(sink, at.program, line, k));
            }
            budget -= 1;
            if budget == 0 {
                return Ok(Progress::Yielded { line });
            }
        }
    }

    /// Whether the level whose text is at `at` has run a statement before `at`
    /// (a PROC line after statements ends the program: it begins the next one).
    fn siemens_level_ran<P: ProgramStore + ?Sized>(&self, at: Cursor, programs: &P) -> bool {
        let start = self.level_start(programs);
        let text = programs.text(at.program).unwrap_or(&[]);
        let mut cur = start;
        while cur.offset < at.offset {
            let Some(l) = next_line(text, &mut cur) else { break };
            if lines::has_statement(l.text) {
                return true;
            }
        }
        false
    }

    /// The first line of the program level being run.
    fn level_start<P: ProgramStore + ?Sized>(&self, programs: &P) -> Cursor {
        for f in self.calls.iter().rev() {
            match f.kind {
                Level::Proc { start, .. } => return start,
                Level::Fanuc => {
                    return programs.start(self.cursor.program).unwrap_or(Cursor::start(self.cursor.program));
                }
                Level::Repeat { .. } => {}
            }
        }
        programs.start(self.cursor.program).unwrap_or(Cursor::start(self.cursor.program))
    }

    /// The labels of the level being run.
    fn section<'t, P: ProgramStore + ?Sized>(&self, text: &'t [u8], programs: &P) -> Section<'t> {
        Section { text, start: self.level_start(programs) }
    }

    /// A REPEAT section whose end the cursor has reached: again, or back after
    /// the REPEAT.
    fn section_end(&mut self) {
        while let Some(f) = self.calls.last_mut() {
            let Level::Repeat { start, end } = f.kind else { return };
            if self.cursor.program != start.program || self.cursor.offset < end {
                return;
            }
            if f.repeats_left > 0 {
                f.repeats_left -= 1;
                self.cursor = start;
                return;
            }
            if let Some(f) = self.calls.pop() {
                self.cursor = f.ret;
            }
        }
    }

    /// M17, RET or the end of a subprogram: back to the caller (REPEAT sections
    /// of the level end with it; a pass still due starts the level again); in
    /// the main program the end. A block's M17 gets here through the
    /// interpreter (`Front::ret`).
    fn siemens_return(&mut self) {
        loop {
            let Some(f) = self.calls.last_mut() else {
                // M17/RET in the main program ends it.
                let _ = self.outbox.push_back(Canon { line: self.cmd.line, action: Action::End { rewind: false } });
                self.phase = Phase::Ended;
                return;
            };
            match f.kind {
                Level::Repeat { .. } => {
                    self.calls.pop();
                }
                Level::Proc { start, skip, .. } if f.repeats_left > 0 => {
                    f.repeats_left -= 1;
                    self.siemens.vars.leave();
                    self.siemens.vars.enter();
                    self.cursor = if skip == 0 {
                        start
                    } else {
                        Cursor { offset: start.offset + usize::from(skip), line: start.line + 1, ..start }
                    };
                    self.started = false;
                    return;
                }
                _ => {
                    let Some(f) = self.calls.pop() else { return };
                    if let Level::Proc { save, .. } = f.kind {
                        self.siemens.vars.leave();
                        if let Some(m) = self.siemens.saved.take().filter(|_| save) {
                            restore_modal(&mut self.state.modal, &m);
                        }
                    }
                    self.loops = f.loops;
                    self.cursor = f.ret;
                    self.started = true;
                    self.language = f.language;
                    return;
                }
            }
        }
    }

    /// The text of the program level ran out: a subprogram returns, a main
    /// program has ended without M02/M30 (alarm 5010; a stream waits for more).
    fn text_end<K: CanonSink + ?Sized>(&mut self, at: Cursor, sink: &mut K) -> Result<Progress, Alarm> {
        let _ = sink;
        if self.calls.iter().any(|f| !matches!(f.kind, Level::Repeat { .. })) {
            self.siemens_return();
            return Ok(Progress::Skipped { line: at.line });
        }
        if self.calls.is_empty() {
            return Err(self.end_of_record(at));
        }
        // A REPEAT section of the main program reaching the end of the text.
        self.section_end();
        if self.cursor.offset < at.offset || !self.calls.is_empty() {
            return Ok(Progress::Skipped { line: at.line });
        }
        Err(self.end_of_record(at))
    }

    /// An NC block: checked, run on the engine, its assignments written when it
    /// succeeded, then its jump and the modal call.
    #[allow(clippy::too_many_arguments)]
    fn siemens_nc<P, E, K>(
        &mut self,
        at: Cursor,
        text: &[u8],
        words: &Words,
        pending: &Pending<'_>,
        jump: Option<Jump<'_>>,
        programs: &P,
        env: &E,
        sink: &mut K,
    ) -> Result<Progress, Alarm>
    where
        P: ProgramStore + ?Sized,
        E: Environment,
        K: CanonSink + ?Sized,
    {
        let line = words.line;
        let extras = match check_into(words, &self.state, &self.cfg, &mut self.cmd) {
            Ok(e) => e,
            Err(k) => return Err(self.alarm_stop(sink, at.program, line, k)),
        };
        let to = match jump.map(|j| self.find_jump(j, at, text, programs)).transpose() {
            Ok(t) => t.flatten(),
            Err(k) => return Err(self.alarm_stop(sink, at.program, line, k)),
        };
        let moves = self.cmd.has_axes()
            && matches!(
                self.cmd.g.motion.unwrap_or(self.state.modal.motion),
                GCode::Rapid | GCode::Linear | GCode::ArcCw | GCode::ArcCcw
            )
            && self.cmd.g.one_shot.is_none();
        let then = After { pending: Some(pending), to, moves };
        self.run_block(at, line, None, extras, then, programs, env, sink)
    }

    /// Runs the command in `self.cmd` (an NC block, or the cycle call `spec`)
    /// as every block runs, and on success writes its assignments, follows its
    /// jump, arms MCALL after a move and delivers it. One copy of the engine's
    /// `run_cmd` for NC blocks and cycle calls alike.
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    fn run_block<P, E, K>(
        &mut self,
        at: Cursor,
        line: u32,
        spec: Option<CallSpec<'_>>,
        extras: Extras,
        then: After<'_, '_>,
        programs: &P,
        env: &E,
        sink: &mut K,
    ) -> Result<Progress, Alarm>
    where
        P: ProgramStore + ?Sized,
        E: Environment,
        K: CanonSink + ?Sized,
    {
        let program = self.program_text(at.program, programs);
        let r = self.run_cmd(env, Some(program), |me, flow| me.siemens_route(flow), spec, move |st| apply(extras, st));
        self.started = true;
        match r {
            Err(k) => Err(self.alarm_stop(sink, at.program, line, k)),
            Ok(next) => {
                if let Some(pending) = then.pending {
                    self.commit(pending);
                }
                if then.moves && self.siemens.mcall.is_some() && !self.in_modal_call() {
                    self.siemens.mcall_due = core::num::NonZeroU32::new(line.max(1));
                }
                match next {
                    Some(next) => {
                        if let (Next::Go, Some(to)) = (next, then.to) {
                            self.cursor = to;
                        }
                        self.go(next);
                    }
                    None => {
                        if let Some(v) = self.validating.as_mut() {
                            v.at = at;
                        }
                        return Ok(Progress::Yielded { line });
                    }
                }
                self.deliver(sink);
                Ok(Progress::Executed { line })
            }
        }
    }

    /// The program text SINUMERIK blocks of program `id` are read in.
    fn program_text<'p, P: ProgramStore + ?Sized>(&self, id: ProgramId, programs: &'p P) -> ProgramText<'p> {
        ProgramText {
            language: Language::Siemens,
            text: programs.text(id).unwrap_or(&[]),
            start: programs.start(id).unwrap_or(Cursor::start(id)),
            vars: None,
            fmt: Some(number_format(self.state.modal.units, &self.cfg)),
        }
    }

    /// Where a block's program flow leads in SINUMERIK: M17 returns.
    fn siemens_route(&self, flow: Flow) -> Result<Next, AlarmKind> {
        Ok(match flow {
            Flow::Continue => Next::Go,
            Flow::Stop => Next::Pause,
            Flow::End => Next::End,
            Flow::Return { .. } => Next::SiemensReturn,
            Flow::Language(l) => Next::Language(l),
            Flow::Call { .. } | Flow::Jump { .. } => {
                return Err(AlarmKind::NotSupportedYet { what: "M98/M91/M92 in SINUMERIK mode" });
            }
        })
    }

    /// Writes a block's assignments (checked when they were read).
    fn commit(&mut self, pending: &Pending<'_>) {
        for (t, v) in pending.each() {
            match t {
                Target::R(n) => {
                    let _ = self.siemens.vars.set_r(n, v.num().unwrap_or(0.0));
                }
                Target::Var(name) => {
                    let _ = self.siemens.vars.set(name, v);
                }
                Target::Zsd(i) => {
                    let x = round_i64(v.num().unwrap_or(0.0)).clamp(-32_768, 32_767);
                    if let Some(z) = self.state.cycle.zsd.get_mut(i) {
                        *z = x as i16;
                    }
                }
                Target::Tool { row, param } => self.write_tool(row, param, v),
            }
        }
    }

    /// `$TC_DPn[t,d]=v`: the offset row's datum (2 edge position, 3/4 lengths in
    /// X/Z, 6 radius, 12/13 wear of the lengths; others are accepted and unused).
    fn write_tool(&mut self, row: u16, param: u8, v: Value<'_>) {
        let Some(o) = self.cfg.tools.get_mut(row) else { return };
        let x = v.num().unwrap_or(0.0);
        let nm = round_i64(x * 1e6).clamp(-1_000_000_000_000_000, 1_000_000_000_000_000);
        match param {
            2 => o.tip = round_i64(x).clamp(0, 9) as u8,
            3 => o.x = nm,
            4 => o.z = nm,
            6 => o.radius = nm.abs(),
            12 => o.x_wear = nm,
            13 => o.z_wear = nm,
            _ => {}
        }
    }

    /// A line of assignments and/or a jump (no NC words).
    fn assignments<P: ProgramStore + ?Sized>(
        &mut self,
        pending: &Pending<'_>,
        jump: Option<Jump<'_>>,
        at: Cursor,
        text: &[u8],
        programs: &P,
    ) -> Result<(), AlarmKind> {
        let to = jump.map(|j| self.find_jump(j, at, text, programs)).transpose()?.flatten();
        self.commit(pending);
        if let Some(to) = to {
            self.cursor = to;
        }
        Ok(())
    }

    /// Where `jump` from the line at `at` goes (`None`: GOTOC without its label).
    fn find_jump<P: ProgramStore + ?Sized>(
        &self,
        jump: Jump<'_>,
        at: Cursor,
        text: &[u8],
        programs: &P,
    ) -> Result<Option<Cursor>, AlarmKind> {
        let sec = self.section(text, programs);
        match sec.jump(jump.dir, at, self.cursor, jump.label) {
            Some(c) => Ok(Some(c)),
            None if jump.dir == Dir::BothQuiet => Ok(None),
            None => Err(S::LabelNotFound.into()),
        }
    }

    fn jump_to<P: ProgramStore + ?Sized>(
        &mut self,
        jump: Jump<'_>,
        at: Cursor,
        text: &[u8],
        programs: &P,
    ) -> Result<(), AlarmKind> {
        if let Some(to) = self.find_jump(jump, at, text, programs)? {
            self.cursor = to;
        }
        Ok(())
    }

    /// REPEAT: the section from the start label to the end label (or to the
    /// first ENDLABEL after it, or to the line before the REPEAT), `count` times.
    #[allow(clippy::too_many_arguments)]
    fn repeat<P: ProgramStore + ?Sized>(
        &mut self,
        start: &[u8],
        end: Option<&[u8]>,
        count: u32,
        single: bool,
        at: Cursor,
        text: &[u8],
        programs: &P,
    ) -> Result<(), AlarmKind> {
        let sec = self.section(text, programs);
        let from = sec.anywhere(at, start).ok_or(AlarmKind::from(S::LabelNotFound))?;
        let stop = if single {
            labels::after_line(text, from).offset
        } else if let Some(e) = end {
            let last = sec.forward(from, e).ok_or(AlarmKind::from(S::LabelNotFound))?;
            labels::after_line(text, last).offset
        } else {
            let before = if from.offset < at.offset { at.offset } else { text.len() };
            match labels::end_label(text, from, before) {
                Some(e) => labels::after_line(text, e).offset,
                None => before,
            }
        };
        if self.calls.is_full() {
            return Err(S::SubprogramLevels.into());
        }
        let frame = Frame {
            ret: self.cursor,
            loops: heapless::Vec::new(),
            repeats_left: u16::try_from(count.saturating_sub(1)).unwrap_or(u16::MAX),
            language: self.language,
            entry: Entry::Subprogram(Caller::Program),
            off: self.codes_off,
            kind: Level::Repeat { start: from, end: stop },
        };
        let _ = self.calls.push(frame);
        self.cursor = from;
        Ok(())
    }

    /// Whether a level opened by MCALL is running.
    fn in_modal_call(&self) -> bool {
        self.calls.iter().any(|f| matches!(f.kind, Level::Proc { modal_call: true, .. }))
    }

    /// A call by name: a subprogram of the program store (its PROC parameters
    /// bound), else a standard cycle, else alarm 14011.
    #[allow(clippy::too_many_arguments)]
    fn call<P, E, K>(
        &mut self,
        name: &[u8],
        list: bool,
        passes: u32,
        args: &mut CallArgs,
        at: Cursor,
        programs: &P,
        env: &E,
        sink: &mut K,
    ) -> Result<Progress, Alarm>
    where
        P: ProgramStore + ?Sized,
        E: Environment,
        K: CanonSink + ?Sized,
    {
        let line = at.line;
        let r = if let Some(entry) = programs.find_named(name) {
            self.enter_proc(entry, args, list, passes, false, programs)
        } else if let Some(sig) = crate::cycles::signature(name) {
            if passes != 1 {
                Err(S::SyntaxError { what: "P (passes) with a cycle" }.into())
            } else {
                match args.bind(sig.types()) {
                    Ok(()) if crate::cycles::is_pattern(sig.name) => return self.start_pattern(sig, args, at, sink),
                    #[cfg(feature = "mill-island")]
                    Ok(()) if matches!(sig.name, "CYCLE74" | "CYCLE75") => self.pocket_contour(sig, args, at, programs),
                    #[cfg(feature = "mill-island")]
                    Ok(()) if sig.name == "CYCLE73" && predrills(args) => {
                        return self.start_predrill(args, at, programs, env, sink);
                    }
                    Ok(()) => return self.cycle(sig, args, at, line, programs, env, sink),
                    Err(k) => Err(k),
                }
            }
        } else {
            Err(S::SubprogramNotFound.into())
        };
        match r {
            Ok(()) => Ok(Progress::Executed { line }),
            Err(k) => Err(self.alarm_stop(sink, at.program, line, k)),
        }
    }

    /// Opens a subprogram level at `entry` (where the named program begins):
    /// its PROC statement's parameters are bound to `args` and defined.
    fn enter_proc<P: ProgramStore + ?Sized>(
        &mut self,
        entry: Cursor,
        args: &mut CallArgs,
        list: bool,
        passes: u32,
        modal_call: bool,
        programs: &P,
    ) -> Result<(), AlarmKind> {
        let text = programs.text(entry.program).ok_or(AlarmKind::from(S::SubprogramNotFound))?;
        let (proc_line, body, proc) = bind_proc(text, entry, args, list)?;
        if passes > 1 && proc.as_ref().is_some_and(|p| !p.params.is_empty()) {
            return Err(S::SyntaxError { what: "P (passes) with a subprogram that has parameters" }.into());
        }
        if self.calls.is_full() {
            return Err(S::SubprogramLevels.into());
        }
        let save = proc.as_ref().is_some_and(|p| p.save);
        if save && self.siemens.saved.is_some() {
            return Err(AlarmKind::NotSupportedYet { what: "PROC … SAVE called from a PROC … SAVE" });
        }
        let frame = Frame {
            ret: self.cursor,
            loops: core::mem::take(&mut self.loops),
            repeats_left: u16::try_from(passes.saturating_sub(1)).unwrap_or(u16::MAX),
            language: self.language,
            entry: Entry::Subprogram(Caller::Program),
            off: self.codes_off,
            kind: Level::Proc {
                start: proc_line.unwrap_or(entry),
                skip: u16::try_from(body.offset - proc_line.map_or(body.offset, |c| c.offset)).unwrap_or(0),
                save,
                modal_call,
            },
        };
        let _ = self.calls.push(frame);
        self.siemens.vars.enter();
        if let Some(p) = &proc
            && let Err(k) = p.define_params(&mut self.siemens.vars, args)
        {
            self.siemens.vars.leave();
            if let Some(f) = self.calls.pop() {
                self.loops = f.loops;
            }
            return Err(k);
        }
        if save {
            self.siemens.saved = Some(self.state.modal);
        }
        self.cursor = body;
        self.started = false;
        self.language = Language::Siemens;
        Ok(())
    }

    /// MCALL name(args): bound now, called after every block that moves an
    /// axis; MCALL alone cancels it. Not inside a modally called subprogram.
    fn set_mcall<P: ProgramStore + ?Sized>(
        &mut self,
        name: Option<&[u8]>,
        list: bool,
        args: &mut CallArgs,
        programs: &P,
    ) -> Result<(), AlarmKind> {
        if self.in_modal_call() {
            return Err(S::ModalCallNested.into());
        }
        let Some(name) = name else {
            self.siemens.mcall = None;
            return Ok(());
        };
        let callee = if let Some(entry) = programs.find_named(name) {
            let text = programs.text(entry.program).unwrap_or(&[]);
            bind_proc(text, entry, args, list)?;
            Callee::Proc(entry)
        } else if let Some(sig) = crate::cycles::signature(name) {
            args.bind(sig.types())?;
            Callee::Cycle(sig)
        } else {
            return Err(S::SubprogramNotFound.into());
        };
        self.siemens.mcall = Some(ModalCall { callee, args: args.clone(), list });
        Ok(())
    }

    /// The modal call after the block on `line` moved an axis.
    fn modal_call<P, E, K>(&mut self, line: u32, programs: &P, env: &E, sink: &mut K) -> Result<Progress, Alarm>
    where
        P: ProgramStore + ?Sized,
        E: Environment,
        K: CanonSink + ?Sized,
    {
        let Some(mc) = self.siemens.mcall.clone() else { return Ok(Progress::Skipped { line }) };
        let at = Cursor { line, ..self.cursor };
        let mut args = mc.args;
        match mc.callee {
            Callee::Cycle(sig) => self.cycle(sig, &args, at, line, programs, env, sink),
            Callee::Proc(entry) => match self.enter_proc(entry, &mut args, mc.list, 1, true, programs) {
                Ok(()) => Ok(Progress::Executed { line }),
                Err(k) => Err(self.alarm_stop(sink, at.program, line, k)),
            },
        }
    }

    /// HOLES1, HOLES2 or CYCLE801 called on `at`: its parameters checked (an
    /// alarm moves nothing), its holes laid out; the holes are approached by
    /// [`Driver::pattern_hole`], one per step. Without a modal call: message 62100
    /// and a stop; NC start positions the pattern without drilling (lines 3095-3101).
    fn start_pattern<K: CanonSink + ?Sized>(
        &mut self,
        sig: &'static Signature,
        args: &CallArgs,
        at: Cursor,
        sink: &mut K,
    ) -> Result<Progress, Alarm> {
        let line = at.line;
        let mut buf = [Arg::Empty; interp_core::lang::siemens::call::MAX_ARGS];
        let laid = crate::cycles::hole_pattern(sig.name, args.args(&mut buf), &self.state, &self.cfg, line);
        let pattern = match laid {
            Err(k) => return Err(self.alarm_stop(sink, at.program, line, k)),
            Ok(p) => p,
        };
        self.started = true;
        match pattern {
            Ok(p) => {
                self.siemens.begin_pattern(p, self.calls.len());
                if self.siemens.mcall.is_none() || self.in_modal_call() {
                    return Ok(self.notice(crate::cycles::Notice::NoDrillingCycle, line));
                }
                Ok(Progress::Executed { line })
            }
            Err(n) => Ok(self.notice(n, line)),
        }
    }

    /// A cycle message (62xxx) on `line`: kept for the display, the program
    /// stopped until NC start (cycle start), as the clear key and NC start of an
    /// 840D (lines 3099-3101).
    fn notice(&mut self, n: crate::cycles::Notice, line: u32) -> Progress {
        self.siemens.notice = Some((n.code(), line));
        self.phase = Phase::Paused;
        Progress::Paused
    }

    /// The next hole of the drilling pattern being run: G0 to it in the plane
    /// (the caller's motion mode kept), the modal call armed after it. `None`
    /// when no pattern is running (or it has just finished).
    fn pattern_hole<P, E, K>(&mut self, programs: &P, env: &E, sink: &mut K) -> Option<Result<Progress, Alarm>>
    where
        P: ProgramStore + ?Sized,
        E: Environment,
        K: CanonSink + ?Sized,
    {
        if self.siemens.pattern.is_none() || self.calls.len() != self.siemens.pattern_depth {
            return None;
        }
        let pattern = self.siemens.pattern.as_mut()?;
        let line = pattern.line;
        let Some((u, v)) = pattern.advance() else {
            self.siemens.end_pattern();
            return None;
        };
        let [a, o, _] = crate::cycles::plane_axes(self.state.modal.plane);
        self.cmd = Command::EMPTY;
        self.cmd.line = line;
        self.cmd.g.motion = Some(GCode::Rapid);
        self.cmd.axes[a.index()] = Some(interp_core::command::AxisWord { value: u, incremental: false });
        self.cmd.axes[o.index()] = Some(interp_core::command::AxisWord { value: v, incremental: false });
        let motion = self.state.modal.motion;
        let at = Cursor { line, ..self.cursor };
        let then = After { pending: None, to: None, moves: true };
        let r = self.run_block(at, line, None, Extras::default(), then, programs, env, sink);
        self.state.modal.motion = motion;
        if r.is_err() {
            self.siemens.end_pattern();
        }
        Some(r)
    }

    /// A standard cycle call as a block of its own: its contour resolved, then
    /// run, validated and delivered as every cycle block.
    #[allow(clippy::too_many_arguments)]
    fn cycle<P, E, K>(
        &mut self,
        sig: &'static Signature,
        args: &CallArgs,
        at: Cursor,
        line: u32,
        programs: &P,
        env: &E,
        sink: &mut K,
    ) -> Result<Progress, Alarm>
    where
        P: ProgramStore + ?Sized,
        E: Environment,
        K: CanonSink + ?Sized,
    {
        self.cmd = Command::EMPTY;
        self.cmd.line = line;
        self.cmd.g.one_shot = Some(GCode::CycleCall);
        let contour = match self.contour_of(sig, args, at, programs) {
            Ok(c) => c,
            Err(k) => return Err(self.alarm_stop(sink, at.program, line, k)),
        };
        // CYCLE73: the edge is its contour, the islands go with the call.
        #[cfg(feature = "mill-island")]
        let mut islands = Islands::new();
        #[cfg(feature = "mill-island")]
        let contour = match sig.name {
            "CYCLE73" => match self.pocket_contours(at, programs, &mut islands) {
                Ok(edge) => Some(edge),
                Err(k) => return Err(self.alarm_stop(sink, at.program, line, k)),
            },
            _ => contour,
        };
        let spec = CallSpec {
            sig,
            front: &SINUMERIK,
            args,
            contour,
            #[cfg(feature = "mill-island")]
            islands: &islands,
        };
        let then = After { pending: None, to: None, moves: false };
        self.run_block(at, line, Some(spec), Extras::default(), then, programs, env, sink)
    }

    /// The contour a cycle's contour parameter names: `"NAME"` (a subprogram: its
    /// blocks after the PROC line), `"START:END"` (labels of the calling program),
    /// `"/_N_…_SPF:START:END"` (labels or block numbers of that program); for
    /// CYCLE950 an empty `_NP1` with `_NP2`/`_NP3` labels of the calling program.
    fn contour_of<'p, P: ProgramStore + ?Sized>(
        &self,
        sig: &Signature,
        args: &CallArgs,
        at: Cursor,
        programs: &'p P,
    ) -> Result<Option<ContourAt<'p>>, AlarmKind> {
        let Some(i) = sig.contour_param() else { return Ok(None) };
        let Arg::Str(spec) = args.get(i) else { return Ok(None) };
        let spec = trim(spec);
        let (prog, start, end): (&[u8], &[u8], &[u8]) = if spec.is_empty() {
            match (sig.param("_NP2").map(|k| args.get(k)), sig.param("_NP3").map(|k| args.get(k))) {
                (Some(Arg::Str(s)), Some(Arg::Str(e))) if !trim(s).is_empty() => (&[], trim(s), trim(e)),
                _ => return Ok(None),
            }
        } else {
            let mut parts = spec.splitn(3, |&c| c == b':');
            let a = parts.next().unwrap_or(&[]);
            match (parts.next(), parts.next()) {
                (None, _) => (a, &[], &[]),
                (Some(b), None) => (&[], a, b),
                (Some(b), Some(c)) => (a, b, c),
            }
        };
        self.contour_at(prog, start, end, at, programs).map(Some)
    }

    /// The contour in program `prog` (empty: the calling program, at `at`) from
    /// label or block number `start` to `end` (empty `start`: the whole
    /// subprogram `prog`).
    fn contour_at<'p, P: ProgramStore + ?Sized>(
        &self,
        prog: &[u8],
        start: &[u8],
        end: &[u8],
        at: Cursor,
        programs: &'p P,
    ) -> Result<ContourAt<'p>, AlarmKind> {
        let (id, text, level_start) = if prog.is_empty() {
            let text = programs.text(at.program).unwrap_or(&[]);
            (at.program, text, self.level_start(programs))
        } else {
            let name = program_name(prog);
            let entry = programs.find_named(name).ok_or(AlarmKind::from(S::SubprogramNotFound))?;
            let text = programs.text(entry.program).ok_or(AlarmKind::from(S::SubprogramNotFound))?;
            (entry.program, text, entry)
        };
        let program = ProgramText {
            language: Language::Siemens,
            text,
            start: programs.start(id).unwrap_or(level_start),
            vars: None,
            fmt: Some(number_format(self.state.modal.units, &self.cfg)),
        };
        if start.is_empty() {
            // A whole subprogram: its blocks after the PROC line.
            let (_, body) = find_proc_line(text, level_start);
            return Ok(ContourAt { program, start: body, end: None });
        }
        let sec = Section { text, start: level_start };
        let s = sec.anywhere(if prog.is_empty() { at } else { level_start }, start);
        let s = s.ok_or(AlarmKind::from(S::LabelNotFound))?;
        let e = sec.forward(s, end).ok_or(AlarmKind::from(S::LabelNotFound))?;
        Ok(ContourAt { program, start: s, end: Some(e) })
    }

    /// CYCLE74 (the pocket's edge: the transfer starts again) or CYCLE75 (one
    /// more island): the contour `_KNAME`/`_LSANF`/`_LSEND` names must be there
    /// (14080/12..., the labels' alarms); its names are kept for CYCLE73 (seed 001
    /// lines 6161-6204). Nothing named: 61983 (edge) or 61980 (island); CYCLE75
    /// before CYCLE74 61900; a 16th contour 61906.
    #[cfg(feature = "mill-island")]
    fn pocket_contour<P: ProgramStore + ?Sized>(
        &mut self,
        sig: &Signature,
        args: &CallArgs,
        at: Cursor,
        programs: &P,
    ) -> Result<(), AlarmKind> {
        let island = |code| AlarmKind::from(CycleAlarm::IslandPocket { code });
        let edge = sig.name == "CYCLE74";
        let mut buf = [Arg::Empty; interp_core::lang::siemens::call::MAX_ARGS];
        let a = args.args(&mut buf);
        let text = |i: usize| match a.get(i) {
            Some(Arg::Str(s)) => trim(s),
            _ => &[],
        };
        let (name, start, end) = (text(0), text(1), text(2));
        if name.is_empty() && start.is_empty() {
            return Err(island(if edge { 61983 } else { 61980 }));
        }
        self.contour_at(name, start, end, at, programs)?;
        let long = |_| AlarmKind::from(S::StringTooLong);
        let kept = PocketContour {
            name: heapless::Vec::from_slice(name).map_err(long)?,
            start: heapless::Vec::from_slice(start).map_err(long)?,
            end: heapless::Vec::from_slice(end).map_err(long)?,
        };
        let pocket = &mut self.siemens.pocket;
        if edge {
            pocket.clear();
        } else if pocket.is_empty() {
            return Err(island(61900));
        }
        pocket.push(kept).map_err(|_| island(61906))
    }

    /// CYCLE73 pre-drilling (`_VARI` units 5, lines 6560-6588): the insertion
    /// points of the clearing its parameters describe, each approached with G0
    /// and drilled by the modal drilling cycle (MCALL) as a drilling pattern's
    /// holes; without one, message 62100 and the points only approached.
    #[cfg(feature = "mill-island")]
    fn start_predrill<P, E, K>(
        &mut self,
        args: &CallArgs,
        at: Cursor,
        programs: &P,
        env: &E,
        sink: &mut K,
    ) -> Result<Progress, Alarm>
    where
        P: ProgramStore + ?Sized,
        E: Environment,
        K: CanonSink + ?Sized,
    {
        let line = at.line;
        let pattern = match self.insertion_points(args, at, programs, env) {
            Ok(p) => p,
            Err(k) => return Err(self.alarm_stop(sink, at.program, line, k)),
        };
        self.started = true;
        self.siemens.begin_pattern(pattern, self.calls.len());
        if self.siemens.mcall.is_none() || self.in_modal_call() {
            return Ok(self.notice(crate::cycles::Notice::NoDrillingCycle, line));
        }
        Ok(Progress::Executed { line })
    }

    /// The insertion points of the pre-drilling CYCLE73 at `at` as a drilling
    /// pattern: the transferred contours read in the plane (61900 without them),
    /// the call checked, more points than a pattern lists 61911.
    #[cfg(feature = "mill-island")]
    fn insertion_points<'p, P, E>(
        &self,
        args: &CallArgs,
        at: Cursor,
        programs: &'p P,
        env: &E,
    ) -> Result<interp_core::cycles::holes::HolePattern, AlarmKind>
    where
        P: ProgramStore + ?Sized,
        E: Environment,
    {
        use interp_core::cycles::{Executor, mill::read_pocket, profile::Profile};
        use interp_core::lang::siemens::call::ContourSource;
        let mut islands = Islands::new();
        let edge = self.pocket_contours(at, programs, &mut islands)?;
        let mut buf = [Arg::Empty; interp_core::lang::siemens::call::MAX_ARGS];
        let spec = crate::cycles::predrill(args.args(&mut buf), &self.state, &self.cfg)?;
        let vars = &self.siemens.vars;
        let src = |c: &ContourAt<'p>| ContourSource {
            program: c.program,
            start: c.start,
            end: c.end,
            vars,
            front: &SINUMERIK,
        };
        let mut profile = Profile::default();
        let execute = <interp_core::exec::Blocks as Executor>::execute;
        let shape =
            read_pocket(&src(&edge), islands.iter().map(src), &self.state, &self.cfg, env, execute, &mut profile)?;
        let points = mill_paths::island::start_points(&spec, &shape.edge, &shape.island_refs())?;
        interp_core::cycles::holes::HolePattern::listed(&points, at.line)
            .ok_or(AlarmKind::from(CycleAlarm::IslandPocket { code: 61911 }))
    }

    /// The contours CYCLE74/CYCLE75 transferred, found again for the CYCLE73 at
    /// `at`: the edge (61900 without a CYCLE74), the islands into `islands`.
    #[cfg(feature = "mill-island")]
    fn pocket_contours<'p, P: ProgramStore + ?Sized>(
        &self,
        at: Cursor,
        programs: &'p P,
        islands: &mut Islands<'p>,
    ) -> Result<ContourAt<'p>, AlarmKind> {
        let mut all = self.siemens.pocket.iter().map(|c| self.contour_at(&c.name, &c.start, &c.end, at, programs));
        let edge = all.next().ok_or(AlarmKind::from(CycleAlarm::IslandPocket { code: 61900 }))??;
        for c in all {
            islands.push(c?).map_err(|_| AlarmKind::from(CycleAlarm::IslandPocket { code: 61906 }))?;
        }
        Ok(edge)
    }
}

/// Blanks around a string argument (`"KONTUR_1 "` as the document prints it).
fn trim(s: &[u8]) -> &[u8] {
    let a = s.iter().position(|c| !c.is_ascii_whitespace()).unwrap_or(s.len());
    let b = s.iter().rposition(|c| !c.is_ascii_whitespace()).map_or(a, |i| i + 1);
    &s[a..b]
}

/// The program name in `/_N_SPF_DIR/_N_KONTUR_1_SPF` (or a plain name).
fn program_name(path: &[u8]) -> &[u8] {
    let last = path.rsplit(|&c| c == b'/').next().unwrap_or(path);
    let last = last.strip_prefix(b"_N_").unwrap_or(last);
    for ext in [b"_SPF", b"_MPF"] {
        if last.len() > 4 && last[last.len() - 4..].eq_ignore_ascii_case(ext) {
            return &last[..last.len() - 4];
        }
    }
    last
}

/// The text of a PROC line after its keyword.
fn proc_body(line: &[u8]) -> &[u8] {
    let i = lines::after_block_number(line);
    line.get(i + 4..).unwrap_or(&[])
}

/// The PROC statement of the program beginning at `entry` in `text` (its line,
/// the cursor after it, its parameters; without one `entry` twice), with `args`
/// bound to its parameters (a call with a list needs a PROC: 14510).
#[allow(clippy::type_complexity)]
fn bind_proc<'t>(
    text: &'t [u8],
    entry: Cursor,
    args: &mut CallArgs,
    list: bool,
) -> Result<(Option<Cursor>, Cursor, Option<Proc<'t>>), AlarmKind> {
    let (proc_line, body) = find_proc_line(text, entry);
    let proc = match proc_line {
        Some(c) => {
            let mut cur = c;
            let l = next_line(text, &mut cur).map(|l| l.text).unwrap_or(&[]);
            Some(proc_params(proc_body(l))?)
        }
        None => None,
    };
    match &proc {
        Some(p) => args.bind(p.types())?,
        None if list && !args.is_empty() => return Err(S::ProcMissing.into()),
        None => {}
    }
    Ok((proc_line, body, proc))
}

/// The PROC line of the program beginning at `entry` (before its first
/// statement), and the cursor after it (or `entry` if it has none).
fn find_proc_line(text: &[u8], entry: Cursor) -> (Option<Cursor>, Cursor) {
    let mut cur = entry;
    loop {
        let at = cur;
        let Some(l) = next_line(text, &mut cur) else { return (None, entry) };
        if lines::proc_name(l.text).is_some() {
            return (Some(at), cur);
        }
        if lines::has_statement(l.text) {
            return (None, entry);
        }
    }
}

/// PROC … SAVE at the return: the modal G functions as they were at the call
/// (compensation, cycles and polygon turning stay as the subprogram left them).
fn restore_modal(m: &mut Modal, saved: &Modal) {
    m.motion = saved.motion;
    m.plane = saved.plane;
    m.units = saved.units;
    m.incremental = saved.incremental;
    m.feed_mode = saved.feed_mode;
    m.css = saved.css;
    m.work_frame = saved.work_frame;
    m.exact_stop_mode = saved.exact_stop_mode;
    m.diameter = saved.diameter;
}

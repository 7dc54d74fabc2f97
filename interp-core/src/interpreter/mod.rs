//! The interpreter driver: at most one NC block and a bounded number of macro
//! statements per [`Interpreter::step`], so a firmware task stays responsive (even
//! in an endless macro loop) and a full motion queue applies back-pressure.
//!
//! Each step first delivers actions still waiting in the outbox; only when the
//! outbox is empty does it read, check and execute the next block. A block runs on
//! the state in place and is undone (from a small saved copy) unless it succeeded — including the
//! lookup of a subprogram or jump target — so an alarm leaves the state exactly as
//! it was.
//!
//! Control flow: GOTO, IF…GOTO, M91/M92 and M99 P move the cursor within a program;
//! M98 pushes a frame (12 levels, 3.1.6) holding the return cursor and the
//! caller's open loops; WHILE/DO push a loop entry (3 per level) whose END is found
//! when the loop is entered, so a jump out of the range closes it. A frame also
//! says how its program was entered ([`Entry`]): a FANUC macro call (G65, G66, a G
//! or M code; [`macro_calls`]) starts a level of local variables that M99 ends.
//!
//! Two languages step their statements here and share the engine: the FANUC
//! dialect (this file) and SINUMERIK ([`siemens`]: labels, PROC calls, REPEAT
//! sections, MCALL, cycle calls). Both hand a checked [`Command`] to the same
//! block execution (`run_cmd`: staging, undo, cycle delivery and validation, the
//! outbox) and share one call stack, whose frames record the caller's language.

// The SINUMERIK front end's state and frames (its driver is the interp-siemens
// crate, which reaches them here).
#[doc(hidden)]
pub mod siemens;

use crate::alarm::{Alarm, AlarmKind};
use crate::axis::Pos;
use crate::canon::CanonSink;
use crate::command::Command;
use crate::config::{MachineConfig, Param};
use crate::cycles::{CycleStage, DryRun, Expansion};
use crate::env::{Environment, Panel};
use crate::exec::execute;
use crate::lang::fanuc::calls::{CallCodes, CallRead, Caller, Calls, ModalCalls};
use crate::lang::fanuc::check::check_into;
use crate::lang::fanuc::macros::find_loop_end;
use crate::lang::fanuc::macros::{MacroStatement, Variables};
use crate::lang::fanuc::parse::{Block, MacroBlock, Read, read_program_block, skip_level};
use crate::lang::{Language, ProgramText};
use crate::modal::State;
use crate::program::{Cursor, ProgramId, ProgramStore, next_block};
use crate::stage::{Flow, Outbox, Staged};
use crate::units::NumberFormat;

mod macro_calls;

/// Subprogram nesting: the main program may call 12 levels deep (3.1.6).
pub const MAX_CALL_DEPTH: usize = 12;

/// Open DO ranges per program level: loop numbers 1–3 (2.24.2 note 3).
pub const MAX_LOOP_DEPTH: usize = 3;

/// Macro statements one [`Interpreter::step`] runs at most before it returns
/// [`Progress::Yielded`], unless [`Interpreter::set_step_budget`] says otherwise.
///
/// Measured (read + evaluate + execute, text parsed every time): on the host
/// 0.2–0.5 µs a statement (`cargo run --release -p host-tests --example
/// macro_bench`); on the Cortex-M4 with software f64, 1 600 instructions to read
/// `#2=#1+1` up to 13 300 for `IF [#1 GT 5] THEN #[10+[#1 MOD 5]]=ATAN[#1]/[3]`
/// (`m4-tests/bench.sh bench_macro`). A step of 32 counter-loop statements is
/// ~56 000 instructions (≈0.35 ms at 168 MHz), 32 function-heavy ones at most
/// ~0.45 M (≈2.7 ms): a firmware task regains control within milliseconds even in
/// an endless `DO1 … END1`.
pub const DEFAULT_STEP_BUDGET: u16 = 32;

/// What a step did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Progress {
    /// Executed the NC block on `line` (after any macro statements before it); its
    /// actions are delivered or waiting.
    Executed {
        /// Source line.
        line: u32,
    },
    /// Passed over a blank, comment-only, record-mark or skipped (`/`) block.
    Skipped {
        /// Source line.
        line: u32,
    },
    /// Ran the step budget of macro statements, the last on `line`, without
    /// reaching an NC block: call again.
    Yielded {
        /// Source line of the last statement run.
        line: u32,
    },
    /// The sink is full; call again when it has room.
    Blocked,
    /// Stopped by M00/M01; call [`Interpreter::cycle_start`] to go on.
    Paused,
    /// The program has ended (M02/M30, or after an end-of-record alarm).
    Ended,
}

/// Where the run is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[doc(hidden)]
pub enum Phase {
    Running,
    Paused,
    Ended,
}

/// An open DO range.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[doc(hidden)]
pub struct Loop {
    /// Loop number 1–3.
    label: u8,
    /// The WHILE/DO block (END comes back here).
    start: Cursor,
    /// Just after the END block (a false WHILE goes on here).
    end: Cursor,
}

/// The open loops of one program level.
#[doc(hidden)]
pub type Loops = heapless::Vec<Loop, MAX_LOOP_DEPTH>;

/// How a program level was entered: what its return gives back. (Two bytes: a
/// [`Next`] that carries one stays as small as before.)
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[doc(hidden)]
pub enum Entry {
    /// M98 (`Caller::Program`), or a subprogram call by an M or T code
    /// (`Caller::Subprogram`): the caller's local variables go on.
    Subprogram(Caller),
    /// A FANUC macro call — G65, a G or M code — with a new level of local
    /// variables #1–#33.
    Macro(Caller),
    /// The G66 modal call `i` after a move: a macro call too.
    Modal(u8),
}

/// A subprogram call in progress.
#[derive(Clone, Debug)]
#[doc(hidden)]
pub struct Frame {
    /// The block after the M98 in the caller.
    pub ret: Cursor,
    /// The caller's open loops.
    pub loops: Loops,
    /// Runs of the subprogram still to come after the current one (M98 L/packed P).
    pub repeats_left: u16,
    /// The caller's language, in force again after the return.
    pub language: Language,
    /// What kind of level the frame opened (a FANUC M98, a SINUMERIK PROC call or
    /// REPEAT section).
    pub kind: siemens::Level,
    /// How the program was entered.
    pub entry: Entry,
    /// The code calls the caller's level had switched off (FANUC: see
    /// [`Caller::switches_off`]).
    pub off: u8,
}

/// What a cycle block hands the interpreter besides its expansion (see
/// [`Interpreter::commit_cycle`]).
#[derive(Clone, Debug, Default)]
struct BlockCycle {
    split: usize,
    writes: heapless::Vec<(crate::stage::Setting, i64), 8>,
    resume: Option<Cursor>,
}

/// A cycle block executed but not yet committed: its dry run goes on a chunk per
/// step ([`DryRun::run`] along the expansion in `Interpreter::cycle`); the block
/// commits when it ends without an alarm.
#[derive(Clone, Debug)]
#[doc(hidden)]
pub struct Validating {
    /// The block's state, to be settled by the dry run's end.
    state: State,
    /// What else the block hands over.
    block: BlockCycle,
    /// Where the program goes after the block.
    next: Next,
    /// The dry run's copy of what the expansion (`Interpreter::cycle`, which
    /// stays as it is until the block commits) moves on.
    dry: DryRun,
    /// Program and line of the cycle block, for alarms.
    pub at: Cursor,
    line: u32,
}

/// Where the program goes after a block, decided (and checked) before the block
/// is committed, so a failed call or jump leaves everything as it was.
#[derive(Clone, Copy, Debug)]
#[doc(hidden)]
pub enum Next {
    Go,
    Pause,
    End,
    /// Into a called program (a call by T code finds its value for #149 in the
    /// block's command).
    Call {
        start: Cursor,
        repeats: u16,
        entry: Entry,
    },
    Return {
        to: Option<Cursor>,
    },
    Repeat {
        start: Cursor,
    },
    Restart {
        start: Cursor,
    },
    Jump {
        to: Cursor,
    },
    Language(Language),
    /// SINUMERIK M17/RET: back to the caller (in a main program: the end).
    #[cfg_attr(not(feature = "siemens"), allow(dead_code))]
    SiemensReturn,
}

/// The lathe interpreter.
///
/// Not `repr(C)`: with a fixed field order the compiler built the ~29 KB value on
/// the boot task's stack (firmware::shell::build's frame 27 KB, stack-bound.py's
/// boot-path gate) and a plain G01 took 14 instructions more on the Cortex-M4
/// than with the compiler's own order.
#[derive(Debug)]
pub struct Interpreter {
    #[doc(hidden)]
    pub phase: Phase,
    /// The language blocks are read in now (the machine's at power-on and reset;
    /// `G290`/`G291` switch it).
    #[doc(hidden)]
    pub language: Language,
    /// A block other than `%`/`O` has been executed in the current program level
    /// (a later `%` or `O` ends the record).
    #[doc(hidden)]
    pub started: bool,
    /// Whether `cursor` has been set to the main program's start.
    positioned: bool,
    #[doc(hidden)]
    pub budget: u16,
    /// The program a run starts with.
    main: ProgramId,
    #[doc(hidden)]
    pub cursor: Cursor,
    /// Where the block the last step read (or failed to read) begins.
    #[doc(hidden)]
    pub last_block: Cursor,
    /// A held move that nose compensation found faulty while the failed block ran
    /// (its line), for [`Interpreter::alarm_stop`].
    fault_line: Option<u32>,
    /// The stream (program 0) is still arriving ([`ProgramStore::still_arriving`],
    /// read at each step): an alarm that only means its text has not come yet
    /// leaves the look-ahead holding, as the board waits for the text.
    stream_open: bool,
    /// The code calls the level in force switches off ([`Caller::switches_off`]).
    #[doc(hidden)]
    pub codes_off: u8,
    /// The block being read, reused from block to block.
    block: Block,
    /// The block checked, reused from block to block.
    #[doc(hidden)]
    pub cmd: Command,
    #[doc(hidden)]
    pub state: State,
    /// Actions waiting for the sink; also where a block stages its actions.
    #[doc(hidden)]
    pub outbox: Outbox,
    #[doc(hidden)]
    pub cfg: MachineConfig,
    #[doc(hidden)]
    pub loops: Loops,
    #[doc(hidden)]
    pub calls: heapless::Vec<Frame, MAX_CALL_DEPTH>,
    /// The canned cycle being delivered (see [`crate::cycles`]).
    #[doc(hidden)]
    pub cycle: Option<Expansion>,
    /// A cycle block whose dry run is still going on.
    #[doc(hidden)]
    pub validating: Option<Validating>,
    /// The codes that call programs at the level in force, and the macro call
    /// block just read with its arguments (`#1–#33` of the level it starts).
    macro_calls: Calls,
    /// The G66 modal calls in force.
    modal: ModalCalls,
    #[doc(hidden)]
    pub vars: Variables,
    /// The SINUMERIK front end's state: variables, the block's words, MCALL.
    #[doc(hidden)]
    pub siemens: siemens::Front,
}

/// The machine configuration of an [`Interpreter`], borrowed to be changed (see
/// [`Interpreter::config_mut`]).
pub struct ConfigMut<'a> {
    interp: &'a mut Interpreter,
}

impl core::ops::Deref for ConfigMut<'_> {
    type Target = MachineConfig;
    fn deref(&self) -> &MachineConfig {
        &self.interp.cfg
    }
}

impl core::ops::DerefMut for ConfigMut<'_> {
    fn deref_mut(&mut self) -> &mut MachineConfig {
        &mut self.interp.cfg
    }
}

impl Drop for ConfigMut<'_> {
    fn drop(&mut self) {
        self.interp.refresh_codes();
    }
}

impl Interpreter {
    /// A powered-on interpreter for machine `cfg`, axes at machine zero, all
    /// variables null, running program 0 (see [`Interpreter::select_main`]).
    pub fn new(cfg: MachineConfig) -> Self {
        let state = State::power_on(&cfg, Pos::ZERO);
        let language = cfg.language;
        // The codes are computed before the literal, which is returned as it is:
        // a value passed through a `self`-taking method would be built on the stack
        // and copied (the board builds its controller in place, see
        // `Controller::new_in`).
        let codes = CallCodes::of(&cfg.params, 0);
        Interpreter {
            cfg,
            state,
            cursor: Cursor::start(0),
            positioned: false,
            main: 0,
            outbox: heapless::Deque::new(),
            block: Block::default(),
            cmd: Command::EMPTY,
            phase: Phase::Running,
            language,
            started: false,
            vars: Variables::new(),
            calls: heapless::Vec::new(),
            loops: heapless::Vec::new(),
            budget: DEFAULT_STEP_BUDGET,
            cycle: None,
            validating: None,
            last_block: Cursor::start(0),
            fault_line: None,
            stream_open: false,
            siemens: siemens::Front::new(),
            macro_calls: Calls { codes, read: CallRead::EMPTY },
            modal: ModalCalls::default(),
            codes_off: 0,
        }
    }

    /// A step of the plugged front end ([`Interpreter::plug`]). Out of line, on
    /// trait objects: the FANUC step that calls it stays as it was (no FANUC
    /// block gets slower, `m4-tests/budget.py`).
    #[inline(never)]
    fn front_step(
        &mut self,
        programs: &dyn ProgramStore,
        env: &dyn Environment,
        sink: &mut dyn CanonSink,
    ) -> Result<Progress, Alarm> {
        // (interp-siemens turns interp-core's `siemens` feature on: without it no
        // front end can be plugged in and the call is left out.)
        #[cfg(feature = "siemens")]
        if let Some(front) = self.siemens.front {
            return front.step(self, programs, env, sink);
        }
        let _ = (programs, env, sink);
        // No front end (a board built without SINUMERIK mode, the F446, whose
        // language setting — $310=1, machine file `language = "siemens"` — asks
        // for it): alarm 4007 on the program's first SINUMERIK block, nothing runs.
        self.phase = Phase::Ended;
        let kind = AlarmKind::NotInThisBuild { what: crate::exec::SINUMERIK };
        Err(Alarm::in_program(self.cursor.program, self.cursor.line, kind))
    }

    /// Plugs in the front end of the language beside FANUC (SINUMERIK:
    /// `interp_siemens::SINUMERIK`): the interpreter hands it every step while
    /// that language is in force. Without one, G290 or a SINUMERIK power-on
    /// language raise alarm 4007 ("SINUMERIK mode not in this build").
    pub fn plug(&mut self, front: &'static dyn crate::lang::Front) {
        self.siemens.front = Some(front);
    }

    /// The machine configuration.
    pub fn config(&self) -> &MachineConfig {
        &self.cfg
    }

    /// Mutable machine configuration (offset and parameter edits between runs).
    /// When the borrow ends, what the interpreter keeps from the parameters (the
    /// codes that call programs, 6001 and 6050–6089) follows them.
    pub fn config_mut(&mut self) -> ConfigMut<'_> {
        ConfigMut { interp: self }
    }

    /// The interpreter state (modal codes, position, frames, tool …).
    pub fn state(&self) -> &State {
        &self.state
    }

    /// The macro variables.
    pub fn variables(&self) -> &Variables {
        &self.vars
    }

    /// The macro variables, to set them from the panel or load the commons
    /// ([`Variables::load_commons`]) and to flush them ([`Variables::flush_commons`]).
    pub fn variables_mut(&mut self) -> &mut Variables {
        &mut self.vars
    }

    /// How program numbers are read now (for [`read_statement`](crate::lang::fanuc::parse::read_statement) outside the
    /// interpreter, e.g. a cycle reading its profile blocks).
    pub fn number_format(&self) -> NumberFormat {
        NumberFormat { units: self.state.modal.units, input: self.cfg.input_mode(), increments: self.cfg.increments }
    }

    /// Sets how many macro statements one step may run (at least 1).
    pub fn set_step_budget(&mut self, statements: u16) {
        self.budget = statements.max(1);
    }

    /// The step budget.
    pub fn step_budget(&self) -> u16 {
        self.budget
    }

    /// Subprogram levels now active (0 in the main program).
    pub fn call_depth(&self) -> usize {
        self.calls.len()
    }

    /// G66 modal calls in force.
    pub fn modal_calls(&self) -> usize {
        self.modal.len()
    }

    /// Where the next block will be read.
    pub fn cursor(&self) -> Cursor {
        self.cursor
    }

    /// The program the next block will be read from (the main program before the
    /// first step). A step reads all its blocks from one program — calls and
    /// returns end a step — so this, asked before a step, tells which program the
    /// actions delivered during that step come from (with a sink that never
    /// refuses, which gets every action in the step that made it).
    pub fn program(&self) -> ProgramId {
        if self.positioned { self.cursor.program } else { self.main }
    }

    /// Tells the interpreter where the axes really are (after homing, jogging, or
    /// an aborted motion), in machine coordinates.
    pub fn set_machine_position(&mut self, pos: Pos) {
        self.state.pos = pos;
    }

    /// Selects the program a run starts with (its O number; 0 for a store's
    /// unnamed main program) and rewinds to it.
    pub fn select_main(&mut self, program: ProgramId) {
        self.main = program;
        self.rewind();
    }

    /// Reset: modal state back to power-on (the G50 shift and the G52 frame
    /// follow parameter 5160), program rewound, pending actions dropped. Macro
    /// variables keep their values (locals clear at power-off only, 2.24.1).
    pub fn reset(&mut self) {
        let keep_local = !self.cfg.params.flag(Param::ResetCancelsLocal);
        let old = self.state;
        self.state = State::power_on(&self.cfg, old.pos);
        self.state.frames.shift = old.frames.shift;
        self.state.tool = old.tool;
        if crate::is_mill(&self.cfg) {
            // A machining centre's reset cancels tool length and cutter radius (G49,
            // G40); the tool in the spindle and the one selected stay.
            self.state.tool = crate::modal::ToolState { tool: old.tool.tool, ..Default::default() };
            self.state.mill.selected = old.mill.selected;
        }
        if keep_local {
            self.state.frames.local = old.frames.local;
        }
        self.state.sum_own_offsets();
        self.language = self.cfg.language;
        self.rewind();
    }

    /// Back to the start of the main program, keeping the modal state; open
    /// subprogram calls and loops are dropped.
    pub fn rewind(&mut self) {
        self.positioned = false;
        self.outbox.clear();
        self.cycle = None;
        self.validating = None;
        self.phase = Phase::Running;
        self.started = false;
        self.state.moved = false;
        self.state.contour.clear();
        // The offsets may have been edited since (config_mut).
        if crate::MILL {
            self.state.refresh_extra_frame(&self.cfg);
        }
        self.calls.clear();
        self.loops.clear();
        self.siemens.rewind();
        self.drop_calls();
    }

    /// The cycle message (SINUMERIK 62xxx: number, line) raised since the last
    /// call, for the operator's display (the link's `[MSG:…]`, `lathe sim`); each
    /// is handed out once.
    pub fn take_notice(&mut self) -> Option<(u16, u32)> {
        #[cfg(feature = "siemens")]
        return self.siemens.notice.take();
        #[cfg(not(feature = "siemens"))]
        None
    }

    /// Cycle start after M00/M01.
    pub fn cycle_start(&mut self) {
        if self.phase == Phase::Paused {
            self.phase = Phase::Running;
        }
    }

    /// Where the block the last step read begins — the block an alarm of that
    /// step came from (for a cycle block, the cycle block), so a caller whose text
    /// was still arriving (the board's stream window) can read it again.
    pub fn block_start(&self) -> Cursor {
        self.last_block
    }

    /// Goes on reading at `at` (a block start from [`Interpreter::block_start`] or
    /// [`Interpreter::cursor`]), running again if an end of text had ended the
    /// run. Together with [`Interpreter::block_start`] this retries a block whose
    /// alarm only said that text was missing: the failed block changed nothing.
    pub fn resume_at(&mut self, at: Cursor) {
        self.cursor = at;
        self.positioned = true;
        self.phase = Phase::Running;
    }

    /// Whether the run has ended (M02/M30, or an end-of-record alarm): the next
    /// step returns [`Progress::Ended`].
    pub fn is_ended(&self) -> bool {
        self.phase == Phase::Ended
    }

    /// Whether a step has work that needs no new block: actions waiting for the
    /// sink, a canned cycle being delivered or validated.
    pub fn has_pending(&self) -> bool {
        !self.outbox.is_empty() || self.cycle.is_some() || self.validating.is_some()
    }

    /// The lowest byte offset into program `program`'s text that the run may still
    /// read: the cursor, open loops (their WHILE blocks), call frames' return
    /// points. `None` if nothing of the run points into it. While a canned cycle is
    /// delivered or validated (it reads its shape blocks by cursor) it is 0.
    pub fn earliest_offset(&self, program: ProgramId) -> Option<usize> {
        if self.has_pending() && self.cursor.program == program {
            return Some(0);
        }
        if !self.positioned && self.main == program {
            return Some(0);
        }
        let mine = |c: &Cursor| (c.program == program).then_some(c.offset);
        let here = self.cursor.program == program;
        let cursor = if self.positioned { mine(&self.cursor) } else { None };
        let loops = self.loops.iter().filter(|_| here).map(|l| l.start.offset);
        let frames = self.calls.iter().flat_map(|f| {
            let own = f.ret.program == program;
            let level = f.kind.kept().and_then(|c| mine(&c));
            mine(&f.ret).into_iter().chain(level).chain(f.loops.iter().filter(move |_| own).map(|l| l.start.offset))
        });
        cursor.into_iter().chain(loops).chain(frames).min()
    }

    /// Program `program`'s text lost its first `bytes` bytes (a stream window
    /// dropping lines already run): every cursor into it moves back by `bytes`.
    /// Only valid when [`Interpreter::earliest_offset`] is at least `bytes`.
    pub fn rebase(&mut self, program: ProgramId, bytes: usize) {
        let shift = |c: &mut Cursor| {
            if c.program == program {
                c.offset = c.offset.saturating_sub(bytes);
            }
        };
        let shift_loops = |loops: &mut Loops| {
            for l in loops.iter_mut() {
                shift(&mut l.start);
                shift(&mut l.end);
            }
        };
        shift(&mut self.cursor);
        shift(&mut self.last_block);
        if self.cursor.program == program {
            shift_loops(&mut self.loops);
        }
        for f in self.calls.iter_mut() {
            if f.ret.program == program {
                shift_loops(&mut f.loops);
            }
            shift(&mut f.ret);
            f.kind.shift(program, bytes);
        }
        self.siemens.shift(program, bytes);
    }

    /// Runs macro statements up to the step budget and at most one NC block (or
    /// delivers pending actions). On an alarm the offending block has been passed
    /// over and the state is unchanged: a control stops there, `lathe check` goes
    /// on to report further alarms.
    pub fn step<P, E, S>(&mut self, programs: &P, env: &E, sink: &mut S) -> Result<Progress, Alarm>
    where
        P: ProgramStore + ?Sized,
        E: Environment,
        S: CanonSink + ?Sized,
    {
        self.stream_open = programs.still_arriving(0);
        if self.validating.is_some() {
            return self.validate(programs, env, sink);
        }
        if !self.deliver(sink) {
            return Ok(Progress::Blocked);
        }
        if let Some(line) = self.run_cycle(programs, env)? {
            self.deliver(sink);
            return Ok(Progress::Executed { line });
        }
        match self.phase {
            Phase::Paused => return Ok(Progress::Paused),
            Phase::Ended => return Ok(Progress::Ended),
            Phase::Running => {}
        }
        if !self.positioned {
            let Some(start) = programs.start(self.main) else {
                self.phase = Phase::Ended;
                return Err(Alarm::in_program(self.main, 0, AlarmKind::ProgramNotFound { program: self.main }));
            };
            self.cursor = start;
            self.positioned = true;
        }
        if self.language == Language::Siemens {
            // The blocks after a G290 (or on a SINUMERIK machine) are SINUMERIK
            // blocks, read by the front end plugged in (interp-siemens). Only an
            // NC block (G290/G291) switches, and it ends a step.
            return self.front_step(&programs, env, &mut &mut *sink);
        }
        let mut budget = self.budget;
        loop {
            let at = self.cursor;
            self.last_block = at;
            let text = programs.text(at.program).unwrap_or(&[]);
            let Some(raw) = next_block(text, &mut self.cursor) else {
                return Err(self.end_of_record(at));
            };
            let line = raw.line;
            if raw.percent {
                return if self.started { Err(self.end_of_record(at)) } else { Ok(Progress::Skipped { line }) };
            }
            if skip_level(raw.text).is_some_and(|l| env.block_skip(l)) {
                return Ok(Progress::Skipped { line });
            }
            let fmt = self.number_format();
            let read = read_program_block(raw.text, line, &self.vars, &fmt, &mut self.block, &mut self.macro_calls);
            match read {
                Ok(Read::Nc) => return self.nc_block(at, fmt, text, programs, env, sink),
                Ok(Read::Macro(m)) if m.statement != MacroStatement::Call => {
                    self.started = true;
                    if let Err(k) = self.macro_statement(&m, at, programs) {
                        return Err(self.alarm_stop(sink, at.program, line, k));
                    }
                }
                Ok(Read::Macro(_)) => {
                    self.started = true;
                    match self.macro_call(programs) {
                        Ok(None) => {}
                        Ok(Some(next)) => {
                            // Into the called program: a step reads one program.
                            self.go(next);
                            self.deliver(sink);
                            return Ok(Progress::Executed { line });
                        }
                        Err(k) => return Err(self.alarm_stop(sink, at.program, line, k)),
                    }
                }
                Err(k) => return Err(self.alarm_stop(sink, at.program, line, k)),
            }
            budget -= 1;
            if budget == 0 {
                return Ok(Progress::Yielded { line });
            }
        }
    }

    /// [`Interpreter::step`] as one non-generic function: the program store and the
    /// sink behind `dyn`, the switches a [`Panel`]. A generic function is compiled at
    /// the opt-level of the crate that instantiates it; this one is compiled here, at
    /// interp-core's (the firmware crate, which calls it from its control task, is
    /// built for size: docs/FIRMWARE-SIZES.md). m4-tests' `bench_interp` measures it.
    #[inline(never)]
    pub fn step_dyn(
        &mut self,
        programs: &dyn ProgramStore,
        env: &Panel,
        sink: &mut dyn CanonSink,
    ) -> Result<Progress, Alarm> {
        self.step(programs, env, sink)
    }

    /// Executes one block typed in MDI (one block: a `;` or line break may end it,
    /// nothing may follow). Macro
    /// assignments work; GOTO/WHILE/DO/END raise alarm 0123, M98/M99/M91/M92 alarm
    /// 4031 (3.1.6 note 2). Alarms and actions carry line 0. The program's run
    /// (cursor, calls, M00 pause) is not touched.
    pub fn mdi<E, S>(&mut self, text: &[u8], env: &E, sink: &mut S) -> Result<Progress, Alarm>
    where
        E: Environment,
        S: CanonSink + ?Sized,
    {
        if !self.deliver(sink) {
            return Ok(Progress::Blocked);
        }
        let alarm = |kind| Alarm::new(0, kind);
        let mut cur = Cursor::start(0);
        let raw = next_block(text, &mut cur).map(|b| b.text).unwrap_or(&[]);
        // One end-of-block character may close the block; a second block may not follow.
        let rest = text.get(raw.len() + 1..).unwrap_or(&[]);
        if let Some(&c) = rest.iter().find(|c| !c.is_ascii_whitespace()) {
            return Err(alarm(AlarmKind::IllegalCharacter { found: c }));
        }
        let fmt = self.number_format();
        let read = read_program_block(raw, 0, &self.vars, &fmt, &mut self.block, &mut self.macro_calls);
        match read.map_err(alarm)? {
            Read::Macro(m) => match m.statement {
                MacroStatement::Call => {
                    return Err(alarm(AlarmKind::NotSupportedYet { what: "a macro call (G65/G66/G67) in MDI" }));
                }
                MacroStatement::Assign { var, value } => self.vars.set(var, value).map_err(alarm)?,
                MacroStatement::Nop => {}
                _ => return Err(alarm(AlarmKind::ControlInMdi)),
            },
            Read::Nc => {
                if self.block.is_empty() {
                    return Ok(Progress::Skipped { line: 0 });
                }
                if let Err(k) = self.run_block(env, None, |_, _| Ok(Next::Go)) {
                    return Err(self.alarm_stop(sink, 0, 0, k));
                }
            }
        }
        self.deliver(sink);
        Ok(Progress::Executed { line: 0 })
    }

    /// The NC block just read into `self.block` by [`Interpreter::step`] from
    /// `text`, the text of its program (`at.program`).
    #[allow(clippy::too_many_arguments)]
    fn nc_block<P, E, S>(
        &mut self,
        at: Cursor,
        fmt: NumberFormat,
        text: &[u8],
        programs: &P,
        env: &E,
        sink: &mut S,
    ) -> Result<Progress, Alarm>
    where
        P: ProgramStore + ?Sized,
        E: Environment,
        S: CanonSink + ?Sized,
    {
        let line = self.block.line;
        if self.block.program.is_some() && self.started {
            // The next program of a multi-program text: this one ran off its end.
            return Err(self.end_of_record(at));
        }
        if self.block.is_empty() {
            return Ok(Progress::Skipped { line });
        }
        self.started = true;
        // (The text step read the block from: one call of the store fewer per block.)
        let here = at.program;
        let program = ProgramText {
            language: self.language,
            text,
            start: programs.start(here).unwrap_or(Cursor::start(here)),
            vars: None,
            fmt: Some(fmt),
        };
        let next = match self.run_block(env, Some(program), |me, flow| me.route(flow, programs)) {
            Ok(next) => next,
            Err(k) => return Err(self.alarm_stop(sink, at.program, line, k)),
        };
        match next {
            Some(next) => self.go(next),
            None => {
                // A canned cycle: its dry run goes on in the next steps.
                if let Some(v) = self.validating.as_mut() {
                    v.at = at;
                }
                return Ok(Progress::Yielded { line });
            }
        }
        self.deliver(sink);
        Ok(Progress::Executed { line })
    }

    /// Runs a chunk of the pending cycle block's dry run; when it has ended, the
    /// block commits and its first actions go out. An alarm drops the block.
    fn validate<P, E, S>(&mut self, programs: &P, env: &E, sink: &mut S) -> Result<Progress, Alarm>
    where
        P: ProgramStore + ?Sized,
        E: Environment,
        S: CanonSink + ?Sized,
    {
        let program = program_text(programs, self.cursor.program, self.language, &self.vars, self.number_format());
        let (Some(v), Some(exp)) = (self.validating.as_mut(), self.cycle.as_ref()) else {
            // (A block is set aside only with its expansion, and both go together.)
            self.validating = None;
            return Ok(Progress::Blocked);
        };
        let (at, line) = (v.at, v.line);
        match v.dry.run(exp, &self.cfg, program, env) {
            Ok(false) => Ok(Progress::Yielded { line }),
            Ok(true) => {
                #[cfg(feature = "siemens")]
                if let Some(code) = exp.notice {
                    self.siemens.notice = Some((code, line));
                }
                if let Some(mut v) = self.validating.take() {
                    v.dry.settle(&mut v.state, &self.cfg);
                    self.state = v.state;
                    self.commit_cycle(&v.block);
                    self.go(v.next);
                }
                self.deliver(sink);
                Ok(Progress::Executed { line })
            }
            Err(k) => {
                self.validating = None;
                self.outbox.clear();
                self.cycle = None;
                Err(self.alarm_stop(sink, at.program, line, k))
            }
        }
    }

    /// Checks and executes `self.block` on the state in place; `route` decides (and
    /// checks) where the program goes next; the block is undone unless all succeeded. The
    /// block's actions are staged in the (empty) outbox and dropped on failure.
    /// `program` is the program the block is in (its variables are filled in
    /// here); `None` in MDI, where calls, jumps and canned cycles are refused.
    ///
    /// A block that starts a canned cycle is not committed yet: it waits in
    /// `validating` for its dry run (`None` is returned), which later steps run.
    fn run_block<E, R>(
        &mut self,
        env: &E,
        program: Option<ProgramText<'_>>,
        route: R,
    ) -> Result<Option<Next>, AlarmKind>
    where
        E: Environment,
        R: FnOnce(&Self, Flow) -> Result<Next, AlarmKind>,
    {
        check_into(&self.block, &self.state, &self.cfg, &mut self.cmd)?;
        self.run_cmd(env, program, route, None, |_| {})
    }

    /// Executes the checked `self.cmd` on the state in place (the engine part of
    /// [`Interpreter::run_block`], shared by the languages): `call` is the
    /// SINUMERIK cycle a cycle-call block starts, `edit` what the block sets on the
    /// state besides the command (SINUMERIK DIAMON, LIMS), undone with the block.
    #[inline(always)]
    #[doc(hidden)]
    pub fn run_cmd<E, R, F>(
        &mut self,
        env: &E,
        program: Option<ProgramText<'_>>,
        route: R,
        call: Option<siemens::CallSpec<'_>>,
        edit: F,
    ) -> Result<Option<Next>, AlarmKind>
    where
        E: Environment,
        R: FnOnce(&Self, Flow) -> Result<Next, AlarmKind>,
        F: FnOnce(&mut State),
    {
        let cmd = &self.cmd;
        if program.is_none() {
            if self.block.sub_call().is_some() {
                return Err(AlarmKind::NotSupportedYet { what: "a subprogram call by M or T code in MDI" });
            }
            if let Some(&(m, _)) = cmd.m.iter().find(|(_, f)| f.is_flow()) {
                return Err(AlarmKind::FlowInMdi { m });
            }
            if crate::cycles::cycle_of(cmd, &self.state).is_some() {
                return Err(AlarmKind::NotSupportedYet { what: "canned cycles in MDI" });
            }
        }
        // A SINUMERIK cycle may change what few blocks do (its tool edge): all is saved.
        let before = if call.is_some() { self.state.save_all() } else { self.state.save(cmd) };
        let held = self.state.contour.is_holding().then_some(self.state.contour);
        // Tests (debug builds) check that an undone block leaves the whole state as it was.
        #[cfg(debug_assertions)]
        let whole = self.state;
        edit(&mut self.state);
        let mut cycle = BlockCycle::default();
        let program = program.map(|p| ProgramText { vars: Some(&self.vars), ..p });
        #[cfg(feature = "siemens")]
        let cycle_call;
        // A cycle the block starts goes straight into `self.cycle` (empty here: a
        // cycle is delivered completely before the next block is read), so the
        // expansion is never moved.
        let mut staged = match program {
            Some(p) => CycleStage::in_program(cmd.line, &mut self.outbox, p, &mut self.cycle),
            None => CycleStage::new(cmd.line, &mut self.outbox),
        };
        // (Only the SINUMERIK driver passes a call: none without its feature.)
        #[cfg(feature = "siemens")]
        if let Some(c) = call {
            cycle_call = c.bind(&self.siemens.vars);
            staged.call = Some(&cycle_call);
        }
        #[cfg(not(feature = "siemens"))]
        let _ = call;
        let done = execute(cmd, &mut self.state, &self.cfg, env, &mut staged);
        let faulty = staged.faulty_move;
        if done.is_ok() {
            cycle.split = staged.split.unwrap_or(staged.actions.len());
            if !staged.writes.is_empty() {
                // Only cycle and G10 blocks write settings: most blocks move nothing here.
                cycle.writes = core::mem::take(&mut staged.writes);
            }
            cycle.resume = staged.resume;
        }
        match done.and_then(|flow| route(self, flow)) {
            Ok(go) => {
                if self.cycle.is_some() {
                    self.set_aside(&before, held.as_ref(), cycle, go);
                    #[cfg(debug_assertions)]
                    debug_assert_eq!(self.state, whole, "a cycle block was not set aside completely");
                    return Ok(None);
                }
                self.commit_cycle(&cycle);
                Ok(Some(go))
            }
            Err(e) => {
                self.state.restore(&before, held.as_ref());
                #[cfg(debug_assertions)]
                debug_assert_eq!(self.state, whole, "a failed block was not undone completely");
                self.outbox.clear();
                self.cycle = None;
                self.fault_line = faulty;
                Err(e)
            }
        }
    }

    /// Sets the cycle block just executed aside for its dry run (`validating`, with
    /// a copy of what its expansion moves on); the state stays as it was (`before`,
    /// `held`) until the dry run has ended. Never inlined: the copy (~3.8 KB with the state) stays
    /// out of the frame of [`Interpreter::nc_block`], which is on the stack under
    /// every block's execution.
    #[inline(never)]
    fn set_aside(
        &mut self,
        before: &crate::stage::Saved,
        held: Option<&crate::contour::Contour>,
        block: BlockCycle,
        next: Next,
    ) {
        let Some(exp) = &self.cycle else { return };
        let (at, line) = (self.cursor, self.cmd.line);
        let dry = exp.dry_copy();
        let state = self.state;
        self.state.restore(before, held);
        self.validating = Some(Validating { state, block, next, dry, at, line });
    }

    /// After a block's alarm (the block undone, the outbox empty): the moves the
    /// contour layer holds back go into the outbox to run before the machine stops,
    /// or, if compensation found one of them faulty (`faulty`, its line), the
    /// machine stops before it and the alarm names that line
    /// ([`crate::contour::stop_on_alarm`]). An alarm that only means the stream
    /// (`program` 0, still arriving) has not delivered the text yet (a jump target,
    /// an END further on) leaves the look-ahead as it is: the board waits for the
    /// text and reads the block again. In a complete text the same alarm is final.
    fn stop_lookahead(&mut self, program: u32, line: u32, faulty: Option<u32>, kind: &AlarmKind) -> Option<u32> {
        let may_come = program == 0 && self.stream_open && kind.waits_for_text();
        if may_come || !self.state.contour.is_holding() {
            return None;
        }
        let mut out = Staged::new(line, &mut self.outbox);
        crate::contour::stop_on_alarm(&mut self.state, faulty, &mut out);
        faulty
    }

    /// The alarm `kind` of the block on `line` of `program`, after the look-ahead
    /// has let go of its held moves ([`Interpreter::stop_lookahead`]) and they have
    /// been offered to `sink`: the alarm names the faulty held move's line if
    /// compensation found one.
    #[doc(hidden)]
    pub fn alarm_stop<S: CanonSink + ?Sized>(
        &mut self,
        sink: &mut S,
        program: u32,
        line: u32,
        kind: AlarmKind,
    ) -> Alarm {
        let faulty = self.fault_line.take();
        let line = self.stop_lookahead(program, line, faulty, &kind).unwrap_or(line);
        self.deliver(sink);
        Alarm::in_program(program, line, kind)
    }

    /// What a successful cycle block hands over: its expansion (taking the actions
    /// staged after the cycle's place as its tail), parameter writes (G71 U → 5147
    /// …) and, after G71–G73, the place after the shape's nf block (a shape after
    /// the cycle block is skipped; one before it leaves the program where it is).
    #[inline]
    fn commit_cycle(&mut self, c: &BlockCycle) {
        // Most blocks start no cycle and write no parameter.
        if self.cycle.is_some() || !c.writes.is_empty() || c.resume.is_some() {
            self.hand_over(c);
        }
    }

    /// [`Interpreter::commit_cycle`] for a block that has something to hand over.
    #[inline(never)]
    fn hand_over(&mut self, c: &BlockCycle) {
        if let Some(exp) = self.cycle.as_mut() {
            exp.take_tail(&mut self.outbox, c.split);
        }
        for &(s, v) in &c.writes {
            s.apply(&mut self.cfg, v);
        }
        // A G10 may have moved the G54.1 frame in force.
        if crate::MILL {
            self.state.refresh_extra_frame(&self.cfg);
        }
        if let Some(r) = c.resume.filter(|r| r.offset > self.cursor.offset) {
            self.jump(Cursor { program: self.cursor.program, ..r });
        }
    }

    /// Lets the cycle in progress refill the outbox (bounded work: until the outbox
    /// is full). `Some(line of the cycle block)` while a cycle is being delivered.
    fn run_cycle<P, E>(&mut self, programs: &P, env: &E) -> Result<Option<u32>, Alarm>
    where
        P: ProgramStore + ?Sized,
        E: Environment,
    {
        // Most steps have no cycle in progress: they leave before the program's
        // text is looked up.
        if self.cycle.is_none() {
            return Ok(None);
        }
        let here = self.cursor.program;
        let program = program_text(programs, here, self.language, &self.vars, self.number_format());
        let Some(exp) = self.cycle.as_mut() else { return Ok(None) };
        let line = exp.line();
        match exp.run(&self.cfg, program, env, &mut self.outbox) {
            Ok(false) => {}
            Ok(true) => self.cycle = None,
            Err(k) => {
                // Cannot happen after the dry run; stop the cycle rather than loop.
                self.cycle = None;
                return Err(Alarm::in_program(here, line, k));
            }
        }
        Ok(Some(line))
    }

    /// Where `flow` leads, with every target looked up and checked.
    #[inline]
    fn route<P: ProgramStore + ?Sized>(&self, flow: Flow, programs: &P) -> Result<Next, AlarmKind> {
        match flow {
            Flow::Continue if !self.modal.any_due() => Ok(Next::Go),
            _ => self.route_flow(flow, programs),
        }
    }

    /// [`Interpreter::route`] for a block that stops, ends, calls, returns or jumps.
    #[inline(never)]
    fn route_flow<P: ProgramStore + ?Sized>(&self, flow: Flow, programs: &P) -> Result<Next, AlarmKind> {
        let here = self.cursor.program;
        let start_of = |id| programs.start(id).ok_or(AlarmKind::ProgramNotFound { program: id });
        Ok(match flow {
            Flow::Continue => self.modal_call_after_move(programs)?,
            Flow::Stop => Next::Pause,
            Flow::End => Next::End,
            Flow::Call { program, repeats, by } => self.subprogram_call(program, repeats, by, programs)?,
            Flow::Return { seq } => match self.calls.last() {
                // M99 in a main program: run it again from the top, P ignored (note 4).
                None => Next::Restart { start: start_of(here)? },
                Some(f) if f.repeats_left > 0 => Next::Repeat { start: start_of(here)? },
                Some(f) => {
                    let to = match seq {
                        None => None,
                        Some(n) => {
                            let caller = start_of(f.ret.program)?;
                            Some(programs.find_sequence(n, caller).ok_or(AlarmKind::JumpTargetNotFound { seq: n })?)
                        }
                    };
                    Next::Return { to }
                }
            },
            Flow::Language(l) => Next::Language(l),
            Flow::Jump { seq } => Next::Jump {
                to: programs.find_sequence(seq, self.cursor).ok_or(AlarmKind::JumpTargetNotFound { seq })?,
            },
        })
    }

    /// Moves the run on as `next` says.
    #[inline]
    #[doc(hidden)]
    pub fn go(&mut self, next: Next) {
        if !matches!(next, Next::Go) {
            self.go_elsewhere(next);
        }
    }

    /// [`Interpreter::go`] anywhere but on to the next block.
    #[inline(never)]
    fn go_elsewhere(&mut self, next: Next) {
        match next {
            Next::Go => {}
            Next::Pause => self.phase = Phase::Paused,
            Next::End => self.phase = Phase::Ended,
            Next::Call { start, repeats, entry } => {
                let frame = Frame {
                    ret: self.cursor,
                    loops: core::mem::take(&mut self.loops),
                    repeats_left: repeats.saturating_sub(1),
                    language: self.language,
                    kind: siemens::Level::Fanuc,
                    entry,
                    off: self.codes_off,
                };
                // `route` checked that there is room.
                let _ = self.calls.push(frame);
                self.enter_call(entry);
                self.enter(start);
            }
            Next::Repeat { start } => {
                if let Some(f) = self.calls.last_mut() {
                    f.repeats_left -= 1;
                }
                self.enter(start);
            }
            Next::Restart { start } => self.enter(start),
            Next::Return { to } => {
                if let Some(f) = self.calls.pop() {
                    self.loops = f.loops;
                    self.cursor = f.ret;
                    self.started = true;
                    self.leave_call(f.entry, f.off);
                    self.language = f.language;
                }
                if let Some(to) = to {
                    self.jump(to);
                }
            }
            Next::Jump { to } => self.jump(to),
            Next::Language(l) => self.language = l,
            // Only the SINUMERIK driver returns it: its front end goes back.
            Next::SiemensReturn => self.front_return(),
        }
    }

    /// Starts a program level at `start`.
    fn enter(&mut self, start: Cursor) {
        self.cursor = start;
        self.loops.clear();
        self.started = false;
    }

    /// Continues at `to` in the current program, leaving the loops whose range does
    /// not contain it (jumping out of a loop is allowed).
    fn jump(&mut self, to: Cursor) {
        let inside = |l: &Loop| l.start.offset <= to.offset && to.offset < l.end.offset;
        let keep = self.loops.iter().take_while(|l| inside(l)).count();
        self.loops.truncate(keep);
        self.cursor = to;
    }

    /// Carries out a macro statement read from block `at` (the cursor is already
    /// past it).
    fn macro_statement<P: ProgramStore + ?Sized>(
        &mut self,
        m: &MacroBlock,
        at: Cursor,
        programs: &P,
    ) -> Result<(), AlarmKind> {
        match m.statement {
            MacroStatement::Assign { var, value } => self.vars.set(var, value),
            MacroStatement::Nop => Ok(()),
            MacroStatement::Goto { seq } => {
                let to = programs.find_sequence(seq, self.cursor).ok_or(AlarmKind::JumpTargetNotFound { seq })?;
                self.jump(to);
                Ok(())
            }
            MacroStatement::Loop { label, enter } => self.loop_start(label, enter, at, programs),
            MacroStatement::End { label } => self.loop_end(label),
            // Taken by `step` before (a call ends the step).
            MacroStatement::Call => Ok(()),
        }
    }

    /// WHILE […] DO m / DO m at block `at`.
    fn loop_start<P: ProgramStore + ?Sized>(
        &mut self,
        label: u8,
        enter: bool,
        at: Cursor,
        programs: &P,
    ) -> Result<(), AlarmKind> {
        if self.loops.last().is_some_and(|l| l.start == at) {
            // Back from END: evaluate again.
            if !enter && let Some(l) = self.loops.pop() {
                self.cursor = l.end;
            }
            return Ok(());
        }
        if self.loops.iter().any(|l| l.label == label) {
            return Err(AlarmKind::LoopsCrossed { label });
        }
        let text = programs.text(self.cursor.program).unwrap_or(&[]);
        let end = find_loop_end(text, self.cursor, label)?;
        if enter {
            self.loops.push(Loop { label, start: at, end }).map_err(|_| AlarmKind::LoopsCrossed { label })?;
        } else {
            self.cursor = end;
        }
        Ok(())
    }

    /// END m: back to the WHILE/DO of the innermost loop, which must be loop m.
    fn loop_end(&mut self, label: u8) -> Result<(), AlarmKind> {
        match self.loops.last() {
            Some(l) if l.label == label && l.end == self.cursor => {
                self.cursor = l.start;
                Ok(())
            }
            _ if self.loops.iter().any(|l| l.label == label) => Err(AlarmKind::LoopsCrossed { label }),
            _ => Err(AlarmKind::EndWithoutDo { label }),
        }
    }

    /// Offers waiting actions to the sink; true when the outbox is empty.
    #[doc(hidden)]
    pub fn deliver<S: CanonSink + ?Sized>(&mut self, sink: &mut S) -> bool {
        while let Some(c) = self.outbox.front() {
            if sink.push_ref(c).is_err() {
                return false;
            }
            self.outbox.pop_front();
        }
        true
    }

    #[doc(hidden)]
    pub fn end_of_record(&mut self, at: Cursor) -> Alarm {
        self.phase = Phase::Ended;
        Alarm::in_program(at.program, at.line, AlarmKind::EndOfRecord)
    }
}

/// The text of program `here` with the variables and number format a cycle needs
/// to read its shape blocks.
fn program_text<'a, P: ProgramStore + ?Sized>(
    programs: &'a P,
    here: ProgramId,
    language: Language,
    vars: &'a Variables,
    fmt: NumberFormat,
) -> ProgramText<'a> {
    ProgramText {
        language,
        text: programs.text(here).unwrap_or(&[]),
        start: programs.start(here).unwrap_or(Cursor::start(here)),
        vars: Some(vars),
        fmt: Some(fmt),
    }
}

/// A build without the `siemens` feature (the F446 board) refuses SINUMERIK mode
/// with alarm 4007 instead of reading a program in a language it does not carry.
/// Run by `cargo test -p interp-core --no-default-features --lib` (.ci/run).
#[cfg(all(test, not(feature = "siemens")))]
mod without_siemens {
    use super::*;
    use crate::canon::RecordingSink;
    use crate::config::Language;
    use crate::env::Panel;
    use crate::program::SingleProgram;

    /// Steps until an alarm or the end; the alarm and the actions staged.
    fn run(cfg: MachineConfig, text: &str) -> (Option<Alarm>, usize) {
        let mut interp = Interpreter::new(cfg);
        let mut sink = RecordingSink::<64>::new();
        for _ in 0..100 {
            match interp.step(&SingleProgram(text.as_bytes()), &Panel::default(), &mut sink) {
                Ok(Progress::Ended) => return (None, sink.actions.len()),
                Ok(_) => {}
                Err(a) => return (Some(a), sink.actions.len()),
            }
        }
        (None, sink.actions.len())
    }

    #[test]
    fn g290_raises_4007_on_its_line_and_nothing_after_it_runs() {
        let (alarm, _) = run(MachineConfig::default(), "G00 X10 Z10\nG290\nG1 X20 Z5 F0.2\nM30\n");
        let alarm = alarm.expect("G290 must be refused");
        assert_eq!(alarm.code(), 4007);
        assert_eq!(alarm.line, 2);
        assert_eq!(alarm.kind, AlarmKind::NotInThisBuild { what: "SINUMERIK mode" });
        let mut text = heapless::String::<64>::new();
        core::fmt::Write::write_fmt(&mut text, format_args!("{}", alarm.kind)).unwrap();
        assert_eq!(text.as_str(), "SINUMERIK mode not in this build");
    }

    #[test]
    fn a_sinumerik_power_on_language_raises_4007_before_any_motion() {
        let cfg = MachineConfig { language: Language::Siemens, ..MachineConfig::default() };
        let (alarm, actions) = run(cfg, "G0 X10 Z10\nM30\n");
        assert_eq!(alarm.map(|a| a.code()), Some(4007));
        assert_eq!(actions, 0);
    }
}

/// An interpreter with SINUMERIK mode built in but no front end plugged in
/// ([`Interpreter::plug`]): the first SINUMERIK block raises alarm 4007 and
/// nothing after it runs (a host tool that forgot to plug interp-siemens in
/// gets an alarm, not a wrong cut).
#[cfg(all(test, feature = "siemens"))]
mod no_front {
    use super::*;
    use crate::canon::RecordingSink;
    use crate::env::Panel;
    use crate::program::SingleProgram;

    #[test]
    fn a_sinumerik_block_without_a_front_end_raises_4007() {
        let text = "G00 X10 Z10\nG290\nG1 X20 Z5 F0.2\nM30\n";
        let mut interp = Interpreter::new(MachineConfig::default());
        let mut sink = RecordingSink::<64>::new();
        let mut alarm = None;
        for _ in 0..20 {
            match interp.step(&SingleProgram(text.as_bytes()), &Panel::default(), &mut sink) {
                Ok(Progress::Ended) => break,
                Ok(_) => {}
                Err(a) => {
                    alarm = Some(a);
                    break;
                }
            }
        }
        let alarm = alarm.expect("the SINUMERIK block must be refused");
        assert_eq!((alarm.code(), alarm.line), (4007, 3));
        let moved = sink.actions.iter().filter(|c| c.action.endpoint().is_some()).count();
        assert_eq!(moved, 1, "only the FANUC G00 moved: {:?}", sink.actions);
    }
}

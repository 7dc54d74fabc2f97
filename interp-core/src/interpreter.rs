//! The interpreter driver: one block per [`Interpreter::step`], bounded work, so a
//! firmware task stays responsive and a full motion queue applies back-pressure.
//!
//! Each step first delivers actions still waiting in the outbox; only when the
//! outbox is empty does it read, check and execute the next block. A block runs on
//! a copy of the state and is committed only if it succeeded, so an alarm leaves
//! the state exactly as it was.

use crate::alarm::{Alarm, AlarmKind};
use crate::axis::Pos;
use crate::canon::CanonSink;
use crate::check::check;
use crate::config::{MachineConfig, Param};
use crate::cycles::Expansion;
use crate::env::Environment;
use crate::exec::{Flow, Outbox, Staged, State, execute};
use crate::parse::{Block, read_block_into};
use crate::program::{Cursor, ProgramStore, next_block};

/// What a step did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Progress {
    /// Executed the block on `line`; its actions are delivered or waiting.
    Executed {
        /// Source line.
        line: u32,
    },
    /// Passed over a blank, comment-only, record-mark or skipped (`/`) block.
    Skipped {
        /// Source line.
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
enum Phase {
    Running,
    Paused,
    Ended,
}

/// The lathe interpreter.
#[derive(Debug)]
pub struct Interpreter {
    cfg: MachineConfig,
    state: State,
    cursor: Cursor,
    /// Actions waiting for the sink; also where a block stages its actions.
    outbox: Outbox,
    /// The block being read, reused from block to block.
    block: Block,
    phase: Phase,
    /// A block other than `%`/`O` has been executed (a later `%` ends the record).
    started: bool,
    /// The canned cycle being delivered (see [`crate::cycles`]).
    cycle: Option<Expansion>,
}

impl Interpreter {
    /// A powered-on interpreter for machine `cfg`, axes at machine zero.
    pub fn new(cfg: MachineConfig) -> Self {
        let state = State::power_on(&cfg, Pos::ZERO);
        Interpreter {
            cfg,
            state,
            cursor: Cursor::start(0),
            outbox: heapless::Deque::new(),
            block: Block::default(),
            phase: Phase::Running,
            started: false,
            cycle: None,
        }
    }

    /// The machine configuration.
    pub fn config(&self) -> &MachineConfig {
        &self.cfg
    }

    /// Mutable machine configuration (offset and parameter edits between runs).
    pub fn config_mut(&mut self) -> &mut MachineConfig {
        &mut self.cfg
    }

    /// The interpreter state (modal codes, position, frames, tool …).
    pub fn state(&self) -> &State {
        &self.state
    }

    /// Tells the interpreter where the axes really are (after homing, jogging, or
    /// an aborted motion), in machine coordinates.
    pub fn set_machine_position(&mut self, pos: Pos) {
        self.state.pos = pos;
    }

    /// Reset: modal state back to power-on (the G50 shift and the G52 frame
    /// follow parameter 5160), program rewound, pending actions dropped.
    pub fn reset(&mut self) {
        let keep_local = !self.cfg.params.flag(Param::ResetCancelsLocal);
        let old = self.state;
        self.state = State::power_on(&self.cfg, old.pos);
        self.state.frames.shift = old.frames.shift;
        self.state.tool = old.tool;
        if keep_local {
            self.state.frames.local = old.frames.local;
        }
        self.rewind();
    }

    /// Back to the start of the main program, keeping the modal state.
    pub fn rewind(&mut self) {
        self.cursor = Cursor::start(0);
        self.outbox.clear();
        self.cycle = None;
        self.phase = Phase::Running;
        self.started = false;
        self.state.moved = false;
    }

    /// Cycle start after M00/M01.
    pub fn cycle_start(&mut self) {
        if self.phase == Phase::Paused {
            self.phase = Phase::Running;
        }
    }

    /// Runs one block (or delivers pending actions). On an alarm the offending
    /// block has been passed over and the state is unchanged: a control stops
    /// there, `lathe check` goes on to report further alarms.
    pub fn step<P, E, S>(&mut self, programs: &P, env: &E, sink: &mut S) -> Result<Progress, Alarm>
    where
        P: ProgramStore + ?Sized,
        E: Environment,
        S: CanonSink + ?Sized,
    {
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
        let text = programs.text(self.cursor.program).unwrap_or(&[]);
        let Some(raw) = next_block(text, &mut self.cursor) else {
            return Err(self.end_of_record(self.cursor.line));
        };
        let line = raw.line;
        if raw.percent {
            return if self.started { Err(self.end_of_record(line)) } else { Ok(Progress::Skipped { line }) };
        }
        read_block_into(raw.text, line, &mut self.block).map_err(|k| Alarm::new(line, k))?;
        let block = &self.block;
        if block.program.is_some() && self.started {
            // The next program of a multi-program text: this one ran off its end.
            return Err(self.end_of_record(line));
        }
        let skipped = block.skip_level.is_some_and(|l| env.block_skip(l));
        if skipped || block.is_empty() {
            return Ok(Progress::Skipped { line });
        }
        self.started = true;
        let mut cycle = BlockCycle::default();
        let flow = run_block(block, &mut self.state, &self.cfg, env, &mut self.outbox, text, &mut cycle)
            .map_err(|k| Alarm::new(line, k))?;
        self.commit_cycle(cycle);
        self.phase = match flow {
            Flow::Continue => Phase::Running,
            Flow::Stop => Phase::Paused,
            Flow::End => Phase::Ended,
        };
        self.deliver(sink);
        Ok(Progress::Executed { line })
    }

    /// Offers waiting actions to the sink; true when the outbox is empty.
    fn deliver<S: CanonSink + ?Sized>(&mut self, sink: &mut S) -> bool {
        while let Some(c) = self.outbox.front() {
            if sink.push(*c).is_err() {
                return false;
            }
            self.outbox.pop_front();
        }
        true
    }

    /// ---- canned cycles (branch `cycles`): what a successful block hands over —
    /// its expansion (taking the actions staged after the cycle's place as its
    /// tail), parameter writes (G71 U → 5147 …) and, after G71–G73, the place after
    /// the shape's nf block (a shape after the cycle block is skipped; one before
    /// it leaves the program where it is).
    fn commit_cycle(&mut self, c: BlockCycle) {
        if let Some(mut exp) = c.exp {
            exp.take_tail(&mut self.outbox, c.split);
            self.cycle = Some(exp);
        }
        for (p, v) in c.params {
            self.cfg.params.set(p, v);
        }
        if let Some(r) = c.resume.filter(|r| r.offset > self.cursor.offset) {
            self.cursor = Cursor { program: self.cursor.program, ..r };
        }
    }

    /// ---- canned cycles (branch `cycles`): lets the cycle in progress refill the
    /// outbox (bounded work: until the outbox is full). `Some(line of the cycle
    /// block)` while a cycle is being delivered.
    fn run_cycle<P, E>(&mut self, programs: &P, env: &E) -> Result<Option<u32>, Alarm>
    where
        P: ProgramStore + ?Sized,
        E: Environment,
    {
        let Some(exp) = self.cycle.as_mut() else { return Ok(None) };
        let line = exp.line();
        let text = programs.text(self.cursor.program).unwrap_or(&[]);
        match exp.run(&self.cfg, text, env, &mut self.outbox) {
            Ok(false) => {}
            Ok(true) => self.cycle = None,
            Err(k) => {
                // Cannot happen after the dry run; stop the cycle rather than loop.
                self.cycle = None;
                return Err(Alarm::new(line, k));
            }
        }
        Ok(Some(line))
    }

    fn end_of_record(&mut self, line: u32) -> Alarm {
        self.phase = Phase::Ended;
        Alarm::new(line, AlarmKind::EndOfRecord)
    }
}

/// ---- canned cycles (branch `cycles`): what a cycle block hands the interpreter.
#[derive(Debug, Default)]
struct BlockCycle {
    exp: Option<Expansion>,
    split: usize,
    params: heapless::Vec<(Param, i64), 8>,
    resume: Option<Cursor>,
}

/// Checks and executes one block on a copy of the state and commits it on success.
/// The block's actions are staged in the (empty) outbox and dropped on failure; a
/// cycle it starts goes into `cycle` only on success.
fn run_block<E: Environment>(
    block: &Block,
    state: &mut State,
    cfg: &MachineConfig,
    env: &E,
    outbox: &mut Outbox,
    text: &[u8],
    cycle: &mut BlockCycle,
) -> Result<Flow, AlarmKind> {
    let cmd = check(block, state, cfg)?;
    let mut next = *state;
    let mut slot = None;
    let mut staged = Staged::in_program(block.line, outbox, text, &mut slot);
    match execute(&cmd, &mut next, cfg, env, &mut staged) {
        Ok(flow) => {
            *state = next;
            cycle.split = staged.split.unwrap_or(staged.actions.len());
            cycle.params = core::mem::take(&mut staged.params);
            cycle.resume = staged.resume;
            cycle.exp = slot;
            Ok(flow)
        }
        Err(e) => {
            outbox.clear();
            Err(e)
        }
    }
}

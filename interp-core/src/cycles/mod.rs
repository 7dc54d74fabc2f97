//! Canned cycles (2.15–2.17, 2.21–2.22): G90/G92/G94 single cycles, G32/G34
//! threading, G70–G76 multiple repetitive cycles, G83–G89 hole cycles and M29
//! rigid tapping, as expansions into the canonical actions.
//!
//! # Expansion design
//! A cycle may produce hundreds of moves while the interpreter's outbox holds 16
//! and the board has 128 KB of RAM, so a cycle never materialises its passes. It is
//! an [`Expansion`]: a small state machine (a generator per cycle family plus, for
//! G71–G73, the finishing shape as at most [`profile::PROFILE_MAX`] segments) kept
//! in the interpreter. Every `step()` lets it plan its next few moves into an
//! 8-step queue and emit them until the outbox is full: bounded work per step.
//!
//! All-or-nothing still holds: when the cycle block executes, a copy of the
//! expansion's moving parts ([`DryRun`]: emitter, generator, queue; the shape is
//! read from the expansion) is run to the end against a sink that only counts
//! (the *dry run*).
//! Every alarm the cycle can raise — the notes' value checks, the shape's codes and
//! monotony, soft limits of every pass, feeds — is raised then, before the first
//! action is delivered, and the state the dry run ends in (position back at the
//! start point, modal changes of G70's blocks) is what the block commits. The real
//! run then replays the same deterministic generator from the start. Generators
//! are pure functions of their inputs, so the real run cannot alarm.
//!
//! Actions of the cycle block itself (spindle, tool, M codes before the motion) go
//! first; the ones after the motion (M05, M09, M30 …) are kept in the expansion
//! and delivered after its last move. Every action carries the cycle block's line.

// The generators are the crate `cycle-paths` (built for size on the board); the
// SINUMERIK cycles (CYCLE93/95, the finishing passes of their contours) use some of
// them and nothing else does: a build without the `siemens` feature leaves them out
// (and their code out of flash).
#[cfg(feature = "siemens")]
mod calls;
mod drilling;
mod emit;
mod finish;
#[cfg(feature = "siemens")]
pub use cycle_paths::holes;
#[cfg(feature = "siemens")]
pub mod mill;
pub mod profile;
mod single;

pub use cycle_paths::{curve, groove, hole, offset, pass, pattern, polar, rough, thread};

pub use crate::command::cycle::CycleArgs;
#[cfg(feature = "siemens")]
pub use calls::CallEngine;
pub use emit::{Emitter, Out, Pt, Step};

use crate::alarm::AlarmKind;
use crate::canon::{Canon, Plane, SpindleDir};
use crate::codes::GCode;
use crate::command::Command;
use crate::command::cycle as args;
use crate::config::{MachineConfig, Param};
use crate::env::Environment;
use crate::modal::{RigidTap, State};
use crate::stage::{Flow, Outbox, Staged};
use emit::Dry;
use finish::FinishGen;
use groove::GrooveGen;
use hole::HoleGen;
use pattern::PatternGen;
use profile::{Profile, ShapeSource};
use rough::RoughGen;
use thread::{MultiThreadGen, ThreadCycleGen};

pub use cycle_paths::StepQueue;
use cycle_paths::sign;

/// Actions of the cycle block that follow its motion (M05, M09, M30 …).
const TAIL: usize = 6;

/// Most planned steps one cycle may have (alarm 4037 beyond): a cycle whose P/Q
/// were written as least increments by mistake (P3 = 0.003 mm) would otherwise
/// expand to millions of pecks.
pub const MAX_CYCLE_STEPS: u32 = 1_000_000;

/// The generator of one cycle. One lives inline in each expansion (there is no heap
/// to box the larger ones into); the expansion's size is bounded by a test.
#[derive(Clone, Debug, PartialEq)]
#[allow(clippy::large_enum_variant)]
enum Gen {
    /// A fixed handful of steps (G90/G94).
    Plan(heapless::Vec<Step, 8>),
    ThreadCycle(ThreadCycleGen),
    Rough(RoughGen),
    Pattern(PatternGen),
    Finish(FinishGen),
    Groove(GrooveGen),
    MultiThread(MultiThreadGen),
    Hole(HoleGen),
    Curve(curve::CurveGen),
    Polar(polar::PolarGen),
    #[cfg(feature = "siemens")]
    Pass(pass::PassGen),
    #[cfg(feature = "siemens")]
    Grooving(groove::GroovingGen),
    /// A milling cycle (SINUMERIK POCKET1–4, SLOT1/2, CYCLE71–77, CYCLE90 …).
    #[cfg(feature = "siemens")]
    Mill(mill::MillRun),
    /// CYCLE73's planned path.
    #[cfg(feature = "mill-island")]
    Island(mill::IslandRun),
}

/// A cycle being delivered: its generator, its copy of the state and what is
/// left to emit.
#[derive(Clone, Debug, PartialEq)]
pub struct Expansion {
    em: Emitter,
    generator: Gen,
    profile: Profile,
    queue: StepQueue,
    gen_done: bool,
    /// The block's actions after the cycle's place, delivered after its last
    /// move (at most [`TAIL`], [`Expansion::take_tail`]). Until the block
    /// commits it is empty, and G71–G73's shape reader stages the shape's blocks
    /// in it ([`profile::read_profile`]): an outbox in the expansion and not on
    /// the stack under the shape's blocks as they run.
    tail: Outbox,
    /// Steps planned so far.
    steps: u32,
    /// A message the cycle raised when it started (SINUMERIK 62xxx: shown, the
    /// program goes on), handed to the operator once its dry run has passed.
    pub notice: Option<u16>,
}

/// What a run of an expansion moves on (the real run's or its dry run's copy):
/// its emitter, generator, step queue and counts.
struct Walk<'w> {
    em: &'w mut Emitter,
    generator: &'w mut Gen,
    queue: &'w mut StepQueue,
    gen_done: &'w mut bool,
    steps: &'w mut u32,
}

impl Walk<'_> {
    /// Emits the generator's steps into `out` while it has room, along `profile`
    /// (the expansion's shape). True when the generator has ended and its queue is
    /// empty (the tail, if any, is the caller's).
    fn advance<E: Environment + ?Sized>(
        &mut self,
        profile: &Profile,
        cfg: &MachineConfig,
        program: crate::lang::ProgramText<'_>,
        env: &E,
        out: &mut dyn Out,
    ) -> Result<bool, AlarmKind> {
        loop {
            if out.room() == 0 {
                return Ok(false);
            }
            if let Some(step) = self.queue.pop_front() {
                *self.steps += 1;
                if *self.steps > MAX_CYCLE_STEPS {
                    return Err(AlarmKind::CycleTooLong);
                }
                self.em.emit(step, cfg, out)?;
                continue;
            }
            if *self.gen_done {
                return Ok(true);
            }
            let here = self.em.here(cfg);
            let queue = &mut *self.queue;
            let more = match &mut *self.generator {
                Gen::Plan(steps) => {
                    for s in steps.iter() {
                        queue.push_back(*s).map_err(|_| AlarmKind::Overflow)?;
                    }
                    false
                }
                Gen::Finish(f) => {
                    if out.room() < crate::stage::STAGE {
                        return Ok(false);
                    }
                    f.step(self.em, cfg, program, env, out, queue)?
                }
                Gen::ThreadCycle(g) => g.fill(queue)?,
                Gen::Rough(g) => g.fill(profile, here, queue)?,
                Gen::Pattern(g) => g.fill(profile, queue)?,
                Gen::Groove(g) => g.fill(queue)?,
                Gen::MultiThread(g) => g.fill(queue)?,
                Gen::Hole(g) => g.fill(queue)?,
                Gen::Curve(g) => g.fill(queue)?,
                Gen::Polar(g) => g.fill(queue)?,
                #[cfg(feature = "siemens")]
                Gen::Pass(g) => g.fill(&profile.segs, queue)?,
                #[cfg(feature = "siemens")]
                Gen::Grooving(g) => g.fill(&profile.segs, here, queue)?,
                #[cfg(feature = "siemens")]
                Gen::Mill(g) => g.fill(profile, emit::work_pos(&self.em.st, cfg), queue)?,
                #[cfg(feature = "mill-island")]
                Gen::Island(g) => g.fill(emit::work_pos(&self.em.st, cfg), queue)?,
            };
            *self.gen_done = !more;
        }
    }
}

/// The dry run of a cycle block set aside (`Interpreter`'s `Validating`): the
/// parts of its [`Expansion`] a run moves on, copied
/// ([`Expansion::dry_copy`]); the shape stays the expansion's. About 2.3 KB where
/// a whole copy of the expansion was 6 KB (static RAM: the interpreter holds
/// both the expansion and this).
#[derive(Clone, Debug, PartialEq)]
pub struct DryRun {
    em: Emitter,
    generator: Gen,
    queue: StepQueue,
    gen_done: bool,
    steps: u32,
}

impl DryRun {
    /// Runs a chunk of at most [`DRY_RUN_CHUNK`] actions of the cycle `exp` (the
    /// expansion this was copied from, unchanged since), raising any alarm the
    /// cycle would raise; true when it has run to the end.
    pub fn run<E: Environment + ?Sized>(
        &mut self,
        exp: &Expansion,
        cfg: &MachineConfig,
        program: crate::lang::ProgramText<'_>,
        env: &E,
    ) -> Result<bool, AlarmKind> {
        let mut walk = Walk {
            em: &mut self.em,
            generator: &mut self.generator,
            queue: &mut self.queue,
            gen_done: &mut self.gen_done,
            steps: &mut self.steps,
        };
        walk.advance(&exp.profile, cfg, program, env, &mut Dry(DRY_RUN_CHUNK))
    }

    /// Once the dry run has ended: the state the cycle block commits
    /// ([`Expansion::settle`]).
    pub fn settle(&self, st: &mut State, cfg: &MachineConfig) {
        settle(&self.em.st, &self.generator, st, cfg);
    }
}

impl Expansion {
    fn new(em: Emitter, generator: Gen, profile: Profile) -> Self {
        Expansion {
            em,
            generator,
            profile,
            queue: StepQueue::new(),
            gen_done: false,
            tail: Outbox::new(),
            steps: 0,
            notice: None,
        }
    }

    /// Line of the cycle block.
    pub fn line(&self) -> u32 {
        self.em.line
    }

    /// Moves the block's actions staged after the cycle's place (`split`) out of
    /// `outbox`, to deliver them after the cycle's last move.
    pub fn take_tail(&mut self, outbox: &mut Outbox, split: usize) {
        let mut tail: heapless::Vec<Canon, TAIL> = heapless::Vec::new();
        while outbox.len() > split {
            // At most the block's after-motion actions (M codes, M05, M30): they fit.
            if let Some(c) = outbox.pop_back() {
                let _ = tail.push(c);
            }
        }
        self.tail.clear();
        for c in tail.into_iter().rev() {
            let _ = self.tail.push_back(c);
        }
    }

    /// Emits actions into `out` while it has room. `program` is the program the
    /// cycle block is in (G70 reads its blocks as it goes). True when finished.
    pub fn run<E: Environment + ?Sized>(
        &mut self,
        cfg: &MachineConfig,
        program: crate::lang::ProgramText<'_>,
        env: &E,
        out: &mut dyn Out,
    ) -> Result<bool, AlarmKind> {
        let mut walk = Walk {
            em: &mut self.em,
            generator: &mut self.generator,
            queue: &mut self.queue,
            gen_done: &mut self.gen_done,
            steps: &mut self.steps,
        };
        if !walk.advance(&self.profile, cfg, program, env, out)? {
            return Ok(false);
        }
        loop {
            if out.room() == 0 {
                return Ok(false);
            }
            if let Some(c) = self.tail.pop_front() {
                out.put(c)?;
                continue;
            }
            return Ok(true);
        }
    }

    /// The dry-run copy of this expansion as its block sets it aside: what a run
    /// moves on (emitter, generator, queue), without the shape, which the dry run
    /// reads from this expansion ([`DryRun::run`]: nothing changes it once the
    /// cycle has started), and without the tail, which is empty until the block
    /// commits.
    pub fn dry_copy(&self) -> DryRun {
        DryRun {
            em: self.em,
            generator: self.generator.clone(),
            queue: self.queue.clone(),
            gen_done: self.gen_done,
            steps: self.steps,
        }
    }

    /// The state after the cycle (for the dry run).
    fn final_state(&self) -> State {
        self.em.st
    }
}

/// What exec tells a cycle about the block.
pub struct Ctx<'a, 'b> {
    /// Machine.
    pub cfg: &'a MachineConfig,
    /// Switches.
    pub env: &'a dyn Environment,
    /// The block's stage (program text, expansion slot, parameter writes).
    pub out: &'a mut CycleStage<'b>,
}

/// Executes a checked block on the state, staging its actions: `exec::execute`,
/// handed down to the cycles that run the blocks of a shape (the cycles sit below
/// `exec`, which dispatches to them).
pub type Execute =
    fn(&Command, &mut State, &MachineConfig, &dyn Environment, &mut CycleStage<'_>) -> Result<Flow, AlarmKind>;

/// How blocks are executed, given to [`execute`] as a type by `exec`
/// (`exec::Blocks`): G70–G73 run their shape's blocks through it. A type and not a
/// value, so that a block that is no cycle carries nothing for it.
pub trait Executor {
    /// Executes `cmd` on `st`, staging the actions in `out` (an [`Execute`]).
    fn execute(
        cmd: &Command,
        st: &mut State,
        cfg: &MachineConfig,
        env: &dyn Environment,
        out: &mut CycleStage<'_>,
    ) -> Result<Flow, AlarmKind>;

    /// Starts the SINUMERIK cycle of a [`GCode::CycleCall`] block (the call is in
    /// `ctx.out.call`): the language's cycles sit above this module.
    fn cycle_call(cmd: &Command, st: &mut State, ctx: &mut Ctx<'_, '_>) -> Result<(), AlarmKind>;
}

/// A block's [`Staged`] actions with the interpreter's expansion slot, where a
/// cycle the block starts goes. Derefs to the [`Staged`] actions.
#[derive(Debug)]
pub struct CycleStage<'a> {
    /// The block's staged actions.
    pub staged: Staged<'a>,
    /// Where a cycle started by this block goes (the interpreter's expansion slot);
    /// `None` where no cycle may start (inside a cycle's own blocks).
    slot: Option<&'a mut Option<Expansion>>,
    /// The SINUMERIK cycle the block calls (its group-00 code is
    /// [`GCode::CycleCall`]), bound by the front end.
    pub call: Option<&'a crate::lang::siemens::call::CycleCall<'a>>,
}

impl<'a> CycleStage<'a> {
    /// Stages the actions of the block on `line` in `outbox` (no cycle may start).
    pub fn new(line: u32, outbox: &'a mut Outbox) -> Self {
        CycleStage { staged: Staged::new(line, outbox), slot: None, call: None }
    }

    /// A stage for a block of `program` that may start a cycle into `slot`.
    pub fn in_program(
        line: u32,
        outbox: &'a mut Outbox,
        program: crate::lang::ProgramText<'a>,
        slot: &'a mut Option<Expansion>,
    ) -> Self {
        let mut staged = Staged::new(line, outbox);
        staged.program = program;
        CycleStage { staged, slot: Some(slot), call: None }
    }

    /// The interpreter's expansion slot, for the block's cycle to be built in place
    /// (an expansion is ~5 KB: built here it is never moved through the frames of
    /// its callers, which are on the stack under the shape's blocks). The cycle's
    /// moves come after the actions staged so far.
    pub fn cycle_slot(&mut self) -> Result<&mut Option<Expansion>, AlarmKind> {
        let slot = self.slot.as_deref_mut().ok_or(AlarmKind::ProfileForbiddenCode { what: "a cycle" })?;
        self.staged.split = Some(self.staged.actions.len());
        Ok(slot)
    }
}

impl CycleStage<'_> {
    /// The cycle this block has started, if any.
    pub fn started(&mut self) -> Option<&mut Expansion> {
        self.slot.as_deref_mut()?.as_mut()
    }
}

impl<'a> core::ops::Deref for CycleStage<'a> {
    type Target = Staged<'a>;
    fn deref(&self) -> &Staged<'a> {
        &self.staged
    }
}

impl<'a> core::ops::DerefMut for CycleStage<'a> {
    fn deref_mut(&mut self) -> &mut Staged<'a> {
        &mut self.staged
    }
}

/// Bookkeeping before a block runs: the thread chain, the clearing of retained
/// cycle data (2.15 note 2), G80 and group-01 codes cancelling hole cycles and rigid
/// tapping, and the M29 rules (2.22.1). Returns whether the previous block was a
/// thread block.
#[inline]
pub fn before_block(cmd: &Command, st: &mut State, cfg: &MachineConfig) -> Result<bool, AlarmKind> {
    let quiet = cmd.m.is_empty()
        && cmd.g.drilling.is_none()
        && cmd.g.one_shot.is_none()
        && !st.cycle.thread_chain
        && st.cycle.rigid == RigidTap::Off;
    if quiet {
        // No M29, no rigid tap pending, no G80, no chain: only a motion code
        // ends the single cycle and the drilling mode (most blocks).
        if cmd.g.motion.is_some() {
            st.cycle.single = None;
            st.modal.drilling = GCode::DrillCancel;
        }
        return Ok(false);
    }
    cycle_words(cmd, st, cfg)
}

/// [`before_block`] for a block with M words, a drilling or group 00 code, or
/// with a thread chain or a rigid tap in progress.
#[inline(never)]
fn cycle_words(cmd: &Command, st: &mut State, cfg: &MachineConfig) -> Result<bool, AlarmKind> {
    use GCode::{FaceTap, LeftTap, SideTap, Tap};
    let chained = core::mem::replace(&mut st.cycle.thread_chain, false);
    if cmd.g.one_shot.is_some_and(|c| c != GCode::Dwell) || cmd.g.motion.is_some() {
        st.cycle.single = None;
    }
    if let Some(code) = cmd.g.drilling.filter(|c| args::is_mill_hole(*c)) {
        if !args::is_hole(st.modal.drilling) {
            // A machining centre's hole mode starts: G00–G03 cancelled the mode
            // with its data (seed 004 @10250); a new initial level follows.
            st.cycle.hole = Default::default();
            st.mill.initial = None;
        }
        if !matches!(code, Tap | LeftTap) && st.cycle.rigid != RigidTap::Off {
            // Another cycle code ends rigid tapping (seed 004 @8400).
            st.cycle.rigid = RigidTap::Off;
        }
    }
    let m29 = cmd.m.iter().any(|&(m, _)| m == 29);
    let taps = matches!(cmd.g.drilling, Some(FaceTap | SideTap | Tap | LeftTap))
        || (cmd.g.drilling.is_none() && matches!(st.modal.drilling, FaceTap | SideTap | Tap | LeftTap));
    if m29 {
        if st.cycle.rigid != RigidTap::Off {
            return Err(AlarmKind::RigidTapSequence);
        }
        // A machining centre's M29 stands alone and taps at the S in force (seed
        // 004 @8320); a lathe's takes S in its block (2.22.1).
        let mill = crate::is_mill(cfg);
        let s = if mill { cmd.speed.or(Some(st.spindle.rpm)) } else { cmd.speed };
        let rpm = s.filter(|s| *s > 0).ok_or(AlarmKind::RigidTapSpeed)?;
        st.cycle.rigid = RigidTap::Pending { rpm, before: st.spindle.dir };
    } else if matches!(st.cycle.rigid, RigidTap::Pending { .. }) && !taps {
        if cmd.speed.is_some() {
            return Err(AlarmKind::RigidTapSequence);
        }
        if cmd.has_axes() {
            return Err(AlarmKind::RigidTapAxisMove);
        }
    }
    if cmd.g.motion.is_some() && cmd.g.drilling.is_none() {
        st.modal.drilling = GCode::DrillCancel;
        st.cycle.rigid = RigidTap::Off;
    }
    if cmd.g.drilling == Some(GCode::DrillCancel) {
        st.cycle.hole = Default::default();
        st.cycle.rigid = RigidTap::Off;
    }
    Ok(chained)
}

/// M29 stops the spindle ("in the M29 block the spindle output is S0", 2.22.1).
pub fn after_spindle(cmd: &Command, st: &mut State, out: &mut Staged<'_>) -> Result<(), AlarmKind> {
    if cmd.m.iter().any(|&(m, _)| m == 29) && st.spindle.dir != SpindleDir::Stop {
        st.spindle.dir = SpindleDir::Stop;
        out.emit(crate::canon::Action::Spindle(crate::canon::SpindleCommand {
            dir: SpindleDir::Stop,
            rpm: None,
            css: None,
        }))?;
    }
    Ok(())
}

/// The cycle code that takes the block's motion, if any.
#[inline(always)]
pub fn cycle_of(cmd: &Command, st: &State) -> Option<GCode> {
    let user = cmd.axis_user(st);
    args::is_cycle(user).then_some(user)
}

/// Executes the block's cycle, if it has one; false if the block is not a cycle
/// block (plain motion goes on as usual).
#[inline(always)]
pub fn execute<X: Executor>(
    cmd: &Command,
    st: &mut State,
    ctx: &mut Ctx<'_, '_>,
    chained: bool,
) -> Result<bool, AlarmKind> {
    let Some(code) = cycle_of(cmd, st) else { return Ok(false) };
    cycle_block::<X>(code, cmd, st, ctx, chained)
}

/// [`execute`] of the block's cycle `code`.
#[inline(never)]
fn cycle_block<X: Executor>(
    code: GCode,
    cmd: &Command,
    st: &mut State,
    ctx: &mut Ctx<'_, '_>,
    chained: bool,
) -> Result<bool, AlarmKind> {
    if code == GCode::CycleCall {
        X::cycle_call(cmd, st, ctx)?;
        return Ok(true);
    }
    if args::is_thread(code) {
        single::thread_block(cmd, st, ctx, chained)?;
        return Ok(true);
    }
    if args::is_hole(code) {
        hole_cycle(code, cmd, st, ctx)?;
        return Ok(true);
    }
    if st.modal.plane != Plane::Zx {
        return Err(AlarmKind::CycleNotInZxPlane);
    }
    for a in [crate::axis::Axis::Y, crate::axis::Axis::C] {
        if cmd.axes[a.index()].is_some() && !(code == GCode::ThreadCycle && a == crate::axis::Axis::C) {
            return Err(AlarmKind::CycleOtherAxis { letter: a.letter() });
        }
    }
    match code {
        GCode::TurningCycle | GCode::FacingCycle | GCode::ThreadCycle => single_cycle(code, cmd, st, ctx)?,
        _ => multiple::<X>(code, cmd, st, ctx)?,
    }
    Ok(true)
}

/// A hole cycle's block (G83–G89 of a lathe, G73–G89 of a machining centre). Out of
/// line: its emitter (a copy of the state) stays out of [`cycle_block`]'s frame,
/// which is on the recursion of a G71–G73 profile (docs/STACK.md).
#[inline(never)]
fn hole_cycle(code: GCode, cmd: &Command, st: &mut State, ctx: &mut Ctx<'_, '_>) -> Result<(), AlarmKind> {
    let block = if crate::MILL && args::is_mill_hole(code) { drilling::hole_block } else { single::hole_block };
    if let Some(generator) = block(code, cmd, st, ctx.cfg)? {
        let em = Emitter { lead: generator.lead(), ..Emitter::for_block(st, cmd.line) };
        start_cycle(em, Gen::Hole(generator), ctx.out)?;
    }
    Ok(())
}

/// G90/G92/G94's block, out of line as [`hole_cycle`].
#[inline(never)]
fn single_cycle(code: GCode, cmd: &Command, st: &mut State, ctx: &mut Ctx<'_, '_>) -> Result<(), AlarmKind> {
    if let Some(generator) = single::single_block(code, cmd, st, ctx.cfg)? {
        start_cycle(Emitter::for_block(st, cmd.line), generator, ctx.out)?;
    }
    Ok(())
}

/// G70–G76: the setup blocks write their parameters, the cycles start their
/// expansion (G71–G73 read their shape straight into it).
fn multiple<X: Executor>(code: GCode, cmd: &Command, st: &mut State, ctx: &mut Ctx<'_, '_>) -> Result<(), AlarmKind> {
    use CycleArgs::{Finish, Groove, GrooveSetup, MultiThread, PatternSetup, RoughSetup, Shape, ThreadSetup};
    let cfg = ctx.cfg;
    let p = |id| cfg.params.get(id);
    let em = Emitter::for_block(st, cmd.line);
    let here = em.here(cfg);
    let generator = match cmd.cycle {
        RoughSetup { depth, retract } => {
            write(ctx, Param::RoughingDepth, depth)?;
            write(ctx, Param::RoughingRetract, retract)?;
            return Ok(());
        }
        PatternSetup { di, dk, count } => {
            write(ctx, Param::PatternReliefX, di)?;
            write(ctx, Param::PatternReliefZ, dk)?;
            write(ctx, Param::PatternDivisions, count.map(i64::from))?;
            return Ok(());
        }
        GrooveSetup { retract } => {
            write(ctx, Param::GrooveRetract, retract)?;
            return Ok(());
        }
        ThreadSetup { packed, min_depth, allowance } => {
            if let Some((m, r, a)) = packed {
                write(ctx, Param::ThreadFinishCount, Some(i64::from(m)))?;
                write(ctx, Param::ThreadChamfer, Some(i64::from(r)))?;
                write(ctx, Param::ThreadToolAngle, Some(i64::from(a)))?;
            }
            write(ctx, Param::ThreadMinDepth, min_depth)?;
            write(ctx, Param::ThreadFinishAllowance, allowance)?;
            return Ok(());
        }
        Finish { ns, nf } => {
            let src = ShapeSource { program: ctx.out.program, ns, nf };
            Gen::Finish(FinishGen::new(profile::start_of(&src)?, ns, nf, here, X::execute))
        }
        Shape { ns, nf, du, dw } => {
            let (src, env) = (ShapeSource { program: ctx.out.program, ns, nf }, ctx.env);
            // The shape is read straight into the expansion (its generator follows).
            let exp = start_cycle(em, Gen::Plan(heapless::Vec::new()), ctx.out)?;
            let shape = &mut exp.profile;
            let resume = profile::read_profile(&src, st, cfg, env, X::execute, shape, &mut exp.tail)?;
            let allowance = Pt::new(du, dw);
            exp.generator = if code == GCode::PatternCycle {
                let count = u32::try_from(p(Param::PatternDivisions)).unwrap_or(0);
                let relief = Pt::new(p(Param::PatternReliefX), p(Param::PatternReliefZ));
                Gen::Pattern(PatternGen::new(here, relief, count, allowance)?)
            } else {
                let spec = rough::RoughSpec {
                    facing: code == GCode::RoughFaceCycle,
                    start: here,
                    depth: p(Param::RoughingDepth),
                    retract: p(Param::RoughingRetract),
                    allowance,
                };
                Gen::Rough(RoughGen::new(&spec, shape)?)
            };
            // The shape's blocks only describe it: the program goes on after nf.
            ctx.out.resume = Some(resume);
            return Ok(());
        }
        Groove { p: di, q: dk, relief } => {
            let end = target(cmd, st, cfg)?;
            let face = code == GCode::FacePeckCycle;
            Gen::Groove(GrooveGen::new(face, here, end, di, dk, relief, p(Param::GrooveRetract))?)
        }
        MultiThread { taper, height, first, lead } => {
            let lead = lead.unwrap_or(st.cycle.lead);
            args::check_lead(lead, st.modal.units)?;
            st.cycle.lead = lead;
            let (start, end) = (here, target(cmd, st, cfg)?);
            if end.x == start.x {
                return Err(AlarmKind::CycleValueIllegal { what: "G76 end point X equals the start point X" });
            }
            let height = height.unwrap_or(0);
            // The thread's line at depth 0: from B (the end's X + i, raised by k,
            // on the start's Z) to D raised by k.
            let inward = sign(end.x - start.x);
            let b = Pt::new(end.x + taper - inward * height, start.z);
            let d = Pt::new(end.x - inward * height, end.z);
            let angle_deg = p(Param::ThreadToolAngle);
            let spec = thread::MultiThreadSpec {
                start,
                points: [b, d, d, d],
                count: 2,
                leads: [lead; 3],
                face: false,
                inward,
                height,
                allowance: p(Param::ThreadFinishAllowance),
                depths: thread::Depths::Root { first: first.unwrap_or(0), min_depth: p(Param::ThreadMinDepth) },
                finish: u32::try_from(p(Param::ThreadFinishCount)).unwrap_or(0),
                flank: thread::Flank::FromStart { angle_udeg: angle_deg * 500_000 },
                pull: thread::Pullout { tenths: p(Param::ThreadChamfer), angle_deg: p(Param::ThreadChamferAngle) },
                retract: start.x,
                starts: 1,
                start_udeg: 0,
            };
            Gen::MultiThread(MultiThreadGen::new(spec)?)
        }
        _ => return Ok(()),
    };
    start_cycle(em, generator, ctx.out).map(|_| ())
}

/// G02.1/G03.1 and G02.2/G03.2 (2.4, 2.5): the curve's cuts as an expansion.
pub fn curve_block(
    cmd: &Command,
    st: &mut State,
    cfg: &MachineConfig,
    out: &mut CycleStage<'_>,
) -> Result<(), AlarmKind> {
    use GCode::*;
    if st.modal.plane != Plane::Zx {
        return Err(AlarmKind::CycleNotInZxPlane);
    }
    for a in [crate::axis::Axis::Y, crate::axis::Axis::C] {
        if cmd.axes[a.index()].is_some() {
            return Err(AlarmKind::CycleOtherAxis { letter: a.letter() });
        }
    }
    let CycleArgs::Curve { a, b, p, q_udeg } = cmd.cycle else { return Ok(()) };
    let em = Emitter::new(*st, cmd.line);
    let (start, end) = (em.here(cfg), target(cmd, st, cfg)?);
    if start == end {
        return Ok(());
    }
    let tol = cfg.motion.chord_tolerance;
    let code = st.modal.motion;
    let missing = |letter| AlarmKind::MissingWord { letter, context: "G02.1/G03.1 and G02.2/G03.2" };
    let generator = match code {
        EllipseCw | EllipseCcw => {
            let (a, b) = (a.ok_or(missing(b'A'))?, b.ok_or(missing(b'B'))?);
            curve::CurveGen::ellipse(start, end, a, b, q_udeg, code == EllipseCw, tol)?
        }
        _ => curve::CurveGen::parabola(start, end, p.ok_or(missing(b'P'))?, q_udeg, code == ParabolaCw, tol)?,
    };
    start_cycle(em, Gen::Curve(generator), out).map(|_| ())
}

/// Polar interpolation (2.7): the virtual moves the contour layer let out for this
/// block become an expansion of real X/C moves. Actions before the first move stay
/// before it; the others follow the moves.
pub fn polar_block(st: &mut State, cfg: &MachineConfig, out: &mut CycleStage<'_>) -> Result<(), AlarmKind> {
    if !out.actions.iter().any(|c| c.action.endpoint().is_some()) {
        return Ok(());
    }
    // The moves leave the outbox; what stays keeps its order, the actions staged
    // before the first move ahead of the cycle and the rest (M05, M30 …) after it.
    // Rotated in place: copies of the outbox (2.3 KB each) would sit on the control
    // task's stack under the profile reader (firmware/stack-bound.py).
    let mut moves: heapless::Vec<Canon, { polar::MOVES }> = heapless::Vec::new();
    let mut before = 0;
    for _ in 0..out.actions.len() {
        let Some(c) = out.actions.pop_front() else { break };
        if c.action.endpoint().is_some() {
            moves.push(c).map_err(|_| AlarmKind::ContourBufferFull)?;
        } else {
            before += usize::from(moves.is_empty());
            // Never full: one action out, one back.
            out.actions.push_back(c).map_err(|_| AlarmKind::Overflow)?;
        }
    }
    let line = moves.first().map_or(0, |c| c.line);
    let generator = polar::PolarGen::new(&moves, emit::work_pos(st, cfg), cfg.motion.chord_tolerance)?;
    start_cycle(Emitter::for_block(st, line), Gen::Polar(generator), out)?;
    out.staged.split = Some(before);
    Ok(())
}

/// The block's X/Z target in work coordinates.
fn target(cmd: &Command, st: &State, cfg: &MachineConfig) -> Result<Pt, AlarmKind> {
    let w = crate::moves::motion::target(cmd, st, cfg)?;
    Ok(Pt::new(w[crate::axis::Axis::X], w[crate::axis::Axis::Z]))
}

/// Stages a parameter write (applied only if the block succeeds).
#[inline(never)]
fn write(ctx: &mut Ctx<'_, '_>, id: Param, v: Option<i64>) -> Result<(), AlarmKind> {
    if let Some(v) = v {
        ctx.out.writes.push((crate::stage::Setting::Param(id), v)).map_err(|_| AlarmKind::Overflow)?;
    }
    Ok(())
}

/// Hands the cycle to the interpreter, which dry-runs it ([`Expansion::dry_run`])
/// before the block commits: the expansion is built in the interpreter's slot
/// (never inlined: the ~5 KB value it builds stays out of the callers' frames,
/// which are on the stack while a shape's blocks run).
#[inline(never)]
fn start_cycle<'s>(em: Emitter, generator: Gen, out: &'s mut CycleStage<'_>) -> Result<&'s mut Expansion, AlarmKind> {
    Ok(out.cycle_slot()?.insert(Expansion::new(em, generator, Profile::default())))
}

/// Actions one dry-run chunk covers: a step of the interpreter validates at most
/// this many (about 0.2 M instructions on the Cortex-M4) before returning.
pub const DRY_RUN_CHUNK: u32 = 128;

impl Expansion {
    /// Runs the dry-run copy of a cycle for at most [`DRY_RUN_CHUNK`] actions,
    /// raising any alarm the cycle would raise; true when it has run to the end.
    pub fn dry_run<E: Environment + ?Sized>(
        &mut self,
        cfg: &MachineConfig,
        program: crate::lang::ProgramText<'_>,
        env: &E,
    ) -> Result<bool, AlarmKind> {
        self.run(cfg, program, env, &mut Dry(DRY_RUN_CHUNK))
    }

    /// Once the dry run (`self`) has ended: the state the cycle block commits,
    /// from the block's state `st` — the position back at the start point, the
    /// spindle as the cycle leaves it (floating tapping stops it, 2.22.3 note 2;
    /// rigid tapping restores it) and, after G70, the modal changes of its blocks.
    pub fn settle(&self, st: &mut State, cfg: &MachineConfig) {
        settle(&self.final_state(), &self.generator, st, cfg);
    }
}

/// The state a cycle block commits after its dry run ended in `end` with the
/// generator `generator`, from the block's state `st` ([`Expansion::settle`]).
fn settle(end: &State, generator: &Gen, st: &mut State, cfg: &MachineConfig) {
    st.pos = end.pos;
    st.moved |= end.moved;
    if matches!(generator, Gen::Finish(_)) {
        let cycle = st.cycle;
        *st = *end;
        st.cycle.single = cycle.single;
    }
    st.spindle.dir = end.spindle.dir;
    if crate::MILL && st.mill.frame.active != 0 {
        // A machining centre's transformation: the programmed position is where
        // the cycle left the tool.
        crate::moves::frame::resync(st, cfg);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The expansion lives in the interpreter on a 128 KB board: keep it small.
    #[test]
    fn expansion_size_is_bounded() {
        let exp = core::mem::size_of::<Expansion>();
        let interp = core::mem::size_of::<crate::Interpreter>();
        // (Its tail is an outbox, 1.7 KB more: the G71–G73 shape reader's
        // staging, which was on the stack under the shape's blocks.)
        assert!(exp < 8 * 1024, "Expansion is {exp} bytes");
        // The macro variables (2.24.1: the levels' #1–#33, the commons, a pool of
        // the others; 4,240 bytes, was 8,024 as a dense #1–#999), the 12-level
        // call stack and the dry-run copy of a cycle block being validated (was a
        // second expansion, now `DryRun`: 2.3 KB, the shape stays shared) live in the interpreter too: 28,264 bytes on a 64-bit
        // host (was 30,608), 27,592 on the M4 (was 29,888). So does the checked command reused
        // from block to block (336 bytes here, 304 on the M4): returning it by
        // value cost ~330 instructions a block. And the FANUC macro calls' state:
        // a call block as read with its arguments (264 + 24), the G66 modal calls
        // (832), the call codes (64). And a machining centre's part of the
        // configuration (the 48 G54.1 offsets, 576 bytes) and of the state (~150
        // bytes in each of its four copies).
        let vars = core::mem::size_of::<crate::lang::fanuc::macros::Variables>();
        assert!(vars <= 4_240, "Variables is {vars} bytes");
        let calls = core::mem::size_of::<crate::lang::fanuc::calls::CallRead>()
            + core::mem::size_of::<crate::lang::fanuc::calls::ModalCalls>()
            + core::mem::size_of::<crate::lang::fanuc::calls::CallCodes>();
        // The SINUMERIK front end's state (its variables and modal call; issue 19),
        // its part of the 12 call frames and the modal state PROC … SAVE keeps add
        // ~2.1 KB (in every build: the interpreter keeps the state's place).
        let siemens = core::mem::size_of::<crate::lang::siemens::vars::Vars>()
            + core::mem::size_of::<crate::lang::siemens::call::CallArgs>()
            + 1024;
        // A build with CYCLE73 (the host: `mill-island` needs a heap) keeps the
        // contours CYCLE74/CYCLE75 name and a drilling pattern of listed points.
        #[cfg(feature = "mill-island")]
        let island = core::mem::size_of::<heapless::Vec<crate::interpreter::siemens::PocketContour, 16>>()
            + cycle_paths::holes::LISTED_MAX * 16;
        #[cfg(not(feature = "mill-island"))]
        let island = 0;
        let siemens = siemens + island;
        assert!(interp < 17 * 1024 + 1_536 + vars + exp + calls + siemens, "Interpreter is {interp} bytes");
        // 28,264 on main before the mill profile; the mill adds 1,200 (G54.1 table,
        // the mill's part of the state in the interpreter's and the dry run's copies).
        assert!(interp <= 29_464 + siemens, "Interpreter is {interp} bytes");
    }
}

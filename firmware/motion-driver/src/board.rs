//! The board's motion types, and the hot code over them as plain (non-generic)
//! functions: the bodies of the step, period and encoder-count interrupts and the
//! control task's planner push.
//!
//! Why they are here: a generic function is compiled at the opt-level of the crate
//! that instantiates it. Called generically from the firmware crate (built for size,
//! "z": docs/FIRMWARE-SIZES.md), `Engine<3>`, `MotionCore<QUEUE>` and `Player<RING, 3>`
//! would be compiled at "z" too, and the 3000 rpm spindle-sync interrupt would cost
//! more than its 10 % of the CPU. Instantiated here, they are compiled at this
//! crate's level (the workspace's `Cargo.toml` sets it), whatever the caller's;
//! `#[inline(never)]` keeps the caller's size optimisations (the machine outliner of
//! a "z" function) out of them. m4-tests' benchmarks (`bench_isr`, `bench_interp`)
//! call these same functions, so their counts are the board's.

use motion_core::canon::{Canon, CanonSink, Full};
use motion_core::motion::{MotionCore, QUEUE};
use motion_core::planner::{MotionParams, Planner, PushError};

use crate::encoder::Window;
use crate::engine::{Engine, RING, Sample};
use crate::playback::{Out, Player};

/// Driven axes (step channels) of the board: X, Z and a third (C on a lathe, Y on a
/// mill).
pub const AXES: usize = 3;

/// The motion core with the board's look-ahead depth.
pub type Core = MotionCore<QUEUE>;
/// The period engine of the board's axes.
pub type BoardEngine = Engine<AXES>;
/// The step player of the board's axes.
pub type BoardPlayer = Player<RING, AXES>;

/// The period interrupt's body ([`Engine::period`]).
#[inline(never)]
pub fn period(engine: &mut BoardEngine, core: &mut Core, s: Sample) {
    engine.period(core, s);
}

/// The encoder-count interrupt's first part ([`Engine::encoder`]): whether an edge
/// was queued (the step interrupt should run now).
#[inline(never)]
pub fn encoder(engine: &mut BoardEngine, core: &mut Core, now: u32, raw_count: u32) -> bool {
    engine.encoder(core, now, raw_count)
}

/// The encoder compares after a period or a count ([`Engine::window`]).
#[inline(never)]
pub fn window(engine: &mut BoardEngine, core: &mut Core) -> Window {
    engine.window(core)
}

/// The step interrupt's body ([`Player::run`]).
#[inline(never)]
pub fn play(player: &mut BoardPlayer, now: u32, estop: bool) -> Out {
    player.run(now, estop)
}

/// Queues a canonical action in the motion core (the control task's push, one per
/// action the interpreter delivers: [`CanonSink::push_ref`] of the core).
#[inline(never)]
pub fn push(core: &mut Core, action: &Canon) -> Result<(), Full> {
    core.push_ref(action)
}

/// The planner's push of the board's queue depth ([`Planner::push`]): what
/// [`push`] runs per action, for the per-block benchmark (m4-tests `bench_interp`).
#[inline(never)]
pub fn plan(planner: &mut Planner<QUEUE>, action: &Canon, p: &MotionParams) -> Result<(), PushError> {
    planner.push(action, p)
}

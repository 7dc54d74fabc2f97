//! Instructions per interpreted block on the Cortex-M4F: one `Interpreter::step` for
//! a G01 block, a G02 block with R, and a G01 block under G96 (surface speed), each
//! read, checked and executed into a sink; then the same steps into the motion
//! planner (text to planned block: the step with its action queued, prepared and
//! look-ahead planned); then a machining centre's 3-axis G01 blocks the same two
//! ways; then the same for SINUMERIK `G1 X.. Z..` blocks (the machine's language
//! SINUMERIK, issue 19). Run through `bench.sh bench_interp`.
#![no_std]
#![no_main]

use cortex_m_rt::entry;
use cortex_m_semihosting::hprintln;
use interp_core::axis::Pos;
use interp_core::canon::{Canon, CanonSink, Full};
use interp_core::{Interpreter, MachineConfig, Panel, Progress, SingleProgram};
use m4_tests::{exit, measure};
use motion_core::motion::QUEUE;
use motion_core::planner::{MotionParams, Planner, PushError};

/// A CAM-style stretch: setup blocks, then the blocks measured one by one.
const PROGRAM: &[u8] = b"G00 X40. Z2.\nG99 M3 S1200\nG01 Z0 F0.12\n\
N100 G01 X40.412 Z-0.05\nN101 G01 X40.824 Z-0.1\nN102 G01 X41.234 Z-0.15\n\
N103 G02 X42.1 Z-1.2 R25.\nN104 G03 X43.05 Z-2.3 R25.\n\
G96 S200\nN105 G01 X43.5 Z-2.5\nN106 G01 X44.0 Z-2.7\nM30\n";

/// The same stretch in SINUMERIK: the blocks measured are plain `G1 X.. Z..`.
const SIEMENS_PROGRAM: &[u8] = b"G0 X40 Z2\nG95 M3 S1200\nG1 Z0 F0.12\n\
N100 G1 X40.412 Z-0.05\nN101 G1 X40.824 Z-0.1\nN102 G1 X41.234 Z-0.15\nM30\n";

/// What the steps of [`SIEMENS_PROGRAM`] read, in order.
const SIEMENS_LABELS: [&str; 6] = [
    "setup SINUMERIK G0",
    "setup SINUMERIK G95 M3 S",
    "setup SINUMERIK G1 F",
    "SINUMERIK G1",
    "SINUMERIK G1",
    "SINUMERIK G1",
];

/// A machining centre's stretch (`MachineConfig::mill`): setup, then 3-axis G01s.
const MILL_PROGRAM: &[u8] = b"G00 X-100. Y-100. Z-10.\nM3 S1200\nG01 Z-20. F300\n\
N100 G01 X-99.588 Y-99.712 Z-20.05\nN101 G01 X-99.176 Y-99.424 Z-20.1\nN102 G01 X-98.766 Y-99.137 Z-20.15\nM30\n";

/// What the steps of [`MILL_PROGRAM`] read, in order.
const MILL_LABELS: [&str; 6] =
    ["mill setup G00", "mill setup M3 S", "mill setup G01 F", "mill G01 XYZ", "mill G01 XYZ", "mill G01 XYZ"];

/// Keeps the last action so the work can't be optimised away.
struct Last(Option<Canon>);

impl CanonSink for Last {
    fn push(&mut self, c: Canon) -> Result<(), Full> {
        self.0 = Some(c);
        Ok(())
    }
}

/// The motion planner as the sink: each action is prepared and queued (what the
/// motion core's `push` does with it), through the non-generic push the firmware's
/// motion core runs (`motion_driver::board`).
struct Plan {
    planner: Planner<QUEUE>,
    params: MotionParams,
}

impl CanonSink for Plan {
    fn push(&mut self, c: Canon) -> Result<(), Full> {
        self.push_ref(&c)
    }

    /// As `MotionCore`'s: the action read where the interpreter keeps it.
    fn push_ref(&mut self, c: &Canon) -> Result<(), Full> {
        match motion_driver::board::plan(&mut self.planner, c, &self.params) {
            Err(PushError::Full) => Err(Full),
            // An alarm would stop the motion core; the benchmark's blocks raise none.
            Err(PushError::Alarm(_)) => exit(false),
            Ok(()) => Ok(()),
        }
    }
}

/// The interpreter, its sink, its program and its switches (held, as the board's
/// controller holds its panel), carried through `measure`.
struct Bench<S> {
    interp: Interpreter,
    sink: S,
    program: &'static [u8],
    panel: Panel,
}

/// Runs one step, through the non-generic entry the firmware's control task calls
/// (the program store and the sink behind `dyn`, as on the board).
fn step<S: CanonSink>(b: &mut Bench<S>) -> bool {
    let program = SingleProgram(b.program);
    matches!(b.interp.step_dyn(&program, &b.panel, &mut b.sink), Ok(Progress::Executed { .. }))
}

/// Runs the program's steps, measuring each (`only`: just the one at that index)
/// with the label `what: label`.
fn run<S: CanonSink>(b: &mut Bench<S>, what: &str, only: Option<usize>, labels: &[&str]) {
    for (k, &label) in labels.iter().enumerate() {
        if only.is_some_and(|o| o != k) {
            if !step(b) {
                exit(false);
            }
            continue;
        }
        hprintln!("bench {}: {}", what, label);
        if !measure(step, &mut *b) {
            hprintln!("unexpected result");
            exit(false);
        }
    }
}

/// What the steps of [`PROGRAM`] read, in order.
const LABELS: [&str; 11] = [
    "setup G00",
    "setup G99 M3 S",
    "setup G01 F",
    "G01",
    "G01",
    "G01",
    "G02 R",
    "G03 R",
    "G96 S",
    "G01 under G96",
    "G01 under G96",
];

#[entry]
fn main() -> ! {
    // `BENCH_ONLY=K` (at build time) measures only the K-th step, for a profile of
    // it; `BENCH_ONLY=pK` only the K-th step into the planner.
    let only = option_env!("BENCH_ONLY");
    let pick = |prefix: &str| only.and_then(|k| k.strip_prefix(prefix)?.parse::<usize>().ok());
    // `BENCH_ONLY=mK` / `mpK`: the K-th step of the mill's program.
    let (steps, planned) = match only {
        Some(k) if k.starts_with('m') => (Some(usize::MAX), Some(usize::MAX)),
        Some(k) if k.starts_with('p') => (Some(usize::MAX), pick("p")),
        Some(_) => (pick(""), Some(usize::MAX)),
        None => (None, None),
    };
    let (mill_steps, mill_planned) = match only {
        Some(k) if k.starts_with("mp") => (Some(usize::MAX), pick("mp")),
        Some(k) if k.starts_with('m') => (pick("m"), Some(usize::MAX)),
        Some(_) => (Some(usize::MAX), Some(usize::MAX)),
        None => (None, None),
    };
    let cfg = MachineConfig::default();
    let mut b =
        Bench { interp: Interpreter::new(cfg.clone()), sink: Last(None), program: PROGRAM, panel: Panel::default() };
    run(&mut b, "step", steps, &LABELS);
    hprintln!("size of Interpreter: {} bytes", core::mem::size_of::<Interpreter>());
    let Ok(params) = MotionParams::new(&cfg) else { exit(false) };
    let plan = Plan { planner: Planner::new(Pos::ZERO), params };
    let mut b = Bench { interp: Interpreter::new(cfg), sink: plan, program: PROGRAM, panel: Panel::default() };
    run(&mut b, "text to planned block", planned, &LABELS);
    let cfg = MachineConfig::mill();
    let mut b = Bench {
        interp: Interpreter::new(cfg.clone()),
        sink: Last(None),
        program: MILL_PROGRAM,
        panel: Panel::default(),
    };
    run(&mut b, "step", mill_steps, &MILL_LABELS);
    let Ok(params) = MotionParams::new(&cfg) else { exit(false) };
    let plan = Plan { planner: Planner::new(Pos::ZERO), params };
    let mut b = Bench { interp: Interpreter::new(cfg), sink: plan, program: MILL_PROGRAM, panel: Panel::default() };
    run(&mut b, "text to planned block", mill_planned, &MILL_LABELS);
    // SINUMERIK (not with BENCH_ONLY: its indexes are the FANUC program's).
    if only.is_none() {
        let cfg = MachineConfig { language: interp_core::config::Language::Siemens, ..MachineConfig::default() };
        let mut b = Bench {
            interp: Interpreter::new(cfg.clone()),
            sink: Last(None),
            program: SIEMENS_PROGRAM,
            panel: Panel::default(),
        };
        b.interp.plug(&interp_siemens::SINUMERIK);
        run(&mut b, "step", None, &SIEMENS_LABELS);
        let Ok(params) = MotionParams::new(&cfg) else { exit(false) };
        let plan = Plan { planner: Planner::new(Pos::ZERO), params };
        let mut b =
            Bench { interp: Interpreter::new(cfg), sink: plan, program: SIEMENS_PROGRAM, panel: Panel::default() };
        b.interp.plug(&interp_siemens::SINUMERIK);
        run(&mut b, "text to planned block", None, &SIEMENS_LABELS);
    }
    exit(true)
}

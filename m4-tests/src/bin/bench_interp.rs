//! Instructions per interpreted block on the Cortex-M4F: one `Interpreter::step` for
//! a G01 block, a G02 block with R, and a G01 block under G96 (surface speed), each
//! read, checked and executed into a sink. Run through `bench.sh bench_interp`.
#![no_std]
#![no_main]

use cortex_m_rt::entry;
use cortex_m_semihosting::hprintln;
use interp_core::canon::{Canon, CanonSink, Full};
use interp_core::{Interpreter, MachineConfig, Panel, Progress, SingleProgram};
use m4_tests::{exit, measure};

/// A CAM-style stretch: setup blocks, then the blocks measured one by one.
const PROGRAM: &[u8] = b"G00 X40. Z2.\nG99 M3 S1200\nG01 Z0 F0.12\n\
N100 G01 X40.412 Z-0.05\nN101 G01 X40.824 Z-0.1\nN102 G01 X41.234 Z-0.15\n\
N103 G02 X42.1 Z-1.2 R25.\nN104 G03 X43.05 Z-2.3 R25.\n\
G96 S200\nN105 G01 X43.5 Z-2.5\nN106 G01 X44.0 Z-2.7\nM30\n";

/// Keeps the last action so the work can't be optimised away.
struct Last(Option<Canon>);

impl CanonSink for Last {
    fn push(&mut self, c: Canon) -> Result<(), Full> {
        self.0 = Some(c);
        Ok(())
    }
}

/// The interpreter, its sink and its program, carried through `measure`.
struct Bench {
    interp: Interpreter,
    sink: Last,
}

/// Runs one step.
fn step(b: &mut Bench) -> bool {
    matches!(b.interp.step(&SingleProgram(PROGRAM), &Panel::default(), &mut b.sink), Ok(Progress::Executed { .. }))
}

#[entry]
fn main() -> ! {
    let mut b = Bench { interp: Interpreter::new(MachineConfig::default()), sink: Last(None) };
    let labels = [
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
    // `BENCH_ONLY=K` (at build time) measures only the K-th step, for a profile of it.
    let only = option_env!("BENCH_ONLY").and_then(|k| k.parse::<usize>().ok());
    for (k, label) in labels.into_iter().enumerate() {
        if only.is_some_and(|o| o != k) {
            if !step(&mut b) {
                exit(false);
            }
            continue;
        }
        hprintln!("bench step: {}", label);
        if !measure(step, &mut b) {
            hprintln!("unexpected result");
            exit(false);
        }
    }
    hprintln!("size of Interpreter: {} bytes", core::mem::size_of::<Interpreter>());
    exit(true)
}

//! Macro statements per second on the host.
//!
//! `cargo run --release -p host-tests --example macro_bench`
//!
//! Runs WHILE loops of typical statements (arithmetic, a trig function, a
//! comparison, END) through the interpreter — read from text and evaluated each
//! time, as the control does — and prints statements per second for each, and the
//! time one step of the default budget takes.

use std::hint::black_box;
use std::time::Instant;

use host_tests::VecSink;
use interp_core::interpreter::DEFAULT_STEP_BUDGET;
use interp_core::{Interpreter, MachineConfig, Panel, Progress, SingleProgram};

/// Loop iterations per program.
const ITERATIONS: u32 = 200_000;

/// A program whose loop body is `body` (statements per iteration: `per`).
struct Case {
    name: &'static str,
    body: &'static str,
    /// Statements per iteration, WHILE and END included.
    per: u32,
}

const CASES: &[Case] = &[
    Case { name: "counter only (WHILE, #1=#1+1, END)", body: "", per: 3 },
    Case { name: "arithmetic #2=[#1*2+3]/4-#2", body: "#2=[#1*2+3]/4-#2\n", per: 4 },
    Case { name: "function #2=SIN[#1]*2+SQRT[16]", body: "#2=SIN[#1]*2+SQRT[16]\n", per: 4 },
    Case { name: "IF [..] THEN and indirection", body: "IF [#1 GT 5] THEN #[10+[#1 MOD 5]]=ATAN[#1]/[3]\n", per: 4 },
];

fn main() {
    println!("macro statements per second (host, --release), {ITERATIONS} loop iterations each:");
    let panel = Panel::default();
    for case in CASES {
        let text = format!("#1=0\nWHILE [#1 LT {ITERATIONS}] DO1\n{}#1=#1+1\nEND1\nM30\n", case.body);
        let store = SingleProgram(text.as_bytes());
        let mut interp = Interpreter::new(MachineConfig::default());
        interp.set_step_budget(u16::MAX);
        let mut sink = VecSink::default();
        let mut steps = 0u64;
        let t = Instant::now();
        loop {
            match interp.step(&store, &panel, &mut sink) {
                Ok(Progress::Ended) => break,
                Ok(_) => steps += 1,
                Err(a) => panic!("{a}"),
            }
        }
        let secs = t.elapsed().as_secs_f64();
        let statements = f64::from(ITERATIONS) * f64::from(case.per);
        let rate = statements / secs;
        black_box(steps);
        println!(
            "  {:<48} {:>12.0} statements/s  ({:.2} us each; a step of {} takes ~{:.0} us)",
            case.name,
            rate,
            1e6 / rate,
            DEFAULT_STEP_BUDGET,
            f64::from(DEFAULT_STEP_BUDGET) * 1e6 / rate
        );
    }
}

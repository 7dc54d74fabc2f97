//! Instruction counts of macro statements on the emulated Cortex-M4F (f64 in
//! software). Run it through `bench.sh bench_macro`, which loads the icount plugin;
//! each measured call then prints `instructions: N`.
//!
//! At 168 MHz and roughly one instruction per cycle (more with flash wait states),
//! 100 000 instructions are about 0.6 ms: these counts size the interpreter's step
//! budget (`interp_core::interpreter::DEFAULT_STEP_BUDGET`).
#![no_std]
#![no_main]

use cortex_m_rt::entry;
use cortex_m_semihosting::hprintln;
use interp_core::canon::RecordingSink;
use interp_core::lang::fanuc::macros::Variables;
use interp_core::lang::fanuc::parse::{Statement, read_statement};
use interp_core::program::{ProgramMemory, ProgramStore};
use interp_core::units::NumberFormat;
use interp_core::{Alarm, Interpreter, MachineConfig, Panel, Progress, SingleProgram};
use m4_tests::{exit, measure};

/// Statements read and evaluated (not executed), one measured call each.
const STATEMENTS: &[&str] = &[
    "#2=#1+1",
    "#2=[#1*2+3]/4-#2",
    "#2=SIN[#1]*2+SQRT[16]",
    "IF [#1 GT 5] THEN #[10+[#1 MOD 5]]=ATAN[#1]/[3]",
    "WHILE [#1 LT 100] DO1",
    "G01 X[#1*2] Z-#2 F#3",
];

/// Reads one statement.
fn read(input: (&[u8], &Variables, &NumberFormat)) -> bool {
    let (text, vars, fmt) = input;
    matches!(read_statement(text, 1, vars, fmt), Ok(Statement::Macro(_) | Statement::Nc(_)))
}

/// The loop every step of the last measurement runs in.
const LOOP: &[u8] = b"#1=0\nWHILE [#1 LT 1000000] DO1\n#1=#1+1\nEND1\nM30\n";

/// One interpreter step: the default budget of statements (through the non-generic
/// entry the firmware's control task calls).
fn step<P: ProgramStore>(input: (&mut Interpreter, &P, &Panel)) -> Result<Progress, Alarm> {
    let (interp, store, panel) = input;
    let mut sink = RecordingSink::<1>::new();
    interp.step_dyn(store, panel, &mut sink)
}

/// G65 calls with two arguments (docs/MACROS.md), the macro one statement and M99.
const CALLS: &[u8] = b"G65 P9100 A1. B2.\nG65 P9100 A3. B4.\nG65 P9100 A5. B6.\nM30\n";
const MACRO: &[u8] = b"O9100\n#3=#1+#2\nM99\n";

#[entry]
fn main() -> ! {
    let mut vars = Variables::new();
    for (n, v) in [(1, 7.25), (2, 3.5), (3, 120.0)] {
        let _ = vars.set(n, Some(v));
    }
    let mut interp = Interpreter::new(MachineConfig::default());
    let fmt = interp.number_format();
    for s in STATEMENTS {
        hprintln!("bench read and evaluate: {}", s);
        measure(read, (s.as_bytes(), &vars, &fmt));
    }
    let store = SingleProgram(LOOP);
    let panel = Panel::default();
    // Warm up into the loop, then measure steps of the default budget.
    let _ = step((&mut interp, &store, &panel));
    hprintln!(
        "bench one step of {} statements (WHILE, #1=#1+1, END), 2 runs",
        interp_core::interpreter::DEFAULT_STEP_BUDGET
    );
    for _ in 0..2 {
        let r = measure(step, (&mut interp, &store, &panel));
        if !matches!(r, Ok(Progress::Yielded { .. })) {
            hprintln!("unexpected: {:?}", r);
            exit(false);
        }
    }
    // A G65 call, as three steps: the call block (a new level with #1, #2, into
    // O9100), the called program's O line, its #3=#1+#2 and the M99 back to level 0.
    // The first call runs unmeasured (warm-up), the second is measured.
    let mut memory = ProgramMemory::<256, 4, 8>::new();
    let (Ok(main), Ok(_)) = (memory.load(CALLS, Some(0)), memory.load(MACRO, None)) else { exit(false) };
    let mut interp = Interpreter::new(MachineConfig::default());
    interp.select_main(main);
    for _ in 0..3 {
        let _ = step((&mut interp, &memory, &panel));
    }
    for (what, level) in [
        ("G65 P9100 A3. B4. (call, 2 arguments)", 1),
        ("O9100 (the called program's O line)", 1),
        ("O9100: #3=#1+#2, M99 (return)", 0),
    ] {
        hprintln!("bench step: {}", what);
        let done = measure(step, (&mut interp, &memory, &panel));
        if !matches!(done, Ok(Progress::Executed { .. } | Progress::Skipped { .. })) || interp.macro_level() != level {
            hprintln!("unexpected: {:?} at level {}", done.map(|_| ()).is_ok(), interp.macro_level());
            exit(false);
        }
    }
    if interp.variables().get(3) != Ok(None) {
        hprintln!("unexpected: #3 of level 0 set");
        exit(false);
    }
    hprintln!("interpreter: {} bytes, variables: {} bytes", size_of::<Interpreter>(), size_of::<Variables>());
    exit(true)
}

//! Whatever the text, reading and running macro programs never panics (debug
//! builds check arithmetic overflow too).

use host_tests::{Memory, run_interp};
use interp_core::lang::fanuc::macros::Variables;
use interp_core::lang::fanuc::parse::read_statement;
use interp_core::{Interpreter, MachineConfig, Panel, SingleProgram};
use proptest::prelude::*;

/// Pieces programs are made of, valid and not.
const PIECES: &[&str] = &[
    "#",
    "#1",
    "#0",
    "#999",
    "#1000",
    "#[",
    "[",
    "]",
    "=",
    "+",
    "-",
    "*",
    "/",
    ",",
    ".",
    "0",
    "1",
    "9",
    "90",
    "0.5",
    "123456789",
    "1e3",
    " ",
    "SIN",
    "COS",
    "TAN",
    "ASIN",
    "ACOS",
    "ATAN",
    "SQRT",
    "ABS",
    "ROUND",
    "FIX",
    "FUP",
    "EXP",
    "MAX",
    "MIN",
    "MOD",
    "AND",
    "OR",
    "XOR",
    "EQ",
    "NE",
    "GT",
    "GE",
    "LT",
    "LE",
    "==",
    "<>",
    "<",
    ">=",
    "IF",
    "GOTO",
    "THEN",
    "WHILE",
    "DO",
    "END",
    "DO1",
    "END1",
    "DO2",
    "END2",
    "N",
    "N10",
    "G01",
    "G00",
    "X",
    "Z",
    "U",
    "F",
    "M98",
    "M99",
    "M91",
    "M92",
    "P",
    "L",
    "P12",
    "P10",
    "M30",
    "(",
    ")",
    "%",
    "O0012",
    "\n",
    ";",
    "/",
];

fn program() -> impl Strategy<Value = String> {
    prop::collection::vec(prop::sample::select(PIECES), 0..60).prop_map(|v| v.concat())
}

proptest! {
    // 2000 cases unless PROPTEST_CASES says otherwise.
    #![proptest_config(ProptestConfig::with_cases(
        std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(2000)
    ))]

    #[test]
    fn reading_never_panics(text in program(), seed in prop::collection::vec(-1e6f64..1e6, 0..8)) {
        let mut vars = Variables::new();
        for (i, v) in seed.iter().enumerate() {
            vars.set(i as u16 + 1, Some(*v)).unwrap();
        }
        let fmt = Interpreter::new(MachineConfig::default()).number_format();
        let _ = read_statement(text.as_bytes(), 1, &vars, &fmt);
    }

    #[test]
    fn running_never_panics(main in program(), sub in program()) {
        let store = SingleProgram(main.as_bytes());
        let _ = run_interp(Interpreter::new(MachineConfig::default()), &store, &Panel::default(), 300);
        let mut memory = Box::new(Memory::new());
        let _ = memory.load(main.as_bytes(), Some(0));
        let _ = memory.load(format!("O0012\n{sub}\nM99\n").as_bytes(), None);
        let _ = run_interp(Interpreter::new(MachineConfig::default()), &*memory, &Panel::default(), 300);
    }
}

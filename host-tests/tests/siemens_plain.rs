//! SINUMERIK's short way for plain lines (issue 19): a line of plain words and
//! numbers (`N.. G1 X40.412 Z-0.05 F.2`) is read by the shared plain reader and
//! checked with SINUMERIK's meanings in interp-core, not by the front end's
//! general statement reader. It must do exactly what the general way does: the
//! same actions and the same alarms, step by step, and the same state after,
//! in every state the words' meanings depend on (G90/G91, DIAMON/DIAMOF,
//! G94/G95, G96 with LIMS=, inch, a work offset, inside a PROC and a REPEAT).

use host_tests::VecSink;
use interp_core::canon::Canon;
use interp_core::command::Command;
use interp_core::config::Language;
use interp_core::lang::fanuc::check::sinumerik_plain;
use interp_core::lang::fanuc::parse::{Block, read_plain_line};
use interp_core::{Alarm, Interpreter, MachineConfig, Panel, Progress, SingleProgram};
use proptest::prelude::*;

fn cfg() -> MachineConfig {
    MachineConfig { language: Language::Siemens, ..MachineConfig::default() }
}

/// What the lines put the machine into before the lines compared run (read the
/// general way either way: they hold names and `=`).
const STATES: &[&str] = &[
    "G90 G95 M3 S1000",
    "G91 G95 M3 S1000",
    "DIAMOF G90 G94 M3 S800",
    "DIAMOF G91 G94 M4 S800",
    "G96 S200 LIMS=3000 M3",
    "DIAMOF G96 S150 LIMS=2500 M4 G91",
    "G70 G90 G95 M3 S500",
    "G55 G0 X100 Z50 G95 M3 S600",
];

/// Lines compared, and whether the short way takes them (from the power-on
/// state; the others go the general way: names, `=`, words or codes the short
/// way leaves to it, and every alarm of reading and checking).
const LINES: &[(&str, bool)] = &[
    ("N100 G1 X40.412 Z-0.05 F.2", true),
    ("N101 G1 X40.824 Z-0.1", true),
    ("X41.234 Z-0.15", true),
    ("G0 X50 Z2", true),
    ("g1 x30 z-10 f0.1", true),
    ("n20 G01 X+10. Z-.5", true),
    ("G1X10Z5F100", true),
    ("G95 G1 X20 F0.15", true),
    ("G94 G1 Z-3 F120", true),
    ("G96 S180", true),
    ("G97 S1200 M3", true),
    ("G90 X12 Z-1", true),
    ("G91 X-1 Z-1", true),
    ("G90", true),
    ("G1 X10 M8", true),
    ("M9", true),
    ("M5", true),
    ("M3 S500", true),
    ("S12.5", true),
    ("G1 Z-5 F0", true),
    ("G2 X30 Z-20", true),
    ("G3 X32 Z-21", true),
    ("G17 G1 X5", true),
    ("G18", true),
    ("G40 G1 X5 Z5", true),
    ("G54 G0 X0 Z0", true),
    ("G71 G1 X5", true),
    ("G70 G1 X1 Z-0.5", true),
    ("G71", true),
    ("G60 G1 X5", true),
    ("G64 X6", true),
    ("N30", true),
    ("", true),
    ("; a comment", true),
    ("N40 ; a comment", true),
    ("G1 X5 ; a move", true),
    ("G1 X999999999.999 Z0", true),
    ("G1 X0.123456789", true),
    ("M1", true),
    ("G1 X5 M3 M8", true),
    ("G1 G90 G95 G18 G40 G54 G64 G71 X5", true),
    ("M3 M8 M5 M9", false),
    ("M3 M8 M10 M13", false),
    ("G0 G90 G95 G18 G40 G54 G64 G71 G17 X5", false),
    ("M4 S-5", false),
    ("S100000", false),
    ("F-1", false),
    ("G1 X1 X2", false),
    ("G0 G1 X5", false),
    ("G95 G96 X1", false),
    ("G1.5 X1", false),
    ("G4 F2", false),
    ("G1 Y5", false),
    ("G1 X1.5EX1", false),
    ("G1 X=10", false),
    ("G1 X=IC(2)", false),
    ("G1 X10 RND=2", false),
    ("G1 X1234567890", false),
    ("G1 X0.0000000001", false),
    ("G1 X5 T1", false),
    ("D1", false),
    ("G1 X5 M3 M4", false),
    ("G1 X5 M3 M3", false),
    ("M6", false),
    ("G33 Z-10 K2", false),
    ("X-", false),
    ("X -5", false),
    ("N10 N20 X1", false),
    ("N10.5 X1", false),
    ("G1 X10 H1", false),
    ("G1 X10 R1", false),
    ("DIAMOF X10", false),
    ("G1 X10 E5", false),
    ("G9 X10", false),
    ("G12 X10", false),
    ("M98", false),
    ("LABEL: G1 X10", false),
    ("/ G1 X10", false),
    ("G1 X10 (no comment)", false),
];

/// One step: what it returned and the actions it delivered.
type StepRecord = (Result<Progress, Alarm>, Vec<Canon>);

/// Runs `text` to its end, recording every step; `general`: every line the
/// front end's general way.
fn run(text: &str, general: bool) -> (Vec<StepRecord>, Interpreter) {
    let mut interp = Interpreter::new(cfg());
    interp.plug(&interp_siemens::SINUMERIK);
    interp.set_siemens_general(general);
    let program = SingleProgram(text.as_bytes());
    let mut steps = Vec::new();
    for _ in 0..10_000 {
        let mut sink = VecSink::default();
        let r = interp.step(&program, &Panel::default(), &mut sink);
        let end = r == Ok(Progress::Ended);
        if r == Ok(Progress::Paused) {
            interp.cycle_start();
        }
        steps.push((r, sink.0));
        if end {
            break;
        }
    }
    (steps, interp)
}

/// Runs `text` both ways and asserts they do the same, step by step.
fn same(text: &str) {
    let (short, a) = run(text, false);
    let (general, b) = run(text, true);
    assert_eq!(short.len(), general.len(), "{text}");
    for (k, (s, g)) in short.iter().zip(&general).enumerate() {
        assert_eq!(s, g, "step {k} of:\n{text}");
    }
    assert_eq!(a.state(), b.state(), "{text}");
    assert_eq!((a.cursor(), a.block_start(), a.language()), (b.cursor(), b.block_start(), b.language()), "{text}");
}

/// Every line on its own, after every state; then all lines in a row after
/// every state (positions, feeds and modes carried from line to line).
#[test]
fn plain_lines_run_as_the_general_way() {
    for state in STATES {
        for (line, _) in LINES {
            same(&format!("G0 X60 Z10\n{state}\nG1 X50 Z5 F0.2\n{line}\nG1 X40 Z0\nM30\n"));
        }
        let all: Vec<&str> = LINES.iter().map(|(l, _)| *l).collect();
        same(&format!("G0 X60 Z10\n{state}\n{}\nM30\n", all.join("\n")));
    }
}

/// The same inside a PROC (a call frame; labels of its level) and a REPEAT
/// section (its lines go the general way: the section's end is the front end's).
#[test]
fn plain_lines_in_procs_and_repeat_sections() {
    let all: Vec<&str> = LINES.iter().map(|(l, _)| *l).collect();
    let body = all.join("\n");
    same(&format!("G0 X60 Z10 G95 M3 S900\nSUB1\nM30\nPROC SUB1\n{body}\nM17\n"));
    same(&format!(
        "G0 X60 Z10 G95 M3 S900\nSTART:\nG1 X50 Z5 F0.2\nX40 Z0\nEND1:\nREPEAT START END1 P=2\n{body}\nM30\n"
    ));
    same(&format!("G0 X60 Z10 G95 M3 S900\nMCALL CYCLE82(2, 0, 1, -5, , 0)\nG0 X0 Z5\nMCALL\n{body}\nM30\n"));
}

/// The short way takes the lines marked so (the comparison above is not only
/// the general way against itself), and leaves the others to the general way.
#[test]
fn the_short_way_takes_plain_lines_only() {
    let interp = Interpreter::new(cfg());
    let mut block = Block::default();
    let mut cmd = Command::EMPTY;
    for (line, short) in LINES {
        let taken = read_plain_line(line.as_bytes(), 1, &mut block)
            && (block.is_empty() || sinumerik_plain(&block, interp.state(), interp.config(), &mut cmd));
        assert_eq!(taken, *short, "{line}");
    }
}

/// What random lines are made of: the short way's words and numbers, and what
/// lies just beside them (other letters, signs, points, `=`, names, comments).
const PIECES: &[&str] = &[
    "G",
    "G",
    "G",
    "M",
    "X",
    "X",
    "Z",
    "Z",
    "Y",
    "F",
    "S",
    "N",
    "T",
    "D",
    "R",
    "E",
    "I",
    "K",
    "C",
    "1",
    "1",
    "0",
    "01",
    "2",
    "3",
    "17",
    "18",
    "40",
    "54",
    "70",
    "71",
    "90",
    "91",
    "94",
    "95",
    "96",
    "97",
    "5",
    "8",
    "30",
    "12.5",
    ".5",
    "10.",
    "0.000001",
    "999999999",
    "1234567890",
    "-",
    "-",
    "+",
    ".",
    " ",
    " ",
    " ",
    "\t",
    ";",
    "=",
    "DIAMOF",
    "(",
];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Random lines near the short way's, after a random state, run both ways:
    /// the same, step by step.
    #[test]
    fn random_lines_run_as_the_general_way(
        state in prop::sample::select(STATES),
        lines in prop::collection::vec(prop::collection::vec(prop::sample::select(PIECES), 0..12), 1..8),
    ) {
        let body: Vec<String> = lines.iter().map(|l| l.concat()).collect();
        same(&format!("G0 X60 Z10\n{state}\nG1 X50 Z5 F0.2\n{}\nM30\n", body.join("\n")));
    }
}

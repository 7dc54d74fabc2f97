//! M98/M99 subprograms (3.1.6, 3.1.7, seed 003 2.5.1), M91/M92 jumps (3.1.5), MDI.

use host_tests::{VecSink, kind_names, memory, path, run, run_interp, run_lib, run_programs};
use interp_core::canon::Action;
use interp_core::{AlarmKind, Interpreter, MachineConfig, Panel, Progress};

const SUB12: &str = "O0012 (step in by 2 on the diameter)\nG01 U-2 F100\nM99\n";

fn clean(main: &str, library: &[&str]) -> host_tests::Run {
    let r = run_lib(main, library);
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    r
}

#[test]
fn m98_calls_and_m99_returns_after_the_calling_block() {
    let r = clean("G00 X50 Z10\nM98 P12\nG00 X60 Z20\nM30\n", &[SUB12]);
    assert_eq!(path(&r), vec![(50.0, 10.0), (48.0, 10.0), (60.0, 20.0)]);
    assert_eq!(r.actions[1].line, 2, "the subprogram's own line");
    assert_eq!(r.interp.call_depth(), 0);
}

#[test]
fn repetitions_packed_p_and_l() {
    for call in ["M98 P30012", "M98 P12 L3", "M98 P0012 L3"] {
        let r = clean(&format!("G00 X50 Z10\n{call}\nM30\n"), &[SUB12]);
        assert_eq!(path(&r), vec![(50.0, 10.0), (48.0, 10.0), (46.0, 10.0), (44.0, 10.0)], "{call}");
    }
    let r = run_lib("M98 P20012 L3\nM30\n", &[SUB12]);
    assert_eq!(r.alarm_codes(), vec![(1, 4011)], "with L, P is the program number only");
    let r = run_lib("M98 P12 L0\nM30\n", &[SUB12]);
    assert_eq!(r.alarm_codes(), vec![(1, 4011)]);
}

#[test]
fn the_blocks_other_codes_run_before_the_call() {
    let r = clean("G00 X40 Z5 M08 M98 P12\nM30\n", &[SUB12]);
    assert_eq!(kind_names(&r)[..3], ["M08", "rapid", "linear"]);
    assert_eq!(path(&r), vec![(40.0, 5.0), (38.0, 5.0)]);
}

/// O0001…O00`deepest`, each moving +1 on X and calling the next; the deepest one
/// calls `last`.
fn chain(deepest: u32, last: &str) -> Vec<String> {
    (1..=deepest)
        .map(|k| {
            let call = if k == deepest { last.to_string() } else { format!("M98 P{}", k + 1) };
            format!("O{k:04}\nG00 U1\n{call}\nM99\n")
        })
        .collect()
}

#[test]
fn twelve_levels_of_nesting_and_no_more() {
    let lib = chain(12, "");
    let refs: Vec<&str> = lib.iter().map(String::as_str).collect();
    let r = clean("G00 X0 Z0\nM98 P1\nM30\n", &refs);
    assert_eq!(path(&r).last(), Some(&(12.0, 0.0)));
    let lib = chain(12, "M98 P13");
    let mut refs: Vec<&str> = lib.iter().map(String::as_str).collect();
    refs.push("O0013\nM99\n");
    let r = run_lib("G00 X0 Z0\nM98 P1\nM30\n", &refs);
    assert_eq!(r.alarms.len(), 1);
    assert_eq!((r.alarms[0].program, r.alarms[0].line, r.alarms[0].code()), (12, 3, 77));
}

#[test]
fn call_alarms() {
    let r = run_lib("M98 P77\nM30\n", &[SUB12]);
    assert_eq!(r.alarms[0].kind, AlarmKind::ProgramNotFound { program: 77 });
    let r = run_lib("M98\nM30\n", &[SUB12]);
    assert_eq!(r.alarms[0].kind, AlarmKind::SubprogramNumberMissing);
    assert_eq!(r.alarms[0].code(), 76);
    let r = run_lib("M98 P0\nM30\n", &[SUB12]);
    assert_eq!(r.alarm_codes(), vec![(1, 4011)]);
    let r = run_lib("M98 P12\nM30\n", &["O0012\nM98 P12\nM99\n"]);
    assert_eq!(r.alarms[0].kind, AlarmKind::SelfCall { program: 12 });
    assert_eq!(r.alarms[0].to_string(), "O0012 line 2: alarm 4040: O0012 calls itself with M98");
    // A single program text has no subprograms.
    let r = run("M98 P12\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(1, 76)]);
}

#[test]
fn a_failed_call_changes_nothing() {
    let r = run_lib("G00 X10 Z10 M98 P77\nM30\n", &[SUB12]);
    assert_eq!(r.alarm_codes(), vec![(1, 76)]);
    assert!(r.actions.iter().all(|c| !matches!(c.action, Action::Rapid(_))), "no motion from the block");
}

#[test]
fn m99_p_returns_to_the_first_such_sequence_number_of_the_caller() {
    let main =
        "#1=0\nN200 #1=#1+1\nIF [#1 GT 1] GOTO 300\nM98 P12\nG00 X10 Z10\nN200 G00 X20 Z20\nN300 G00 X30 Z30\nM30\n";
    let r = clean(main, &["O0012\nM99 P200\n"]);
    assert_eq!(path(&r), vec![(30.0, 30.0)], "back to the N200 on line 2, not line 6");
    let r = run_lib("M98 P12\nM30\n", &["O0012\nM99 P9\n"]);
    assert_eq!(r.alarms[0].kind, AlarmKind::JumpTargetNotFound { seq: 9 });
    assert_eq!(r.alarms[0].program, 12);
}

#[test]
fn m99_p_takes_effect_after_the_last_repetition() {
    let main = "M98 P12 L2\nG00 X10 Z10\nN5 G00 X20 Z20\nM30\n";
    let r = clean(main, &["O0012\nG00 U1\nM99 P5\n"]);
    assert_eq!(path(&r), vec![(1.0, 0.0), (2.0, 0.0), (20.0, 20.0)]);
}

#[test]
fn a_missing_main_program_is_an_alarm() {
    let (store, _) = memory("M30\n", &[]);
    let mut interp = Interpreter::new(MachineConfig::default());
    interp.select_main(5);
    let r = run_interp(interp, &*store, &Panel::default(), 10);
    assert_eq!(r.alarms[0].kind, AlarmKind::ProgramNotFound { program: 5 });
    assert_eq!(r.alarms.len(), 1, "then the run has ended");
}

#[test]
fn running_off_the_end_of_a_subprogram_is_end_of_record() {
    let r = run_lib("M98 P12\nM30\n", &["O0012\nG00 X1 Z1\n"]);
    assert_eq!((r.alarms[0].program, r.alarms[0].code()), (12, 5010));
}

#[test]
fn m99_in_a_main_program_repeats_it_ignoring_p() {
    let (store, id) = memory("G00 U2\nM99 P5\nN5 G00 X99\n", &[]);
    let mut interp = Interpreter::new(MachineConfig::default());
    interp.select_main(id);
    let r = run_interp(interp, &*store, &Panel::default(), 6);
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    assert_eq!(path(&r), vec![(2.0, 0.0), (4.0, 0.0), (6.0, 0.0)]);
}

#[test]
fn m99_must_be_alone() {
    for block in ["G00 X1 M99", "M99 M08", "G00 M99", "M99 X1"] {
        let r = run_lib("M98 P12\nM30\n", &[&format!("O0012\n{block}\n")]);
        assert_eq!(r.alarms[0].code(), 4042, "{block}");
    }
    let r = clean("M98 P12\nM30\n", &["O0012\nN10 M99\n"]);
    assert!(r.alarms.is_empty());
}

#[test]
fn m02_or_m30_in_a_subprogram_ends_the_program() {
    let r = clean("M98 P12\nG00 X99 Z99\nM30\n", &["O0012\nG00 X5 Z5\nM30\nM99\n"]);
    assert_eq!(path(&r), vec![(5.0, 5.0)]);
    assert_eq!(r.actions.last().map(|c| c.action), Some(Action::End { rewind: true }));
}

#[test]
fn loops_belong_to_their_program_level() {
    let main = "#1=0\nWHILE [#1 LT 2] DO1\nM98 P12\n#1=#1+1\nEND1\nM30\n";
    let sub = "O0012\n#2=0\nWHILE [#2 LT 3] DO1\n#2=#2+1\n#3=#3+1\nEND1\nM99\n";
    let r = clean(main, &[sub]);
    assert_eq!(r.interp.variables().get(3), Ok(Some(6.0)));
}

#[test]
fn main_and_subprogram_in_one_file() {
    let file = "%\nO0001\nG00 X50 Z10\nM98 P12\nM30\nO0012\nG01 U-2 F100\nM99\n%\n";
    let r = clean(file, &[]);
    assert_eq!(path(&r), vec![(50.0, 10.0), (48.0, 10.0)]);
    assert_eq!(r.actions[1].line, 7, "lines are the file's");
    // Running main O0001 and calling P1 is a self-call.
    let r = run_lib("%\nO0001\nM98 P1\nM30\n%\n", &[]);
    assert_eq!(r.alarms[0].kind, AlarmKind::SelfCall { program: 1 });
}

/// The manual's M92 example (3.1.5) with the jump input set to `level`.
fn m9x(m: u16, level: bool) -> Vec<(f64, f64)> {
    let main = format!("N50 M{m} P100\nN60 G0 X10 Z10\nN70 G0 X15 Z15\nN100 G0 X20 Z30\nM30\n");
    let cfg = MachineConfig { jump_input: 5, ..MachineConfig::default() };
    let panel = Panel { inputs: u32::from(level) << 5, ..Panel::default() };
    let r = run_programs(&main, &[], cfg, panel);
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    path(&r)
}

#[test]
fn m91_and_m92_jump_on_the_external_input() {
    let all = vec![(10.0, 10.0), (15.0, 15.0), (20.0, 30.0)];
    assert_eq!(m9x(92, true), vec![(20.0, 30.0)], "M92 jumps on 1");
    assert_eq!(m9x(92, false), all);
    assert_eq!(m9x(91, false), vec![(20.0, 30.0)], "M91 jumps on 0");
    assert_eq!(m9x(91, true), all);
}

#[test]
fn m91_m92_alarms() {
    let cfg = MachineConfig { jump_input: 40, ..MachineConfig::default() };
    let r = run_programs("M92 P10\nN10 M30\n", &[], cfg, Panel::default());
    assert_eq!(r.alarms[0].kind, AlarmKind::InputNotAvailable { input: 40 });
    let r = run_lib("M91\nM30\n", &[]);
    assert_eq!(r.alarm_codes(), vec![(1, 4006)]);
    let r = run_lib("M91 P0\nM30\n", &[]);
    assert_eq!(r.alarm_codes(), vec![(1, 4011)]);
    let r = run_lib("M91 P10\nM30\n", &[]);
    assert_eq!(r.alarm_codes(), vec![(1, 78)], "input 0 is low: M91 jumps to a missing N10");
    let r = run_lib("M92 P10\nM30\n", &[]);
    assert!(r.alarms.is_empty(), "no jump, no lookup");
    let r = run_lib("G04 X1 M98 P12\nM30\n", &[SUB12]);
    assert_eq!(r.alarm_codes(), vec![(1, 4005)], "G04's P or M98's?");
}

#[test]
fn mdi_runs_one_block_and_refuses_calls_and_jumps() {
    let mut interp = Interpreter::new(MachineConfig::default());
    let mut sink = VecSink::default();
    let panel = Panel::default();
    assert_eq!(interp.mdi(b"#500=7", &panel, &mut sink), Ok(Progress::Executed { line: 0 }));
    assert_eq!(interp.variables().get(500), Ok(Some(7.0)));
    assert_eq!(interp.mdi(b"G00 X#500 Z1", &panel, &mut sink), Ok(Progress::Executed { line: 0 }));
    assert_eq!(host_tests::xz(&sink.0[0]), Some((7.0, 1.0)));
    let code = |r: Result<Progress, interp_core::Alarm>| r.unwrap_err().code();
    assert_eq!(code(interp.mdi(b"M98 P12", &panel, &mut sink)), 4041, "3.1.6 note 2");
    assert_eq!(code(interp.mdi(b"M99", &panel, &mut sink)), 4041);
    assert_eq!(code(interp.mdi(b"M91 P5", &panel, &mut sink)), 4041);
    assert_eq!(code(interp.mdi(b"GOTO 5", &panel, &mut sink)), 123);
    assert_eq!(code(interp.mdi(b"WHILE [1 EQ 1] DO1", &panel, &mut sink)), 123);
    assert_eq!(code(interp.mdi(b"G90 X10 Z-5 F100", &panel, &mut sink)), 4007, "no canned cycles in MDI");
    assert_eq!(code(interp.mdi(b"G00 X1;G00 X2", &panel, &mut sink)), 4019);
    assert_eq!(code(interp.mdi(b"G00 X1\nG00 X2\n", &panel, &mut sink)), 4019);
    assert_eq!(sink.0.len(), 1, "nothing else moved");
    assert_eq!(interp.mdi(b"G00 X3 ;\n", &panel, &mut sink), Ok(Progress::Executed { line: 0 }));
    assert_eq!(interp.mdi(b"(nothing)\n", &panel, &mut sink), Ok(Progress::Skipped { line: 0 }));
    assert_eq!(host_tests::xz(&sink.0[1]), Some((3.0, 1.0)));
}

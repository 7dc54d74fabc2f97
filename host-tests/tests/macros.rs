//! The macro language of 2.24 through the interpreter: address substitution,
//! null words, loops, jumps, the step budget and common-variable persistence.

use std::collections::HashMap;

use host_tests::{VecSink, mm, path, run, run_with};
use interp_core::canon::Action;
use interp_core::lang::fanuc::macros::{CommonStore, Value};
use interp_core::{Interpreter, MachineConfig, Panel, Progress, SingleProgram};

/// Variable `n` after the run.
fn var(r: &host_tests::Run, n: u16) -> Value {
    r.interp.variables().get(n).unwrap()
}

fn clean(text: &str) -> host_tests::Run {
    let r = run(text);
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    r
}

#[test]
fn manual_2_24_1_address_substitution() {
    // F#203 = F15, Z-#210 = Z-250, G#230 = G1 (G3 in the manual; G1 needs no centre),
    // and #1=1.23456 positions X to 1.235 (least increment 0.001).
    let r = clean("#1=1.23456\n#203=15\n#210=250\n#230=1\nG00 X20 Z0\nG#230 X#1 Z-#210 F#203\nM30\n");
    assert_eq!(path(&r), vec![(20.0, 0.0), (1.235, -250.0)]);
    let Action::Linear(m) = r.actions[1].action else { panic!("{:?}", r.actions[1]) };
    assert_eq!(m.feed.value, mm(15.0));
    assert_eq!(r.actions[1].line, 6);
}

#[test]
fn manual_2_24_2_round_examples() {
    // #2=1.2345, #3=2.5456: G00 X#2 → 1.235 mm, G00 X#3 → 2.546 mm; ROUND[1.2345] = 1.
    let r = clean("#2=1.2345\n#3=2.5456\nG00 X#2 Z0\nG00 X#3\n#4=ROUND[#2]\nG00 X[ROUND[#2]+ROUND[#3]]\nM30\n");
    assert_eq!(path(&r), vec![(1.235, 0.0), (2.546, 0.0), (3.781, 0.0)]);
    assert_eq!(var(&r, 4), Some(1.0));
}

#[test]
fn a_null_variable_drops_its_word_g00_x10_y11() {
    // #10 = 0, #11 null: G00 X#10 Y#11 is G00 X0 — even on a lathe without Y.
    let r = clean("#10=0\nG00 X40 Z5\nG00 X#10 Y#11\nM30\n");
    assert_eq!(path(&r), vec![(40.0, 5.0), (0.0, 5.0)]);
}

#[test]
fn a_block_whose_words_are_all_null_keeps_only_its_g_code() {
    // G01 X#1 Z#2 with both null is G01 alone: no motion, G01 becomes modal — what
    // the block means when the words are not written at all (FANUC ignores them).
    let r = clean("G00 X10 Z10\nG01 X#1 Z#2 F100\nX20\nM30\n");
    let kinds: Vec<_> = r.actions.iter().map(|c| (c.line, matches!(c.action, Action::Linear(_)))).collect();
    assert_eq!(kinds[..2], [(1, false), (3, true)]);
    assert_eq!(path(&r), vec![(10.0, 10.0), (20.0, 10.0)]);
}

#[test]
fn if_then_example_and_arithmetic_into_motion() {
    let r = clean("#2=3\n#3=3\n#4=9\nIF[#2 EQ #3] THEN #4=0\nIF [#2 NE #3] THEN #5=1\nG00 X[#4+10] Z[#5]\nM30\n");
    assert_eq!(var(&r, 4), Some(0.0));
    assert_eq!(var(&r, 5), None);
    assert_eq!(path(&r), vec![(10.0, 0.0)], "Z[#5] with #5 null is dropped: Z stays 0");
}

#[test]
fn while_loop_sums_one_to_ten() {
    let r = clean("#1=0\n#2=1\nWHILE [#2 LE 10] DO1\n#1=#1+#2\n#2=#2+1\nEND1\nG00 X#1 Z0\nM30\n");
    assert_eq!(var(&r, 1), Some(55.0));
    assert_eq!(path(&r), vec![(55.0, 0.0)]);
}

#[test]
fn three_nested_loops_and_a_reused_loop_number() {
    let text = "#10=0\n#1=0\nWHILE [#1 LT 2] DO1\n#2=0\nWHILE [#2 LT 3] DO2\n#3=0\nWHILE [#3 LT 4] DO3\n\
                #10=#10+1\n#3=#3+1\nEND3\n#2=#2+1\nEND2\n#1=#1+1\nEND1\n\
                #4=0\nWHILE [#4 LT 5] DO1\n#4=#4+1\nEND1\nM30\n";
    let r = clean(text);
    assert_eq!((var(&r, 10), var(&r, 4)), (Some(24.0), Some(5.0)));
}

#[test]
fn a_false_while_skips_its_range_with_inner_loops() {
    let r = clean("WHILE [1 EQ 2] DO1\nDO2\nG00 X99 Z99\nEND2\nEND1\nG00 X1 Z1\nM30\n");
    assert_eq!(path(&r), vec![(1.0, 1.0)]);
}

/// Runs `text` for at most 200 steps (after a loop alarm the rest of a broken
/// program may loop for ever, as `lathe check` would find).
fn run_briefly(text: &str) -> host_tests::Run {
    let store = SingleProgram(text.as_bytes());
    host_tests::run_interp(Interpreter::new(MachineConfig::default()), &store, &Panel::default(), 200)
}

#[test]
fn loop_structure_alarms() {
    // Crossed ranges (note 4), detected at the DO whose range is broken.
    let r = run_briefly("WHILE [1 EQ 1] DO1\nWHILE [1 EQ 1] DO2\nEND1\nEND2\nM30\n");
    assert_eq!(r.alarm_codes()[0], (1, 124));
    // Missing END.
    let r = run("#1=0\nWHILE [#1 LT 2] DO1\n#1=#1+1\nM30\n");
    assert_eq!(r.alarm_codes()[0], (2, 124));
    // END without DO.
    let r = run("G00 X1 Z1\nEND2\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(2, 124)]);
    // The same number nested.
    let r = run_briefly("DO1\nDO1\nEND1\nEND1\nM30\n");
    assert_eq!(r.alarm_codes()[0], (1, 124));
    // Loop numbers other than 1–3 (note 3).
    let r = run("WHILE [1 EQ 1] DO4\nEND4\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(1, 126), (2, 126)]);
}

#[test]
fn goto_backward_and_forward() {
    let r = clean("#1=0\nN10 #1=#1+1\nIF [#1 LT 5] GOTO 10\nGOTO 20\nG00 X99 Z99\nN20 G00 X#1 Z0\nM30\n");
    assert_eq!(path(&r), vec![(5.0, 0.0)]);
    // Computed targets: GOTO #i and GOTO [expr].
    let r = clean("#5=3\nGOTO [#5*10]\nN20 G00 X20 Z0\nN30 G00 X30 Z0\nM30\n");
    assert_eq!(path(&r), vec![(30.0, 0.0)]);
}

#[test]
fn jumping_out_of_a_loop_closes_it() {
    // DO without WHILE loops for ever (note 5) until a GOTO leaves it; loop number
    // 1 is free again afterwards.
    let r = clean(
        "#1=0\nDO1\n#1=#1+1\nIF [#1 GE 3] GOTO 50\nEND1\nN50 WHILE [#1 LT 6] DO1\n#1=#1+1\nEND1\nG00 X#1 Z0\nM30\n",
    );
    assert_eq!(path(&r), vec![(6.0, 0.0)]);
}

#[test]
fn jump_alarms() {
    let r = run("GOTO 77\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(1, 78)]);
    let r = run("#1=0\nGOTO #1\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(2, 128)]);
    let r = run("GOTO 123456\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(1, 128)]);
}

#[test]
fn endless_loops_return_control_after_the_step_budget() {
    let text = "N1 #1=#1+1\nGOTO 1\n";
    let store = SingleProgram(text.as_bytes());
    let mut interp = Interpreter::new(MachineConfig::default());
    let mut sink = VecSink::default();
    let panel = Panel::default();
    interp.set_step_budget(7);
    // 7 statements: #1=1, GOTO, #1=2, GOTO, #1=3, GOTO, #1=4.
    assert_eq!(interp.step(&store, &panel, &mut sink), Ok(Progress::Yielded { line: 1 }));
    assert_eq!(interp.variables().get(1), Ok(Some(4.0)));
    assert_eq!(interp.step(&store, &panel, &mut sink), Ok(Progress::Yielded { line: 2 }));
    assert_eq!(interp.variables().get(1), Ok(Some(7.0)));
    // DO1 … END1 with nothing in it.
    let store = SingleProgram(b"DO1\nEND1\n");
    let mut interp = Interpreter::new(MachineConfig::default());
    assert_eq!(interp.step_budget(), interp_core::interpreter::DEFAULT_STEP_BUDGET);
    for _ in 0..1000 {
        assert!(matches!(interp.step(&store, &panel, &mut sink), Ok(Progress::Yielded { .. })));
    }
    // Reset regains the program: it starts over.
    interp.reset();
    assert_eq!(interp.cursor().line, 1);
}

#[test]
fn macro_statements_before_an_nc_block_run_in_the_same_step() {
    let store = SingleProgram(b"#1=5\n#2=6\nG00 X#1 Z#2\nM30\n");
    let mut interp = Interpreter::new(MachineConfig::default());
    let mut sink = VecSink::default();
    assert_eq!(interp.step(&store, &Panel::default(), &mut sink), Ok(Progress::Executed { line: 3 }));
    assert_eq!(host_tests::xz(&sink.0[0]), Some((5.0, 6.0)));
}

#[test]
fn skipped_blocks_are_not_evaluated() {
    let on = Panel { block_skip: 1, ..Panel::default() };
    let r = run_with("/#1=1/0\n/ G00 X#1 Z0\nM30\n", MachineConfig::default(), on);
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    let r = run("/#1=1/0\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(1, 112)]);
}

#[test]
fn macro_alarms_carry_their_line_and_change_nothing() {
    let r = run("#1=5\n#1=SQRT[-#1]\n#2=#1\nG00 X#2 Z[TAN[90]]\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(2, 119), (4, 112)]);
    assert_eq!(var(&r, 1), Some(5.0), "the failed assignment left #1 alone");
    assert!(path(&r).is_empty());
    let r = run("G00 X1 Z1 #1=2\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(1, 127)]);
}

/// A host-style store of the commons (a file in `lathe sim`).
#[derive(Default)]
struct MapStore(HashMap<u16, f64>);

impl CommonStore for MapStore {
    type Error = ();
    fn load(&mut self, n: u16) -> Result<Value, ()> {
        Ok(self.0.get(&n).copied())
    }
    fn store(&mut self, n: u16, v: Value) -> Result<(), ()> {
        match v {
            Some(x) => self.0.insert(n, x),
            None => self.0.remove(&n),
        };
        Ok(())
    }
}

#[test]
fn common_variables_survive_power_off_locals_do_not() {
    let mut store = MapStore::default();
    let r = clean("#500=12.5\n#401=[#401+1]\n#1=3\n#650=4\nM30\n");
    let mut interp = r.interp;
    interp.variables_mut().flush_commons(&mut store).unwrap();
    assert_eq!(store.0, HashMap::from([(500, 12.5), (401, 1.0)]));
    // Power on again: a fresh interpreter loads the commons; the locals are null.
    let mut again = Interpreter::new(MachineConfig::default());
    again.variables_mut().load_commons(&mut store).unwrap();
    let prog = "#401=#401+1\nG00 X#500 Z#401\nM30\n";
    let r = host_tests::run_interp(again, &SingleProgram(prog.as_bytes()), &Panel::default(), 100);
    assert_eq!(path(&r), vec![(12.5, 2.0)]);
    assert_eq!((var(&r, 1), var(&r, 650)), (None, None));
}

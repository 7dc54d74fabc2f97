//! FANUC custom macro B calls (the manual names G65, G66, G67 as macro statements,
//! 2.24.2 note 7; the rest follows FANUC 0i): arguments of specification I and
//! II, local levels, nesting, G66 modal calls, calls by G, M and T code, alarms.

use host_tests::{Run, kind_names, path, run_lib, run_programs};
use interp_core::canon::Action;
use interp_core::config::Param;
use interp_core::{AlarmKind, MachineConfig, Panel};

/// Copies `#1–#33` of its level into `#401–#433` (null stays null).
const DUMP: &str = "O9000\n#34=1\nWHILE [#34 LE 33] DO1\n#[400+#34]=#[#34]\n#34=#34+1\nEND1\nM99\n";

fn clean(main: &str, library: &[&str]) -> Run {
    clean_on(MachineConfig::default(), main, library)
}

fn clean_on(cfg: MachineConfig, main: &str, library: &[&str]) -> Run {
    let r = run_programs(main, library, cfg, Panel::default());
    assert!(r.alarms.is_empty(), "{main}: {:?}", r.alarms);
    r
}

/// `#1–#33` as the call block `call` (to O9000) gives them to the macro.
fn args_on(cfg: MachineConfig, call: &str) -> [Option<f64>; 33] {
    let r = clean_on(cfg, &format!("{call}\nM30\n"), &[DUMP]);
    core::array::from_fn(|i| r.interp.variables().get(401 + i as u16).unwrap())
}

fn args_of(call: &str) -> [Option<f64>; 33] {
    args_on(MachineConfig::default(), call)
}

/// The arguments given, as (variable, value).
fn given(args: &[Option<f64>; 33]) -> Vec<(u16, f64)> {
    (1..).zip(args).filter_map(|(n, v)| v.map(|v| (n, v))).collect()
}

fn with(params: &[(Param, i64)]) -> MachineConfig {
    let mut cfg = MachineConfig::default();
    for &(p, v) in params {
        cfg.params.set(p, v);
    }
    cfg
}

#[test]
fn argument_specification_i_sets_the_variable_of_each_address() {
    let a = args_of("G65 P9000 A1. B-2.5 C3 D4. E5 F6 H7 I8 J9 K10 M11 Q12 R13 S14 T15 U16 V17 W18 X19 Y20 Z21");
    assert_eq!(
        given(&a),
        [
            (1, 1.0),
            (2, -2.5),
            (3, 3.0),
            (4, 8.0),
            (5, 9.0),
            (6, 10.0),
            (7, 4.0),
            (8, 5.0),
            (9, 6.0),
            (11, 7.0),
            (13, 11.0),
            (17, 12.0),
            (18, 13.0),
            (19, 14.0),
            (20, 15.0),
            (21, 16.0),
            (22, 17.0),
            (23, 18.0),
            (24, 19.0),
            (25, 20.0),
            (26, 21.0),
        ]
    );
    // #10, #12, #14–#16 and #27–#33 have no address in specification I.
    for n in [10, 12, 14, 15, 16, 27, 33] {
        assert_eq!(a[n - 1], None, "#{n}");
    }
}

#[test]
fn vacant_arguments_are_null_not_zero() {
    let a = args_of("G65 P9000 A1. C#0 D#5");
    assert_eq!(given(&a), [(1, 1.0)], "B not given, C and D from null variables: all vacant");
    // In the macro, a vacant argument is <空>: EQ #0 holds, and it is not 0.
    let m = "O9001\nIF [#2 EQ #0] THEN #401=1\nIF [#2 NE 0] THEN #402=1\n#403=#2\n#404=#2+0\nM99\n";
    let r = clean("G65 P9001 A1.\nM30\n", &[m]);
    let v = |n| r.interp.variables().get(n).unwrap();
    assert_eq!((v(401), v(402), v(403), v(404)), (Some(1.0), Some(1.0), None, Some(0.0)));
}

#[test]
fn argument_specification_ii_fills_ten_ijk_triples() {
    let mut call = String::from("G65 P9000 A1 B2 C3");
    for k in 0..10 {
        call.push_str(&format!(" I{} J{} K{}", 4 + 3 * k, 5 + 3 * k, 6 + 3 * k));
    }
    let a = args_of(&call);
    assert_eq!(given(&a), (1..=33).map(|n| (n, f64::from(n))).collect::<Vec<_>>());
    // A triple may leave letters out: a letter not after the last one in I J K order
    // starts the next triple.
    let a = args_of("G65 P9000 I1. K3. J5. K6. I7.");
    assert_eq!(given(&a), [(4, 1.0), (6, 3.0), (8, 5.0), (9, 6.0), (10, 7.0)]);
    // An eleventh triple is alarm 0129.
    let r = run_lib(&format!("{call} I34\nM30\n"), &[DUMP]);
    assert_eq!(r.alarm_codes(), [(1, 129)]);
    assert_eq!(r.alarms[0].kind, AlarmKind::IllegalArgumentAddress { letter: b'I' });
}

#[test]
fn of_specifications_i_and_ii_mixed_the_later_argument_counts() {
    // FANUC's example: I4.0 and D5.0 both set #7, D5.0 last.
    let a = args_of("G65 A1.0 B2.0 I-3.0 I4.0 D5.0 P9000");
    assert_eq!(given(&a), [(1, 1.0), (2, 2.0), (4, -3.0), (7, 5.0)]);
    let a = args_of("G65 P9000 D5.0 I-3.0 I4.0");
    assert_eq!(given(&a), [(4, -3.0), (7, 4.0)]);
}

#[test]
fn decimal_point_rules_of_arguments() {
    // Calculator-type input (parameter 3401 = 1, the default): as #1=123 (2.24.1),
    // a value without a point is a whole number.
    let a = args_of("G65 P9000 X60 Z-5 A90 F100 U60.5");
    assert_eq!(given(&a), [(1, 90.0), (9, 100.0), (21, 60.5), (24, 60.0), (26, -5.0)]);
    // Least-increment input (3401 = 0): lengths and angles without a point are
    // counts of their least input increment (IS-B: 0.001 mm, 0.001 degrees), as
    // FANUC 0i reads arguments; other addresses and values with a point as written.
    let cfg = with(&[(Param::CalculatorInput, 0)]);
    let a = args_on(cfg.clone(), "G65 P9000 X60 Z-5 A90 F100 S500 U60. R1234");
    assert_eq!(given(&a), [(1, 0.09), (9, 100.0), (18, 1.234), (19, 500.0), (21, 60.0), (24, 0.06), (26, -0.005)]);
    // Macro values are passed as computed.
    let a = args_on(cfg, "#100=2.5\nG65 P9000 A#100 B[#100*2] C-#100");
    assert_eq!(given(&a), [(1, 2.5), (2, 5.0), (3, -2.5)]);
}

#[test]
fn each_macro_call_has_its_own_locals_and_m99_restores_the_callers() {
    // Main level 0: #1 = 5, #2 = 6. O9001 (level 1): #1 = A, #2 vacant; sets #2 and
    // calls O9002 (level 2) with no arguments, then M98 O9003, which shares level 1.
    let main = "#1=5\n#2=6\nG65 P9001 A7.\n#405=#1\n#406=#2\nM30\n";
    let o9001 = "O9001\n#411=#1\n#412=#2\n#2=8\nG65 P9002\n#413=#1\n#414=#2\nM98 P9003\n#415=#3\nM99\n";
    let o9002 = "O9002\n#421=#1\n#422=#2\n#1=99\nM99\n";
    let o9003 = "O9003\n#431=#1\n#432=#2\n#3=10\nM99\n";
    let r = clean(main, &[o9001, o9002, o9003]);
    let v = |n| r.interp.variables().get(n).unwrap();
    assert_eq!((v(411), v(412)), (Some(7.0), None), "level 1 starts with its arguments");
    assert_eq!((v(421), v(422)), (None, None), "level 2 starts vacant");
    assert_eq!((v(413), v(414)), (Some(7.0), Some(8.0)), "M99 brings back level 1");
    assert_eq!((v(431), v(432)), (Some(7.0), Some(8.0)), "M98 shares its caller's level");
    assert_eq!(v(415), Some(10.0));
    assert_eq!((v(405), v(406)), (Some(5.0), Some(6.0)), "level 0 as it was");
    assert_eq!((r.interp.macro_level(), r.interp.call_depth()), (0, 0));
}

#[test]
fn four_levels_of_macro_calls_within_twelve_levels_of_calls() {
    // O9001–O9004 each call the next with G65; the fourth calls O9005.
    let lib: Vec<String> = (1..=4)
        .map(|k| format!("O900{k}\n#[500+{k}]=#1\nG65 P900{} A{}.\nM99\n", k + 1, k + 1))
        .chain(["O9005\n#505=#1\nM99\n".to_string()])
        .collect();
    let refs: Vec<&str> = lib.iter().map(String::as_str).collect();
    let r = run_lib("G65 P9001 A1.\nM30\n", &refs);
    assert_eq!(r.alarms.len(), 1, "{:?}", r.alarms);
    assert_eq!((r.alarms[0].program, r.alarms[0].line, r.alarms[0].code()), (9004, 3, 77));
    assert_eq!(r.alarms[0].kind, AlarmKind::MacroNestingTooDeep);
    let v = |n| r.interp.variables().get(n).unwrap();
    assert_eq!([v(501), v(502), v(503), v(504), v(505)], [Some(1.0), Some(2.0), Some(3.0), Some(4.0), None]);
    // M98 levels count to the 12 only: 4 macro levels under 8 subprogram levels.
    let mut lib: Vec<String> = (1..=8).map(|k| format!("O{k:04}\nM98 P{}\nM99\n", k + 1)).collect();
    lib[7] = "O0008\nG65 P9001 A1.\nM99\n".into();
    lib.extend((1..=4).map(|k| format!("O900{k}\nG65 P900{}\nM99\n", k + 1)));
    lib.push("O9005\nM99\n".into());
    let refs: Vec<&str> = lib.iter().map(String::as_str).collect();
    let r = run_lib("M98 P1\nM30\n", &refs);
    // 8 M98 levels + 4 macro levels = 12: the fifth macro call is both.
    assert_eq!(r.alarm_codes(), [(2, 77)]);
    assert_eq!(r.alarms[0].program, 9004);
    lib[7] = "O0008\nM98 P9\nM99\n".into();
    lib.push("O0009\nG65 P9001\nM99\n".into());
    let refs: Vec<&str> = lib.iter().map(String::as_str).collect();
    let r = run_lib("M98 P1\nM30\n", &refs);
    assert_eq!(r.alarms[0].kind, AlarmKind::CallNestingTooDeep, "13 levels of calls");
    assert_eq!(r.alarms[0].program, 9003);
}

#[test]
fn l_repeats_the_macro_with_the_arguments_set_once() {
    // Each run counts #500 up and keeps #1 of its level (FANUC: the arguments are
    // set for the first run; the level goes on from run to run).
    let m = "O9001\n#500=#500+1\n#[510+#500]=#1\n#1=#1+10\nG00 U1.\nM99\n";
    let r = clean("G65 P9001 L3 A1.\nG00 Z5.\nM30\n", &[m]);
    let v = |n| r.interp.variables().get(n).unwrap();
    assert_eq!([v(500), v(511), v(512), v(513)], [Some(3.0), Some(1.0), Some(11.0), Some(21.0)]);
    assert_eq!(path(&r), [(1.0, 0.0), (2.0, 0.0), (3.0, 0.0), (3.0, 5.0)]);
    assert_eq!(r.interp.variables().get(1), Ok(None), "the main level's #1 is untouched");
}

#[test]
fn m99_p_from_a_macro_returns_to_the_sequence_number_with_the_callers_locals() {
    let main = "#1=3\nG65 P9001 A9.\nG00 X99\nN50 #401=#1\nM30\n";
    let r = clean(main, &["O9001\n#402=#1\nM99 P50\n"]);
    let v = |n| r.interp.variables().get(n).unwrap();
    assert_eq!((v(401), v(402)), (Some(3.0), Some(9.0)));
    assert!(path(&r).is_empty(), "the G00 X99 was jumped over");
}

/// The grooving macro a G66 calls: in by U (#21, on the diameter), out again.
const GROOVE: &str = "O9100\n#500=#500+1\nG01 U-#21 F#9\nG04 X0.1\nG00 U#21\nM99\n";

#[test]
fn g66_calls_after_every_move_until_g67_and_not_after_its_own_moves() {
    let main = "G00 X50. Z0\nG66 P9100 U4. F0.1\nZ-10.\nZ-20.\nM08\nG01 Z-25. F0.2\nG67\nG00 Z-40.\nM30\n";
    let r = clean(main, &[GROOVE]);
    assert_eq!(
        path(&r),
        [
            (50.0, 0.0),
            (50.0, -10.0),
            (46.0, -10.0),
            (50.0, -10.0),
            (50.0, -20.0),
            (46.0, -20.0),
            (50.0, -20.0),
            (50.0, -25.0),
            (46.0, -25.0),
            (50.0, -25.0),
            (50.0, -40.0),
        ]
    );
    // The G66 block itself, the M08 block and the moves after G67 call nothing.
    assert_eq!(r.interp.variables().get(500), Ok(Some(3.0)));
    assert_eq!(r.interp.modal_calls(), 0);
    // The macro's moves are on its own lines, the dwells between them.
    let names = kind_names(&r);
    assert_eq!(names.iter().filter(|n| *n == "dwell 100").count(), 3);
    assert_eq!(r.actions[2].line, 3, "the plunge is the macro's line 3");
}

#[test]
fn g66_arguments_start_every_call_afresh() {
    let m = "O9101\n#21=#21+1\n#[510+#500]=#21\n#500=#500+1\nM99\n";
    let r = clean("G66 P9101 U1.\nG00 X10\nX20\nX30\nG67\nM30\n", &[m]);
    let v = |n| r.interp.variables().get(n).unwrap();
    assert_eq!([v(510), v(511), v(512)], [Some(2.0), Some(2.0), Some(2.0)]);
    assert_eq!(r.interp.variables().get(21), Ok(None));
}

#[test]
fn nested_g66_calls_the_newest_then_the_older_one_from_its_moves() {
    // O9200's moves call the older O9110; O9110's own moves call nothing.
    let o9110 = "O9110\n#501=#501+1\nG00 W-1.\nM99\n";
    let o9200 = "O9200\n#502=#502+1\nG00 U-2.\nG00 U2.\nM99\n";
    let main = "G00 X50 Z0\nG66 P9110\nG66 P9200\nZ-10.\nG67\nZ-20.\nG67\nZ-30.\nM30\n";
    let r = clean(main, &[o9110, o9200]);
    let v = |n| r.interp.variables().get(n).unwrap();
    // Z-10: O9200 (two moves, each calling O9110); Z-20: O9110 once.
    assert_eq!((v(501), v(502)), (Some(3.0), Some(1.0)));
    assert_eq!(
        path(&r),
        [
            (50.0, 0.0),
            (50.0, -10.0),
            (48.0, -10.0),
            (48.0, -11.0),
            (50.0, -11.0),
            (50.0, -12.0),
            (50.0, -20.0),
            (50.0, -21.0),
            (50.0, -30.0),
        ]
    );
    // A fourth G66 while three are in force is alarm 0122.
    let r = run_lib("G66 P9110\nG66 P9110\nG66 P9110\nG66 P9110\nM30\n", &[o9110]);
    assert_eq!(r.alarm_codes(), [(4, 122)]);
}

#[test]
fn a_modal_call_past_the_nesting_limit_stops_the_move_block_undone() {
    // G66 at macro level 4: the move there would call a fifth level.
    let lib: Vec<String> = (1..=3)
        .map(|k| format!("O900{k}\nG65 P900{}\nM99\n", k + 1))
        .chain(["O9004\nG66 P9110\nG00 X10. Z5.\nG67\nM99\n".to_string(), "O9110\nM99\n".to_string()])
        .collect();
    let refs: Vec<&str> = lib.iter().map(String::as_str).collect();
    let r = run_lib("G00 X5. Z5.\nG65 P9001\nM30\n", &refs);
    assert_eq!(r.alarms.len(), 1);
    assert_eq!((r.alarms[0].program, r.alarms[0].line, r.alarms[0].code()), (9004, 3, 77));
    assert!(r.actions.iter().all(|c| c.line != 3 || c.action.endpoint().is_none()), "no motion from the block");
    assert_eq!(path(&r), [(5.0, 5.0)]);
}

#[test]
fn a_g_code_calls_its_macro_with_the_blocks_words_as_arguments() {
    let cfg = with(&[(Param::CallG9010, 100)]);
    let o9010 = "O9010\n#401=#24\n#402=#26\n#403=#9\n#404=#1\n#500=#500+1\nG00 U#24 W#26\nM99\n";
    let r = clean_on(cfg.clone(), "G100 X30. Z-5. F0.1 L2\nM30\n", &[o9010]);
    let v = |n| r.interp.variables().get(n).unwrap();
    assert_eq!([v(401), v(402), v(403), v(404), v(500)], [Some(30.0), Some(-5.0), Some(0.1), None, Some(2.0)]);
    assert_eq!(path(&r), [(30.0, -5.0), (60.0, -10.0)]);
    // In the macro a G100 is an ordinary G code (alarm 0010), and G65 still calls.
    let r =
        run_programs("G100 A1.\nM30\n", &["O9010\nG100\nG65 P9000 B2.\nM99\n", DUMP], cfg.clone(), Panel::default());
    assert_eq!(r.alarm_codes(), [(2, 10)]);
    assert_eq!(r.interp.variables().get(402), Ok(Some(2.0)));
    // Alarms: P is no argument of a call by code; the code must begin its block.
    let r = run_programs("G100 P5\nM30\n", &[o9010], cfg.clone(), Panel::default());
    assert_eq!(r.alarm_codes(), [(1, 129)]);
    let r = run_programs("G00 X1 G100\nM30\n", &[o9010], cfg, Panel::default());
    assert_eq!(r.alarm_codes(), [(1, 127)]);
    assert!(host_tests::on_line(&r, 1).is_empty());
}

#[test]
fn an_existing_g_code_set_in_6050_calls_the_macro_which_uses_it_plainly() {
    // G01 itself: the macro sees the words and runs G01 as G01.
    let cfg = with(&[(Param::CallG9011, 1)]);
    let o9011 = "O9011\n#500=#500+1\nG01 X#24 Z#26 F#9\nM99\n";
    let r = clean_on(cfg, "G01 X20. Z-3. F0.2\nG01 X22. Z-4. F0.2\nM30\n", &[o9011]);
    assert_eq!(r.interp.variables().get(500), Ok(Some(2.0)));
    assert_eq!(path(&r), [(20.0, -3.0), (22.0, -4.0)]);
}

#[test]
fn an_m_code_calls_its_macro_and_is_plain_inside_it() {
    let cfg = with(&[(Param::CallM9020, 50), (Param::CallG9010, 100)]);
    let o9020 = "O9020\n#401=#1\n#402=#13\nG100 A3.\nM50\nM99\n";
    let o9010 = "O9010\n#403=#1\nM99\n";
    let r = run_programs("M50 A1. M2.\nM30\n", &[o9020, o9010], cfg, Panel::default());
    // M50 inside O9020 is an ordinary M code (unknown here: 4008); G100 still calls.
    assert_eq!(r.alarm_codes(), [(5, 4008)]);
    let v = |n| r.interp.variables().get(n).unwrap();
    assert_eq!([v(401), v(402), v(403)], [Some(1.0), Some(2.0), Some(3.0)]);
}

#[test]
fn an_m_code_calls_a_subprogram_after_the_blocks_other_codes() {
    let cfg = with(&[(Param::SubM9001, 6)]);
    // O9001 shares the caller's level; an M06 in it is an ordinary M code.
    let o9001 = "O9001\n#401=#1\nG00 U-2.\nM99\n";
    let r = clean_on(cfg.clone(), "#1=4\nG00 X40. Z2. M06 M08\nM30\n", &[o9001]);
    assert_eq!(kind_names(&r)[..3], ["M08", "rapid", "rapid"]);
    assert_eq!(path(&r), [(40.0, 2.0), (38.0, 2.0)]);
    assert_eq!(r.interp.variables().get(401), Ok(Some(4.0)));
    let r = run_programs("M06\nM30\n", &["O9001\nM06\nM99\n"], cfg.clone(), Panel::default());
    assert_eq!(r.alarm_codes(), [(2, 4008)]);
    // A dwell's P beside it is the dwell's (the call takes no P).
    let r = clean_on(cfg.clone(), "G04 P500 M06\nM30\n", &[o9001]);
    assert_eq!(kind_names(&r)[..2], ["dwell 500", "rapid"]);
    // Two calls, or one with M98/M99/M30, is an alarm, and the block does nothing.
    let r = run_programs("M98 P9001 M06\nM30\n", &[o9001], cfg.clone(), Panel::default());
    assert_eq!(r.alarms[0].kind, AlarmKind::ConflictingMCodes { first: 98, second: 6 });
    let r = run_programs("M06 M30\nM30\n", &[o9001], cfg.clone(), Panel::default());
    assert_eq!(r.alarms[0].kind, AlarmKind::ConflictingMCodes { first: 6, second: 30 });
    let r = run_programs("M06 P9001\nM30\n", &[o9001], cfg.clone(), Panel::default());
    assert_eq!(r.alarm_codes(), [(1, 4005)], "the call takes no P");
    // With M98 in the block it is an alarm, and the block does nothing.
    let r = run_programs("G00 X10 M06 M98 P9001\nM30\n", &[o9001], cfg, Panel::default());
    assert_eq!(r.alarms[0].kind, AlarmKind::ConflictingMCodes { first: 6, second: 98 });
    assert!(host_tests::on_line(&r, 1).is_empty());
}

#[test]
fn a_t_code_calls_o9000_with_its_value_in_149() {
    let cfg = with(&[(Param::TCodeCall, 1)]);
    // O9000 does the tool change: a T code in it indexes the turret.
    let o9000 = "O9000\nG00 U10.\nT#149\nG00 U-10.\nM99\n";
    let r = clean_on(cfg.clone(), "G00 X40. Z5. T0303\nG01 Z0 F100\nM30\n", &[o9000]);
    assert_eq!(r.interp.variables().get(149), Ok(Some(303.0)));
    assert_eq!(kind_names(&r), ["rapid", "rapid", "tool 3 3", "rapid", "linear", "end true"]);
    // Without 6001#5 the T indexes the turret directly.
    let r = clean("G00 X40. Z5. T0303\nM30\n", &[o9000]);
    assert_eq!(kind_names(&r), ["tool 3 3", "rapid", "end true"]);
    // With M98 in the block it is an alarm.
    let r = run_programs("T0101 M98 P9000\nM30\n", &[o9000], cfg, Panel::default());
    assert_eq!(r.alarm_codes(), [(1, 4005)]);
}

#[test]
fn macro_call_alarms_name_their_line_and_change_nothing() {
    for (block, code) in [
        ("G65 A1.", 76),
        ("G65 P77", 76),
        ("G66 P77", 76),
        ("G66 A1.", 76),
        ("G00 G65 P9000", 127),
        ("X10. G65 P9000", 127),
        ("G65 P9000 X10. #1=2", 127),
        ("G65 P9000 G01", 129),
        ("G65 P9000 N5", 129),
        ("G65 P9000 O5", 129),
        ("G65 P9000 ,C1.", 129),
        ("G67 A1.", 129),
        ("G65 P9000 A1. A2.", 4004),
        ("G65 P9000 P9001", 4004),
        ("G65 P9000 L0", 4011),
        ("G65 P0", 4011),
        ("G65 P9000 L2 L3", 4004),
        ("G65 P9000.", 7),
    ] {
        let r = run_lib(&format!("G00 X50. Z5.\n{block}\nG00 X60.\nM30\n"), &[DUMP]);
        assert_eq!(r.alarm_codes(), [(2, code)], "{block}");
        assert_eq!(path(&r), [(50.0, 5.0), (60.0, 5.0)], "{block}: nothing from the block, the run goes on");
        assert_eq!(r.interp.variables().get(401), Ok(None), "{block}: O9000 never ran");
    }
}

#[test]
fn g67_without_g66_does_nothing_and_reset_ends_modal_calls() {
    let r = clean("G67\nG00 X10.\nM30\n", &[]);
    assert_eq!(path(&r), [(10.0, 0.0)]);
    let (store, id) = host_tests::memory("G66 P9100 U1. F0.1\nG00 X10.\nM30\n", &[GROOVE]);
    let mut interp = interp_core::Interpreter::new(MachineConfig::default());
    interp.select_main(id);
    let mut sink = host_tests::VecSink::default();
    for _ in 0..2 {
        interp.step(&*store, &Panel::default(), &mut sink).unwrap();
    }
    assert_eq!((interp.modal_calls(), interp.macro_level()), (1, 1), "in the modally called O9100");
    interp.reset();
    assert_eq!((interp.modal_calls(), interp.macro_level(), interp.call_depth()), (0, 0, 0));
}

#[test]
fn macro_calls_in_mdi_and_in_a_shape_are_refused() {
    let mut interp = interp_core::Interpreter::new(MachineConfig::default());
    let mut sink = host_tests::VecSink::default();
    let a = interp.mdi(b"G65 P9000 A1.", &Panel::default(), &mut sink).unwrap_err();
    assert_eq!(a.code(), 4007);
    let r = run_lib(
        "G00 X60. Z2.\nG71 U1. R0.5\nG71 P10 Q20 U0.2 W0.1 F0.2\nN10 G00 X40.\nG65 P9000\nN20 G01 Z-20. F0.2\nM30\n",
        &[DUMP],
    );
    assert_eq!(r.alarm_codes(), [(3, 66)]);
}

#[test]
fn a_call_block_may_carry_a_sequence_number_and_comments() {
    let a = args_of("/ N10 G65 (BOLT CIRCLE) P9000 A1. (FIRST) B2.");
    assert_eq!(given(&a), [(1, 1.0), (2, 2.0)]);
    let r = clean("G65 P9000 A5.\nM30\n", &[DUMP]);
    assert!(r.kinds().iter().all(|a| matches!(a, Action::End { .. })));
}

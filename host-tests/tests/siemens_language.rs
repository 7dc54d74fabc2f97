//! SINUMERIK mode (issue 19, seed 001): the language — blocks, words, variables,
//! expressions, labels, REPEAT, PROC calls with parameters, MCALL, G290/G291 —
//! run to canonical actions whose positions are computed here from the programs'
//! numbers.

use host_tests::{Memory, Run, kind_names, moves, run_interp};
use interp_core::alarm::SiemensAlarm as S;
use interp_core::config::Language;
use interp_core::{AlarmKind, Interpreter, MachineConfig, Panel, SingleProgram};

fn cfg() -> MachineConfig {
    MachineConfig { language: Language::Siemens, ..MachineConfig::default() }
}

/// Runs a SINUMERIK program (main program and PROCs in one text).
fn siemens(text: &str) -> Run {
    run_interp(Interpreter::new(cfg()), &SingleProgram(text.as_bytes()), &Panel::default(), 100_000)
}

/// Runs `main` with the SINUMERIK subprogram files `library` in program memory.
fn siemens_lib(main: &str, library: &[&str]) -> Run {
    let mut m = Box::new(Memory::new());
    let id = m.load_named(main.as_bytes(), Some(0)).expect("main program loads");
    for t in library {
        m.load_named(t.as_bytes(), None).expect("library loads");
    }
    let mut interp = Interpreter::new(cfg());
    interp.select_main(id);
    run_interp(interp, &*m, &Panel::default(), 100_000)
}

fn clean(r: &Run) {
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
}

#[test]
fn g0_g1_diamon_diamof_ac_ic_and_g91() {
    let r = siemens(
        "N10 G0 X50 Z10\nN20 G1 X40 Z-5 F100\nN30 DIAMOF\nN40 G1 X30 Z=IC(-5)\nN50 X=IC(-2) Z=AC(-20)\n\
         N60 G91 X-3 Z-1\nN70 DIAMON G90 X10\nM30\n",
    );
    clean(&r);
    // DIAMOF: X30 is a radius (diameter 60); G91 increments a radius too.
    assert_eq!(
        moves(&r),
        vec![
            ('r', 50.0, 10.0),
            ('l', 40.0, -5.0),
            ('l', 60.0, -10.0),
            ('l', 56.0, -20.0),
            ('l', 50.0, -21.0),
            ('l', 10.0, -21.0)
        ]
    );
    assert_eq!(r.actions[0].line, 1);
}

#[test]
fn r_parameters_def_variables_and_expressions_position_the_tool() {
    let r = siemens(
        "DEF REAL MID=7, FFR=200, XE\nDEF INT ZAEHL=1\nN10 R1=5 R2=0.1\nN20 G0 X=R1*10 Z=MID*0.5\n\
         N30 XE=R1*4+SQRT(POT(3)+POT(4)) FFR=FFR+100\nN40 G1 X=XE Z=-ZAEHL F=FFR\n\
         N50 G1 X=2*R1 Z=ATAN2(1,1)/45-10 R1=R1+1 X=R1\nM30\n",
    );
    // N50 has X twice: alarm 16420, nothing of it runs.
    assert_eq!(r.alarm_codes(), vec![(7, 16420)]);
    assert_eq!(moves(&r), vec![('r', 50.0, 3.5), ('l', 25.0, -1.0)]);
    let feed = match r.actions[1].action {
        interp_core::canon::Action::Linear(m) => m.feed.value,
        _ => 0,
    };
    assert_eq!(feed, 300_000_000, "F=FFR after FFR=FFR+100");
    assert_eq!(r.interp.siemens_vars().r(1), Ok(5.0), "the failed block's R1=R1+1 was not written");
}

#[test]
fn labels_and_gotob_loop_as_the_document_counts_holes() {
    // Seed 001 lines 3034-3085 (成排孔_5) without the cycle: the label loop runs
    // the block at MA1 five times, G91 Z20 each.
    let r = siemens(
        "DEF INT ZAEHL=1\nN30 G18 G0 X30 Z20\nN50 MA1: G91 Z20\nN60 ZAEHL=ZAEHL+1\nN70 IF ZAEHL<6 GOTOB MA1\n\
         N80 G90 X40\nN90 GOTOF _ENDE\nN100 X99\n_ENDE: M30\n",
    );
    clean(&r);
    let z: Vec<f64> = moves(&r).iter().map(|m| m.2).collect();
    assert_eq!(z, vec![20.0, 40.0, 60.0, 80.0, 100.0, 120.0, 120.0]);
    assert_eq!(moves(&r).last(), Some(&('r', 40.0, 120.0)), "N100 is jumped over");
}

/// The document's fictitious CYCLE100 (lines 598-701) as a user subprogram: its
/// parameters come back as moves (X = MID, Z = -FAL, F = FFR; VARI as dwell s).
const CYCLE100: &str = "%_N_CYCLE100_SPF\n; $PATH=/_N_CUS_DIR\nPROC CYCLE100 (CHAR FORM, REAL MID, REAL FFR, INT VARI, REAL FAL)\n\
    IF FORM==\"F\" GOTOF FORM_F\nG1 X=MID Z=-FAL F=FFR\nGOTOF DONE\nFORM_F: G1 X=MID+100 Z=-FAL F=FFR\n\
    DONE: G4 F=VARI+1\nG0 X0 Z1\nM17\n";

#[test]
fn cycle100_call_forms_of_the_document() {
    let main = "DEF CHAR FORM=\"E\"\nDEF REAL MID=5, FFR, FAL\nDEF INT VARI=1\nN5 G0 X0 Z1\n\
        N10 CYCLE100 (\"E\", 5, 0.1, 1, 0)\n\
        N20 FFR=0.1 FAL=0\nN30 CYCLE100 (FORM, MID, FFR, VARI, FAL)\n\
        N40 R1=5 R2=0.1 R3=1 R4=0\nN50 CYCLE100 (FORM, R1, R2, R3, R4)\n\
        N60 CYCLE100 (\"F\", 3, 0.3, , 1)\nN70 CYCLE100 (\"F\", 3, 0.3)\n\
        N80 MID=7 FFR=200\nN90 CYCLE100 (\"E\", MID*0.5, FFR+100,1)\nN100 M30\n";
    let r = siemens_lib(main, &[CYCLE100]);
    clean(&r);
    assert_eq!(
        moves(&r),
        vec![
            ('r', 0.0, 1.0),
            ('l', 5.0, 0.0),
            ('r', 0.0, 1.0),
            ('l', 5.0, 0.0),
            ('r', 0.0, 1.0),
            ('l', 5.0, 0.0),
            ('r', 0.0, 1.0),
            ('l', 103.0, -1.0),
            ('r', 0.0, 1.0),
            ('l', 103.0, 0.0),
            ('r', 0.0, 1.0),
            ('l', 3.5, 0.0),
            ('r', 0.0, 1.0),
        ]
    );
    let dwells: Vec<String> = kind_names(&r).into_iter().filter(|k| k.starts_with("dwell")).collect();
    // VARI 1, 1, 1 (R3 = 1.0 to INT), omitted (0), closed early (0), 1.
    assert_eq!(dwells, vec!["dwell 2000", "dwell 2000", "dwell 2000", "dwell 1000", "dwell 1000", "dwell 2000"]);
    assert_eq!(r.interp.call_depth(), 0);
}

#[test]
fn too_many_parameters_12340_and_wrong_type_12330_stop_the_call() {
    let main = "N5 G0 X0 Z1\nN10 CYCLE100 (\"E\", 5, 0.1, 1, 0, 9)\nN20 CYCLE100 (5, 5)\nN30 CYCLE100 (\"E\", \"5\")\n\
        N40 CYCLE100 (\"EF\")\nN50 G1 X1 Z1 F10\nM30\n";
    let r = siemens_lib(main, &[CYCLE100]);
    assert_eq!(r.alarm_codes(), vec![(2, 12340), (3, 12330), (4, 12330), (5, 12330)]);
    assert_eq!(r.alarms[1].kind, AlarmKind::from(S::ParameterType { index: 1 }));
    assert_eq!(r.alarms[2].kind, AlarmKind::from(S::ParameterType { index: 2 }));
    assert_eq!(moves(&r), vec![('r', 0.0, 1.0), ('l', 1.0, 1.0)], "no motion from the refused calls");
    assert_eq!(r.interp.call_depth(), 0);
}

#[test]
fn g290_and_g291_switch_both_ways_in_one_program() {
    // A FANUC program (the machine's language) switches to SINUMERIK and back.
    let text = "G00 X50 Z10\nG290\nR1=21 ; a SINUMERIK comment\nG1 X=R1*2 Z=IC(-4) F100\nG291\nG01 U-2 W-1 F50\n\
                G290\nG0 Z=R1\nG291\nM30\n";
    let r = run_interp(
        Interpreter::new(MachineConfig::default()),
        &SingleProgram(text.as_bytes()),
        &Panel::default(),
        10_000,
    );
    clean(&r);
    assert_eq!(moves(&r), vec![('r', 50.0, 10.0), ('l', 42.0, 6.0), ('l', 40.0, 5.0), ('r', 40.0, 21.0)]);
    assert_eq!(r.interp.language(), Language::Fanuc);
    // In SINUMERIK mode a FANUC word is refused, and G291 must stand alone.
    let r = siemens("G1 U-2 F10\nG291 X1\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(1, 12550), (2, 4016)]);
}

#[test]
fn repeat_sections_and_subprogram_passes() {
    let r = siemens(
        "N10 G0 X0 Z1\nSTART: G91 Z-1\nN30 Z-1\nEND1: Z-1\nN50 REPEAT START END1 P=2\nN60 G90 Z-20\n\
         HOLE: G91 X2\nN80 Z-1\nENDLABEL: X2\nN100 REPEAT HOLE\nN110 REPEATB N80 P=3\nN120 KONTUR P2\nM30\n\
         PROC KONTUR\nG91 Z-10\nM17\n",
    );
    clean(&r);
    let xz: Vec<(f64, f64)> = moves(&r).iter().map(|m| (m.1, m.2)).collect();
    let want = [
        (0.0, 1.0),
        (0.0, 0.0),
        (0.0, -1.0),
        (0.0, -2.0),
        // REPEAT START END1 P=2: the section twice more.
        (0.0, -3.0),
        (0.0, -4.0),
        (0.0, -5.0),
        (0.0, -6.0),
        (0.0, -7.0),
        (0.0, -8.0),
        (0.0, -20.0),
        (2.0, -20.0),
        (2.0, -21.0),
        (4.0, -21.0),
        // REPEAT HOLE: HOLE to ENDLABEL once more.
        (6.0, -21.0),
        (6.0, -22.0),
        (8.0, -22.0),
        // REPEATB N80 P=3: the block N80 three times.
        (8.0, -23.0),
        (8.0, -24.0),
        (8.0, -25.0),
        // KONTUR P2: the subprogram twice.
        (8.0, -35.0),
        (8.0, -45.0),
    ];
    assert_eq!(xz, want);
    assert_eq!(r.interp.call_depth(), 0);
}

#[test]
fn alarms_of_the_language_with_their_numbers_and_lines() {
    let cases: &[(&str, u32, u16)] = &[
        ("G0 X1 Z1\nG1 X2 (Z3\n", 2, 12080),
        ("DEF STRING[4] SS\nSS=\"ABCDEF\"\n", 2, 12160),
        ("DEF REAL AA\nAA=\"X\"\n", 2, 12150),
        ("DEF REAL AA\nDEF INT AA\n", 2, 12170),
        ("G0 X1\nDEF REAL AA\n", 2, 14500),
        ("G12 X1\n", 1, 12470),
        ("G0 X1\nNOPE=3\n", 2, 12550),
        ("G0 X1\nNOWHERE(1, 2)\n", 2, 14011),
        ("G0 X1\nGOTOF NIX\n", 2, 14080),
        ("G0 X1\nGOTOB N9\n", 2, 14080),
        ("R100=1\n", 1, 17020),
        ("T3 D4\n", 1, 17180),
        ("G1 X1 X2 F1\n", 1, 16420),
        ("G0 X1\nREPEAT NIX\n", 2, 14080),
    ];
    for &(text, line, code) in cases {
        let r = siemens(&format!("{text}M30\n"));
        assert_eq!(r.alarm_codes().first(), Some(&(line, code)), "{text:?}: {:?}", r.alarms);
        assert!(r.actions.iter().all(|a| a.line != line), "{text:?}: no action from the refused block");
    }
    // 12460: more DEF variables than the board holds (32).
    let defs: String = (0..33).map(|i| format!("DEF REAL V{i:02}\n")).collect();
    assert_eq!(siemens(&format!("{defs}M30\n")).alarm_codes(), vec![(33, 12460)]);
    // 14012: subprograms nested deeper than 12 levels (a PROC calling itself).
    let r = siemens("DEEP\nM30\nPROC DEEP\nG0 X1\nDEEP\nM17\n");
    assert_eq!(r.alarm_codes().first().map(|a| a.1), Some(14012));
    // 14510: arguments for a subprogram without PROC parameters.
    let r = siemens_lib("PLAIN(1)\nM30\n", &["%_N_PLAIN_SPF\nG0 X1\nM17\n"]);
    assert_eq!(r.alarm_codes(), vec![(1, 14510)]);
    // 4052: MCALL inside a modally called subprogram.
    let r = siemens_lib("MCALL INNER\nG0 X10\nMCALL\nM30\n", &["%_N_INNER_SPF\nPROC INNER\nMCALL INNER\nM17\n"]);
    assert_eq!(r.alarm_codes().first(), Some(&(3, 4052)));
}

//! Canned cycles in macro programs: the shape blocks of G70–G73 read with the
//! variables, macro statements refused inside a shape, P/Q found in the cycle's
//! own program when a file holds several, and a cycle inside a WHILE loop.

use host_tests::{moves, run, run_lib};

/// Figure 2.32 (see cycles_multiple.rs) with the shape's numbers in variables.
const FIG_2_32: &str = "G00 X200 Z10 M03 S800\nG71 U2 R1 F200\nG71 P80 Q120 U0.5 W2.0\nN80 G00 X40 S1200\n\
    G01 Z-30 F100\nX60 W-30\nW-20\nN120 X100 W-10\nG70 P80 Q120\nM30\n";

#[test]
fn shape_blocks_use_the_variables() {
    let with_vars = "#1=40\n#2=-30\n#3=60\n#4=100\nG00 X200 Z10 M03 S800\nG71 U2 R1 F200\nG71 P80 Q120 U0.5 W2.0\n\
        N80 G00 X#1 S1200\nG01 Z#2 F100\nX#3 W[#2]\nW-20\nN120 X#4 W-10\nG70 P80 Q120\nM30\n";
    let a = run(FIG_2_32);
    let b = run(with_vars);
    assert!(a.alarms.is_empty() && b.alarms.is_empty(), "{:?} {:?}", a.alarms, b.alarms);
    assert_eq!(moves(&a), moves(&b));
    assert!(moves(&b).len() > 100);
}

#[test]
fn a_macro_statement_inside_a_shape_is_refused() {
    let r = run("G00 X200 Z10 M03 S800\nG71 U2 R1 F200\nG71 P80 Q120\nN80 G00 X40\n#1=1\nN120 G01 Z-30 F100\nM30\n");
    assert_eq!(r.alarm_codes()[0], (3, 66));
    assert!(r.alarms[0].to_string().contains("a macro statement"), "{}", r.alarms[0]);
}

#[test]
fn p_and_q_are_found_in_the_cycles_own_program() {
    // O0001 has its own N80/N120 before O0002's: G70 in O0002 must use O0002's.
    let file = "O0001\nM98 P2\nM30\nN80 G00 X10\nN120 G00 X11\nO0002\nG00 X60 Z5 M3 S500\n\
                G70 P80 Q120\nN80 G01 X50 Z0 F100\nN120 G01 Z-10\nM99\n";
    let r = run_lib(file, &[]);
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    let m = moves(&r);
    assert!(m.contains(&('l', 50.0, 0.0)) && m.contains(&('l', 50.0, -10.0)), "{m:?}");
    assert!(!m.iter().any(|p| p.1 == 10.0 || p.1 == 11.0), "{m:?}");
}

#[test]
fn a_single_cycle_in_a_while_loop_steps_in() {
    // G90 passes at X46, X42, X38 (a loop instead of repeating the block).
    let r = run("G00 X55 Z2 M3 S500\n#1=46\nWHILE [#1 GE 38] DO1\nG90 X#1 Z-30 F100\n#1=#1-4\nEND1\nG00 X100\nM30\n");
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    let cuts: Vec<f64> = moves(&r).iter().filter(|m| m.0 == 'l' && m.2 == -30.0 && m.1 < 55.0).map(|m| m.1).collect();
    assert_eq!(cuts, [46.0, 42.0, 38.0]);
}

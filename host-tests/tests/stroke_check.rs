//! Stored stroke check 2, G22/G23 (2.10): forbidden inside or outside of a box,
//! checked along the whole path before a block moves, with every note.

use host_tests::{Run, moves, run, run_with};
use interp_core::config::Param;
use interp_core::{MachineConfig, Panel};

/// The box X Ø20–Ø40, Z -30…-10 (machine = work on the default machine).
const BOX: &str = "G22 X40 Z-10 I20 K-30\n";

fn outside_forbidden() -> MachineConfig {
    let mut cfg = MachineConfig::default();
    cfg.params.set(Param::Stroke2Outside, 1);
    cfg
}

fn codes(r: &Run) -> Vec<(u32, u16)> {
    r.alarm_codes()
}

#[test]
fn a_line_into_the_inside_area_stops_before_moving() {
    let r = run(&format!("G00 X60 Z0\n{BOX}G01 X30 F100\nZ-20\nM30\n"));
    assert_eq!(codes(&r), vec![(4, 503)], "entering through the Z-10 face moving in -Z");
    assert_eq!(moves(&r), vec![('r', 60.0, 0.0), ('l', 30.0, 0.0)], "the Z-20 block does not move");
    assert!(r.alarms[0].to_string().contains("- Z"), "{}", r.alarms[0]);
}

#[test]
fn a_line_through_the_area_with_both_ends_outside_is_refused() {
    let r = run(&format!("G00 X30 Z0\n{BOX}G01 Z-40 F100\nM30\n"));
    assert_eq!(codes(&r), vec![(3, 503)]);
    // Crossing diagonally, in + X.
    let r = run(&format!("G00 X10 Z-5\n{BOX}G01 X50 Z-35 F100\nM30\n"));
    assert_eq!(codes(&r), vec![(3, 502)]);
}

#[test]
fn moves_along_a_face_or_beside_the_area_are_allowed() {
    let r = run(&format!("G00 X40 Z0\n{BOX}G01 Z-40 F100\nX16\nZ0\nM30\n"));
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
}

#[test]
fn an_arc_bulging_into_the_area_is_refused_and_one_bulging_away_is_not() {
    // From (Ø50, Z-5) to (Ø50, Z-35) with R20: G02 dips to radius 18.2 (inside Ø20–Ø40).
    let r = run(&format!("G00 X50 Z-5\n{BOX}G02 Z-35 R20 F100\nM30\n"));
    assert_eq!(codes(&r), vec![(3, 503)]);
    let r = run(&format!("G00 X50 Z-5\n{BOX}G03 Z-35 R20 F100\nM30\n"));
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
}

#[test]
fn g23_switches_the_check_off() {
    let r = run(&format!("G00 X30 Z0\n{BOX}G23\nG01 Z-40 F100\nM30\n"));
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
}

#[test]
fn outside_forbidden_keeps_the_tool_in_the_box() {
    let body = "G00 X50 Z0\nG22 X100 Z10 I0 K-100\nG01 X80 Z-50 F100\nX120\nM30\n";
    let r = run_with(body, outside_forbidden(), Panel::default());
    assert_eq!(codes(&r), vec![(4, 502)]);
    // An arc whose end points are in the box but whose extent is not.
    let body = "G00 X80 Z0\nG22 X100 Z10 I0 K-100\nG03 Z-40 R22 F100\nM30\n";
    let r = run_with(body, outside_forbidden(), Panel::default());
    assert_eq!(codes(&r), vec![(3, 502)]);
}

#[test]
fn note_7_switching_on_inside_the_forbidden_area() {
    // Outside forbidden and the tool already outside: alarm at once, at the G22 block.
    let r = run_with("G00 X150 Z50\nG22 X100 Z10 I0 K-100\nM30\n", outside_forbidden(), Panel::default());
    assert_eq!(codes(&r), vec![(2, 502)]);
    // Inside forbidden and the tool inside: the next move alarms, whichever way.
    let r = run(&format!("G00 X30 Z-20\n{BOX}G01 X60 F100\nM30\n"));
    assert_eq!(codes(&r), vec![(3, 502)]);
}

#[test]
fn note_6_g22_stands_alone_and_parameters_give_the_box() {
    let r = run("G22 G01 X40 Z-10 I20 K-30\nM30\n");
    assert_eq!(codes(&r), vec![(1, 4016)]);
    let mut cfg = MachineConfig::default();
    for (n, v) in [(1360, 40.0), (1362, -10.0), (1370, 20.0), (1372, -30.0)] {
        cfg.params.set_from_file(n, v).unwrap();
    }
    let r = run_with("G00 X30 Z0\nG22\nG01 Z-40 F100\nM30\n", cfg.clone(), Panel::default());
    assert_eq!(codes(&r), vec![(3, 503)]);
    // Words override the parameters axis by axis.
    let r = run_with("G00 X30 Z0\nG22 X60 I50\nG01 Z-40 F100\nM30\n", cfg.clone(), Panel::default());
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    // Note 8: a box in the wrong order switches the check off.
    cfg.params.set_from_file(1370, 50.0).unwrap();
    let r = run_with("G00 X30 Z0\nG22\nG01 Z-40 F100\nM30\n", cfg, Panel::default());
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
}

#[test]
fn the_g22_block_does_not_move_and_cycles_are_checked_before_their_first_move() {
    let r = run(&format!("G00 X60 Z0\n{BOX}M30\n"));
    assert_eq!(moves(&r).len(), 1);
    // G90 down to Ø30 at Z-40 crosses the area: nothing of the cycle moves.
    let r = run(&format!("G00 X60 Z0\n{BOX}G90 X30 Z-40 F100\nM30\n"));
    assert_eq!(codes(&r), vec![(3, 503)]);
    assert_eq!(moves(&r).len(), 1);
}

//! G00, G01, G02/G03, G04, G09/G61/G64 and planes, with the manual's examples.

use host_tests::{kind_names, mm, path, run, run_with, xz};
use interp_core::canon::{Action, Plane};
use interp_core::config::{AxisConfig, Param};
use interp_core::{Axis, MachineConfig, Panel};

/// Runs `body` after positioning at (X dia, Z) with a rapid; returns the end points
/// of the body's moves.
fn from(x: f64, z: f64, body: &str) -> Vec<(f64, f64)> {
    let r = run(&format!("G00 X{x} Z{z}\n{body}\nM30\n"));
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    path(&r)[1..].to_vec()
}

#[test]
fn figure_2_1_rapid_absolute_incremental_and_mixed_reach_the_same_point() {
    for body in ["G0 X20.0 Z25.0", "G0 U-22.0 W-18.0", "G0 X20.0 W-18.0", "G0 U-22.0 Z25.0"] {
        assert_eq!(from(42.0, 43.0, body), vec![(20.0, 25.0)], "{body}");
    }
}

#[test]
fn figure_2_2_linear_absolute_incremental_and_mixed() {
    for body in ["G01 X60 Z7 F500", "G01 U20 W-25 F500", "G01 X60 W-25 F500", "G01 U20 Z7 F500"] {
        assert_eq!(from(40.0, 32.0, body), vec![(60.0, 7.0)], "{body}");
    }
    let r = run("G01 X60 Z7 F500\nM30\n");
    let Action::Linear(m) = r.actions[0].action else { panic!() };
    assert_eq!(m.feed.value, mm(500.0));
    assert!(!m.exact_stop);
}

#[test]
fn rapids_carry_the_modal_feed_mode_and_stop_exactly() {
    let r = run("G99 G00 X10 Z10\nM30\n");
    let Action::Rapid(m) = r.actions[0].action else { panic!() };
    assert_eq!(m.feed.mode, interp_core::canon::FeedMode::PerRev);
    assert!(m.exact_stop);
    assert!(!m.independent);
}

/// The arc of figure 2.5 written four ways: R, U/W with R, I with K=0, U/W with I.
#[test]
fn figure_2_5_arc_forms_agree() {
    for body in [
        "G02 X50.0 Z30.0 R25.0 F30",
        "G02 U20.0 W-20.0 R25.0 F30",
        "G02 X50.0 Z30.0 I25.0 F30",
        "G02 U20.0 W-20.0 I25.0 F30",
    ] {
        let r = run(&format!("G00 X30 Z50\n{body}\nM30\n"));
        assert!(r.alarms.is_empty(), "{body}: {:?}", r.alarms);
        let Action::Arc(a) = r.actions[1].action else { panic!("{body}") };
        assert_eq!(xz(&r.actions[1]), Some((50.0, 30.0)), "{body}");
        assert_eq!((2 * a.center.work[Axis::X], a.center.work[Axis::Z]), (mm(80.0), mm(50.0)), "{body}");
        assert!(a.cw && !a.full_circle && a.plane == Plane::Zx);
    }
}

#[test]
fn figure_2_6_program_with_tangent_arcs() {
    let r = run("N001 G0 X40 Z5\nN002 M03 S200\nN003 G01 X0 Z0 F900\nN005 G03 U24 W-24 R15\n\
         N006 G02 X26 Z-31 R5\nN007 G01 Z-40\nN008 X40 Z5\nN009 M30\n");
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    assert_eq!(path(&r), vec![(40.0, 5.0), (0.0, 0.0), (24.0, -24.0), (26.0, -31.0), (26.0, -40.0), (40.0, 5.0)]);
    let centers: Vec<_> = r
        .actions
        .iter()
        .filter_map(|c| match c.action {
            Action::Arc(a) => Some((2 * a.center.work[Axis::X], a.center.work[Axis::Z], a.cw)),
            _ => None,
        })
        .collect();
    // R15 ball end centred on the axis at Z-15; R5 fillet centred at X32 (dia) Z-27.
    assert_eq!(centers, vec![(0, mm(-15.0), false), (mm(32.0), mm(-27.0), true)]);
    assert_eq!(kind_names(&r)[1], "spindle Cw Some(200)");
}

#[test]
fn negative_r_takes_the_arc_over_180_degrees() {
    let r = run("G00 X60 Z0\nG02 W-20 R-10.5 F100\nM30\n");
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    let Action::Arc(a) = r.actions[1].action else { panic!() };
    // Chord 20 along -Z, |R| 10.5: the centre is h = sqrt(10.5² - 10²) = 3.2016 mm
    // off the chord, on the left of the travel for a clockwise arc of more than 180°.
    assert_eq!(a.center.work[Axis::Z], mm(-10.0));
    assert_eq!(a.center.work[Axis::X], mm(30.0) - 3_201_562);
    let r = run("G00 X60 Z0\nG02 W-20 R10.5 F100\nM30\n");
    let Action::Arc(a) = r.actions[1].action else { panic!() };
    assert_eq!(a.center.work[Axis::X], mm(30.0) + 3_201_562);
}

#[test]
fn full_circle_with_offsets_and_zero_degree_circle_with_r() {
    let r = run("G00 X20 Z0\nG02 I5 F100\nG02 R5\nM30\n");
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    assert_eq!(r.actions.len(), 3, "{:?}", kind_names(&r));
    let Action::Arc(a) = r.actions[1].action else { panic!() };
    assert!(a.full_circle);
    assert_eq!(a.center.work[Axis::X], mm(15.0));
}

#[test]
fn i_and_k_zero_is_a_straight_line() {
    let r = run("G00 X20 Z0\nG02 X30 Z-5 I0 K0 F100\nG03 X40 Z-10 I0 F100\nM30\n");
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    assert_eq!(kind_names(&r), vec!["rapid", "linear", "linear", "end true"]);
}

#[test]
fn arc_without_centre_alarms_or_moves_straight_by_parameter_3403() {
    let r = run("G00 X20 Z0\nG02 X30 Z-5 F100\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(2, 22)]);
    let mut cfg = MachineConfig::default();
    cfg.params.set(Param::ArcWithoutCenterIsLine, 1);
    let r = run_with("G00 X20 Z0\nG02 X30 Z-5 F100\nM30\n", cfg, Panel::default());
    assert!(r.alarms.is_empty());
    assert_eq!(kind_names(&r), vec!["rapid", "linear", "end true"]);
}

#[test]
fn arc_radius_alarms() {
    // R too small for the chord; I/K with the end point off the circle; R0.
    let r = run("G00 X60 Z0\nG02 W-20 R5 F100\nG02 X70 Z-10 I3 K-5\nG02 W-10 R0\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(2, 20), (3, 20), (4, 23)]);
    // R wins over I/K (2.3 note 4): the bad I is ignored.
    let r = run("G00 X60 Z0\nG02 W-20 R10 I3 F100\nM30\n");
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
}

#[test]
fn arc_with_an_axis_outside_the_plane_alarms_0021() {
    let mut cfg = MachineConfig::default();
    cfg.axes[Axis::Y.index()] = AxisConfig::linear(-50, 50, 3000);
    let r =
        run_with("G00 X20 Z0\nG02 X30 Z-5 Y4 R10 F100\nG17 G02 X30 Y5 R10 F100\nM30\n", cfg.clone(), Panel::default());
    assert_eq!(r.alarm_codes(), vec![(2, 21)]);
    let Action::Arc(a) = r.actions[1].action else { panic!("{:?}", kind_names(&r)) };
    assert_eq!(a.plane, Plane::Xy);
    // 2.13 note 5: linear moves may use any axis in any plane.
    let r = run_with("G17\nG01 X100 Y50 Z20 F100\nG02 X20 Z50 R100\nM30\n", cfg, Panel::default());
    assert_eq!(r.alarm_codes(), vec![(3, 21)]);
}

#[test]
fn y_word_without_a_y_axis_is_alarm_0009() {
    let r = run("G01 Y10 F100\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(1, 9)]);
}

#[test]
fn dwell_forms_and_exact_stop() {
    let r = run("G04 P1500\nG04 X2.5\nG04 U0.5\nG04\nG04 P0\nM30\n");
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    assert_eq!(kind_names(&r), vec!["dwell 1500", "dwell 2500", "dwell 500", "dwell 0", "dwell 0", "end true"]);
    // P takes no decimal point (2.6), no sign, and not together with X.
    let r = run("G04 P1.5\nG04 P-5\nG04 P100 X1\nG04 X-1\nG04 X1 U1\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(1, 7), (2, 6), (3, 4005), (4, 6), (5, 4020)]);
}

#[test]
fn g04_with_a_motion_code_must_stand_alone() {
    let r = run("G01 G04 X1 F100\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(1, 4016)]);
}

#[test]
fn g09_and_g61_exact_stop_g64_takes_effect_next_block() {
    let r = run("G01 X10 F100\nG09 X20\nX30\nG61 X40\nX50\nG64 X60\nX70\nM30\n");
    let stops: Vec<bool> = r
        .actions
        .iter()
        .filter_map(|c| match c.action {
            Action::Linear(m) => Some(m.exact_stop),
            _ => None,
        })
        .collect();
    // 2.14 item 5: G61/G64 take effect from the next block.
    assert_eq!(stops, vec![false, true, false, false, true, true, false]);
}

#[test]
fn feed_zero_is_alarm_0011() {
    let r = run("G01 X10\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(1, 11)]);
}

#[test]
fn zero_length_moves_are_dropped() {
    let r = run("G00 X10 Z5\nG00 X10\nG01 Z5 F100\nM30\n");
    assert_eq!(kind_names(&r), vec!["rapid", "end true"]);
}

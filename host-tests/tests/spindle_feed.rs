//! Spindle speed (2.19), feed modes (2.20), M codes and their timing (1.2, 3.1).

use host_tests::{kind_names, mm, run, run_with};
use interp_core::canon::{Action, FeedMode, SpindleDir};
use interp_core::config::{MTiming, UserMCode};
use interp_core::{MachineConfig, Panel};

/// The rpm each motion carries.
fn move_rpms(r: &host_tests::Run) -> Vec<Option<u32>> {
    r.actions
        .iter()
        .filter_map(|c| match c.action {
            Action::Rapid(m) | Action::Linear(m) => Some(m.spindle.rpm),
            Action::Arc(a) => Some(a.spindle.rpm),
            _ => None,
        })
        .collect()
}

#[test]
fn figure_2_73_constant_surface_speed() {
    let r = run("M3 G96 S300\nG0 X100 Z100\nG0 X50 Z0\nG1 W-30 F200\nX80 W-20 F150\nG0 X100 Z100\nM30\n");
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    assert_eq!(move_rpms(&r), vec![Some(955), Some(1910), Some(1910), Some(1194), Some(955)]);
    let Action::Linear(m) = r.actions[4].action else { panic!("{:?}", kind_names(&r)) };
    assert_eq!(m.spindle.css, Some(300_000), "the move carries the surface speed so the speed follows X");
}

#[test]
fn g50_s_clamps_only_under_g96() {
    let r = run("G50 S1500\nM3 G96 S300\nG0 X40 Z0\nG97 S2000\nG0 X30\nM30\n");
    assert_eq!(move_rpms(&r), vec![Some(1500), Some(2000)]);
    // G50 S0 holds the spindle at 0 under G96.
    let r = run("G50 S0\nG96 S100 M3\nG0 X40 Z0\nM30\n");
    assert_eq!(move_rpms(&r), vec![Some(0)]);
}

#[test]
fn spindle_maximum_and_gear_limits_apply_to_every_speed() {
    let mut cfg = MachineConfig::default();
    cfg.spindle.gear_max_rpm = [800, 1600, 0, 0];
    let r = run_with("M41 M3 S1200\nG0 X10\nM42\nG0 X20\nS9000\nG0 X30\nG96 S300\nG0 X0\nM30\n", cfg, Panel::default());
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    // Gear 1 caps at 800, gear 2 at 1600; G96 at the centre is capped too (note 7).
    assert_eq!(move_rpms(&r), vec![Some(800), Some(1200), Some(1600), Some(1600)]);
}

#[test]
fn css_and_rpm_memories_of_notes_2_and_3() {
    // Note 3: G97 without S keeps the last G96 speed. Note 2: back in G96 without S
    // the stored surface speed returns.
    let r = run("G0 X100 Z0\nM3 G96 S300\nG97\nG0 X50\nG96\nG0 X100\nM30\n");
    assert_eq!(move_rpms(&r), vec![None, Some(955), Some(955)]);
    // Note 2: no surface speed ever given: the lowest G96 speed.
    let r = run("G0 X100 Z0\nM3 G96\nG0 X50\nM30\n");
    assert_eq!(move_rpms(&r), vec![None, Some(50)]);
}

#[test]
fn spindle_actions_and_their_order_around_motion() {
    let r = run("G0 X50 Z0 M3 S800 M8\nG1 W-10 F100 M5 M9\nM4 S500\nS600\nM5\nM30\n");
    assert_eq!(
        kind_names(&r),
        vec![
            "spindle Cw Some(800)",
            "M08",
            "rapid",
            "linear",
            "M09",
            "spindle Stop None",
            "spindle Ccw Some(500)",
            "spindle Ccw Some(600)",
            "spindle Stop None",
            "end true",
        ]
    );
    assert_eq!(r.interp.state().spindle.dir, SpindleDir::Stop);
}

#[test]
fn feed_modes_remember_their_own_f_note_4() {
    let r = run("M3 S100\nG98 G01 X10 F300\nG99 X20 F0.2\nG98 X30\nG99 X40\nM30\n");
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    let feeds: Vec<_> = r
        .actions
        .iter()
        .filter_map(|c| match c.action {
            Action::Linear(m) => Some((m.feed.mode, m.feed.value)),
            _ => None,
        })
        .collect();
    assert_eq!(
        feeds,
        vec![
            (FeedMode::PerMin, mm(300.0)),
            (FeedMode::PerRev, mm(0.2)),
            (FeedMode::PerMin, mm(300.0)),
            (FeedMode::PerRev, mm(0.2)),
        ]
    );
}

#[test]
fn feed_per_rev_needs_a_turning_spindle() {
    let r = run("G99 G01 X10 F0.2\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(1, 4013)]);
}

#[test]
fn m00_m01_m02_m30_and_the_optional_stop_switch() {
    let text = "G0 X10 M00\nM01\nM02\n";
    let r = run(text);
    assert_eq!(kind_names(&r), vec!["rapid", "stop false", "end false"]);
    let r = run_with(text, MachineConfig::default(), Panel { optional_stop: true, ..Panel::default() });
    assert_eq!(kind_names(&r), vec!["rapid", "stop false", "stop true", "end false"]);
}

#[test]
fn aux_codes_of_tables_1_2_and_3_1() {
    let r = run("M07 M08\nM09\nM10\nM11\nM12\nM13\nM19\nM20\nM29 S500\nM31\nM32\nM33\nM41\nM45\nM63\nM64\nM65\nM30\n");
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    let ms: Vec<_> = r
        .actions
        .iter()
        .filter_map(|c| match c.action {
            Action::Aux { m } => Some(m),
            _ => None,
        })
        .collect();
    assert_eq!(ms, vec![7, 8, 9, 10, 11, 12, 13, 19, 20, 29, 31, 32, 33, 41, 45, 63, 64, 65]);
}

#[test]
fn unknown_and_conflicting_m_codes() {
    let r = run("M50\nM03 M04\nM08 M09\nM3 M8 M41 M0\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(1, 4008), (2, 4009), (3, 4009), (4, 4010)]);
    let mut cfg = MachineConfig::default();
    cfg.user_m_codes.push(UserMCode { m: 50, timing: MTiming::Before }).unwrap();
    let r = run_with("G0 X10 M50\nM30\n", cfg, Panel::default());
    assert_eq!(kind_names(&r), vec!["M50", "rapid", "end true"]);
}

#[test]
fn s_takes_no_decimal_point_or_sign() {
    let r = run("S100.5\nS-5\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(1, 7), (2, 6)]);
}

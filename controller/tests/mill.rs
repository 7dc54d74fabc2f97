//! The board on a mill (docs/MILL-BOARD.md): `$311` switches the machine kind, the
//! wire carries the real Y, M06 by hand stops for the operator, three axes home,
//! Y's limit switch alarms.

mod common;

use common::{Rig, field};
use interp_core::axis::Axis;
use interp_core::canon::SpindleDir;
use interp_core::config::MachineConfig;

fn idle(mut r: Rig) -> Rig {
    r.run_ms(2);
    r.take_lines();
    r
}

fn mpos(r: &mut Rig) -> Vec<f64> {
    let s = r.status();
    field(&s, "MPos:").split(',').map(|v| v.parse().unwrap()).collect()
}

#[test]
fn setting_311_switches_a_lathe_board_to_a_mill_and_back() {
    let mut r = idle(Rig::new());
    let all = r.command("$$");
    assert!(all.contains(&"$311=0".to_string()), "{all:?}");
    assert!(!all.iter().any(|l| l.starts_with("$101=")), "a lathe has no Y settings: {all:?}");
    assert_eq!(r.command("$101=400").last().unwrap(), "error:2");
    assert_eq!(r.command("$311=2").last().unwrap(), "error:2");

    assert_eq!(r.command("$311=1"), vec!["[MSG:Machine kind: mill]", "ok"]);
    assert!(r.ctl.take_dirty().settings, "$311 is stored");
    assert_eq!(r.command("$I")[0], "[VER:1.1h.mill:]");
    let all = r.command("$$");
    for want in ["$311=1", "$101=400", "$111=8000", "$131=400"] {
        assert!(all.contains(&want.to_string()), "{want} missing from {all:?}");
    }
    // The mill's power-on modes (G17) after the switch.
    assert!(r.command("$G")[0].contains(" G17 "), "{:?}", r.command("$G"));
    assert!(r.port.core.params().limits[Axis::Y.index()].present);
    // Y's own settings now reach the motion core.
    assert_eq!(r.command("$101=800"), vec!["ok"]);
    assert_eq!(r.port.core.params().scale[Axis::Y.index()].steps(1_000_000), 800);

    assert_eq!(r.command("$311=0"), vec!["[MSG:Machine kind: lathe]", "ok"]);
    assert_eq!(r.command("$I")[0], "[VER:1.1h.lathe:]");
    assert!(!r.port.core.params().limits[Axis::Y.index()].present);
    assert!(r.command("$G")[0].contains(" G18 "));
}

#[test]
fn a_mill_reports_the_real_y_while_it_moves() {
    let mut r = idle(Rig::with(MachineConfig::mill()));
    assert_eq!(r.command("$I")[0], "[VER:1.1h.mill:]");
    r.send(b"G17 G90 G01 X-30. Y-40. Z-10. F600\n");
    let mut seen = Vec::new();
    assert!(r.run_until(20_000, |r| {
        let p = mpos(r);
        seen.push(p[1]);
        p == [-30.0, -40.0, -10.0] && r.port.core.is_idle()
    }));
    assert!(seen.iter().any(|&y| -40.0 < y && y < 0.0), "Y never between its ends: {seen:?}");
    // X is a radius on a mill: not doubled.
    assert_eq!(mpos(&mut r), [-30.0, -40.0, -10.0]);
}

#[test]
fn m06_by_hand_stops_with_a_message_and_cycle_start_goes_on() {
    let mut r = idle(Rig::with(MachineConfig::mill()));
    let text = "S1000 M03\nG00 X-10. Y-10.\nT02 M06\nG00 X-20. Y-30.\nM30\n";
    let answers = r.stream(text, 5_000);
    assert!(answers.iter().any(|l| l == "[MSG:Load T02]"), "{answers:?}");
    assert!(!answers.iter().any(|l| l == "[MSG:Pgm End]"), "ran past the tool change: {answers:?}");
    assert!(r.status().starts_with("<Hold:0|MPos:-10.000,-10.000,0.000|"), "{}", r.status());
    // The spindle stopped for the operator's hands.
    assert_eq!(r.port.core.spindle_output().0, SpindleDir::Stop);
    r.run_ms(500);
    assert_eq!(mpos(&mut r), [-10.0, -10.0, 0.0], "no motion while the operator changes the tool");
    r.send(b"~");
    let ok = r.run_until(20_000, |r| r.lines().iter().any(|l| l == "[MSG:Pgm End]") && r.port.core.is_idle());
    assert!(ok, "{:?}", r.lines());
    assert_eq!(mpos(&mut r), [-20.0, -30.0, 0.0]);
    // Stopped at M06, started again as it was at cycle start.
    assert_eq!(r.io.spindle[..3], [(SpindleDir::Cw, 1000), (SpindleDir::Stop, 0), (SpindleDir::Cw, 1000)]);
}

#[test]
fn three_axes_home_z_first_then_x_then_y() {
    let mut r = idle(Rig::with(MachineConfig::mill()));
    let answers = r.stream("G90 G00 X-100. Y-100. Z-100.\nM30\n", 20_000);
    assert!(answers.iter().any(|l| l == "[MSG:Pgm End]"), "{answers:?}");
    assert_eq!(mpos(&mut r), [-100.0, -100.0, -100.0]);
    assert_eq!(r.command("$22=1"), vec!["ok"]);
    assert_eq!(r.command("$25=3000"), vec!["ok"]);
    assert_eq!(r.command("$H"), vec!["ok"]);
    // Switches 60 mm above the start on every axis; which one tripped first is
    // recorded.
    let mut order: Vec<char> = Vec::new();
    let ok = r.run_until(120_000, |r| {
        let p = r.port.core.position();
        for (a, c) in [(Axis::X, 'X'), (Axis::Y, 'Y'), (Axis::Z, 'Z')] {
            let on = p[a] >= -40_000_000;
            if on && !order.contains(&c) {
                order.push(c);
            }
        }
        r.inputs.home_x = p[Axis::X] >= -40_000_000;
        r.inputs.home_y = p[Axis::Y] >= -40_000_000;
        r.inputs.home_z = p[Axis::Z] >= -40_000_000;
        r.lines().iter().any(|l| l == "[MSG:Homed]" || l == "ALARM:9")
    });
    assert!(ok && r.lines().iter().any(|l| l == "[MSG:Homed]"), "{:?}", r.lines());
    assert_eq!(order, ['Z', 'X', 'Y']);
    (r.inputs.home_x, r.inputs.home_y, r.inputs.home_z) = (false, false, false);
    assert!(r.run_until(5_000, |r| r.port.core.is_idle()));
    // Every switch point is the reference (0, 0, 0), pulled off 1 mm.
    let p = mpos(&mut r);
    assert!(p.iter().all(|v| (v + 1.0).abs() < 0.05), "{p:?}");
}

#[test]
fn the_y_limit_switch_alarms() {
    let mut r = idle(Rig::with(MachineConfig::mill()));
    r.send(b"G01 Y-100. F500\n");
    r.run_ms(200);
    r.inputs.limit_y = true;
    r.run_ms(2);
    let got = r.take_lines();
    assert!(got.contains(&"[MSG:Hard limit Y]".to_string()) && got.contains(&"ALARM:1".to_string()), "{got:?}");
    assert!(r.status().contains("|Pn:Y"));
}

/// A mill with the automatic tool changer (`$312=1`), the program stopped at its
/// `T02 M06` with the request out.
fn at_automatic_m06() -> Rig {
    let mut r = idle(Rig::with(MachineConfig::mill()));
    assert_eq!(r.command("$312=1"), vec!["ok"]);
    let text = "S1000 M03\nG00 X-10. Y-10.\nT02 M06\nG00 X-20. Y-30.\nM30\n";
    let answers = r.stream(text, 2_000);
    assert!(answers.iter().any(|l| l == "[MSG:Tool change T02 (tool changer)]"), "{answers:?}");
    assert!(!answers.iter().any(|l| l == "[MSG:Pgm End]"), "ran past the tool change: {answers:?}");
    assert_eq!(r.io.requests, [Some(2)], "the tool number and the request go out once");
    assert_eq!(mpos(&mut r), [-10.0, -10.0, 0.0]);
    r
}

#[test]
fn automatic_m06_requests_the_tool_waits_for_done_and_goes_on() {
    let mut r = at_automatic_m06();
    // Waiting: the spindle stopped, nothing after the M06 moves, the board is busy.
    assert_eq!(r.port.core.spindle_output().0, SpindleDir::Stop);
    assert!(r.status().starts_with("<Run|"), "{}", r.status());
    r.send(b"~");
    r.run_ms(3_000);
    assert_eq!(mpos(&mut r), [-10.0, -10.0, 0.0], "cycle start does not skip the tool changer");
    assert_eq!(r.io.requests, [Some(2)]);
    // Done: the request drops, the spindle starts again as it was, the program goes on.
    r.inputs.tool_change_done = true;
    let ok = r.run_until(20_000, |r| r.lines().iter().any(|l| l == "[MSG:Pgm End]") && r.port.core.is_idle());
    assert!(ok, "{:?}", r.lines());
    assert_eq!(r.io.requests, [Some(2), None]);
    assert_eq!(mpos(&mut r), [-20.0, -30.0, 0.0]);
    assert_eq!(r.io.spindle[..3], [(SpindleDir::Cw, 1000), (SpindleDir::Stop, 0), (SpindleDir::Cw, 1000)]);
    assert!(!r.lines().iter().any(|l| l.starts_with("ALARM")), "{:?}", r.lines());
}

#[test]
fn no_done_within_313_seconds_is_alarm_4511_and_nothing_moves() {
    let mut r = idle(Rig::with(MachineConfig::mill()));
    assert_eq!(r.command("$313=5"), vec!["ok"]);
    assert_eq!(r.command("$312=1"), vec!["ok"]);
    r.send(b"S1000 M03\nG00 X-10. Y-10.\nT02 M06\nG00 X-20. Y-30.\nM30\n");
    assert!(r.run_until(5_000, |r| !r.io.requests.is_empty()), "{:?}", r.lines());
    let start = r.now;
    let alarm = "[MSG:ALARM 4511 line 3: tool changer did not report done within 5 s of the request for T02 \
                 ($313; ATC done input)]";
    assert!(r.run_until(10_000, |r| r.lines().iter().any(|l| l == alarm)), "{:?}", r.lines());
    let waited = (r.now - start) as f64 / 1e9;
    assert!((4.999..=5.002).contains(&waited), "alarm {waited} s after the request");
    assert!(r.lines().iter().any(|l| l == "ALARM:20"), "{:?}", r.lines());
    assert_eq!(r.io.requests, [Some(2), None], "the request drops with the alarm");
    // The job is over: no motion, the spindle stays stopped, even if done comes late.
    r.inputs.tool_change_done = true;
    r.run_ms(2_000);
    assert_eq!(mpos(&mut r), [-10.0, -10.0, 0.0]);
    assert_eq!(r.port.core.spindle_output().0, SpindleDir::Stop);
    assert!(r.status().starts_with("<Alarm|"), "{}", r.status());
    assert!(!r.lines().iter().any(|l| l == "[MSG:Pgm End]"));
}

#[test]
fn reset_during_the_tool_change_aborts_it_and_drops_the_request() {
    let mut r = at_automatic_m06();
    r.send(b"\x18");
    r.run_ms(10);
    assert_eq!(r.io.requests, [Some(2), None]);
    assert!(r.status().starts_with("<Idle|"), "{}", r.status());
    // A done after the reset moves nothing, and no alarm comes later either.
    r.inputs.tool_change_done = true;
    r.run_ms(40_000);
    assert_eq!(mpos(&mut r), [-10.0, -10.0, 0.0]);
    assert!(!r.lines().iter().any(|l| l.starts_with("ALARM")), "{:?}", r.lines());
    assert_eq!(r.io.requests, [Some(2), None]);
}

#[test]
fn feed_hold_during_the_tool_change_holds_after_done_until_cycle_start() {
    let mut r = at_automatic_m06();
    r.send(b"!");
    r.run_ms(100);
    // The change itself finishes (the changer is not stopped half-way).
    r.inputs.tool_change_done = true;
    r.run_ms(1_000);
    assert_eq!(r.io.requests, [Some(2), None]);
    assert!(r.status().starts_with("<Hold:0|"), "{}", r.status());
    assert_eq!(mpos(&mut r), [-10.0, -10.0, 0.0], "held: nothing moves after done");
    assert_eq!(r.port.core.spindle_output().0, SpindleDir::Stop);
    r.send(b"~");
    let ok = r.run_until(20_000, |r| r.lines().iter().any(|l| l == "[MSG:Pgm End]") && r.port.core.is_idle());
    assert!(ok, "{:?}", r.lines());
    assert_eq!(mpos(&mut r), [-20.0, -30.0, 0.0]);
}

#[test]
fn a_done_left_on_from_before_does_not_end_the_next_change() {
    let mut r = idle(Rig::with(MachineConfig::mill()));
    assert_eq!(r.command("$312=1"), vec!["ok"]);
    r.inputs.tool_change_done = true;
    r.stream("G00 X-10. Y-10.\nT05 M06\nG00 X-20.\nM30\n", 1_000);
    r.run_ms(1_000);
    assert_eq!(mpos(&mut r), [-10.0, -10.0, 0.0], "a stuck done is not this change's");
    r.inputs.tool_change_done = false;
    r.run_ms(5);
    r.inputs.tool_change_done = true;
    let ok = r.run_until(20_000, |r| r.lines().iter().any(|l| l == "[MSG:Pgm End]") && r.port.core.is_idle());
    assert!(ok, "{:?}", r.lines());
    assert_eq!(r.io.requests, [Some(5), None]);
}

#[test]
fn settings_312_and_313_are_a_mills() {
    let mut r = idle(Rig::new());
    let all = r.command("$$");
    assert!(!all.iter().any(|l| l.starts_with("$312=") || l.starts_with("$313=")), "{all:?}");
    assert_eq!(r.command("$312=1").last().unwrap(), "error:2");
    assert_eq!(r.command("$311=1").last().unwrap(), "ok");
    let all = r.command("$$");
    for want in ["$312=0", "$313=30"] {
        assert!(all.contains(&want.to_string()), "{want} missing from {all:?}");
    }
    assert_eq!(r.command("$313=0").last().unwrap(), "error:2");
    assert_eq!(r.command("$313=3601").last().unwrap(), "error:2");
    assert_eq!(r.command("$313=2.5").last().unwrap(), "error:2");
    assert_eq!(r.command("$312=2").last().unwrap(), "error:2");
    assert_eq!(r.command("$312=1"), vec!["ok"]);
    assert_eq!(r.command("$313=45"), vec!["ok"]);
    assert!(r.ctl.take_dirty().settings, "stored");
    let all = r.command("$$");
    assert!(all.contains(&"$312=1".to_string()) && all.contains(&"$313=45".to_string()), "{all:?}");
    let cfg = r.ctl.interpreter().config();
    assert_eq!(cfg.tool_changer, interp_core::config::ToolChanger::Automatic);
    assert_eq!(cfg.tool_change_timeout.seconds(), 45);
}

/// A SINUMERIK cycle message (62xxx) reaches the sender as `[MSG:…]` with its
/// line: HOLES1 without a modal drilling cycle only positions, 62100 (seed 001
/// lines 3095-3101), and waits for cycle start before it goes on.
#[test]
fn a_cycle_message_reaches_the_sender_with_its_line() {
    let cfg = MachineConfig { language: interp_core::config::Language::Siemens, ..MachineConfig::mill() };
    let mut r = idle(Rig::with(cfg));
    let answers = r.stream("G17 G90 G0 X0 Y0 Z-10\nHOLES1(10, 20, 0, 5, 10, 3)\nM30\n", 5_000);
    let want =
        "[MSG:line 2: message 62100: no drilling cycle active (program MCALL CYCLE81-89/840 before the pattern)]";
    assert!(answers.iter().any(|l| l == want), "{answers:?}");
    assert_eq!(answers.iter().filter(|l| l.contains("62100")).count(), 1, "shown once: {answers:?}");
}

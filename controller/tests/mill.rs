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
    assert!(r.status().starts_with("<Hold:1|MPos:-10.000,-10.000,0.000|"), "{}", r.status());
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

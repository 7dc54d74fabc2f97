//! `$` commands, jogging, homing, inputs and check mode.

mod common;

use common::{Rig, direct, field};

fn idle_rig() -> Rig {
    let mut r = Rig::new();
    r.run_ms(2);
    r.take_lines();
    r
}

#[test]
fn settings_read_write_and_reconfigure_the_motion_core() {
    let mut r = idle_rig();
    let all = r.command("$$");
    assert!(all.contains(&"$100=400".to_string()), "{all:?}");
    assert!(all.contains(&"$102=320".to_string()));
    assert!(all.contains(&"$130=165".to_string()));
    assert!(all.contains(&"$20=1".to_string()));
    assert_eq!(r.ctl.take_dirty(), controller::Dirty::default());
    assert_eq!(r.command("$102=640"), vec!["ok"]);
    assert!(r.ctl.take_dirty().settings);
    assert!(r.command("$$").contains(&"$102=640".to_string()));
    assert_eq!(r.port.core.params().scale[2].steps(1_000_000), 640);
    assert_eq!(r.command("$22=2").last().unwrap(), "error:2");
    assert_eq!(r.command("$999=1").last().unwrap(), "error:3");
    assert_eq!(r.command("$P5147=1.5"), vec!["ok"]);
    assert_eq!(r.ctl.param(5147), Some(1.5));
    assert!(r.command("$P").contains(&"$P5147=1.5".to_string()));
    assert_eq!(r.command("$P1=1").last().unwrap(), "error:3");
    assert_eq!(r.command("$RST=$"), vec!["ok"]);
    assert!(r.command("$$").contains(&"$102=320".to_string()));
}

#[test]
fn modal_state_offsets_and_build_info() {
    let mut r = idle_rig();
    let answers = r.stream("G99 G96 S120 M03 T0101\nG00 X50 Z5\nM30\n", 20_000);
    assert!(answers.iter().any(|l| l == "[MSG:Pgm End]"), "{answers:?}");
    let g = r.command("$G");
    assert_eq!(g[0], "[GC:G0 G54 G18 G21 G96 G99 M3 M9 T0101 F0 S120]");
    let h = r.command("$#");
    assert_eq!(h[0], "[G54:0.000,0.000,0.000]");
    assert_eq!(h[6], "[G28:300.000,0.000,250.000]");
    assert!(h.iter().any(|l| l.starts_with("[TLO:")));
    let i = r.command("$I");
    assert_eq!(i[0], "[VER:1.1h.lathe:]");
    assert_eq!(i[1], "[OPT:,64,128]");
    assert_eq!(r.command("$").last().unwrap(), "ok");
}

#[test]
fn startup_blocks_run_after_reset() {
    let mut r = idle_rig();
    assert_eq!(r.command("$N0=G55"), vec!["ok"]);
    assert_eq!(r.command("$N").as_slice(), ["$N0=G55", "$N1=", "ok"]);
    r.send(&[0x18]);
    r.run_ms(20);
    let got = r.take_lines();
    assert_eq!(got, vec!["Grbl 1.1h ['$' for help]", ">G55:ok"]);
    assert_eq!(r.ctl.interpreter().state().modal.work_frame, 1);
}

#[test]
fn common_variables_and_link_numbers() {
    let mut r = idle_rig();
    let answers = r.stream("#500=1.5\n#1=2\nM30\n", 5_000);
    assert!(answers.iter().any(|l| l == "[MSG:Pgm End]"));
    assert_eq!(r.command("$V"), vec!["[VAR:#500=1.5]", "ok"]);
    assert_eq!(r.command("$LN=5"), vec!["[LN:5]", "ok"]);
    let a = r.command(&controller::frame_line(4, "G00 X1"));
    assert_eq!(a, vec!["ok"], "a duplicate is answered ok and dropped");
    let a = r.command(&controller::frame_line(6, "G00 X1"));
    assert_eq!(a, vec!["[MSG:Resend:5]", "error:88"]);
    let a = r.command("G00 X1");
    assert_eq!(a, vec!["[MSG:Resend:5]", "error:88"], "plain lines refused once checksums are on");
    assert_eq!(r.command(&controller::frame_line(5, "G00 X1")), vec!["ok"]);
}

/// A late resend of line 1 inside a streamed job is a duplicate (answered `ok`,
/// dropped), not a restart that would run the job's first lines twice; once the
/// job has ended, line 1 starts the next job's numbering.
#[test]
fn line_one_inside_a_job_is_a_duplicate_not_a_restart() {
    let mut r = idle_rig();
    assert_eq!(r.command(&controller::frame_line(1, "G98 G01 F600")), vec!["ok"]);
    assert_eq!(r.command(&controller::frame_line(2, "W-1")), vec!["ok"]);
    assert_eq!(r.command(&controller::frame_line(1, "G98 G01 F600")), vec!["ok"]);
    assert_eq!(r.command(&controller::frame_line(2, "W-1")), vec!["ok"]);
    assert_eq!(r.command(&controller::frame_line(3, "M30")), vec!["ok"]);
    assert!(r.run_until(20_000, |r| r.port.core.is_idle() && r.status().starts_with("<Idle")));
    // One W-1 ran, not two.
    assert!(r.status().contains("MPos:0.000,0.000,-1.000"), "{}", r.status());
    assert_eq!(r.command(&controller::frame_line(1, "G00 W-1")), vec!["ok"], "a new job numbers from 1");
    assert_eq!(r.command(&controller::frame_line(2, "M30")), vec!["ok"]);
    assert!(r.run_until(20_000, |r| r.port.core.is_idle() && r.status().starts_with("<Idle")));
    assert!(r.status().contains("MPos:0.000,0.000,-2.000"), "{}", r.status());
}

#[test]
fn jogging_moves_and_jog_cancel_brakes() {
    let mut r = idle_rig();
    assert_eq!(r.command("$J=G91 X10 Z-5 F1000"), vec!["ok"]);
    assert!(r.status().starts_with("<Jog"));
    assert!(r.run_until(5_000, |r| r.port.core.is_idle()));
    r.run_ms(2);
    let s = r.status();
    assert!(s.starts_with("<Idle|MPos:10.000,0.000,-5.000"), "{s}");
    assert_eq!(r.command("$J=G90 X400 F1000").last().unwrap(), "error:15");
    assert_eq!(r.command("$J=G91 X10").last().unwrap(), "error:16");
    assert_eq!(r.command("$J=G53 Z-100 F600"), vec!["ok"]);
    r.run_ms(1_000);
    r.send(&[0x85]);
    assert!(r.run_until(3_000, |r| r.port.core.is_idle()));
    r.run_ms(2);
    let s = r.status();
    let z: f64 = field(&s, "MPos:").split(',').nth(2).unwrap().parse().unwrap();
    assert!(s.starts_with("<Idle") && z < -5.0 && z > -100.0, "{s}");
    // The interpreter knows where the jog left the axes.
    assert_eq!(r.command("G00 W-1"), vec!["ok"]);
    r.run_ms(500);
    let z2: f64 = field(&r.status(), "MPos:").split(',').nth(2).unwrap().parse().unwrap();
    assert!((z2 - (z - 1.0)).abs() < 0.002, "{z} {z2}");
}

#[test]
fn homing_without_switches_sets_the_reference_where_the_axes_stand() {
    let mut r = idle_rig();
    let a = r.command("$H");
    assert_eq!(a.last().unwrap(), "ok");
    assert!(r.status().contains("MPos:300.000,0.000,250.000"));
}

#[test]
fn homing_with_switches_finds_them() {
    let mut r = idle_rig();
    assert_eq!(r.command("$22=1"), vec!["ok"]);
    assert_eq!(r.command("$25=2000"), vec!["ok"]);
    // Not homed yet: G28 needs the reference.
    assert_eq!(r.command("G28 U0")[0], "ok");
    assert!(r.run_until(50, |r| r.lines().iter().any(|l| l == "ALARM:20")), "{:?}", r.lines());
    assert_eq!(r.command("$X").last().unwrap(), "ok");
    assert_eq!(r.command("$H"), vec!["ok"]);
    // The switches sit 20 mm (X radius) and 40 mm (Z) above the start.
    let ok = r.run_until(60_000, |r| {
        let p = r.port.core.position();
        r.inputs.home_x = p.0[0] >= 20_000_000;
        r.inputs.home_z = p.0[2] >= 40_000_000;
        r.lines().iter().any(|l| l == "[MSG:Homed]" || l == "ALARM:9")
    });
    assert!(ok && r.lines().iter().any(|l| l == "[MSG:Homed]"), "{:?}", r.lines());
    r.inputs.home_x = false;
    r.inputs.home_z = false;
    assert!(r.run_until(5_000, |r| r.port.core.is_idle()));
    r.run_ms(2);
    let s = r.status();
    // Pulled off 1 mm from the switch points, which are now the reference (X 300 dia, Z 250).
    let x: f64 = field(&s, "MPos:").split(',').next().unwrap().parse().unwrap();
    let z: f64 = field(&s, "MPos:").split(',').nth(2).unwrap().parse().unwrap();
    assert!(
        (x - 298.0).abs() < 0.05 && (z - 249.0).abs() < 0.05,
        "{s} {:?}",
        r.port.pushed.iter().map(|c| c.action.endpoint().unwrap().machine).collect::<Vec<_>>()
    );
}

#[test]
fn estop_and_hard_limit_alarms() {
    let mut r = idle_rig();
    r.send(b"G98 G01 Z-100 F500\n");
    r.run_ms(200);
    r.inputs.estop = true;
    r.run_ms(2);
    let got = r.take_lines();
    assert!(got.contains(&"ALARM:10".to_string()), "{got:?}");
    assert!(r.status().contains("|Pn:E>"));
    assert_eq!(r.command("$X").last().unwrap(), "error:9");
    r.inputs.estop = false;
    assert!(r.run_until(1_000, |r| r.port.core.is_idle()));
    assert_eq!(r.command("$X").last().unwrap(), "ok");
    assert!(r.status().starts_with("<Idle"));
    r.send(b"G01 Z-100 F500\n");
    r.run_ms(100);
    r.inputs.limit_z = true;
    r.run_ms(2);
    assert!(r.take_lines().contains(&"ALARM:1".to_string()));
    assert_eq!(r.command("G00 Z0").last().unwrap(), "error:9");
}

#[test]
fn check_mode_interprets_without_motion() {
    let mut r = idle_rig();
    assert_eq!(r.command("$C"), vec!["[MSG:Enabled]", "ok"]);
    let answers = r.stream("G98 G00 X20 Z0\nG01 Z-50 F100\nM30\n", 5_000);
    assert!(answers.iter().any(|l| l == "[MSG:Pgm End]"), "{answers:?}");
    assert!(r.port.pushed.is_empty());
    assert!(r.status().starts_with("<Check|MPos:0.000,0.000,0.000"));
    assert_eq!(r.command("$C"), vec!["[MSG:Disabled]", "ok"]);
}

#[test]
fn run_from_memory_and_door() {
    let mut r = idle_rig();
    let prog = "O0100\nG98 G00 X20 Z0\nG01 Z-30 F600\nG00 X40\nM30\n";
    r.ctl.memory_mut().load(prog.as_bytes(), None).unwrap();
    assert_eq!(r.command("$PR=100"), vec!["ok"]);
    assert_eq!(r.command("G00 X1").last().unwrap(), "error:8");
    r.run_ms(300);
    r.inputs.door = true;
    r.run_ms(1_000);
    assert!(r.status().starts_with("<Door:1"));
    r.inputs.door = false;
    r.run_ms(2);
    assert!(r.status().starts_with("<Door:0"));
    r.send(b"~");
    let ok = r.run_until(20_000, |r| r.lines().iter().any(|l| l == "[MSG:Pgm End]") && r.port.core.is_idle());
    assert!(ok);
    let mut mem = interp_core::program::ProgramMemory::<16384, 16, 512>::new();
    mem.load(prog.as_bytes(), None).unwrap();
    assert_eq!(r.port.pushed, direct("M98 P100\n", Some(&mem)));
    assert!(r.status().starts_with("<Idle|MPos:40.000,0.000,-30.000"));
    assert_eq!(r.command("$PR=7").last().unwrap(), "error:20");
}

/// A grbl sender's closing `G4 P0.5` runs as a 0.5 s dwell (`$303=1`, the default);
/// with `$303=0` the line is the board's language as written: G04 P takes no
/// decimal point (2.6), alarm 0007, and nothing of it moves.
#[test]
fn a_grbl_sync_dwell_runs_as_seconds_or_raises_0007_as_the_manual_says() {
    use interp_core::canon::Action;
    let mut r = idle_rig();
    let answers = r.stream("G4 P0.5\nM30\n", 5_000);
    assert!(answers.contains(&"[MSG:Pgm End]".to_string()), "{answers:?}");
    assert!(r.port.pushed.iter().any(|c| c.line == 1 && c.action == Action::Dwell { ms: 500 }), "{:?}", r.port.pushed);
    let mut r = idle_rig();
    assert_eq!(r.command("$303=0"), vec!["ok"]);
    let answers = r.stream("G4 P0.5\n", 5_000);
    assert!(answers.iter().any(|l| l.starts_with("[MSG:ALARM 0007 line 1")), "{answers:?}");
    assert!(answers.contains(&"ALARM:20".to_string()), "{answers:?}");
    assert!(r.port.pushed.is_empty(), "{:?}", r.port.pushed);
    // FANUC milliseconds are never rewritten.
    let mut r = idle_rig();
    r.stream("G4 P500\nM30\n", 5_000);
    assert!(r.port.pushed.iter().any(|c| c.line == 1 && c.action == Action::Dwell { ms: 500 }));
}

/// `$310`: the language at power-on and after a reset (FANUC 0, SINUMERIK 1),
/// kept with the settings; `$I` names the language in force; a SINUMERIK
/// program streams after the reset.
#[test]
fn setting_310_selects_the_sinumerik_language_from_the_next_reset() {
    let mut r = idle_rig();
    assert!(r.command("$$").contains(&"$310=0".to_string()));
    assert!(r.command("$I").iter().any(|l| l.contains("FANUC lathe language")));
    assert_eq!(r.command("$310=2").last().unwrap(), "error:2");
    assert_eq!(r.command("$310=1"), vec!["ok"]);
    assert!(r.ctl.take_dirty().settings, "stored like the other settings");
    assert!(r.command("$$").contains(&"$310=1".to_string()));
    r.send(&[0x18]);
    r.run_ms(20);
    r.take_lines();
    assert!(r.command("$I").iter().any(|l| l.contains("SINUMERIK lathe language")), "{:?}", r.command("$I"));
    let answers = r.stream("R1=25 ; SINUMERIK\nG0 X=R1*2 Z=IC(5)\nM30\n", 20_000);
    assert!(answers.iter().any(|l| l == "[MSG:Pgm End]"), "{answers:?}");
    assert_eq!(r.ctl.interpreter().siemens_vars().r(1), Ok(25.0));
}

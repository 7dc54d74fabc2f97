//! The grbl line protocol and streaming, on a real motion core.

mod common;

use common::{Rig, direct, field};

const SHAFT: &str = "G21 G18 G97 G98
G00 X100 Z5
M03 S800
G01 X40 Z2 F500
Z-20 F300
X50 Z-30
G02 X60 Z-35 R5
G01 Z-50
G03 X70 Z-55 R5
G00 X100
Z5
M05
M30
";

#[test]
fn welcome_then_idle_status() {
    let mut r = Rig::new();
    r.run_ms(2);
    assert_eq!(r.take_lines(), vec!["Grbl 1.1h ['$' for help]".to_string()]);
    let s = r.status();
    assert_eq!(s, "<Idle|MPos:0.000,0.000,0.000|FS:0,0|Bf:64,128|Ln:0|WCO:0.000,0.000,0.000|Ov:100,100,100>");
}

#[test]
fn a_streamed_program_runs_exactly_the_interpreters_actions() {
    let mut r = Rig::new();
    let answers = r.stream(SHAFT, 60_000);
    assert_eq!(answers.iter().filter(|l| *l == "ok").count(), SHAFT.lines().count(), "{answers:?}");
    assert!(answers.iter().any(|l| l == "[MSG:Pgm End]"), "{answers:?}");
    assert_eq!(r.port.pushed, direct(SHAFT, None));
    let s = r.status();
    assert!(s.starts_with("<Idle|MPos:100.000,0.000,5.000|"), "{s}");
    assert_eq!(r.io.spindle.first().map(|s| s.1), Some(800));
}

#[test]
fn g71_g70_streamed_waits_for_the_shape_lines() {
    let text = std::fs::read_to_string("../examples/cycles_g71_g70.nc").unwrap();
    // Faster feeds: the same actions, a shorter simulation.
    let body: String = text
        .lines()
        .filter(|l| l.trim() != "%")
        .map(|l| format!("{}\n", l.replace("F200", "F2000").replace("F100", "F1000")))
        .collect();
    let mut r = Rig::new();
    let answers = r.stream(&body, 600_000);
    assert!(answers.iter().any(|l| l == "[MSG:Pgm End]"), "{answers:?}");
    assert!(!answers.iter().any(|l| l.starts_with("ALARM")), "{answers:?}");
    assert!(r.ctl.counters().lookahead_waits > 0);
    let want = direct(&body, None);
    assert!(want.len() > 20);
    assert_eq!(r.port.pushed, want);
}

#[test]
fn backward_goto_and_while_inside_the_window() {
    let text = "G98 G00 X20 Z0
#1=0
WHILE [#1 LT 5] DO1
G01 W-1 F600
#1=#1+1
END1
N50 #2=[#2+1]
IF [#2 LT 3] GOTO50
G00 X30 Z#2
M30
";
    let mut r = Rig::new();
    let answers = r.stream(text, 60_000);
    assert!(answers.iter().any(|l| l == "[MSG:Pgm End]"), "{answers:?}");
    let want = direct(text, None);
    assert_eq!(r.port.pushed, want);
    assert_eq!(r.ctl.interpreter().variables().get(2).map(|v| v.unwrap_or(0.0)), Ok(3.0));
}

#[test]
fn a_jump_out_of_the_window_is_a_clear_alarm() {
    // A 512-byte window: N10 is long gone when the GOTO comes.
    let mut text = String::from("N10 G98 G00 X20 Z0\n");
    for i in 0..80 {
        text.push_str(&format!("G01 Z-{}.{:03} F3000\n", i / 10, i % 10));
    }
    text.push_str("GOTO10\nM30\n");
    let mut r: Rig<controller::Controller<512, 1024, 4, 64>> = Rig::with(interp_core::MachineConfig::default());
    let answers = r.stream(&text, 60_000);
    let msg = answers.iter().find(|l| l.starts_with("[MSG:ALARM")).expect("alarm message");
    assert!(msg.contains("line 82"), "{msg}");
    assert!(answers.iter().any(|l| l.contains("upload the program")), "{answers:?}");
    assert!(answers.iter().any(|l| l == "ALARM:20"), "{answers:?}");
    assert!(r.ctl.counters().window_dropped > 0);
}

#[test]
fn feed_hold_and_resume_mid_program() {
    let text = "G98 G00 X20 Z0\nG01 Z-40 F600\nZ-80\nG00 X40\nM30\n";
    let mut r = Rig::new();
    let mut sender = common::Counting::new(text.lines().map(String::from).collect());
    sender.pump(&mut r);
    r.run_ms(2_000);
    r.send(b"!");
    let s = r.status();
    assert!(s.starts_with("<Hold:0") || s.starts_with("<Hold:1"), "{s}");
    r.run_ms(1_000);
    let held = r.status();
    assert!(held.starts_with("<Hold:0"), "{held}");
    r.run_ms(500);
    assert_eq!(field(&r.status(), "MPos:"), field(&held, "MPos:"));
    r.send(b"~");
    let ok = r.run_until(60_000, |r| r.lines().iter().any(|l| l == "[MSG:Pgm End]") && r.port.core.is_idle());
    assert!(ok, "{:?}", r.lines());
    assert!(r.status().contains("MPos:40.000,0.000,-80.000"));
    assert_eq!(r.port.pushed, direct(text, None));
}

#[test]
fn soft_reset_mid_program_stops_and_welcomes() {
    let text = "G98 G00 X20 Z0\nG01 Z-200 F300\nM30\n";
    let mut r = Rig::new();
    r.send(text.as_bytes());
    r.run_ms(1_500);
    assert!(r.status().starts_with("<Run"));
    r.take_lines();
    r.send(&[0x18]);
    r.run_ms(5);
    assert_eq!(
        r.take_lines(),
        ["Grbl 1.1h ['$' for help]", "[MSG:Reset in motion: braked on the path, position kept]"]
    );
    assert!(r.run_until(2_000, |r| r.port.core.is_idle()));
    let s = r.status();
    assert!(s.starts_with("<Idle"), "{s}");
    let z: f64 = field(&s, "MPos:").split(',').nth(2).unwrap().parse().unwrap();
    assert!(z < -1.0 && z > -200.0, "{s}");
    // The interpreter continues from where the axes stopped.
    let a = r.command("G00 W1");
    assert_eq!(a, vec!["ok"]);
    r.run_ms(500);
    let z2: f64 = field(&r.status(), "MPos:").split(',').nth(2).unwrap().parse().unwrap();
    assert!((z2 - (z + 1.0)).abs() < 0.01, "{z} {z2}");
}

#[test]
fn overrides_show_in_ov() {
    let mut r = Rig::new();
    r.send(&[0x91, 0x91, 0x93, 0x96, 0x9A]);
    let s = r.status();
    assert_eq!(field(&s, "Ov:"), "121,50,110");
    r.send(&[0x90, 0x95, 0x99, 0x92, 0x92]);
    assert_eq!(field(&r.status(), "Ov:"), "80,100,100");
    // The spindle override changes the speed the drive is told (and measures).
    assert_eq!(r.command("M03 S1000"), vec!["ok"]);
    r.run_ms(100);
    let rpm = |r: &mut Rig| -> i32 { field(&r.status(), "FS:").split(',').nth(1).unwrap().parse().unwrap() };
    assert!((rpm(&mut r) - 1000).abs() <= 2);
    r.send(&[0x9A, 0x9A]);
    r.run_ms(100);
    assert!((rpm(&mut r) - 1200).abs() <= 2);
    assert_eq!(r.port.core.spindle_output().1, 1200);
}

#[test]
fn error_lines() {
    let mut r = Rig::new();
    r.run_ms(2);
    let a = r.command("G01 X1\u{1}");
    assert_eq!(a.last().unwrap(), "error:1");
    let long = "G01 X1 ".repeat(30);
    let a = r.command(&long);
    assert_eq!(a.last().unwrap(), "error:11");
    let a = r.command("$Q");
    assert_eq!(a.last().unwrap(), "error:3");
    let a = r.command("G01 X1 \u{e9}");
    assert_eq!(a, vec!["[MSG:Byte 0xC3 is not G-code text: line refused]", "error:1"]);
    // Real-time bytes inside a line act and leave the line intact.
    r.send(b"G00 W");
    r.send(&[0x91]);
    r.send(b"0.5");
    assert_eq!(r.command(""), vec!["ok"]);
    assert_eq!(field(&r.status(), "Ov:"), "110,100,100");
    // A % inside a running stream is text: the interpreter's end-of-record alarm.
    let a = r.command("%");
    assert_eq!(a[0], "ok");
    assert!(r.run_until(100, |r| r.lines().iter().any(|l| l.starts_with("[MSG:ALARM 5010 line 2"))), "{:?}", r.lines());
    assert_eq!(r.command("$X").last().unwrap(), "ok");
    let a = r.command("G00 X500");
    assert_eq!(a[0], "ok");
    assert!(r.run_until(100, |r| r.lines().iter().any(|l| l == "ALARM:2")), "{:?}", r.lines());
    assert!(r.lines().iter().any(|l| l == "[MSG:ALARM 0500 line 1: move exceeds the + soft limit of axis X]"));
    let a = r.command("G00 X10");
    assert_eq!(a.last().unwrap(), "error:9");
    let a = r.command("$X");
    assert_eq!(a, vec!["[MSG:Caution: Unlocked]", "ok"]);
    assert_eq!(r.command("G00 X10"), vec!["ok"]);
}

#[test]
fn a_program_alarm_midway_stops_with_its_line_and_nothing_of_that_block() {
    let text = "G98 G00 X20 Z0\nG01 Z-10 F600\nZ-20\nM98 P9999\nG00 X40\nM30\n";
    let mut r = Rig::new();
    let answers = r.stream(text, 30_000);
    let msg = answers.iter().find(|l| l.starts_with("[MSG:ALARM")).expect("alarm");
    assert!(msg.contains("line 4"), "{msg}");
    assert!(answers.iter().any(|l| l == "ALARM:20"));
    assert!(r.port.pushed.iter().all(|c| c.line < 4), "{:?}", r.port.pushed);
    assert!(r.status().starts_with("<Alarm"));
}

#[test]
fn a_runaway_loop_still_answers_status_and_reset_within_10ms() {
    let mut r = Rig::new();
    r.send(b"WHILE [1 EQ 1] DO1\n#1=#1+1\nEND1\n");
    r.run_ms(50);
    r.take_lines();
    r.send(b"?");
    r.run_ms(10);
    let got = r.take_lines();
    assert!(got.iter().any(|l| l.starts_with("<Run")), "{got:?}");
    r.send(&[0x18]);
    r.run_ms(10);
    assert!(r.take_lines().iter().any(|l| l.starts_with("Grbl 1.1h")));
    assert!(r.status().starts_with("<Idle"));
}

#[test]
fn loops_survive_the_window_dropping_old_text() {
    // A 512-byte window: text before and after the loop moves through it while
    // the loop runs; its WHILE block stays.
    let mut text = String::from("G98 G00 X20 Z0\n");
    for _ in 0..40 {
        text.push_str("G01 W-0.100 F3000\n");
    }
    text.push_str("#1=0\nWHILE [#1 LT 20] DO1\nG01 U0.2 F3000\nG01 U-0.2\n#1=#1+1\nEND1\n");
    for _ in 0..40 {
        text.push_str("G01 W-0.100 F3000\n");
    }
    text.push_str("M30\n");
    let mut r: Rig<controller::Controller<512, 1024, 4, 64>> = Rig::with(interp_core::MachineConfig::default());
    let answers = r.stream(&text, 60_000);
    assert!(answers.iter().any(|l| l == "[MSG:Pgm End]"), "{answers:?}");
    assert!(r.ctl.counters().window_dropped > 1000);
    assert_eq!(r.port.pushed, direct(&text, None));
}

#[test]
fn m00_waits_for_cycle_start() {
    let text = "G98 G00 X20 Z0\nM00\nG00 Z-10\nM30\n";
    let mut r = Rig::new();
    r.send(text.as_bytes());
    r.run_ms(1_000);
    assert!(r.status().starts_with("<Hold:0|MPos:20.000,0.000,0.000"));
    r.run_ms(500);
    assert!(r.status().starts_with("<Hold:0|MPos:20.000,0.000,0.000"));
    r.send(b"~");
    assert!(r.run_until(5_000, |r| r.lines().iter().any(|l| l == "[MSG:Pgm End]") && r.port.core.is_idle()));
    assert!(r.status().starts_with("<Idle|MPos:20.000,0.000,-10.000"));
    assert_eq!(r.port.pushed, direct(text, None));
}

#[test]
fn a_look_ahead_beyond_a_full_window_is_an_alarm_not_a_deadlock() {
    // G71's shape starts 40 lines later: it cannot fit into a 512-byte window
    // together with the cycle block.
    let mut text = String::from("G98 G00 X100 Z5\nG71 U2 R1 F2000\nG71 P100 Q200 U0.5 W0.2\n");
    for _ in 0..40 {
        text.push_str("(FILLER COMMENT LINE)\n");
    }
    text.push_str("N100 G00 X40\nG01 Z-30 F1000\nN200 X100\nM30\n");
    let mut r: Rig<controller::Controller<512, 1024, 4, 64>> = Rig::with(interp_core::MachineConfig::default());
    let answers = r.stream(&text, 10_000);
    let msg = answers.iter().find(|l| l.starts_with("[MSG:ALARM")).expect("alarm");
    assert!(msg.contains("line 3"), "{msg}");
    assert!(answers.iter().any(|l| l.contains("upload the program")));
    // Every line was answered: `ok` before the alarm, `error:9` after it.
    assert_eq!(answers.iter().filter(|l| *l == "ok" || l.starts_with("error:")).count(), text.lines().count());
}

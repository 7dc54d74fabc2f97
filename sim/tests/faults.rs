//! Machine faults on the virtual board (the controller on the simulated machine):
//! e-stop mid-move and mid-thread, a limit switch hit, the encoder signal lost
//! mid-thread, the spindle stalled or slowed (threads and G99), a thread too fast
//! for the drives, the link lost mid-stream. Each must end in a controlled stop
//! with the right alarm, no step after the stop, and a state from which a soft
//! reset and a new program work.

use interp_core::alarm::AlarmKind;
use interp_core::axis::Axis;
use interp_core::{Alarm, MachineConfig};
use motion_core::motion::State;
use sim::board::VirtualBoard;
use sim::{Faults, Span};

/// 1 ms of simulated time.
const MS: u64 = 1_000_000;
/// Axis acceleration of the default machine, mm/s².
const ACCEL: f64 = 500.0;

/// A board on the default machine, welcomed and in grbl mode (`?` seen).
fn board() -> VirtualBoard {
    board_on(MachineConfig::default())
}

fn board_on(cfg: MachineConfig) -> VirtualBoard {
    let mut b = VirtualBoard::new(cfg).expect("machine");
    b.run_for(10 * MS);
    assert!(status(&mut b).starts_with("<Idle|"));
    b
}

/// One `?` status report.
fn status(b: &mut VirtualBoard) -> String {
    b.transmit();
    b.receive(b"?");
    b.run_for(2 * MS);
    let out = String::from_utf8_lossy(&b.transmit()).to_string();
    out.lines().find(|l| l.starts_with('<')).unwrap_or_default().to_string()
}

/// Sends `text` line by line (grbl character counting: 128 bytes in flight) until
/// every line is answered or `until` says stop; returns everything received.
fn stream(b: &mut VirtualBoard, text: &str, mut until: impl FnMut(&VirtualBoard) -> bool) -> String {
    let mut lines: Vec<&str> = text.lines().rev().collect();
    let mut in_flight: std::collections::VecDeque<usize> = Default::default();
    let mut log = String::new();
    for _ in 0..600_000 {
        while let Some(l) = lines.last() {
            if in_flight.iter().sum::<usize>() + l.len() + 1 > 128 {
                break;
            }
            b.receive(format!("{l}\n").as_bytes());
            in_flight.push_back(l.len() + 1);
            lines.pop();
        }
        b.run_for(MS);
        let out = String::from_utf8_lossy(&b.transmit()).to_string();
        for l in out.lines() {
            if l == "ok" || l.starts_with("error:") {
                in_flight.pop_front();
            }
        }
        log.push_str(&out);
        if until(b) || (lines.is_empty() && in_flight.is_empty()) {
            return log;
        }
    }
    panic!("stream never finished: {log}");
}

/// Runs until `cond` holds (at most `limit_ms`); false if it never did.
fn run_until(b: &mut VirtualBoard, limit_ms: u64, mut cond: impl FnMut(&VirtualBoard) -> bool) -> bool {
    for _ in 0..limit_ms {
        if cond(b) {
            return true;
        }
        b.run_for(MS);
    }
    cond(b)
}

/// Runs until the motion core is idle with every step issued, then checks that
/// nothing moves for another half second; returns the output collected.
fn settle(b: &mut VirtualBoard) -> String {
    assert!(run_until(b, 20_000, |b| b.sim.core.is_idle()), "never stopped: {:?}", b.sim.core.state());
    let pulses = b.sim.pulses();
    let at = b.position();
    let mut out = String::from_utf8_lossy(&b.transmit()).to_string();
    b.run_for(500 * MS);
    out.push_str(&String::from_utf8_lossy(&b.transmit()));
    assert_eq!(b.sim.pulses(), pulses, "a step after the stop");
    assert_eq!(b.position(), at);
    out
}

/// Machine Z / X (radius), mm.
fn z_mm(b: &VirtualBoard) -> f64 {
    b.position()[Axis::Z] as f64 / 1e6
}

/// The motion core's alarm kind.
fn core_alarm(b: &VirtualBoard) -> Option<AlarmKind> {
    b.sim.core.alarm().map(|a: Alarm| a.kind)
}

/// Soft reset with the fault cleared, then a short program: it must run to its end
/// and put Z at `z` (mm).
fn restart_works(b: &mut VirtualBoard, z: f64) {
    b.sim.faults = Faults::default();
    b.switches = Default::default();
    b.receive(&[0x18]);
    b.run_for(20 * MS);
    let st = status(b);
    assert!(st.starts_with("<Idle|"), "after reset: {st}");
    let log = stream(b, &format!("G00 Z{z}\nM30\n"), |_| false);
    assert!(!log.contains("error") && !log.contains("ALARM"), "{log}");
    settle(b);
    assert!((z_mm(b) - z).abs() < 0.01, "restart ended at Z {}", z_mm(b));
    assert_eq!(b.ctl.alarm(), None);
}

#[test]
fn estop_mid_feed_brakes_on_the_path_and_alarms_10() {
    let mut b = board();
    let v = 3_000.0 / 60.0; // mm/s
    stream(&mut b, "G98 G01 Z100 F3000\nM30\n", |b| z_mm(b) < 200.0);
    assert!(run_until(&mut b, 5_000, |b| z_mm(b) < 200.0));
    let (z0, x0) = (z_mm(&b), b.position()[Axis::X]);
    b.switches.estop = true;
    let out = settle(&mut b);
    let d = z0 - z_mm(&b);
    let brake = v * v / (2.0 * ACCEL);
    eprintln!("e-stop mid-feed: {d:.3} mm to stop at {v} mm/s (v²/2a = {brake:.3})");
    assert!(d > 0.8 * brake && d < brake + v * 0.003, "stop distance {d:.3} mm, braking {brake:.3} mm");
    assert_eq!(b.position()[Axis::X], x0, "stays on the path");
    assert!(out.contains("ALARM:10"), "{out}");
    assert_eq!(b.ctl.alarm(), Some(10));
    assert_eq!(core_alarm(&b), Some(AlarmKind::EmergencyStop));
    assert_eq!(b.sim.core.state(), State::Idle);
    assert!(status(&mut b).starts_with("<Alarm|"));
    restart_works(&mut b, 220.0);
}

/// A thread pass from Z10 to Z-60 at lead 2 mm, 600 rpm (20 mm/s).
const THREAD: &str = "G97 S600 M03\nG00 X40 Z10\nG32 Z-60 F2\nG00 X60\nZ10\nM30\n";

/// Streams THREAD and runs until the pass is locked and Z is below -20.
fn mid_thread(b: &mut VirtualBoard) {
    stream(b, THREAD, |_| false);
    assert!(run_until(b, 20_000, |b| b.sim.core.state() == State::Locked && z_mm(b) < -20.0));
}

#[test]
fn estop_mid_thread_brakes_along_the_thread_and_stops_the_spindle() {
    let mut b = board();
    mid_thread(&mut b);
    let z0 = z_mm(&b);
    let x0 = b.position()[Axis::X];
    b.switches.estop = true;
    let out = settle(&mut b);
    let v = 20.0;
    let d = z0 - z_mm(&b);
    let brake = v * v / (2.0 * ACCEL);
    eprintln!("e-stop mid-thread: {d:.3} mm to stop at {v} mm/s (v²/2a = {brake:.3})");
    assert!(d > 0.5 * brake && d < brake + v * 0.003, "stop distance {d:.3} mm, braking {brake:.3} mm");
    assert_eq!(b.position()[Axis::X], x0, "the tool stays in the thread's line");
    assert!(out.contains("ALARM:10"), "{out}");
    assert_eq!(core_alarm(&b), Some(AlarmKind::EmergencyStop));
    assert_eq!(b.sim.core.spindle_output().1, 0, "spindle commanded to stop");
    assert!(run_until(&mut b, 2_000, |b| b.sim.spindle.rpm().abs() < 1.0), "spindle runs down");
    restart_works(&mut b, 30.0);
}

#[test]
fn limit_switch_hit_after_lost_steps_alarms_1_and_brakes() {
    let mut b = board();
    stream(&mut b, "G00 Z150\n", |_| false);
    settle(&mut b);
    // The Z axis slips 25 mm toward +: the machine stands at 175 believing 150; a
    // rapid to 298 (inside the soft limit 300) runs into the switch at 301 at full
    // speed.
    b.sim.slip(Axis::Z, 25_000_000);
    stream(&mut b, "G00 Z298\n", |_| false);
    assert!(run_until(&mut b, 5_000, |b| z_mm(b) > 301.0));
    let z0 = z_mm(&b);
    let out = settle(&mut b);
    let v = 8_000.0 / 60.0;
    let d = z_mm(&b) - z0;
    let brake = v * v / (2.0 * ACCEL);
    eprintln!("hard limit: {d:.3} mm past the switch at {v:.1} mm/s (v²/2a = {brake:.3})");
    assert!(d > 0.8 * brake && d < brake + v * 0.003, "stop distance {d:.3} mm past the switch, braking {brake:.3}");
    assert!(out.contains("Hard limit Z") && out.contains("ALARM:1"), "{out}");
    assert_eq!(b.ctl.alarm(), Some(1));
    assert_eq!(b.sim.core.state(), State::Idle);
    assert!(status(&mut b).starts_with("<Alarm|"));
    // Reset: the switch is still pressed but only its edge alarms; move away.
    b.receive(&[0x18]);
    b.run_for(20 * MS);
    let believed = b.sim.core.position()[Axis::Z] as f64 / 1e6;
    let log = stream(&mut b, "G00 Z250\nM30\n", |_| false);
    settle(&mut b);
    assert!(!log.contains("ALARM"), "{log}");
    assert!((z_mm(&b) - 275.0).abs() < 0.01, "at {} (believed {believed} before)", z_mm(&b));
    assert_eq!(b.ctl.alarm(), None);
}

#[test]
fn encoder_lost_mid_thread_alarms_4503_and_the_axes_stop_with_the_count() {
    let mut b = board();
    mid_thread(&mut b);
    let t0 = b.now();
    b.sim.faults.encoder_lost = Some(Span::from(t0));
    let z0 = z_mm(&b);
    let out = settle(&mut b);
    let d = z0 - z_mm(&b);
    eprintln!("encoder lost mid-thread: {d:.4} mm moved after the loss");
    assert!(d.abs() < 0.05, "moved {d:.3} mm without counts");
    assert!(out.contains("ALARM 4503") && out.contains("ALARM:20"), "{out}");
    assert_eq!(b.ctl.alarm(), Some(20));
    assert_eq!(b.sim.core.spindle_output().1, 0, "spindle commanded to stop");
    assert!(run_until(&mut b, 2_000, |b| b.sim.spindle.rpm().abs() < 1.0), "spindle runs down");
    let _ = t0;
    restart_works(&mut b, 30.0);
}

#[test]
fn spindle_stall_mid_thread_alarms_4503_after_the_axes_ran_down_with_it() {
    let mut b = board();
    mid_thread(&mut b);
    b.sim.faults.spindle_load = Some((b.now(), 0.0));
    let z0 = z_mm(&b);
    let count0 = b.sim.spindle.encoder_degrees();
    let out = settle(&mut b);
    let revs = (b.sim.spindle.encoder_degrees() - count0) / 360.0;
    let d = z0 - z_mm(&b);
    eprintln!("spindle stall mid-thread: {d:.3} mm over {revs:.3} rev after the stall");
    assert!((d - 2.0 * revs).abs() < 0.01, "{d:.3} mm over {revs:.3} rev: the lead holds to the stop");
    assert!(out.contains("ALARM 4503") && out.contains("ALARM:20"), "{out}");
    restart_works(&mut b, 30.0);
}

/// A G99 cut from Z10 toward Z-60 at 0.2 mm/rev, 600 rpm (2 mm/s).
const G99_CUT: &str = "G99 G97 S600 M03\nG00 X40 Z10\nG01 Z-60 F0.2\nG00 X60\nM30\n";

#[test]
fn spindle_stall_under_g99_alarms_4503_and_the_feed_stops_with_it() {
    let mut b = board();
    stream(&mut b, G99_CUT, |_| false);
    assert!(run_until(&mut b, 20_000, |b| z_mm(b) < 5.0));
    b.sim.faults.spindle_load = Some((b.now(), 0.0));
    let z0 = z_mm(&b);
    let deg0 = b.sim.spindle.encoder_degrees();
    let out = settle(&mut b);
    let revs = (b.sim.spindle.encoder_degrees() - deg0) / 360.0;
    let d = z0 - z_mm(&b);
    eprintln!("spindle stall under G99: {d:.3} mm over {revs:.3} rev after the stall");
    assert!(d > 0.0 && d < 0.2 * revs + 0.05, "{d:.3} mm over {revs:.3} rev");
    assert!(out.contains("ALARM 4503") && out.contains("ALARM:20"), "{out}");
    assert_eq!(b.ctl.alarm(), Some(20));
    restart_works(&mut b, 30.0);
}

#[test]
fn spindle_slowed_under_g99_keeps_the_feed_per_revolution() {
    let mut b = board();
    stream(&mut b, G99_CUT, |_| false);
    assert!(run_until(&mut b, 20_000, |b| z_mm(b) < 5.0));
    b.sim.faults.spindle_load = Some((b.now(), 0.5));
    b.run_for(1_000 * MS); // the drive settles at 300 rpm
    let (z0, deg0, t0) = (z_mm(&b), b.sim.spindle.encoder_degrees(), b.now());
    b.run_for(2_000 * MS);
    let revs = (b.sim.spindle.encoder_degrees() - deg0) / 360.0;
    let rpm = revs * 60.0 / ((b.now() - t0) as f64 / 1e9);
    let per_rev = (z0 - z_mm(&b)) / revs;
    assert!((rpm - 300.0).abs() < 5.0, "{rpm} rpm");
    assert!((per_rev - 0.2).abs() < 0.002, "{per_rev} mm/rev");
    assert_eq!(core_alarm(&b), None);
}

#[test]
fn a_thread_too_fast_for_the_drives_alarms_4501_before_any_step() {
    let mut cfg = MachineConfig::default();
    cfg.axes[Axis::Z.index()].drive.max_step_hz = 30_000; // 93.75 mm/s on Z
    let mut b = board_on(cfg);
    stream(&mut b, "G97 S600 M03\nG00 X40 Z10\n", |_| false);
    settle(&mut b);
    let pulses = b.sim.pulses();
    // Lead 10 at 600 rpm: 100 mm/s.
    let log = stream(&mut b, "G32 Z-60 F10\nM30\n", |_| false);
    let out = log + &settle(&mut b);
    assert!(out.contains("ALARM 4501") && out.contains("ALARM:20"), "{out}");
    assert_eq!(b.sim.pulses(), pulses, "no step of the thread");
    assert_eq!(b.sim.violations(), 0);
    restart_works(&mut b, 30.0);
}

#[test]
fn link_lost_mid_stream_stops_at_the_end_of_the_last_block_received() {
    let mut b = board();
    // 1000 blocks of 0.2 mm: more than the stream window holds.
    let ends: Vec<i64> = (1..=1_000).map(|k| 250_000 - 200 * k).collect(); // µm
    let prog: String =
        ends.iter().map(|z| format!("G98 G01 Z{:.1} F2000\n", *z as f64 / 1e3)).chain(["M30\n".to_string()]).collect();
    let log = stream(&mut b, &prog, |b| z_mm(b) < 225.0);
    assert!(!log.contains("error"), "{log}");
    b.sim.faults.link_down = Some(b.now());
    let _ = stream(&mut b, "G00 Z0\n", |_| true); // lost on the wire
    let out = settle(&mut b);
    let z_um = b.position()[Axis::Z] / 1_000;
    assert!(ends.contains(&z_um) && z_um > 100_000, "stopped at {z_um} µm: not the end of a block");
    assert!(z_um < 225_000);
    assert_eq!(core_alarm(&b), None, "{out}");
    assert_eq!(b.sim.core.state(), State::Idle);
    restart_works(&mut b, 100.0);
}

#[test]
fn a_short_encoder_glitch_mid_thread_is_ridden_through() {
    let mut b = board();
    mid_thread(&mut b);
    let t = b.now();
    // 50 ms without counts (under the 100 ms watch): the axes wait, then catch up
    // with the count at their step rate.
    b.sim.faults.encoder_lost = Some(Span { from: t, until: t + 50 * MS });
    let out = settle(&mut b);
    assert!(out.contains("Pgm End") && !out.contains("ALARM"), "{out}");
    assert_eq!(b.sim.violations(), 0);
    assert!((z_mm(&b) - 10.0).abs() < 1e-3, "the program ran to its end");
}

#[test]
fn spindle_runaway_mid_thread_alarms_4501_and_brakes_along_the_thread() {
    let mut cfg = MachineConfig::default();
    cfg.axes[Axis::Z.index()].drive.max_step_hz = 30_000; // 5625 mm/min on Z
    let mut b = board_on(cfg);
    // Lead 7 at 600 rpm: 4200 mm/min, inside the 5000 mm/min feed limit with the
    // 10 % margin; the drive then runs away to 900 rpm (6300 mm/min).
    stream(&mut b, "G97 S600 M03\nG00 X40 Z10\nG32 Z-100 F7\nG00 X60\nZ10\nM30\n", |_| false);
    assert!(run_until(&mut b, 20_000, |b| b.sim.core.state() == State::Locked && z_mm(b) < -20.0));
    let x0 = b.position()[Axis::X];
    let (z0, deg0) = (z_mm(&b), b.sim.spindle.encoder_degrees());
    b.sim.faults.spindle_load = Some((b.now(), 1.5));
    assert!(run_until(&mut b, 2_000, |b| b.ctl.alarm().is_some()));
    let lead = (z0 - z_mm(&b)) / ((b.sim.spindle.encoder_degrees() - deg0) / 360.0);
    let z1 = z_mm(&b);
    let out = settle(&mut b);
    let v = 5_000.0 / 60.0;
    let d = z1 - z_mm(&b);
    eprintln!("spindle runaway mid-thread: lead {lead:.4} mm/rev up to the alarm, {d:.3} mm to stop");
    assert!((lead - 7.0).abs() < 0.01, "the lead held up to the alarm: {lead}");
    assert!(d > 0.0 && d < v * v / (2.0 * ACCEL) + v * 0.003, "stop distance {d:.3} mm");
    assert!(out.contains("ALARM 4501") && out.contains("ALARM:20"), "{out}");
    assert_eq!(b.position()[Axis::X], x0, "the tool stays in the thread's line");
    assert_eq!(b.sim.violations(), 0, "the drive's step rate was never exceeded");
    restart_works(&mut b, 30.0);
}

//! The motion core on the simulated machine: spindle speed and feed per revolution,
//! the order of commands and motion, feed hold, overrides, single block, dwell,
//! starvation, reset and the queue's back-pressure.

use interp_core::axis::{Axis, Pos};
use interp_core::canon::css_rpm;
use interp_core::canon::{Action, Canon, CanonSink, Endpoint, Feed, FeedMode, Move, SpindleDir, SpindleSpeed};
use interp_core::{MachineConfig, Panel};
use motion_core::fixed::STEP_ONE;
use motion_core::motion::{EventKind, MotionCore, QUEUE, State};
use sim::{Report, Sim, SimOptions, SpindleModel, TickSample};

fn sim_with(model: SpindleModel) -> Sim {
    Sim::new(
        MachineConfig::default(),
        SimOptions { samples: true, trace: true, spindle: model, ..SimOptions::default() },
    )
    .unwrap()
}

fn sim() -> Sim {
    sim_with(SpindleModel::default())
}

fn assert_clean(r: &Report) {
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    assert!(r.ended, "did not end: {r:?}");
    assert_eq!(r.timing_violations, 0, "driver timing violated");
}

/// Samples of the periods that ran line `line`.
fn on_line(samples: &[TickSample], line: u32) -> Vec<TickSample> {
    samples.iter().filter(|s| s.line == line && s.state == State::Moving).copied().collect()
}

#[test]
fn feed_per_revolution_follows_the_measured_spindle_speed() {
    // ±5 % ripple at 2 Hz and noise: the feed must follow the spindle, not the command.
    let model = SpindleModel { ripple: 0.05, ripple_hz: 2.0, noise: 0.01, seed: 3, ..SpindleModel::default() };
    let mut s = sim_with(model);
    let r = s.run_program("G0 X40 Z1\nM3 S600\nG99 G1 Z-60 F0.25\nG0 X60\nM30\n");
    assert_clean(&r);
    // Over each 100 ms window in the middle of the cut: feed = F × revolutions.
    let rows: Vec<_> = s.trace.iter().filter(|t| t.z_mm < -5.0 && t.z_mm > -55.0).collect();
    let (first, last) = (rows[0], rows[rows.len() - 1]);
    let mut worst = 0.0f64;
    let mut t0 = first;
    for row in &rows {
        if row.t - t0.t >= 0.1 {
            let feed = (t0.z_mm - row.z_mm) / ((row.spindle_deg - t0.spindle_deg) / 360.0);
            worst = worst.max((feed / 0.25 - 1.0).abs());
            t0 = row;
        }
    }
    assert!(worst < 0.01, "feed per revolution off by {:.2} %", worst * 100.0);
    let revs = (last.spindle_deg - first.spindle_deg) / 360.0;
    let feed = (first.z_mm - last.z_mm) / revs;
    assert!((feed - 0.25).abs() < 0.0025, "{feed} mm/rev over the cut");
}

#[test]
fn constant_surface_speed_follows_x_with_the_clamp() {
    // Facing from X100 to X0 at 200 m/min, clamp 2500 rev/min (G50 S).
    let mut s = sim_with(SpindleModel { accel_rpm_s: 5_000.0, ..SpindleModel::default() });
    let text = "G50 S2500\nG0 X100 Z0\nM3 G96 S200\nG98 G1 X0 F150\nG0 Z5\nM30\n";
    let r = s.run_program(text);
    assert_clean(&r);
    let cut = on_line(&s.samples, 4);
    assert!(cut.len() > 1000);
    let mut checked = 0;
    for w in cut.windows(5) {
        // The speed commanded now was computed from X at most 4 periods ago.
        let x = |t: &TickSample| (t.commanded[0] as f64 / STEP_ONE as f64 * 2_500.0) as i64 - t.offset[Axis::X];
        let rpm = w[4].spindle_cmd;
        let lo = css_rpm(200_000, x(&w[4])).min(2_500);
        let hi = css_rpm(200_000, x(&w[0])).min(2_500);
        assert!(rpm >= lo.min(hi) && rpm <= lo.max(hi), "rpm {rpm} not in {lo}..{hi}");
        checked += 1;
    }
    assert!(checked > 1000);
    // 200 m/min at X100 is 637 rev/min; at X25.46 the clamp takes over.
    assert_eq!(cut[0].spindle_cmd, css_rpm(200_000, 50_000_000));
    assert_eq!(cut.last().unwrap().spindle_cmd, 2_500);
}

#[test]
fn the_spindle_runs_before_the_cut_and_stops_after_it() {
    let mut s = sim();
    let r = s.run_program("G0 X50 Z2\nM3 S800\nG1 Z-10 F300\nM5\nG0 X60\nM30\n");
    assert_clean(&r);
    let start = s.events.iter().find(|e| matches!(e.kind, EventKind::Spindle { dir: SpindleDir::Cw, .. })).unwrap();
    let stop = s.events.iter().find(|e| matches!(e.kind, EventKind::Spindle { dir: SpindleDir::Stop, .. })).unwrap();
    let cut: Vec<_> = s.trace.iter().filter(|t| t.z_mm < 2.0 && t.x_mm == 50.0).collect();
    let (first, last) = (cut[0], cut[cut.len() - 1]);
    assert!(start.t as f64 / 1e9 < first.t, "M03 before the cut");
    assert!(stop.t as f64 / 1e9 >= last.t, "M05 after the cut's last step");
    // The cut began at speed (within 10 %): the encoder had turned by then.
    let sample = s.samples.iter().find(|t| t.t as f64 / 1e9 >= first.t).unwrap();
    assert!(sample.spindle_measured > 720.0, "{}", sample.spindle_measured);
}

#[test]
fn feed_hold_brakes_on_the_path_and_resumes_from_there() {
    let text = "G0 X40 Z0\nG1 X80 Z-40 F600\nG0 X100\nM30\n";
    let mut plain = sim();
    let r0 = plain.run_program(text);
    let mut s = sim();
    let r = s.run_program_with(text, |sim| {
        let t = sim.time_s();
        if (2.0..2.001).contains(&t) {
            sim.core.feed_hold();
        }
        if (3.5..3.501).contains(&t) {
            sim.core.cycle_start();
        }
    });
    assert_clean(&r);
    assert_eq!(r.end, r0.end);
    assert!(r.max_dev_nm <= 3_125.0 + 1_000.0, "left the path by {} nm", r.max_dev_nm);
    // Held: the commanded position stood still for a while, on the line.
    let held: Vec<_> = s.samples.iter().filter(|t| t.state == State::Held).collect();
    assert!(held.len() > 1000, "held for {} periods", held.len());
    assert!(held.windows(2).all(|w| w[0].commanded == w[1].commanded));
    // It took longer by the hold (1.5 s) and the extra braking and acceleration.
    assert!(r.cycle_time_s > r0.cycle_time_s + 1.4, "{} vs {}", r.cycle_time_s, r0.cycle_time_s);
}

#[test]
fn feed_override_scales_cutting_feed_and_rapid_override_rapids() {
    let text = "G0 X40 Z0\nG1 Z-50 F300\nM30\n";
    let time = |feed: u16, rapid: u16| {
        let mut s = sim();
        s.core.set_feed_override(feed);
        s.core.set_rapid_override(rapid);
        let r = s.run_program(text);
        assert_clean(&r);
        let cut: Vec<_> = s.trace.iter().filter(|t| t.z_mm < -5.0 && t.z_mm > -45.0).collect();
        (cut[cut.len() - 1].t - cut[0].t, r.cycle_time_s)
    };
    let (normal, _) = time(100, 100);
    let (half, _) = time(50, 100);
    let (fast, _) = time(200, 100);
    assert!((normal - 8.0).abs() < 0.05, "40 mm at 300 mm/min: {normal}");
    assert!((half / normal - 2.0).abs() < 0.02);
    assert!((fast / normal - 0.5).abs() < 0.02);
    let (_, total) = time(100, 100);
    let (_, slow_rapids) = time(100, 25);
    assert!(slow_rapids > total + 0.3, "{slow_rapids} vs {total}");
}

#[test]
fn single_block_stops_after_every_block() {
    let mut s = sim();
    s.core.set_single_block(true);
    let mut starts = 0;
    let r = s.run_program_with("G0 X40 Z0\nG1 Z-5 F600\nZ-10\nZ-15\nM30\n", |sim| {
        if sim.core.state() == State::Stopped {
            starts += 1;
            sim.core.cycle_start();
        }
    });
    assert_clean(&r);
    assert_eq!(starts, 4, "a stop after each of the four moves");
}

#[test]
fn dwell_waits_between_moves() {
    let mut s = sim();
    let r = s.run_program("G0 X40 Z0\nG1 Z-2 F600\nG04 P750\nG1 Z-4\nM30\n");
    assert_clean(&r);
    let z: Vec<_> = s.trace.iter().filter(|t| t.axis == 2 && t.z_mm < 0.0).collect();
    let gap = z.windows(2).map(|w| w[1].t - w[0].t).fold(0.0, f64::max);
    assert!((0.75..0.76).contains(&gap), "gap {gap}");
}

fn linear(z_mm: i64, feed_mm_min: i64, line: u32) -> Canon {
    let to = Pos::xz(20_000_000, z_mm * 1_000_000);
    let m = Move {
        to: Endpoint { machine: to, work: to },
        feed: Feed { mode: FeedMode::PerMin, value: feed_mm_min * 1_000_000 },
        spindle: SpindleSpeed { rpm: None, css: None, max_rpm: 3_000 },
        exact_stop: false,
        independent: false,
    };
    Canon { line, action: Action::Linear(m) }
}

#[test]
fn an_empty_queue_while_streaming_is_counted_not_fatal() {
    let mut s = sim();
    // No M02/M30 came: the queue ran empty while streaming, the axes at rest.
    let r = s.run_actions(&[linear(0, 3_000, 1), linear(-5, 600, 2)]);
    assert_eq!(r.starvations, 1);
    assert_eq!(r.end, Pos::xz(20_000_000, -5_000_000));
    // The next block arrives late: it runs from there, and counts again.
    let r = s.run_actions(&[linear(-10, 600, 3)]);
    assert_eq!(r.starvations, 2);
    assert_eq!(r.end, Pos::xz(20_000_000, -10_000_000));
    assert!(s.events.iter().any(|e| e.kind == EventKind::Starved));
}

#[test]
fn a_full_queue_pushes_back() {
    let mut core: MotionCore<QUEUE> = MotionCore::new(&MachineConfig::default(), Pos::ZERO).unwrap();
    for k in 0..QUEUE as i64 {
        assert_eq!(core.push(linear(-k - 1, 600, k as u32)), Ok(()));
    }
    assert!(core.push(linear(-100, 600, 99)).is_err());
    core.tick(0, Default::default());
    assert_eq!(core.push(linear(-100, 600, 99)), Ok(()), "the running block left a slot");
}

#[test]
fn reset_brakes_and_drops_the_queue() {
    let mut s = sim();
    let r = s.run_program_with("G0 X40 Z0\nM3 S500\nG1 Z-50 F900\nG1 X60\nM30\n", |sim| {
        if (2.0..2.001).contains(&sim.time_s()) {
            sim.core.reset();
        }
    });
    assert!(!r.ended);
    assert_eq!(s.core.state(), State::Idle);
    assert_eq!(s.core.queued(), 0);
    assert_eq!(s.core.spindle_output(), (SpindleDir::Stop, 0));
    // Stopped on the cut's line, short of its end, after braking (no jump).
    assert_eq!(r.end[Axis::X], 20_000_000);
    assert!(r.end[Axis::Z] < 0 && r.end[Axis::Z] > -50_000_000);
    assert!(r.max_dev_nm <= 3_125.0 + 1_000.0);
    assert_eq!(r.timing_violations, 0);
}

#[test]
fn feed_per_revolution_waits_for_the_spindle() {
    let mut s = sim_with(SpindleModel { accel_rpm_s: 500.0, ..SpindleModel::default() });
    let r = s.run_program("G0 X40 Z0\nM3 S1000\nG99 G1 Z-2 F0.1\nM30\n");
    assert_clean(&r);
    let first = s.trace.iter().find(|t| t.axis == 2 && t.z_mm < 0.0).unwrap();
    // 1000 rev/min at 500 rev/min/s: 1.8 s to within 10 %.
    assert!(first.t > 1.8, "cut started at {}", first.t);
}

#[test]
fn spindle_that_never_gets_to_speed_is_alarm_4504() {
    let mut cfg = MachineConfig::default();
    cfg.motion.at_speed_timeout_ms = 500;
    let mut s = Sim::new(
        cfg,
        SimOptions { spindle: SpindleModel { accel_rpm_s: 100.0, ..SpindleModel::default() }, ..SimOptions::default() },
    )
    .unwrap();
    let r = s.run_program("G0 X40 Z0\nM3 S2000\nG1 Z-2 F100\nM30\n");
    assert_eq!(r.alarms.iter().map(|a| (a.line, a.code())).collect::<Vec<_>>(), vec![(3, 4504)]);
    assert_eq!(r.end, Pos::xz(20_000_000, 0), "no motion from the cut");
    let _ = Panel::default();
}

#[test]
fn rebuilding_in_place_is_building_anew() {
    // After a program ran (queue used, counters, overrides, events), rebuilding for
    // another machine leaves exactly what a new core at that position would be.
    let mut s = sim();
    let r = s.run_program("G0 X40 Z0\nM3 S500\nG1 Z-5 F900\nM5\nM30\n");
    assert_clean(&r);
    s.core.set_feed_override(150);
    let mut cfg = MachineConfig::default();
    cfg.spindle.max_rpm = 2500;
    cfg.motion.speed_window_ticks = 7;
    let fresh: MotionCore<QUEUE> = MotionCore::new(&cfg, s.core.position()).unwrap();
    s.core.rebuild(&cfg).unwrap();
    assert_eq!(format!("{:?}", s.core), format!("{fresh:?}"));
    // A machine the core refuses leaves it as it was.
    let before = format!("{:?}", s.core);
    let mut bad = cfg.clone();
    bad.axes[Axis::Z.index()].drive.steps = 0;
    assert!(s.core.rebuild(&bad).is_err());
    assert_eq!(format!("{:?}", s.core), before);
}

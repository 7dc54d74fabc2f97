//! Dense programs at full feed (issue 22), on the host: CAM-style chains of G01
//! blocks of 0.01, 0.02 and 0.05 mm along a smooth curve (X = 80 + 4·sin(z/10 mm)
//! on the diameter, radius of curvature at least 50 mm, IS-B text) at F6000, each
//! 40 mm long, on the lathe with 500 (the default), 2,000 and 5,000 mm/s² and a
//! 10 m/min cutting feed.
//!
//! For each: the simulated machine (interpreter, planner, interpolator, step
//! generation, the stepped axes measured against the programmed polyline) runs the
//! program; printed are the feed achieved over the middle 20 mm of Z against the
//! programmed feed and against what the 64-block queue allows (a period at `v`
//! must still brake to rest by the queue's end, `v² + a·v ≤ 2a·D`, `D` = 64
//! blocks), the blocks per second of machine time, the largest deviation from the
//! path, and the host's own speed through the whole chain (parse → plan → steps,
//! blocks per second of host time, without the simulator's bookkeeping).
//!
//! `cargo run --release -p host-tests --example dense_bench`

use std::time::Instant;

use host_tests::fast_lathe;
use interp_core::axis::{AXIS_COUNT, Axis, Pos};
use interp_core::{Interpreter, MachineConfig, Panel, Progress, SingleProgram};
use motion_core::motion::{Feedback, MotionCore, QUEUE, State};
use sim::{Sim, SimOptions};

const MM: i64 = 1_000_000;
const FEED: f64 = 6_000.0;

/// X (radius, mm) of the curve at Z (mm).
fn x_at(z: f64) -> f64 {
    40.0 + 2.0 * (z / 10.0).sin()
}

fn program(seg: f64) -> String {
    let mut s = String::from("G98 G00 X80. Z0.\nG01 F6000\n");
    for k in 1..=(40.0 / seg).round() as usize {
        let z = -(k as f64) * seg;
        s.push_str(&format!("X{:.3} Z{:.3}\n", 2.0 * x_at(z), z));
    }
    s.push_str("G00 X100.\nM30\n");
    s
}

/// Path length (mm) of the curve between Z −10 and −30 mm.
fn middle_path() -> f64 {
    (0..20_000)
        .map(|k| {
            let (z0, z1) = (-10.0 - k as f64 * 0.001, -10.0 - (k + 1) as f64 * 0.001);
            (x_at(z1) - x_at(z0)).hypot(0.001)
        })
        .sum()
}

/// The speed (mm/min) at which a period still brakes to rest within the 64
/// queued blocks, on the profile's grid of whole accelerations.
fn queue_limit(accel: i64, seg: f64) -> f64 {
    let a = accel as f64; // mm/s² is nm per (1 ms period)²
    let d = 64.0 * seg * 1e6;
    let v = (2.0 * a * d + a * a / 4.0).sqrt() - a / 2.0;
    (v / a).floor() * a * 0.06
}

/// The whole chain on the host without the simulator: interpreter → motion core
/// → every step event; blocks per second of host time.
fn host_rate(cfg: &MachineConfig, text: &str) -> f64 {
    let store = SingleProgram(text.as_bytes());
    let mut best = 0.0f64;
    for _ in 0..3 {
        let mut interp = Interpreter::new(cfg.clone());
        let mut core: Box<MotionCore<QUEUE>> = Box::new(MotionCore::new(cfg, Pos::xz(40 * MM, 0)).unwrap());
        let (mut t, mut ended) = (0u64, false);
        let start = Instant::now();
        while !(ended && core.is_idle()) {
            for _ in 0..4 * QUEUE {
                match interp.step(&store, &Panel::default(), &mut *core) {
                    Ok(Progress::Ended) => {
                        ended = true;
                        break;
                    }
                    Ok(Progress::Blocked) => break,
                    Ok(_) => {}
                    Err(a) => panic!("{a}"),
                }
            }
            core.tick(t, Feedback::default());
            t += 1_000_000;
            for axis in 0..AXIS_COUNT {
                while core.next_step(axis, t).is_some() {}
            }
        }
        best = best.max(core.stats().blocks as f64 / start.elapsed().as_secs_f64());
    }
    best
}

fn main() {
    println!(
        "{:>6} {:>7} {:>9} {:>9} {:>9} {:>10} {:>10} {:>8} {:>12}",
        "accel", "segment", "achieved", "queue", "old cap", "blocks/s", "deviation", "overruns", "host"
    );
    println!(
        "{:>6} {:>7} {:>9} {:>9} {:>9} {:>10} {:>10} {:>8} {:>12}",
        "mm/s²", "mm", "mm/min", "limit", "mm/min", "(machine)", "µm (steps)", "", "blocks/s"
    );
    let path = middle_path();
    for accel in [500, 2_000, 5_000] {
        for seg in [0.01, 0.02, 0.05] {
            let cfg = fast_lathe(accel);
            let text = program(seg);
            let opts = SimOptions { samples: true, start: Pos::xz(40 * MM, 0), ..SimOptions::default() };
            let mut sim = Sim::new(cfg.clone(), opts).unwrap();
            let r = sim.run_program(&text);
            assert!(r.alarms.is_empty() && r.ended, "{r:?}");
            let z = |s: &sim::TickSample| s.commanded[Axis::Z.index()] as f64 / 65_536.0 / 320.0;
            let moving = |s: &&sim::TickSample| s.state == State::Moving;
            let a = sim.samples.iter().filter(moving).find(|s| z(s) <= -10.0).unwrap();
            let b = sim.samples.iter().filter(moving).find(|s| z(s) <= -30.0).unwrap();
            let minutes = (b.t - a.t) as f64 / 60e9;
            let feed = path / minutes;
            let blocks_per_s = 20.0 / seg / (minutes * 60.0);
            println!(
                "{:>6} {:>7} {:>9.0} {:>9.0} {:>9.0} {:>10.0} {:>5.2} ({:.2}) {:>8} {:>12.0}",
                accel,
                seg,
                feed,
                queue_limit(accel, seg).min(FEED),
                seg * 60_000.0,
                blocks_per_s,
                r.max_dev_nm / 1000.0,
                r.max_dev_steps,
                sim.core.stats().overruns,
                host_rate(&cfg, &text)
            );
        }
    }
    println!("programmed F{FEED}; old cap: one block per 1 ms period (before issue 22)");
}

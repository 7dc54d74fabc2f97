//! Host throughput of the motion core (run with --release):
//! - blocks per second the planner prepares and looks ahead over;
//! - blocks and step events per second of the whole core (planner, interpolator,
//!   step generation) on a program of short G01 chords, without the simulator;
//! - step events per second of a step generator alone;
//! - how fast the simulated machine runs an example program.
//!
//! `cargo run --release -p host-tests --example motion_bench`

use std::hint::black_box;
use std::time::Instant;

use interp_core::MachineConfig;
use interp_core::axis::{AXIS_COUNT, Pos};
use interp_core::canon::{Action, Canon, CanonSink, Endpoint, Feed, FeedMode, Move, SpindleSpeed};
use motion_core::fixed::STEP_ONE;
use motion_core::motion::{Feedback, MotionCore, QUEUE};
use motion_core::planner::{Item, MotionParams, Planner};
use motion_core::stepgen::AxisStepGen;
use sim::{Sim, SimOptions};

const MM: i64 = 1_000_000;

/// Chords of about 0.2 mm around a circle of radius 30 mm (942 of them), G01 at
/// `feed` mm/min, computed once so the loops below time the motion core only.
fn circle(feed: i64) -> Vec<Canon> {
    (0..942).map(|k| chord(k, feed)).collect()
}

fn chord(k: i64, feed: i64) -> Canon {
    let a = k as f64 * std::f64::consts::TAU / 942.0;
    let p = Pos::xz((40e6 + 30e6 * a.cos()) as i64, (-30e6 * a.sin()) as i64);
    let m = Move {
        to: Endpoint { machine: p, work: p },
        feed: Feed { mode: FeedMode::PerMin, value: feed * MM },
        spindle: SpindleSpeed { rpm: Some(1_000), css: None, max_rpm: 3_000 },
        exact_stop: false,
        independent: false,
    };
    Canon { line: k as u32, action: Action::Linear(m) }
}

fn rate(n: f64, t: Instant) -> String {
    let r = n / t.elapsed().as_secs_f64();
    if r > 1e6 { format!("{:.2} million", r / 1e6) } else { format!("{:.0}", r) }
}

fn main() {
    let cfg = MachineConfig::default();
    let p = MotionParams::new(&cfg).unwrap();

    // Planner alone: queue at half depth, one push and one pop per block.
    let n = 2_000_000;
    let blocks = circle(1_000);
    let mut planner: Planner<QUEUE> = Planner::new(Pos::xz(70 * MM, 0));
    let t = Instant::now();
    for k in 1..=n {
        planner.push(&blocks[k % blocks.len()], &p).unwrap();
        if planner.len() > QUEUE / 2 {
            black_box(planner.pop());
        }
    }
    println!("planner: {} blocks/s (prepare + junction + look-ahead)", rate(n as f64, t));

    // The whole core: blocks at 5000 mm/min (0.2 mm chords, 2.4 ms each), every
    // period's step events issued.
    let n = 500_000;
    let blocks = circle(5_000);
    let mut core: MotionCore<QUEUE> = MotionCore::new(&cfg, Pos::xz(70 * MM, 0)).unwrap();
    let (mut now, mut steps, mut k) = (0u64, 0u64, 1usize);
    let t = Instant::now();
    while k <= n || !core.is_idle() {
        while k <= n && core.push(blocks[k % blocks.len()]).is_ok() {
            k += 1;
        }
        core.tick(now, Feedback::default());
        now += u64::from(p.tick_ns);
        for axis in 0..AXIS_COUNT {
            while core.next_step(axis, now).is_some() {
                steps += 1;
            }
        }
    }
    let secs = t.elapsed().as_secs_f64();
    println!(
        "motion core: {:.2} million blocks/s, {:.1} million step events/s ({} blocks, {} steps, {:.0} s of motion in {:.2} s)",
        n as f64 / secs / 1e6,
        steps as f64 / secs / 1e6,
        n,
        steps,
        now as f64 / 1e9,
        secs
    );

    // A step generator alone: 40 steps per period.
    let mut g = AxisStepGen::new(p.timing[0], 0);
    let periods = 2_000_000u64;
    let t = Instant::now();
    let mut events = 0u64;
    for i in 0..periods {
        g.ramp(i * 1_000_000, 1_000_000, (i as i64 + 1) * 40 * STEP_ONE);
        while g.next_event((i + 1) * 1_000_000).is_some() {
            events += 1;
        }
    }
    println!("step generator: {} step events/s", rate(events as f64, t));

    // The simulated machine on an example program.
    let text = include_str!("../../examples/shaft.nc");
    let mut sim = Sim::new(cfg.clone(), SimOptions { start: cfg.reference[0], ..SimOptions::default() }).unwrap();
    let t = Instant::now();
    let r = sim.run_program(text);
    println!(
        "simulator: examples/shaft.nc, {:.1} s of machining in {:.2} s ({} step events, {})",
        r.cycle_time_s,
        t.elapsed().as_secs_f64(),
        r.steps,
        rate(r.steps as f64, t) + " step events/s"
    );

    println!(
        "RAM: MotionCore<{QUEUE}> {} bytes, of which the queue {} bytes ({} per entry)",
        std::mem::size_of::<MotionCore<QUEUE>>(),
        std::mem::size_of::<Planner<QUEUE>>(),
        std::mem::size_of::<Item>()
    );
}

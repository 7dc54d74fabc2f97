//! Instruction counts of the motion core on the Cortex-M4F: planning a short G01
//! block and a short G02 block (preparation and look-ahead) and starting them in
//! the interpolator, an
//! interpolation period on a line and on an arc, a step event, an encoder count of
//! a locked thread (constant lead and G34 variable lead), and the RAM the motion
//! core takes. Run through
//! `bench.sh bench_motion`.
#![no_std]
#![no_main]

use core::hint::black_box;

use cortex_m_rt::entry;
use cortex_m_semihosting::hprintln;
use interp_core::axis::{AXIS_COUNT, Pos};
use interp_core::canon::{Action, ArcMove, Canon, CanonSink as _, Endpoint, Feed, FeedMode, Move, Plane, SpindleSpeed};
use interp_core::config::MachineConfig;
use m4_tests::{exit, measure};
use motion_core::fixed::STEP_ONE;
use motion_core::interpolator::Segment;
use motion_core::motion::{Feedback, MotionCore, QUEUE};
use motion_core::planner::{Block, Item, MotionParams, Planner};
use motion_core::stepgen::{AxisStepGen, StepEvent};
use motion_core::sync::{Gear, Gearing, Leg, Phase, Ratio};

const MM: i64 = 1_000_000;

/// `BENCH_ONLY=g01` or `g02` (at build time) measures only the pushes of one short
/// G01 or G02 block (for a profile of planning it: `profile.sh bench_motion`).
const ONLY: Option<&str> = option_env!("BENCH_ONLY");

fn at(x: i64, z: i64) -> Endpoint {
    let p = Pos::xz(x, z);
    Endpoint { machine: p, work: p }
}

fn feed() -> Feed {
    Feed { mode: FeedMode::PerMin, value: 1_000 * MM }
}

fn spindle() -> SpindleSpeed {
    SpindleSpeed { rpm: Some(1_000), css: None, max_rpm: 3_000 }
}

/// The k-th point of a circle of radius 30 mm in 0.2 mm chords (X radius, Z).
fn point(k: i64) -> (i64, i64) {
    let a = k as f64 * 0.2 / 30.0;
    ((40.0 + 30.0 * libm::cos(a)) as i64 * 1_000, (-30.0 * libm::sin(a) * 1e3) as i64 * 1_000)
}

/// A short G01 block: the next chord.
fn chord(k: i64) -> Canon {
    let (x, z) = point(k);
    let m = Move { to: at(x, z), feed: feed(), spindle: spindle(), exact_stop: false, independent: false };
    Canon { line: k as u32, action: Action::Linear(m) }
}

/// Queues one block (preparation, junction, backward pass).
fn push(input: (&mut Planner<QUEUE>, &Canon, &MotionParams)) -> bool {
    input.0.push(input.1, input.2).is_ok()
}

/// Starts a queued block in the interpolator.
fn start(input: (&Block, &[i64; AXIS_COUNT], &MotionParams)) -> Segment {
    Segment::new(input.0, input.1, input.2)
}

/// One interpolation period of the motion core.
fn tick(input: (&mut MotionCore<QUEUE>, u64)) {
    input.0.tick(input.1, Feedback::default());
}

/// The next step event of a step generator.
fn step_event(g: &mut AxisStepGen) -> Option<StepEvent> {
    g.next_event(u64::MAX)
}

/// A new interpolation period of a step generator (the time per step, once).
fn ramp(input: (&mut AxisStepGen, u64, i64)) {
    input.0.ramp(input.1, 1_000_000, input.2);
}

/// One encoder count of a locked thread.
fn count(input: (&mut Gear, i64)) -> bool {
    input.0.on_count(input.1)
}

/// A 0.01 mm block along Z at 5000 mm/min: too short to reach speed on its own.
fn tiny(k: i64) -> Canon {
    let to = at(40 * MM, -k * 10_000);
    let m = Move {
        to,
        feed: Feed { mode: FeedMode::PerMin, value: 5_000 * MM },
        spindle: spindle(),
        exact_stop: false,
        independent: false,
    };
    Canon { line: k as u32, action: Action::Linear(m) }
}

/// Fills a queue with `QUEUE - 1` tiny blocks from rest, then measures pushing one
/// more: every block's entry speed rises, the backward pass visits the whole queue.
fn plan_worst_case() {
    let p = MotionParams::new(&MachineConfig::default()).unwrap_or_else(|_| exit(false));
    let mut planner: Planner<QUEUE> = Planner::new(Pos::xz(40 * MM, 0));
    for k in 1..QUEUE as i64 {
        planner.push(&tiny(k), &p).unwrap_or_else(|_| exit(false));
    }
    hprintln!("bench worst case: push re-planning all {} queued blocks", QUEUE - 1);
    let c = tiny(QUEUE as i64);
    if !measure(push, (&mut planner, &c, &p)) {
        exit(false);
    }
}

/// Plans `n` chords from `first` keeping the queue at `depth`, measuring each push
/// and each start; prints the averages.
fn plan_blocks(label: &str, first: i64, n: i64, depth: usize) {
    let cfg = MachineConfig::default();
    let p = MotionParams::new(&cfg).unwrap_or_else(|_| exit(false));
    let start_pos = point(first - 1);
    let mut planner: Planner<QUEUE> = Planner::new(Pos::xz(start_pos.0, start_pos.1));
    let mut from = [0i64; AXIS_COUNT];
    let mut k = first;
    while planner.len() < depth {
        planner.push(&chord(k), &p).unwrap_or_else(|_| exit(false));
        k += 1;
    }
    hprintln!("bench {}: {} blocks, queue depth {}", label, n, depth);
    for _ in 0..n {
        let c = chord(k);
        k += 1;
        if !measure(push, (&mut planner, &c, &p)) {
            exit(false);
        }
        let Some(Item::Motion(b)) = planner.pop() else { exit(false) };
        let seg = if ONLY.is_some() { start((&b, &from, &p)) } else { measure(start, (&b, &from, &p)) };
        from = *black_box(&seg).end_steps();
    }
}

/// A short G02 block: the next 0.2 mm of the same circle as an arc around its centre.
fn arc_chord(k: i64) -> Canon {
    let (x, z) = point(k);
    let a = ArcMove {
        to: at(x, z),
        center: at(40 * MM, 0),
        plane: Plane::Zx,
        cw: true,
        full_circle: false,
        feed: feed(),
        spindle: spindle(),
        exact_stop: false,
    };
    Canon { line: k as u32, action: Action::Arc(a) }
}

/// Plans `n` short arcs after a queue of `depth` chords, measuring each push and
/// each start.
fn plan_arcs(n: i64, depth: usize) {
    let p = MotionParams::new(&MachineConfig::default()).unwrap_or_else(|_| exit(false));
    let start_pos = point(0);
    let mut planner: Planner<QUEUE> = Planner::new(Pos::xz(start_pos.0, start_pos.1));
    let mut from = [0i64; AXIS_COUNT];
    let mut k = 1;
    while planner.len() < depth {
        planner.push(&arc_chord(k), &p).unwrap_or_else(|_| exit(false));
        k += 1;
    }
    hprintln!("bench short G02 block (0.2 mm of R30) planned (push) and started: {} blocks, queue depth {}", n, depth);
    for _ in 0..n {
        let c = arc_chord(k);
        k += 1;
        if !measure(push, (&mut planner, &c, &p)) {
            exit(false);
        }
        let Some(Item::Motion(b)) = planner.pop() else { exit(false) };
        let seg = if ONLY.is_some() { start((&b, &from, &p)) } else { measure(start, (&b, &from, &p)) };
        from = *black_box(&seg).end_steps();
    }
}

#[entry]
fn main() -> ! {
    // Planning: a polyline at steady speed (the look-ahead pass stops after a block
    // or two), then a worst case: a queue of blocks too short to reach speed, where
    // each new block raises the entry speed of every block before it.
    match ONLY {
        Some("g01") => {
            plan_blocks("short G01 block planned (push)", 1, 1, 32);
            exit(true)
        }
        Some("g02") => {
            plan_arcs(1, 32);
            exit(true)
        }
        _ => {}
    }
    plan_blocks("short G01 block planned (push) and started", 1, 6, 32);
    plan_worst_case();
    plan_arcs(3, 32);

    // Interpolation periods: a core moving along a line and along an arc.
    let cfg = MachineConfig::default();
    let mut core: MotionCore<QUEUE> = MotionCore::new(&cfg, Pos::xz(40 * MM, 0)).unwrap_or_else(|_| exit(false));
    let line =
        Move { to: at(40 * MM, -100 * MM), feed: feed(), spindle: spindle(), exact_stop: true, independent: false };
    let _ = core.push(Canon { line: 1, action: Action::Linear(line) });
    let arc = ArcMove {
        to: at(40 * MM, -140 * MM),
        center: at(40 * MM, -120 * MM),
        plane: Plane::Zx,
        cw: true,
        full_circle: false,
        feed: feed(),
        spindle: spindle(),
        exact_stop: true,
    };
    let _ = core.push(Canon { line: 2, action: Action::Arc(arc) });
    let mut t = 0u64;
    for _ in 0..300 {
        core.tick(t, Feedback::default());
        drain(&mut core, t + 1_000_000);
        t += 1_000_000;
    }
    hprintln!("bench interpolation period, line at 1000 mm/min");
    for _ in 0..3 {
        measure(tick, (&mut core, t));
        drain(&mut core, t + 1_000_000);
        t += 1_000_000;
    }
    while core.line() == 1 {
        core.tick(t, Feedback::default());
        drain(&mut core, t + 1_000_000);
        t += 1_000_000;
    }
    for _ in 0..300 {
        core.tick(t, Feedback::default());
        drain(&mut core, t + 1_000_000);
        t += 1_000_000;
    }
    hprintln!("bench interpolation period, arc R20 at 1000 mm/min");
    for _ in 0..3 {
        measure(tick, (&mut core, t));
        drain(&mut core, t + 1_000_000);
        t += 1_000_000;
    }

    // Step events: 40 steps in one period (40 kHz), each measured.
    let timing = core.params().timing[0];
    let mut g = AxisStepGen::new(timing, 0);
    hprintln!("bench step generator: new period (time per step)");
    measure(ramp, (&mut g, 0, 40 * STEP_ONE + 1_234));
    hprintln!("bench step event (40 in the period)");
    for _ in 0..40 {
        if measure(step_event, &mut g).is_none() {
            exit(false);
        }
    }

    // A locked thread: 2 mm lead on Z at 320 steps/mm, 4096 counts (5/32 step/count).
    let leg = Leg { start: [0; AXIS_COUNT], end: [0, 0, -20_000, 0], long: 2 };
    let Ok(mut gear) = Gear::thread(leg, Ratio { n: 5, d: 32 }, 18_000, 1, 0) else { exit(false) };
    for c in 1..20_000 {
        gear.on_count(c);
    }
    hprintln!("bench encoder count, thread locked");
    for c in 20_000..20_008 {
        measure(count, (&mut gear, c));
    }
    // The ramp zone (the last v·R + 4 = 2,816 steps): its first count finds once the
    // count where the deceleration starts; the counts after it are plain locked ones.
    let mut c = 20_007;
    while gear.remaining() > 2_816 {
        c += 1;
        gear.on_count(c);
    }
    hprintln!("bench encoder count, thread entering the ramp zone (the deceleration's first count found)");
    c += 1;
    measure(count, (&mut gear, c));
    hprintln!("bench encoder count, thread in the ramp zone");
    for c in c + 1..c + 9 {
        measure(count, (&mut gear, c));
    }
    if gear.phase() != Phase::Locked {
        exit(false);
    }

    // A locked G34 thread: lead 2 mm growing by 0.1 mm per revolution, same axis.
    let Ok(g34) = Gearing::new(2_000_000, 100_000, 1, 3_125, 4_096) else { exit(false) };
    let leg = Leg { start: [0; AXIS_COUNT], end: [0, 0, -40_000, 0], long: 2 };
    let Ok(mut gear) = Gear::thread(leg, g34, 18_000, 1, 0) else { exit(false) };
    for c in 1..40_000 {
        gear.on_count(c);
    }
    hprintln!("bench encoder count, G34 thread locked");
    for c in 40_000..40_008 {
        measure(count, (&mut gear, c));
    }
    // Near the end: the exact test for where the deceleration starts runs each count.
    let mut c = 40_008;
    while gear.remaining() > 6_000 {
        c += 1;
        gear.on_count(c);
    }
    hprintln!("bench encoder count, G34 thread near its end (deceleration test)");
    for c in c + 1..c + 9 {
        measure(count, (&mut gear, c));
    }
    let mut c = c + 8;
    while !matches!(gear.phase(), Phase::RampDown { .. }) {
        c += 1;
        gear.on_count(c);
    }
    hprintln!("bench encoder count, G34 thread decelerating");
    for c in c + 1..c + 9 {
        measure(count, (&mut gear, c));
    }
    // In the ramp-up after the synchronised count (linear and quadratic parts).
    let Ok(mut gear) = Gear::thread(leg, g34, 18_000, 1, 0) else { exit(false) };
    for c in 1..12_000 {
        gear.on_count(c);
    }
    hprintln!("bench encoder count, G34 thread ramp-up");
    for c in 12_000..12_008 {
        measure(count, (&mut gear, c));
    }

    hprintln!("size of MotionCore<{}>: {} bytes", QUEUE, core::mem::size_of::<MotionCore<QUEUE>>());
    hprintln!("size of Planner<{}>: {} bytes", QUEUE, core::mem::size_of::<Planner<QUEUE>>());
    hprintln!("size of a queue entry: {} bytes", core::mem::size_of::<Item>());
    exit(true)
}

/// Issues the period's step events (what the step interrupt does).
fn drain(core: &mut MotionCore<QUEUE>, until: u64) {
    for axis in 0..AXIS_COUNT {
        while core.next_step(axis, until).is_some() {}
    }
}

//! Dense programs at full feed (issue 22): chains of 0.01–0.05 mm blocks run at
//! the programmed feed, several blocks an interpolation period, on exactly the
//! profile the planner planned.
//!
//! The planner and interpolator are driven directly here (as the motion core
//! drives them) so that every block boundary a period crosses can be checked:
//! its speed against the planned entry, the acceleration, the exact end points.
//! The motion core and the simulated machine then check feed hold, exact stops,
//! threads after a chain, G96, the override and the path deviation.

use host_tests::fast_lathe;
use interp_core::axis::{AXIS_COUNT, Axis, Pos};
use interp_core::canon::{Action, Canon, CanonSink, Endpoint, Feed, FeedMode, Move, SpindleSpeed};
use interp_core::{MachineConfig, Panel};
use motion_core::interpolator::{Interpolator, Live, Status};
use motion_core::motion::{Feedback, MotionCore, QUEUE, State};
use motion_core::planner::{Item, MotionParams, Planner};
use sim::{Sim, SimOptions};

const MM: i64 = 1_000_000;

fn spindle() -> SpindleSpeed {
    SpindleSpeed { rpm: Some(1_000), css: None, max_rpm: 3_000 }
}

fn linear(line: u32, to: Pos, feed_mm_min: i64, exact_stop: bool) -> Canon {
    let m = Move {
        to: Endpoint { machine: to, work: to },
        feed: Feed { mode: FeedMode::PerMin, value: feed_mm_min * MM },
        spindle: spindle(),
        exact_stop,
        independent: false,
    };
    Canon { line, action: Action::Linear(m) }
}

/// `n` blocks of about `seg` nm along `curve` (path length in nm → machine point,
/// nm, X radius), rounded to whole micrometres as IS-B programs are, from line 1.
fn chain(curve: impl Fn(f64) -> (f64, f64), seg: f64, n: usize, feed: i64) -> Vec<Canon> {
    (1..=n)
        .map(|k| {
            let (x, z) = curve(k as f64 * seg);
            let um = |v: f64| (v / 1000.0).round() as i64 * 1000;
            linear(k as u32, Pos::xz(um(x), um(z)), feed, false)
        })
        .collect()
}

/// Along −Z at X 40 mm.
fn straight(s: f64) -> (f64, f64) {
    (40e6, -s)
}

/// A gentle S along −Z: X = 40 mm + 2 mm · sin(z / 10 mm) (radius at least 50 mm).
fn wave(s: f64) -> (f64, f64) {
    (40e6 + 2e6 * (s / 10e6).sin(), -s)
}

/// What one period did at the block boundaries it crossed.
#[derive(Debug, Default)]
struct Trace {
    /// Speed of every period, Q8 nm.
    speeds: Vec<u64>,
    /// Periods until the last block ended.
    periods: u64,
    /// Blocks crossed in the busiest period.
    most_crossed: u64,
    /// Largest speed change in a period over the acceleration of the block it began in.
    worst_accel: f64,
    /// Crossings checked.
    crossings: u64,
}

/// Runs `actions` (from `start`) through a planner and an interpolator as the
/// motion core does — blocks pushed while the queue takes them, a block from rest
/// started when the interpolator is idle — one period at a time, with `live` from
/// `live_at(period)`. Checks at every period: each boundary crossed is crossed at
/// or below the planned entry of the block after it, the crossed blocks end on
/// their exact whole-step end points, the speed changes by at most the
/// acceleration of the block the period began in; at the end, the axes stand on
/// the last end point.
fn run(cfg: &MachineConfig, start: Pos, actions: &[Canon], live_at: impl Fn(u64) -> Live) -> Trace {
    let p = MotionParams::new(cfg).unwrap();
    let mut planner: Planner<QUEUE> = Planner::new(start);
    let steps0: [i64; AXIS_COUNT] = std::array::from_fn(|i| p.scale[i].steps(start.0[i]));
    let mut interp = Interpolator::new(steps0);
    let mut next = 0;
    let mut trace = Trace::default();
    // The accel of the running block.
    let mut accel = 0u64;
    let mut last_v = 0u64;
    for period in 0..2_000_000u64 {
        while next < actions.len() && planner.push(&actions[next], &p).is_ok() {
            next += 1;
        }
        if interp.segment().is_none() {
            match planner.pop() {
                Some(Item::Motion(b)) => {
                    accel = u64::from(b.plan.accel_q8);
                    interp.start(&b, &p);
                    last_v = 0;
                }
                Some(Item::Command { .. }) => continue,
                None if next == actions.len() => {
                    trace.periods = period;
                    break;
                }
                None => panic!("starved at period {period}"),
            }
        }
        // The queue as the period sees it.
        let ahead: Vec<_> = planner
            .iter()
            .filter_map(|i| match i {
                Item::Motion(b) => Some((b.plan.entry_q8(), b.exec.end_steps, u64::from(b.plan.accel_q8))),
                Item::Command { .. } => None,
            })
            .collect();
        let end_before = *interp.segment().unwrap().end_steps();
        let taken = planner.taken();
        let status = interp.tick(&mut planner, &live_at(period), &p);
        let v = interp.speed();
        let crossed = (planner.taken() - taken) as usize;
        trace.most_crossed = trace.most_crossed.max(crossed as u64);
        for (i, (entry, _, _)) in ahead.iter().take(crossed).enumerate() {
            assert!(v <= *entry, "period {period}: crossed boundary {i} at {v} > planned entry {entry}");
            trace.crossings += 1;
        }
        if crossed > 0 {
            // The running block starts on the exact end of the one before it.
            let prev = if crossed >= 2 { ahead[crossed - 2].1 } else { end_before };
            assert_eq!(*interp.start_steps(), prev, "period {period}");
        }
        if status == Status::Finished {
            trace.speeds.push(0);
            continue;
        }
        let step = v.abs_diff(last_v) as f64 / accel as f64;
        trace.worst_accel = trace.worst_accel.max(step);
        assert!(v.abs_diff(last_v) <= accel, "period {period}: speed {last_v} -> {v}, acceleration {accel}");
        if crossed > 0 {
            accel = ahead[crossed - 1].2;
        }
        last_v = v;
        trace.speeds.push(v);
    }
    assert_eq!(interp.overruns(), 0, "the braking test found no speed");
    // The axes end exactly on the last programmed point.
    let last = actions.iter().rev().find_map(|c| c.action.endpoint()).unwrap().machine;
    let want: [i64; AXIS_COUNT] =
        std::array::from_fn(|i| if p.limits[i].present { p.scale[i].steps(last.0[i]) } else { 0 });
    let got = interp.start_steps();
    for i in [Axis::X.index(), Axis::Z.index()] {
        assert_eq!(got[i], want[i], "axis {i} ends off its end point");
    }
    trace
}

fn normal() -> impl Fn(u64) -> Live {
    |_| Live::NORMAL
}

/// The programmed feed in Q8 nm per 1 ms period.
fn q8_per_period(mm_min: i64) -> u64 {
    (mm_min * MM * 256 / 60_000) as u64
}

/// 2,000 blocks of 0.02 mm along Z at F6000 on a 5,000 mm/s² machine: the queue
/// holds more than the braking distance, so the chain runs the analytic trapezoid
/// of the whole 40 mm — 20 periods up at 5 µm/period², about 380 at 100 µm/period,
/// 20 down — five blocks a period.
#[test]
fn a_dense_straight_chain_runs_the_analytic_trapezoid() {
    let cfg = fast_lathe(5_000);
    let actions = chain(straight, 20_000.0, 2_000, 6_000);
    let t = run(&cfg, Pos::xz(40 * MM, 0), &actions, normal());
    // Continuous trapezoid: L/v + v/a = 40/100 + 100/5000 s = 420 ms.
    assert!((419..=422).contains(&t.periods), "{} periods", t.periods);
    let top = q8_per_period(6_000);
    let at_feed = t.speeds.iter().filter(|v| **v >= top - 1).count();
    assert!((379..=381).contains(&at_feed), "{at_feed} periods at the programmed feed");
    assert_eq!(t.most_crossed, 5);
    assert!(t.crossings >= 1_990, "{}", t.crossings);
    // Up and down at exactly the acceleration.
    let a = (5_000 * 256) as u64;
    assert_eq!(t.speeds[..20], (1..=20).map(|k| k * a).collect::<Vec<_>>()[..]);
    let end = t.speeds.len() - 1;
    let down: Vec<u64> = t.speeds[end - 19..end].to_vec();
    assert!(down.windows(2).all(|w| w[0] - w[1] == a), "{down:?}");
}

/// The speed (nm/period) at which a period can still brake to rest within `d`
/// nm at `a` nm/period² (`v² + a·v ≤ 2a·d`), on the profile's grid of whole
/// accelerations from rest.
fn queue_limit(a: f64, d: f64) -> f64 {
    let v = (2.0 * a * d + a * a / 4.0).sqrt() - a / 2.0;
    (v / a).floor() * a
}

/// The same 0.02 mm blocks along a gentle S curve (radius ≥ 50 mm, IS-B points):
/// the curve allows the programmed feed, so the time is the straight chain's
/// within a few periods; every junction crossed at or below its entry.
#[test]
fn a_dense_smooth_curve_runs_at_the_programmed_feed() {
    let cfg = fast_lathe(5_000);
    let actions = chain(wave, 20_000.0, 2_000, 6_000);
    let t = run(&cfg, Pos::xz(40 * MM, 0), &actions, normal());
    // Path length a little over 40 mm (the S adds 0.4 %).
    assert!((419..=426).contains(&t.periods), "{} periods", t.periods);
    let top = q8_per_period(6_000);
    let at_feed = t.speeds.iter().filter(|v| **v + 256 >= top).count();
    assert!(at_feed >= 370, "{at_feed} periods at the programmed feed");
}

/// On the default machine's 500 mm/s² the 64-block queue, not the interpolator,
/// limits 0.02 mm blocks: the speed settles where braking to rest at the queue's
/// end just fits, `v² + a·v ≤ 2·a·D` with D the queued path.
#[test]
fn the_queue_limits_dense_blocks_on_a_slow_machine() {
    let cfg = fast_lathe(500);
    let actions = chain(straight, 20_000.0, 3_000, 6_000);
    let t = run(&cfg, Pos::xz(40 * MM, 0), &actions, normal());
    let middle = &t.speeds[t.speeds.len() / 3..2 * t.speeds.len() / 3];
    let cruise = middle.iter().sum::<u64>() as f64 / middle.len() as f64 / 256.0;
    // The queue holds 64 blocks (1.28 mm) plus the rest of the running block.
    let (low, high) = (queue_limit(500.0, 1_280_000.0), queue_limit(500.0, 1_300_000.0));
    assert!(cruise >= low && cruise <= high, "{cruise} nm/period, {low}..{high}");
    // 2,130 mm/min: 1.8 times the 1,200 mm/min of one block a period.
    assert!(cruise * 0.06 > 2_100.0, "{} mm/min", cruise * 0.06);
}

/// Corners in a dense chain: 0.01 mm blocks zig-zagging at random small and
/// large angles, random lengths and feeds. Every boundary is crossed at or below
/// its planned entry, the acceleration holds, every block ends exactly.
#[test]
fn junction_speeds_hold_at_every_boundary_of_random_dense_chains() {
    let mut rng = interp_core::canon::xorshift::XorShift::new(0x5eed_cafe_f00d_1234);
    for round in 0..12 {
        let cfg = fast_lathe([500, 2_000, 5_000][round % 3]);
        let mut at = (40_000_000i64, 0i64);
        let mut dir = 0.0f64;
        let mut actions = Vec::new();
        for k in 1..=1_500u32 {
            // Mostly gentle turns, sometimes a sharp corner.
            let turn =
                if rng.signed(20) == 0 { rng.signed(1_500) as f64 / 1_000.0 } else { rng.signed(30) as f64 / 1_000.0 };
            dir = (dir + turn).clamp(-1.2, 1.2);
            let len = [10_000.0, 20_000.0, 50_000.0, 300_000.0][(rng.signed(1_000).unsigned_abs() % 4) as usize];
            at = (at.0 + (len * dir.sin()) as i64 / 1000 * 1000, at.1 - (len * dir.cos()) as i64 / 1000 * 1000);
            let feed = [3_000, 6_000, 9_000][(rng.signed(1_000).unsigned_abs() % 3) as usize];
            actions.push(linear(k, Pos::xz(at.0, at.1), feed, rng.signed(200) == 0));
        }
        let t = run(&cfg, Pos::xz(40 * MM, 0), &actions, normal());
        assert!(t.crossings > 1_000, "round {round}: {} crossings", t.crossings);
        assert!(t.worst_accel <= 1.0);
    }
}

/// A dense chain whose 1,000th block has an exact stop (G09): the period that
/// reaches it ends there, at rest, on its exact end point, and the chain after
/// it starts from rest.
#[test]
fn a_dense_chain_stops_exactly_at_an_exact_stop() {
    let cfg = fast_lathe(5_000);
    let mut actions = chain(straight, 20_000.0, 2_000, 6_000);
    let Action::Linear(ref mut m) = actions[999].action else { unreachable!() };
    m.exact_stop = true;
    let stop_at = m.to.machine;
    let t = run(&cfg, Pos::xz(40 * MM, 0), &actions, normal());
    // Twice the trapezoid of 20 mm: 2 × (200 + 20) periods, and one more for the
    // stop: the speed is 0 once, mid-way.
    assert!((438..=444).contains(&t.periods), "{} periods", t.periods);
    let zeros: Vec<usize> = t.speeds.iter().enumerate().filter(|(_, v)| **v == 0).map(|(k, _)| k).collect();
    assert!(zeros.len() <= 3 && zeros.iter().any(|k| (215..=225).contains(k)), "{zeros:?}");

    // The motion core on the same program: at the stop the axes stand on its point.
    let mut core: Box<MotionCore<QUEUE>> = Box::new(MotionCore::new(&cfg, Pos::xz(40 * MM, 0)).unwrap());
    let mut next = 0;
    let mut stood = None;
    for period in 0..1_000u64 {
        while next < actions.len() && core.push(actions[next]).is_ok() {
            next += 1;
        }
        core.tick(period * 1_000_000, Feedback::default());
        for axis in 0..AXIS_COUNT {
            while core.next_step(axis, (period + 1) * 1_000_000).is_some() {}
        }
        if core.path_speed() == 0 && core.line() >= 999 && core.line() <= 1_001 && stood.is_none() {
            stood = Some(core.position());
        }
    }
    assert_eq!(stood, Some(stop_at), "the axes stop on the exact stop's end point");
    assert!(core.is_idle());
    assert_eq!(core.stats().overruns, 0);
}

/// Feed hold at full feed in the middle of a dense chain: the speed falls by the
/// acceleration every period, across block boundaries, and the path stops within
/// the discrete braking distance `(v² + a·v) / 2a` of where the hold began; cycle
/// start finishes the chain on its end point.
#[test]
fn feed_hold_mid_chain_stops_within_the_braking_distance() {
    let cfg = fast_lathe(5_000);
    let actions = chain(wave, 20_000.0, 2_000, 6_000);
    let hold_from = 200u64;
    let resume_at = 400u64;
    let hold = move |period: u64| Live { hold: (hold_from..resume_at).contains(&period), ..Live::NORMAL };
    let t = run(&cfg, Pos::xz(40 * MM, 0), &actions, hold);
    let v0 = t.speeds[hold_from as usize - 1];
    let a = 5_000 * 256u64;
    assert_eq!(v0, q8_per_period(6_000), "at full feed when held");
    // Braking at exactly `a` per period from the first held period on.
    let braking = &t.speeds[hold_from as usize..];
    let stop = braking.iter().position(|v| *v == 0).unwrap();
    for (k, v) in braking[..stop].iter().enumerate() {
        assert_eq!(*v, v0.saturating_sub(a * (k as u64 + 1)), "held period {k}");
    }
    let travelled: u64 = braking[..stop].iter().sum();
    assert!(travelled <= (v0 * v0 + a * v0) / (2 * a), "{travelled} after the hold");
    // Stands still until cycle start, then runs on to the chain's end (run checks it).
    assert!(braking[stop..(resume_at - hold_from) as usize].iter().all(|v| *v == 0));
}

/// With 50 % feed override the dense chain cruises at half the feed; above
/// 100 % it keeps the programmed feed (junction speeds are planned at 100 %).
#[test]
fn feed_override_scales_a_dense_chain() {
    let cfg = fast_lathe(5_000);
    let actions = chain(straight, 20_000.0, 1_000, 6_000);
    for (pct, want) in [(128u64, 3_000), (384, 6_000)] {
        let t = run(&cfg, Pos::xz(40 * MM, 0), &actions, move |_| Live { feed_ovr: pct, ..Live::NORMAL });
        let cruise = t.speeds[t.speeds.len() / 2];
        assert!(cruise.abs_diff(q8_per_period(want)) <= 256, "{pct}/256: {cruise}");
    }
}

/// The simulated machine runs 0.01/0.02/0.05 mm IS-B programs of the S curve at
/// F6000: the feed achieved on the middle of the curve is the programmed one, the
/// stepped axes stay within one step plus the chord tolerance of the programmed
/// polyline, the status line shows every block's line in order.
#[test]
fn the_simulated_machine_runs_dense_programs_at_the_programmed_feed_within_a_step() {
    for seg in [0.01, 0.02, 0.05] {
        let cfg = fast_lathe(5_000);
        let mut text = String::from("G98 G00 X80. Z0.\nG01 F6000\n");
        let n = (40.0 / seg) as usize;
        for k in 1..=n {
            let (x, z) = wave(k as f64 * seg * 1e6);
            text.push_str(&format!("X{:.3} Z{:.3}\n", 2.0 * x / 1e6, z / 1e6));
        }
        text.push_str("G00 X100.\nM30\n");
        let opts = SimOptions { samples: true, start: Pos::xz(40 * MM, 0), ..SimOptions::default() };
        let mut sim = Sim::new(cfg, opts).unwrap();
        let r = sim.run_program(&text);
        assert!(r.alarms.is_empty() && r.ended, "{seg}: {r:?}");
        assert_eq!(r.timing_violations, 0);
        // One X step is 2.5 µm, the chord tolerance 1 µm.
        assert!(r.max_dev_nm <= 2_500.0 + 1_000.0, "{seg} mm: {} nm at line {}", r.max_dev_nm, r.max_dev_line);
        // Feed along the path over Z −10 … −30 mm: the programmed one, or for
        // 0.01 mm blocks the 64-block queue's limit (0.64 mm of path: the
        // 1 mm braking distance from F6000 at 5,000 mm/s² does not fit).
        let z = |s: &sim::TickSample| s.commanded[Axis::Z.index()] as f64 / 65_536.0 / 320.0;
        let a = sim.samples.iter().find(|s| z(s) <= -10.0).unwrap();
        let b = sim.samples.iter().find(|s| z(s) <= -30.0).unwrap();
        let path: f64 = (0..2_000)
            .map(|k| {
                let (p, q) = (wave(10e6 + k as f64 * 10_000.0), wave(10e6 + (k + 1) as f64 * 10_000.0));
                ((q.0 - p.0).powi(2) + (q.1 - p.1).powi(2)).sqrt() / 1e6
            })
            .sum();
        let feed = path / ((b.t - a.t) as f64 / 60e9);
        let want = (queue_limit(5_000.0, 64.0 * seg * 1e6) * 0.06).min(6_000.0);
        assert!(feed >= want * 0.995 && feed <= 6_000.0 * 1.005, "{seg} mm: {feed:.0} mm/min, {want:.0} wanted");
        // Lines in order, every block's line reported or passed within a period.
        let lines: Vec<u32> = sim.samples.iter().filter(|s| s.state == State::Moving).map(|s| s.line).collect();
        assert!(lines.windows(2).all(|w| w[0] <= w[1]), "{seg}: lines out of order");
        let per_period = (6_000.0 / 60.0 / seg).ceil() as u32 / 1_000 + 1;
        assert!(lines.windows(2).all(|w| w[1] - w[0] <= per_period + 1), "{seg}: a line skipped");
    }
}

/// A dense chain followed by a G32 thread: the chain ends at rest on its last
/// point (a spindle-locked block is never blended into) and the thread then
/// starts at its index as always.
#[test]
fn a_period_never_crosses_into_a_thread() {
    let cfg = fast_lathe(5_000);
    let mut text = String::from("G98 G00 X80. Z1.\nM3 S500\nG01 F6000\n");
    for k in 1..=500 {
        text.push_str(&format!("Z{:.3}\n", 1.0 - k as f64 * 0.02));
    }
    text.push_str("G32 Z-30. F1.5\nG00 X90.\nM30\n");
    let opts = SimOptions { samples: true, start: Pos::xz(40 * MM, MM), ..SimOptions::default() };
    let mut sim = Sim::new(cfg, opts).unwrap();
    let r = sim.run_program(&text);
    assert!(r.alarms.is_empty() && r.ended, "{r:?}");
    let first_wait =
        sim.samples.iter().position(|s| matches!(s.state, State::SyncWait { .. } | State::Locked)).unwrap();
    // Z stands on the chain's end (Z −9 mm, 320 steps/mm) when the thread waits.
    let z = sim.samples[first_wait].commanded[Axis::Z.index()];
    assert_eq!(z, -9 * 320 * 65_536);
    assert!((r.end.0[Axis::Z.index()] + 30 * MM).abs() < 4_000);
}

/// G96 along a dense chain facing down X: the commanded speed follows the work X
/// of each period (it is updated every 4 periods), across blocks.
#[test]
fn constant_surface_speed_follows_x_along_a_dense_chain() {
    let cfg = fast_lathe(5_000);
    let mut text = String::from("G98 G00 X80. Z0.\nG50 S3000\nG96 S200 M3\nG01 F3000\n");
    for k in 1..=2_000 {
        text.push_str(&format!("X{:.3}\n", 80.0 - k as f64 * 0.02));
    }
    text.push_str("G00 Z5.\nM30\n");
    let opts = SimOptions { samples: true, start: Pos::xz(40 * MM, 0), ..SimOptions::default() };
    let mut sim = Sim::new(cfg, opts).unwrap();
    let r = sim.run_program(&text);
    assert!(r.alarms.is_empty() && r.ended, "{r:?}");
    let mut checked = 0;
    for s in sim.samples.iter().filter(|s| s.state == State::Moving && s.line > 100 && s.line < 1_900) {
        let x_mm = s.commanded[Axis::X.index()] as f64 / 65_536.0 / 400.0;
        // 200 m/min on the diameter 2·x.
        let want = 200_000.0 / (std::f64::consts::PI * 2.0 * x_mm);
        // Updated every 4 periods: X moves up to 0.2 mm (diameter) meanwhile.
        assert!(
            (f64::from(s.spindle_cmd) - want).abs() / want < 0.01,
            "line {}: {} vs {want:.0}",
            s.line,
            s.spindle_cmd
        );
        checked += 1;
    }
    assert!(checked > 300, "{checked}");
}

/// Interpreter to motion core through the `CanonSink` back-pressure, at the
/// queue's rate: the panel and the interpreter as the board runs them.
#[test]
fn the_interpreter_keeps_the_queue_full_at_5000_blocks_per_second() {
    let cfg = fast_lathe(5_000);
    let mut text = String::from("G98 G01 F6000\n");
    for k in 1..=5_000 {
        let (x, z) = wave(k as f64 * 20_000.0);
        text.push_str(&format!("X{:.3} Z{:.3}\n", 2.0 * x / 1e6, z / 1e6));
    }
    text.push_str("M30\n");
    let store = interp_core::SingleProgram(text.as_bytes());
    let mut interp = interp_core::Interpreter::new(cfg.clone());
    let mut core: Box<MotionCore<QUEUE>> = Box::new(MotionCore::new(&cfg, Pos::xz(40 * MM, 0)).unwrap());
    let mut t = 0u64;
    let mut ended = false;
    while !(ended && core.is_idle()) && t < 10_000_000_000 {
        for _ in 0..4 * QUEUE {
            match interp.step(&store, &Panel::default(), &mut *core) {
                Ok(interp_core::Progress::Ended) => {
                    ended = true;
                    break;
                }
                Ok(interp_core::Progress::Blocked) => break,
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
    let st = core.stats();
    assert_eq!(st.blocks, 5_000);
    assert_eq!(st.starvations, 0);
    assert_eq!(st.overruns, 0);
    // 100 mm of curve at 6 m/min: 1.0 s, plus 20 ms each to speed up and stop.
    let secs = t as f64 / 1e9;
    assert!(secs < 1.06, "{secs} s: {:.0} blocks/s", 5_000.0 / secs);
}

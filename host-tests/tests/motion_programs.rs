//! Whole programs through interpreter → planner → interpolator → steps on the
//! simulated machine: the example programs, G32/G92 threads and G84 rigid tapping
//! written in G code, and a million blocks without drift.

use interp_core::axis::{AXIS_COUNT, Pos};
use interp_core::canon::{Action, Canon, CanonSink as _, Endpoint, Feed, FeedMode, Move, SpindleSpeed};
use interp_core::lang::fanuc::macros::Variables;
use interp_core::{Axis, MachineConfig};
use motion_core::fixed::round_steps;
use motion_core::motion::{Feedback, MotionCore, QUEUE, State};
use sim::{Report, Sim, SimOptions, SpindleModel, TraceRow};

const CPR: i64 = 4_096;

fn sim(model: SpindleModel, trace: bool) -> Sim {
    let cfg = MachineConfig::default();
    let start = cfg.reference[0];
    Sim::new(cfg, SimOptions { spindle: model, trace, start, max_time_s: 3_600.0, ..SimOptions::default() }).unwrap()
}

fn assert_clean(name: &str, r: &Report) {
    assert!(r.alarms.is_empty(), "{name}: {:?}", r.alarms);
    assert!(r.ended, "{name}: did not end");
    assert_eq!(r.timing_violations, 0, "{name}: driver timing violated");
    // One step of Z (3.125 µm, the coarser axis) plus the chord tolerance (1 µm).
    assert!(r.max_dev_nm <= 4_125.0, "{name}: {} nm from the path on line {}", r.max_dev_nm, r.max_dev_line);
}

/// The `.nc` files of `examples/<sub>`, sorted.
fn nc_files(sub: &str) -> Vec<std::path::PathBuf> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples").join(sub);
    let mut v: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "nc"))
        .collect();
    v.sort();
    v
}

#[test]
fn every_example_program_runs_on_the_path() {
    let read = |p: &std::path::PathBuf| std::fs::read_to_string(p).unwrap();
    let library: Vec<String> = nc_files("lib").iter().map(read).collect();
    let library: Vec<&str> = library.iter().map(String::as_str).collect();
    let programs = nc_files("");
    assert!(programs.len() >= 10);
    for p in &programs {
        // The subprograms of examples/lib are in program memory, as on the machine.
        let (store, main) = host_tests::memory(&read(p), &library);
        let r = sim(SpindleModel::default(), false).run_store(&*store, main, &Variables::new(), |_| {});
        assert_clean(&p.display().to_string(), &r);
    }
}

/// Z steps of the thread on `line` between Z`hi` and Z`lo` (the synchronised length).
fn thread_rows(trace: &[TraceRow], line: u32, hi: f64, lo: f64) -> Vec<TraceRow> {
    trace.iter().filter(|t| t.line == line && t.axis == 2 && t.z_mm < hi && t.z_mm > lo).copied().collect()
}

/// (count at which Z first reaches `z` − index) mod counts per revolution.
fn phase(rows: &[TraceRow], z: f64, index: i64) -> i64 {
    (rows.iter().find(|t| t.z_mm <= z + 1e-9).unwrap().count - index).rem_euclid(CPR)
}

/// Largest Z error (steps of 3.125 µm) from the line through the first row at `lead`.
fn lead_error(rows: &[TraceRow], lead: f64) -> f64 {
    let r0 = rows[0];
    let ideal = |r: &TraceRow| r0.z_mm - (r.count - r0.count) as f64 * lead / CPR as f64;
    rows.iter().map(|r| ((r.z_mm - ideal(r)) * 1e6).abs() / 3_125.0).fold(0.0, f64::max)
}

#[test]
fn g32_passes_at_200_800_and_2000_rpm_cut_one_groove() {
    let text = "G97 S200 M3\nG0 X40 Z20\nG32 Z-40 F2\nG0 X50\nZ20\n\
                S800\nX39.8\nG32 Z-40 F2\nG0 X50\nZ20\n\
                S2000\nX39.6\nG32 Z-40 F2\nG0 X50\nZ20\nM30\n";
    let ripple = SpindleModel { ripple: 0.05, ripple_hz: 2.0, noise: 0.005, seed: 9, ..SpindleModel::default() };
    let mut s = sim(ripple, true);
    let r = s.run_program(text);
    assert_clean("G32", &r);
    let index = s.spindle_index();
    let mut phases = Vec::new();
    for line in [3, 8, 13] {
        let rows = thread_rows(&s.trace, line, 12.0, -32.0);
        assert!(lead_error(&rows, 2.0) <= 1.0 + 488.0 / 3_125.0, "line {line}");
        phases.push(phase(&rows, -10.0, index));
    }
    assert!(phases.iter().max().unwrap() - phases.iter().min().unwrap() <= 1, "{phases:?}");
}

#[test]
fn g92_at_2000_rpm_pulls_out_and_repeats_the_groove() {
    // Pull-out of one lead at 45° (parameters 5130/5131): the deceleration from
    // 4000 mm/min needs more than the pull-out and starts in the thread before it.
    let text = "G97 S2000 M3\nG0 X65 Z5\nG92 X58.7 Z-28 F2\nX57.7\nX57\nG0 X100\nM30\n";
    let mut s = sim(SpindleModel::default(), true);
    let r = s.run_program(text);
    assert_clean("G92", &r);
    let index = s.spindle_index();
    let p: Vec<_> = (3..=5).map(|l| phase(&thread_rows(&s.trace, l, -2.0, -20.0), -10.0, index)).collect();
    assert!(p.iter().max().unwrap() - p.iter().min().unwrap() <= 1, "{p:?}");
    // Each pass ended exactly at the end of its pull-out (X dia + 2 × 2 mm, Z-28) and
    // went no deeper.
    for (line, x) in [(3, 62.7), (4, 61.7), (5, 61.0)] {
        let rows: Vec<_> = s.trace.iter().filter(|t| t.line == line).collect();
        assert!(rows.iter().all(|t| t.z_mm >= -28.0), "line {line}");
        assert!(rows.iter().any(|t| t.x_mm == x && t.z_mm == -28.0), "line {line}");
    }
}

#[test]
fn g84_rigid_tap_follows_the_spindle_in_and_out() {
    let text = "G98 G0 X0 Z10\nM29 S600\nG84 Z-18 R-7 P300 F900\nG80\nG0 X100 Z50\nM30\n";
    let mut s = sim(SpindleModel::default(), true);
    let mut origin = None;
    let r = s.run_program_with(text, |sim| {
        if let Some(g) = sim.core.gear() {
            origin.get_or_insert(g.origin());
        }
    });
    assert_clean("G84", &r);
    let c0 = origin.unwrap();
    // Locked from R (Z3) to the bottom (Z-18) and back: lead F/S = 1.5 mm.
    let rows: Vec<_> = s.trace.iter().filter(|t| t.line == 3 && t.axis == 2 && t.z_mm <= 3.0).collect();
    assert!(rows.iter().any(|t| t.z_mm <= -18.0));
    for t in &rows {
        let ideal = 3.0 - (t.count - c0) as f64 * 1.5 / CPR as f64;
        assert!(((t.z_mm - ideal) * 1e6).abs() <= 3_125.0, "Z {} vs {ideal}", t.z_mm);
    }
}

/// A straight cutting move to `to` (machine = work, nm) at 3000 mm/min.
fn linear(to: Pos, exact_stop: bool, line: u32) -> Canon {
    let m = Move {
        to: Endpoint { machine: to, work: to },
        feed: Feed { mode: FeedMode::PerMin, value: 3_000_000_000 },
        spindle: SpindleSpeed { rpm: None, css: None, max_rpm: 3_000 },
        exact_stop,
        independent: false,
    };
    Canon { line, action: Action::Linear(m) }
}

#[test]
fn a_million_blocks_end_exactly_where_the_nanometres_say() {
    let cfg = MachineConfig::default();
    let mut core: MotionCore<QUEUE> = MotionCore::new(&cfg, Pos::xz(50_000_000, 0)).unwrap();
    let scale = core.params().scale;
    let steps_of = |p: &Pos| -> [i64; AXIS_COUNT] { core::array::from_fn(|i| scale[i].steps(p.0[i])) };
    // A pseudo-random walk of odd nanometre amounts, every 1000th block an exact stop.
    let mut seed = 12_345u64;
    let mut pos = Pos::xz(50_000_000, 0);
    let (mut t, mut checked) = (0u64, 0);
    for k in 0..1_000_000u32 {
        seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        let dx = (seed >> 40) as i64 % 40_001 - 20_000;
        let dz = (seed >> 20) as i64 % 60_001 - 30_000;
        pos = Pos::xz((pos[Axis::X] + dx).clamp(10_000_000, 90_000_000), (pos[Axis::Z] + dz).clamp(-50_000_000, 0));
        let stop = k % 1_000 == 999;
        let block = linear(pos, stop, k + 1);
        while core.push(block).is_err() {
            core.tick(t, Feedback::default());
            t += 1_000_000;
        }
        if stop {
            // Run to the stop and compare with the exact conversion of the end point.
            while core.queued() > 0 || core.state() != State::Idle {
                core.tick(t, Feedback::default());
                t += 1_000_000;
            }
            assert_eq!(core.commanded().map(round_steps), steps_of(&pos), "block {k}");
            checked += 1;
        }
    }
    assert_eq!(checked, 1_000);
}

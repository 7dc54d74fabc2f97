//! The encoder compare (issue 22): the motion core is given the spindle encoder only
//! at the counts where something falls due ([`MotionCore::encoder_due`]), as the
//! firmware's compare interrupt gives it, instead of at every count. On the
//! simulated machine, with a rippling spindle, every spindle-locked motion — G32
//! tapers and multi-start threads, G34 variable lead, G92 with its pull-out, G76,
//! rigid tapping G84 and G88 (M29), polygon turning G51.2 — must make every step at
//! the same time and encoder count as when every count is handed over, and the
//! count interrupt must run far less often than once a count.
//!
//! [`MotionCore::encoder_due`]: motion_core::motion::MotionCore::encoder_due

use interp_core::MachineConfig;
use sim::{Report, Sim, SimOptions, SpindleModel, TraceRow};

/// A spindle with 5 % ripple and noise (speed changes all the time).
fn rippling() -> SpindleModel {
    SpindleModel { ripple: 0.05, ripple_hz: 3.0, noise: 0.005, seed: 7, ..SpindleModel::default() }
}

fn run(cfg: &MachineConfig, text: &str, every_count: bool) -> (Report, Vec<TraceRow>) {
    let opts = SimOptions { trace: true, spindle: rippling(), every_count, ..SimOptions::default() };
    let mut sim = Sim::new(cfg.clone(), opts).unwrap();
    let report = sim.run_program(text);
    (report, std::mem::take(&mut sim.trace))
}

fn example(path: &str) -> String {
    std::fs::read_to_string(format!("{}/../examples/{path}", env!("CARGO_MANIFEST_DIR"))).unwrap()
}

fn polygon_machine() -> MachineConfig {
    lathe::machine::parse(include_str!("../../examples/machines/polygon.toml")).unwrap()
}

/// Runs `text` both ways; asserts identical step traces and end, and returns the
/// share of the locked counts that went to the core.
fn both_ways(name: &str, cfg: &MachineConfig, text: &str) -> f64 {
    let (every, every_trace) = run(cfg, text, true);
    let (due, due_trace) = run(cfg, text, false);
    assert!(due.alarms.is_empty(), "{name}: {:?}", due.alarms);
    assert!(due.ended, "{name}: did not end");
    assert_eq!(due.timing_violations, 0, "{name}");
    assert!(due.locked_counts > 10_000, "{name}: only {} counts locked", due.locked_counts);
    assert_eq!(every.encoder_calls, every.locked_counts, "{name}");
    assert_eq!(every_trace.len(), due_trace.len(), "{name}: step count");
    for (k, (a, b)) in every_trace.iter().zip(&due_trace).enumerate() {
        assert_eq!(a, b, "{name}: step {k} differs (every count, then due counts only)");
    }
    assert_eq!((every.end, every.steps), (due.end, due.steps), "{name}");
    let share = due.encoder_calls as f64 / due.locked_counts as f64;
    println!("{name}: {} of {} locked counts to the core ({share:.3})", due.encoder_calls, due.locked_counts);
    share
}

#[test]
fn threads_of_every_kind_step_alike_with_only_the_due_counts() {
    let cfg = MachineConfig::default();
    // G32 taper, G92 with pull-out, G76 (continuing legs), G34 growing by K; coarse
    // leads (3, 4–6 mm: up to 0.6 Z steps a count) make a step every few counts.
    let share = both_ways("cycles_threads.nc", &cfg, &example("cycles_threads.nc"));
    assert!(share < 0.35, "{share}");
    // Multi-start (Q0/Q120/Q240) tapers at 3000 rpm, 1.4 mm lead (the most the
    // default Z takes with the 10 % margin and this spindle's 5 % ripple).
    let multi = "G21 G18 G97 G99\nM03 S3000\n\
        G00 X40. Z5.\nG32 X44. Z-40. F1.4 Q0\nG00 X50.\nZ5.\nX40.\n\
        G32 X44. Z-40. F1.4 Q120\nG00 X50.\nZ5.\nX40.\n\
        G32 X44. Z-40. F1.4 Q240\nG00 X50.\nZ5.\nM30\n";
    let share = both_ways("multi-start at 3000 rpm", &cfg, multi);
    assert!(share < 0.15, "{share}");
}

#[test]
fn rigid_taps_along_z_and_x_step_alike_with_only_the_due_counts() {
    let cfg = MachineConfig::default();
    let share = both_ways("cycles_drill_tap.nc", &cfg, &example("cycles_drill_tap.nc"));
    assert!(share < 0.5, "{share}");
    // G88: a rigid side tap along X (M29, G99 F = lead), in and reversed out.
    let side = "G21 G18 G97 G99\nG00 X60. Z-10.\nM29 S800\nG88 X20. R-2. F1.5\nG80\nG00 X100.\nM30\n";
    let share = both_ways("G88 side tap", &cfg, side);
    assert!(share < 0.5, "{share}");
}

#[test]
fn polygon_turning_steps_alike_with_only_the_due_counts() {
    // C at 3600 steps a turn, P1 Q2 then P1 Q3: 1.76 and 2.6 C steps a count: every
    // count moves C, so every count is due; the core is told so, and the two ways
    // still step alike.
    let share = both_ways("polygon_g51_2.nc", &polygon_machine(), &example("c_axis/polygon_g51_2.nc"));
    assert!(share <= 1.0, "{share}");
}

//! The motion core on the simulated machine: path accuracy, exact end points,
//! speed and acceleration limits, blending and exact stop.

use interp_core::MachineConfig;
use interp_core::axis::{AXIS_COUNT, Pos};
use motion_core::fixed::STEP_ONE;
use motion_core::motion::State;
use proptest::prelude::*;
use sim::{Report, Sim, SimOptions, TickSample};

fn sim(cfg: MachineConfig) -> Sim {
    Sim::new(cfg, SimOptions { samples: true, ..SimOptions::default() }).unwrap()
}

fn run(text: &str) -> (Sim, Report) {
    let mut s = sim(MachineConfig::default());
    let r = s.run_program(text);
    (s, r)
}

/// The deviation bound: one step of the coarser axis plus the chord tolerance.
fn bound(cfg: &MachineConfig) -> f64 {
    let step = cfg.axes.iter().filter(|a| a.present).map(|a| a.drive.per_nm as f64 / a.drive.steps as f64);
    step.fold(0.0, f64::max) + cfg.motion.chord_tolerance as f64
}

fn assert_clean(r: &Report) {
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    assert!(r.ended, "did not end: {r:?}");
    assert_eq!(r.timing_violations, 0, "driver timing violated");
}

const CONTOUR: &str = "\
G0 X20 Z2
M3 S1000
G1 Z0 F300
X30 Z-5
G3 X50 Z-15 R10
G1 Z-25
G2 X70 Z-35 I10 K0
G1 X72 W-20
G3 X72 Z-65 I0 K-5
G2 X60 Z-90 R15
G1 U10 W-3 F1200
G1 X100
G0 X120 Z20
M30
";

#[test]
fn lines_and_arcs_stay_within_one_step_plus_chord_tolerance() {
    let (s, r) = run(CONTOUR);
    assert_clean(&r);
    let cfg = MachineConfig::default();
    assert!(r.max_dev_nm <= bound(&cfg), "deviation {} nm on line {}", r.max_dev_nm, r.max_dev_line);
    let chord_steps = cfg.motion.chord_tolerance as f64 / 2_500.0;
    assert!(r.max_dev_steps <= 1.0 + chord_steps, "{} steps", r.max_dev_steps);
    // 117 mm at 300 mm/min (23.4 s), 26 mm at 1200 mm/min, rapids and spindle start.
    assert!(r.cycle_time_s > 25.0 && r.cycle_time_s < 28.0, "cycle {}", r.cycle_time_s);
    assert!(s.samples.iter().any(|t| t.state == State::Moving));
}

#[test]
fn the_program_ends_exactly_on_its_end_point() {
    let (s, r) = run(CONTOUR);
    assert_clean(&r);
    // X120 (radius 60 mm = 24000 steps at 400/mm), Z20 (6400 steps at 320/mm).
    assert_eq!(r.end, Pos::xz(60_000_000, 20_000_000));
    assert_eq!(s.axes[0].steps, 24_000);
    assert_eq!(s.axes[2].steps, 6_400);
}

/// Per-axis speed (Q16 steps per period) of every period from the samples.
fn speeds(samples: &[TickSample]) -> Vec<[i64; AXIS_COUNT]> {
    samples.windows(2).map(|w| core::array::from_fn(|i| w[1].commanded[i] - w[0].commanded[i])).collect()
}

/// Checks that no axis goes faster than its limit or changes speed by more than its
/// acceleration per period plus the junction jump allowed.
fn assert_kinematics(cfg: &MachineConfig, samples: &[TickSample], rapid_pct: f64) {
    let dt = cfg.motion.tick_ns as f64 / 1e9;
    let v = speeds(samples);
    for axis in [0usize, 2] {
        let ax = &cfg.axes[axis];
        let q16_per_nm = ax.drive.steps as f64 / ax.drive.per_nm as f64 * STEP_ONE as f64;
        let vmax = ax.rapid_per_min.max(ax.max_feed_per_min) as f64 / 60.0 * dt * q16_per_nm * rapid_pct.max(1.0);
        let accel = ax.accel_per_s2 as f64 * dt * dt * q16_per_nm;
        let jump = ax.max_jump_per_min as f64 / 60.0 * dt * q16_per_nm;
        let mut worst = (0.0f64, 0usize);
        for (k, s) in v.iter().enumerate() {
            assert!((s[axis] as f64).abs() <= vmax * 1.001, "axis {axis} speed {} > {vmax} at {k}", s[axis]);
            if k > 0 {
                let dv = (s[axis] - v[k - 1][axis]).abs() as f64;
                if dv > worst.0 {
                    worst = (dv, k);
                }
            }
        }
        assert!(
            worst.0 <= accel * 1.01 + jump + 2.0,
            "axis {axis}: speed change {} per period at {} (accel {accel}, jump {jump}), line {}",
            worst.0,
            worst.1,
            samples[worst.1].line
        );
    }
}

#[test]
fn speed_and_acceleration_limits_are_never_exceeded() {
    let cfg = MachineConfig::default();
    let (s, r) = run(CONTOUR);
    assert_clean(&r);
    assert_kinematics(&cfg, &s.samples, 1.0);
    // Rapids at full rate: Z reaches 8000 mm/min, X 6000 mm/min.
    let (s, r) = run("G0 X200 Z-400\nG0 X0 Z0\nM30\n");
    assert_clean(&r);
    assert_kinematics(&cfg, &s.samples, 1.0);
    let top = speeds(&s.samples).iter().map(|v| v[2].abs()).max().unwrap();
    // 8000 mm/min = 133.3 µm per ms = 42.67 steps per ms at 320 steps/mm; the rapid
    // is a straight line, so Z runs at the path speed its share allows.
    assert!(top > 30 * STEP_ONE, "Z top speed {top}");
}

#[test]
fn blending_keeps_speed_through_gentle_corners_and_exact_stop_stops() {
    // A polyline of 0.5 mm chords of a circle (1° apart): G64 keeps moving.
    let mut text = String::from("G0 X0 Z0\nG1 F1500\n");
    for k in 1..=60 {
        let a = (k as f64).to_radians();
        text += &format!("X{:.4} Z{:.4}\n", 2.0 * 30.0 * (1.0 - a.cos()), -30.0 * a.sin());
    }
    text += "M30\n";
    let (s, r) = run(&text);
    assert_clean(&r);
    let slowest = moving_min_speed(&s.samples);
    assert!(slowest > 10.0, "G64 polyline slowed to {slowest} um/period");
    // The same with G61: every block ends at rest.
    let (s61, r61) = run(&text.replace("G1 F1500", "G61 G1 F1500"));
    assert_clean(&r61);
    assert!(r61.cycle_time_s > r.cycle_time_s * 1.5, "{} vs {}", r61.cycle_time_s, r.cycle_time_s);
    // At rest between blocks: the last period before the stop creeps less than one
    // period's acceleration (0.5 µm).
    assert!(moving_min_speed(&s61.samples) < 0.5);
    assert_eq!(r.end, r61.end);
}

/// Smallest path speed (µm per period) while the polyline runs (after it got going).
fn moving_min_speed(samples: &[TickSample]) -> f64 {
    let v: Vec<f64> = samples
        .windows(2)
        .filter(|w| w[0].line > 3 && w[1].line < 62)
        .map(|w| {
            let dx = (w[1].commanded[0] - w[0].commanded[0]) as f64 / STEP_ONE as f64 * 2.5;
            let dz = (w[1].commanded[2] - w[0].commanded[2]) as f64 / STEP_ONE as f64 * 3.125;
            (dx * dx + dz * dz).sqrt()
        })
        .collect();
    v.iter().cloned().fold(f64::MAX, f64::min)
}

#[test]
fn independent_rapids_move_each_axis_at_its_own_rate() {
    // Dog-leg G00 (and G28/G30 always): X (radius 50 mm at 6 m/min, 0.2 s to get to
    // speed) arrives after 0.7 s, Z (200 mm at 8 m/min, 0.27 s) after 1.77 s.
    let cfg = MachineConfig { rapid_independent: true, ..MachineConfig::default() };
    let mut s = sim(cfg.clone());
    let r = s.run_program("G0 X100 Z-200\nM30\n");
    assert_clean(&r);
    assert_eq!(r.end, Pos::xz(50_000_000, -200_000_000));
    let done = |axis: usize, end: i64| s.samples.iter().position(|t| t.commanded[axis] == end * STEP_ONE).unwrap();
    let (x_at, z_at) = (done(0, 20_000), done(2, -64_000));
    assert!((690..720).contains(&x_at) && (1_760..1_790).contains(&z_at), "X at {x_at} ms, Z at {z_at} ms");
    assert_kinematics(&cfg, &s.samples, 1.0);
}

#[test]
fn a_right_angle_corner_is_taken_at_the_junction_speed() {
    let (s, r) = run("G0 X0 Z0\nG1 Z-10 F2000\nX20\nM30\n");
    assert_clean(&r);
    let v = speeds(&s.samples);
    // At the corner Z has almost stopped when X starts: neither axis runs above the
    // junction speed (2.83 µm per period, chord limit) plus one period's acceleration.
    let corner = v.iter().position(|s| s[0] != 0).unwrap();
    let z_um = v[corner - 1][2].abs() as f64 / STEP_ONE as f64 * 3.125;
    assert!(z_um > 0.5 && z_um < 2.83 + 0.5 + 0.5, "Z speed into the corner {z_um} um/ms");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    /// Random contours of lines and arcs: always within the bound, always ending exactly.
    #[test]
    fn random_contours_stay_on_the_path(
        moves in prop::collection::vec((0u8..4, 1.0f64..40.0, -40.0f64..-0.5, 0.5f64..6.0), 2..8),
        feed in 50.0f64..3000.0,
    ) {
        let mut text = format!("G0 X60 Z0\nG1 F{feed:.0}\n");
        let mut z = 0.0;
        for (kind, x, dz, r) in moves {
            z += dz;
            let x = x * 2.0 + 10.0;
            text += &match kind {
                0 | 1 => format!("G1 X{x:.3} Z{z:.3}\n"),
                2 => format!("G2 X{x:.3} Z{z:.3} R{:.3}\n", r * 20.0),
                _ => format!("G3 X{x:.3} Z{z:.3} R{:.3}\n", r * 20.0),
            };
        }
        text += "G0 X150\nM30\n";
        let (s, r) = run(&text);
        prop_assume!(r.alarms.is_empty()); // R too small for the chord: alarm 0020
        prop_assert!(r.ended);
        prop_assert!(r.max_dev_nm <= bound(&MachineConfig::default()), "{} nm at line {}", r.max_dev_nm, r.max_dev_line);
        prop_assert_eq!(r.end.0[0], 75_000_000);
        let z_nm = (format!("{z:.3}").parse::<f64>().unwrap() * 1e6).round() as i64;
        let scale = s.core.params().scale[2];
        prop_assert_eq!(r.end.0[2], scale.nm(scale.steps(z_nm)));
        assert_kinematics(&MachineConfig::default(), &s.samples, 1.0);
    }
}

//! The motion core on a 3-axis machining centre (issue 20, "the board and the
//! motion core"): a line moving X, Y and Z at once and a helix (G17 G03 with Z)
//! stay within one step plus the chord tolerance of the programmed path — measured
//! here against the ideal line and helix computed from the program's numbers, at
//! every interpolation period — and end on their end points exactly, in integer
//! steps of every axis.

use interp_core::MachineConfig;
use interp_core::axis::{Axis, Pos};
use motion_core::fixed::STEP_ONE;
use sim::{Sim, SimOptions};

/// The built-in machining centre: 400 steps/mm on X, Y and Z (2.5 µm a step).
const NM_PER_STEP: f64 = 2_500.0;

const PROGRAM: &str = "\
G17 G90 G21 G94
G00 X-50. Y-50. Z-10.
G01 X-120. Y-80. Z-30. F1500
G03 X-80. Y-80. Z-40. I20. J0 F800
M30
";

/// Commanded position (mm) of every period of `line`.
fn samples_of(s: &Sim, line: u32) -> Vec<[f64; 3]> {
    let mm = |q: i64| q as f64 / STEP_ONE as f64 * NM_PER_STEP / 1e6;
    s.samples
        .iter()
        .filter(|t| t.line == line)
        .map(|t| [mm(t.commanded[0]), mm(t.commanded[1]), mm(t.commanded[2])])
        .collect()
}

#[test]
fn a_three_axis_line_and_a_helix_stay_on_the_path_and_end_exactly() {
    let cfg = MachineConfig::mill();
    let chord_mm = cfg.motion.chord_tolerance as f64 / 1e6;
    let bound = NM_PER_STEP / 1e6 + chord_mm;
    let mut s = Sim::new(cfg, SimOptions { samples: true, ..SimOptions::default() }).unwrap();
    let r = s.run_program(PROGRAM);
    assert!(r.alarms.is_empty() && r.ended, "{r:?}");
    assert_eq!(r.timing_violations, 0);
    assert!(r.max_dev_nm <= bound * 1e6, "sim deviation {} nm on line {}", r.max_dev_nm, r.max_dev_line);

    // The line (-50,-50,-10) → (-120,-80,-30): distance of every period's point
    // from the segment.
    let (a, b) = ([-50.0, -50.0, -10.0], [-120.0, -80.0, -30.0]);
    let d: [f64; 3] = core::array::from_fn(|i| b[i] - a[i]);
    let len2: f64 = d.iter().map(|v| v * v).sum();
    let line = samples_of(&s, 3);
    assert!(line.len() > 100, "{} periods", line.len());
    let mut worst = 0.0f64;
    for p in &line {
        let t = ((0..3).map(|i| (p[i] - a[i]) * d[i]).sum::<f64>() / len2).clamp(0.0, 1.0);
        let off: f64 = (0..3).map(|i| (p[i] - a[i] - t * d[i]).powi(2)).sum::<f64>().sqrt();
        worst = worst.max(off);
    }
    assert!(worst <= bound, "line: {worst} mm off the segment (bound {bound})");
    // Y really moved along with X and Z, in proportion.
    let mid = line[line.len() / 2];
    assert!((mid[1] - (a[1] + (mid[0] - a[0]) / d[0] * d[1])).abs() <= bound, "{mid:?}");

    // The helix: centre (-100,-80), radius 20, from angle 180° counter-clockwise
    // to 360° (through Y -100), Z from -30 to -40 in proportion to the angle.
    let helix = samples_of(&s, 4);
    assert!(helix.len() > 100, "{} periods", helix.len());
    let mut worst_r = 0.0f64;
    let mut worst_z = 0.0f64;
    let mut lowest_y = 0.0f64;
    for p in &helix {
        let (x, y) = (p[0] + 100.0, p[1] + 80.0);
        worst_r = worst_r.max(((x * x + y * y).sqrt() - 20.0).abs());
        let mut angle = y.atan2(x);
        if angle > 0.5 {
            angle -= 2.0 * core::f64::consts::PI; // 180° is reached from below
        }
        let frac = ((angle + core::f64::consts::PI) / core::f64::consts::PI).clamp(0.0, 1.0);
        worst_z = worst_z.max((p[2] - (-30.0 - 10.0 * frac)).abs());
        lowest_y = lowest_y.min(p[1]);
    }
    assert!(worst_r <= bound, "helix: {worst_r} mm off the radius (bound {bound})");
    assert!(worst_z <= bound, "helix: Z {worst_z} mm off its linear rise (bound {bound})");
    assert!((lowest_y + 100.0).abs() <= bound, "counter-clockwise through Y-100: lowest Y {lowest_y}");

    // The end point, exactly, in steps of every axis.
    assert_eq!(r.end, Pos([-80_000_000, -80_000_000, -40_000_000, 0]));
    let steps = |a: Axis| s.axes[a.index()].steps;
    assert_eq!([steps(Axis::X), steps(Axis::Y), steps(Axis::Z)], [-32_000, -32_000, -16_000]);
}

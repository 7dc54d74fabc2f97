//! Polar coordinate interpolation G12.1/G13.1 (2.7) with the manual's figure 2.12:
//! the machine's X/C points, mapped back to the Cartesian polar plane, lie on the
//! programmed contour (or one nose radius off it under G42), the straight X/C
//! moves between them stay within the chord tolerance, and the feed is tangential.

use host_tests::{Run, mm, run_with};
use interp_core::canon::Action;
use interp_core::config::AxisConfig;
use interp_core::{Axis, MachineConfig, Panel};

fn machine(radius: f64) -> MachineConfig {
    let mut cfg = MachineConfig::default();
    cfg.axes[Axis::C.index()] = AxisConfig::linear(-100_000, 100_000, 36_000);
    let row = cfg.tools.get_mut(1).unwrap();
    row.radius = mm(radius);
    cfg
}

/// Figure 2.12 (N210 with its G01 written out: after G03 the manual's `C0` would be
/// an arc without R).
const FIG_2_12: &str = "G98 M03 S500 T0101
N100 G00 X150 C0 Z0
N110 G12.1
N120 G42 G01 X60 F200
N130 C25
N140 G03 X50 C30 R5
N150 G01 X-50
N160 G03 X-60 C25 R5
N170 G01 C-25
N180 G03 X-50 C-30 R5
N190 G01 X50
N200 G03 X60 C-25 R5
N210 G01 C0
N220 G40 X150
N230 G13.1
N240 Z100
N250 M30
";

/// The real moves as (line, X radius mm, C degrees, feed mm/min).
fn real(r: &Run) -> Vec<(u32, f64, f64, f64)> {
    r.actions
        .iter()
        .filter_map(|c| match c.action {
            Action::Linear(m) | Action::Rapid(m) => Some((
                c.line,
                m.to.work.0[Axis::X.index()] as f64 / 1e6,
                m.to.work.0[Axis::C.index()] as f64 / 1e6,
                m.feed.value as f64 / 1e6,
            )),
            _ => None,
        })
        .collect()
}

fn cart(r: f64, deg: f64) -> (f64, f64) {
    (r * deg.to_radians().cos(), r * deg.to_radians().sin())
}

fn seg_dist(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let t = (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
    (p.0 - a.0 - t * dx).hypot(p.1 - a.1 - t * dy)
}

/// Distance from `p` to the rounded square of figure 2.12 (x, c in mm).
fn contour_dist(p: (f64, f64)) -> f64 {
    let lines = [
        ((30.0, -25.0), (30.0, 25.0)),
        ((25.0, 30.0), (-25.0, 30.0)),
        ((-30.0, 25.0), (-30.0, -25.0)),
        ((-25.0, -30.0), (25.0, -30.0)),
    ];
    let corners = [(25.0, 25.0), (-25.0, 25.0), (-25.0, -25.0), (25.0, -25.0)];
    let mut d = lines.iter().map(|&(a, b)| seg_dist(p, a, b)).fold(f64::MAX, f64::min);
    for c in corners {
        // A corner arc: the quarter facing away from the square's centre.
        if (p.0 - c.0) * c.0.signum() >= 0.0 && (p.1 - c.1) * c.1.signum() >= 0.0 {
            d = d.min(((p.0 - c.0).hypot(p.1 - c.1) - 5.0).abs());
        }
    }
    d
}

fn ok(text: &str, radius: f64) -> Run {
    let r = run_with(text, machine(radius), Panel::default());
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    r
}

/// Checks every point of lines `from..=to` and the midpoint of every straight X/C
/// move between them against `want` (distance from the contour), within 1 µm.
fn check_path(pts: &[(u32, f64, f64, f64)], lines: std::ops::RangeInclusive<u32>, want: f64) {
    let mut n = 0;
    for w in pts.windows(2) {
        let (a, b) = (w[0], w[1]);
        if !lines.contains(&b.0) || !lines.contains(&a.0) {
            continue;
        }
        let p = cart(b.1, b.2);
        assert!((contour_dist(p) - want).abs() < 1.1e-3, "line {} point {p:?}: {}", b.0, contour_dist(p));
        // What the machine does between the points: X and C straight.
        let mid = cart((a.1 + b.1) / 2.0, (a.2 + b.2) / 2.0);
        assert!((contour_dist(mid) - want).abs() < 1.1e-3, "line {} between {a:?} and {b:?}", b.0);
        n += 1;
    }
    assert!(n > 50, "{n} moves checked");
}

#[test]
fn figure_2_12_runs_on_the_contour() {
    let r = ok(FIG_2_12, 0.0);
    let pts = real(&r);
    check_path(&pts, 4..=13, 0.0);
    // After G13.1 the plane is back: Z100 moves Z alone, C stays at 0° (mod 360).
    let last = r.actions.iter().rev().find_map(|c| c.action.endpoint().copied()).unwrap();
    assert_eq!(last.work.0[Axis::Z.index()], mm(100.0));
    assert_eq!(last.work.0[Axis::C.index()].rem_euclid(360_000_000), 0);
}

#[test]
fn figure_2_12_with_g42_runs_one_nose_radius_outside() {
    let r = ok(FIG_2_12, 0.8);
    // Lines 5-13 (N130-N210) are offset mode: every point 0.8 mm outside.
    check_path(&real(&r), 6..=13, 0.8);
}

#[test]
fn the_feed_is_tangential_in_the_polar_plane() {
    let r = ok(FIG_2_12, 0.0);
    let pts = real(&r);
    for w in pts.windows(2).filter(|w| w[1].0 >= 5 && w[1].0 <= 13 && w[0].0 >= 4) {
        let (a, b) = (w[0], w[1]);
        let cart_len = {
            let (p, q) = (cart(a.1, a.2), cart(b.1, b.2));
            (q.0 - p.0).hypot(q.1 - p.1)
        };
        // The planner measures X in mm and C in degrees alike.
        let planner_len = (b.1 - a.1).hypot(b.2 - a.2);
        let time_min = planner_len / b.3;
        assert!((cart_len / time_min - 200.0).abs() < 0.5, "{a:?} -> {b:?}: {} mm/min", cart_len / time_min);
    }
}

#[test]
fn alarms_of_2_7() {
    let cases: &[(&str, u32, u16)] = &[
        // Note 4: G00 in polar interpolation.
        ("G00 X60 C0\nG12.1\nG00 X40\nM30\n", 3, 4045),
        ("G00 X60 C0\nG12.1\nG28 U0\nM30\n", 3, 4045),
        // Note 6: R only.
        ("G00 X60 C0\nG12.1\nG02 X40 C10 I5 F100\nM30\n", 3, 4046),
        // Note 8: not under G41/G42.
        ("G00 X60 C0\nG42 G01 X50 F100\nG12.1\nM30\n", 3, 37),
        // Alone in its block.
        ("G00 X60 C0\nG12.1 G01 X40\nM30\n", 2, 4016),
    ];
    for &(text, line, code) in cases {
        let r = run_with(text, machine(0.0), Panel::default());
        assert_eq!(r.alarm_codes().first(), Some(&(line, code)), "{text}");
    }
    // A machine without a C axis cannot interpolate in polar coordinates.
    let r = run_with("G12.1\nM30\n", MachineConfig::default(), Panel::default());
    assert_eq!(r.alarm_codes(), vec![(1, 9)]);
}

#[test]
fn the_polar_example_runs_on_a_machine_with_a_c_axis() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/c_axis/polar_g12_1.nc");
    let text = std::fs::read_to_string(path).unwrap();
    let r = ok(&text, 0.8);
    assert!(matches!(r.actions.last().map(|c| c.action), Some(Action::End { rewind: true })));
}

/// A block's other actions keep their place around the polar moves (the moves leave
/// the block's outbox, the rest stays in order: `cycles::polar_block`): a spindle
/// start staged before the block's move comes before the first X/C move, an M05
/// after it comes after the last, exactly as the same block does outside G12.1.
#[test]
fn actions_of_a_polar_block_stay_before_and_after_its_moves() {
    let order = |text: &str| -> Vec<&'static str> {
        let r = ok(text, 0.0);
        let mut out = Vec::new();
        for c in r.actions.iter().filter(|c| c.line == 4) {
            let k = match c.action {
                Action::Linear(_) | Action::Rapid(_) => "move",
                _ => "other",
            };
            if out.last() != Some(&k) {
                out.push(k);
            }
        }
        out
    };
    let polar = order("G98 G00 X60 C0 Z0\nG12.1\nG01 X40 F100\nG01 X20 C10 S300 M05\nG13.1\nM30\n");
    let plain = order("G98 G00 X60 C0 Z0\nG01 X40 F100\nM03 S300\nG01 X20 C10 S300 M05\nM30\n");
    assert!(polar.contains(&"move") && polar.contains(&"other"), "{polar:?}");
    assert_eq!(polar, plain);
}

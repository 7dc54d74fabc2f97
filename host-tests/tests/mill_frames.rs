//! A machining centre's programmable transformations (seed 004 @4094–@5360):
//! G15/G16 polar coordinates, G50/G51 scaling, G50.1/G51.1 mirror image, G68/G69
//! rotation, in the seed's order (scaling before rotation) and FANUC's (mirror
//! first). Every expected point is computed here from the seed's formulas.

mod mill_common;

use host_tests::{Run, run_with};
use interp_core::Panel;
use interp_core::canon::{Action, Canon};
use mill_common::{alarms, go, mill};

/// Work end point (X, Y) mm of a motion action.
fn xy(c: &Canon) -> Option<(f64, f64)> {
    c.action.endpoint().map(|e| (e.work.0[0] as f64 / 1e6, e.work.0[1] as f64 / 1e6))
}

/// The (X, Y) end points of the moves of lines `lines`.
fn points(r: &Run, lines: core::ops::RangeInclusive<u32>) -> Vec<(f64, f64)> {
    r.actions.iter().filter(|c| lines.contains(&c.line)).filter_map(xy).collect()
}

fn near(a: &[(f64, f64)], b: &[(f64, f64)]) {
    assert_eq!(a.len(), b.len(), "{a:?} vs {b:?}");
    for (p, q) in a.iter().zip(b) {
        assert!((p.0 - q.0).abs() < 1.5e-6 && (p.1 - q.1).abs() < 1.5e-6, "{a:?} vs {b:?}");
    }
}

fn polar(r: f64, deg: f64) -> (f64, f64) {
    let a = deg.to_radians();
    (r * a.cos(), r * a.sin())
}

/// Seed 004 @4182–@4265: in G17, X is the radius and Y the angle, counter-clockwise
/// from +X; point A is X50.0 Y30.0.
#[test]
fn g16_point_a_radius_and_angle() {
    let r = go("G00 X0 Y0 Z10.\nG16\nG01 X50.0 Y30.0 F200\nY-30.\nG15\nG01 X0 Y0\nM30\n");
    near(&points(&r, 3..=4), &[polar(50.0, 30.0), polar(50.0, -30.0)]);
    near(&points(&r, 6..=6), &[(0.0, 0.0)]);
}

/// A bolt circle drilled with G16 (FANUC's bolt-hole example): radius 100, holes at
/// 30°, 150°, 270° with absolute angles, and again with G91 angle increments of
/// 120° (the radius kept from the first hole).
#[test]
fn g16_bolt_circle_with_absolute_and_incremental_angles() {
    let want = [polar(100.0, 30.0), polar(100.0, 150.0), polar(100.0, 270.0)];
    let holes = |r: &Run| -> Vec<(f64, f64)> {
        // The feed moves are the holes: their X/Y.
        r.actions.iter().filter(|c| matches!(c.action, Action::Linear(_))).filter_map(xy).collect()
    };
    let r = go(
        "G00 X0 Y0 Z30.\nM03 S1000\nG17 G90 G16\nG81 X100.0 Y30.0 Z-20.0 R-5.0 F200.0\nY150.0\nY270.0\nG15 G80\nM30\n",
    );
    near(&holes(&r), &want);
    let r = go(
        "G00 X0 Y0 Z30.\nM03 S1000\nG17 G90 G16\nG81 X100.0 Y30.0 Z-20.0 R-5.0 F200.0\nG91 Y120.0\nY120.0\nG90 G15 G80\nM30\n",
    );
    near(&holes(&r), &want);
}

/// Seed 004 @4330, @4336: under G91 the radius is measured from the current point
/// and the angle adds to the last one (here 0°: where G16 found the tool).
#[test]
fn g16_incremental_radius_from_the_current_point() {
    let r = go("G00 X10. Y0 Z10.\nG16\nG91 G01 X20. Y90. F100\nX10. Y-90.\nG90 G15\nM30\n");
    near(&points(&r, 3..=4), &[(10.0, 20.0), (20.0, 20.0)]);
    assert_eq!(alarms("G16\nG02 X10. Y90. I5. F100\nM30\n"), vec![(2, 4046)], "G16 arcs take R");
}

/// Seed 004 @4506: G51 X Y Z P scales about XYZ by P (0.001–999.999): a square
/// ABCD becomes abcd about O. P1500 and P1.5 are both 1.5; incremental moves
/// scale as well.
#[test]
fn g51_p_scales_about_the_centre() {
    let sq = "G01 X10. Y10. F300\nX90.\nY90.\nX10.\nY10.\n";
    let r = go(&format!("G00 X0 Y0 Z10.\nG51 X50. Y50. P500\n{sq}G50\nG00 X0 Y0\nM30\n"));
    let s = |p: f64| 50.0 + (p - 50.0) * 0.5;
    near(
        &points(&r, 3..=7),
        &[(s(10.0), s(10.0)), (s(90.0), s(10.0)), (s(90.0), s(90.0)), (s(10.0), s(90.0)), (s(10.0), s(10.0))],
    );
    near(&points(&r, 9..=9), &[(0.0, 0.0)]);
    let r = go("G00 X0 Y0 Z10.\nG51 X0 Y0 P1.5\nG91 G01 X10. F300\nX10.\nG90 G50\nM30\n");
    near(&points(&r, 3..=4), &[(15.0, 0.0), (30.0, 0.0)]);
}

/// Seed 004 @4740: G51 I J K per axis (thousandths, no decimal point), negative
/// factors mirror: the arc turns the other way.
#[test]
fn g51_ijk_per_axis_and_negative_mirrors() {
    let r = go("G00 X0 Y0 Z10.\nG51 X0 Y0 I2000 J-500\nG01 X10. Y10. F300\nG02 X20. Y0 R10.\nG50\nM30\n");
    near(&points(&r, 3..=4), &[(20.0, -5.0), (40.0, 0.0)]);
    // R takes the larger factor (FANUC): 10 × 2 = 20; one axis mirrored: G02 runs as G03.
    match r.actions.iter().find(|c| c.line == 4).map(|c| c.action) {
        Some(Action::Arc(a)) => assert!(!a.cw, "mirrored by J-500"),
        other => panic!("{other:?}"),
    }
    // FANUC's example: G51 I2000 J1000, G02 X100 Y0 R100 from X0 Y100 is G02 X200 Y0 R200.
    let r = go("G00 X0 Y100. Z10.\nG51 X0 Y0 Z0 I2000 J1000\nG02 X100.0 Y0 R100.0 F500\nG50\nM30\n");
    let Some(Action::Arc(a)) = r.actions.iter().find(|c| c.line == 3).map(|c| c.action) else { panic!() };
    let (cx, cy) = (a.center.work.0[0] as f64 / 1e6, a.center.work.0[1] as f64 / 1e6);
    let rs = ((0.0 - cx).powi(2) + (100.0 - cy).powi(2)).sqrt();
    let re = ((200.0 - cx).powi(2) + (0.0 - cy).powi(2)).sqrt();
    assert!((rs - 200.0).abs() < 1e-5 && (re - 200.0).abs() < 1e-5, "R200: {rs} {re}");
    // With I/J the radii at start and end differ: FANUC's tolerance alarm (0020).
    assert_eq!(alarms("G00 X0 Y100.\nG51 X0 Y0 I2000 J1000\nG02 X100. Y0 I0 J-100. F500\nM30\n"), vec![(3, 20)]);
}

#[test]
fn g51_factor_range_and_form() {
    for (text, code) in [
        ("G51 X0 Y0 P0\n", 142),
        ("G51 X0 Y0 P1000000\n", 142),
        ("G51 X0 Y0 I10000\n", 142),
        ("G51 X0 Y0 I0\n", 142),
        ("G51 X0 Y0 I1.5\n", 7),
        ("G51 X0 Y0\n", 4006),
        ("G51 X0 Y0 P2000 I2000\n", 4005),
        ("G51 G01 X0 Y0 P2000\n", 4016),
    ] {
        assert_eq!(alarms(&format!("{text}M30\n")), vec![(1, code)], "{text}");
    }
}

/// Seed 004 @5030: G68 X0 Y0 R20. rotates 20° counter-clockwise about the origin,
/// clockwise; G69 cancels.
#[test]
fn g68_rotates_about_the_centre() {
    let rot = |p: (f64, f64), deg: f64| {
        let (s, c) = deg.to_radians().sin_cos();
        (p.0 * c - p.1 * s, p.0 * s + p.1 * c)
    };
    let sq = [(40.0, 0.0), (40.0, 20.0), (0.0, 20.0), (0.0, 0.0)];
    let prog = "G01 X40. Y0 F300\nY20.\nX0\nY0\n";
    for deg in [20.0, -20.0] {
        let r = go(&format!("G00 X0 Y0 Z10.\nG68 X0 Y0 R{deg:.1}\n{prog}G69\nG00 X40. Y0\nM30\n"));
        near(&points(&r, 3..=6), &sq.map(|p| rot(p, deg)));
        near(&points(&r, 8..=8), &[(40.0, 0.0)]);
    }
    // About X10 Y10, and G91 R adds to the rotation in force.
    let r = go("G00 X10. Y10. Z10.\nG68 X10. Y10. R45.\nG91 G68 X10. Y10. R45.\nG90 G01 X20. Y10. F300\nG69\nM30\n");
    near(&points(&r, 4..=4), &[(10.0, 20.0)]);
    assert_eq!(alarms("G68 X0 Y0\nM30\n"), vec![(1, 4006)]);
    assert_eq!(alarms("G68 X0 Y0 R10.\nG18\nM30\n"), vec![(2, 212)]);
}

/// Seed 004 @5293: with scaling, scaling comes first, then rotation; FANUC scales
/// the rotation centre too, not the angle.
#[test]
fn scaling_then_rotation() {
    let r = go("G00 X0 Y0 Z10.\nG51 X0 Y0 P2000\nG68 X5. Y0 R90.\nG01 X10. Y0 F300\nG69\nG50\nM30\n");
    // S(10, 0) = (20, 0); the centre S(5, 0) = (10, 0); 90° about it: (10, 10).
    near(&points(&r, 4..=4), &[(10.0, 10.0)]);
    assert_eq!(alarms("G68 X0 Y0 R10.\nG51 X0 Y0 P2000\nM30\n"), vec![(2, 4051)]);
    assert_eq!(alarms("G51 X0 Y0 P2000\nG51.1 X0\nM30\n"), vec![(2, 4051)]);
}

/// G51.1 mirror image about the positions given: G02 turns into G03 for one axis
/// mirrored, and back for two; G50.1 cancels.
#[test]
fn g51_1_mirror_reverses_arcs() {
    let r = go("G00 X0 Y0 Z10.\nG51.1 X50.\nG01 X10. Y10. F300\nG02 X20. Y0 R10.\nG50.1 X0\nG00 X0 Y0\nM30\n");
    near(&points(&r, 3..=4), &[(90.0, 10.0), (80.0, 0.0)]);
    let cw: Vec<bool> = r
        .actions
        .iter()
        .filter_map(|c| match c.action {
            Action::Arc(a) => Some(a.cw),
            _ => None,
        })
        .collect();
    assert_eq!(cw, vec![false]);
    let r = go("G00 X0 Y0 Z10.\nG51.1 X0 Y0\nG01 X10. Y10. F300\nG02 X20. Y0 R10.\nG50.1\nM30\n");
    near(&points(&r, 3..=4), &[(-10.0, -10.0), (-20.0, 0.0)]);
    assert!(r.actions.iter().any(|c| matches!(c.action, Action::Arc(a) if a.cw)), "two axes: G02 stays G02");
}

/// The transformations come before the soft limits: a scaled move past the travel
/// is refused (0500/0501) and nothing moves; a transformation cannot change while
/// cutter compensation is in force (4049).
#[test]
fn transformed_points_meet_the_soft_limits_and_cutter_comp_rules() {
    // G54 X-300: work X300 is machine 0, the + limit; scaled ×2 about 0, X160 is 320.
    let r = run_with("G00 X0 Y0 Z10.\nG51 X0 Y0 P2000\nG01 X160. F300\nM30\n", mill(), Panel::default());
    assert_eq!(r.alarm_codes(), vec![(3, 500)]);
    assert!(r.actions.iter().all(|c| c.line != 3));
    assert_eq!(alarms("G00 X0 Y0 Z10.\nG41 D1 G01 X10. F300\nG51 X0 Y0 P2000\nM30\n"), vec![(3, 4049)]);
}

//! A machining centre's cutter radius compensation G40/G41/G42 with D (FANUC 0i-M;
//! the seed names it only, @5212): the lathe's nose compensation in the selected
//! plane with the radius of D. The cutter centre stays exactly D from the
//! programmed contour on every segment (distances computed here), outer corners
//! are lengthened to the tangents' crossing (FANUC's 90° ≤ α < 180°), inner ones
//! cut short; plunges and retracts along Z between compensated moves are made at
//! the corner; an overcut is alarm 3605 and the faulty move does not run.

mod mill_common;

use host_tests::{Run, run_with};
use interp_core::Panel;
use interp_core::canon::{Action, Canon};
use mill_common::{go, mill};

/// Work (X, Y, Z) mm.
fn xyz(c: &Canon) -> Option<[f64; 3]> {
    c.action.endpoint().map(|e| [0, 1, 2].map(|i| e.work.0[i] as f64 / 1e6))
}

/// Signed distance of `p` from the line through `a` and `b`, positive on its left.
fn left_of(a: (f64, f64), b: (f64, f64), p: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    ((p.1 - a.1) * dx - (p.0 - a.0) * dy) / (dx * dx + dy * dy).sqrt()
}

/// The programmed rectangle: start-up to (0, 0), up to (0, 30), right to (40, 30),
/// down to (40, 0), back to (0, 0), cancel to (−20, −20). G41 D1 (5 mm): the
/// cutter outside, on the left of travel.
const RECT: &str =
    "G00 X-20. Y-20. Z10.\nG41 D1 X0 Y0\nG01 Z-5. F100\nM08\nY30. F300\nX40.\nY0\nX0\nG00 Z10.\nG40 X-20. Y-20.\nM30\n";

/// Every contour segment is the programmed one moved 5 mm to its left: both ends
/// of each compensated move lie on the line 5 mm left of its programmed edge;
/// the outer corners are the tangents' crossings (−5, 35), (45, 35), (45, −5).
#[test]
fn rectangle_offset_exactly_by_d_with_lengthened_outer_corners() {
    let r = go(RECT);
    let edges = [
        (5, (0.0, 0.0), (0.0, 30.0)),
        (6, (0.0, 30.0), (40.0, 30.0)),
        (7, (40.0, 30.0), (40.0, 0.0)),
        (8, (40.0, 0.0), (0.0, 0.0)),
    ];
    let mut from = None;
    for c in &r.actions {
        let Some(p) = xyz(c) else { continue };
        if let Some(&(_, a, b)) = edges.iter().find(|e| e.0 == c.line) {
            let s: [f64; 3] = from.expect("a move before");
            for q in [(s[0], s[1]), (p[0], p[1])] {
                let d = left_of(a, b, q);
                assert!((d - 5.0).abs() < 1e-6, "line {}: {q:?} is {d} from its edge", c.line);
            }
            assert_eq!(p[2], -5.0);
        }
        from = Some(p);
    }
    let corners: Vec<[f64; 3]> = r.actions.iter().filter(|c| (5..=7).contains(&c.line)).filter_map(xyz).collect();
    for (got, want) in corners.iter().zip([[-5.0, 35.0], [45.0, 35.0], [45.0, -5.0]]) {
        assert!((got[0] - want[0]).abs() < 1e-6 && (got[1] - want[1]).abs() < 1e-6, "{corners:?}");
    }
}

/// The plunge (Z-5), the M08 and the retract (Z10) between compensated moves wait
/// behind the held move and are made at the corner: the plunge where the start-up
/// move meets the first edge's offset, the retract where the last edge meets the
/// cancel move's. Start-up and cancel follow the corner rules with the start-up
/// and cancel lines' offsets.
#[test]
fn plunge_and_retract_between_compensated_moves_are_made_at_the_corner() {
    let r = go(RECT);
    let at = |line: u32| r.actions.iter().find(|c| c.line == line).and_then(xyz).unwrap();
    let plunge = at(3);
    let startup = at(2);
    assert_eq!([plunge[0], plunge[1]], [startup[0], startup[1]], "the plunge stays where the start-up ended");
    assert_eq!(plunge[2], -5.0);
    // The start-up line (−20,−20)→(0,0) offset 5 to its left meets x = −5 at
    // y = −5 + 5√2 (an inner corner of the two offsets).
    let y = -5.0 + 5.0 * 2f64.sqrt();
    assert!((startup[0] + 5.0).abs() < 1e-6 && (startup[1] - y).abs() < 1e-6, "{startup:?}");
    let names = host_tests::kind_names(&r);
    let m08 = names.iter().position(|n| n == "M08").unwrap();
    assert!(names[..m08].iter().filter(|n| n.starts_with("linear")).count() == 1, "M08 after the plunge: {names:?}");
    let retract = at(9);
    let last = r.actions.iter().filter(|c| c.line == 8).filter_map(xyz).next_back().unwrap();
    assert_eq!([retract[0], retract[1]], [last[0], last[1]]);
    assert_eq!(retract[2], 10.0);
    let cancel = at(10);
    assert_eq!(cancel, [-20.0, -20.0, 10.0]);
}

/// An arc of the contour: its offset is the concentric arc, R − D inside (the
/// cutter right of a clockwise arc, G42) or R + D outside (G41).
#[test]
fn arc_offset_is_concentric() {
    for (side, r_off, end_y) in [("G42", 5.0, 25.0), ("G41", 15.0, 35.0)] {
        let text = format!(
            "G00 X-20. Y0 Z-5.\n{side} D1 G01 X0 Y0 F300\nY20.\nG02 X10. Y30. R10.\nG01 X40.\nG40 X50. Y50.\nM30\n"
        );
        let r = go(&text);
        let a = r
            .actions
            .iter()
            .find_map(|c| match c.action {
                Action::Arc(a) if c.line == 4 => Some(a),
                _ => None,
            })
            .expect("the arc");
        let (cx, cy) = (a.center.work.0[0] as f64 / 1e6, a.center.work.0[1] as f64 / 1e6);
        assert!((cx - 10.0).abs() < 1e-6 && (cy - 20.0).abs() < 1e-6, "{side}");
        let (ex, ey) = (a.to.work.0[0] as f64 / 1e6, a.to.work.0[1] as f64 / 1e6);
        assert!((((ex - cx).powi(2) + (ey - cy).powi(2)).sqrt() - r_off).abs() < 1e-6, "{side}");
        assert!((ex - 10.0).abs() < 1e-6 && (ey - end_y).abs() < 1e-6, "{side}: ({ex}, {ey})");
    }
}

/// A groove narrower than the cutter: the groove bottom's offset runs against it
/// (interference, alarm 3605); the machine stops before that move: nothing of the
/// groove bottom is cut.
#[test]
fn interference_is_an_alarm_and_the_faulty_move_does_not_run() {
    let text = "G00 X-10. Y10. Z-5.\nG41 D1 G01 X0 Y0 F300\nX20.\nY-4.\nX24.\nY0\nX50.\nG40 X60. Y10.\nM30\n";
    let r = run_with(text, mill(), Panel::default());
    let first = r.alarms.first().expect("an alarm");
    assert_eq!(first.code(), 3605);
    assert_eq!(first.line, 5, "the groove bottom X24 is the faulty move");
    assert!(r.actions.iter().all(|c| c.line != 5 || c.action.endpoint().is_none()), "X24 cut nothing");
}

/// D2 (4 mm − 0.02 wear) in the middle of a contour: the held move ends on its
/// normal with 5 mm, the following ones are offset by 3.98 mm.
#[test]
fn a_new_d_changes_the_radius_from_its_block() {
    let r = go("G00 X-20. Y0 Z-5.\nG41 D1 G01 X0 Y0 F300\nX20.\nD2 X40.\nX60.\nG40 X70. Y-10.\nM30\n");
    let y = |line: u32| r.actions.iter().filter(|c| c.line == line).filter_map(xyz).next_back().unwrap()[1];
    assert!((y(3) - 5.0).abs() < 1e-6);
    assert!((y(5) - 3.98).abs() < 1e-6, "{}", y(5));
}

/// G51.1 mirrors the contour and swaps G41 and G42: the cutter stays outside.
#[test]
fn mirror_swaps_g41_and_g42() {
    let plain = go(RECT);
    let mirrored = go(&format!("G51.1 X0\n{}", RECT.replace("M30\n", "G50.1\nM30\n")));
    let pts = |r: &Run| -> Vec<(f64, f64)> {
        r.actions.iter().filter(|c| c.action.endpoint().is_some()).filter_map(xyz).map(|p| (p[0], p[1])).collect()
    };
    let (a, b) = (pts(&plain), pts(&mirrored));
    assert_eq!(a.len(), b.len());
    for (p, q) in a.iter().zip(&b) {
        assert!((p.0 + q.0).abs() < 1e-6 && (p.1 - q.1).abs() < 1e-6, "{a:?}\n{b:?}");
    }
}

/// G68 rotates the contour before the compensation: each rotated edge's offset is
/// still 5 mm to its left.
#[test]
fn rotation_before_compensation() {
    let r = go(&format!("G68 X0 Y0 R30.\n{}", RECT.replace("M30\n", "G69\nM30\n")));
    let rot = |p: (f64, f64)| {
        let (s, c) = 30f64.to_radians().sin_cos();
        (p.0 * c - p.1 * s, p.0 * s + p.1 * c)
    };
    let edges = [(6, (0.0, 30.0), (40.0, 30.0)), (7, (40.0, 30.0), (40.0, 0.0))];
    for (line, a, b) in edges {
        let p = r.actions.iter().filter(|c| c.line == line).filter_map(xyz).next_back().unwrap();
        let d = left_of(rot(a), rot(b), (p[0], p[1]));
        assert!((d - 5.0).abs() < 1e-6, "line {line}: {d}");
    }
}

#[test]
fn tool_change_and_reference_return_in_compensation() {
    let r = run_with("G00 X-20. Y0 Z-5.\nG41 D1 G01 X0 Y0 F300\nT2 M06\nM30\n", mill(), Panel::default());
    assert_eq!(r.alarm_codes().first(), Some(&(3, 3577)));
    // G28 in G41: a temporary cancel (FANUC), the offset starts up again after.
    go("G00 X-20. Y0 Z-5.\nG41 D1 G01 X0 Y0 F300\nX20.\nG28 Z0\nG29 Z-5.\nX40.\nG40 X50.\nM30\n");
}

//! Tool-nose radius compensation G40/G41/G42 (2.18): the nose centre stays exactly
//! one radius from the programmed contour on every segment (distances computed
//! here, independently of the interpreter's geometry), corners of the manual's
//! three types, imaginary tip directions, start-up and cancel, and the alarms.

use host_tests::{Run, mm, run_with};
use interp_core::canon::{Action, Canon};
use interp_core::{MachineConfig, Panel};

const R: f64 = 0.8;

/// The default machine with offset 1: nose radius 0.8 mm, tip direction `tip`.
fn machine(tip: u8) -> MachineConfig {
    let mut cfg = MachineConfig::default();
    let row = cfg.tools.get_mut(1).unwrap();
    row.radius = mm(R);
    row.tip = tip;
    cfg
}

fn ok(text: &str, tip: u8) -> Run {
    let r = run_with(text, machine(tip), Panel::default());
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    r
}

/// (Z, X radius) mm of a machine point (X internal radius).
fn zr(e: &interp_core::canon::Endpoint) -> (f64, f64) {
    (e.machine.0[2] as f64 / 1e6, e.machine.0[0] as f64 / 1e6)
}

/// The tip vector (Z, X radius) of direction `tip`, mm.
fn tip_vec(tip: u8) -> (f64, f64) {
    let (x, z) = match tip {
        1 => (1.0, 1.0),
        2 => (1.0, -1.0),
        3 => (-1.0, -1.0),
        4 => (-1.0, 1.0),
        5 => (0.0, 1.0),
        6 => (1.0, 0.0),
        7 => (0.0, -1.0),
        8 => (-1.0, 0.0),
        _ => (0.0, 0.0),
    };
    (z * R, x * R)
}

/// A move of the tool: end point and, for arcs, the centre and direction.
#[derive(Debug, Clone, Copy)]
struct Mv {
    end: (f64, f64),
    arc: Option<((f64, f64), bool)>,
    line: u32,
}

/// The machine moves as nose-centre moves (tip vector taken off).
fn centre_moves(r: &Run, tip: u8) -> Vec<Mv> {
    let t = tip_vec(tip);
    let sub = |p: (f64, f64)| (p.0 - t.0, p.1 - t.1);
    r.actions
        .iter()
        .filter_map(|c: &Canon| match c.action {
            Action::Rapid(m) | Action::Linear(m) => Some(Mv { end: sub(zr(&m.to)), arc: None, line: c.line }),
            Action::Arc(a) => Some(Mv { end: sub(zr(&a.to)), arc: Some((sub(zr(&a.center)), a.cw)), line: c.line }),
            _ => None,
        })
        .collect()
}

fn dist(p: (f64, f64), q: (f64, f64)) -> f64 {
    (p.0 - q.0).hypot(p.1 - q.1)
}

/// Distance from `p` to the infinite line through `a`, `b`.
fn line_dist(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    ((p.0 - a.0) * dy - (p.1 - a.1) * dx).abs() / dx.hypot(dy)
}

fn near(a: (f64, f64), b: (f64, f64)) -> bool {
    dist(a, b) < 2e-6
}

/// The OD profile: face up from the centre, Ø20 to Z-20, shoulder, Ø40 to Z-40.
const OD: &str = "T0101\nG00 X0 Z5\nG42 G01 Z0 F0.1\nX20\nZ-20\nX40\nZ-40\nG40 G00 X60\nM30\n";

#[test]
fn od_profile_with_tip_0_inner_corners_shorten_outer_corners_lengthen() {
    let r = ok(OD, 0);
    let m: Vec<_> = centre_moves(&r, 0).iter().map(|m| m.end).collect();
    let expect = [
        (5.0, 0.0),
        (R, R),        // start-up: shortened to the crossing with the face's offset
        (R, 10.0 + R), // face, lengthened (α = 90°) to the crossing of the tangents
        (-20.0 + R, 10.0 + R),
        (-20.0 + R, 20.0 + R),
        (-40.0 + R, 20.0 + R), // shortened by the cancel line's offset
        (-40.0, 30.0),         // cancel: back on the programmed point
    ];
    assert_eq!(m.len(), expect.len(), "{m:?}");
    for (a, b) in m.iter().zip(expect) {
        assert!(near(*a, b), "{a:?} vs {b:?}");
    }
}

#[test]
fn tip_3_puts_the_imaginary_tip_on_faces_and_diameters() {
    // Tip 3 (−X −Z from the centre): on faces and diameters the imaginary tip
    // runs exactly on the programmed points.
    let r = ok(OD, 3);
    let pts: Vec<_> = r.actions.iter().filter_map(host_tests::xz).collect();
    assert_eq!(pts[1..6], [(0.0, 0.0), (20.0, 0.0), (20.0, -20.0), (40.0, -20.0), (40.0, -40.0)]);
}

/// Checks that every move of `r` between `from_line` and `to_line` (offset mode,
/// not start-up, cancel or corner lines) keeps its nose centre exactly R from
/// its programmed segment, given here as (start, end, arc centre) in (Z, r).
type Seg = ((f64, f64), (f64, f64), Option<(f64, f64)>);

fn assert_offset(moves: &[Mv], line: u32, seg: Seg, start: (f64, f64)) -> (f64, f64) {
    let own: Vec<&Mv> = moves.iter().filter(|m| m.line == line).collect();
    let first = own[0];
    match seg.2 {
        None => {
            assert!((line_dist(start, seg.0, seg.1) - R).abs() < 1e-5, "start {start:?} of line {line}");
            assert!((line_dist(first.end, seg.0, seg.1) - R).abs() < 1e-5, "end {:?} of line {line}", first.end);
        }
        Some(c) => {
            let (ac, _) = first.arc.expect("an arc");
            assert!(near(ac, c), "arc centre of line {line}: {ac:?}");
            let r = dist(seg.0, c);
            let ro = dist(first.end, c);
            assert!(((ro - r).abs() - R).abs() < 1e-5, "arc of line {line}: radius {ro} vs {r}");
            assert!((dist(start, c) - ro).abs() < 1e-5);
        }
    }
    own.last().unwrap().end
}

#[test]
fn taper_and_arcs_stay_one_radius_from_the_contour() {
    // G42 along an OD: Ø20 to Z-10, taper to Ø30 at Z-20, G02 R5 to Ø40 Z-25
    // (centre Z-20 r20), G03 R5 to Ø50 Z-30 (centre Z-30 r20), then along Ø50 to
    // Z-45 and cancel.
    let prog = "T0101\nG00 X20 Z5\nG42 G01 Z0 F0.1\nZ-10\nX30 Z-20\nG02 X40 Z-25 R5\nG03 X50 Z-30 R5\nG01 Z-45\nG40 G00 X70\nM30\n";
    for tip in [0, 3] {
        let r = ok(prog, tip);
        let mv = centre_moves(&r, tip);
        // Line numbers: 4 Z-10, 5 taper, 6 G02, 7 G03, 8 Z-45.
        let segs: [(u32, Seg); 5] = [
            (4, ((0.0, 10.0), (-10.0, 10.0), None)),
            (5, ((-10.0, 10.0), (-20.0, 15.0), None)),
            (6, ((-20.0, 15.0), (-25.0, 20.0), Some((-20.0, 20.0)))),
            (7, ((-25.0, 20.0), (-30.0, 25.0), Some((-30.0, 20.0)))),
            (8, ((-30.0, 25.0), (-45.0, 25.0), None)),
        ];
        let mut start = mv.iter().find(|m| m.line == 3).unwrap().end;
        for (line, seg) in segs {
            start = assert_offset(&mv, line, seg, start);
        }
    }
}

#[test]
fn insertion_at_a_sharp_outer_corner_extends_both_moves_by_r() {
    // G41 (tool below the path): along -Z at r10, then back up-right to (Z-5, r20):
    // an outer corner with α ≈ 63° < 90°.
    let r = ok("T0101\nG00 X20 Z5\nG41 G01 Z0 F0.1\nZ-10\nX40 Z-5\nG40 G00 X60\nM30\n", 0);
    let mv = centre_moves(&r, 0);
    let own: Vec<_> = mv.iter().filter(|m| m.line == 4).map(|m| m.end).collect();
    // o1 at r = 10 - R ends at Z-10; + R along -Z.
    assert!(near(own[0], (-10.0 - R, 10.0 - R)), "{own:?}");
    // Then to o2's start - R·t2: t2 = (5, 10)/√125, o2's normal on the left is (-10, 5)/√125.
    let s = 125f64.sqrt();
    let (t2, n2) = ((5.0 / s, 10.0 / s), (-10.0 / s, 5.0 / s));
    let o2s = (-10.0 + R * n2.0, 10.0 + R * n2.1);
    assert!(near(own[1], (o2s.0 - R * t2.0, o2s.1 - R * t2.1)), "{own:?}");
    // The taper itself runs on its offset line from there.
    let taper = mv.iter().find(|m| m.line == 5).unwrap();
    assert!((line_dist(taper.end, (-10.0, 10.0), (-5.0, 20.0)) - R).abs() < 1e-6);
}

#[test]
fn blocks_without_motion_keep_their_place_after_the_held_move() {
    let r = ok("T0101\nG00 X0 Z5\nG42 G01 Z0 F0.1\nM08\nG04 P100\nX20\nG40 G00 X40 Z5\nM30\n", 0);
    let kinds = host_tests::kind_names(&r);
    let i = kinds.iter().position(|k| k == "M08").unwrap();
    assert_eq!(kinds[i - 1], "linear", "{kinds:?}");
    assert_eq!(kinds[i + 1], "dwell 100");
    assert_eq!(kinds[i + 2], "linear");
}

#[test]
fn g28_cancels_the_offset_for_its_moves_and_the_next_move_starts_up() {
    let prog = "T0101\nG00 X0 Z5\nG42 G01 Z0 F0.1\nX20\nG28 U0\nG00 X30 Z-10\nG01 Z-20\nX40\nG40 G00 X60\nM30\n";
    let r = ok(prog, 0);
    let mv = centre_moves(&r, 0);
    // The held facing move runs before the G28 move (not after it, from the
    // reference point back to the part).
    let lines: Vec<u32> = mv.iter().map(|m| m.line).collect();
    assert!(lines.windows(2).all(|w| w[0] <= w[1]), "{lines:?}");
    // The facing move ends on its normal (Z+R); the G28 move is not offset.
    let face = mv.iter().rfind(|m| m.line == 4).unwrap();
    assert!(near(face.end, (R, 10.0)), "{face:?}");
    let g28 = mv.iter().rfind(|m| m.line == 5).unwrap();
    assert!((g28.end.0 - 0.0).abs() < 1e-9, "the G28 move keeps the programmed Z: {g28:?}");
    // The next move starts the offset up again: the Ø30 cut runs at r15 + R.
    let cut = mv.iter().rfind(|m| m.line == 7).unwrap();
    assert!((cut.end.1 - (15.0 + R)).abs() < 1e-6, "{cut:?}");
}

#[test]
fn g70_finishes_compensated_and_g71_roughs_the_programmed_shape() {
    let prog = "T0101\nG00 X42 Z2\nG71 U1 R0.5 F0.2\nG71 P10 Q20 U0 W0\nN10 G42 G00 X20\nG01 Z-10\nX40 Z-20\nN20 G40 X42\nG70 P10 Q20\nM30\n";
    let r = ok(prog, 0);
    // Roughing (line 4) ends on the programmed taper: points with r = 10 + (−z − 10)/2.
    let rough: Vec<_> = centre_moves(&r, 0).into_iter().filter(|m| m.line == 4).collect();
    assert!(
        rough
            .iter()
            .any(|m| (m.end.0 < -10.0 && m.end.0 > -20.0) && (m.end.1 - (10.0 + (-m.end.0 - 10.0))).abs() < 1e-6)
    );
    // Finishing (line 9): the taper move's nose centre lies R off the taper.
    let fin: Vec<_> = centre_moves(&r, 0).into_iter().filter(|m| m.line == 9).collect();
    let on_taper = fin.iter().filter(|m| (line_dist(m.end, (-10.0, 10.0), (-20.0, 20.0)) - R).abs() < 1e-6).count();
    assert!(on_taper >= 1, "{fin:?}");
}

#[test]
fn alarms_of_2_18() {
    let cases: &[(&str, u32, u16)] = &[
        ("T0101\nG00 X0 Z5\nG42 G01 Z0 F0.1\nG41 X20\nM30\n", 4, 3576),
        ("T0101\nG00 X0 Z5\nG42 G01 Z0 F0.1\nT0202\nM30\n", 4, 3577),
        ("T0101\nG00 X20 Z5\nG42 G02 X30 Z0 R5 F0.1\nM30\n", 3, 34),
        ("T0101\nG00 X20 Z5\nG42 G01 Z0 F0.1\nG40 G02 X30 Z-5 R5\nM30\n", 4, 34),
        ("T0101\nG00 X20 Z5\nG42 G01 Z0 F0.1\nG17 X30\nM30\n", 4, 37),
        // An inside arc smaller than the nose (R0.5 < 0.8): the nose cannot follow it.
        ("T0101\nG00 X20 Z5\nG41 G01 Z0 F0.1\nZ-10\nG03 X21 Z-10.5 R0.5\nG01 Z-20\nG40 X40\nM30\n", 5, 3605),
        // A groove 1 mm wide is narrower than the nose (1.6 mm): the groove bottom's
        // offset runs backwards, found when the block after it is read; the alarm
        // names the groove bottom.
        ("T0101\nG00 X40 Z5\nG42 G01 Z0 F0.1\nZ-10\nX30\nZ-11\nX40\nZ-20\nG40 X60\nM30\n", 6, 3605),
        // Going straight back: no corner angle left (α < 0.1°).
        ("T0101\nG00 X20 Z5\nG42 G01 Z0 F0.1\nZ-10\nZ0\nM30\n", 5, 3607),
        // Five blocks of M codes behind one held move: more than the look-ahead holds.
        ("T0101\nG00 X20 Z5\nG42 G01 Z0 F0.1\nM08\nM09\nM08\nM09\nM08\nZ-10\nM30\n", 8, 4044),
    ];
    for &(text, line, code) in cases {
        let r = run_with(text, machine(3), Panel::default());
        assert_eq!(r.alarm_codes().first(), Some(&(line, code)), "{text}");
    }
}

/// Runs `text` like the board: up to the first alarm, then stops. Returns the
/// actions that ran and the alarm (line, code).
fn until_alarm(text: &str, tip: u8) -> (Vec<Canon>, Option<(u32, u16)>) {
    let mut interp = interp_core::Interpreter::new(machine(tip));
    let mut sink = host_tests::VecSink::default();
    let store = interp_core::SingleProgram(text.as_bytes());
    for _ in 0..100_000 {
        match interp.step(&store, &Panel::default(), &mut sink) {
            Ok(interp_core::Progress::Ended) => break,
            Ok(_) => {}
            Err(a) => return (sink.0, Some((a.line, a.kind.code()))),
        }
    }
    (sink.0, None)
}

/// The last move that ran before the alarm: its line and tip end point (Z, r).
fn last_move(actions: &[Canon]) -> (u32, (f64, f64)) {
    let c = actions.iter().rfind(|c| c.action.endpoint().is_some()).unwrap();
    (c.line, zr(c.action.endpoint().unwrap()))
}

#[test]
fn an_alarm_in_the_next_block_lets_the_held_move_run_to_its_normal_first() {
    // Line 3 (start-up onto the face, −Z under G42: the centre is R on +X) waits
    // for line 4, which is faulty (G41 without G40, 3576): line 3 runs and ends
    // on its normal at (Z0, r0.8); line 4 moves nothing.
    let (acts, alarm) = until_alarm("T0101\nG00 X0 Z5\nG42 G01 Z0 F0.1\nG41 X20\nX20\nG40 G00 X40\nM30\n", 0);
    assert_eq!(alarm, Some((4, 3576)));
    let (line, end) = last_move(&acts);
    assert_eq!(line, 3);
    assert!(near(end, (0.0, R)), "{end:?}");
    assert!(acts.iter().all(|c| c.line < 4), "{acts:?}");
    // A block that is no G code (G07, 0010) after a ,C block: the chamfered face
    // runs to its programmed end (the chamfer needs the faulty block) on its
    // normal (+Z for +X travel under G42).
    let (acts, alarm) = until_alarm("T0101\nG00 X0 Z5\nG42 G01 Z0 F0.1\nX20 ,C1\nG07 Z-10\nM30\n", 0);
    assert_eq!(alarm, Some((5, 10)));
    let (line, end) = last_move(&acts);
    assert_eq!(line, 4);
    assert!(near(end, (R, 10.0)), "{end:?}");
    assert!(acts.iter().all(|c| c.line < 5));
}

#[test]
fn a_missing_sequence_number_in_a_stored_program_lets_the_held_move_run() {
    // G71 P8 Q9 with no N8 (0063) in a complete text is final, not "wait for the
    // stream": line 3 (held for its end normal) runs to (Z0, r0.8) before the stop,
    // as after any other alarm. (A stream keeps it held while the board waits for
    // the text: controller tests.)
    let (acts, alarm) = until_alarm("T0101\nG00 X0 Z5\nG42 G01 Z0 F0.1\nG71 P8 Q9 U0.5 W0.1\nM30\n", 0);
    assert_eq!(alarm, Some((4, 63)));
    let (line, end) = last_move(&acts);
    assert_eq!(line, 3);
    assert!(near(end, (0.0, R)), "{end:?}");
}

#[test]
fn interference_stops_before_the_block_whose_offset_runs_backwards() {
    // The groove bottom (line 6, 1 mm) is narrower than the nose (1.6 mm): its
    // offset would run +Z. The machine stops at the end of line 5 — the corner of
    // the wall's offset (Z−10−R) and the bottom's (r15+R) — and the alarm names
    // line 6; neither line 6 nor line 7 moves.
    let text = "T0101\nG00 X40 Z5\nG42 G01 Z0 F0.1\nZ-10\nX30\nZ-11\nX40\nZ-20\nG40 X60\nM30\n";
    let (acts, alarm) = until_alarm(text, 0);
    assert_eq!(alarm, Some((6, 3605)));
    let (line, end) = last_move(&acts);
    assert_eq!(line, 5);
    assert!(near(end, (-10.0 - R, 15.0 + R)), "{end:?}");
    assert!(acts.iter().all(|c| c.line < 6));
}

#[test]
fn a_faulty_block_leaves_the_mode_and_the_next_move_starts_up_again() {
    // Going on after the alarm (as `lathe check` does): G42 is still in force and
    // line 5 starts up from the uncompensated point (Z0, r0): its offset is r10+R...
    let bad =
        run_with("T0101\nG00 X0 Z5\nG42 G01 Z0 F0.1\nG41 X20\nZ-10\nG40 G00 X40\nM30\n", machine(0), Panel::default());
    assert_eq!(bad.alarm_codes(), vec![(4, 3576)]);
    let mv = centre_moves(&bad, 0);
    let z = mv.iter().find(|m| m.line == 5).unwrap();
    assert!((z.end.1 - R).abs() < 1e-6, "{z:?}");
}

#[test]
fn a_chamfer_under_g42_is_offset_like_any_other_line() {
    // Face up to Ø20 with ,C2, then along -Z: the chamfer (Z0,r8)→(Z-2,r10) is
    // inserted into the contour, then offset by R like the face and the diameter.
    let r = ok("T0101\nG00 X0 Z5\nG42 G01 Z0 F0.1\nX20 ,C2\nZ-10\nG40 G00 X40\nM30\n", 0);
    let mv = centre_moves(&r, 0);
    let own: Vec<_> = mv.iter().filter(|m| m.line == 4).map(|m| m.end).collect();
    // The face's offset ends where it meets the chamfer's offset (an outer 45° turn:
    // lengthened), then the chamfer's offset runs R from the chamfer line.
    let chamfer = ((0.0, 8.0), (-2.0, 10.0));
    let on_chamfer: Vec<_> = own.iter().filter(|p| (line_dist(**p, chamfer.0, chamfer.1) - R).abs() < 1e-6).collect();
    assert!(on_chamfer.len() >= 2, "{own:?}");
    let diameter = mv.iter().find(|m| m.line == 5).unwrap();
    assert!((diameter.end.1 - (10.0 + R)).abs() < 1e-6, "{diameter:?}");
}

#[test]
fn g52_and_g50_cancel_the_offset_for_the_next_move_to_start_up() {
    for code in ["G52 W0", "G50 X20 Z0"] {
        let prog = format!("T0101\nG00 X0 Z5\nG42 G01 Z0 F0.1\nX20\n{code}\nZ-10\nX30\nG40 G00 X50\nM30\n");
        let r = ok(&prog, 0);
        let mv = centre_moves(&r, 0);
        let face = mv.iter().rfind(|m| m.line == 4).unwrap();
        assert!(near(face.end, (R, 10.0)), "{code}: the face ends on its normal: {face:?}");
        // Z-10 starts up again from the uncompensated point: a line from (R, 10).
        let z = mv.iter().find(|m| m.line == 6).unwrap();
        assert!((z.end.1 - (10.0 + R)).abs() < 1e-6, "{code}: {z:?}");
    }
}

#[test]
fn offset_points_beyond_the_soft_limits_are_refused() {
    // Facing up at Z-599.5 with the tool on the -Z side: the offset runs at
    // Z-600.3, past the Z travel (-600).
    let text = "T0101\nG00 X20 Z-595\nG41 G01 Z-599.5 F0.1\nX40\nG40 G00 X60\nM30\n";
    let r = run_with(text, machine(0), Panel::default());
    assert_eq!(r.alarm_codes().first(), Some(&(4, 501)));
}

#[test]
fn a_start_up_shorter_than_the_radius_is_not_interference() {
    // Approaching the face from 0.5 mm with R0.8: the start-up move runs back in Z
    // to the offset corner, which is no gouge.
    let r = ok("T0101\nG00 X0 Z0.5\nG42 G01 Z0 F0.1\nX20\nZ-10\nG40 G00 X40\nM30\n", 0);
    let first = centre_moves(&r, 0).into_iter().find(|m| m.line == 3).unwrap();
    assert!(near(first.end, (R, R)), "{first:?}");
}

/// The tip positions (Z, X radius) of the moves of `line`, work coordinates.
fn tips_of(r: &Run, line: u32) -> Vec<(f64, f64)> {
    r.actions.iter().filter(|c| c.line == line).filter_map(host_tests::xz).map(|(x, z)| (z, x / 2.0)).collect()
}

/// Signed distance of `p` from the line `a`→`b` (positive on its left, Z right
/// and X up).
fn side_dist(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    (dx * (p.1 - a.1) - dy * (p.0 - a.0)) / dx.hypot(dy)
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 2e-6
}

#[test]
fn g90_taper_under_g42_cuts_one_radius_inside_the_cycle_for_every_tip() {
    // A = (Z2, r25); B = (Z2, r20 − 5); C = (Z−20, r20); D = (Z−20, r25).
    let (a, b, c) = ((2.0, 25.0), (2.0, 15.0), (-20.0, 20.0));
    for tip in [0, 2, 3, 8] {
        let r = ok("T0101\nG42 G00 X50 Z2\nG90 X40 Z-20 R-5 F0.2\nG40 G00 X60 Z10\nM30\n", tip);
        let tips = tips_of(&r, 3);
        assert_eq!(tips.len(), 4, "tip {tip}: {tips:?}");
        let t = tip_vec(tip);
        let centre = |p: (f64, f64)| (p.0 - t.0, p.1 - t.1);
        let (bc, cc, dc) = (centre(tips[0]), centre(tips[1]), centre(tips[2]));
        // ② The cut's nose centre runs R off the taper, on the stock side
        // (left of B→C: the cycle runs clockwise, the stock is inside it).
        for p in [bc, cc] {
            assert!(close(side_dist(p, b, c), -R), "tip {tip}: {p:?} is {} off the taper", side_dist(p, b, c));
        }
        // ③ The retract runs R off the shoulder Z−20, at the cycle's side.
        assert!(close(cc.0, -20.0 + R) && close(dc.0, -20.0 + R), "tip {tip}: {cc:?} {dc:?}");
        // ① approach and ③ retract stay X moves, ④ returns to A exactly.
        assert!(close(tips[0].0, a.0), "tip {tip}: approach {tips:?}");
        assert!(close(tips[2].1, a.1), "tip {tip}: retract {tips:?}");
        assert_eq!(tips[3], a, "tip {tip}");
    }
}

#[test]
fn g90_and_g94_straight_with_tip_3_run_as_programmed() {
    let r = ok("T0101\nG42 G00 X50 Z2\nG90 X40 Z-20 F0.2\nG94 X20 Z-2\nG40 G00 X60 Z10\nM30\n", 3);
    assert_eq!(tips_of(&r, 3), [(2.0, 20.0), (-20.0, 20.0), (-20.0, 25.0), (2.0, 25.0)]);
    assert_eq!(tips_of(&r, 4), [(-2.0, 25.0), (-2.0, 10.0), (2.0, 10.0), (2.0, 25.0)]);
}

#[test]
fn g94_taper_under_g41_faces_one_radius_off_the_cone() {
    // G41 or G42 alike: the side comes from the cycle. A = (Z2, r25), B = (Z−3, r25),
    // C = (Z−2, r10), D = (Z2, r10); the cycle runs counter-clockwise.
    let (a, b, c) = ((2.0, 25.0), (-3.0, 25.0), (-2.0, 10.0));
    for tip in [0, 3] {
        let r = ok("T0101\nG41 G00 X50 Z2\nG94 X20 Z-2 R-1 F0.2\nG40 G00 X60 Z10\nM30\n", tip);
        let tips = tips_of(&r, 3);
        let t = tip_vec(tip);
        let centre = |p: (f64, f64)| (p.0 - t.0, p.1 - t.1);
        for p in [centre(tips[0]), centre(tips[1])] {
            assert!(close(side_dist(p, b, c), R), "tip {tip}: {p:?}");
        }
        assert!(close(centre(tips[1]).1, 10.0 + R) && close(centre(tips[2]).1, 10.0 + R), "{tips:?}");
        assert!(close(tips[0].1, a.1) && close(tips[2].0, a.0), "{tips:?}");
        assert_eq!(tips[3], a);
    }
}

#[test]
fn g90_boring_taper_keeps_the_nose_inside_the_bore() {
    // Inside: A = (Z2, r10), B = (Z2, r14), C = (Z−15, r15), D = (Z−15, r10).
    let (b, c) = ((2.0, 14.0), (-15.0, 15.0));
    let r = ok("T0101\nG41 G00 X20 Z2\nG90 X30 Z-15 R-1 F0.2\nG40 G00 X10 Z10\nM30\n", 2);
    let t = tip_vec(2);
    let tips = tips_of(&r, 3);
    let centre = |p: (f64, f64)| (p.0 - t.0, p.1 - t.1);
    for p in [centre(tips[0]), centre(tips[1])] {
        // Left of B→C (going −Z) is −X: the centre is below the bore wall.
        assert!(close(side_dist(p, b, c), R), "{p:?}");
    }
    assert!(close(centre(tips[1]).0, -15.0 + R), "{tips:?}");
}

#[test]
fn g90_whose_cut_is_shorter_than_the_nose_is_interference_before_any_motion() {
    // A 0.5 mm cut with R0.8: the offset cut would run backwards.
    let text = "T0101\nG42 G00 X50 Z2\nG90 X40 Z1.5 F0.2\nM30\n";
    let r = run_with(text, machine(0), Panel::default());
    assert_eq!(r.alarm_codes().first(), Some(&(3, 3605)));
    assert!(r.actions.iter().all(|c| c.line != 3 || c.action.endpoint().is_none()));
}

#[test]
fn g92_threads_on_the_programmed_path_under_g42() {
    // The manual compensates no thread cycle: G92 runs as programmed.
    let r = ok("T0101 M03 S500\nG42 G00 X50 Z2\nG92 X38 Z-20 F1.5\nG40 G00 X60 Z10\nM30\n", 0);
    let tips = tips_of(&r, 3);
    assert_eq!(tips.first(), Some(&(2.0, 19.0)), "{tips:?}");
    // The thread runs at r19 (to the pull-out chamfer), not R off it.
    assert_eq!(tips.get(1).map(|p| p.1), Some(19.0), "{tips:?}");
}

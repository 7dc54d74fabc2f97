//! SINUMERIK CYCLE60 engraving on the mill (seed 001 lines 9799-10068): the
//! characters' strokes scaled to the height _WID, their pitch _DF, the total
//! width, the angle _STA, the text on the top and bottom of a circle, polar
//! reference points, the depth and the feeds, and the alarms. The expected
//! points are computed here from the Hershey Roman simplex grid (capitals 21
//! units high): "I" is the stroke (4,21)-(4,0), "T" (8,21)-(8,0) and
//! (1,21)-(15,21), "L" (4,21)-(4,0)-(16,0); a character's box starts at its
//! leftmost stroke point.

mod mill_common;

use mill_common::plane::siemens;

use interp_core::canon::Canon;

const HEAD: &str = "G17 G0 G90 X0 Y0 Z100 F2000 S1500 M3 T1 D1\n";

/// Moves of a call: (rapid, from, to, feed mm/min), work mm.
fn moves(call: &str) -> Vec<(bool, [f64; 3], [f64; 3], f64)> {
    let r = siemens(&format!("{HEAD}{call}\nM30\n"));
    assert!(r.alarms.is_empty(), "{call}: {:?}", r.alarms);
    path(&r.actions)
}

fn path(actions: &[Canon]) -> Vec<(bool, [f64; 3], [f64; 3], f64)> {
    mill_common::plane::moves(actions)
        .into_iter()
        .filter(|s| s.arc.is_none())
        .map(|s| (s.feed == 0.0, s.from, s.to, s.feed))
        .collect()
}

/// The cutting strokes at depth: (from, to) in the plane.
fn strokes(call: &str, depth: f64) -> Vec<([f64; 2], [f64; 2])> {
    moves(call)
        .into_iter()
        .filter(|m| !m.0 && near(m.1[2], depth) && near(m.2[2], depth))
        .map(|m| ([m.1[0], m.1[1]], [m.2[0], m.2[1]]))
        .collect()
}

fn near(a: f64, b: f64) -> bool {
    (a - b).abs() < 2e-6
}

fn same(got: &[([f64; 2], [f64; 2])], want: &[([f64; 2], [f64; 2])]) {
    assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
    for (g, w) in got.iter().zip(want) {
        for (a, b) in [(g.0, w.0), (g.1, w.1)] {
            assert!(near(a[0], b[0]) && near(a[1], b[1]), "{got:?} vs {want:?}");
        }
    }
}

/// CYCLE60 with text `t`, reference PA/PO, STA, centre CP1/CP2, WID, DF, VARI.
#[allow(clippy::too_many_arguments)]
fn call(t: &str, pa: f64, po: f64, sta: f64, cp: (f64, f64), wid: f64, df: f64, vari: u32) -> String {
    format!("CYCLE60(\"{t}\",100,0,1,-1.5,0,{pa},{po},{sta},{},{},{wid},{df},2500,2000,{vari},1252)", cp.0, cp.1)
}

/// "T" at X10 Y25 (bottom left), 14 high: its grid scaled by 14/21, the box's
/// left edge on the reference point; cut at the depth at the surface feed,
/// plunged at the depth feed, retracted to the safety plane between strokes and
/// to the retract plane at the end.
#[test]
fn a_glyph_is_its_grid_scaled_to_the_height() {
    let k = 14.0 / 21.0;
    let x = |g: f64| 10.0 + (g - 1.0) * k;
    let y = |g: f64| 25.0 + g * k;
    let c = call("T", 10.0, 25.0, 0.0, (0.0, 0.0), 14.0, 5.0, 0);
    same(&strokes(&c, -1.5), &[([x(8.0), y(21.0)], [x(8.0), y(0.0)]), ([x(1.0), y(21.0)], [x(15.0), y(21.0)])]);
    let m = moves(&c);
    // Plunges: G1 at _FFD from the safety plane Z1 to the depth, one per stroke.
    let plunges: Vec<_> = m.iter().filter(|m| !m.0 && m.1[2] > m.2[2]).collect();
    assert_eq!(plunges.len(), 2);
    assert!(plunges.iter().all(|p| near(p.1[2], 1.0) && near(p.2[2], -1.5) && p.3 == 2500.0));
    assert!(m.iter().filter(|m| !m.0 && near(m.2[2], -1.5) && near(m.1[2], -1.5)).all(|m| m.3 == 2000.0));
    // Every rise is a rapid; the last move is up to the retract plane Z100.
    assert!(m.iter().filter(|m| m.2[2] > m.1[2]).all(|m| m.0));
    assert!(near(m.last().unwrap().2[2], 100.0));
    assert!(m.iter().filter(|m| m.2[2] > m.1[2] && !near(m.2[2], 100.0)).all(|m| near(m.2[2], 1.0)));
}

/// _DF is the distance between neighbouring characters' boxes; in the total
/// width mode (hundred-thousands 1) the first box's left to the last's right.
#[test]
fn character_pitch_and_total_width() {
    let k = 14.0 / 21.0;
    let stem = |x: f64| ([x, 25.0 + 21.0 * k], [x, 25.0]);
    same(&strokes(&call("II", 10.0, 25.0, 0.0, (0.0, 0.0), 14.0, 5.0, 0), -1.5), &[stem(10.0), stem(15.0)]);
    // "L" is 12 units wide: the next character starts 12 k + DF further on.
    let l = strokes(&call("LI", 10.0, 25.0, 0.0, (0.0, 0.0), 14.0, 5.0, 0), -1.5);
    assert!(near(l[2].0[0], 10.0 + 12.0 * k + 5.0), "{l:?}");
    // Total width 30: "III" spread from X10 to X40.
    same(
        &strokes(&call("III", 10.0, 25.0, 0.0, (0.0, 0.0), 14.0, 30.0, 100000), -1.5),
        &[stem(10.0), stem(25.0), stem(40.0)],
    );
    // Right aligned (thousands 2): the text ends on the reference point;
    // centred at the middle (thousands 1, ten-thousands 1: half the height).
    same(&strokes(&call("II", 10.0, 25.0, 0.0, (0.0, 0.0), 14.0, 5.0, 2000), -1.5), &[stem(5.0), stem(10.0)]);
    same(&strokes(&call("II", 10.0, 25.0 + 7.0, 0.0, (0.0, 0.0), 14.0, 5.0, 11000), -1.5), &[stem(7.5), stem(12.5)]);
}

/// _STA turns the line; a polar reference point (units 1) is radius and angle
/// about the work zero.
#[test]
fn angle_and_polar_reference() {
    // At 90 degrees the text runs up +Y, the letters' tops towards −X.
    same(&strokes(&call("I", 10.0, 25.0, 90.0, (0.0, 0.0), 14.0, 5.0, 0), -1.5), &[([-4.0, 25.0], [10.0, 25.0])]);
    // PA 30 at PO 90 degrees is X0 Y30.
    same(&strokes(&call("I", 30.0, 90.0, 0.0, (0.0, 0.0), 14.0, 5.0, 1), -1.5), &[([0.0, 44.0], [0.0, 30.0])]);
}

/// On a circle of radius 40 about X50 Y50: a stem stands radially on the
/// reference radius (top: outwards; bottom: towards the centre); the opening
/// angle sets the angle between the first and last centre lines, spacing is an
/// arc length on the reference radius.
#[test]
fn text_on_a_circle() {
    let radial = |deg: f64, r0: f64, r1: f64| {
        let (s, c) = deg.to_radians().sin_cos();
        ([50.0 + r1 * c, 50.0 + r1 * s], [50.0 + r0 * c, 50.0 + r0 * s])
    };
    // Top, centred on X50 Y90, 9 high, 90 degrees: stems at 135, 90 and 45 degrees.
    same(
        &strokes(&call("III", 50.0, 90.0, 0.0, (50.0, 50.0), 9.0, 90.0, 201010), -1.5),
        &[radial(135.0, 40.0, 49.0), radial(90.0, 40.0, 49.0), radial(45.0, 40.0, 49.0)],
    );
    // Bottom, left aligned on X50 Y10, spacing 10 mm of arc: the second stem 10/40 rad on.
    let d = (10.0f64 / 40.0).to_degrees();
    same(
        &strokes(&call("II", 50.0, 10.0, 0.0, (50.0, 50.0), 9.0, 10.0, 20), -1.5),
        &[radial(-90.0, 40.0, 31.0), radial(-90.0 + d, 40.0, 31.0)],
    );
    // 360: spread evenly round the whole circle, the text's middle (between the
    // second and third) at the top.
    same(
        &strokes(&call("IIII", 50.0, 90.0, 0.0, (50.0, 50.0), 9.0, 360.0, 201010), -1.5),
        &[radial(225.0, 40.0, 49.0), radial(135.0, 40.0, 49.0), radial(45.0, 40.0, 49.0), radial(-45.0, 40.0, 49.0)],
    );
    // Polar centre (millions 1: radius 50 at 0 degrees = X50 Y0) and polar
    // reference point about it (units 1: radius 40 at 90 degrees = X50 Y40).
    let c = call("I", 40.0, 90.0, 0.0, (50.0, 0.0), 9.0, 5.0, 1001011);
    same(&strokes(&c, -1.5), &[([50.0, 49.0], [50.0, 40.0])]);
}

/// Bad calls stop on their line with the document's alarm and move nothing.
#[test]
fn alarms_of_cycle60_move_nothing() {
    let ok = call("AB", 10.0, 25.0, 0.0, (0.0, 0.0), 14.0, 5.0, 0);
    for (c, code) in [
        (format!("D0\n{ok}"), 61000),
        (ok.replace("100,0,1,-1.5,0", "0,0,1,0,1.5"), 61101),
        (call("AB", 10.0, 25.0, 0.0, (0.0, 0.0), 14.0, 5.0, 3), 61002),
        (call("AB", 10.0, 25.0, 0.0, (0.0, 0.0), 14.0, 5.0, 30), 61002),
        (call("AB", 10.0, 25.0, 0.0, (0.0, 0.0), 14.0, 5.0, 100010), 61002),
        (call("AB", 10.0, 25.0, 0.0, (0.0, 0.0), 14.0, 5.0, 200000), 61002),
        (call("AB", 10.0, 25.0, 0.0, (0.0, 0.0), 0.0, 5.0, 0), 61019),
        (call("AB", 50.0, 50.0, 0.0, (50.0, 50.0), 9.0, 5.0, 10), 61019),
        (call("AB", 10.0, 25.0, 0.0, (0.0, 0.0), 14.0, 10.0, 100000), 61176),
        (call("AB", 10.0, 25.0, 0.0, (0.0, 0.0), 14.0, -5.0, 0), 61176),
        (call("ABCDEFGH", 50.0, 52.0, 0.0, (50.0, 50.0), 9.0, 5.0, 10), 61176),
        (ok.replace("1252)", "850)"), 61178),
        (call("A\u{c6}B", 10.0, 25.0, 0.0, (0.0, 0.0), 14.0, 5.0, 0), 61179),
        (call(&"A".repeat(92), 10.0, 25.0, 0.0, (0.0, 0.0), 1.0, 0.0, 0), 61179),
    ] {
        let r = siemens(&format!("{HEAD}{c}\nM30\n"));
        let line = 2 + c.matches('\n').count() as u32;
        assert_eq!(r.alarm_codes(), vec![(line, code)], "{c}");
        let before = siemens(&format!("{HEAD}{}M30\n", if line == 3 { "D0\n" } else { "" }));
        assert_eq!(r.actions.len(), before.actions.len(), "{c} moved");
    }
}

/// The document's accented letters (code page 1252, written in UTF-8 in the
/// program) are their letter and the accent: "Ü" is "U" and two dots above it.
#[test]
fn accented_letters() {
    let u = strokes(&call("U", 10.0, 25.0, 0.0, (0.0, 0.0), 21.0, 5.0, 0), -1.5);
    let uu = strokes(&call("\u{dc}", 10.0, 25.0, 0.0, (0.0, 0.0), 21.0, 5.0, 0), -1.5);
    assert_eq!(uu.len(), u.len() + 2);
    same(&uu[..u.len()], &u);
    // U's box is x 4..18 on the grid (anchor 11), the dots at 11 ± 2 from 23 to 24.
    same(&uu[u.len()..], &[([15.0, 48.0], [15.0, 49.0]), ([19.0, 48.0], [19.0, 49.0])]);
}

/// A double quote in the text is written in single quotes (lines 9990-10000):
/// "A'"'B" engraves A, ", B (" is two strokes).
#[test]
fn a_quote_in_single_quotes() {
    let plunges = |t: &str| {
        moves(&call(t, 10.0, 25.0, 0.0, (0.0, 0.0), 14.0, 5.0, 0)).iter().filter(|m| !m.0 && m.2[2] < m.1[2]).count()
    };
    assert_eq!(plunges("A'\"'B"), plunges("A") + 2 + plunges("B"));
    // A ; inside the string is text, not a comment.
    assert_eq!(plunges("A;B"), plunges("A") + plunges(";") + plunges("B"));
}

/// The document's examples (lines 10003-10068) run and cut at the depth.
#[test]
fn the_documents_examples_run() {
    for f in ["cycle60.mpf", "cycle60_arc.mpf"] {
        let text =
            std::fs::read_to_string(format!("{}/../examples/sinumerik/mill/{f}", env!("CARGO_MANIFEST_DIR"))).unwrap();
        let r = siemens(&text);
        assert!(r.alarms.is_empty(), "{f}: {:?}", r.alarms);
        let p = path(&r.actions);
        assert!(p.iter().filter(|m| !m.0 && near(m.2[2], -1.5)).count() > 50, "{f}");
    }
}

/// Extreme and odd calls end in an alarm or a path, never a panic.
#[test]
fn odd_calls_do_not_panic() {
    let big = 99_999_999.0;
    for vari in [0, 1, 10, 11, 20, 21, 1010, 12020, 22010, 101000, 201010, 1001021, 2201020, 9999999, 99999999] {
        for (pa, po, wid, df) in [
            (big, big, big, big),
            (9e6, -9e6, 9e6, 9e6),
            (-9e6, 1.0, 9e6, 3e6),
            (-big, 0.0, 0.001, -big),
            (0.0, 0.0, 1.0, 360.0),
            (1e-6, 1e-6, 1e-6, 0.0),
        ] {
            for cp in [(0.0, 0.0), (big, -big), (9e6, -9e6), (1e-6, 0.0)] {
                for t in ["", " ", "~}|{", "\u{e9}\u{ff}\u{c7}"] {
                    let c = call(t, pa, po, big, cp, wid, df, vari);
                    let _ = siemens(&format!("{HEAD}{c}\nM30\n"));
                }
            }
        }
    }
}

/// In G19 the text lies in the Y/Z plane (Y the abscissa) and the depth is along X.
#[test]
fn the_plane_g19() {
    let c = call("I", 10.0, 25.0, 0.0, (0.0, 0.0), 14.0, 5.0, 0);
    let r = siemens(&format!("G19 G0 G90 X100 Y0 Z0 F2000 S1500 M3 T1 D1\n{c}\nM30\n"));
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    let cuts: Vec<_> =
        path(&r.actions).into_iter().filter(|m| !m.0 && near(m.1[0], -1.5) && near(m.2[0], -1.5)).collect();
    assert_eq!(cuts.len(), 1, "{cuts:?}");
    let (from, to) = (cuts[0].1, cuts[0].2);
    assert!(near(from[1], 10.0) && near(from[2], 39.0) && near(to[1], 10.0) && near(to[2], 25.0), "{cuts:?}");
}

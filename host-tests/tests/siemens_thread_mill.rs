//! SINUMERIK thread milling and the setting cycles on the mill (seed 001
//! chapter 3): CYCLE90 (lines 3538-3772), CYCLE800 (7391-7790, 9188-9260).
//! Geometry is computed here from the document's formulas and compared with the
//! actions the interpreter emits.

mod mill_common;

use mill_common::plane::{cfg, mm3, siemens};

use host_tests::{Run, run_with};
use interp_core::Panel;

const HEAD: &str = "G17 G0 G90 X0 Y0 Z20 F200 S500 M3 T1 D1\n";

/// CYCLE800 on a board without swivel kinematics (lines 9197, 12241): every call
/// that would swivel raises 61180 on its line and moves nothing; `CYCLE800()`
/// and `_TC="0"` deselect (lines 7517, 7633) and are accepted.
#[test]
fn cycle800_swivels_raise_61180_and_deselect_is_accepted() {
    let before = siemens(&format!("{HEAD}M30\n"));
    assert!(before.alarms.is_empty(), "{:?}", before.alarms);
    for call in [
        "CYCLE800(1, \"\", 0, 57, 0, 0, 0, 0, 0, 0, 0, 0, -1)",
        "CYCLE800(1,\"\",0,57,0,40,0,-45,0,0,0,0,-1)",
        "CYCLE800(0, \"HEAD1\", 0, 27, 0, 0, 0, 0, 30, 0, 0, 0, 0, 0)",
        "CYCLE800(2, \"\", 1, 0, 10, 0, 0, 0, 0, 90, 0, 0, 0, 1)",
    ] {
        let r = siemens(&format!("{HEAD}{call}\nM30\n"));
        assert_eq!(r.alarm_codes(), vec![(2, 61180)], "{call}");
        assert_eq!(r.actions.len(), before.actions.len(), "{call} moved");
    }
    for call in ["CYCLE800()", "CYCLE800(1, \"0\", 0, 57, 0, 0, 0, 0, 0, 0, 0, 0, -1)", "CYCLE800(, \"0\")"] {
        let r = siemens(&format!("{HEAD}{call}\nG1 X5\nM30\n"));
        assert!(r.alarms.is_empty(), "{call}: {:?}", r.alarms);
        let moved = siemens(&format!("{HEAD}G1 X5\nM30\n"));
        assert_eq!(r.kinds(), moved.kinds(), "{call} changed the actions");
    }
}

/// A cutting move in work mm: start, end, arc centre and direction.
#[derive(Clone, Copy, Debug)]
struct Cut {
    from: [f64; 3],
    to: [f64; 3],
    arc: Option<([f64; 2], bool)>,
    feed: f64,
}

/// The cutting moves (G17: X, Y the plane, Z the applicate) and the rapids'
/// end points of the program's line `line`, in order.
fn moves_of(r: &Run, line: u32) -> (Vec<Cut>, Vec<[f64; 3]>) {
    use interp_core::canon::Action;
    let (mut cuts, mut rapids) = (Vec::new(), Vec::new());
    let mut at = [0.0; 3];
    for c in &r.actions {
        let Some(e) = c.action.endpoint() else { continue };
        let to = mm3(&e.work);
        if c.line == line {
            match c.action {
                Action::Rapid(_) => rapids.push(to),
                Action::Linear(m) => cuts.push(Cut { from: at, to, arc: None, feed: m.feed.value as f64 / 1e6 }),
                Action::Arc(a) => {
                    let cc = mm3(&a.center.work);
                    cuts.push(Cut { from: at, to, arc: Some(([cc[0], cc[1]], a.cw)), feed: a.feed.value as f64 / 1e6 })
                }
                _ => {}
            }
        }
        at = to;
    }
    (cuts, rapids)
}

/// Angle an arc sweeps, radians (> 0; a full circle is 2π).
fn sweep(c: &Cut) -> f64 {
    let (cc, cw) = c.arc.expect("an arc");
    let a0 = (c.from[1] - cc[1]).atan2(c.from[0] - cc[0]);
    let a1 = (c.to[1] - cc[1]).atan2(c.to[0] - cc[0]);
    let mut d = if cw { a0 - a1 } else { a1 - a0 };
    while d <= 1e-9 {
        d += std::f64::consts::TAU;
    }
    d
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 2e-6
}

/// The helix of a call: the arcs about the thread's centre `c`.
fn helix(cuts: &[Cut], c: [f64; 2]) -> Vec<Cut> {
    cuts.iter().filter(|m| m.arc.is_some_and(|(cc, _)| close(cc[0], c[0]) && close(cc[1], c[1]))).copied().collect()
}

/// The document's internal example (lines 3749-3772): M60 × 2 at X60 Y50, from
/// RFP 40 down 40 mm, G2, a 5 mm cutter (T1 D1 here for its T5 D1). The helix
/// radius is DIATH/2 − r = 25, the depth falls 2 mm per turn from Z40 to Z0,
/// every turn G2; the cutter goes in and out at the centre and leaves at RTP.
#[test]
fn cycle90_internal_example() {
    let text = "N10 G90 G0 G17 X0 Y0 Z80 S200 M3\nN20 T1 D1\n\
                N30 CYCLE90(48, 40, 5, , 40, 60, 50, 2, 500, 2, 0, 60, 50)\nN40 G0 G90 Z100\nN50 M02\n";
    let r = siemens(text);
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    let (cuts, rapids) = moves_of(&r, 3);
    assert_eq!(rapids.first(), Some(&[60.0, 50.0, 48.0]), "over the centre at RTP");
    assert_eq!(rapids.last(), Some(&[60.0, 50.0, 48.0]), "back at RTP over the centre");
    let h = helix(&cuts, [60.0, 50.0]);
    let (wr, dia, pit) = (5.0, 60.0, 2.0);
    let mut turned = 0.0;
    for m in &h {
        let (_, cw) = m.arc.unwrap();
        assert!(cw, "CDIR 2: G2");
        for p in [m.from, m.to] {
            assert!(close((p[0] - 60.0).hypot(p[1] - 50.0), dia / 2.0 - wr), "{p:?}");
        }
        let s = sweep(m);
        turned += s;
        assert!(close((m.from[2] - m.to[2]) / s * std::f64::consts::TAU, pit), "{m:?}");
        // FFR 500 at the cutting edge (line 3672): the centre at 500·25/30.
        assert!((m.feed - 500.0 * 25.0 / 30.0).abs() < 1e-3, "{}", m.feed);
    }
    assert!(close(turned, 20.0 * std::f64::consts::TAU), "40 mm at 2 mm per turn: {turned}");
    assert_eq!((h[0].from[2], h[h.len() - 1].to[2]), (40.0, 0.0));
    // In and out on semicircles (SW 6.3), the depth overrun p/2·(r + DIATH/2)/DIATH.
    let dz = pit / 2.0 * (wr + dia / 2.0) / dia;
    let first = cuts[0];
    assert_eq!((first.to[0], first.to[1]), (60.0, 50.0));
    assert!(close(first.to[2], 40.0 + dz), "{first:?}");
    let out = cuts[cuts.len() - 1];
    assert!(close(sweep(&out), std::f64::consts::PI) && close(out.to[2], -dz), "{out:?}");
    assert_eq!((out.to[0], out.to[1]), (60.0, 50.0));
    // Nothing cuts beyond the thread's diameter: the cutter's centre stays
    // within DIATH/2 − r of the centre.
    assert!(cuts.iter().all(|m| (m.to[0] - 60.0).hypot(m.to[1] - 50.0) <= 25.0 + 1e-6));
}

/// The document's bottom-up example (lines 3636-3650): from Z−20 up to Z0 at 3 mm
/// per turn, RTP 8 beyond DP, G3; the hole must reach at least Z−21.5 (line 3650):
/// the arc in starts Δz = p/2·(r + DIATH/2)/DIATH below RFP.
#[test]
fn cycle90_from_the_bottom_up() {
    let text = "N10 G17 X100 Y100 S300 M3 T1 D1 F1000\nN20 Z8\n\
                N30 CYCLE90 (8, -20, 0, 0, 0, 46, 40, 3, 800, 3, 0, 50, 50)\nN40 M2\n";
    let r = siemens(text);
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    let (cuts, _) = moves_of(&r, 3);
    let h = helix(&cuts, [50.0, 50.0]);
    let mut turned = 0.0;
    for m in &h {
        assert!(!m.arc.unwrap().1, "CDIR 3: G3");
        assert!(close((m.to[0] - 50.0).hypot(m.to[1] - 50.0), 23.0 - 5.0));
        assert!(m.to[2] > m.from[2]);
        turned += sweep(m);
    }
    assert!(close(turned, 20.0 / 3.0 * std::f64::consts::TAU), "{turned}");
    assert_eq!((h[0].from[2], h[h.len() - 1].to[2]), (-20.0, 0.0));
    let low = cuts.iter().map(|m| m.to[2]).fold(f64::MAX, f64::min);
    assert!(close(low, -20.0 - 1.5 * (5.0 + 23.0) / 46.0) && low >= -21.5, "{low}");
}

/// An external thread (TYPTH 1), G3: helix radius DIATH/2 + r; the cutter starts
/// in the 4th quadrant (line 3611) at RTP, goes in and out on quarter circles
/// against the helix (G2), Δz = p/4·(2r + RDIFF)/DIATH, RDIFF = DIATH/2 + r;
/// with G2 the start is in the 1st quadrant.
#[test]
fn cycle90_external() {
    let call = |cdir| format!("{HEAD}N2 CYCLE90(10, 0, 2, -12, , 20, 17, 1.5, 300, {cdir}, 1, 40, 30)\nM30\n");
    let r = siemens(&call(3));
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    let (cuts, rapids) = moves_of(&r, 2);
    let (wr, dia, p) = (5.0, 20.0, 1.5);
    let rc = dia / 2.0 + wr;
    assert!(close(rapids[0][0], 40.0 + 1.5 * rc) && close(rapids[0][1], 30.0 - rc / 2.0), "{:?}", rapids[0]);
    assert_eq!(rapids[0][2], 10.0);
    let h = helix(&cuts, [40.0, 30.0]);
    let mut turned = 0.0;
    for m in &h {
        assert!(!m.arc.unwrap().1);
        assert!(close((m.to[0] - 40.0).hypot(m.to[1] - 30.0), rc));
        turned += sweep(m);
    }
    assert!(close(turned, 8.0 * std::f64::consts::TAU));
    let arcs_in_out: Vec<_> = cuts.iter().filter(|m| m.arc.is_some() && !h.iter().any(|x| x.to == m.to)).collect();
    assert_eq!(arcs_in_out.len(), 2);
    let dz = p / 4.0 * (2.0 * wr + dia / 2.0 + wr) / dia;
    for m in &arcs_in_out {
        assert!(m.arc.unwrap().1, "against the helix");
        assert!(close(sweep(m), std::f64::consts::FRAC_PI_2));
        assert!(close((m.from[2] - m.to[2]).abs(), dz), "{m:?}");
    }
    // Nothing cuts inside the thread's diameter.
    assert!(cuts.iter().all(|m| (m.to[0] - 40.0).hypot(m.to[1] - 30.0) >= rc - 1e-6));
    let r = siemens(&call(2));
    let (_, rapids) = moves_of(&r, 2);
    assert!(rapids[0][0] > 40.0 && rapids[0][1] > 30.0, "1st quadrant: {:?}", rapids[0]);
}

/// A CDIR other than 2 or 3 is G3 and the message 62101 (line 3717); the cycle runs.
#[test]
fn cycle90_wrong_direction_is_g3_with_a_message() {
    let text = format!("{HEAD}N2 CYCLE90(10, 0, 2, -6, , 20, 17, 1.5, 300, 7, 1, 40, 30)\nM30\n");
    let r = siemens(&text);
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    let g3 = siemens(&text.replace(", 7, 1,", ", 3, 1,"));
    assert_eq!(r.kinds(), g3.kinds());
    assert_eq!(r.interp.siemens.notice.map(|n| n.0), Some(62101));
}

/// Each alarm of the section on its line, and nothing moves.
#[test]
fn cycle90_alarms() {
    let before = siemens(&format!("{HEAD}M30\n")).actions.len();
    let ok = "CYCLE90(10, 0, 2, -6, , 30, 27, 1.5, 300, 2, 0, 40, 30)";
    for (head, call, code) in [
        ("D0", ok, 61000),
        ("T4 D1", ok, 61000),
        ("", "CYCLE90(0, 0, 2, -6, 6, 30, 27, 1.5, 300, 2, 0, 40, 30)", 61101),
        ("", "CYCLE90(10, 0, 2, 15, , 30, 27, 1.5, 300, 2, 0, 40, 30)", 61101),
        ("", "CYCLE90(10, 0, 2, -6, , 30, 27, 0, 300, 2, 0, 40, 30)", 61001),
        ("", "CYCLE90(10, 0, 2, -6, , 30, 27, 2000.5, 300, 2, 0, 40, 30)", 61001),
        ("", "CYCLE90(10, 0, 2, -6, , 30, 31, 1.5, 300, 2, 0, 40, 30)", 61001),
        ("", "CYCLE90(10, 0, 2, -6, , 30, , 1.5, 300, 2, 0, 40, 30)", 61001),
        ("", "CYCLE90(10, 0, 2, -6, , 30, 27, 1.5, 300, 2, 2, 40, 30)", 61002),
        ("", "CYCLE90(10, 0, 2, -6, , 30, 10, 1.5, 300, 2, 0, 40, 30)", 61105),
        ("F0", "CYCLE90(10, 0, 2, -6, , 30, 27, 1.5, 0, 2, 0, 40, 30)", 61003),
    ] {
        let r = siemens(&format!("{HEAD}{head}\n{call}\nM30\n"));
        let line = 3 + head.matches('\n').count() as u32;
        assert_eq!(r.alarm_codes(), vec![(line, code)], "{head} {call}");
        let moved = r.actions.len() - before;
        assert!(moved <= 1, "{head} {call}: {:?}", &r.actions[before..]);
    }
}

/// The example programs (examples/sinumerik/mill/cycle90*.mpf) run and cut the
/// helix the tests above measure: the same moves as the calls written out.
#[test]
fn cycle90_example_files_run() {
    for (f, line, c, rc) in [("cycle90.mpf", 12, [60.0, 50.0], 25.0), ("cycle90_up.mpf", 6, [50.0, 50.0], 18.0)] {
        let text =
            std::fs::read_to_string(format!("{}/../examples/sinumerik/mill/{f}", env!("CARGO_MANIFEST_DIR"))).unwrap();
        let r = siemens(&text);
        assert!(r.alarms.is_empty(), "{f}: {:?}", r.alarms);
        let (cuts, _) = moves_of(&r, line);
        let h = helix(&cuts, c);
        assert!(h.len() > 10, "{f}");
        assert!(h.iter().all(|m| close((m.to[0] - c[0]).hypot(m.to[1] - c[1]), rc)), "{f}");
    }
}

/// Odd values never panic: each call ends in an alarm or runs.
#[test]
fn cycle90_odd_values_do_not_panic() {
    let vals = ["", "0", "-1", "1e9", "-1e12", "0.0005", "3", "-40", "2000", "1e-9"];
    for (i, v) in vals.iter().enumerate() {
        for k in 0..13 {
            let mut args: Vec<String> =
                ["10", "0", "2", "-6", "", "30", "27", "1.5", "300", "2", "0", "40", "30"].map(String::from).to_vec();
            args[k] = v.to_string();
            args[(k + i) % 13] = vals[(i * 7 + k) % vals.len()].to_string();
            let text = format!("{HEAD}N2 CYCLE90({})\nM30\n", args.join(", "));
            let r = run_interp_limited(&text);
            assert!(r.alarms.len() <= 1, "{text}: {:?}", r.alarms);
        }
    }
}

fn run_interp_limited(text: &str) -> Run {
    host_tests::run_interp(
        interp_core::Interpreter::new(cfg()),
        &interp_core::SingleProgram(text.as_bytes()),
        &Panel::default(),
        20_000,
    )
}

/// In G19 the thread lies in the Y/Z plane and is cut along X (the plane's
/// applicate): the helix about Y40 Z30 at DIATH/2 + r, X falling from 0 to −6.
#[test]
fn cycle90_in_g19_cuts_along_x() {
    let text =
        "G19 G0 G90 X20 Y0 Z20 F200 S500 M3 T1 D1\nN2 CYCLE90(10, 0, 2, -6, , 20, 17, 1.5, 300, 3, 1, 40, 30)\nM30\n";
    let r = siemens(text);
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    let (cuts, _) = moves_of(&r, 2);
    let arcs: Vec<_> = cuts.iter().filter(|m| m.arc.is_some()).collect();
    assert!(arcs.len() > 8);
    let on_helix: Vec<_> = arcs.iter().filter(|m| close((m.to[1] - 40.0).hypot(m.to[2] - 30.0), 15.0)).collect();
    assert!(on_helix.len() >= 8, "{arcs:?}");
    let xs: Vec<f64> = on_helix.iter().map(|m| m.to[0]).collect();
    assert!(xs.windows(2).all(|w| w[1] <= w[0]) && close(xs[xs.len() - 1], -6.0), "{xs:?}");
}

/// A cutter radius below zero (row 3's wear beyond its radius: the D offset's
/// geometry + wear) is 61112 "tool radius negative" (table 5.3), nothing moves.
#[test]
fn cycle90_negative_radius_is_61112() {
    let mut c = cfg();
    if let Some(row) = c.tools.get_mut(3) {
        row.x_wear = -4_000_000;
    }
    let text =
        "G17 G0 G90 X0 Y0 Z20 F200 S500 M3 T3 D1\nCYCLE90(10, 0, 2, -6, , 30, 27, 1.5, 300, 2, 0, 40, 30)\nM30\n";
    let r = run_with(text, c, Panel::default());
    assert_eq!(r.alarm_codes(), vec![(2, 61112)]);
}

//! Every program of `examples/mill` runs on examples/machines/mill.toml (with the
//! subprograms of `examples/mill/lib`) without an alarm to its M30, and cuts what
//! it says: the seed's worked examples, the G16 bolt circle, the scaled and
//! rotated pockets, the G98/G99 drilling levels, the offsets G10 sets, the
//! compensated contour. Expected points are computed here.

mod mill_common;

use std::fs;
use std::path::PathBuf;

use host_tests::{Run, kind_names, run_programs};
use interp_core::Panel;
use interp_core::canon::{Action, Canon};
use mill_common::mill;

fn dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../examples/mill")
}

fn texts(sub: &str) -> Vec<(String, String)> {
    let mut v: Vec<(String, String)> = fs::read_dir(dir().join(sub))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "nc"))
        .map(|p| (p.file_name().unwrap().to_string_lossy().into_owned(), fs::read_to_string(&p).unwrap()))
        .collect();
    v.sort();
    v
}

fn run_text(text: &str) -> Run {
    let lib: Vec<String> = texts("lib").into_iter().map(|(_, t)| t).collect();
    let refs: Vec<&str> = lib.iter().map(String::as_str).collect();
    run_programs(text, &refs, mill(), Panel::default())
}

fn run(name: &str) -> Run {
    let r = run_text(&fs::read_to_string(dir().join(name)).unwrap());
    assert!(r.alarms.is_empty(), "{name}: {:?}", r.alarms);
    r
}

fn xyz(c: &Canon) -> Option<[f64; 3]> {
    c.action.endpoint().map(|e| [0, 1, 2].map(|i| e.work.0[i] as f64 / 1e6))
}

fn mxyz(c: &Canon) -> Option<[f64; 3]> {
    c.action.endpoint().map(|e| [0, 1, 2].map(|i| e.machine.0[i] as f64 / 1e6))
}

fn near(a: (f64, f64), b: (f64, f64)) -> bool {
    (a.0 - b.0).abs() < 1.5e-6 && (a.1 - b.1).abs() < 1.5e-6
}

fn feeds(r: &Run) -> Vec<[f64; 3]> {
    r.actions.iter().filter(|c| matches!(c.action, Action::Linear(_))).filter_map(xyz).collect()
}

#[test]
fn every_mill_example_runs_to_m30() {
    let all = texts("");
    assert!(all.len() >= 7, "{} examples", all.len());
    for (name, text) in all {
        let r = run_text(&text);
        assert!(r.alarms.is_empty(), "{name}: {:?}", r.alarms);
        assert_eq!(kind_names(&r).last().map(String::as_str), Some("end true"), "{name}");
    }
}

/// Six holes on R40 about X100 Y60 (the G52 origin) at 0°, 60° … 300°; the first
/// five leave the tool on R (G99, Z2), the last returns to the initial Z50 (G98).
#[test]
fn bolt_circle_points_and_levels() {
    let r = run("bolt_circle_g16.nc");
    let holes: Vec<[f64; 3]> = feeds(&r);
    assert_eq!(holes.len(), 6);
    for (k, h) in holes.iter().enumerate() {
        let a = (60.0 * k as f64).to_radians();
        assert!(near((h[0], h[1]), (40.0 * a.cos(), 40.0 * a.sin())), "hole {k}: {h:?} (local frame)");
        assert_eq!(h[2], -10.0);
    }
    let after_last = r.actions.iter().filter(|c| c.line == 16).filter_map(xyz).next_back().unwrap();
    assert_eq!(after_last[2], 50.0, "G98: back to the initial level");
    let before_last = r.actions.iter().filter(|c| c.line == 15).filter_map(xyz).next_back().unwrap();
    assert_eq!(before_last[2], 2.0, "G99: stays on R");
    let m = r.actions.iter().filter(|c| matches!(c.action, Action::Linear(_))).filter_map(mxyz).next().unwrap();
    assert!(near((m[0], m[1]), (-300.0 + 140.0, -200.0 + 60.0)), "the local origin X100 Y60: {m:?}");
}

/// The pocket (30 × 20 about the local origin) as drawn, at half size (G51 I/J 0.5),
/// turned 30° (G68), and 1.5 times turned −15° (scaling first, seed 004 @5293).
#[test]
fn pockets_scaled_and_rotated() {
    let r = run("pockets_scaled_rotated.nc");
    let cuts: Vec<(f64, f64)> = r
        .actions
        .iter()
        .filter(|c| matches!(c.action, Action::Linear(_)))
        .filter_map(mxyz)
        .map(|p| (p[0] + 300.0, p[1] + 200.0))
        .collect();
    // Each pocket: the plunge, then four sides.
    let corners = [(-15.0, -10.0), (15.0, -10.0), (15.0, 10.0), (-15.0, 10.0), (-15.0, -10.0)];
    let pocket = |origin: (f64, f64), k: f64, deg: f64| -> Vec<(f64, f64)> {
        let (s, c) = deg.to_radians().sin_cos();
        corners.iter().map(|&(x, y)| (origin.0 + k * (x * c - y * s), origin.1 + k * (x * s + y * c))).collect()
    };
    let want = [
        pocket((40.0, 40.0), 1.0, 0.0),
        pocket((120.0, 40.0), 0.5, 0.0),
        pocket((40.0, 110.0), 1.0, 30.0),
        pocket((120.0, 110.0), 1.5, -15.0),
    ];
    assert_eq!(cuts.len(), 4 * 5);
    for (i, w) in want.iter().enumerate() {
        for (j, p) in w.iter().enumerate() {
            let got = cuts[i * 5 + j];
            assert!(near(got, *p), "pocket {i} point {j}: {got:?} vs {p:?}");
        }
    }
}

/// G98/G99 levels of the drilling program: between G99 holes the tool stays on R
/// (Z2), after the G98 hole it is back on the initial level (Z30); the G82 and G89
/// dwells; G76 shifts −X (parameter 5149 = 2); the taps' leads.
#[test]
fn drilling_levels_dwells_and_taps() {
    let r = run("drilling_g98_g99.nc");
    let last_z = |line: u32| r.actions.iter().filter(|c| c.line == line).filter_map(xyz).next_back().unwrap()[2];
    assert_eq!([last_z(9), last_z(10), last_z(11)], [2.0, 2.0, 30.0]);
    assert_eq!([last_z(13), last_z(14)], [2.0, 30.0]);
    let k = kind_names(&r);
    assert_eq!(k.iter().filter(|n| *n == "dwell 300").count(), 2);
    assert_eq!(k.iter().filter(|n| *n == "dwell 500").count(), 1);
    let shifted: Vec<[f64; 3]> = r.actions.iter().filter(|c| c.line == 23).filter_map(xyz).collect();
    assert!(shifted.iter().any(|p| (p[0] - 69.7).abs() < 1e-9 && p[2] == -12.0), "{shifted:?}");
    let leads: Vec<i64> = r
        .actions
        .iter()
        .filter_map(|c| match c.action {
            Action::Tap(t) => Some(t.lead),
            Action::Linear(m) if c.line == 28 => Some(m.feed.value),
            _ => None,
        })
        .collect();
    assert_eq!(leads, vec![1_250_000, 1_250_000, 1_000_000, 1_000_000, 1_000_000, 1_000_000]);
}

/// The offsets G10 wrote are in effect: G55 (−150, −200, −250) with H4 110 − 0.02,
/// then G54.1 P2 (−420, −120, −260).
#[test]
fn g10_offsets_in_effect() {
    let r = run("g10_offsets.nc");
    let cut: Vec<[f64; 3]> =
        r.actions.iter().filter(|c| matches!(c.action, Action::Linear(_))).filter_map(mxyz).collect();
    let z = -1.0 + 109.98;
    let want = [
        [-150.0, -200.0, z - 250.0],
        [-130.0, -200.0, z - 250.0],
        [-420.0, -120.0, z - 260.0],
        [-420.0, -100.0, z - 260.0],
    ];
    for (g, w) in cut.iter().zip(want) {
        assert!(g.iter().zip(w).all(|(a, b)| (a - b).abs() < 1e-9), "{cut:?}");
    }
    let cfg = r.interp.config();
    assert_eq!(cfg.tools.get(4).map(|t| (t.length(), t.cutter_radius())), Some((109_980_000, 6_000_000)));
}

/// The compensated contour: every straight edge 5 mm out (D1), the R20 corner a
/// concentric R25, the chamfer's offset parallel to it.
#[test]
fn contour_offset_by_d() {
    let r = run("contour_g41.nc");
    let left = |a: (f64, f64), b: (f64, f64), p: [f64; 3]| {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        ((p[1] - a.1) * dx - (p[0] - a.0) * dy) / (dx * dx + dy * dy).sqrt()
    };
    let edges = [
        (13, (0.0, 0.0), (0.0, 40.0)),
        (15, (20.0, 60.0), (70.0, 60.0)),
        (16, (70.0, 60.0), (80.0, 50.0)),
        (17, (80.0, 50.0), (80.0, 0.0)),
        (18, (80.0, 0.0), (0.0, 0.0)),
    ];
    let mut from: Option<[f64; 3]> = None;
    for c in &r.actions {
        let Some(p) = xyz(c) else { continue };
        if let Some(&(_, a, b)) = edges.iter().find(|e| e.0 == c.line)
            && matches!(c.action, Action::Linear(_))
        {
            for q in [from.unwrap(), p] {
                assert!((left(a, b, q) - 5.0).abs() < 1e-6, "line {}: {q:?}", c.line);
            }
        }
        if c.line == 14
            && let Action::Arc(a) = c.action
        {
            let (cx, cy) = (a.center.work.0[0] as f64 / 1e6, a.center.work.0[1] as f64 / 1e6);
            assert!(near((cx, cy), (20.0, 40.0)));
            for q in [from.unwrap(), p] {
                assert!((((q[0] - cx).powi(2) + (q[1] - cy).powi(2)).sqrt() - 25.0).abs() < 1e-6, "{q:?}");
            }
        }
        from = Some(p);
    }
}

/// Seed 004's examples: E6 point A, E7's abcd, E8's rotated square, E9's G29
/// through G28's intermediate point, E11's tool change.
#[test]
fn seed_examples_points() {
    let r = run("seed004_examples.nc");
    let at = |line: u32| r.actions.iter().filter(|c| c.line == line).filter_map(xyz).collect::<Vec<_>>();
    let a = at(35)[0];
    assert!(near((a[0], a[1]), (50.0 * 30f64.to_radians().cos(), 50.0 * 30f64.to_radians().sin())), "A {a:?}");
    // E7: about O(40, 30) by 0.5: A(20, 20) → (30, 25), B(60, 20) → (50, 25) …
    let abcd: Vec<(f64, f64)> = (39..=43).map(|l| at(l)[0]).map(|p| (p[0], p[1])).collect();
    for (g, w) in abcd.iter().zip([(30.0, 25.0), (50.0, 25.0), (50.0, 35.0), (30.0, 35.0), (30.0, 25.0)]) {
        assert!(near(*g, w), "{abcd:?}");
    }
    for (first, deg) in [(47, 20.0f64), (52, -20.0)] {
        let (s, c) = deg.to_radians().sin_cos();
        let rot = |x: f64, y: f64| (x * c - y * s, x * s + y * c);
        let pts: Vec<(f64, f64)> = (first..first + 3).map(|l| at(l)[0]).map(|p| (p[0], p[1])).collect();
        for (g, w) in pts.iter().zip([rot(40.0, 0.0), rot(40.0, 20.0), rot(0.0, 20.0)]) {
            assert!(near(*g, w), "{deg}: {pts:?}");
        }
    }
    // G91 G28 Z0 left Z's intermediate point where Z was (Z20).
    let g29 = at(59);
    assert_eq!(g29, vec![[40.0, 30.0, 20.0], [60.0, 20.0, 20.0]]);
    assert!(matches!(r.actions[0].action, Action::ToolChange(t) if t.tool == 8));
}

/// E1: the three contours W1–W3 at the G52 origins (6, 6), (10.5, 4.8), (14.5, 8.3);
/// E12: M98 P101 L3 drills three spots 10 apart.
#[test]
fn local_frames_and_subprogram_repeats() {
    let r = run("local_frames_g52.nc");
    let cuts: Vec<(f64, f64)> = r
        .actions
        .iter()
        .filter(|c| matches!(c.action, Action::Linear(_)))
        .filter_map(mxyz)
        .map(|p| ((p[0] + 300.0 + 1e-9).round_ties_even_3(), (p[1] + 200.0).round_ties_even_3()))
        .collect();
    let mut want = Vec::new();
    for (x, y) in [(6.0, 6.0), (10.5, 4.8), (14.5, 8.3)] {
        want.extend([(x, y), (x + 4.0, y), (x + 4.0, y + 3.0), (x, y + 3.0), (x, y)]);
    }
    want.extend([(40.0, 0.0), (50.0, 0.0), (60.0, 0.0)]);
    assert_eq!(cuts, want);
}

trait Round3 {
    fn round_ties_even_3(self) -> f64;
}

impl Round3 for f64 {
    fn round_ties_even_3(self) -> f64 {
        (self * 1000.0).round() / 1000.0
    }
}

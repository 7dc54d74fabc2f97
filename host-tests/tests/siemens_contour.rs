//! SINUMERIK CYCLE72 contour milling on the mill (seed 001 lines 5450-5764): the
//! offset path, the depth levels, the approach and departure, the alarms. The
//! programmed contour is built here from the document's example (chamfers of
//! length 10, a G2 arc of radius 25) and every cutting move the cycle emits on
//! it is sampled and measured against it.

mod mill_common;

use mill_common::plane::*;

use host_tests::{Run, run_with};
use interp_core::Panel;

/// The document's contour MYKONTUR (lines 5712-5720): CHF=10 is a chamfer of
/// length 10, legs 10/√2.
fn corners() -> Vec<[f64; 2]> {
    let c = 10.0 / 2f64.sqrt();
    vec![
        [150.0, 160.0],
        [230.0 - c, 160.0],
        [230.0, 160.0 - c],
        [230.0, 80.0 + c],
        [230.0 - c, 80.0],
        [125.0, 80.0],
        [125.0, 135.0],
    ]
}

/// Distance of `p` to the programmed contour: the lines, then the G2 arc from
/// (125, 135) to (150, 160) about (150, 135) (the quarter from 180° to 90°).
fn dist(p: [f64; 2]) -> f64 {
    let k = corners();
    let mut d = f64::MAX;
    for w in k.windows(2) {
        d = d.min(seg_dist(p, w[0], w[1]));
    }
    let (cx, cy) = (150.0, 135.0);
    let ang = (p[1] - cy).atan2(p[0] - cx).to_degrees();
    let on_arc = if (90.0..=180.0).contains(&ang) { ((p[0] - cx).hypot(p[1] - cy) - 25.0).abs() } else { f64::MAX };
    let ends =
        [[125.0, 135.0], [150.0, 160.0]].iter().map(|e| (p[0] - e[0]).hypot(p[1] - e[1])).fold(f64::MAX, f64::min);
    d.min(on_arc).min(ends)
}

const HEAD: &str = "$TC_DP1[20,1]=120 $TC_DP6[20,1]=7\nT20 D1\nM6\nS500 M3 F3000\nG17 G0 G90 G94 X100 Y200 Z250\n";
const CONTOUR: &str = "M02\nPROC MYKONTUR\nN100 G1 G90 X150 Y160\nN110 X230 CHF=10\nN120 Y80 CHF=10\nN130 X125\nN140 Y135\nN150 G2 X150 Y160 CR=25\nN160 M17\n";

fn run72(args: &str) -> Run {
    go(&format!("{HEAD}CYCLE72(\"MYKONTUR\", {args})\n{CONTOUR}"))
}

/// The cuts at depth `z` on the contour (the approach before, the departure after
/// left out: the moves between the first and last cut of the level).
fn passes(segs: &[Seg], z: f64) -> Vec<Seg> {
    let at: Vec<Seg> =
        segs.iter().copied().filter(|s| (s.from[2] - z).abs() < 1e-6 && (s.to[2] - z).abs() < 1e-6).collect();
    at[1..at.len() - 1].to_vec()
}

/// Levels the cutter cuts in the plane at.
fn levels(segs: &[Seg]) -> Vec<f64> {
    let mut z: Vec<f64> = Vec::new();
    for s in segs {
        if s.feed == 800.0 && (s.from[2] - s.to[2]).abs() < 1e-9 && !z.iter().any(|q| (q - s.to[2]).abs() < 1e-6) {
            z.push(s.to[2]);
        }
    }
    z
}

/// Finishing (VARI 2) G41: every point of every pass is the cutter radius 7 from
/// the contour; roughing (VARI 1) radius + _FAL = 8. Nothing comes closer.
#[test]
fn the_offset_path_keeps_radius_plus_allowance_from_the_contour() {
    for (vari, off) in [(2, 7.0), (1, 8.0)] {
        let r = run72(&format!("250, 200, 3, 175, 10, 1, 1.5, 800, 400, {vari}, 41, 2, 20, 1000, 2, 20"));
        let segs = moves(&r.actions);
        let lv = levels(&segs);
        assert!(!lv.is_empty());
        for &z in &lv {
            let ps = passes(&segs, z);
            assert!(ps.len() >= 7, "{ps:?}");
            for s in &ps {
                for p in samples(s) {
                    assert!((dist(p) - off).abs() < 1e-4, "VARI {vari} z {z}: {p:?} is {} off", dist(p));
                }
            }
        }
        for s in segs.iter().filter(|s| s.to[2] < 200.0 && s.from[2] < 200.0) {
            for p in samples(s) {
                assert!(dist(p) > off - 1e-4, "gouge at {p:?}");
            }
        }
    }
}

/// G42 runs on the other side (inside the closed contour clockwise), G40 on it.
#[test]
fn right_and_centre() {
    let r = run72("250, 200, 3, 175, 30, 0, 0, 800, 400, 2, 40, 1, 5, 1000, 1, 5");
    let segs = moves(&r.actions);
    for s in passes(&segs, 175.0) {
        for p in samples(&s) {
            assert!(dist(p) < 1e-4, "{p:?}");
        }
    }
    let r = run72("250, 200, 3, 175, 30, 0, 0, 800, 400, 2, 42, 1, 5, 1000, 1, 5");
    let segs = moves(&r.actions);
    let ps = passes(&segs, 175.0);
    // The first pass runs along Y = 160 − 7 (inside).
    assert!((ps[0].from[1] - 153.0).abs() < 1e-6 && (ps[0].to[1] - 153.0).abs() < 1e-6, "{:?}", ps[0]);
    for s in &ps {
        for p in samples(s) {
            assert!((dist(p) - 7.0).abs() < 1e-4, "{p:?} is {} off", dist(p));
        }
    }
}

/// MID divides the depth evenly: roughing from RFP + SDIS 203 to DP + FALD
/// 176.5 (3 levels), finishing to DP 175; MID 0 is one level.
#[test]
fn depth_levels_per_mid() {
    let each = |vari: i32, mid: f64| {
        levels(&moves(
            &run72(&format!("250, 200, 3, 175, {mid}, 1, 1.5, 800, 400, {vari}, 41, 2, 20, 1000, 2, 20")).actions,
        ))
    };
    let want =
        |from: f64, to: f64, n: usize| (1..=n).map(|k| from + (to - from) * k as f64 / n as f64).collect::<Vec<_>>();
    for (got, w) in [
        (each(1, 10.0), want(203.0, 176.5, 3)),
        (each(2, 10.0), want(203.0, 175.0, 3)),
        (each(2, 0.0), want(203.0, 175.0, 1)),
        (each(1, 5.0), want(203.0, 176.5, 6)),
    ] {
        assert_eq!(got.len(), w.len(), "{got:?} {w:?}");
        for (g, w) in got.iter().zip(&w) {
            assert!((g - w).abs() < 1e-5, "{got:?} {w:?}");
        }
    }
}

/// The approach: quarter circle of radius _LP1 tangent at the offset start
/// (150, 167) with its centre on the cutter's side; semicircle; straight along
/// the tangent for _LP1 + the radius (the cutter's edge, line 5652). The
/// departure mirrors it at the end. Between levels VARI's hundreds digit.
#[test]
fn approach_and_departure_geometry() {
    let z = 175.0;
    for (as1, a, centre) in [
        (2, [140.0, 177.0], Some([150.0, 177.0])),
        (3, [150.0, 187.0], Some([150.0, 177.0])),
        (1, [150.0 - 17.0, 167.0], None),
    ] {
        let r = run72(&format!("250, 200, 3, 175, 0, 0, 0, 800, 400, 2, 41, {as1}, 10, 1000, {as1}, 10"));
        let segs = moves(&r.actions);
        let i = segs.iter().position(|s| (s.to[2] - z).abs() < 1e-6 && (s.from[2] - z).abs() < 1e-6).unwrap();
        let app = segs[i];
        assert!((app.from[0] - a[0]).abs() < 1e-6 && (app.from[1] - a[1]).abs() < 1e-6, "{as1}: {app:?}");
        assert!((app.to[0] - 150.0).abs() < 1e-6 && (app.to[1] - 167.0).abs() < 1e-6, "{as1}: {app:?}");
        assert_eq!(app.arc, centre.map(|c| (c, false)), "{as1}");
        // The departure ends where the approach began, mirrored about X150.
        let dep = segs.iter().rev().find(|s| (s.from[2] - z).abs() < 1e-6 && (s.to[2] - z).abs() < 1e-6).unwrap();
        assert!((dep.from[0] - 150.0).abs() < 1e-6 && (dep.from[1] - 167.0).abs() < 1e-6, "{dep:?}");
        assert!((dep.to[0] - (300.0 - a[0])).abs() < 1e-6 && (dep.to[1] - a[1]).abs() < 1e-6, "{as1}: {dep:?}");
        // One level: the cycle ends over the departure point at RTP.
        let last = segs.last().unwrap();
        assert_eq!(last.to, [300.0 - a[0], a[1], 250.0]);
    }
    // In space (tens 1): the approach descends from 175 + SDIS onto the level.
    let r = run72("250, 200, 3, 175, 0, 0, 0, 800, 400, 2, 41, 12, 20, 1000, 12, 20");
    let segs = moves(&r.actions);
    let app = segs.iter().find(|s| s.arc.is_some()).unwrap();
    assert_eq!((app.from[2], app.to[2]), (178.0, 175.0));
    // Between levels: hundreds 0 RTP, 1 RFP + SDIS, 2 by SDIS over the level.
    for (h, lift) in [(0, 250.0), (1, 203.0), (2, 203.0 - 14.0 + 3.0)] {
        let r = run72(&format!("250, 200, 3, 175, 14, 0, 0, 800, 400, {h}12, 41, 2, 20, 1000, 2, 20"));
        let segs = moves(&r.actions);
        let up = segs.iter().find(|s| s.to[2] > s.from[2]).unwrap();
        assert_eq!(up.to[2], lift, "hundreds {h}");
        assert_eq!(up.feed, 1000.0, "G1 at _FF3");
    }
}

/// Bad calls stop on their line with the document's alarm and move nothing.
#[test]
fn alarms_move_nothing() {
    let ok = "250, 200, 3, 175, 10, 1, 1.5, 800, 400, 111, 41, 2, 20, 1000, 2, 20";
    for (edit, args, code) in [
        ("", "250, 200, 3, 175, 10, 1, 1.5, 800, 400, 111, 41, 2, 0, 1000, 2, 20", 61116),
        ("", "250, 200, 3, 175, 10, 1, 1.5, 800, 400, 111, 41, 2, 20, 1000, 1, 0", 61116),
        ("", "250, 200, 3, 175, 10, 1, 1.5, 800, 400, 3, 41, 2, 20, 1000, 2, 20", 61002),
        ("", "250, 200, 3, 175, 10, 1, 1.5, 800, 400, 131, 41, 2, 20, 1000, 2, 20", 61002),
        ("", "250, 200, 3, 175, 10, 1, 1.5, 800, 400, 1, 43, 2, 20, 1000, 2, 20", 61002),
        ("", "250, 200, 3, 175, 10, 1, 1.5, 800, 400, 1, 41, 4, 20, 1000, 2, 20", 61002),
        ("", "250, 200, 3, 210, 10, 1, 1.5, 800, 400, 1, 41, 2, 20, 1000, 2, 20", 61101),
        ("", "250, 200, 3, 175, 10, 1, 30, 800, 400, 1, 41, 2, 20, 1000, 2, 20", 61101),
        ("T20 D0", ok, 61000),
        ("M6\nS", ok, 61009),
        // Inside (G42) the G2 arc of radius 25 would be offset through its centre.
        ("DP6[20,1]=30", "250, 200, 3, 175, 10, 1, 1.5, 800, 400, 111, 42, 1, 5, 1000, 1, 5", 61105),
    ] {
        let head = match edit {
            "" => HEAD.to_string(),
            "T20 D0" => HEAD.replace("T20 D1", edit),
            "M6\nS" => HEAD.replace("M6\n", ";\n"),
            e => HEAD.replace("DP6[20,1]=7", e),
        };
        let text = format!("{head}CYCLE72(\"MYKONTUR\", {args})\n{CONTOUR}");
        let r = siemens(&text);
        let line = 6;
        assert_eq!(r.alarm_codes(), vec![(line, code)], "{edit}{args}");
        assert!(!r.actions.iter().any(|c| c.line == line && c.action.endpoint().is_some()), "{args} moved");
    }
    // A negative cutter radius (row 3's wear beyond its radius, as CYCLE90's test).
    let mut c = cfg();
    if let Some(row) = c.tools.get_mut(3) {
        row.x_wear = -4_000_000;
    }
    let text =
        format!("T3 D1\nM6\nS500 M3 F3000\nG17 G0 G90 G94 X100 Y200 Z250\nCYCLE72(\"MYKONTUR\", {ok})\n{CONTOUR}");
    let r = run_with(&text, c, Panel::default());
    assert_eq!(r.alarm_codes(), vec![(5, 61112)]);
    // A label that is not there.
    let r = siemens(&format!("{HEAD}CYCLE72(\"ANFANG:ENDE\", {ok})\nM02\n"));
    assert_eq!(r.alarm_codes().len(), 1, "{:?}", r.alarms);
    assert_eq!(r.alarm_codes()[0].0, 6);
    assert!(!r.actions.iter().any(|c| c.line == 6 && c.action.endpoint().is_some()));
}

/// The document's two examples run (subprogram, label section) and cut alike.
#[test]
fn the_documents_examples_run() {
    let a = go(include_str!("../../examples/sinumerik/mill/cycle72.mpf"));
    let b = go(include_str!("../../examples/sinumerik/mill/cycle72_labels.mpf"));
    let (sa, sb) = (moves(&a.actions), moves(&b.actions));
    assert!(sa.iter().filter(|s| s.arc.is_some()).count() > 10);
    assert_eq!(levels(&sa), levels(&sb));
}

/// G19: the contour's points in Y (abscissa) and Z (ordinate), the infeed along
/// X; a contour of two blocks (start point and one line, line 5594) is enough.
#[test]
fn g19_reads_the_contour_in_its_plane() {
    let r = go("T1 D1\nM6\nS500 M3 F3000\nG19 G0 G90 G94 X100 Y0 Z50\n\
        CYCLE72(\"KLINE\", 100, 80, 2, 70, 0, 0, 0, 800, 400, 2, 41, 1, 5, 1000, 1, 5)\nM02\n\
        PROC KLINE\nG1 Y10 Z20\nY60\nM17\n");
    let ends: Vec<[f64; 3]> =
        r.actions.iter().filter(|c| c.line == 5).filter_map(|c| c.action.endpoint()).map(|e| mm3(&e.work)).collect();
    // Left of +Y in G19 is +Z: Z = 20 + radius 5; straight approach and departure
    // of _LP 5 + the radius; at X = DP 70.
    let cut: Vec<[f64; 3]> = ends.iter().copied().filter(|p| p[0] == 70.0).collect();
    assert_eq!(cut, [[70.0, 0.0, 25.0], [70.0, 10.0, 25.0], [70.0, 60.0, 25.0], [70.0, 70.0, 25.0]]);
    assert_eq!(ends.last(), Some(&[100.0, 70.0, 25.0]));
}

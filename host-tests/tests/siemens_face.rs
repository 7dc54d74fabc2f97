//! SINUMERIK CYCLE71 face milling and the spigots CYCLE76/CYCLE77 on the mill
//! (seed 001 lines 5260-6111). The expected geometry is computed here from the
//! document's definitions — the face is the rectangle from the corner _PA/_PO
//! with the signed _LENG/_WID turned by _STA; a spigot's wall is the rounded
//! rectangle _LENG × _WID (corner radius _CRAD) or the circle of diameter _PRAD —
//! and every move the cycle emits is measured against it.

mod mill_common;

use mill_common::plane::*;

/// The distinct depths of the cutting moves in the plane, in order.
fn cut_levels(segs: &[Seg]) -> Vec<f64> {
    let mut v: Vec<f64> = segs.iter().filter(|s| s.feed > 0.0 && s.from[2] == s.to[2]).map(|s| um(s.to[2])).collect();
    v.dedup();
    v
}

// ---------------------------------------------------------------- CYCLE71

/// The face: corner, signed sides along its own axes, the angle of its length.
struct Rect {
    corner: [f64; 2],
    leng: f64,
    wid: f64,
    sta: f64,
}

impl Rect {
    /// A plane point in the face's axes from the corner: (along the length,
    /// along the width), both towards the face (0 … |LENG|, 0 … |WID|).
    fn local(&self, p: [f64; 2]) -> [f64; 2] {
        let (s, c) = self.sta.to_radians().sin_cos();
        let (x, y) = (p[0] - self.corner[0], p[1] - self.corner[1]);
        let (u, v) = (x * c + y * s, -x * s + y * c);
        [u * self.leng.signum(), v * self.wid.signum()]
    }

    /// The plane point of local `(u, v)`.
    fn plane(&self, u: f64, v: f64) -> [f64; 2] {
        let (s, c) = self.sta.to_radians().sin_cos();
        let (u, v) = (u * self.leng.signum(), v * self.wid.signum());
        [self.corner[0] + u * c - v * s, self.corner[1] + u * s + v * c]
    }

    /// How far a point is outside the face (0 inside).
    fn outside(&self, p: [f64; 2]) -> f64 {
        let [u, v] = self.local(p);
        let du = (-u).max(u - self.leng.abs()).max(0.0);
        let dv = (-v).max(v - self.wid.abs()).max(0.0);
        du.hypot(dv)
    }
}

const HEAD71: &str = "G17 G0 G90 X0 Y0 Z20 F500 S1000 M3 T1 D1\nM6\n";

/// CYCLE71 for each machining direction (_VARI tens 1-4): at the final depth
/// the paths run parallel to the face's length (tens 1, 3) or width (2, 4), each
/// from r + _FDP before the face to r + _FDP beyond it; across, the first lies at
/// _MIDA − r, the last at the width + _FDP1 − r, none more than _MIDA apart;
/// every point of the face is within the cutter radius of a path; the levels
/// are the _MID division from RFP + SDIS to _DP + _FALD; every G0 into the depth
/// is made where the cutter is clear of the face (in the overrun).
#[test]
fn cycle71_paths_cover_the_face() {
    let r = 5.0; // D1
    let (fdp, fdp1, mida) = (3.0, 1.5, 7.0);
    for (tens, leng, wid, sta) in
        [(1, 60.0, 40.0, 0.0), (2, -50.0, 33.0, 25.0), (3, 45.0, -28.0, 170.0), (4, -30.0, -47.0, 90.0)]
    {
        let vari = tens * 10 + 1;
        let text = format!(
            "{HEAD71}CYCLE71(10, 0, 2, -9, 100, 80, {leng}, {wid}, {sta}, 4, {mida}, {fdp}, 0.5, 800, {vari}, {fdp1})\nM30\n"
        );
        let segs = moves(&go(&text).actions);
        let face = Rect { corner: [100.0, 80.0], leng, wid, sta };
        assert_eq!(cut_levels(&segs), levels(2.0, -8.5, 4.0), "VARI {vari}");
        let last: Vec<Seg> = segs.iter().copied().filter(|s| s.feed > 0.0 && near(s.to[2], -8.5)).collect();
        // Paths: cutting moves along the cut direction (index 0 local u, 1 v).
        let (ax, ls, wt) = if tens % 2 == 1 { (0, leng.abs(), wid.abs()) } else { (1, wid.abs(), leng.abs()) };
        let mut across = Vec::new();
        for s in &last {
            let (a, b) = (face.local([s.from[0], s.from[1]]), face.local([s.to[0], s.to[1]]));
            if near(a[1 - ax], b[1 - ax]) {
                let (lo, hi) = (a[ax].min(b[ax]), a[ax].max(b[ax]));
                assert!(near(lo, -(r + fdp)) && near(hi, ls + r + fdp), "VARI {vari}: path {lo}..{hi}");
                across.push(a[1 - ax]);
            } else {
                // A step across (alternating): in the overrun, at the feed.
                assert!(tens >= 3, "VARI {vari}: a diagonal cut");
                assert!(near(a[ax], b[ax]) && (a[ax] < -r || a[ax] > ls + r));
            }
        }
        assert!(near(across[0], mida - r), "VARI {vari}: first path {}", across[0]);
        assert!(near(*across.last().unwrap(), wt + fdp1 - r), "VARI {vari}");
        for w in across.windows(2) {
            assert!(w[1] - w[0] > 0.0 && w[1] - w[0] <= mida + 1e-6, "VARI {vari}: step {}", w[1] - w[0]);
        }
        // Alternating directions cut back and forth; one direction always the same way.
        let dirs: Vec<bool> = last
            .iter()
            .filter_map(|s| {
                let (a, b) = (face.local([s.from[0], s.from[1]]), face.local([s.to[0], s.to[1]]));
                near(a[1 - ax], b[1 - ax]).then_some(b[ax] > a[ax])
            })
            .collect();
        if tens >= 3 {
            assert!(dirs.iter().enumerate().all(|(i, &d)| d == (i % 2 == 0)), "VARI {vari}: {dirs:?}");
        } else {
            assert!(dirs.iter().all(|&d| d), "VARI {vari}");
        }
        // Every point of the face is within r of a path at the final depth.
        let pts: Vec<[f64; 2]> = last.iter().flat_map(samples).collect();
        for i in 0..=30 {
            for j in 0..=30 {
                let p = face.plane(leng.abs() * i as f64 / 30.0, wid.abs() * j as f64 / 30.0);
                let d = pts.iter().map(|q| (q[0] - p[0]).hypot(q[1] - p[1])).fold(f64::MAX, f64::min);
                assert!(d <= r + 0.2, "VARI {vari}: {p:?} uncut ({d})");
            }
        }
        // G0 into the depth only in the overrun, clear of the face.
        for s in segs.iter().filter(|s| s.feed == 0.0 && s.to[2] < 0.0 && s.to[2] < s.from[2]) {
            assert!(face.outside([s.to[0], s.to[1]]) >= r - 1e-3, "VARI {vari}: G0 down over the face at {:?}", s.to);
        }
        // The end: up to RTP where it is.
        let end = segs.last().unwrap();
        assert!(end.feed == 0.0 && near(end.to[2], 10.0) && end.from[0] == end.to[0]);
    }
}

/// One direction: between paths the cutter lifts by the infeed + SDIS when
/// roughing (lines 5325-5327), by _FALD + SDIS when finishing; finishing cuts
/// once, at _DP. The approach: G0 at the height of the call, G0 to RFP + SDIS.
#[test]
fn cycle71_lifts_between_paths() {
    let text = format!("{HEAD71}CYCLE71(10, 0, 2, -9, 100, 80, 60, 40, 0, 4, 8, 3, 0.5, 800, 11, 1.5)\nM30\n");
    let segs = moves(&go(&text).actions);
    let lv = levels(2.0, -8.5, 4.0);
    let ups: Vec<f64> =
        segs.iter().filter(|s| s.feed == 0.0 && s.to[2] > s.from[2] && s.to[2] < 10.0).map(|s| um(s.to[2])).collect();
    assert!(!ups.is_empty());
    let above: Vec<f64> = std::iter::once(2.0).chain(lv.iter().copied()).map(|l| um(l + 2.0)).collect();
    assert!(ups.iter().all(|u| above.contains(u)), "{ups:?}");
    assert_eq!(segs[0].to, [100.0 - 8.0, 80.0 + 8.0 - 5.0, 20.0], "approach at the call's height");
    assert_eq!(segs[1].to[2], 2.0);
    // Finishing: once at -9, lifts of FALD 0.5 + SDIS 2.
    let text = format!("{HEAD71}CYCLE71(10, 0, 2, -9, 100, 80, 60, 40, 0, 4, 8, 3, 0.5, 800, 12, 1.5)\nM30\n");
    let segs = moves(&go(&text).actions);
    assert_eq!(cut_levels(&segs), [-9.0]);
    let ups: Vec<f64> =
        segs.iter().filter(|s| s.feed == 0.0 && s.to[2] > s.from[2] && s.to[2] < 10.0).map(|s| um(s.to[2])).collect();
    assert!(!ups.is_empty() && ups.iter().all(|&u| u == -6.5), "{ups:?}");
}

/// A face whose width + _FDP1 is below _MIDA is one path at _MIDA − r (line
/// 5317); _MIDA 0 is 80 % of the cutter diameter (line 5361).
#[test]
fn cycle71_one_path_and_the_default_width() {
    let text = format!("{HEAD71}CYCLE71(10, 0, 2, -1, 0, 0, 50, 5, 0, 0, 8, 2, 0, 800, 11, 1)\nM30\n");
    let segs = moves(&go(&text).actions);
    let cuts: Vec<Seg> = segs.iter().copied().filter(|s| s.feed > 0.0).collect();
    assert_eq!(cuts.len(), 1);
    assert!(near(cuts[0].to[1], 3.0) && near(cuts[0].from[0], -7.0) && near(cuts[0].to[0], 57.0), "{cuts:?}");
    // _MIDA 0: 8 mm steps for a 5 mm cutter; 30 + 0 − 5 − (8 − 5) = 22 mm in 3 steps.
    let text = format!("{HEAD71}CYCLE71(10, 0, 2, -1, 0, 0, 50, 30, 0, 0, 0, 2, 0, 800, 31, 0)\nM30\n");
    let segs = moves(&go(&text).actions);
    let ys: Vec<f64> = segs.iter().filter(|s| s.feed > 0.0 && s.from[1] == s.to[1]).map(|s| um(s.to[1])).collect();
    assert_eq!(ys, [3.0, 10.333, 17.667, 25.0]);
}

/// The document's example (lines 5407-5448) and the spigots' run.
#[test]
fn the_documents_examples_run() {
    for f in ["cycle71.mpf", "cycle76.mpf", "cycle77.mpf"] {
        let text =
            std::fs::read_to_string(format!("{}/../examples/sinumerik/mill/{f}", env!("CARGO_MANIFEST_DIR"))).unwrap();
        let segs = moves(&go(&text).actions);
        assert!(segs.iter().any(|s| s.feed > 0.0), "{f}");
    }
}

// ---------------------------------------------------------------- spigots

const HEAD76: &str = "G17 G0 G90 X0 Y0 Z20 F500 S1000 M3 T1 D1\nM6\n";

/// The cutting moves below the reference plane, split into the rings (every
/// point at one distance from the wall) and the rest.
fn below(segs: &[Seg]) -> Vec<Seg> {
    segs.iter().copied().filter(|s| s.feed > 0.0 && s.to[2] < 0.0 && s.from[2] == s.to[2]).collect()
}

/// CYCLE76 roughing, from the centre (_ZSD[2] = 0) and from a corner (1): no
/// cutting move comes closer to the wall than r + _FAL, the rings run on it at
/// every level (_MID division to _DP + _FALD), the plunge point is clear of the
/// blank by the cutter radius, and semicircles reach and leave the ring.
#[test]
fn cycle76_walls_at_size_plus_allowance_plus_radius() {
    let r = 5.0;
    for (zsd, pa, po, leng, wid) in
        [(0, 60.0, 50.0, 40.0_f64, 30.0_f64), (1, 80.0, 60.0, -60.0, -40.0), (1, 10.0, 20.0, 50.0, -34.0)]
    {
        let sta = 20.0;
        let text = format!(
            "{HEAD76}_ZSD[2]={zsd}\nCYCLE76(10, 0, 2, -12, , {leng}, {wid}, 6, {pa}, {po}, {sta}, 5, 0.4, 0.3, 300, 100, 0, 1, {}, {})\nM30\n",
            leng.abs() + 8.0,
            wid.abs() + 6.0
        );
        let segs = moves(&go(&text).actions);
        // The centre, computed from the corner in the turned axes.
        let c = if zsd == 0 {
            [pa, po]
        } else {
            let (s, co) = f64::to_radians(sta).sin_cos();
            [pa + leng / 2.0 * co - wid / 2.0 * s, po + leng / 2.0 * s + wid / 2.0 * co]
        };
        let wall = Wall { c, sta, hl: leng.abs() / 2.0, hw: wid.abs() / 2.0, cr: 6.0 };
        let cut = below(&segs);
        let d: Vec<f64> = cut.iter().flat_map(samples).map(|p| wall.outside(p)).collect();
        let min = d.iter().copied().fold(f64::MAX, f64::min);
        assert!(near(min, r + 0.4), "ZSD {zsd}: closest {min}");
        // The rings: the moves all of whose points are at r + FAL; a full ring per level.
        let ring: Vec<&Seg> =
            cut.iter().filter(|s| samples(s).iter().all(|p| near(wall.outside(*p), r + 0.4))).collect();
        // Per level four corners and four sides, the first side in two halves
        // (the ring starts and ends on the length axis).
        assert_eq!(ring.len(), 9 * 3, "ZSD {zsd}");
        assert!(ring.iter().all(|s| s.arc.is_none_or(|a| a.1)), "M3 climb milling: G2");
        assert_eq!(cut_levels(&segs), levels(2.0, -11.7, 5.0), "ZSD {zsd}");
        // The plunges at FFD, at a point clear of the blank (80 + 8 … ) by r.
        let blank = Wall { c, sta, hl: leng.abs() / 2.0 + 4.0, hw: wid.abs() / 2.0 + 3.0, cr: 0.0 };
        let plunges: Vec<&Seg> = segs.iter().filter(|s| s.feed == 100.0).collect();
        assert_eq!(plunges.len(), 3);
        for p in &plunges {
            assert!(blank.outside([p.to[0], p.to[1]]) >= r - 1e-3, "plunge into the blank at {:?}", p.to);
        }
        // Semicircles: 2 per level, G3 (the other way from the ring), tangent.
        let semis: Vec<&Seg> = cut.iter().filter(|s| s.arc.is_some_and(|a| !a.1)).collect();
        assert_eq!(semis.len(), 2 * 3);
    }
}

/// CYCLE77: the rings are circles about _PA/_PO of radius _PRAD/2 + r + _FAL
/// (roughing) or _PRAD/2 + r (finishing); _CDIR 2/3 give G2/G3, 0/1 climb or
/// conventional from the spindle: outside a contour climb under M3 is G2,
/// under M4 G3.
#[test]
fn cycle77_circles_and_directions() {
    let r = 5.0;
    for (vari, fal, want) in [(1, 0.5, 25.0 + r + 0.5), (2, 0.5, 25.0 + r)] {
        let text =
            format!("{HEAD76}CYCLE77(10, 0, 3, -20, , 50, 60, 70, 10, {fal}, 0, 900, 800, 0, {vari}, 62)\nM30\n");
        let segs = moves(&go(&text).actions);
        let cut = below(&segs);
        let ring: Vec<&Seg> = cut.iter().filter(|s| s.arc.is_some_and(|a| a.0 == [60.0, 70.0])).collect();
        assert_eq!(ring.len(), 4 * 3, "VARI {vari}");
        for s in &ring {
            for p in samples(s) {
                assert!(near((p[0] - 60.0).hypot(p[1] - 70.0), want), "VARI {vari}: {p:?}");
            }
        }
        let dmin = cut.iter().flat_map(samples).map(|p| (p[0] - 60.0).hypot(p[1] - 70.0)).fold(f64::MAX, f64::min);
        assert!(near(dmin, want));
        assert_eq!(cut_levels(&segs), levels(3.0, -20.0, 10.0), "VARI {vari}");
    }
    for (m, cdir, cw) in
        [("M3", 2, true), ("M3", 3, false), ("M3", 0, true), ("M3", 1, false), ("M4", 0, false), ("M4", 1, true)]
    {
        let text = format!(
            "G17 G0 G90 X0 Y0 Z20 F500 S600 {m} T1 D1\nM6\nCYCLE77(10, 0, 3, -5, , 50, 60, 70, 10, 0, 0, 900, 800, {cdir}, 1, 62)\nM30\n"
        );
        let segs = moves(&go(&text).actions);
        let dirs: Vec<bool> = segs.iter().filter_map(|s| s.arc.filter(|a| a.0 == [60.0, 70.0]).map(|a| a.1)).collect();
        assert!(!dirs.is_empty() && dirs.iter().all(|&d| d == cw), "{m} CDIR {cdir}");
    }
}

/// Finishing with only a floor allowance (_FAL 0, _FALD > 0) is one ring at _DP;
/// with a wall allowance the wall is finished per _MID down to _DP.
#[test]
fn spigot_finishing_floor_or_wall() {
    let call = |fal: f64, fald: f64| {
        let text =
            format!("{HEAD76}CYCLE77(10, 0, 3, -20, , 50, 60, 70, 10, {fal}, {fald}, 900, 800, 0, 2, 62)\nM30\n");
        cut_levels(&moves(&go(&text).actions))
    };
    assert_eq!(call(0.0, 0.5), [-20.0]);
    assert_eq!(call(0.5, 0.5), levels(3.0, -20.0, 10.0));
}

/// Bad calls stop on their line with the document's alarm and move nothing.
#[test]
fn alarms_move_nothing() {
    let c71 = |vari: &str, leng: &str, mida: &str| {
        format!("CYCLE71(10, 0, 2, -9, 100, 80, {leng}, 40, 0, 4, {mida}, 3, 0.5, 800, {vari}, 1.5)")
    };
    let c77 = "CYCLE77(10, 0, 3, -20, , 50, 60, 70, 10, 0.5, 0, 900, 800, 0, 1, 62)";
    for (pre, call, code) in [
        ("D0\n", c71("11", "60", "8"), 61000),
        ("", c71("13", "60", "8"), 61002),
        ("", c71("51", "60", "8"), 61002),
        ("", c71("1", "60", "8"), 61002),
        ("F0\n", c71("11", "60", "8").replace("800, 11", "0, 11"), 61003),
        ("NO M6", c71("11", "60", "8"), 61009),
        ("NO M6", c71("11", "60", "0"), 61124),
        ("", c71("11", "60", "8").replace("(10, 0, 2, -9", "(10, 0, 2, 9"), 61101),
        ("", c71("11", "60", "10.01"), 61111),
        ("T3 D0\nM6\n", c71("11", "60", "8"), 61000),
        ("", c71("11", "0", "8"), 61118),
        ("D0\n", c77.to_string(), 61009),
        ("NO M6", c77.to_string(), 61009),
        ("", c77.replace("0, 1, 62)", "0, 3, 62)"), 61002),
        ("", c77.replace("0, 1, 62)", "4, 1, 62)"), 61002),
        ("", c77.replace("(10, 0, 3, -20", "(10, 0, 3, 20"), 61101),
        ("", c77.replace("50, 60, 70", "0, 60, 70"), 61213),
        ("", c77.replace("1, 62)", "1, 50)"), 61215),
        ("", c77.replace("1, 62)", "1, )"), 61215),
        ("", c77.replace("70, 10, 0.5", "70, 0, 0.5"), 61610),
        ("F0\n", c77.replace("900, 800", "900, 0"), 61003),
        ("", "CYCLE76(10, 0, 2, -12, , 40, 0, 6, 60, 50, 0, 5, 0.4, 0.3, 300, 100, 0, 1, 48, 36)".into(), 61605),
        ("", "CYCLE76(10, 0, 2, -12, , 40, 30, 15.1, 60, 50, 0, 5, 0.4, 0.3, 300, 100, 0, 1, 48, 36)".into(), 61605),
        ("", "CYCLE76(10, 0, 2, -12, , 40, 30, 6, 60, 50, 0, 5, 0.4, 0.3, 300, 100, 0, 1, 48, 30)".into(), 61215),
        ("", "CYCLE76(10, 0, 2, -12, , 40, 30, 6, 60, 50, 0, 5, 0.4, 0.3, 300, 100, 0, 3, 48, 36)".into(), 61002),
    ] {
        // No M6: T1 is only selected, the spindle holds no tool (T0).
        let (head, pre) = match pre {
            "NO M6" => ("G17 G0 G90 X0 Y0 Z20 F500 S600 M3 T1 D1\n\n", ""),
            _ => ("G17 G0 G90 X0 Y0 Z20 F500 S600 M3 T1 D1\nM6\n", pre),
        };
        let r = siemens(&format!("{head}{pre}{call}\nM30\n"));
        let line = 3 + pre.matches('\n').count() as u32;
        assert_eq!(r.alarm_codes(), vec![(line, code)], "{pre}{call}");
        let before = siemens(&format!("{head}{pre}M30\n"));
        assert_eq!(r.actions.len(), before.actions.len(), "{call} moved");
    }
}

/// Odd values in every parameter (zero, negative, tiny, huge, out of range)
/// raise an alarm or cut; nothing panics.
#[test]
fn odd_calls_do_not_panic() {
    let odd = ["0", "-1", "0.001", "1e6", "-7.5", "99", ""];
    for (name, base) in [
        (
            "CYCLE71",
            ["10", "0", "2", "-9", "100", "80", "60", "40", "0", "4", "8", "3", "0.5", "800", "31", "1.5"].as_slice(),
        ),
        (
            "CYCLE76",
            &[
                "10", "0", "2", "-12", "", "40", "30", "6", "60", "50", "0", "5", "0.4", "0.3", "300", "100", "0", "1",
                "48", "36",
            ],
        ),
        ("CYCLE77", &["10", "0", "3", "-20", "", "50", "60", "70", "10", "0.5", "0", "900", "800", "0", "1", "62"]),
    ] {
        for i in 0..base.len() {
            for v in odd {
                let mut a: Vec<&str> = base.to_vec();
                a[i] = v;
                let text = format!("{HEAD76}_ZSD[2]={}\n{name}({})\nM30\n", i % 2, a.join(", "));
                let _ = siemens(&text);
            }
        }
    }
}

/// In G19 a spigot lies in the Y/Z plane and the infeed runs along X (lines
/// 3486-3494): CYCLE77's ring is a circle about Y_PA Z_PO, the levels along X.
#[test]
fn cycle77_in_g19() {
    let text = "G19 G0 G90 X20 Y0 Z0 F500 S600 M3 T1 D1\nM6\nCYCLE77(10, 0, 3, -20, , 50, 60, 70, 10, 0.5, 0, 900, 800, 0, 1, 62)\nM30\n";
    let segs = moves(&go(text).actions);
    // The arcs about the centre: their centre's Y (the abscissa) is _PA (the
    // semicircles' lies beyond the ring); Seg keeps the centre's X and Y.
    let ring: Vec<&Seg> = segs.iter().filter(|s| s.arc.is_some_and(|a| a.0[1] == 60.0)).collect();
    assert_eq!(ring.len(), 4 * 3);
    for s in &ring {
        assert!(near((s.to[1] - 60.0).hypot(s.to[2] - 70.0), 25.0 + 5.0 + 0.5), "{s:?}");
        assert_eq!(s.from[0], s.to[0]);
    }
    let xs: Vec<f64> = ring.iter().map(|s| um(s.to[0])).collect();
    let mut lv = xs.clone();
    lv.dedup();
    assert_eq!(lv, levels(3.0, -20.0, 10.0));
}

/// `_ZSD[1]=1` starts the depth infeeds at RFP instead of RFP + SDIS (lines
/// 3522-3536, named for CYCLE71 at line 5339); the spigots are not in its list
/// (line 3531) and start at RFP + SDIS whatever it says.
#[test]
fn cycle71_infeeds_from_rfp_with_zsd1() {
    let text = format!("{HEAD71}_ZSD[1]=1\nCYCLE71(10, 0, 2, -9, 100, 80, 60, 40, 0, 4, 8, 3, 0, 800, 31, 1.5)\nM30\n");
    assert_eq!(cut_levels(&moves(&go(&text).actions)), levels(0.0, -9.0, 4.0));
    let text =
        format!("{HEAD76}_ZSD[1]=1\nCYCLE77(10, 0, 3, -20, , 50, 60, 70, 10, 0.5, 0, 900, 800, 0, 1, 62)\nM30\n");
    assert_eq!(cut_levels(&moves(&go(&text).actions)), levels(3.0, -20.0, 10.0));
}

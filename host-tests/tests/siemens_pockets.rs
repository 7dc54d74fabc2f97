//! SINUMERIK POCKET1 to POCKET4 on the mill (seed 001 lines 4421-5258): the
//! pocket walls, the infeed depths, the machining types and the alarms. The
//! expected geometry is computed here from the document's definitions — the
//! wall is the programmed rectangle (LENG × WID, corner radius CRAD, turned by
//! STA1 about CPA/CPO) or circle (PRAD) — and every cutting move the cycle
//! emits is measured against it, sampled along lines and arcs.

mod mill_common;

use mill_common::plane::*;

use interp_core::canon::Action;

impl Wall {
    /// Distance of a point inside the pocket to the wall.
    fn inside(&self, p: [f64; 2]) -> f64 {
        -self.outside(p)
    }

    /// The closest any sample of `segs` comes to the wall, and the farthest.
    fn range(&self, segs: &[Seg]) -> (f64, f64) {
        let d: Vec<f64> = segs.iter().flat_map(samples).map(|p| self.inside(p)).collect();
        (d.iter().copied().fold(f64::MAX, f64::min), d.iter().copied().fold(f64::MIN, f64::max))
    }
}

/// The depths of the plunges: the Z of every feed move straight down the Z axis
/// at `feed`, rounded to µm.
fn plunges(segs: &[Seg], feed: f64) -> Vec<f64> {
    segs.iter()
        .filter(|s| s.arc.is_none() && s.from[0] == s.to[0] && s.from[1] == s.to[1] && s.to[2] < s.from[2])
        .filter(|s| s.feed == feed)
        .map(|s| (s.to[2] * 1000.0).round() / 1000.0)
        .collect()
}

const HEAD: &str = "G17 G0 G90 X60 Y40 Z20 F500 S600 M3 T1 D1\n";

/// POCKET1 roughing (VARI 1): nothing comes closer to the wall than the cutter
/// radius (D1: 5 mm) plus FAL, the outermost ring is exactly there, the plunges
/// at the centre at the MID levels from RFP + SDIS, no finishing feed.
#[test]
fn pocket1_roughing_leaves_the_allowance() {
    let r = go(&format!("{HEAD}POCKET1(5, 0, 1, -12, , 60, 40, 8, 60, 40, 30, 100, 300, 4, 3, 0.75, 1, 0, 77)\nM30\n"));
    let segs = cuts(&r.actions);
    let wall = Wall { c: [60.0, 40.0], sta: 30.0, hl: 30.0, hw: 20.0, cr: 8.0 };
    let cut: Vec<Seg> = segs.iter().copied().filter(|s| s.to[2] < 0.0 || s.from[2] < 0.0).collect();
    let (min, _) = wall.range(&cut);
    assert!(near(min, 5.75), "closest to the wall {min}");
    assert_eq!(plunges(&segs, 100.0), levels(1.0, -12.0, 4.0));
    assert!(segs.iter().all(|s| s.feed != 77.0), "no finishing in VARI 1");
    // It starts at the centre, at the retract plane, and ends there.
    let rapids: Vec<[f64; 3]> = r
        .actions
        .iter()
        .filter_map(|c| if let Action::Rapid(m) = c.action { Some(mm3(&m.to.work)) } else { None })
        .collect();
    assert_eq!(rapids.get(1), Some(&[60.0, 40.0, 5.0]));
    assert_eq!(rapids.last(), Some(&[60.0, 40.0, 5.0]));
}

/// POCKET1 complete (VARI 0): the wall is finished at exactly the cutter radius
/// (the finishing ring at FFP2 and SSF, every point of it), in one depth per
/// MIDF; the corner radius below the cutter radius leaves the cutter's (line
/// 4519): the finishing ring's corners are sharp.
#[test]
fn pocket1_complete_finishes_the_wall() {
    let r = go(&format!(
        "{HEAD}POCKET1(5, 0, 1, -12, , 60, 40, 3, 60, 40, 0, 100, 300, 6, 3, 0.5, 0, 5, 80, 900)\nG0 X0\nM30\n"
    ));
    let segs = cuts(&r.actions);
    let wall = Wall { c: [60.0, 40.0], sta: 0.0, hl: 30.0, hw: 20.0, cr: 3.0 };
    let (min, _) = wall.range(&segs);
    assert!(near(min, 5.0), "closest to the wall {min}");
    let centre = |p: [f64; 3]| near(p[0], 60.0) && near(p[1], 40.0);
    let ring: Vec<Seg> = segs.iter().copied().filter(|s| s.feed == 80.0 && !centre(s.from) && !centre(s.to)).collect();
    assert!(!ring.is_empty());
    for s in &ring {
        for p in samples(s) {
            assert!(near(wall.inside(p), 5.0), "finishing off the wall: {p:?}");
        }
        assert_eq!(s.rpm, 900, "finishing speed SSF");
    }
    assert!(ring.iter().all(|s| s.arc.is_none()), "CRAD 3 < r 5: sharp tool-centre corners");
    // Roughing per MID 6, finishing per MIDF 5 from RFP + SDIS.
    let p = plunges(&segs, 100.0);
    let (rough, finish) = (levels(1.0, -12.0, 6.0), levels(1.0, -12.0, 5.0));
    assert_eq!(p, [rough, finish].concat());
    // Each finishing level cuts the whole wall once: 4 sides.
    assert_eq!(ring.len(), 3 * 5, "{ring:?}");
    // The speed is set back after the cycle (the next block's move runs at S600).
    let last = r.actions.iter().rev().find_map(|c| if let Action::Rapid(m) = c.action { m.spindle.rpm } else { None });
    assert_eq!(last, Some(600));
}

/// VARI 2 finishes only: every cutting move in the plane is at FFP2 (FFP1 when
/// FFP2 is left out), at the cutter radius from the wall.
#[test]
fn pocket1_finishing_only() {
    let r = go(&format!("{HEAD}POCKET1(5, 0, 1, -10, , 60, 40, 8, 60, 40, 0, 100, 300, 4, 3, 0.5, 2)\nM30\n"));
    let segs = cuts(&r.actions);
    assert!(segs.iter().all(|s| s.feed == 300.0 || s.feed == 100.0));
    assert_eq!(plunges(&segs, 100.0), [-10.0]);
    let wall = Wall { c: [60.0, 40.0], sta: 0.0, hl: 30.0, hw: 20.0, cr: 8.0 };
    let arcs: Vec<Seg> = segs.iter().copied().filter(|s| s.arc.is_some()).collect();
    assert_eq!(arcs.len(), 4);
    let (min, max) = wall.range(&arcs);
    assert!(near(min, 5.0) && near(max, 5.0), "{min} {max}");
}

/// CDIR 2/3 give G2/G3; 0 (climb) and 1 (conventional) follow the spindle:
/// M3 climb is G3, M4 climb G2 (line 4098).
#[test]
fn cdir_picks_the_arc_direction() {
    for (m, cdir, cw) in
        [("M3", 2, true), ("M3", 3, false), ("M3", 0, false), ("M3", 1, true), ("M4", 0, true), ("M4", 1, false)]
    {
        let text = format!(
            "G17 G0 G90 X60 Y40 Z20 F500 S600 {m} T1 D1\nPOCKET2(5, 0, 1, -5, , 20, 60, 40, 100, 300, 0, {cdir}, 0, 2)\nM30\n"
        );
        let segs = cuts(&go(&text).actions);
        let dirs: Vec<bool> = segs.iter().filter_map(|s| s.arc.map(|a| a.1)).collect();
        assert!(!dirs.is_empty() && dirs.iter().all(|&d| d == cw), "{m} CDIR {cdir}");
    }
}

/// POCKET2 complete: rings of quarter arcs about the centre from the inside
/// out, the outermost roughing ring at PRAD − r − FAL, the finish at PRAD − r.
#[test]
fn pocket2_circle() {
    let r = go(&format!("{HEAD}POCKET2(5, 0, 1, -8, , 25, 60, 40, 100, 300, 4, 3, 0.5, 0, 0, 200)\nM30\n"));
    let segs = cuts(&r.actions);
    let wall = Wall { c: [60.0, 40.0], sta: 0.0, hl: 25.0, hw: 25.0, cr: 25.0 };
    let (min, _) = wall.range(&segs);
    assert!(near(min, 5.0), "{min}");
    let radii: Vec<f64> = segs
        .iter()
        .filter(|s| s.arc.is_some() && s.feed == 300.0)
        .map(|s| ((s.to[0] - 60.0).hypot(s.to[1] - 40.0) * 1000.0).round() / 1000.0)
        .collect();
    // 19.5 mm in steps of at most 8 mm: 3 rings at 6.5, 13, 19.5, four arcs each,
    // on each level.
    let ring = [[6.5; 4], [13.0; 4], [19.5; 4]].concat();
    assert_eq!(radii, ring.repeat(levels(1.0, -8.0, 4.0).len()));
    let fin: Vec<Seg> = segs.iter().copied().filter(|s| s.arc.is_some() && s.feed == 200.0).collect();
    assert_eq!(fin.len(), 4);
    let (lo, hi) = wall.range(&fin);
    assert!(near(lo, 5.0) && near(hi, 5.0));
    assert!(fin.iter().all(|s| s.arc.unwrap().0 == [60.0, 40.0]));
    // Depth: plunges at the centre per MID 4 from RFP + SDIS, then the finish
    // (MIDF 0: straight to the depth).
    assert_eq!(plunges(&segs, 100.0), [levels(1.0, -8.0, 4.0), vec![-8.0]].concat());
}

/// Bad calls stop on their line with the document's alarm and move nothing.
#[test]
fn alarms_of_the_pockets_move_nothing() {
    let head = "G17 G0 G90 X60 Y40 Z20 F500 S600 M3 T1 D1\n";
    for (call, code) in [
        ("D0\nPOCKET1(5, 0, 1, -10, , 60, 40, 8, 60, 40, 0, 100, 300, 4, 3, 0.5, 1)", 61000),
        ("POCKET1(5, 0, 1, -10, , 60, 40, 8, 60, 40, 0, 100, 300, 4, 3, 0.5, 3)", 61002),
        ("POCKET1(5, 0, 1, -10, , 60, 40, 8, 60, 40, 0, 100, 300, 4, 3, 0.5, 11)", 61002),
        ("POCKET2(5, 0, 1, -10, , 20, 60, 40, 100, 300, 4, 4, 0.5, 1)", 61002),
        ("POCKET1(5, 5, 1, , 10, 60, 40, 8, 60, 40, 0, 100, 300, 4, 3, 0.5, 1)", 61101),
        ("POCKET2(5, 0, 1, 3, , 20, 60, 40, 100, 300, 4, 3, 0.5, 1)", 61101),
        ("POCKET1(5, 0, 1, -10, , 60, 9.9, 8, 60, 40, 0, 100, 300, 4, 3, 0.5, 1)", 61105),
        ("POCKET2(5, 0, 1, -10, , 4.9, 60, 40, 100, 300, 4, 3, 0.5, 1)", 61105),
    ] {
        let r = siemens(&format!("{head}{call}\nM30\n"));
        let line = 2 + call.matches('\n').count() as u32;
        assert_eq!(r.alarm_codes(), vec![(line, code)], "{call}");
        let before = siemens(&format!("{head}{}M30\n", if line == 3 { "D0\n" } else { "" }));
        assert_eq!(r.actions.len(), before.actions.len(), "{call} moved");
    }
}

/// The document's examples (lines 4543-4574, 4688-4712) run.
#[test]
fn the_documents_examples_run() {
    for f in ["pocket1.mpf", "pocket2.mpf", "pocket3.mpf", "pocket4.mpf"] {
        let text =
            std::fs::read_to_string(format!("{}/../examples/sinumerik/mill/{f}", env!("CARGO_MANIFEST_DIR"))).unwrap();
        let r = go(&text);
        assert!(r.actions.iter().any(|c| matches!(c.action, Action::Arc(_))), "{f}");
    }
}

// ---- POCKET3 / POCKET4 (lines 4714-5258) ----

/// The segment's length in the plane and its drop along Z.
fn plane_len(s: &Seg) -> f64 {
    (s.to[0] - s.from[0]).hypot(s.to[1] - s.from[1])
}

fn at_centre(p: [f64; 3], c: [f64; 2]) -> bool {
    near(p[0], c[0]) && near(p[1], c[1])
}

/// POCKET4 roughing on a helix (_VARI 21): every insertion turn is a full
/// circle of radius _RAD1 about the centre dropping exactly _DP1 (the level
/// step 4 mm is two turns of 2 mm), followed by one flat turn at the level;
/// nothing comes closer to the wall than the cutter radius + _FAL.
#[test]
fn pocket4_helix_insertion_pitch_and_wall() {
    let r = go(&format!("{HEAD}POCKET4(5, 0, 1, -11, 25, 60, 40, 4, 0.5, 0, 300, 100, 3, 21, 0, 0, 0, 3, 2)\nM30\n"));
    let segs = cuts(&r.actions);
    let c = [60.0, 40.0];
    let helix: Vec<Seg> = segs.iter().copied().filter(|s| s.arc.is_some() && !near(s.from[2], s.to[2])).collect();
    let lv = levels(1.0, -11.0, 4.0);
    assert_eq!(helix.len(), 2 * lv.len(), "{helix:?}");
    for h in &helix {
        let (cc, cw) = h.arc.unwrap();
        assert!(near(cc[0], c[0]) && near(cc[1], c[1]));
        assert!(!cw, "G3: CDIR 3");
        assert!(near((h.from[0] - c[0]).hypot(h.from[1] - c[1]), 3.0), "helix radius _RAD1");
        assert!(near(plane_len(h), 0.0), "a full turn");
        assert!(near(h.from[2] - h.to[2], 2.0), "pitch _DP1: {h:?}");
        assert_eq!(h.feed, 100.0, "_FFD");
    }
    // After the turns, one flat turn at each level.
    for z in &lv {
        assert!(
            segs.iter().any(|s| s.arc.is_some() && near(s.from[2], *z) && near(s.to[2], *z) && near(plane_len(s), 0.0)),
            "flat turn at {z}"
        );
    }
    let wall = Wall { c, sta: 0.0, hl: 25.0, hw: 25.0, cr: 25.0 };
    let (min, _) = wall.range(&segs);
    assert!(near(min, 5.5), "closest to the wall {min}");
}

/// POCKET3 roughing (_VARI 11): the wall at half size − _FAL − r from every
/// segment (turned by _STA), the floor left at _DP + _FALD, the rings at most
/// _MIDA apart and evenly spaced.
#[test]
fn pocket3_roughing_leaves_wall_and_floor_allowances() {
    let r = go(&format!("{HEAD}POCKET3(5, 0, 1, -10, 60, 40, 8, 60, 40, 30, 4, 0.75, 0.5, 300, 100, 3, 11, 3)\nM30\n"));
    let segs = cuts(&r.actions);
    let wall = Wall { c: [60.0, 40.0], sta: 30.0, hl: 30.0, hw: 20.0, cr: 8.0 };
    let (min, _) = wall.range(&segs);
    assert!(near(min, 5.75), "closest to the wall {min}");
    let deepest = segs.iter().map(|s| s.to[2]).fold(f64::MAX, f64::min);
    assert!(near(deepest, -9.5), "floor allowance: {deepest}");
    assert_eq!(plunges(&segs, 100.0), levels(1.0, -9.5, 4.0));
    // The ring starts on the length axis at the first level: their distances
    // from the centre step outwards by at most _MIDA, all steps equal.
    let z1 = levels(1.0, -9.5, 4.0)[0];
    let (s, c) = 30f64.to_radians().sin_cos();
    let mut d: Vec<f64> = segs
        .iter()
        .filter(|g| g.arc.is_none() && near(g.to[2], z1) && near(g.from[2], z1))
        .map(|g| ((g.to[0] - 60.0) * c + (g.to[1] - 40.0) * s, -(g.to[0] - 60.0) * s + (g.to[1] - 40.0) * c))
        .filter(|(u, v)| near(*v, 0.0) && *u > 0.0)
        .map(|(u, _)| u)
        .collect();
    d.sort_by(f64::total_cmp);
    d.dedup_by(|a, b| near(*a, *b));
    // Outermost ring start at 30 − 5.75; the innermost 24.25 − 14.25 = 10.
    assert!(near(*d.last().unwrap(), 24.25) && near(d[0], 10.0), "{d:?}");
    let steps: Vec<f64> = d.windows(2).map(|w| w[1] - w[0]).collect();
    assert!(steps.iter().all(|&x| x <= 3.0 + 1e-3 && near(x, steps[0])), "{steps:?}");
}

/// POCKET3 finishing (_VARI 12): the wall ring at exactly the cutter radius,
/// reached and left on quarter arcs, per _MID level down to _DP + _FALD; then
/// the floor at _DP, plunged at _FFD from _DP + _FALD + _SDIS.
#[test]
fn pocket3_finishing_edge_then_floor() {
    let r = go(&format!("{HEAD}POCKET3(5, 0, 1, -10, 60, 40, 8, 60, 40, 0, 4, 0.75, 0.5, 300, 100, 3, 12)\nM30\n"));
    let segs = cuts(&r.actions);
    let wall = Wall { c: [60.0, 40.0], sta: 0.0, hl: 30.0, hw: 20.0, cr: 8.0 };
    let (min, _) = wall.range(&segs);
    assert!(near(min, 5.0), "{min}");
    let edge = levels(1.0, -9.5, 4.0);
    for z in &edge {
        // The ring at this level: every segment at the wall distance 5 exactly.
        let ring: Vec<Seg> = segs
            .iter()
            .copied()
            .filter(|s| near(s.from[2], *z) && near(s.to[2], *z) && near(wall.inside([s.from[0], s.from[1]]), 5.0))
            .filter(|s| near(wall.inside([s.to[0], s.to[1]]), 5.0))
            .collect();
        assert_eq!(ring.len(), 9, "4 sides (the first split at the start), 4 corners at {z}: {ring:?}");
        let (lo, hi) = wall.range(&ring);
        assert!(near(lo, 5.0) && near(hi, 5.0));
        // Quarter arcs of 2 mm in and out.
        let quarter = segs
            .iter()
            .filter(|s| {
                near(s.to[2], *z) && s.arc.is_some_and(|(c, _)| near((s.to[0] - c[0]).hypot(s.to[1] - c[1]), 2.0))
            })
            .count();
        assert_eq!(quarter, 2, "approach and departure at {z}");
    }
    // The floor: one G1 down at the centre from -10 + 0.5 + 1 to -10, then rings.
    let down: Vec<&Seg> = segs.iter().filter(|s| s.feed == 100.0 && at_centre(s.to, [60.0, 40.0])).collect();
    assert_eq!(down.len(), 1, "{down:?}");
    assert!(near(down[0].from[2], -8.5) && near(down[0].to[2], -10.0));
    let floor: Vec<Seg> = segs.iter().copied().filter(|s| near(s.to[2], -10.0) && s.feed == 300.0).collect();
    let (lo, _) = wall.range(&floor);
    assert!(near(lo, 5.0), "the floor up to the wall: {lo}");
    // No roughing feed into the material other than that: the edge levels at G0.
    assert!(segs.iter().all(|s| s.feed == 300.0 || s.feed == 100.0));
}

/// POCKET3 oscillating insertion (_VARI 31, _RAD1 = 10°): along the pocket's
/// length, never steeper than 10°, down to each level, then one flat stroke.
#[test]
fn pocket3_oscillating_insertion() {
    let r = go(&format!(
        "{HEAD}POCKET3(5, 0, 1, -6, 60, 40, 8, 60, 40, 90, 3, 0, 0, 300, 100, 3, 31, 0, 0, 0, 0, 10)\nM30\n"
    ));
    let segs = cuts(&r.actions);
    let ins: Vec<Seg> = segs.iter().copied().filter(|s| s.feed == 100.0 && s.arc.is_none()).collect();
    assert!(!ins.is_empty());
    let tan = 10f64.to_radians().tan();
    let mut sloped = 0;
    for s in &ins {
        // Along the length (STA 90: along Y), on the centre line X60.
        assert!(near(s.from[0], 60.0) && near(s.to[0], 60.0), "{s:?}");
        let dz = s.from[2] - s.to[2];
        assert!(dz >= -1e-6, "never up: {s:?}");
        if dz > 1e-6 {
            sloped += 1;
            assert!(dz <= plane_len(s) * tan + 1e-3, "steeper than 10°: {s:?}");
        }
    }
    assert!(sloped >= 4);
    for z in levels(1.0, -6.0, 3.0) {
        assert!(ins.iter().any(|s| near(s.from[2], z) && near(s.to[2], z) && plane_len(s) > 1.0), "flat stroke at {z}");
    }
    let wall = Wall { c: [60.0, 40.0], sta: 90.0, hl: 30.0, hw: 20.0, cr: 8.0 };
    let (min, _) = wall.range(&segs);
    assert!(near(min, 5.0), "{min}");
}

/// A pre-machined pocket (_AP1 × _AP2, _AD deep): above _AD no ring runs
/// inside it (each ring's cutter reaches outside the blank), fewer rings there
/// than below; the plunge is straight down at the centre.
#[test]
fn pocket3_pre_machined_pocket_is_not_cut_again() {
    let call = |ap: &str| {
        cuts(
            &go(&format!(
                "{HEAD}POCKET3(5, 0, 1, -10, 60, 40, 8, 60, 40, 0, 4, 0, 0, 300, 100, 3, 21, 4, {ap}, 2, 1)\nM30\n"
            ))
            .actions,
        )
    };
    let segs = call("40, 24, 6");
    let full = call("0, 0, 0");
    let lv = levels(1.0, -10.0, 4.0);
    let arcs =
        |s: &[Seg], z: f64| s.iter().filter(|g| g.arc.is_some() && near(g.to[2], z) && near(g.from[2], z)).count();
    for z in &lv {
        let ring_arcs: Vec<Seg> = segs
            .iter()
            .copied()
            .filter(|g| g.arc.is_some() && near(g.to[2], *z) && near(g.from[2], *z) && g.feed == 300.0)
            .collect();
        if *z >= -6.0 {
            for g in &ring_arcs {
                let out = samples(g)
                    .iter()
                    .any(|p| (p[0] - 60.0).abs() + 5.0 > 20.0 + 1e-3 || (p[1] - 40.0).abs() + 5.0 > 12.0 + 1e-3);
                assert!(out, "a ring inside the blank at {z}: {g:?}");
            }
            assert!(arcs(&segs, *z) < arcs(&full, *z), "fewer rings at {z}");
            // Straight down at the centre: no helix at this level.
            assert!(!segs.iter().any(|g| g.arc.is_some() && near(g.to[2], *z) && !near(g.from[2], g.to[2])));
        } else {
            assert_eq!(arcs(&segs, *z), arcs(&full, *z), "the whole ring set below _AD at {z}");
        }
    }
}

/// `_ZSD[2]=1`: _PA/_PO is a corner and _LENG/_WID carry the sign towards the
/// centre (lines 3533-3534): the same pocket from either corner.
#[test]
fn pocket3_corner_dimensioning() {
    for (pa, po, l, w) in [(30.0, 20.0, 60.0, 40.0), (90.0, 60.0, -60.0, -40.0), (30.0, 60.0, 60.0, -40.0)] {
        let r = go(&format!(
            "{HEAD}_ZSD[2]=1\nPOCKET3(5, 0, 1, -4, {l}, {w}, 8, {pa}, {po}, 0, 4, 0.5, 0, 300, 100, 3, 11)\nM30\n"
        ));
        let segs = cuts(&r.actions);
        let wall = Wall { c: [pa + l / 2.0, po + w / 2.0], sta: 0.0, hl: 30.0, hw: 20.0, cr: 8.0 };
        assert_eq!(wall.c, [60.0, 40.0]);
        let (min, _) = wall.range(&segs);
        assert!(near(min, 5.5), "{pa} {po}: {min}");
    }
}

/// _CDIR 0/1 follow the spindle as POCKET1's, 2/3 are G2/G3 (line 4960).
#[test]
fn pocket4_cdir() {
    for (m, cdir, cw) in [("M3", 0, false), ("M3", 1, true), ("M4", 0, true), ("M4", 1, false), ("M3", 2, true)] {
        let text = format!(
            "G17 G0 G90 X60 Y40 Z20 F500 S600 {m} T1 D1\nPOCKET4(5, 0, 1, -5, 20, 60, 40, 0, 0, 0, 300, 100, {cdir}, 11)\nM30\n"
        );
        let segs = cuts(&go(&text).actions);
        let dirs: Vec<bool> = segs.iter().filter_map(|s| s.arc.map(|a| a.1)).collect();
        assert!(!dirs.is_empty() && dirs.iter().all(|&d| d == cw), "{m} CDIR {cdir}");
    }
}

/// Bad POCKET3/POCKET4 calls stop on their line with the alarm the table gives
/// (lines 12201-12233) and move nothing.
#[test]
fn alarms_of_pocket3_and_pocket4_move_nothing() {
    let p3 = |tail: &str| format!("POCKET3(5, 0, 1, -10, 60, 40, 8, 60, 40, 0, {tail})");
    let p4 = |tail: &str| format!("POCKET4(5, 0, 1, -10, 20, 60, 40, {tail})");
    for (call, code) in [
        (format!("D0\n{}", p3("4, 0.5, 0, 300, 100, 3, 11")), 61000),
        (p3("4, 0.5, 0, 300, 100, 3, 13"), 61002),
        (p3("4, 0.5, 0, 300, 100, 3, 10"), 61002),
        (p3("4, 0.5, 0, 300, 100, 3, 41"), 61002),
        (p4("4, 0.5, 0, 300, 100, 3, 31"), 61002),
        ("POCKET3(5, 0, 1, 3, 60, 40, 8, 60, 40, 0, 4, 0.5, 0, 300, 100, 3, 11)".into(), 61101),
        (format!("M5\n{}", p4("4, 0.5, 0, 300, 100, 0, 11")), 61102),
        ("POCKET3(5, 0, 1, -10, 60, 9.9, 4, 60, 40, 0, 4, 0.5, 0, 300, 100, 3, 11)".into(), 61105),
        ("POCKET4(5, 0, 1, -10, 4.9, 60, 40, 4, 0.5, 0, 300, 100, 3, 11)".into(), 61105),
        (p4("4, 0.5, 0, 300, 100, 3, 21, 0, 0, 0, 0, 2"), 61108),
        (p4("4, 0.5, 0, 300, 100, 3, 21, 0, 0, 0, 3, 0"), 61108),
        (p4("4, 0.5, 0, 300, 100, 3, 21, 0, 0, 0, 15, 2"), 61108),
        (p3("4, 0.5, 0, 300, 100, 3, 31, 0, 0, 0, 0, 90"), 61108),
        (p3("4, 0.5, 0, 300, 100, 3, 31, 0, 0, 0, 0, 0"), 61108),
        (p3("4, 0.5, 0, 300, 100, 4, 11"), 61109),
        (p4("4, 0.5, 0, 300, 100, -1, 11"), 61109),
        (p3("4, 0.5, 4.5, 300, 100, 3, 11"), 61110),
        (p4("0, 0.5, 11, 300, 100, 3, 11"), 61110),
        (p3("4, 0.5, 0, 300, 100, 3, 11, 10.1"), 61111),
        (p4("4, 0.5, 0, 300, 100, 3, 11, 10.1"), 61111),
        ("POCKET3(5, 0, 1, -10, 60, 40, 20.1, 60, 40, 0, 4, 0.5, 0, 300, 100, 3, 11)".into(), 61113),
    ] {
        let head = "G17 G0 G90 X60 Y40 Z20 F500 S600 M3 T1 D1\n";
        let r = siemens(&format!("{head}{call}\nM30\n"));
        let line = 2 + call.matches('\n').count() as u32;
        assert_eq!(r.alarm_codes(), vec![(line, code)], "{call}");
        let pre = call.split_inclusive('\n').take(call.matches('\n').count()).collect::<String>();
        let before = siemens(&format!("{head}{pre}M30\n"));
        assert_eq!(r.actions.len(), before.actions.len(), "{call} moved");
    }
}

/// POCKET4 edge roughing only (lines 5181-5199): with `_ZSD[1]=1`, `_DP` −21,
/// `_FALD` 1.25 and `_AD` 19.75 every level is inside the pre-machined pocket
/// (radius `_AP1` 15): each level goes straight down at the centre and cuts only
/// the rings whose cutter reaches beyond 15 mm, down to −19.75.
#[test]
fn pocket4_edge_roughing_only() {
    let r = go(&format!(
        "{HEAD}_ZSD[1]=1\nPOCKET4(5, 0, 2, -21, 25, 60, 40, 5, 0, 1.25, 300, 100, 3, 21, 0, 15, 19.75, 3, 2)\nM30\n"
    ));
    let segs = cuts(&r.actions);
    assert!(segs.iter().all(|s| s.arc.is_none() || near(s.from[2], s.to[2])), "no helix in the air");
    let rings: Vec<f64> = segs
        .iter()
        .filter(|s| s.arc.is_some() && s.feed == 300.0)
        .map(|s| (s.to[0] - 60.0).hypot(s.to[1] - 40.0))
        .collect();
    assert!(!rings.is_empty() && rings.iter().all(|&rad| rad + 5.0 > 15.0 + 1e-3), "{rings:?}");
    let deepest = segs.iter().map(|s| s.to[2]).fold(f64::MAX, f64::min);
    assert!(near(deepest, -19.75), "{deepest}");
    assert_eq!(plunges(&segs, 100.0), levels(0.0, -19.75, 5.0));
}

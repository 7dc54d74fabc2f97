//! SINUMERIK LONGHOLE, SLOT1 and SLOT2 on the mill (seed 001 lines 3774-4419):
//! the slots on their circle, their ends and walls, the infeed depths, the
//! machining types and the alarms. The expected geometry is computed here from
//! the document's definitions — slot k at STA1 + k·INDA on the circle CPA/CPO,
//! RAD; LONGHOLE/SLOT1 LENG long along the radius about the point at RAD, SLOT1
//! WID wide (LONGHOLE: the cutter's width); SLOT2 WID wide along the circle over
//! AFSL degrees between its end caps' centres — and every cutting move the cycle
//! emits is measured against it, sampled along lines and arcs.

mod mill_common;

use mill_common::plane::*;

use interp_core::canon::Action;

/// The cutter radius of T1 D1 on the mill.
const R: f64 = 5.0;

/// The vertical infeeds at `feed`: (point in the plane, depth reached).
fn plunges(segs: &[Seg], feed: f64) -> Vec<([f64; 2], f64)> {
    segs.iter()
        .filter(|s| s.arc.is_none() && s.from[0] == s.to[0] && s.from[1] == s.to[1] && s.to[2] < s.from[2])
        .filter(|s| s.feed == feed)
        .map(|s| ([um(s.to[0]), um(s.to[1])], um(s.to[2])))
        .collect()
}

/// Slot `k`'s axis (the path of its end caps' centres) as the document defines it.
#[derive(Clone, Copy, Debug)]
struct Axis {
    a: [f64; 2],
    b: [f64; 2],
    /// SLOT2: the circle's centre and radius, the axis ccw from `a` to `b`.
    arc: Option<([f64; 2], f64)>,
}

fn polar(c: [f64; 2], r: f64, deg: f64) -> [f64; 2] {
    let (s, co) = deg.to_radians().sin_cos();
    [c[0] + r * co, c[1] + r * s]
}

/// LONGHOLE/SLOT1: LENG along the radius about the point at RAD, WID wide.
fn radial(c: [f64; 2], rad: f64, deg: f64, leng: f64, wid: f64) -> Axis {
    let e = (leng - wid) / 2.0;
    Axis { a: polar(c, rad - e, deg), b: polar(c, rad + e, deg), arc: None }
}

/// SLOT2: along the circle from `deg` over `afsl` degrees.
fn circumferential(c: [f64; 2], rad: f64, deg: f64, afsl: f64) -> Axis {
    Axis { a: polar(c, rad, deg), b: polar(c, rad, deg + afsl), arc: Some((c, rad)) }
}

fn dist(p: [f64; 2], q: [f64; 2]) -> f64 {
    (p[0] - q[0]).hypot(p[1] - q[1])
}

impl Axis {
    /// Distance of `p` to the axis.
    fn dist(&self, p: [f64; 2]) -> f64 {
        let ends = dist(p, self.a).min(dist(p, self.b));
        match self.arc {
            None => {
                let (d, v) = ([self.b[0] - self.a[0], self.b[1] - self.a[1]], [p[0] - self.a[0], p[1] - self.a[1]]);
                let l2 = d[0] * d[0] + d[1] * d[1];
                if l2 == 0.0 {
                    return ends;
                }
                let t = ((v[0] * d[0] + v[1] * d[1]) / l2).clamp(0.0, 1.0);
                dist(p, [self.a[0] + t * d[0], self.a[1] + t * d[1]])
            }
            Some((c, r)) => {
                let ang = |q: [f64; 2]| (q[1] - c[1]).atan2(q[0] - c[0]);
                let tau = std::f64::consts::TAU;
                let sweep = (ang(self.b) - ang(self.a)).rem_euclid(tau);
                let at = (ang(p) - ang(self.a)).rem_euclid(tau);
                if at <= sweep { (dist(p, c) - r).abs() } else { ends }
            }
        }
    }

    /// How far a point is along the axis beyond its middle (straight axes).
    fn along(&self, p: [f64; 2]) -> f64 {
        let m = [(self.a[0] + self.b[0]) / 2.0, (self.a[1] + self.b[1]) / 2.0];
        let l = dist(self.a, self.b);
        let u = if l == 0.0 { [1.0, 0.0] } else { [(self.b[0] - self.a[0]) / l, (self.b[1] - self.a[1]) / l] };
        ((p[0] - m[0]) * u[0] + (p[1] - m[1]) * u[1]).abs()
    }
}

/// The slot (of `axes`) a point lies closest to, and its distance.
fn nearest(axes: &[Axis], p: [f64; 2]) -> (usize, f64) {
    axes.iter().map(|a| a.dist(p)).enumerate().fold((0, f64::MAX), |b, (i, d)| if d < b.1 { (i, d) } else { b })
}

/// The farthest the moves `segs` (below the surface) stray from their slot's
/// axis: every sample is assigned to the nearest slot.
fn widest(axes: &[Axis], segs: &[Seg]) -> f64 {
    segs.iter().filter(|s| s.to[2] < 0.0).flat_map(samples).map(|p| nearest(axes, p).1).fold(0.0, f64::max)
}

const HEAD: &str = "G17 G0 G90 X60 Y40 Z20 F500 S600 M3 T1 D1\n";

/// LONGHOLE: three holes 30 mm long on a circle of radius 25 about X60 Y40 at
/// 10°, 130°, 250° (INDA 0: 360/NUM). The tool only runs on each hole's axis
/// (the width is the cutter's), whose ends leave the hole LENG long; the
/// infeeds alternate between the two ends, at the MID levels from RFP + SDIS.
#[test]
fn longhole_oscillates_between_the_ends() {
    let r = go(&format!("{HEAD}LONGHOLE(5, 0, 1, -12, , 3, 30, 60, 40, 25, 10, 0, 100, 320, 4)\nM30\n"));
    let segs = cuts(&r.actions);
    let c = [60.0, 40.0];
    let axes: Vec<Axis> = (0..3).map(|k| radial(c, 25.0, 10.0 + 120.0 * f64::from(k), 30.0, 2.0 * R)).collect();
    assert!(widest(&axes, &segs) < 0.0015, "off the axis");
    let want = levels(1.0, -12.0, 4.0);
    let p = plunges(&segs, 100.0);
    assert_eq!(p.len(), 3 * want.len());
    for (k, ax) in axes.iter().enumerate() {
        let mine: Vec<_> = p.iter().filter(|(q, _)| nearest(&axes, *q).0 == k).collect();
        assert_eq!(mine.iter().map(|m| m.1).collect::<Vec<_>>(), want, "slot {k}");
        // Alternately at either end; the ends LENG/2 − r from the hole's middle.
        for w in mine.windows(2) {
            assert!(near(dist(w[0].0, w[1].0), 30.0 - 2.0 * R), "{w:?}");
        }
        for m in &mine {
            assert!(near(ax.along(m.0) + R, 15.0), "{m:?}");
        }
        // The traverses at FFP1 reach both ends at each level.
        let ends: Vec<f64> = segs
            .iter()
            .filter(|s| s.feed == 320.0 && nearest(&axes, [s.to[0], s.to[1]]).0 == k)
            .map(|s| ax.along([s.to[0], s.to[1]]) + R)
            .collect();
        assert_eq!(ends.len(), want.len());
        assert!(ends.iter().all(|&e| near(e, 15.0)), "{ends:?}");
    }
    // The middles of the holes on the circle, at the start angle and INDA.
    for (k, ax) in axes.iter().enumerate() {
        let m = [(ax.a[0] + ax.b[0]) / 2.0, (ax.a[1] + ax.b[1]) / 2.0];
        assert!(near(dist(m, c), 25.0), "slot {k}");
    }
    // Back at RTP at the end.
    let last =
        r.actions.iter().rev().find_map(|c| if let Action::Rapid(m) = c.action { Some(mm3(&m.to.work)) } else { None });
    assert!(near(last.unwrap()[2], 5.0));
}

/// SLOT1 complete, vertical G1 insertion (VARI 10): roughing stays WID/2 − r −
/// FAL from the axis and reaches it (the outermost ring), finishing runs at
/// exactly WID/2 − r at FFP2 and SSF; the slot's ends (tool edge) at LENG/2 from
/// its middle; roughing per MID down to DP + _FALD, finishing per MIDF to DP.
#[test]
fn slot1_walls_ends_and_depths() {
    let (leng, wid, fal, fald) = (40.0, 16.0, 0.5, 0.4);
    let r = go(&format!(
        "{HEAD}SLOT1(5, 0, 1, -12, , 2, {leng}, {wid}, 60, 40, 30, 20, 90, 100, 300, 5, 3, {fal}, 10, 7, 80, 900, {fald})\nM30\n"
    ));
    let segs = cuts(&r.actions);
    let c = [60.0, 40.0];
    let axes: Vec<Axis> = (0..2).map(|k| radial(c, 30.0, 20.0 + 90.0 * f64::from(k), leng, wid)).collect();
    let rough: Vec<Seg> = segs.iter().copied().filter(|s| s.feed == 300.0).collect();
    let finish: Vec<Seg> = segs.iter().copied().filter(|s| s.feed == 80.0).collect();
    assert!(near(widest(&axes, &rough), wid / 2.0 - R - fal), "{}", widest(&axes, &rough));
    assert!(near(widest(&axes, &finish), wid / 2.0 - R));
    assert!(finish.iter().all(|s| s.rpm == 900) && rough.iter().all(|s| s.rpm == 600));
    for (k, ax) in axes.iter().enumerate() {
        let far = finish
            .iter()
            .flat_map(samples)
            .filter(|p| nearest(&axes, *p).0 == k)
            .map(|p| ax.along(p) + R)
            .fold(0.0, f64::max);
        assert!(near(far, leng / 2.0), "slot {k}: {far}");
    }
    // Infeeds at the slot's inner end centre: roughing per MID to DP + _FALD,
    // finishing per MIDF to DP, for each slot.
    let p = plunges(&segs, 100.0);
    let per_slot = [levels(1.0, -12.0 + fald, 5.0), levels(1.0, -12.0, 7.0)].concat();
    assert_eq!(p.iter().map(|x| x.1).collect::<Vec<_>>(), [per_slot.clone(), per_slot].concat());
    for (q, _) in &p {
        assert!(axes.iter().any(|a| near(dist(*q, a.a), 0.0)), "{q:?}");
    }
    // G3 (CDIR 3): every arc counterclockwise.
    assert!(segs.iter().filter_map(|s| s.arc).all(|a| !a.1));
    // Roughing leaves _FALD on the floor, finishing cuts it.
    let deepest = |v: &[Seg]| v.iter().map(|s| um(s.to[2])).fold(f64::MAX, f64::min);
    assert_eq!((deepest(&rough), deepest(&finish)), (-12.0 + fald, -12.0));
}

/// SLOT1 with oscillating insertion (VARI 31, roughing): every infeed runs
/// along the axis no steeper than _STA2 and ends where a vertical infeed would
/// (the same point in the plane), at the MID levels.
#[test]
fn slot1_oscillating_insertion() {
    let sta2 = 4.0_f64;
    let r = go(&format!(
        "{HEAD}SLOT1(5, 0, 1, -9, , 1, 40, 16, 60, 40, 30, 0, 0, 100, 300, 3, 2, 0.5, 31, 0, 0, 0, 0, {sta2})\nM30\n"
    ));
    let segs = cuts(&r.actions);
    let ax = radial([60.0, 40.0], 30.0, 0.0, 40.0, 16.0);
    let dives: Vec<Seg> = segs.iter().copied().filter(|s| s.feed == 100.0 && s.to[2] < s.from[2]).collect();
    assert!(!dives.is_empty());
    for s in &dives {
        let run = dist([s.from[0], s.from[1]], [s.to[0], s.to[1]]);
        assert!(run > 0.0, "vertical: {s:?}");
        assert!((s.from[2] - s.to[2]) / run <= sta2.to_radians().tan() + 1e-6, "{s:?}");
        assert!(near(ax.dist([s.to[0], s.to[1]]), 0.0));
    }
    // The last dive of each level (the one the axis pass at FFP1 follows) ends
    // at the plunge point, the axis's inner end, at the level.
    let ends: Vec<f64> = segs
        .windows(2)
        .filter(|w| w[0].feed == 100.0 && w[0].to[2] < w[0].from[2] && w[1].feed == 300.0)
        .map(|w| {
            assert!(near(dist([w[0].to[0], w[0].to[1]], ax.a), 0.0), "{w:?}");
            um(w[0].to[2])
        })
        .collect();
    assert_eq!(ends, levels(1.0, -9.0, 3.0));
    assert!(segs.iter().filter_map(|s| s.arc).all(|a| a.1), "CDIR 2: G2");
}

/// SLOT2: three circumferential slots (the document's example in G17): the
/// roughing rings WID/2 − r − FAL from the slot's arc, the finish at WID/2 − r,
/// the ends AFSL apart on the circle, each slot's start at STA1 + k·INDA.
/// Started near a slot's far end (X75 Y100: B of the first slot) the slots are
/// entered there, the axis run the other way: the same walls.
#[test]
fn slot2_circumferential_slots() {
    for start in ["X60 Y40", "X75 Y100"] {
        slot2_from(start);
    }
}

fn slot2_from(start: &str) {
    let head = HEAD.replace("X60 Y40", start);
    let r = go(&format!("{head}SLOT2(2, 0, 2, -23, , 3, 70, 15, 60, 60, 42, , 120, 100, 300, 6, 2, 0.5)\nM30\n"));
    let segs = cuts(&r.actions);
    let c = [60.0, 60.0];
    let axes: Vec<Axis> = (0..3).map(|k| circumferential(c, 42.0, 120.0 * f64::from(k), 70.0)).collect();
    let rough: Vec<Seg> = segs.iter().copied().filter(|s| s.to[2] > -23.0 || s.from[2] > -23.0).collect();
    let all = widest(&axes, &segs);
    assert!(near(all, 7.5 - R), "{all}");
    assert!(near(widest(&axes, &rough), 7.5 - R - 0.5), "{}", widest(&axes, &rough));
    // The axis traverses: arcs about the circle's centre of radius RAD from
    // end to end, AFSL apart.
    let axis: Vec<Seg> = segs
        .iter()
        .copied()
        .filter(|s| s.arc.is_some_and(|a| near(dist(a.0, c), 0.0)) && near(dist([s.to[0], s.to[1]], c), 42.0))
        .collect();
    assert!(!axis.is_empty());
    for s in &axis {
        let chord = dist([s.from[0], s.from[1]], [s.to[0], s.to[1]]);
        assert!(near(chord, 2.0 * 42.0 * 35f64.to_radians().sin()), "{s:?}");
    }
    // The plunges at the slots' starts (STA1 + k·INDA or its other end), per
    // MID; the finish (VARI 0x: G0 down to the floor already cut) has none.
    let p = plunges(&segs, 100.0);
    let per_slot = levels(2.0, -23.0, 6.0);
    assert_eq!(p.iter().map(|x| x.1).collect::<Vec<_>>(), per_slot.repeat(3));
    for (q, _) in &p {
        assert!(axes.iter().any(|a| near(dist(*q, a.a), 0.0) || near(dist(*q, a.b), 0.0)), "{q:?}");
    }
    // The first slot entered at its end nearer the start.
    let first = if start == "X60 Y40" { axes[0].a } else { axes[0].b };
    assert!(near(dist(p[0].0, first), 0.0), "{start}: {:?}", p[0]);
}

/// SLOT2 VARI 11 (roughing, slot to slot on the circle at _FFCP): the
/// transitions are arcs about the centre at RTP at _FFCP; VARI 3 (the wall
/// only) cuts nothing but the finishing ring at each MID level.
#[test]
fn slot2_circular_transitions_and_wall_only() {
    let r = go(&format!(
        "{HEAD}SLOT2(5, 0, 2, -6, , 3, 40, 15, 60, 60, 42, 0, 120, 100, 300, 6, 3, 0.5, 11, 0, 0, 0, 777)\nM30\n"
    ));
    let segs = cuts(&r.actions);
    let moves: Vec<Seg> = segs.iter().copied().filter(|s| s.feed == 777.0).collect();
    assert_eq!(moves.len(), 2);
    for s in &moves {
        assert!(near(s.from[2], 5.0) && near(s.to[2], 5.0));
        assert_eq!(s.arc.map(|a| a.0), Some([60.0, 60.0]));
        assert!(near(dist([s.to[0], s.to[1]], [60.0, 60.0]), 42.0));
    }
    let r = go(&format!(
        "{HEAD}SLOT2(5, 0, 2, -6, , 1, 40, 24, 60, 60, 42, 0, 120, 100, 300, 3, 3, 0.5, 3, 0, 250)\nM30\n"
    ));
    let segs = cuts(&r.actions);
    let ax = [circumferential([60.0, 60.0], 42.0, 0.0, 40.0)];
    let off = |p: [f64; 3]| !near(nearest(&ax, [p[0], p[1]]).1, 0.0);
    let ring: Vec<Seg> = segs.iter().copied().filter(|s| s.feed == 250.0 && off(s.from) && off(s.to)).collect();
    assert!(!ring.is_empty());
    // Two levels (MID 3 over 8 mm … 3 infeeds), the wall ring at 12 − r.
    for s in &ring {
        for q in samples(s) {
            let d = nearest(&ax, q).1;
            assert!(d < 0.0015 || near(d, 12.0 - R), "{q:?} {d}");
        }
    }
    let levels_cut: Vec<f64> = {
        let mut v: Vec<f64> = ring.iter().filter(|s| s.arc.is_some()).map(|s| um(s.to[2])).collect();
        v.dedup();
        v
    };
    assert_eq!(levels_cut, levels(2.0, -6.0, 3.0));
}

/// The document's examples (LONGHOLE 3914-3956 and SLOT1 4204-4235 in G19,
/// SLOT2 4391-4419 in G17) run.
#[test]
fn the_documents_examples_run() {
    for f in ["longhole.mpf", "slot1.mpf", "slot2.mpf"] {
        let text =
            std::fs::read_to_string(format!("{}/../examples/sinumerik/mill/{f}", env!("CARGO_MANIFEST_DIR"))).unwrap();
        let r = go(&text);
        assert!(r.actions.iter().any(|c| matches!(c.action, Action::Linear(_))), "{f}");
    }
}

/// Bad calls stop on their line with the document's alarm and move nothing.
#[test]
fn alarms_of_the_slots_move_nothing() {
    let head = "G17 G0 G90 X60 Y40 Z20 F500 S600 M3 T1 D1\n";
    for (call, code) in [
        ("D0\nLONGHOLE(5, 0, 1, -10, , 3, 30, 60, 40, 25, 0, 0, 100, 300, 4)", 61000),
        ("LONGHOLE(5, 5, 1, , 10, 3, 30, 60, 40, 25, 0, 0, 100, 300, 4)", 61101),
        ("LONGHOLE(5, 0, 1, -10, , 0, 30, 60, 40, 25, 0, 0, 100, 300, 4)", 61106),
        ("LONGHOLE(5, 0, 1, -10, , 4, 30, 60, 40, 25, 0, 120, 100, 300, 4)", 61106),
        ("LONGHOLE(5, 0, 1, -10, , 3, 9.9, 60, 40, 25, 0, 0, 100, 300, 4)", 61105),
        ("LONGHOLE(5, 0, 1, -10, , 3, 0, 60, 40, 25, 0, 0, 100, 300, 4)", 61609),
        // Inner ends 25 − 10 = 15 mm from the centre, 10° apart: 2.6 mm < 10.
        ("LONGHOLE(5, 0, 1, -10, , 3, 30, 60, 40, 25, 0, 10, 100, 300, 4)", 61104),
        ("G1 F0\nLONGHOLE(5, 0, 1, -10, , 3, 30, 60, 40, 25, 0, 0, 0, 300, 4)", 61003),
        ("SLOT1(5, 0, 1, -10, , 2, 30, 15, 60, 40, 25, 0, 90, 100, 300, 4, 2, 0.5, 3)", 61002),
        ("SLOT1(5, 0, 1, -10, , 2, 30, 15, 60, 40, 25, 0, 90, 100, 300, 4, 2, 0.5, 21)", 61002),
        ("SLOT1(5, 0, 1, -10, , 2, 30, 15, 60, 40, 25, 0, 90, 100, 300, 4, 5, 0.5, 0)", 61002),
        ("SLOT1(5, 0, 1, -10, , 2, 30, 15, 60, 40, 25, 0, 90, 100, 300, 4, 2, 0.5, 30)", 61128),
        ("SLOT1(5, 0, 1, -10, , 2, 30, 9, 60, 40, 25, 0, 90, 100, 300, 4, 2, 0.5, 0)", 61105),
        ("SLOT1(5, 0, 1, -10, , 2, 14, 15, 60, 40, 25, 0, 90, 100, 300, 4, 2, 0.5, 0)", 61609),
        ("SLOT1(5, 0, 1, -10, , 2, 30, 15, 60, 40, 10, 0, 90, 100, 300, 4, 2, 0.5, 0)", 61104),
        ("SLOT1(5, 0, 1, -10, , 2, 30, 15, 60, 40, 25, 0, 360, 100, 300, 4, 2, 0.5, 0)", 61106),
        ("SLOT2(5, 0, 1, -10, , 3, 70, 9, 60, 40, 42, 0, 120, 100, 300, 4, 2, 0.5, 0)", 61105),
        ("SLOT2(5, 0, 1, -10, , 3, 70, 24, 60, 40, 42, 0, 120, 100, 300, 4, 2, 0.5, 0)", 61905),
        ("SLOT2(5, 0, 1, -10, , 3, 115, 15, 60, 40, 42, 0, 120, 100, 300, 4, 2, 0.5, 0)", 61104),
        ("SLOT2(5, 0, 1, -10, , 1, 70, 15, 60, 40, 5, 0, 0, 100, 300, 4, 2, 0.5, 0)", 61104),
        ("SLOT2(5, 0, 1, -10, , 3, 70, 15, 60, 40, 42, 0, 120, 100, 300, 4, 2, 0.5, 21)", 61002),
        ("SLOT2(5, 0, 1, -10, , 3, 70, 15, 60, 40, 42, 0, 120, 100, 300, 4, 2, 0.5, 4)", 61002),
    ] {
        let r = siemens(&format!("{head}{call}\nM30\n"));
        let line = 2 + call.matches('\n').count() as u32;
        assert_eq!(r.alarm_codes(), vec![(line, code)], "{call}");
        let pre = call.lines().count() > 1;
        let before = siemens(&format!(
            "{head}{}M30\n",
            if pre { format!("{}\n", call.lines().next().unwrap()) } else { String::new() }
        ));
        assert_eq!(r.actions.len(), before.actions.len(), "{call} moved");
    }
}

/// SLOT1 VARI 0x (vertical insertion with G0): where the floor is already cut
/// the tool drops to it at G0 and feeds only the rest — the finishing infeed
/// goes G0 down to the rough floor (DP + _FALD) and at FFD to DP.
#[test]
fn slot1_g0_insertion_drops_to_the_cut_floor() {
    let r = go(&format!(
        "{HEAD}SLOT1(5, 0, 1, -12, , 1, 40, 16, 60, 40, 30, 0, 0, 100, 300, 6, 3, 0.5, 0, 0, 0, 0, 0.5)\nM30\n"
    ));
    let a = radial([60.0, 40.0], 30.0, 0.0, 40.0, 16.0).a;
    let rapids: Vec<[f64; 3]> = r
        .actions
        .iter()
        .filter_map(|c| if let Action::Rapid(m) = c.action { Some(mm3(&m.to.work)) } else { None })
        .collect();
    assert!(rapids.iter().any(|p| near(p[0], a[0]) && near(p[1], a[1]) && near(p[2], -11.5)), "{rapids:?}");
    let p = plunges(&cuts(&r.actions), 100.0);
    assert_eq!(p.iter().map(|x| x.1).collect::<Vec<_>>(), [levels(1.0, -11.5, 6.0), vec![-12.0]].concat());
}

/// Odd calls (negative, zero and huge values, every VARI/CDIR digit in a
/// valid call, one to three parameters at a time) end in an alarm or a run,
/// never a panic.
#[test]
fn odd_calls_never_panic() {
    let mut seed = 0x2545_f491_4f6c_dd1d_u64;
    let mut next = move |n: usize| {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed % n as u64) as usize
    };
    let odd = [
        "0", "-3", "7.5", "15", "1e9", "0.001", "-90", "359.9", "400", "1e300", "-1", "1", "2", "3", "4", "10", "11",
        "13", "21", "30", "31", "33", "99", "",
    ];
    let base: [&[&str]; 3] = [
        &["5", "0", "1", "-10", "", "3", "30", "60", "40", "25", "10", "0", "100", "320", "4"],
        &[
            "5", "0", "1", "-10", "", "2", "30", "15", "60", "40", "25", "0", "90", "100", "300", "4", "2", "0.5",
            "30", "3", "80", "900", "0.4", "5",
        ],
        &[
            "5", "0", "1", "-10", "", "3", "40", "15", "60", "60", "42", "0", "120", "100", "300", "4", "2", "0.5",
            "10", "3", "80", "900", "250",
        ],
    ];
    let mut ran = 0;
    for _ in 0..300 {
        let k = next(3);
        let mut args: Vec<&str> = base[k].to_vec();
        for _ in 0..=next(3) {
            let i = next(args.len());
            args[i] = odd[next(odd.len())];
        }
        let name = ["LONGHOLE", "SLOT1", "SLOT2"][k];
        let r = siemens(&format!("{HEAD}{name}({})\nM30\n", args.join(", ")));
        ran += usize::from(r.alarms.is_empty());
    }
    assert!(ran > 30, "{ran} of 300 odd calls ran");
}

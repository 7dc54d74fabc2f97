//! Properties of the contour layer: whatever the program, chamfers, corner R, G22
//! and nose compensation never panic and keep the all-or-nothing rule (but for the
//! moves held back, which an alarm lets go of); on random
//! outside profiles the compensated nose centre keeps exactly one radius from each
//! programmed line and never comes closer than that to any part of the contour.

use host_tests::{VecSink, mm, run_with};
use interp_core::canon::Action;
use interp_core::{Interpreter, MachineConfig, Panel, Progress, SingleProgram};
use proptest::prelude::*;

const R: f64 = 0.8;

/// A programmed segment: source line, start and end (Z, X radius) in mm.
type Seg = (u32, (f64, f64), (f64, f64));

fn machine() -> MachineConfig {
    let mut cfg = MachineConfig::default();
    for (n, tip) in [(1, 0), (2, 3)] {
        let row = cfg.tools.get_mut(n).unwrap();
        row.radius = mm(R);
        row.tip = tip;
    }
    cfg
}

fn drive(text: &[u8]) {
    let mut interp = Interpreter::new(machine());
    let mut sink = VecSink::default();
    let store = SingleProgram(text);
    for _ in 0..3_000 {
        let before = *interp.state();
        match interp.step(&store, &Panel::default(), &mut sink) {
            Ok(Progress::Ended) => return,
            Ok(Progress::Paused) => interp.cycle_start(),
            Ok(_) => {}
            Err(alarm) => {
                // All as before, but the look-ahead has let go of the moves it held
                // (they run before the machine stops); G41/G42 stays in force.
                let after = *interp.state();
                assert!(!after.contour.is_holding(), "alarm {alarm} left a move held");
                assert_eq!(after.contour.comp.side, before.contour.comp.side, "alarm {alarm}");
                let mut expect = before;
                expect.contour = after.contour;
                assert_eq!(after, expect, "alarm {alarm} changed the state");
                let _ = alarm.to_string();
            }
        }
    }
}

/// Distance from `p` to the segment `a`–`b`.
fn seg_dist(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let l2 = dx * dx + dy * dy;
    let t = if l2 == 0.0 { 0.0 } else { (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / l2).clamp(0.0, 1.0) };
    (p.0 - a.0 - t * dx).hypot(p.1 - a.1 - t * dy)
}

fn line_dist(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    ((p.0 - a.0) * dy - (p.1 - a.1) * dx).abs() / dx.hypot(dy)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 600, ..ProptestConfig::default() })]

    #[test]
    fn contour_programs_never_panic(
        blocks in prop::collection::vec(
            (prop::sample::select(vec!["G00", "G01", "G02", "G03", "G04", "G28", "G40", "G41", "G42", "G22", "G23",
                "G02.1", "G03.1", "G02.2", "G03.2", "G17", "G18", "G71", "G70", "G90", "M00", "M08", "T0101",
                "T0202", ""]),
             prop::collection::vec((prop::sample::select(vec!["X", "Z", "U", "W", "R", "A", "B", "P", "Q", "I", "K",
                ",C", ",R", "F"]), -60i32..60), 0..4)),
            1..30),
    ) {
        let text: String = blocks
            .iter()
            .map(|(code, words)| {
                let w: Vec<String> = words.iter().map(|(l, v)| format!("{l}{v}")).collect();
                format!("{code} {}\n", w.join(" "))
            })
            .collect();
        drive(format!("G01 F100\n{text}M30\n").as_bytes());
    }

    #[test]
    fn compensated_od_profiles_keep_one_radius(
        steps in prop::collection::vec((3u32..20, 0u32..15, prop::bool::ANY), 2..8),
        face_first in prop::bool::ANY,
    ) {
        // An outside profile going -Z, each step a diameter and a shoulder or taper
        // (X growing), cut with G42 and tip 0 (the machine positions the centre).
        let (mut z, mut x) = (0.0f64, 10.0f64);
        let start = (0.0, if face_first { 0.0 } else { x });
        let mut prog = format!("T0101\nG00 X{} Z5\nG42 G01 Z0 F100\n", 2.0 * start.1);
        // (source line, start, end) of every programmed segment after the start-up.
        let mut segs: Vec<Seg> = Vec::new();
        let mut line = 3;
        let mut here = start;
        let mut cut = |prog: &mut String, to: (f64, f64), text: String| {
            line += 1;
            prog.push_str(&text);
            segs.push((line, here, to));
            here = to;
        };
        if face_first {
            cut(&mut prog, (0.0, x), format!("X{}\n", 2.0 * x));
        }
        for &(len, rise, taper) in &steps {
            z -= f64::from(len);
            cut(&mut prog, (z, x), format!("Z{z}\n"));
            if rise > 0 {
                x += f64::from(rise);
                if taper {
                    z -= f64::from(rise);
                }
                cut(&mut prog, (z, x), format!("X{} Z{z}\n", 2.0 * x));
            }
        }
        prog.push_str(&format!("G40 G00 X{}\nM30\n", 2.0 * (x + 10.0)));
        let r = run_with(&prog, machine(), Panel::default());
        prop_assume!(r.alarms.iter().all(|a| a.code() != 3605));
        prop_assert!(r.alarms.is_empty(), "{:?}\n{prog}", r.alarms);
        let moves: Vec<(u32, (f64, f64))> = r
            .actions
            .iter()
            .filter(|c| matches!(c.action, Action::Linear(_) | Action::Rapid(_)))
            .filter_map(|c| host_tests::xz(c).map(|(x, z)| (c.line, (z, x / 2.0))))
            .collect();
        let contour: Vec<(f64, f64)> = std::iter::once(start).chain(segs.iter().map(|s| s.2)).collect();
        // Every vertex of the offset path keeps at least R from the whole contour.
        let offset_moves = moves.iter().filter(|m| m.0 >= 3 && m.0 <= line);
        for &(_, p) in offset_moves {
            let d = contour.windows(2).map(|w| seg_dist(p, w[0], w[1])).fold(f64::MAX, f64::min);
            prop_assert!(d > R - 1e-5, "{p:?} is {d} from the contour\n{prog}");
        }
        // The first move of each programmed segment's block runs on its offset line:
        // its start and end lie exactly R from the segment's line.
        for &(l, a, b) in &segs {
            let i = moves.iter().position(|m| m.0 == l).expect("every segment moves");
            let (from, to) = (moves[i - 1].1, moves[i].1);
            prop_assert!((line_dist(from, a, b) - R).abs() < 1e-5, "line {l} starts off its offset\n{prog}");
            prop_assert!((line_dist(to, a, b) - R).abs() < 1e-5, "line {l} ends off its offset\n{prog}");
        }
    }
}

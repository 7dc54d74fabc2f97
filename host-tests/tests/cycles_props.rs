//! Property tests of the cycles: G71/G72 roughing never cuts inside the shape
//! shifted by the allowances and no level is deeper than Δd; G73 passes are
//! translated copies of the shape; G76 depths follow √n and end exactly at k;
//! every cycle returns to its start point.

use host_tests::{Run, run, xz};
use interp_core::canon::{Action, ThreadSync};
use proptest::prelude::*;

/// mm with three decimals, as a program writes it.
fn f(um: i64) -> String {
    let s = if um < 0 { "-" } else { "" };
    format!("{s}{}.{:03}", um.abs() / 1000, um.abs() % 1000)
}

/// A motion of a block: kind, start and end (X dia, Z).
type Segment = (char, (f64, f64), (f64, f64));

/// (X dia, Z) of every motion end of the block on `line`, with the point before it.
fn segments(r: &Run, line: u32, from: (f64, f64)) -> Vec<Segment> {
    let mut prev = from;
    let mut out = vec![];
    for c in &r.actions {
        let Some(p) = xz(c) else { continue };
        if c.line == line {
            let k = match c.action {
                Action::Rapid(_) => 'r',
                Action::Linear(_) => 'l',
                Action::Arc(_) => 'a',
                Action::Thread(_) => 't',
                _ => 'p',
            };
            out.push((k, prev, p));
        }
        prev = p;
    }
    out
}

/// A type I shape: B's X, then (ΔX dia ≥ 0, ΔZ < 0) steps, all in µm.
fn shape() -> impl Strategy<Value = (i64, Vec<(i64, i64)>)> {
    (10_000i64..60_000, prop::collection::vec((0i64..15_000, -20_000i64..-500), 1..6))
}

/// Shape X (dia) at `z` of a polyline given as points, for z within it.
fn x_at(pts: &[(f64, f64)], z: f64) -> Option<f64> {
    pts.windows(2).find_map(|w| {
        let ((x0, z0), (x1, z1)) = (w[0], w[1]);
        if z <= z0 + 1e-9 && z >= z1 - 1e-9 && z0 != z1 { Some(x0 + (x1 - x0) * (z0 - z) / (z0 - z1)) } else { None }
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn g71_stays_outside_the_shifted_shape_and_steps_by_depth(
        (bx, steps) in shape(),
        above in 2_000i64..20_000,
        za in 1_000i64..10_000,
        depth in 300i64..3_000,
        retract in 100i64..1_000,
        du in 0i64..1_000,
        dw in 0i64..1_000,
        feed_infeed in any::<bool>(),
    ) {
        let mut pts = vec![(bx, za)];
        let (mut x, mut z) = (bx, za);
        let mut body = String::new();
        for (dx, dz) in &steps {
            x += dx;
            z += dz;
            pts.push((x, z));
            body += &format!("X{} Z{}\n", f(x), f(z));
        }
        // A finishing allowance longer than the shape leaves nothing to rough: that
        // is alarm 0062 (tested separately), not a property case.
        prop_assume!(za - z > dw + 1);
        let xa = x + above;
        let ns = if feed_infeed { "G01" } else { "G00" };
        let prog = format!(
            "G00 X{} Z{} M3 S500\nG71 U{} R{} F100\nG71 P10 Q20 U{} W{}\nN10 {ns} X{}\nG01\n{body}N20 G01 Z{}\nM30\n",
            f(xa), f(za), f(depth), f(retract), f(du), f(dw), f(bx), f(z)
        );
        let r = run(&prog);
        prop_assert!(r.alarms.is_empty(), "{:?}\n{prog}", r.alarms);
        let start = (xa as f64 / 1000.0, za as f64 / 1000.0);
        let segs = segments(&r, 3, start);
        prop_assert_eq!(segs.last().map(|s| s.2), Some(start), "returns to the start");
        // The shifted shape, mm (X dia).
        let shifted: Vec<(f64, f64)> = pts.iter().map(|&(x, z)| ((x + du) as f64 / 1000.0, (z + dw) as f64 / 1000.0)).collect();
        let z_end = shifted.last().unwrap().1;
        let mut levels = vec![];
        for (k, a, b) in &segs {
            if *k != 'l' {
                continue;
            }
            for i in 0..=10 {
                let t = f64::from(i) / 10.0;
                let (px, pz) = (a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t);
                prop_assert!(pz >= z_end - 1e-6, "cut past C' at {pz}");
                if let Some(sx) = x_at(&shifted, pz) {
                    prop_assert!(px >= sx - 2e-6, "cut at X{px} Z{pz} inside the shape (X{sx})\n{prog}");
                }
            }
            if a.0 == b.0 && b.1 < a.1 {
                levels.push(a.0);
            }
        }
        // Rough levels: Δd (radius) apart, the first Δd below the start; the final
        // contour pass is the last of them.
        levels.pop();
        levels.dedup();
        let mut want = xa as f64 / 1000.0 - 2.0 * depth as f64 / 1000.0;
        for l in &levels {
            prop_assert!((l - want).abs() < 2e-6, "level {l} != {want}");
            want -= 2.0 * depth as f64 / 1000.0;
        }
    }

    #[test]
    fn g73_passes_are_translated_copies(
        di in -5_000i64..15_000,
        dk in -5_000i64..15_000,
        count in 1u32..6,
        du in 100i64..2_000,
        dw in 0i64..1_000,
    ) {
        // A pass whose shape ends at the start's X (X180 + offset = X200) has a
        // zero-length retract, which is dropped like every zero-length move: the
        // pass then has 7 moves, not 8. Not a case of this property.
        let den = i64::from(count.max(2) - 1);
        prop_assume!((0..count).all(|n| {
            let left = if count == 1 { 0 } else { i64::from(count - 1 - n) };
            180_000 * den + 2 * di * left + du * den != 200_000 * den
        }));
        let prog = format!(
            "G00 X200 Z40 M3 S500\nG73 U{} W{} R{count}\nG73 P1 Q2 U{} W{} F100\nN1 G00 X80 Z0\nG01 Z-20\n\
             X120 Z-30\nG02 X160 Z-50 R20\nN2 G01 X180 Z-60\nM30\n",
            f(di), f(dk), f(du), f(dw)
        );
        let r = run(&prog);
        prop_assert!(r.alarms.is_empty(), "{:?}", r.alarms);
        let shape = [(80.0, 0.0), (80.0, -20.0), (120.0, -30.0), (160.0, -50.0), (180.0, -60.0)];
        let segs = segments(&r, 3, (200.0, 40.0));
        let ends: Vec<_> = segs.iter().map(|s| s.2).collect();
        prop_assert_eq!(ends.len() as u32, count * 8);
        for n in 0..count {
            let pass = &ends[(n * 8) as usize..(n * 8 + 8) as usize];
            let left = if count == 1 { 0.0 } else { f64::from(count - 1 - n) / f64::from(count - 1) };
            let off = ((2 * di) as f64 / 1000.0 * left + du as f64 / 1000.0, dk as f64 / 1000.0 * left + dw as f64 / 1000.0);
            for (i, &(x, z)) in shape.iter().enumerate() {
                let (px, pz) = pass[i + 1];
                prop_assert!((px - (x + off.0)).abs() < 3e-3 && (pz - (z + off.1)).abs() < 3e-3, "pass {n} point {i}: {:?} vs {:?}", (px, pz), (x + off.0, z + off.1));
            }
            // All points of a pass share one offset exactly.
            let d0 = (pass[1].0 - shape[0].0, pass[1].1 - shape[0].1);
            for (i, &(x, z)) in shape.iter().enumerate() {
                prop_assert!((pass[i + 1].0 - x - d0.0).abs() < 1e-9 && (pass[i + 1].1 - z - d0.1).abs() < 1e-9);
            }
            prop_assert_eq!(pass[7], (200.0, 40.0), "back at the start");
        }
    }

    #[test]
    fn g76_depths_follow_the_root_rule_and_end_at_k(
        k in 500i64..5_000,
        first_frac in 5u32..100,
        dmin in 0i64..300,
        d in 0i64..300,
        m in 1u32..4,
    ) {
        prop_assume!(d < k && dmin <= k);
        let first = (k * i64::from(first_frac) / 100).max(10);
        let prog = format!(
            "M3 S300\nG00 X80 Z10\nG76 P{m:02}0060 Q{} R{}\nG76 X60 Z-30 P{} Q{} F2\nM30\n",
            f(dmin), f(d), f(k), f(first)
        );
        let r = run(&prog);
        prop_assert!(r.alarms.is_empty(), "{:?}", r.alarms);
        let segs = segments(&r, 4, (80.0, 10.0));
        prop_assert_eq!(segs.last().map(|s| s.2), Some((80.0, 10.0)));
        // Depth of a pass in nm: from the crest (radius 30 mm + k) to the pass's start X.
        let crest = 30_000_000 + k * 1000;
        let depths: Vec<i64> = r.actions.windows(2).filter_map(|w| match (w[0].action, w[1].action) {
            (Action::Rapid(mv), Action::Thread(t)) if t.sync == ThreadSync::Index => Some(crest - mv.to.work.0[0]),
            _ => None,
        }).collect();
        let (k, first, dmin, d) = (k * 1000, first * 1000, dmin * 1000, d * 1000);
        let mut want = vec![];
        let mut prev = 0i64;
        for n in 1.. {
            let root = ((n as f64).sqrt() * first as f64).round() as i64;
            let dn = if n == 1 { first } else { root.max(prev + dmin) };
            if dn >= k - d {
                want.push(k - d);
                break;
            }
            want.push(dn);
            prev = dn;
        }
        want.extend(std::iter::repeat_n(k, m as usize));
        prop_assert_eq!(depths, want);
    }

    #[test]
    fn single_and_groove_cycles_return_to_the_start(
        x in 20_000i64..100_000,
        z in -5_000i64..20_000,
        u in -18_000i64..18_000,
        w in 1_000i64..40_000,
        towards_chuck in any::<bool>(),
        code in 0usize..5,
    ) {
        let w = if towards_chuck { -w } else { w };
        let (xe, ze) = (x + u, z + w);
        prop_assume!(xe > 2_000);
        let block = match code {
            0 => format!("G90 X{} Z{} F100", f(xe), f(ze)),
            1 => format!("G94 X{} Z{} F100", f(xe), f(ze)),
            2 => format!("G92 X{} Z{} F1", f(xe), f(ze)),
            3 => format!("G74 X{} Z{} P2500 Q3000 R0.2 F50", f(xe), f(ze)),
            _ => format!("G75 X{} Z{} P2500 Q3000 R0.2 F50", f(xe), f(ze)),
        };
        let r = run(&format!("G00 X{} Z{} M3 S500\n{block}\nM30\n", f(x), f(z)));
        prop_assert!(r.alarms.is_empty(), "{block}: {:?}", r.alarms);
        let start = (x as f64 / 1000.0, z as f64 / 1000.0);
        let segs = segments(&r, 2, start);
        prop_assert_eq!(segs.last().map(|s| s.2), Some(start), "{}", block);
    }
}

/// A sink that takes at most `room` actions between steps (a motion queue that
/// drains slowly).
struct Slow {
    got: Vec<interp_core::Canon>,
    room: usize,
}

impl interp_core::CanonSink for Slow {
    fn push(&mut self, a: interp_core::Canon) -> Result<(), interp_core::canon::Full> {
        if self.room == 0 {
            return Err(interp_core::canon::Full);
        }
        self.room -= 1;
        self.got.push(a);
        Ok(())
    }
}

/// The expansion refills the outbox a little per step: with a sink that takes one
/// action per step the actions are the same as with an unlimited sink, and no step
/// ever produces more than the outbox holds.
#[test]
fn back_pressure_gives_the_same_actions_with_bounded_work_per_step() {
    let text = "G00 X200 Z10 M03 S800\nG71 U2 R1 F200\nG71 P80 Q120 U0.5 W2.0\nN80 G00 X40 S1200\nG01 Z-30 F100\n\
        X60 W-30\nW-20\nN120 X100 W-10\nG70 P80 Q120\nG76 P020560 Q0.15 R0.1\nG76 X60.64 Z-62 P3.68 Q1.8 F6\nM30\n";
    let want = run(text).actions;
    let mut interp = interp_core::Interpreter::new(interp_core::MachineConfig::default());
    let store = interp_core::SingleProgram(text.as_bytes());
    let mut sink = Slow { got: vec![], room: 0 };
    let mut steps = 0;
    loop {
        sink.room = 1;
        let before = sink.got.len();
        match interp.step(&store, &interp_core::Panel::default(), &mut sink) {
            Ok(interp_core::Progress::Ended) => break,
            Ok(_) => {}
            Err(a) => panic!("{a}"),
        }
        assert!(sink.got.len() - before <= 1);
        steps += 1;
        assert!(steps < 10_000);
    }
    assert_eq!(sink.got, want);
    assert!(want.len() > 200, "a long expansion: {}", want.len());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Whatever the words of a cycle block, the interpreter raises alarms and never
    /// panics (debug builds check every overflow).
    #[test]
    fn random_cycle_words_never_panic(
        code in prop::sample::select(vec!["G90", "G92", "G94", "G32", "G34", "G71", "G72", "G73", "G74", "G75", "G76", "G83", "G84", "G85", "G87", "G70"]),
        words in prop::collection::vec(
            (prop::sample::select(vec!['X', 'Z', 'U', 'W', 'R', 'P', 'Q', 'F', 'E', 'H', 'K', 'I', 'C']),
             prop::sample::select(vec![0i64, 1, -1, 3, 250, -3_000, 999_999_999, -999_999_999, 123_456])),
            0..6),
        point in any::<bool>(),
    ) {
        let mut block = String::from(code);
        let mut seen = std::collections::BTreeSet::new();
        for (l, v) in words {
            if seen.insert(l) {
                block += &format!(" {l}{v}{}", if point { "." } else { "" });
            }
        }
        let prog = format!("G00 X80 Z10 M3 S500\nG71 U1 R0.5\n{block}\nN10 G00 X40\nG01 Z-20 F0.2\nN20 X90\nM30\n");
        let mut cfg = interp_core::MachineConfig::default();
        cfg.axes[3] = interp_core::config::AxisConfig { min: -1, max: 1, ..interp_core::config::AxisConfig::linear(0, 0, 6_000) };
        let _ = host_tests::run_with(&prog, cfg, interp_core::Panel::default());
    }
}

//! G70–G76 (2.16, 2.17.4) with the manual's worked examples and seed 003's
//! programs. The manual's figures are missing from its text: each test states the
//! geometry reconstructed from the program and the definitions tables.

use host_tests::{Run, moves, round3, run, run_with};
use interp_core::canon::{Action, ThreadSync};
use interp_core::config::{AxisConfig, Param};
use interp_core::{MachineConfig, Panel};

/// A machine with room for seed 003's G50 frames.
fn wide() -> MachineConfig {
    let mut cfg = MachineConfig::default();
    cfg.axes[0] = AxisConfig::linear(-200, 200, 6_000);
    cfg.axes[2] = AxisConfig::linear(-600, 600, 8_000);
    cfg
}

fn ok(r: &Run) {
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
}

const FIG_2_32: &str = "G00 X200 Z10 M03 S800\nG71 U2 R1 F200\nG71 P80 Q120 U0.5 W2.0\nN80 G00 X40 S1200\n\
    G01 Z-30 F100\nX60 W-30\nW-20\nN120 X100 W-10\nG70 P80 Q120\nM30\n";

/// The rough cut's end Z of figure 2.32 at level `x` (diameter): where the shape
/// shifted by (Δu/2, Δw) = (0.25, 2) reaches the level, -88 (C') above it.
fn fig_2_32_hit(x: f64) -> f64 {
    let r = x / 2.0;
    if r > 50.25 {
        -88.0
    } else if r > 30.25 {
        -78.0 - (r - 30.25) / 20.0 * 10.0
    } else {
        -28.0 - (r - 20.25) / 10.0 * 30.0
    }
}

/// Figure 2.32. Reconstruction: start A (X200, Z10); shape a→e: B = X40 on Z10
/// (ns is G00 X40: type I), Z-30, X60 Z-60, Z-80, X100 Z-90. Δd = 2 (radius),
/// e = 1, Δu = 0.5, Δw = 2. Levels X196, X192 … X44 (above B' = X40.5): G00 infeed
/// at Z10 (the ns block's mode), cut along Z to the shifted shape, 45° retract by e,
/// rapid back to Z10. Then to B' (X40.5, Z12), the contour B'→C' at F200, back to A
/// X first. The shape blocks are not executed; G70 then runs them with F100/S1200.
#[test]
fn figure_2_32_g71_and_g70() {
    let r = run(FIG_2_32);
    ok(&r);
    let mut want = vec![('r', 200.0, 10.0)];
    let mut x = 196.0;
    while x > 40.5 {
        let z = round3(fig_2_32_hit(x));
        want.extend([('r', x, 10.0), ('l', x, z), ('l', x + 2.0, round3(z + 1.0))]);
        if x - 4.0 > 40.5 {
            want.push(('r', x + 2.0, 10.0));
        } else {
            want.push(('r', x + 2.0, 12.0));
        }
        x -= 4.0;
    }
    want.extend([('r', 40.5, 12.0), ('l', 40.5, -28.0), ('l', 60.5, -58.0), ('l', 60.5, -78.0), ('l', 100.5, -88.0)]);
    want.extend([('r', 200.0, -88.0), ('r', 200.0, 10.0)]);
    // G70.
    want.extend([
        ('r', 40.0, 10.0),
        ('l', 40.0, -30.0),
        ('l', 60.0, -60.0),
        ('l', 60.0, -80.0),
        ('l', 100.0, -90.0),
        ('r', 200.0, 10.0),
    ]);
    assert_eq!(moves(&r), want);
    // Every roughing action carries the G71 line; G70's carry line 9.
    assert!(r.actions.iter().filter(|c| matches!(c.action, Action::Linear(_))).all(|c| c.line == 3 || c.line == 9));
    let feeds: Vec<_> = r
        .actions
        .iter()
        .filter_map(|c| match c.action {
            Action::Linear(m) => Some((c.line, m.feed.value / 1_000_000)),
            _ => None,
        })
        .collect();
    assert!(feeds.iter().all(|&(l, f)| (l == 3 && f == 200) || (l == 9 && f == 100)), "{feeds:?}");
    // U2 R1 went into parameters 5147/5148.
    let p = &r.interp.config().params;
    assert_eq!((p.get(Param::RoughingDepth), p.get(Param::RoughingRetract)), (2_000_000, 1_000_000));
    // G70's S1200 from the ns block.
    assert!(r.actions.iter().any(|c| c.line == 9 && matches!(c.action, Action::Spindle(s) if s.rpm == Some(1200))));
}

/// Figure 2.31: the four allowance quadrants. The same part mirrored in Z (cutting
/// towards +Z, Δw < 0) and about X100 (a bore cut outwards, Δu < 0) gives the
/// mirrored tool path exactly.
#[test]
fn figure_2_31_quadrants_mirror_the_path() {
    let base = moves(&run(FIG_2_32));
    let mirror_z = run("G00 X200 Z-10 M03 S800\nG71 U2 R1 F200\nG71 P80 Q120 U0.5 W-2.0\nN80 G00 X40 S1200\n\
        G01 Z30 F100\nX60 W30\nW20\nN120 X100 W10\nG70 P80 Q120\nM30\n");
    ok(&mirror_z);
    let want: Vec<_> = base.iter().map(|&(k, x, z)| (k, x, -z)).collect();
    assert_eq!(moves(&mirror_z), want);
    let mirror_x = run("G00 X0 Z10 M03 S800\nG71 U2 R1 F200\nG71 P80 Q120 U-0.5 W2.0\nN80 G00 X160 S1200\n\
        G01 Z-30 F100\nX140 W-30\nW-20\nN120 X100 W-10\nG70 P80 Q120\nM30\n");
    ok(&mirror_x);
    let want: Vec<_> = base.iter().map(|&(k, x, z)| (k, round3(200.0 - x), z)).collect();
    assert_eq!(moves(&mirror_x), want);
    let both = run("G00 X0 Z-10 M03 S800\nG71 U2 R1 F200\nG71 P80 Q120 U-0.5 W-2.0\nN80 G00 X160 S1200\n\
        G01 Z30 F100\nX140 W30\nW20\nN120 X100 W10\nG70 P80 Q120\nM30\n");
    let want: Vec<_> = base.iter().map(|&(k, x, z)| (k, round3(200.0 - x), -z)).collect();
    assert_eq!(moves(&both), want);
}

/// Figure 2.41. Reconstruction: start (X176, Z10); shape a→d: N10 G00 Z-55 (type I
/// for G72: Z only), X160, X80 Z-35, Z-20, X40 Z0. Δd = 2 in Z, e = 0.5, Δu = 0.2,
/// Δw = 0.1. Levels Z8 … Z-54; each cuts along -X from X176 to the shifted shape,
/// retracts 45° by e (X +1 dia, Z +0.5), returns in X.
#[test]
fn figure_2_41_g72() {
    let r = run("G00 X176 Z10 M3 S500 T0202\nG72 W2.0 R0.5 F300\nG72 P10 Q20 U0.2 W0.1\nN10 G00 Z-55 S800\n\
        G01 X160 F120\nX80 W20\nW15\nN20 X40 W20\nG70 P10 Q20\nM30\n");
    ok(&r);
    // Shifted shape (radius): (88.1,-54.9) (80.1,-54.9) (40.1,-34.9) (40.1,-19.9) (20.1,0.1).
    let hit = |z: f64| -> f64 {
        let r = if z >= 0.1 {
            20.1
        } else if z >= -19.9 {
            20.1 + (0.1 - z)
        } else if z >= -34.9 {
            40.1
        } else {
            40.1 + 2.0 * (-34.9 - z)
        };
        round3(2.0 * r)
    };
    let mut want = vec![('r', 176.0, 10.0)];
    let mut z = 8.0;
    while z > -54.9 {
        let x = hit(z);
        want.extend([('r', 176.0, z), ('l', x, z), ('l', round3(x + 1.0), z + 0.5)]);
        if z - 2.0 > -54.9 {
            want.push(('r', 176.0, z + 0.5));
        }
        z -= 2.0;
    }
    want.extend([('r', 176.2, -53.5), ('r', 176.2, -54.9)]);
    want.extend([('l', 160.2, -54.9), ('l', 80.2, -34.9), ('l', 80.2, -19.9), ('l', 40.2, 0.1)]);
    want.extend([('r', 40.2, 10.0), ('r', 176.0, 10.0)]);
    want.extend([
        ('r', 176.0, -55.0),
        ('l', 160.0, -55.0),
        ('l', 80.0, -35.0),
        ('l', 80.0, -20.0),
        ('l', 40.0, 0.0),
        ('r', 176.0, 10.0),
    ]);
    assert_eq!(moves(&r), want);
}

/// Figure 2.44. Reconstruction: start (X200, Z10); shape N1 G0 X80 Z0, Z-20,
/// X120 Z-30, Z-50, G02 X160 Z-70 R20, X180 Z-80. Δi = Δk = 15, d = 3, Δu = 2,
/// Δw = 1: pass offsets (X dia, Z) = (32, 16), (17, 8.5), (2, 1), each a translated
/// copy of the shape from A_n; back to A X first after each pass.
#[test]
fn figure_2_44_g73() {
    let r = run("G99 G00 X200 Z10 M3 S500\nG73 U15 W15 R3\nG73 P1 Q2 U2 W1 F0.3\nN1 G0 X80 Z0\nG01 W-20 F0.15 S600\n\
        X120 W-10\nW-20\nG02 X160 W-20 R20\nN2 G01 X180 W-10\nG70 P1 Q2\nM30\n");
    ok(&r);
    let shape = [
        ('r', 80.0, 0.0),
        ('l', 80.0, -20.0),
        ('l', 120.0, -30.0),
        ('l', 120.0, -50.0),
        ('a', 160.0, -70.0),
        ('l', 180.0, -80.0),
    ];
    let mut want = vec![('r', 200.0, 10.0)];
    for (dx, dz) in [(32.0, 16.0), (17.0, 8.5), (2.0, 1.0)] {
        want.push(('r', 200.0 + dx, 10.0 + dz));
        want.extend(shape.iter().map(|&(k, x, z)| (k, x + dx, z + dz)));
        want.extend([('r', 200.0, -80.0 + dz), ('r', 200.0, 10.0)]);
    }
    want.extend(shape);
    want.push(('r', 200.0, 10.0));
    assert_eq!(moves(&r), want);
    let p = &r.interp.config().params;
    assert_eq!(
        (p.get(Param::PatternReliefX), p.get(Param::PatternReliefZ), p.get(Param::PatternDivisions)),
        (15_000_000, 15_000_000, 3)
    );
    // The arc keeps its centre relative to the pass: R20 centre 20 mm (radius) off.
    let arcs: Vec<_> = r
        .actions
        .iter()
        .filter_map(|c| match c.action {
            Action::Arc(a) => {
                Some((round3(2.0 * a.center.work.0[0] as f64 / 1e6), round3(a.center.work.0[2] as f64 / 1e6), a.cw))
            }
            _ => None,
        })
        .collect();
    assert_eq!(arcs, vec![(192.0, -34.0, true), (177.0, -41.5, true), (162.0, -49.0, true), (160.0, -50.0, true)]);
}

/// Figure 2.46. The manual writes `P3 Q5` and says 3 mm / 5 mm; P/Q of G74/G75 are
/// least increments without a decimal point (its own G75 example: P6000 = 6 mm),
/// so the test writes P3000 Q5000. Columns X40, 34, 28, 22, 20; pecks of 5 with
/// 0.5 back (R0.5 = e); no relief (R(Δd) omitted).
#[test]
fn figure_2_46_g74() {
    let r = run("G0 X40 Z5 M3 S500\nG74 R0.5\nG74 X20 Z-20 P3000 Q5000 F50\nM30\n");
    ok(&r);
    let mut want = vec![('r', 40.0, 5.0)];
    let cols = [40.0, 34.0, 28.0, 22.0, 20.0];
    for (i, x) in cols.iter().enumerate() {
        if i > 0 {
            want.push(('r', *x, 5.0));
        }
        want.extend([
            ('l', *x, 0.0),
            ('r', *x, 0.5),
            ('l', *x, -5.0),
            ('r', *x, -4.5),
            ('l', *x, -10.0),
            ('r', *x, -9.5),
        ]);
        want.extend([('l', *x, -15.0), ('r', *x, -14.5), ('l', *x, -20.0), ('r', *x, 5.0)]);
    }
    want.push(('r', 40.0, 5.0));
    assert_eq!(moves(&r), want);
    assert_eq!(r.interp.config().params.get(Param::GrooveRetract), 500_000);
}

/// Figure 2.48: from (X125, Z-20) to X40 Z-50, pecks of 6 (radius) with 0.5 back,
/// columns every 3 mm: Z-20, -23 … -50.
#[test]
fn figure_2_48_g75() {
    let r = run("G00 X150 Z50 M3 S500\nG0 X125 Z-20\nG75 R0.5 F150\nG75 X40 Z-50 P6000 Q3000\nG0 X150 Z50\nM30\n");
    ok(&r);
    let m = moves(&r);
    let mut want = vec![];
    for k in 0..11 {
        let z = -20.0 - 3.0 * f64::from(k);
        if k > 0 {
            want.push(('r', 125.0, z));
        }
        let mut x = 125.0;
        loop {
            let next = x - 12.0;
            if next <= 40.0 {
                want.push(('l', 40.0, z));
                break;
            }
            want.extend([('l', next, z), ('r', next + 1.0, z)]);
            x = next + 1.0 - 1.0;
        }
        want.push(('r', 125.0, z));
    }
    want.push(('r', 125.0, -20.0));
    assert_eq!(m[2..m.len() - 1], want[..]);
}

/// Figure 2.60 (M68×6). The G50 block's S300 is the spindle clamp in this manual
/// (2.19), its comment says it is the speed: the test adds S300 as the speed.
/// P020560: m = 2, r = 0.5 lead (3 mm), a = 60°; Δdmin 0.15, d 0.1, k 3.68,
/// Δd 1.8. Depths √n·1.8 = 1.8, 2.546, 3.118, then k − d = 3.58, then 3.68 twice.
/// Infeed along the flank: Z shifted by depth·tan 30° towards the thread end.
#[test]
fn figure_2_60_g76() {
    let r = run("G00 X100 Z50\nG50 X100 Z50 M3 S300\nS300\nG00 X80 Z10\nG76 P020560 Q0.15 R0.1\n\
        G76 X60.64 Z-62 P3.68 Q1.8 F6\nG00 X100 Z50\nM30\n");
    ok(&r);
    let starts: Vec<_> = r
        .actions
        .windows(2)
        .filter_map(|w| match (w[0].action, w[1].action) {
            (Action::Rapid(m), Action::Thread(t)) if t.sync == ThreadSync::Index => {
                Some((round3(2.0 * m.to.work.0[0] as f64 / 1e6), round3(m.to.work.0[2] as f64 / 1e6), t.lead))
            }
            _ => None,
        })
        .collect();
    let k = 3.68;
    let tan30 = (30.0f64).to_radians().tan();
    let depths = [1.8, (2.0f64).sqrt() * 1.8, (3.0f64).sqrt() * 1.8, 3.58, k, k];
    let want: Vec<_> = depths
        .iter()
        .map(|d| {
            let d = (d * 1e6f64).round() / 1e6;
            (round3(68.0 - 2.0 * d), round3(10.0 - d * tan30), 6_000_000)
        })
        .collect();
    assert_eq!(starts, want);
    // Each pass: thread to Z-59 (3 mm pull-out), pull-out 3 mm at 45°, X to 80, Z to 10.
    let m = moves(&r);
    assert_eq!(
        m[2..7],
        [('r', 64.4, 8.961), ('t', 64.4, -59.0), ('t', 70.4, -62.0), ('r', 80.0, -62.0), ('r', 80.0, 10.0)]
    );
    let p = &r.interp.config().params;
    assert_eq!(
        [
            Param::ThreadFinishCount,
            Param::ThreadChamfer,
            Param::ThreadToolAngle,
            Param::ThreadMinDepth,
            Param::ThreadFinishAllowance
        ]
        .map(|q| p.get(q)),
        [2, 5, 60, 150_000, 100_000]
    );
}

/// G76 notes: missing P(k)/Q(Δd), Δdmin or d above k (note 7), pull-out longer than
/// the thread (note 8), first depth beyond k − d (note 6: one rough pass), internal
/// thread (U > 0) and taper R(i).
#[test]
fn g76_notes_and_quadrants() {
    let pre = "M3 S300\nG00 X80 Z10\n";
    let al = |b: &str| run(&format!("{pre}{b}\nM30\n")).alarm_codes();
    assert_eq!(al("G76 X60 Z-30 Q1 F2"), vec![(3, 62)]);
    assert_eq!(al("G76 X60 Z-30 P1.2 F2"), vec![(3, 62)]);
    assert_eq!(al("G76 Q2.0\nG76 X60 Z-30 P1.2 Q0.5 F2"), vec![(4, 62)]);
    assert_eq!(al("G76 P011060\nG76 X60 Z-30 P1.2 Q0.5 F50"), vec![(4, 4034)]);
    let r = run(&format!("{pre}G76 P010060 Q0.1 R0.2\nG76 X70 Z-30 P1000 Q5000 F2\nM30\n"));
    ok(&r);
    let threads = r.actions.iter().filter(|c| matches!(c.action, Action::Thread(_))).count();
    assert_eq!(threads, 2, "one rough pass at k-d and one finishing pass");
    // Internal: start X20, thread end X30 (U > 0): B is k below C, passes go outward.
    let r = run("M3 S300\nG00 X20 Z5\nG76 P010000 Q0.1 R0\nG76 X30 Z-20 P1000 Q500 F2\nM30\n");
    ok(&r);
    assert_eq!(moves(&r)[1..4], [('r', 29.0, 5.0), ('t', 29.0, -20.0), ('r', 20.0, -20.0)]);
    // Towards +Z (W > 0): the flank shift follows A→D, so the start moves to +Z.
    let r = run("M3 S300\nG00 X80 Z-40\nG76 P010060 Q0.1 R0\nG76 X60 Z0 P1000 Q500 F2\nM30\n");
    ok(&r);
    let tan30 = 30f64.to_radians().tan();
    assert_eq!(moves(&r)[1], ('r', 61.0, round3(-40.0 + 0.5 * tan30)));
    assert_eq!(moves(&r)[2], ('t', 61.0, 0.0), "r = 00: no pull-out");
    // Internal G92 (U > 0): thread at X30 from X20, pull-out and retract towards X20.
    let r = run("M3 S300\nG00 X20 Z5\nG92 X30 Z-20 F2\nM30\n");
    assert_eq!(
        moves(&r)[1..],
        [('r', 30.0, 5.0), ('t', 30.0, -18.0), ('t', 26.0, -20.0), ('r', 20.0, -20.0), ('r', 20.0, 5.0)]
    );
    // Taper R(i) = -1: passes start 2 mm (dia) smaller and are parallel to C→D.
    let r = run("M3 S300\nG00 X80 Z10\nG76 P010000 Q0.1 R0\nG76 X60 Z-30 R-1 P1000 Q1000 F2\nM30\n");
    ok(&r);
    assert_eq!(moves(&r)[1..3], [('r', 58.0, 10.0), ('t', 60.0, -30.0)]);
}

/// Seed 003's G71 program in system B style: G90 (absolute), G95 (per revolution)
/// and G40/G42 D01. Translated to system A: G90 dropped (absolute is the default),
/// G95 → G99, nose compensation dropped (not applied inside G71, 2.16.7 note 5);
/// `N130 X-120 Z-130` read as X120 (a minus through the axis is a typo). The end
/// point C' (X122) lies beyond the start X120: the contour pass ends in air.
#[test]
fn seed_003_g71() {
    let r = run_with(
        "O0001\nN10 G50 X200 Z140 T0101\nN20 G40 G97 G99 S240 M03\nN30 G00 X120 Z12 M08\nN40 G96 S120\n\
        N50 G71 U2 R0.1\nN60 G71 P70 Q130 U2 W2 F0.3\nN70 G00 X40\nN80 G01 Z-30 F0.15 S150\nN90 X60 Z-60\n\
        N100 Z-80\nN110 X100 Z-90\nN120 Z-110\nN130 X120 Z-130\nN140 G00 X125\nN150 X200 Z140\nN160 M02\n",
        wide(),
        Panel::default(),
    );
    ok(&r);
    let m = moves(&r);
    assert_eq!(m[1], ('r', 116.0, 12.0));
    assert_eq!(m[2], ('l', 116.0, -122.0), "X116 meets the last shifted segment (X102 Z-108)-(X122 Z-128)");
    let contour: Vec<_> = m.iter().rev().skip(4).take(7).rev().copied().collect();
    assert_eq!(
        contour,
        vec![
            ('r', 42.0, 14.0),
            ('l', 42.0, -28.0),
            ('l', 62.0, -58.0),
            ('l', 62.0, -78.0),
            ('l', 102.0, -88.0),
            ('l', 102.0, -108.0),
            ('l', 122.0, -128.0)
        ]
    );
    assert_eq!(m[m.len() - 4..], [('r', 122.0, 12.0), ('r', 120.0, 12.0), ('r', 125.0, 12.0), ('r', 200.0, 140.0)]);
}

/// Seed 003's G73 program with the G70 it suggests (N140), translated like the G71
/// one (G90 and G42/G40 dropped).
#[test]
fn seed_003_g73_g70() {
    let r = run_with(
        "N10 G50 X200 Z200 T0101\nN20 G97 G40 S200 M03\nN30 G00 X140 Z40 M08\nN40 G96 S120\n\
        N50 G73 U9.5 W9.5 R3\nN60 G73 P70 Q130 U1.0 W0.5 F0.3\nN70 G00 X20 Z0\nN80 G01 Z-20 F0.15 S150\n\
        N90 X40 Z-30\nN100 Z-50\nN110 G02 X80 Z-70 R20\nN120 G01 X100 Z-80\nN130 X105\nN140 G70 P70 Q130\n\
        N150 G00 X200 Z200\nN160 M02\n",
        wide(),
        Panel::default(),
    );
    ok(&r);
    let m = moves(&r);
    // Pass 1 from A + (19 + 1, 9.5 + 0.5), pass 3 from A + (1, 0.5).
    assert_eq!(m[1..3], [('r', 160.0, 50.0), ('r', 40.0, 10.0)]);
    let g70: Vec<_> = r.actions.iter().filter(|c| c.line == 14).count().to_string().chars().collect();
    assert!(!g70.is_empty());
    assert!(m.contains(&('r', 21.0, 0.5)));
}

/// Seed 003's G75 parting program: `G75 X-1 P5 F0.15` (no Z: one column; P5 read
/// as 5 mm per the book, written P5000), e = 1, G20-free metric.
#[test]
fn seed_003_g75() {
    let r = run_with(
        "N10 G50 X200 Z200 T0505\nN20 G97 S700 M03\nN30 G00 G40 X35 Z-50 M08\nN40 G96 S80\nN50 G75 R1\n\
        N60 G75 X-1 P5000 F0.15\nN70 G00 X200 Z200 T0500\nN80 M02\n",
        wide(),
        Panel::default(),
    );
    ok(&r);
    let m = moves(&r);
    assert_eq!(
        m[1..9],
        [
            ('l', 25.0, -50.0),
            ('r', 27.0, -50.0),
            ('l', 15.0, -50.0),
            ('r', 17.0, -50.0),
            ('l', 5.0, -50.0),
            ('r', 7.0, -50.0),
            ('l', -1.0, -50.0),
            ('r', 35.0, -50.0)
        ]
    );
}

/// Seed 003's G92 program (system B's G90 dropped): Φ30 M30×1.5, four passes.
#[test]
fn seed_003_g92() {
    let r = run_with(
        "N50 G50 X270 Z260\nN60 G97 S300\nN70 T0101 M03\nN80 G00 X35 Z104\nN90 G92 X29.2 Z56 F1.5\n\
        N100 X28.6\nN110 X28.2\nN120 X28.04\nN130 G00 X270 Z260 T0100 M05\nN140 M02\n",
        wide(),
        Panel::default(),
    );
    ok(&r);
    let xs: Vec<_> = moves(&r).iter().filter(|m| m.0 == 't').map(|m| (m.1, m.2)).step_by(2).collect();
    assert_eq!(xs, vec![(29.2, 57.5), (28.6, 57.5), (28.2, 57.5), (28.04, 57.5)]);
}

/// 2.16.7 notes 1–3 and the shape checks: the alarms, and no motion or parameter
/// change from the alarming block.
#[test]
fn shape_alarms() {
    let pre = "G00 X100 Z5 M3 S500\nG71 U1 R0.5 F100\n";
    let body = "N20 Z-20\nN30 X80\nM30\n";
    let al = |g71: &str, ns: &str| run(&format!("{pre}{g71}\nN10 {ns}\n{body}")).alarm_codes()[0];
    assert_eq!(al("G71 P10 U0.5", "G00 X40"), (3, 61));
    assert_eq!(al("G71 P10 Q99 U0.5", "G00 X40"), (3, 63));
    assert_eq!(al("G71 P11 Q30", "G00 X40"), (3, 63));
    assert_eq!(al("G71 P10 Q30", "X40"), (3, 65));
    assert_eq!(al("G71 P10 Q30", "G00 Z-5"), (3, 65));
    assert_eq!(al("G71 P10 Q30", "G00 X40 G28 U0"), (3, 4016));
    let al2 = |mid: &str| run(&format!("{pre}G71 P10 Q30\nN10 G00 X40\n{mid}\n{body}")).alarm_codes()[0];
    assert!(run(&format!("{pre}G71 P10 Q30\nN10 G00 X40\nG04 P10\n{body}")).alarms.is_empty(), "G04 is allowed");
    assert_eq!(al2("G28 U0"), (3, 66));
    assert_eq!(al2("G20"), (3, 66));
    assert_eq!(al2("M98 P100"), (3, 66));
    assert_eq!(al2("G32 W-5 F1"), (3, 66));
    assert_eq!(al2("G90 X30 W-5"), (3, 66));
    assert_eq!(al2("M30"), (3, 66));
    // Not monotone: Z goes back (0064); X goes back in type I (0329).
    assert_eq!(run(&format!("{pre}G71 P10 Q30\nN10 G00 X40\nG01 Z-10\nZ-5\nN30 X80\nM30\n")).alarm_codes()[0], (3, 64));
    assert_eq!(
        run(&format!("{pre}G71 P10 Q30\nN10 G00 X40\nG01 Z-10\nX30 Z-15\nN30 X80\nM30\n")).alarm_codes()[0],
        (3, 329)
    );
    // Depth of cut zero.
    assert_eq!(
        run("G00 X100 Z5 M3 S500\nG71 U0 R0.5 F100\nG71 P10 Q30\nN10 G00 X40\nN30 G01 Z-5\nM30\n").alarm_codes()[0],
        (3, 62)
    );
    // Not in the ZX plane.
    assert_eq!(run(&format!("G17\n{pre}G71 P10 Q30\nN10 G00 X40\n{body}")).alarm_codes()[0], (3, 4031));
    // A G71 U R block that alarms leaves 5147/5148 alone.
    let r = run("G71 U3 R0.7 F100 Q5\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(1, 61)]);
    assert_eq!(
        r.interp.config().params.get(Param::RoughingDepth),
        MachineConfig::default().params.get(Param::RoughingDepth)
    );
    // Soft limits of every pass, before any motion: a contour beyond the X travel.
    let r = run(&format!("{pre}G71 P10 Q30 U0.5\nN10 G00 X40\nG01 Z-20\nN30 X400\nM30\n"));
    assert_eq!(r.alarm_codes()[0], (3, 500));
    assert!(host_tests::on_line(&r, 3).is_empty(), "no action from the alarming cycle");
}

/// Type II (pockets): both axes in the ns block. The first pocket is cut to its
/// bottom before the second (note 3: G1 approach from e above the cut level), 45°
/// retracts, the X allowance only (note 2), and the return of note 7 (X to the
/// start + allowance + Δd, Z, X).
#[test]
fn g71_type_ii_pockets() {
    let r = run("G00 X100 Z5 M3 S500\nG71 U2 R0.5 F200\nG71 P10 Q20 U0.4 W3\nN10 G00 X90 Z3\nG01 X80 Z-10 F100\n\
        X60 Z-20\nZ-30\nX80 Z-40\nX60 Z-50\nX80 Z-60\nN20 X100\nM30\n");
    ok(&r);
    let m = moves(&r);
    // First level: rapid along over the start level to where the ns line reaches X96.
    assert_eq!(m[1..4], [('r', 100.0, 4.12), ('l', 96.0, 4.12), ('l', 96.0, -60.0)]);
    // After the first pocket's bottom level (X64), up to the level that spans both
    // pockets (X84) + e, along to the second pocket, G1 down.
    let i = m.iter().position(|&p| p == ('l', 64.0, -31.8)).unwrap();
    assert_eq!(m[i + 1..i + 5], [('l', 65.0, -31.3), ('r', 85.0, -31.3), ('r', 85.0, -40.2), ('l', 80.0, -40.2)]);
    // Contour with X allowance only, then note 7.
    assert_eq!(m[m.len() - 3..], [('r', 104.4, -60.0), ('r', 104.4, 5.0), ('r', 100.0, 5.0)]);
    assert!(m.contains(&('l', 60.4, -20.0)) && m.contains(&('l', 60.4, -50.0)));
}

#[test]
fn g71_allowance_longer_than_the_shape_is_alarm_0062() {
    // The shape runs 0.502 mm along Z; W0.503 shifts its end C' behind the start point.
    let r = run("G00 X12 Z1 M3 S500\nG71 U0.3 R0.1 F100\nG71 P10 Q20 U0 W0.503\nN10 G00 X10\nG01 X10 Z0.498\n\
         N20 G01 Z0.498\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(3, 62)]);
    assert!(r.alarms[0].to_string().contains("ends before the start point"), "{}", r.alarms[0]);
}

#[test]
fn g73_pass_ending_at_the_start_x_drops_its_zero_length_retract() {
    // First pass offset 2 × 9.09 + 1.82 = 20 (dia): its shape ends at X200, the
    // start's X, so the retract to X200 has no length and is not emitted.
    let r = run("G00 X200 Z40 M3 S500\nG73 U9.09 W0 R2\nG73 P1 Q2 U1.82 W0 F100\nN1 G00 X80 Z0\nG01 Z-20\n\
         X120 Z-30\nG02 X160 Z-50 R20\nN2 G01 X180 Z-60\nM30\n");
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    let ends: Vec<_> = r.actions.iter().filter(|c| c.line == 3).filter_map(host_tests::xz).collect();
    assert_eq!(ends.len(), 15);
    assert_eq!(ends[5], (200.0, -60.0), "first pass ends on the start's X");
    assert_eq!(ends[6], (200.0, 40.0), "then straight back to the start");
    assert_eq!(ends.last(), Some(&(200.0, 40.0)));
}

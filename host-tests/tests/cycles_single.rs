//! G90/G94 single cycles and G92/G32/G34 threading (2.15, 2.17), with the manual's
//! examples. Figures are missing from the manual's text; each test says how the
//! geometry was reconstructed from the program and the definitions tables.

use host_tests::{kind_names, mm, moves, run, run_with};
use interp_core::canon::{Action, ThreadSync};
use interp_core::config::Param;
use interp_core::{MachineConfig, Panel};

/// Figure 2.25 (stock Φ125 × 110). The OCR lost the `G90` of two blocks and merged
/// two lines; reconstruction: `G90 X120 Z-110 F200`, then X110 Z-30, X100 … X60
/// repeating the cycle with Z retained (note 2), and the taper
/// `G90 X120 Z-44 F150` … `Z-80 R-30` from (X120, Z-30): a cone from Φ60 at
/// Z-30 to Φ120 at Z-80 (R = start-of-cut X minus end X, radius).
#[test]
fn figure_2_25_g90_straight_and_taper() {
    let r = run("M03 S300\nG00 X130 Z3\nG90 X120 Z-110 F200\nX110 Z-30\nX100\nX90\nX80\nX70\nX60\n\
         G00 X120 Z-30\nG90 X120 Z-44 R-7.5 F150\nZ-56 R-15\nZ-68 R-22.5\nZ-80 R-30\nM30\n");
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    let mut want =
        vec![('r', 130.0, 3.0), ('r', 120.0, 3.0), ('l', 120.0, -110.0), ('l', 130.0, -110.0), ('r', 130.0, 3.0)];
    for x in [110.0, 100.0, 90.0, 80.0, 70.0, 60.0] {
        want.extend([('r', x, 3.0), ('l', x, -30.0), ('l', 130.0, -30.0), ('r', 130.0, 3.0)]);
    }
    want.push(('r', 120.0, -30.0));
    for (b, z) in [(105.0, -44.0), (90.0, -56.0), (75.0, -68.0), (60.0, -80.0)] {
        // ③ (X back to 120) is no move: the cut ends at the start's X.
        want.extend([('r', b, -30.0), ('l', 120.0, z), ('r', 120.0, -30.0)]);
    }
    assert_eq!(moves(&r), want);
    let Action::Linear(m) = r.actions[3].action else { panic!() };
    assert_eq!(m.feed.value, mm(200.0));
}

/// Figure 2.24: the four U/W/R sign combinations; a taper larger than U/2 with the
/// opposite sign is alarm 4030.
#[test]
fn figure_2_24_g90_sign_cases() {
    let case = |body: &str| moves(&run(&format!("G00 X100 Z10\n{body} F100\nM30\n")))[1..].to_vec();
    // 1) U>0 W<0 R>0: boring from X100 to X120, cut starts at X120+2R.
    assert_eq!(
        case("G90 U20 W-30 R5"),
        vec![('r', 130.0, 10.0), ('l', 120.0, -20.0), ('l', 100.0, -20.0), ('r', 100.0, 10.0)]
    );
    // 2) U<0 W<0 R<0.
    assert_eq!(
        case("G90 U-40 W-30 R-5"),
        vec![('r', 50.0, 10.0), ('l', 60.0, -20.0), ('l', 100.0, -20.0), ('r', 100.0, 10.0)]
    );
    // 3) U>0 W<0 R<0, |R| <= |U/2| (here equal: the cut starts at the start point, ① is no move).
    assert_eq!(case("G90 U20 W-30 R-10"), vec![('l', 120.0, -20.0), ('l', 100.0, -20.0), ('r', 100.0, 10.0)]);
    // 4) U<0 W<0 R>0, |R| <= |U/2|.
    assert_eq!(case("G90 U-40 W-30 R20"), vec![('l', 60.0, -20.0), ('l', 100.0, -20.0), ('r', 100.0, 10.0)]);
    let r = run("G00 X100 Z10\nG90 U-40 W-30 R21 F100\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(2, 4030)]);
    assert_eq!(moves(&r).len(), 1, "no motion from the alarming block");
    // Seed 003's I form equals R.
    assert_eq!(case("G90 U-40 W-30 I-5"), case("G90 U-40 W-30 R-5"));
}

/// Figure 2.29 (stock Φ125 × 112): facing to the centre, the Φ120 outside by the
/// retract at feed, then the cone from Φ60/Z-30 to Φ120/Z-80 in five facing passes
/// (R = start-of-cut Z minus end Z).
#[test]
fn figure_2_29_g94() {
    let r = run("G00 X130 Z5 M3 S500\nG94 X0 Z0 F200\nX120 Z-110 F300\nG00 X120 Z0\nG94 X108 Z-30 R-10\n\
         X96 R-20\nX84 R-30\nX72 R-40\nX60 R-50\nM30\n");
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    let mut want = vec![('r', 130.0, 5.0), ('r', 130.0, 0.0), ('l', 0.0, 0.0), ('l', 0.0, 5.0), ('r', 130.0, 5.0)];
    want.extend([('r', 130.0, -110.0), ('l', 120.0, -110.0), ('l', 120.0, 5.0), ('r', 130.0, 5.0), ('r', 120.0, 0.0)]);
    for (x, zb) in [(108.0, -40.0), (96.0, -50.0), (84.0, -60.0), (72.0, -70.0), (60.0, -80.0)] {
        want.extend([('r', 120.0, zb), ('l', x, -30.0), ('l', x, 0.0), ('r', 120.0, 0.0)]);
    }
    assert_eq!(moves(&r), want);
}

/// Figure 2.28 sign cases of G94 and the |R| <= |W| rule.
#[test]
fn figure_2_28_g94_sign_cases() {
    let case = |body: &str| moves(&run(&format!("G00 X100 Z10\n{body} F100\nM30\n")))[1..].to_vec();
    assert_eq!(
        case("G94 U-60 W-20 R-5"),
        vec![('r', 100.0, -15.0), ('l', 40.0, -10.0), ('l', 40.0, 10.0), ('r', 100.0, 10.0)]
    );
    assert_eq!(
        case("G94 U20 W-20 R-5"),
        vec![('r', 100.0, -15.0), ('l', 120.0, -10.0), ('l', 120.0, 10.0), ('r', 100.0, 10.0)]
    );
    assert_eq!(case("G94 U-60 W-20 R20"), vec![('l', 40.0, -10.0), ('l', 40.0, 10.0), ('r', 100.0, 10.0)]);
    assert_eq!(run("G00 X100 Z10\nG94 U-60 W-20 R21 F100\nM30\n").alarm_codes(), vec![(2, 4030)]);
}

/// 2.15 note 2: X/Z/R are kept for the next blocks of the cycle until a group 00
/// code other than G04 or another group 01 code clears them.
#[test]
fn note_2_retained_values_and_their_clearing() {
    let r = run("G00 X100 Z10\nG90 X80 Z-20 R-2 F100\nX70\nG04 P10\nX60\nM30\n");
    let m = moves(&r);
    assert_eq!(m[9], ('r', 56.0, 10.0), "X60 with Z-20 R-2 kept across G04");
    assert_eq!(m[10], ('l', 60.0, -20.0));
    // G00 clears them: a later G90 with X only cuts to the current Z.
    let r = run("G00 X100 Z10\nG90 X80 Z-20 F100\nG00 X100\nG90 X80\nM30\n");
    // ① to X80, ② no move (already at Z10), ③ X back at feed.
    assert_eq!(moves(&r)[5..], [('r', 80.0, 10.0), ('l', 100.0, 10.0)]);
    // A cycle outside the ZX plane and an axis other than X/Z are alarms.
    assert_eq!(run("G17\nG90 X80 Z-20 F100\nM30\n").alarm_codes(), vec![(2, 4031)]);
}

/// Figure 2.57 (M60×3 external thread, start X65 Z5): four passes, Z retained.
/// Pull-out with the default parameters 5130 = 10 (one lead, 3 mm) and 5131 = 0
/// (45°): the thread runs to Z-25, then a continuing thread move pulls X out 3 mm
/// (radius) while Z reaches -28; ③ X rapid to 65, ④ Z rapid to 5.
#[test]
fn figure_2_57_g92() {
    let r = run("M3 S300 G0 X150 Z50 T0101\nG0 X65 Z5\nG92 X58.7 Z-28 F3\nX57.7\nX57\nX56.9\nM30\n");
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    let mut want = vec![('r', 150.0, 50.0), ('r', 65.0, 5.0)];
    for x in [58.7, 57.7, 57.0, 56.9] {
        want.extend([
            ('r', x, 5.0),
            ('t', x, -25.0),
            ('t', host_tests::round3(x + 6.0), -28.0),
            ('r', 65.0, -28.0),
            ('r', 65.0, 5.0),
        ]);
    }
    assert_eq!(moves(&r), want);
    let threads: Vec<_> = r
        .actions
        .iter()
        .filter_map(|c| match c.action {
            Action::Thread(t) => Some((t.lead, t.sync, t.start_udeg, c.line)),
            _ => None,
        })
        .collect();
    assert_eq!(threads[0], (mm(3.0), ThreadSync::Index, 0, 3));
    assert_eq!(threads[1], (mm(3.0), ThreadSync::Continue, 0, 3));
    assert_eq!(threads[7].3, 6);
}

/// 2.17.3: H starts (lead = H × F, start angles 0, 120, 240), E threads per inch,
/// 5131 angle, note 5 (pull-out longer than the thread) and note 6 (short axis
/// limited to the retract distance), taper R with the |R| <= |U/2| rule.
#[test]
fn g92_starts_inch_leads_and_pullout_notes() {
    let r = run("M3 S300\nG0 X40 Z5\nG92 X30 Z-20 F2 H3\nM30\n");
    let t: Vec<_> = r
        .actions
        .iter()
        .filter_map(|c| match c.action {
            Action::Thread(t) if t.sync == ThreadSync::Index => Some((t.lead, t.start_udeg)),
            _ => None,
        })
        .collect();
    assert_eq!(t, vec![(mm(6.0), 0), (mm(6.0), 120_000_000), (mm(6.0), 240_000_000)]);
    let r = run("M3 S300\nG0 X40 Z5\nG92 X30 Z-20 E8\nM30\n");
    let Action::Thread(t) = r.actions[3].action else { panic!("{:?}", kind_names(&r)) };
    assert_eq!(t.lead, 3_175_000);
    // 5130 = 0: no pull-out.
    let mut cfg = MachineConfig::default();
    cfg.params.set(Param::ThreadChamfer, 0);
    let r = run_with("M3 S300\nG0 X40 Z5\nG92 X30 Z-20 F2\nM30\n", cfg.clone(), Panel::default());
    assert_eq!(moves(&r)[1..], [('r', 30.0, 5.0), ('t', 30.0, -20.0), ('r', 40.0, -20.0), ('r', 40.0, 5.0)]);
    // 5130 = 15 (3 mm), 5131 = 30°: short axis 3·tan 30° = 1.732 mm radius.
    cfg.params.set(Param::ThreadChamfer, 15);
    cfg.params.set(Param::ThreadChamferAngle, 30);
    let r = run_with("M3 S300\nG0 X40 Z5\nG92 X30 Z-20 F2\nM30\n", cfg.clone(), Panel::default());
    assert_eq!(moves(&r)[2..4], [('t', 30.0, -17.0), ('t', 33.464, -20.0)]);
    // Note 6: only 1 mm (radius) to retract: the short axis pulls out 1 mm.
    cfg.params.set(Param::ThreadChamferAngle, 0);
    let r = run_with("M3 S300\nG0 X32 Z5\nG92 X30 Z-20 F2\nM30\n", cfg.clone(), Panel::default());
    assert_eq!(moves(&r)[3], ('t', 32.0, -20.0));
    // Note 5: 20 leads of pull-out on a 25 mm thread.
    cfg.params.set(Param::ThreadChamfer, 200);
    let r = run_with("M3 S300\nG0 X40 Z5\nG92 X30 Z-20 F2\nM30\n", cfg, Panel::default());
    assert_eq!(r.alarm_codes(), vec![(3, 4034)]);
    // Taper: cut starts at X30+2R; the pull-out starts 2 mm (one lead) of Z before
    // the end, on the taper line: X 28 + 2·(23/25) = 29.84.
    let r = run("M3 S300\nG0 X40 Z5\nG92 X30 Z-20 R-1 F2\nM30\n");
    assert_eq!(moves(&r)[1..3], [('r', 28.0, 5.0), ('t', 29.84, -18.0)]);
    assert_eq!(run("M3 S300\nG0 X40 Z5\nG92 X30 Z-20 R6 F2\nM30\n").alarm_codes(), vec![(3, 4030)]);
}

/// Figure 2.52: taper thread lead 2 in two passes; each G32 waits for the index.
/// Q gives the start angle; a thread block right after a thread block continues
/// without the index and ignores its Q (Q rule 2, note 2).
#[test]
fn figure_2_52_g32() {
    let r = run("M3 S500\nG00 X28 Z3\nG32 X51 W-75 F2.0\nG00 X55\nW75\nX27\nG32 X50 W-75 F2.0\nG00 X55\nW75\nM30\n");
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    assert_eq!(
        moves(&r),
        vec![
            ('r', 28.0, 3.0),
            ('t', 51.0, -72.0),
            ('r', 55.0, -72.0),
            ('r', 55.0, 3.0),
            ('r', 27.0, 3.0),
            ('t', 50.0, -72.0),
            ('r', 55.0, -72.0),
            ('r', 55.0, 3.0)
        ]
    );
    let r = run("M3 S500\nG00 X28 Z3\nG32 W-30 F2 Q180\nG32 X40 W-10 Q90\nG32 X50 Z-50\nG00 X60\nM30\n");
    let t: Vec<_> = r
        .actions
        .iter()
        .filter_map(|c| match c.action {
            Action::Thread(t) => Some((t.start_udeg, t.sync, t.lead)),
            _ => None,
        })
        .collect();
    assert_eq!(
        t,
        vec![
            (180_000_000, ThreadSync::Index, mm(2.0)),
            (0, ThreadSync::Continue, mm(2.0)),
            (0, ThreadSync::Continue, mm(2.0))
        ]
    );
    assert_eq!(run("M3 S500\nG32 W-30 F2 Q361\nM30\n").alarm_codes(), vec![(2, 4033)]);
    assert_eq!(run("M3 S500\nG32 W-30 F2 Q-1\nM30\n").alarm_codes(), vec![(2, 4033)]);
    // Spindle stopped: the pass would wait for the index for ever.
    assert_eq!(run("G32 W-30 F2\nM30\n").alarm_codes(), vec![(1, 4013)]);
}

/// Seed 003's G32 program (figure 3-32: F4, δ1 = 3, δ2 = 1.5, 74.5 mm per pass),
/// two passes. The position before N100 is not given ("……"); reconstructed as
/// X124 Z3 (δ1 = 3 before the thread), so U-62 reaches X62 and U-64 X60.
#[test]
fn seed_003_g32_program() {
    let r = run(
        "M3 S300\nG00 X124 Z3\nN100 G00 U-62\nN110 G32 W-74.5 F4\nN130 G00 U62\nN140 W74.5\nN150 U-64\nN160 G32 W-74.5\nN170 G00 U64\nN180 W74.5\nM30\n",
    );
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    assert_eq!(moves(&r)[2], ('t', 62.0, -71.5));
    assert_eq!(moves(&r)[6], ('t', 60.0, -71.5), "lead F4 kept for the second pass");
}

/// Figure 2.54: variable lead from 4 mm, +0.2 mm per revolution, two passes. The
/// lead at the end of 78 mm is √(4² + 2·0.2·78) = 6.87 mm, inside the range.
/// K beyond ±499.99 and a lead that would reach zero are alarm 0014.
#[test]
fn figure_2_54_g34() {
    let r = run("G00 X60 Z4 M03 S500\nG00 U-10\nG00 U-0.7\nG34 W-78 F4 K0.2\nG00 U10\nZ4\nG00 X50\nG00 U-1.0\n\
         G34 W-78 F4 K0.2\nG00 U10\nZ4\nM30\n");
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    let t: Vec<_> = r
        .actions
        .iter()
        .filter_map(|c| match c.action {
            Action::Thread(t) => Some((t.lead, t.lead_delta, t.sync)),
            _ => None,
        })
        .collect();
    assert_eq!(t, vec![(mm(4.0), 200_000, ThreadSync::Index); 2]);
    assert_eq!(moves(&r)[3], ('t', 49.3, -74.0));
    assert_eq!(moves(&r)[8], ('t', 49.0, -74.0));
    assert_eq!(run("M3 S500\nG34 W-78 F4 K-0.2\nM30\n").alarm_codes(), vec![(2, 14)]);
    assert_eq!(run("M3 S500\nG34 W-78 F4 K500\nM30\n").alarm_codes(), vec![(2, 14)]);
}

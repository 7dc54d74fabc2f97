//! CYCLE81–CYCLE89 and CYCLE840 on the lathe centre line (G17, drilling along Z,
//! or G18 with `_AXN=1`): the document's examples (seed 001 chapter 2.1) with the
//! drilling position X0 (a lathe has no Y), their depths computed here from the
//! document's formulas, and every alarm of the sections.

use super::*;
use interp_core::alarm::CycleAlarm;
use interp_core::canon::Plane;

/// The lathe at X0 (centre line), Z `z` mm, G17, feed `f` mm/min (G94), spindle
/// M3 at 500 rev/min.
fn centre(z: f64, f: f64) -> (MachineConfig, State) {
    let cfg = machine();
    let mut st = at(&cfg, 0.0, z);
    st.modal.plane = Plane::Xy;
    st.modal.feed_mode = FeedMode::PerMin;
    st.feed.per_min = mm(f);
    st.spindle.rpm = 500;
    (cfg, st)
}

/// The Z of every new depth the cycle feeds to (a linear move deeper than any before).
fn depths(c: &Called) -> Vec<f64> {
    let mut out = Vec::new();
    let mut deepest = f64::MAX;
    for (k, _, z) in moves(c) {
        if k == 'l' && z < deepest {
            deepest = z;
            out.push(z);
        }
    }
    out
}

/// The document's degression rules (lines 1789-1831), written out independently of
/// the generator: the first depth; then each stroke the last one less DAM (at
/// least DAM) or times |DAM| (at least MDEP); the last two strokes share the rest
/// equally once it is at most two strokes; a rest of at most one stroke in one.
fn doc_depths(rfp: f64, dp: f64, first: f64, dam: f64, mdep: f64) -> Vec<f64> {
    let total = rfp - dp;
    let mut out = vec![rfp - first];
    let (mut done, mut last) = (first, first);
    while total - done > 1e-9 {
        let left = total - done;
        let mut s = if dam > 0.0 { (last - dam).max(dam) } else { (last * -dam).max(mdep) };
        if left <= s {
            s = left;
        } else if left <= 2.0 * s {
            s = left / 2.0;
        }
        done += s;
        last = s;
        out.push(r3(rfp - done));
    }
    out
}

/// Lines 1805-1815 and 1827-1836: the two degression examples. RTP = RFP = 0, SDIS
/// 0, DP −40; FDEP −12, DAM 3 → −12 −21 −27 −30 −33 −36 −38 −40; FDEP −10, DAM
/// −0.8, _MDEP 5 → −10 −18 −24.4 −29.52 −34.52 −37.26 −40 (chip breaking: back 1 mm
/// by G1 between the strokes).
#[test]
fn cycle83_degression_examples_of_the_document() {
    let (cfg, st) = centre(0.0, 100.0);
    let amount = call(
        "CYCLE83",
        &reals(&[Some(0.0), Some(0.0), Some(0.0), Some(-40.0), None, Some(-12.0), None, Some(3.0)]),
        &st,
        &cfg,
    )
    .unwrap();
    let doc = doc_depths(0.0, -40.0, 12.0, 3.0, 0.0);
    assert_eq!(doc, [-12.0, -21.0, -27.0, -30.0, -33.0, -36.0, -38.0, -40.0]);
    assert_eq!(depths(&amount), doc);
    // Chip breaking: G1 back by the default 1 mm, G1 on, G0 out to RTP.
    assert_eq!(moves(&amount)[..4], [('l', 0.0, -12.0), ('l', 0.0, -11.0), ('l', 0.0, -21.0), ('l', 0.0, -20.0)]);
    assert_eq!(moves(&amount).last(), Some(&('r', 0.0, 0.0)));

    let mut args = reals(&[Some(0.0), Some(0.0), Some(0.0), Some(-40.0), None, Some(-10.0), None, Some(-0.8)]);
    args.extend([Arg::Empty, Arg::Empty, Arg::Empty, Arg::Int(0), Arg::Empty, Arg::Real(5.0)]);
    let factor = call("CYCLE83", &args, &st, &cfg).unwrap();
    let doc = doc_depths(0.0, -40.0, 10.0, -0.8, 5.0);
    assert_eq!(doc, [-10.0, -18.0, -24.4, -29.52, -34.52, -37.26, -40.0]);
    assert_eq!(depths(&factor), doc);
}

/// The programming example (lines 1919-1956) on the centre line: RTP 155, RFP 150,
/// SDIS 1. N40: DP 5, FDEP 100, DAM 20, FRF 1, chip breaking, _VRT 0.8; N60: DPR
/// 145, FDPR 50, DAM −0.6, DTB 1 s, FRF 0.5, chip removal, _MDEP 10, _DIS1 0.4.
#[test]
fn cycle83_programming_example() {
    let (cfg, st) = centre(155.0, 50.0);
    // N40 CYCLE83 (RTP, RFP, SDIS, DP, , FDEP, , DAM, , , FRF, VARI, , , _VRT)
    let mut n40 = reals(&[
        Some(155.0),
        Some(150.0),
        Some(1.0),
        Some(5.0),
        None,
        Some(100.0),
        None,
        Some(20.0),
        None,
        None,
        Some(1.0),
    ]);
    n40.extend([Arg::Int(0), Arg::Empty, Arg::Empty, Arg::Real(0.8)]);
    let c = call("CYCLE83", &n40, &st, &cfg).unwrap();
    let doc = doc_depths(150.0, 5.0, 50.0, 20.0, 0.0);
    assert_eq!(doc, [100.0, 70.0, 50.0, 30.0, 17.5, 5.0]);
    assert_eq!(depths(&c), doc);
    let m = moves(&c);
    // G0 to RFP+SDIS, G1 to the first depth, G1 back 0.8 (_VRT), G1 on.
    assert_eq!(m[..4], [('r', 0.0, 151.0), ('l', 0.0, 100.0), ('l', 0.0, 100.8), ('l', 0.0, 70.0)]);
    assert_eq!(m[m.len() - 2..], [('r', 0.0, 151.0), ('r', 0.0, 155.0)]);

    // N60 CYCLE83 (RTP, RFP, SDIS, , DPR, , FDPR, DAM, DTB, , FRF, VARI, , _MDEP, , , _DIS1)
    let mut n60 = reals(&[
        Some(155.0),
        Some(150.0),
        Some(1.0),
        None,
        Some(145.0),
        None,
        Some(50.0),
        Some(-0.6),
        Some(1.0),
        None,
        Some(0.5),
    ]);
    n60.extend([Arg::Int(1), Arg::Empty, Arg::Real(10.0), Arg::Empty, Arg::Empty, Arg::Real(0.4)]);
    let c = call("CYCLE83", &n60, &st, &cfg).unwrap();
    let doc = doc_depths(150.0, 5.0, 50.0, -0.6, 10.0);
    assert_eq!(doc, [100.0, 70.0, 52.0, 41.2, 31.2, 21.2, 13.1, 5.0]);
    assert_eq!(depths(&c), doc);
    let m = moves(&c);
    // Chip removal: G0 to RFP+SDIS, G0 back to 0.4 (_DIS1) before the depth reached.
    assert_eq!(m[..5], [('r', 0.0, 151.0), ('l', 0.0, 100.0), ('r', 0.0, 151.0), ('r', 0.0, 100.4), ('l', 0.0, 70.0)]);
    // The first stroke at F × FRF (25 mm/min), the others at F50; DTB 1 s at each
    // intermediate depth and _DTD = DTB at the bottom.
    let feeds: Vec<i64> = c
        .actions
        .iter()
        .filter_map(|a| if let Action::Linear(m) = a.action { Some(m.feed.value) } else { None })
        .collect();
    assert_eq!(feeds[0], mm(25.0));
    assert!(feeds[1..].iter().all(|&f| f == mm(50.0)));
    let dwells = c.actions.iter().filter(|a| matches!(a.action, Action::Dwell { ms: 1000 })).count();
    assert_eq!(dwells, doc.len());
}

/// The automatic anticipation distance (line 1909): 0.6 mm up to 30 mm deep, then
/// the depth / 50, at most 7 mm.
#[test]
fn cycle83_automatic_anticipation_distance() {
    let (cfg, st) = centre(2.0, 100.0);
    // RTP 2, RFP 0, SDIS 0, DP −100, FDEP −40 (no degression), chip removal.
    let mut args = reals(&[Some(2.0), Some(0.0), None, Some(-100.0), None, Some(-20.0), None, None, None, None, None]);
    args.push(Arg::Int(1));
    let c = call("CYCLE83", &args, &st, &cfg).unwrap();
    let reentries: Vec<f64> =
        moves(&c).windows(2).filter(|w| w[0] == ('r', 0.0, 0.0) && w[1].0 == 'r').map(|w| w[1].2).collect();
    // After −20 (20 mm deep: 0.6), −40 (40/50 = 0.8), −60 (1.2), −80 (1.6); then
    // out to RTP.
    assert_eq!(reentries, [-19.4, -39.2, -58.8, -78.4, 2.0]);
    assert_eq!(depths(&c), [-20.0, -40.0, -60.0, -80.0, -100.0]);
}

/// CYCLE81 (lines 1593-1611) and CYCLE82 (1670-1701): G0 to RFP+SDIS, G1 to the
/// depth (DP absolute or DPR relative), dwell, G0 to RTP.
#[test]
fn cycle81_and_cycle82_examples() {
    let (cfg, st) = centre(110.0, 200.0);
    let n40 = call("CYCLE81", &reals(&[Some(110.0), Some(100.0), Some(2.0), Some(35.0)]), &st, &cfg).unwrap();
    assert_eq!(moves(&n40), [('r', 0.0, 102.0), ('l', 0.0, 35.0), ('r', 0.0, 102.0), ('r', 0.0, 110.0)]);
    let n60 = call("CYCLE81", &reals(&[Some(110.0), Some(102.0), None, Some(35.0)]), &st, &cfg).unwrap();
    assert_eq!(moves(&n60)[..2], [('r', 0.0, 102.0), ('l', 0.0, 35.0)]);
    let n90 = call("CYCLE81", &reals(&[Some(110.0), Some(100.0), Some(2.0), None, Some(65.0)]), &st, &cfg).unwrap();
    assert_eq!(moves(&n90)[..2], [('r', 0.0, 102.0), ('l', 0.0, 35.0)]);
    assert_eq!(n90.state.work_pos(&cfg)[Axis::Z], mm(110.0));

    let c = call("CYCLE82", &reals(&[Some(110.0), Some(102.0), Some(4.0), Some(75.0), None, Some(2.0)]), &st, &cfg)
        .unwrap();
    assert_eq!(moves(&c), [('r', 0.0, 106.0), ('l', 0.0, 75.0), ('r', 0.0, 106.0), ('r', 0.0, 110.0)]);
    assert!(c.actions.iter().any(|a| a.action == Action::Dwell { ms: 2000 }));
}

/// G18 with `_AXN=1` drills along Z as G17 does (lines 1865-1883).
#[test]
fn g18_with_axn_1_drills_on_the_centre_line() {
    let (cfg, mut st) = centre(155.0, 50.0);
    let mut args = reals(&[
        Some(155.0),
        Some(150.0),
        Some(1.0),
        Some(5.0),
        None,
        Some(100.0),
        None,
        Some(20.0),
        None,
        None,
        Some(1.0),
    ]);
    args.extend([Arg::Int(0), Arg::Int(0), Arg::Empty, Arg::Real(0.8)]);
    let g17 = call("CYCLE83", &args, &st, &cfg).unwrap();
    st.modal.plane = Plane::Zx;
    args[12] = Arg::Int(1);
    let g18 = call("CYCLE83", &args, &st, &cfg).unwrap();
    assert_eq!(moves(&g17), moves(&g18));
}

/// CYCLE85 (lines 2577-2625): in at FFR, out at RFF; CYCLE89 (2979-2995) in and out
/// at the feed in force, dwell DTB.
#[test]
fn boring_feeds_in_and_out() {
    let (cfg, st) = centre(105.0, 100.0);
    // CYCLE85 (RFP+3, RFP, SDIS, , DPR, , FFR, RFF) with RFP 102, DPR 25, FFR 300, RFF 1.5 × FFR.
    let c = call(
        "CYCLE85",
        &reals(&[Some(105.0), Some(102.0), Some(2.0), None, Some(25.0), None, Some(300.0), Some(450.0)]),
        &st,
        &cfg,
    )
    .unwrap();
    let lin: Vec<(f64, i64)> = c
        .actions
        .iter()
        .filter_map(
            |a| if let Action::Linear(m) = a.action { Some((um(m.to.work[Axis::Z]), m.feed.value)) } else { None },
        )
        .collect();
    assert_eq!(lin, [(77.0, mm(300.0)), (104.0, mm(450.0))]);
    // CYCLE89 (RTP, RFP, 5, DP, , DTB): RFP 102, RTP 107, DP 72, DTB 3.
    let (cfg, st) = centre(107.0, 100.0);
    let c = call("CYCLE89", &reals(&[Some(107.0), Some(102.0), Some(5.0), Some(72.0), None, Some(3.0)]), &st, &cfg)
        .unwrap();
    assert_eq!(moves(&c), [('l', 0.0, 72.0), ('l', 0.0, 107.0)]);
    assert!(c.actions.iter().any(|a| a.action == Action::Dwell { ms: 3000 }));
}

/// The spindle actions of a call, in order.
fn spindle(c: &Called) -> Vec<SpindleDir> {
    c.actions.iter().filter_map(|a| if let Action::Spindle(s) = a.action { Some(s.dir) } else { None }).collect()
}

/// CYCLE86 (lines 2725-2751): oriented stop (M19), off the wall by RPA (X −1 as a
/// diameter; RPO on the missing Y is ignored), out, back, spindle on; CYCLE87
/// (2819-2835): M5, M0, out; CYCLE88 (2900-2918): dwell, M5 M0 — or only M5 with
/// `_ZSD[5]` = 1 — with the spindle started M4 (SDIR 4).
#[test]
fn boring_with_spindle_stop() {
    let (cfg, st) = centre(112.0, 200.0);
    let c = call(
        "CYCLE86",
        &reals(&[Some(112.0), Some(110.0), None, Some(77.0), None, Some(2.0)])
            .into_iter()
            .chain([Arg::Int(3), Arg::Real(-1.0), Arg::Real(-1.0), Arg::Real(1.0), Arg::Real(45.0)])
            .collect::<Vec<_>>(),
        &st,
        &cfg,
    )
    .unwrap();
    assert_eq!(
        moves(&c),
        [('r', 0.0, 110.0), ('l', 0.0, 77.0), ('r', -1.0, 77.0), ('r', -1.0, 112.0), ('r', 0.0, 112.0)]
    );
    assert!(c.actions.iter().any(|a| a.action == Action::Aux { m: 19 }));
    assert_eq!(spindle(&c), [SpindleDir::Cw]);

    let (cfg, st) = centre(113.0, 200.0);
    let c = call(
        "CYCLE87",
        &reals(&[Some(113.0), Some(110.0), Some(2.0), Some(77.0), None])
            .into_iter()
            .chain([Arg::Int(3)])
            .collect::<Vec<_>>(),
        &st,
        &cfg,
    )
    .unwrap();
    assert_eq!(moves(&c), [('r', 0.0, 112.0), ('l', 0.0, 77.0), ('r', 0.0, 113.0)]);
    assert_eq!(spindle(&c), [SpindleDir::Stop, SpindleDir::Cw]);
    assert!(c.actions.iter().any(|a| a.action == Action::Stop { optional: false }));

    let (cfg, mut st) = centre(105.0, 100.0);
    let args: Vec<_> = reals(&[Some(105.0), Some(102.0), Some(3.0), None, Some(72.0), Some(3.0)])
        .into_iter()
        .chain([Arg::Int(4)])
        .collect();
    let c = call("CYCLE88", &args, &st, &cfg).unwrap();
    // RFP+SDIS is RTP, where the tool is: no move before the cut.
    assert_eq!(moves(&c), [('l', 0.0, 30.0), ('r', 0.0, 105.0)]);
    assert_eq!(spindle(&c), [SpindleDir::Ccw, SpindleDir::Stop, SpindleDir::Ccw]);
    assert!(c.actions.iter().any(|a| a.action == Action::Stop { optional: false }));
    st.cycle.zsd[5] = 1;
    let c = call("CYCLE88", &args, &st, &cfg).unwrap();
    assert!(!c.actions.iter().any(|a| matches!(a.action, Action::Stop { .. })));
}

/// CYCLE840 (lines 2452-2504): without an encoder (ENC 1) the lead is F/S (200/500
/// = 0.4 mm), dwell 1 s, out with SDR M4, SDAC M3 after; with an encoder PIT 3.5,
/// the direction reversed automatically. CYCLE84 (line 2180, the example cut off
/// by the print: M5 → pitch 0.8): locked to the spindle in and out.
#[test]
fn tapping_examples() {
    let (cfg, st) = centre(60.0, 200.0);
    let args: Vec<_> = reals(&[Some(59.0), Some(56.0), None, Some(15.0), None, Some(1.0)])
        .into_iter()
        .chain([Arg::Int(4), Arg::Int(3), Arg::Int(1)])
        .collect();
    let c = call("CYCLE840", &args, &st, &cfg).unwrap();
    assert_eq!(moves(&c), [('r', 0.0, 56.0), ('l', 0.0, 15.0), ('l', 0.0, 56.0), ('r', 0.0, 59.0)]);
    let leads: Vec<_> = c
        .actions
        .iter()
        .filter_map(|a| if let Action::Linear(m) = a.action { Some((m.feed.mode, m.feed.value)) } else { None })
        .collect();
    assert_eq!(leads, [(FeedMode::PerRev, mm(0.4)), (FeedMode::PerRev, mm(0.4))]);
    assert_eq!(spindle(&c), [SpindleDir::Ccw, SpindleDir::Cw]);
    assert!(c.actions.iter().any(|a| a.action == Action::Dwell { ms: 1000 }));

    let (cfg, mut st) = centre(60.0, 200.0);
    st.spindle.dir = SpindleDir::Ccw;
    let args = reals(&[Some(59.0), Some(56.0), None, Some(15.0), None, None, None, None, None, None, Some(3.5)]);
    let c = call("CYCLE840", &args, &st, &cfg).unwrap();
    let lead = c.actions.iter().find_map(|a| if let Action::Linear(m) = a.action { Some(m.feed.value) } else { None });
    assert_eq!(lead, Some(mm(3.5)));
    assert_eq!(spindle(&c), [SpindleDir::Cw, SpindleDir::Ccw]);

    let (cfg, st) = centre(40.0, 200.0);
    // CYCLE84 (40, 36, 2, , 30, , 3, 5, , 90, 200, 500)
    let args: Vec<_> = reals(&[Some(40.0), Some(36.0), Some(2.0), None, Some(30.0), None])
        .into_iter()
        .chain([Arg::Int(3), Arg::Real(5.0), Arg::Empty, Arg::Real(90.0), Arg::Real(200.0), Arg::Real(500.0)])
        .collect();
    let c = call("CYCLE84", &args, &st, &cfg).unwrap();
    let taps: Vec<_> = c
        .actions
        .iter()
        .filter_map(|a| {
            if let Action::Tap(t) = a.action { Some((um(t.to.work[Axis::Z]), um(t.lead), t.dir)) } else { None }
        })
        .collect();
    assert_eq!(taps, [(6.0, 0.8, SpindleDir::Cw), (38.0, 0.8, SpindleDir::Ccw)]);
    assert_eq!(moves(&c).first(), Some(&('r', 0.0, 38.0)));
    assert_eq!(moves(&c).last(), Some(&('r', 0.0, 40.0)));
}

/// Every alarm of chapter 2.1's sections, each with no motion (`call` checks it).
#[test]
fn drilling_alarms_move_nothing() {
    let (cfg, st) = centre(110.0, 100.0);
    let err = |name: &str, args: &[Arg<'_>], st: &State| call(name, args, st, &cfg).unwrap_err();
    let sc = AlarmKind::SiemensCycle;
    // 61101: DPR with RTP = RFP; a depth on the retract plane's side.
    assert_eq!(
        err("CYCLE81", &reals(&[Some(100.0), Some(100.0), Some(2.0), None, Some(10.0)]), &st),
        sc(CycleAlarm::ReferencePlaneWrong)
    );
    assert_eq!(
        err("CYCLE81", &reals(&[Some(110.0), Some(100.0), Some(2.0), Some(105.0)]), &st),
        sc(CycleAlarm::ReferencePlaneWrong)
    );
    // 61107: first depth beyond the final depth.
    assert_eq!(
        err("CYCLE83", &reals(&[Some(110.0), Some(100.0), None, Some(50.0), None, Some(40.0)]), &st),
        sc(CycleAlarm::FirstDepthWrong)
    );
    // 61019: DAM < −1.
    assert_eq!(
        err("CYCLE83", &reals(&[Some(110.0), Some(100.0), None, Some(50.0), None, Some(90.0), None, Some(-2.0)]), &st),
        sc(CycleAlarm::ParameterWrong)
    );
    // 61002: VARI 2 of CYCLE83.
    let mut vari = reals(&[Some(110.0), Some(100.0), None, Some(50.0), None, Some(90.0), None, None, None, None, None]);
    vari.push(Arg::Int(2));
    assert_eq!(err("CYCLE83", &vari, &st), sc(CycleAlarm::MachiningTypeWrong));
    // 61803: _AXN = 2 in G17 is Y, which the lathe lacks.
    vari[11] = Arg::Int(0);
    vari.push(Arg::Int(2));
    assert_eq!(err("CYCLE83", &vari, &st), sc(CycleAlarm::AxisNotPresent));
    // 61005: G18 without _AXN drills along Y.
    let mut g18 = st;
    g18.modal.plane = Plane::Zx;
    assert_eq!(
        err("CYCLE81", &reals(&[Some(110.0), Some(100.0), None, Some(50.0)]), &g18),
        sc(CycleAlarm::NoThirdAxis)
    );
    assert_eq!(
        err("CYCLE86", &reals(&[Some(110.0), Some(100.0), None, Some(50.0), None, None, Some(3.0)]), &g18),
        sc(CycleAlarm::NoThirdAxis)
    );
    // 61102: SDIR other than 3/4.
    let sdir5: Vec<_> =
        reals(&[Some(110.0), Some(100.0), None, Some(50.0), None]).into_iter().chain([Arg::Int(5)]).collect();
    assert_eq!(err("CYCLE87", &sdir5, &st), sc(CycleAlarm::NoSpindleDirection));
    // CYCLE840: 61102 spindle stopped; 61807 SDR = the direction into the hole;
    // 61102 SDR = 0 without an encoder; 61125 _TECHNO; 61001 no pitch.
    let tap = |sdr: i64, enc: i64| -> Vec<Arg<'static>> {
        reals(&[Some(110.0), Some(100.0), None, Some(80.0), None, None])
            .into_iter()
            .chain([Arg::Int(sdr), Arg::Int(3), Arg::Int(enc), Arg::Empty, Arg::Real(1.0)])
            .collect()
    };
    let mut stopped = st;
    stopped.spindle.dir = SpindleDir::Stop;
    assert_eq!(err("CYCLE840", &tap(4, 11), &stopped), sc(CycleAlarm::NoSpindleDirection));
    assert_eq!(err("CYCLE840", &tap(3, 11), &st), sc(CycleAlarm::WrongSpindleDirection));
    assert_eq!(err("CYCLE840", &tap(0, 11), &st), sc(CycleAlarm::NoSpindleDirection));
    assert_eq!(err("CYCLE840", &tap(0, 7), &st), sc(CycleAlarm::ParameterWrong));
    let mut techno = tap(4, 11);
    techno.extend([Arg::Empty, Arg::Empty, Arg::Int(5)]);
    assert_eq!(err("CYCLE840", &techno, &st), sc(CycleAlarm::TechnologyWrong));
    let mut no_pitch = tap(4, 11);
    no_pitch[10] = Arg::Empty;
    assert_eq!(err("CYCLE840", &no_pitch, &st), sc(CycleAlarm::ThreadPitchWrong));
    // CYCLE84: MPIT 5 (pitch 0.8) against PIT 1.0: 61001.
    let contra: Vec<_> = reals(&[Some(110.0), Some(100.0), None, Some(80.0), None, None])
        .into_iter()
        .chain([Arg::Int(3), Arg::Real(5.0), Arg::Real(1.0)])
        .collect();
    assert_eq!(err("CYCLE84", &contra, &st), sc(CycleAlarm::ThreadPitchWrong));
    assert_eq!(sc(CycleAlarm::FirstDepthWrong).code(), 61107);
    assert_eq!(sc(CycleAlarm::WrongSpindleDirection).code(), 61807);
}

/// A length beyond 10 m stops the call where it is read: its alarm wins over the
/// checks after it, not over those before it; nothing moves.
#[test]
fn an_overflowing_length_is_the_alarm_where_it_is_read() {
    let (cfg, st) = centre(110.0, 100.0);
    let err = |name: &str, args: &[Arg<'_>], st: &State| call(name, args, st, &cfg).unwrap_err();
    // RTP out of range: before the levels' 61101.
    assert_eq!(
        err("CYCLE81", &reals(&[Some(1e20), Some(100.0), Some(2.0), None, Some(10.0)]), &st),
        AlarmKind::Overflow
    );
    assert_eq!(
        err("CYCLE81", &reals(&[Some(110.0), Some(100.0), Some(2.0), Some(f64::MAX)]), &st),
        AlarmKind::Overflow
    );
    // FDEP out of range: after VARI's 61002, before the first depth's 61107.
    let mut vari = reals(&[Some(110.0), Some(100.0), None, Some(50.0), None, Some(1e20), None, None, None, None, None]);
    vari.push(Arg::Int(2));
    assert_eq!(err("CYCLE83", &vari, &st), AlarmKind::SiemensCycle(CycleAlarm::MachiningTypeWrong));
    vari[11] = Arg::Int(0);
    assert_eq!(err("CYCLE83", &vari, &st), AlarmKind::Overflow);
    // _VRT out of range with a good hole: the overflow, nothing drilled.
    let mut vrt = reals(&[Some(110.0), Some(100.0), None, Some(50.0), None, Some(90.0)]);
    vrt.resize(14, Arg::Empty);
    vrt.push(Arg::Real(-1e20));
    assert_eq!(err("CYCLE83", &vrt, &st), AlarmKind::Overflow);
}

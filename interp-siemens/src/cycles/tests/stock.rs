//! CYCLE95 against the document: the roughing depths of lines 10727–10737 (39 mm,
//! MID 5 → 8 passes of 4.875; 36 mm → 8 of 4.5; 7 mm → 2 of 3.5) on the example's
//! contour KONTUR_1, the finishing contour's end points, the machining types, the
//! alarms. Until the SINUMERIK reader lands the contours are given in the FANUC
//! dialect (the same geometry: `,R5` is RND=5), read by the same engine.

use super::*;
use interp_core::alarm::CycleAlarm;
use interp_core::canon::Action;
use interp_core::config::Language;
use interp_core::program::Cursor;

/// KONTUR_1 (lines 10908–10921) in the FANUC dialect (X diameter): RND=5 of N130
/// rounds the corner at its end point.
const KONTUR_1: &str = "G01 Z120 X37\nZ117 X40\nZ112\nG01 Z95 X65 ,R5\nZ87\nZ77 X29\nZ62\nZ58 X44\nZ52\n\
                        Z41 X37\nZ35\nG01 X76\nM30\n";

/// A contour source over `text` (the whole text up to its M30).
fn contour(text: &str) -> ContourSource<'_> {
    let program = ProgramText {
        text: text.as_bytes(),
        start: Cursor::start(0),
        language: Language::Fanuc,
        vars: None,
        fmt: None,
    };
    static NO_VARS: interp_core::lang::siemens::vars::Vars = interp_core::lang::siemens::vars::Vars::new();
    ContourSource { program, start: Cursor::start(0), end: None, vars: &NO_VARS, front: &crate::SINUMERIK }
}

/// CYCLE95 arguments: MID, FALZ, FALX, FAL, FF1, FF2, FF3 (REAL), VARI, DT, DAM, _VRT.
fn c95(r: [f64; 7], vari: i64, dt: f64, dam: f64, vrt: f64) -> Vec<Arg<'static>> {
    let mut a = vec![Arg::Str(b"KONTUR_1")];
    a.extend(r.iter().map(|&v| Arg::Real(v)));
    a.extend([Arg::Int(vari), Arg::Real(dt), Arg::Real(dam), Arg::Real(vrt)]);
    a
}

/// Feeds told apart: FF1 0.3, FF2 0.1, FF3 0.2 mm/rev.
const FF: [f64; 3] = [0.3, 0.1, 0.2];

/// The X (diameter) of each roughing cut: an FF1 move along Z (X unchanged)
/// right after an infeed (a rapid, or the FF2 plunge along an undercut).
fn cut_levels(c: &Called) -> Vec<f64> {
    cut_levels_at(c, FF[0], FF[1])
}

/// [`cut_levels`] with the roughing feed `ff1` and the plunge feed `ff2`.
fn cut_levels_at(c: &Called, ff1: f64, ff2: f64) -> Vec<f64> {
    let mut out = Vec::new();
    let mut prev: Option<(bool, f64)> = None; // (was an infeed, X)
    for a in &c.actions {
        match a.action {
            Action::Rapid(m) => prev = Some((true, um(2 * m.to.work[Axis::X]))),
            Action::Linear(m) => {
                let x = um(2 * m.to.work[Axis::X]);
                let feed = um(m.feed.value);
                if let Some((true, px)) = prev
                    && feed == ff1
                    && px == x
                {
                    out.push(x);
                }
                prev = Some((feed == ff2, x));
            }
            _ => prev = Some((false, 0.0)),
        }
    }
    out
}

/// The document's depths: 39 mm in 8 passes of 4.875, the first undercut's 36 mm in
/// 8 of 4.5, the second's 7 mm in 2 of 3.5 (no allowance, no nose radius: the
/// depths are the contour's own diameters 76 − 37, 65 − 29, 44 − 37).
#[test]
fn cycle95_depths_of_the_document() {
    let cfg = machine();
    let st = at(&cfg, 81.0, 125.0);
    let a = c95([5.0, 0.0, 0.0, 0.0, FF[0], FF[1], FF[2]], 1, 0.0, 0.0, 0.5);
    let c = call_with("CYCLE95", &a, &st, &cfg, Some(contour(KONTUR_1))).unwrap();
    let levels = |top: f64, depth: f64, mid: f64| {
        let n = libm::ceil(depth / mid);
        (1..=n as u32).map(move |k| r3(top - depth * f64::from(k) / n))
    };
    let mut want: Vec<f64> = levels(76.0, 39.0, 5.0).collect();
    assert_eq!(want[0], 71.125);
    want.extend(levels(65.0, 36.0, 5.0));
    want.extend(levels(44.0, 7.0, 5.0));
    assert_eq!(want.len(), 8 + 8 + 2);
    assert_eq!(cut_levels(&c), want);
    let m = moves(&c);
    // The start point: _VRT 0.5 above X76 and before Z120; roughing ends there.
    assert_eq!(m[0], ('r', 77.0, 120.5));
    assert_eq!(m.last(), Some(&('r', 77.0, 120.5)));
}

/// Roughing leaves the allowances: the last pass of the main section cuts at X37
/// plus FALX (0.6 on the diameter) and its pull along the contour stays FALZ (1.2)
/// off the shoulder faces; the depths keep their count.
#[test]
fn cycle95_allowances() {
    let cfg = machine();
    let st = at(&cfg, 81.0, 125.0);
    let a = c95([5.0, 1.2, 0.6, 0.0, FF[0], FF[1], FF[2]], 1, 0.0, 0.0, 0.0);
    let c = call_with("CYCLE95", &a, &st, &cfg, Some(contour(KONTUR_1))).unwrap();
    let l = cut_levels(&c);
    assert_eq!(l.len(), 18);
    // Main section: the whole contour 0.6 higher (and 1.2 towards +Z): from X76.6
    // down to 37.6, the same 39 mm in 8 passes of 4.875.
    assert_eq!(l[7], 37.6);
    assert_eq!(l[0], 71.725);
    // The undercuts keep their depths too: 65.6 → 29.6 (36 in 8 of 4.5), 44.6 → 37.6.
    assert_eq!(l[8..], [61.1, 56.6, 52.1, 47.6, 43.1, 38.6, 34.1, 29.6, 41.1, 37.6]);
    // Nothing is cut inside the allowance: no cut end below X37.6 before Z117 …
    let m = moves(&c);
    assert!(m.iter().all(|&(_, x, z)| !(35.0..=120.0).contains(&z) || x >= 29.6 - 1e-9), "{m:?}");
    // … and no move reaches the end face at Z35 + 1.2.
    assert!(m.iter().all(|&(_, _, z)| z >= 36.2 - 1e-9));
}

/// Finishing only (VARI 5): the contour in its programmed direction at FF3 from an
/// approach 1 mm before its start, ending with the rounding R5 of N130 whose end
/// points lie 5·tan(θ/2) from the corner on both lines.
#[test]
fn cycle95_finishing_end_points() {
    let cfg = machine();
    let st = at(&cfg, 81.0, 125.0);
    let a = c95([5.0, 1.2, 0.6, 0.0, FF[0], FF[1], FF[2]], 5, 0.0, 0.0, 0.5);
    let c = call_with("CYCLE95", &a, &st, &cfg, Some(contour(KONTUR_1))).unwrap();
    let m = moves(&c);
    // Taper Z112/Ø40 → Z95/Ø65 (radius 12.5 over 17), then the cylinder Ø65.
    let theta = libm::atan2(12.5, 17.0);
    let l = 5.0 * libm::tan(theta / 2.0);
    let on_taper = (r3(65.0 - 2.0 * l * libm::sin(theta)), r3(95.0 + l * libm::cos(theta)));
    // From the start point (allowance + _VRT off the contour: X76 + 0.6 + 1,
    // Z120 + 1.2 + 0.5) to 1 mm + the allowances before the contour's start
    // (X: 0.3 + 1 of radius, Z: 1.2 + 1), G1 onto it.
    let want = vec![
        ('r', 77.6, 121.7),
        ('r', 39.6, 122.2),
        ('l', 37.0, 120.0),
        ('l', 40.0, 117.0),
        ('l', 40.0, 112.0),
        ('l', on_taper.0, on_taper.1),
        ('a', 65.0, r3(95.0 - l)),
        ('l', 65.0, 87.0),
        ('l', 29.0, 77.0),
        ('l', 29.0, 62.0),
        ('l', 44.0, 58.0),
        ('l', 44.0, 52.0),
        ('l', 37.0, 41.0),
        ('l', 37.0, 35.0),
        ('l', 76.0, 35.0),
        ('r', 77.6, 35.0),
        ('r', 77.6, 121.7),
    ];
    assert_eq!(m, want);
    // Every finishing move at FF3.
    assert!(c.actions.iter().all(|a| match a.action {
        Action::Linear(m) => um(m.feed.value) == FF[2],
        Action::Arc(m) => um(m.feed.value) == FF[2],
        _ => true,
    }));
}

/// A contour programmed from the shoulder down (the other way round): roughing
/// turns it (the same passes), finishing only runs it as programmed.
#[test]
fn cycle95_contour_direction() {
    let cfg = machine();
    let st = at(&cfg, 81.0, 125.0);
    let reversed = "G01 X76 Z35\nX37\nZ41\nZ52 X44\nZ58\nZ62 X29\nZ77\nZ87 X65\nZ95\nZ112 X40\nZ117\nZ120 X37\nM30\n";
    let a = c95([5.0, 0.0, 0.0, 0.0, FF[0], FF[1], FF[2]], 1, 0.0, 0.0, 0.5);
    let fwd = "G01 Z120 X37\nZ117 X40\nZ112\nZ95 X65\nZ87\nZ77 X29\nZ62\nZ58 X44\nZ52\nZ41 X37\nZ35\nX76\nM30\n";
    let (c1, c2) = (
        call_with("CYCLE95", &a, &st, &cfg, Some(contour(reversed))).unwrap(),
        call_with("CYCLE95", &a, &st, &cfg, Some(contour(fwd))).unwrap(),
    );
    assert_eq!(moves(&c1), moves(&c2));
    let a = c95([5.0, 0.0, 0.0, 0.0, FF[0], FF[1], FF[2]], 5, 0.0, 0.0, 0.5);
    let c = call_with("CYCLE95", &a, &st, &cfg, Some(contour(reversed))).unwrap();
    let m = moves(&c);
    // From before X76/Z35 (1 mm outside and beyond it), first along the face down.
    assert_eq!(m[1], ('r', 78.0, 34.0));
    assert_eq!(m[2], ('l', 76.0, 35.0));
    assert_eq!(m[3], ('l', 37.0, 35.0));
}

/// _ZSD[0] = 1: MID is a radius (5 mm: 19.5 mm of radius in 4 passes).
#[test]
fn cycle95_mid_as_radius() {
    let cfg = machine();
    let mut st = at(&cfg, 81.0, 125.0);
    st.cycle.zsd[0] = 1;
    let a = c95([5.0, 0.0, 0.0, 0.0, FF[0], FF[1], FF[2]], 1, 0.0, 0.0, 0.5);
    let c = call_with("CYCLE95", &a, &st, &cfg, Some(contour(KONTUR_1))).unwrap();
    let l = cut_levels(&c);
    assert_eq!(l[..4], [66.25, 56.5, 46.75, 37.0]);
}

/// DAM 10 with DT 0.5 s: every roughing cut stops for 500 ms after each 10 mm.
#[test]
fn cycle95_chip_breaking() {
    let cfg = machine();
    let st = at(&cfg, 81.0, 125.0);
    let a = c95([5.0, 0.0, 0.0, 0.0, FF[0], FF[1], FF[2]], 1, 0.5, 10.0, 0.5);
    let c = call_with("CYCLE95", &a, &st, &cfg, Some(contour(KONTUR_1))).unwrap();
    // The first cut: X71.125 from Z120.5 to Z35 (the end face): dwells at 110.5 … 40.5.
    let mut first = Vec::new();
    for a in c.actions.iter().skip(2) {
        match a.action {
            Action::Linear(m) => first.push(('l', um(m.to.work[Axis::Z]))),
            Action::Dwell { ms } => first.push(('d', f64::from(ms))),
            _ => break,
        }
        if first.len() == 18 {
            break;
        }
    }
    assert_eq!(first[..4], [('l', 110.5), ('d', 500.0), ('l', 100.5), ('d', 500.0)]);
    assert_eq!(first[16], ('l', 35.0));
}

/// An inside contour (VARI 3): infeed towards +X from the bore, cut towards -Z.
#[test]
fn cycle95_inside_longitudinal() {
    let cfg = machine();
    let st = at(&cfg, 10.0, 5.0);
    let bore = "G01 X40 Z0\nZ-10\nX30 Z-15\nZ-30\nX20\nM30\n";
    let a = c95([4.0, 0.0, 0.0, 0.0, FF[0], FF[1], FF[2]], 3, 0.0, 0.0, 1.0);
    let c = call_with("CYCLE95", &a, &st, &cfg, Some(contour(bore))).unwrap();
    // From the bore Ø20 up to Ø40 (20 mm of diameter) in 5 passes of 4.
    assert_eq!(cut_levels(&c), [24.0, 28.0, 32.0, 36.0, 40.0]);
    assert_eq!(moves(&c)[0], ('r', 18.0, 1.0));
}

/// A face contour (VARI 2): infeed along -Z, cuts along X towards the centre.
#[test]
fn cycle95_face_outside() {
    let cfg = machine();
    let st = at(&cfg, 100.0, 10.0);
    let face = "G01 X20 Z0\nX40\nZ-2\nX60 Z-4\nX80\nZ-8\nM30\n";
    let a = c95([2.0, 0.0, 0.0, 0.0, FF[0], FF[1], FF[2]], 2, 0.0, 0.0, 1.0);
    let c = call_with("CYCLE95", &a, &st, &cfg, Some(contour(face))).unwrap();
    let m = moves(&c);
    // Start point 1 mm in front of Z0 and 1 mm outside X80 … the cuts along X at
    // Z-2, -4, -6, -8 (8 mm in passes of 2).
    let cuts: Vec<f64> =
        m.windows(2).filter(|w| w[0].0 == 'r' && w[1].0 == 'l' && w[0].2 == w[1].2).map(|w| w[1].2).collect();
    assert_eq!(cuts, [-2.0, -4.0, -6.0, -8.0]);
}

#[test]
fn cycle95_alarms_move_nothing() {
    let cfg = machine();
    let st = at(&cfg, 81.0, 125.0);
    let k1 = || Some(contour(KONTUR_1));
    for vari in [0, 13, 109, 313, 1001] {
        let a = c95([5.0, 0.0, 0.0, 0.0, FF[0], FF[1], FF[2]], vari, 0.0, 0.0, 0.5);
        assert_eq!(
            call_with("CYCLE95", &a, &st, &cfg, k1()).unwrap_err(),
            AlarmKind::SiemensCycle(CycleAlarm::MachiningTypeWrong),
            "{vari}"
        );
    }
    let a = c95([5.0, 0.0, 0.0, 0.0, FF[0], FF[1], FF[2]], 9, 0.0, 0.0, 0.5);
    // Started inside the contour's rectangle: 61607.
    let inside = at(&cfg, 50.0, 100.0);
    assert_eq!(
        call_with("CYCLE95", &a, &inside, &cfg, k1()).unwrap_err(),
        AlarmKind::SiemensCycle(CycleAlarm::StartPointWrong)
    );
    assert_eq!(AlarmKind::SiemensCycle(CycleAlarm::StartPointWrong).code(), 61607);
    // The undercut 65 → 29 falls at atan(18/10) = 61°: a 30° clearance angle cannot cut it.
    let mut cfg30 = cfg.clone();
    cfg30.tools.get_mut(1).unwrap().clearance_udeg = 30_000_000;
    let mut st1 = st;
    st1.tool.offset_number = 1;
    assert_eq!(
        call_with("CYCLE95", &a, &st1, &cfg30, k1()).unwrap_err(),
        AlarmKind::SiemensCycle(CycleAlarm::ToolViolatesContour)
    );
    assert_eq!(AlarmKind::SiemensCycle(CycleAlarm::ToolViolatesContour).code(), 61604);
    // 62° is enough; 0 = no check.
    cfg30.tools.get_mut(1).unwrap().clearance_udeg = 62_000_000;
    assert!(call_with("CYCLE95", &a, &st1, &cfg30, k1()).is_ok());
    // Contour preparation (61606): too few blocks (10933), a thread (10930), G41 (10931).
    let prep = |cause| AlarmKind::SiemensCycle(CycleAlarm::ContourPreparation { cause });
    for (text, cause) in [
        ("G01 Z120 X37\nZ35\nM30\n", 10933),
        ("G01 Z120 X37\nZ100\nG32 Z90 F2\nX76\nM30\n", 10930),
        ("G01 Z120 X37\nG42 Z100\nZ90\nX76\nM30\n", 10931),
        ("Z120 X37\nG01 Z100\nZ90\nX76\nM30\n", 15800),
    ] {
        assert_eq!(call_with("CYCLE95", &a, &st, &cfg, Some(contour(text))).unwrap_err(), prep(cause), "{text}");
    }
    assert_eq!(prep(10933).code(), 61606);
    // G41/G42 in force at the call: 15800.
    let mut g42 = st;
    g42.modal.nose_comp = interp_core::codes::GCode::NoseCompRight;
    assert_eq!(call_with("CYCLE95", &a, &g42, &cfg, k1()).unwrap_err(), prep(15800));
    // A contour turning back along Z (an overhang): 61605.
    let back = "G01 Z120 X37\nZ100\nZ105 X50\nZ90\nX76\nM30\n";
    assert_eq!(
        call_with("CYCLE95", &a, &st, &cfg, Some(contour(back))).unwrap_err(),
        AlarmKind::SiemensCycle(CycleAlarm::ContourWrong)
    );
    assert_eq!(AlarmKind::SiemensCycle(CycleAlarm::ContourWrong).code(), 61605);
}

/// The document's example 1 (lines 10891–10925): CYCLE95 (UPNAME, 5, 1.2, 0.6, ,
/// 0.2, 0.1, 0.2, 9, , , 0.5) from Z125 X81: complete machining; the roughing's 18
/// passes (39, 36 and 7 mm of diameter), then the finishing pass through the
/// contour's points at FF3.
#[test]
fn cycle95_example_1_complete() {
    let cfg = machine();
    let st = at(&cfg, 81.0, 125.0);
    let mut a = vec![Arg::Str(b"KONTUR_1"), Arg::Real(5.0), Arg::Real(1.2), Arg::Real(0.6), Arg::Empty];
    a.extend([Arg::Real(0.2), Arg::Real(0.1), Arg::Real(0.2), Arg::Int(9), Arg::Empty, Arg::Empty, Arg::Real(0.5)]);
    let c = call_with("CYCLE95", &a, &st, &cfg, Some(contour(KONTUR_1))).unwrap();
    let m = moves(&c);
    // The finishing pass: after the last G0 back to the start point and to the
    // approach point, the contour's points.
    let fin = m.iter().rposition(|x| *x == ('r', 39.6, 122.2)).map(|i| &m[i..]);
    let fin = fin.unwrap_or_else(|| panic!("{:?}", &m[m.len() - 20..]));
    let pts: Vec<(f64, f64)> = fin.iter().skip(1).filter(|x| x.0 != 'r').map(|x| (x.1, x.2)).collect();
    assert_eq!(pts[..3], [(37.0, 120.0), (40.0, 117.0), (40.0, 112.0)]);
    // The rounding R5 between the taper and Ø65: its ends 5·tan(θ/2) from the corner.
    let theta = libm::atan2(12.5, 17.0);
    let l = 5.0 * libm::tan(theta / 2.0);
    let near = |p: (f64, f64), q: (f64, f64)| (p.0 - q.0).abs() < 0.002 && (p.1 - q.1).abs() < 0.002;
    assert!(near(pts[3], (65.0 - 2.0 * l * libm::sin(theta), 95.0 + l * libm::cos(theta))), "{:?}", pts[3]);
    assert!(near(pts[4], (65.0, 95.0 - l)), "{:?}", pts[4]);
    assert_eq!(
        pts[5..],
        [
            (65.0, 87.0),
            (29.0, 77.0),
            (29.0, 62.0),
            (44.0, 58.0),
            (44.0, 52.0),
            (37.0, 41.0),
            (37.0, 35.0),
            (76.0, 35.0)
        ]
    );
    // Back: X first to the start point's X, then Z.
    assert_eq!(m[m.len() - 2..], [('r', 77.6, 35.0), ('r', 77.6, 121.7)]);
    assert_eq!(cut_levels_at(&c, 0.2, 0.1).len(), 18);
}

/// Complete machining with a nose radius 0.8 and cutting edge position 3: the
/// finishing pass positions the tip on the cylinders and faces as programmed, rounds
/// the outside corner on an arc of the nose, and ends on the last element's normal.
#[test]
fn cycle95_nose_compensation() {
    let mut cfg = machine();
    *cfg.tools.get_mut(1).unwrap() = interp_core::config::ToolOffset { radius: mm(0.8), tip: 3, ..Default::default() };
    let mut st = at(&cfg, 50.0, 5.0);
    st.tool.offset_number = 1;
    st.tool.nose_radius = mm(0.8);
    st.tool.tip = 3;
    let text = "G01 X20 Z0\nZ-20\nX40\nZ-40\nM30\n";
    let a = c95([4.0, 0.0, 0.0, 0.0, FF[0], FF[1], FF[2]], 9, 0.0, 0.0, 1.0);
    let c = call_with("CYCLE95", &a, &st, &cfg, Some(contour(text))).unwrap();
    let m = moves(&c);
    let i = m.iter().rposition(|x| x.0 == 'r' && x.2 > 0.0 && x.1 < 40.0).unwrap();
    assert_eq!(
        m[i + 1..],
        [
            ('l', 20.0, -0.8),
            ('l', 20.0, -20.0),
            ('l', 38.4, -20.0),
            ('a', 40.0, -20.8),
            ('l', 40.0, -40.8),
            ('r', 42.0, -40.8),
            ('r', 42.0, 1.0),
        ]
    );
    // Roughing: Ø40 → Ø20 (20 mm in 5 of 4): cuts at Ø36 … Ø20 with the tip.
    assert_eq!(cut_levels(&c), [36.0, 32.0, 28.0, 24.0, 20.0]);
}

/// The document's example 2 (lines 10927–10954): DIAMOF, the contour X10 Z100 →
/// Z90 → Z70 at 150° → Z50 at 135° → X50 (radius values), CYCLE95 ("ANFANG:ENDE",
/// 2.5, 0.8, 0.8, 0, 0.8, 0.75, 0.6, 1) from X70 Z60: roughing only; MID is a
/// radius under DIAMOF; the contour moved by 0.8 in X and Z spans X10.8 to 50.8:
/// 40 mm in 16 passes of 2.5.
#[test]
fn cycle95_example_2_diamof() {
    let mut cfg = machine();
    cfg.diameter_x = false;
    let mut st = at(&cfg, 140.0, 60.0);
    st.modal.diameter = false;
    let (x2, x3) = (10.0 + 20.0 * libm::tan(30f64.to_radians()), 10.0 + 20.0 * libm::tan(30f64.to_radians()) + 20.0);
    let text = std::format!("G01 X10 Z100\nZ90\nX{x2:.6} Z70\nX{x3:.6} Z50\nX50 Z50\nM30\n");
    let a = [2.5, 0.8, 0.8, 0.0, 0.8, 0.75, 0.6].map(Arg::Real);
    let mut a: Vec<Arg<'static>> = std::iter::once(Arg::Str(b"ANFANG:ENDE")).chain(a).collect();
    a.push(Arg::Int(1));
    let c = call_with("CYCLE95", &a, &st, &cfg, Some(contour(&text))).unwrap();
    let levels: Vec<f64> = cut_levels_at(&c, 0.8, 0.75).iter().map(|x| r3(x / 2.0)).collect();
    let want: Vec<f64> = (1..=16).map(|k| r3(50.8 - 2.5 * f64::from(k))).collect();
    assert_eq!(levels, want);
    // Start point: 1 mm (_VRT 0) above X50.8, 1 mm before Z100.8.
    assert_eq!(moves(&c)[0], ('r', 2.0 * 51.8, 101.8));
}

/// CYCLE950 arguments: _VARI, _MID, _FALZ, _FALX, _FF1–_FF4, _VRT, _ANGB, _SDIS; the blank
/// `_APZ, _APZA, _APX, _APXA`; _TOL1.
fn c950(vari: i64, r: [f64; 10], blank: (f64, i64, f64, i64), tol: f64) -> Vec<Arg<'static>> {
    let mut a = vec![Arg::Str(b"KONTUR_1"), Arg::Empty, Arg::Empty, Arg::Str(b"BEARBEITE"), Arg::Int(vari)];
    a.extend(r.iter().map(|&v| Arg::Real(v)));
    a.extend([Arg::Empty, Arg::Empty, Arg::Empty, Arg::Empty]);
    a.extend([Arg::Real(blank.0), Arg::Int(blank.1), Arg::Real(blank.2), Arg::Int(blank.3), Arg::Real(tol)]);
    a
}

/// _MID 5 on KONTUR_1: full steps of 5 until less than 10 are left, then two halves
/// (lines 11702–11706): the main section's 39 mm as 6 × 5 + 2 × 4.5, the first
/// undercut's 36 as 6 × 5 + 2 × 3, the second's 7 as 2 × 3.5. Feeds: _FF1 along Z.
#[test]
fn cycle950_full_steps_then_halves() {
    let cfg = machine();
    let st = at(&cfg, 81.0, 125.0);
    let r = [5.0, 0.0, 0.0, 0.3, 0.1, 0.2, 0.05, 0.5, 0.0, 0.0];
    let c = call_with("CYCLE950", &c950(311111, r, (0.0, 0, 0.0, 0), 0.0), &st, &cfg, Some(contour(KONTUR_1))).unwrap();
    let steps = |top: f64, depth: f64, mid: f64| {
        let full = ((depth - 2.0 * mid) / mid).floor().max(-1.0) as i32 + 1;
        let mut v: Vec<f64> = (1..=full).map(|k| top - mid * f64::from(k)).collect();
        let rest = depth - mid * f64::from(full);
        v.extend([r3(top - mid * f64::from(full) - rest / 2.0), r3(top - depth)]);
        v
    };
    let mut want = steps(76.0, 39.0, 5.0);
    assert_eq!(want, [71.0, 66.0, 61.0, 56.0, 51.0, 46.0, 41.5, 37.0]);
    want.extend(steps(65.0, 36.0, 5.0));
    want.extend(steps(44.0, 7.0, 5.0));
    assert_eq!(cut_levels_at(&c, 0.3, 0.1), want);
    // Without the undercuts (ten-thousands 2): the main section only.
    let c = call_with("CYCLE950", &c950(321111, r, (0.0, 0, 0.0, 0), 0.0), &st, &cfg, Some(contour(KONTUR_1))).unwrap();
    assert_eq!(cut_levels_at(&c, 0.3, 0.1), steps(76.0, 39.0, 5.0));
}

/// Without following the contour (thousands 2) each cut leaves it at once at
/// _ANGB: 30° takes _VRT 0.5 along Z and 0.5·tan 30° up (never more than _VRT).
#[test]
fn cycle950_retract_angle_without_pull() {
    let cfg = machine();
    let st = at(&cfg, 81.0, 125.0);
    let r = [5.0, 0.0, 0.0, 0.3, 0.1, 0.2, 0.05, 0.5, 30.0, 0.0];
    let c = call_with("CYCLE950", &c950(322111, r, (0.0, 0, 0.0, 0), 0.0), &st, &cfg, Some(contour(KONTUR_1))).unwrap();
    let m = moves(&c);
    // The first cut at Ø71 ends on the end face (Z35), leaves it to Z35.5 and up.
    let i = m.iter().position(|x| *x == ('l', 71.0, 35.0)).unwrap();
    assert_eq!(m[i + 1], ('l', r3(71.0 + 2.0 * 0.5 * libm::tan(30f64.to_radians())), 35.5));
}

/// A blank cylinder Ø80 (_APX 80, _APXA 90): the main section starts there.
#[test]
fn cycle950_blank_cylinder() {
    let cfg = machine();
    let st = at(&cfg, 90.0, 125.0);
    let r = [5.0, 0.0, 0.0, 0.3, 0.1, 0.2, 0.05, 0.5, 0.0, 0.0];
    let c =
        call_with("CYCLE950", &c950(321111, r, (0.0, 0, 80.0, 90), 2.0), &st, &cfg, Some(contour(KONTUR_1))).unwrap();
    let l = cut_levels_at(&c, 0.3, 0.1);
    assert_eq!(l[0], 75.0);
    assert_eq!(l.last(), Some(&37.0));
    // The start point: _VRT above Ø80, _TOL1 (2) before Z120.
    assert_eq!(moves(&c)[0], ('r', 81.0, 122.0));
}

/// Contour-parallel roughing (units 3) with a blank 2 mm (radius) round the contour
/// and _MID 1: G73's passes one _MID in from the blank each, the first 1 mm out,
/// the last on the contour, then the finishing pass at _FF3 with its arc at _FF4.
#[test]
fn cycle950_contour_parallel() {
    let cfg = machine();
    let st = at(&cfg, 100.0, 130.0);
    let text = "G01 X40 Z120\nZ100\nG02 X60 Z90 R10\nG01 X80\nZ60\nM30\n";
    let r = [1.0, 0.0, 0.0, 0.3, 0.1, 0.2, 0.05, 0.5, 0.0, 0.0];
    let c = call_with("CYCLE950", &c950(311313, r, (2.0, 91, 4.0, 91), 0.0), &st, &cfg, Some(contour(text))).unwrap();
    let m = moves(&c);
    // The start point outside the blank: _VRT (0.5) over Ø80 + 4, _TOL1 (1) before Z120 + 2.
    assert_eq!(m[0], ('r', 85.0, 123.0));
    // Pass 1: the contour moved 1 out (X+2 on the diameter) and 1 back (Z+1); pass 2 on it.
    assert!(m.contains(&('l', 42.0, 101.0)), "{m:?}");
    assert!(m.contains(&('l', 40.0, 100.0)), "{m:?}");
    assert!(!m.contains(&('l', 44.0, 102.0)), "{m:?}");
    // Finishing: the arc at _FF4.
    let arcs: Vec<i64> = c
        .actions
        .iter()
        .filter_map(|a| match a.action {
            Action::Arc(m) => Some(m.feed.value),
            _ => None,
        })
        .collect();
    assert_eq!(arcs.last(), Some(&mm(0.05)));
}

#[test]
fn cycle950_alarms_move_nothing() {
    let cfg = machine();
    let st = at(&cfg, 81.0, 125.0);
    let r = [5.0, 0.0, 0.0, 0.3, 0.1, 0.2, 0.05, 0.5, 0.0, 0.0];
    let k1 = || Some(contour(KONTUR_1));
    for vari in [311114, 311115, 311131, 111111, 311411, 313111, 331111, 1311111, 0] {
        let e = call_with("CYCLE950", &c950(vari, r, (0.0, 0, 0.0, 0), 0.0), &st, &cfg, k1()).unwrap_err();
        assert_eq!(e, AlarmKind::SiemensCycle(CycleAlarm::IllegalInput), "{vari}");
    }
    assert_eq!(AlarmKind::SiemensCycle(CycleAlarm::IllegalInput).code(), 61720);
    // Z+ asked for a contour that can only be cut towards Z-: 61721.
    let e = call_with("CYCLE950", &c950(411111, r, (0.0, 0, 0.0, 0), 0.0), &st, &cfg, k1()).unwrap_err();
    assert_eq!(e, AlarmKind::SiemensCycle(CycleAlarm::ContourDirection));
    assert_eq!(AlarmKind::SiemensCycle(CycleAlarm::ContourDirection).code(), 61721);
    // No finished contour: 61701; a blank neither absolute nor incremental: 61702.
    let e = call_with("CYCLE950", &c950(311111, r, (0.0, 0, 0.0, 0), 0.0), &st, &cfg, None).unwrap_err();
    assert_eq!(e, AlarmKind::SiemensCycle(CycleAlarm::FinishedContourWrong));
    assert_eq!(AlarmKind::SiemensCycle(CycleAlarm::FinishedContourWrong).code(), 61701);
    let e = call_with("CYCLE950", &c950(311111, r, (0.0, 0, 80.0, 92), 0.0), &st, &cfg, k1()).unwrap_err();
    assert_eq!(e, AlarmKind::SiemensCycle(CycleAlarm::BlankContourWrong));
    assert_eq!(AlarmKind::SiemensCycle(CycleAlarm::BlankContourWrong).code(), 61702);
    // A blank contour program is not supported: 4007.
    let mut a = c950(311111, r, (0.0, 0, 0.0, 0), 0.0);
    a[15] = Arg::Str(b"ROHTEIL1");
    assert_eq!(call_with("CYCLE950", &a, &st, &cfg, k1()).unwrap_err().code(), 4007);
}

/// The whole toolpath of CYCLE95/CYCLE950 in every machining direction and form
/// (rough with the overlapping and the previous-cut pull, finish, complete, chip
/// breaking, inside, face, CYCLE950's steps, angle, blank), one line per move:
/// kind, X diameter and Z in mm, and the feed (mm/rev) when it changes. Pinned in
/// `tests/golden_stock.txt`, so that moving the roughing onto G71/G72's engine
/// (issue 19) shows every move it changes. `GOLDEN=write cargo test -p interp-core --lib
/// pinned` writes the file anew.
#[test]
fn cycle95_and_cycle950_toolpaths_are_pinned() {
    /// Title, cycle, arguments, start point (X diameter, Z), contour text.
    type Case = (&'static str, &'static str, Vec<Arg<'static>>, (f64, f64), &'static str);
    use core::fmt::Write as _;
    let cfg = machine();
    let r950 = [5.0, 0.0, 0.0, 0.3, 0.1, 0.2, 0.05, 0.5, 0.0, 0.0];
    let bore = "G01 X40 Z0\nZ-10\nX30 Z-15\nZ-30\nX20\nM30\n";
    let face = "G01 X20 Z0\nX40\nZ-2\nX60 Z-4\nX80\nZ-8\nM30\n";
    let cases: Vec<Case> = vec![
        (
            "CYCLE95 VARI 1",
            "CYCLE95",
            c95([5.0, 0.0, 0.0, 0.0, FF[0], FF[1], FF[2]], 1, 0.0, 0.0, 0.5),
            (81.0, 125.0),
            KONTUR_1,
        ),
        (
            "CYCLE95 VARI 201",
            "CYCLE95",
            c95([5.0, 0.0, 0.0, 0.0, FF[0], FF[1], FF[2]], 201, 0.0, 0.0, 0.5),
            (81.0, 125.0),
            KONTUR_1,
        ),
        (
            "CYCLE95 VARI 9 allowances",
            "CYCLE95",
            c95([5.0, 1.2, 0.3, 0.2, FF[0], FF[1], FF[2]], 9, 0.0, 0.0, 0.5),
            (81.0, 125.0),
            KONTUR_1,
        ),
        (
            "CYCLE95 VARI 5",
            "CYCLE95",
            c95([5.0, 0.0, 0.0, 0.0, FF[0], FF[1], FF[2]], 5, 0.0, 0.0, 0.5),
            (81.0, 125.0),
            KONTUR_1,
        ),
        (
            "CYCLE95 VARI 1 chip breaking",
            "CYCLE95",
            c95([5.0, 0.0, 0.0, 0.0, FF[0], FF[1], FF[2]], 1, 0.5, 10.0, 0.5),
            (81.0, 125.0),
            KONTUR_1,
        ),
        (
            "CYCLE95 VARI 11 bore",
            "CYCLE95",
            c95([4.0, 0.0, 0.0, 0.0, FF[0], FF[1], FF[2]], 11, 0.0, 0.0, 1.0),
            (10.0, 5.0),
            bore,
        ),
        (
            "CYCLE95 VARI 10 face",
            "CYCLE95",
            c95([2.0, 0.0, 0.0, 0.0, FF[0], FF[1], FF[2]], 10, 0.0, 0.0, 1.0),
            (100.0, 10.0),
            face,
        ),
        ("CYCLE950 311111", "CYCLE950", c950(311111, r950, (0.0, 0, 0.0, 0), 0.0), (81.0, 125.0), KONTUR_1),
        (
            "CYCLE950 322111 30 deg",
            "CYCLE950",
            c950(
                322111,
                {
                    let mut r = r950;
                    r[8] = 30.0;
                    r
                },
                (0.0, 0, 0.0, 0),
                0.0,
            ),
            (81.0, 125.0),
            KONTUR_1,
        ),
        ("CYCLE950 321111 blank", "CYCLE950", c950(321111, r950, (0.0, 0, 80.0, 90), 2.0), (90.0, 125.0), KONTUR_1),
    ];
    let mut text = std::string::String::new();
    for (title, name, args, (x, z), shape) in &cases {
        let st = at(&cfg, *x, *z);
        let c = call_with(name, args, &st, &cfg, Some(contour(shape))).unwrap_or_else(|e| panic!("{title}: {e:?}"));
        let _ = writeln!(text, "# {title}");
        let mut feed = None;
        for a in &c.actions {
            let (k, to, f) = match a.action {
                Action::Rapid(m) => ('r', m.to.work, None),
                Action::Linear(m) => ('l', m.to.work, Some(m.feed.value)),
                Action::Arc(m) => ('a', m.to.work, Some(m.feed.value)),
                _ => continue,
            };
            let _ = write!(text, "{k} {} {}", um(2 * to[Axis::X]), um(to[Axis::Z]));
            if f.is_some() && f != feed {
                let _ = write!(text, " F{}", um(f.unwrap_or(0)));
                feed = f;
            }
            text.push('\n');
        }
    }
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/golden_stock.txt");
    if std::env::var("GOLDEN").as_deref() == Ok("write") {
        std::fs::write(path, &text).unwrap();
    }
    let want = std::fs::read_to_string(path).expect("tests/golden_stock.txt (GOLDEN=write writes it)");
    for (i, (got, want)) in text.lines().zip(want.lines()).enumerate() {
        assert_eq!(got, want, "line {} of tests/golden_stock.txt", i + 1);
    }
    assert_eq!(text.lines().count(), want.lines().count(), "moves in tests/golden_stock.txt");
}

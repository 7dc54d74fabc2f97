//! CYCLE97 and CYCLE98 against the document: pass diameters for constant infeed
//! and constant cross-section, the flank infeed, starts, pitches per segment, the
//! alarms.

use super::*;
use interp_core::alarm::CycleAlarm;

/// CYCLE97 arguments: PIT, MPIT, SPL, FPL, DM1, DM2, APP, ROP, TDEP, FAL, IANG, NSP
/// as REAL, NRC, NID, VARI, NUMT as INT, _VRT.
fn c97(r: [f64; 12], nrc: i64, nid: i64, vari: i64, numt: i64, vrt: f64) -> Vec<Arg<'static>> {
    let mut a: Vec<Arg<'static>> = r.iter().map(|&v| Arg::Real(v)).collect();
    a.extend([Arg::Int(nrc), Arg::Int(nid), Arg::Int(vari), Arg::Int(numt), Arg::Real(vrt)]);
    a
}

/// The document's example (lines 11231–11251): M42 (MPIT 42: pitch 4.5), Z0 to
/// Z-35, APP 10, ROP 3, TDEP 1.23, no allowance, flank infeed IANG 30, NRC 5, NID 2,
/// VARI 3 (outside, constant cross-section), from X60 Z100. PIT is left out.
fn example(vari: i64) -> Vec<Arg<'static>> {
    let mut a = c97([0.0, 42.0, 0.0, -35.0, 42.0, 42.0, 10.0, 3.0, 1.23, 0.0, 30.0, 0.0], 5, 2, vari, 1, 0.0);
    a[0] = Arg::Empty;
    a
}

/// The passes the document's formulas give for the example: rough pass k of n at
/// TDEP·√(k/n) (constant cross-section) or TDEP·k/n (constant infeed), then NID
/// idle passes at TDEP; every pass on the flank that the last one cuts at Z0:
/// moved by (TDEP − d)·tan 30° towards the thread end. Start point 1 mm above the
/// diameter at SPL + APP, retract _VRT = 1 mm above it, back to Z10.
fn expected(section: bool) -> Vec<(char, f64, f64)> {
    let (t, n) = (1.23, 5.0);
    let mut depths: Vec<f64> =
        (1..=5).map(|k| if section { t * libm::sqrt(k as f64 / n) } else { t * k as f64 / n }).collect();
    depths.extend([t, t]);
    let mut want = vec![('r', 44.0, 10.0)];
    for d in depths {
        let shift = (t - d) * libm::tan(30f64.to_radians());
        let x = r3(42.0 - 2.0 * d);
        want.extend([
            ('r', x, r3(10.0 - shift)),
            ('t', x, r3(-38.0 - shift)),
            ('r', 44.0, r3(-38.0 - shift)),
            ('r', 44.0, 10.0),
        ]);
    }
    want
}

#[test]
fn cycle97_example_constant_cross_section() {
    let cfg = machine();
    let c = call("CYCLE97", &example(3), &at(&cfg, 60.0, 100.0), &cfg).unwrap();
    assert_eq!(moves(&c), expected(true));
    // Pass diameters 40.900, 40.444, 40.094, 39.800, 39.540, 39.540, 39.540.
    let dia: Vec<f64> = threads(&c).iter().map(|t| t.0).collect();
    assert_eq!(dia, [40.9, 40.444, 40.094, 39.8, 39.54, 39.54, 39.54]);
    // Lead 4.5 (M42), every pass waits for the index at 0°.
    assert!(threads(&c).iter().all(|t| t.2 == 4.5 && t.3 == 0.0 && t.4));
    // The block ends where the last pass returned to.
    assert_eq!((um(2 * c.state.work_pos(&cfg)[Axis::X]), um(c.state.work_pos(&cfg)[Axis::Z])), (44.0, 10.0));
}

#[test]
fn cycle97_constant_infeed() {
    let cfg = machine();
    let c = call("CYCLE97", &example(1), &at(&cfg, 60.0, 100.0), &cfg).unwrap();
    assert_eq!(moves(&c), expected(false));
    let dia: Vec<f64> = threads(&c).iter().map(|t| t.0).collect();
    assert_eq!(dia, [41.508, 41.016, 40.524, 40.032, 39.54, 39.54, 39.54]);
}

/// An inside thread (VARI 4) goes deeper towards +X; the start point is 1 mm
/// inside the bore; with an allowance there is a finishing pass before the idle one.
#[test]
fn cycle97_inside_with_allowance_and_radial_infeed() {
    let cfg = machine();
    let a = c97([2.0, 0.0, 0.0, -20.0, 30.0, 30.0, 5.0, 2.0, 1.2, 0.1, 0.0, 0.0], 3, 1, 4, 1, 0.5);
    let c = call("CYCLE97", &a, &at(&cfg, 20.0, 50.0), &cfg).unwrap();
    let rough = 1.1;
    let mut depths: Vec<f64> = (1..=3).map(|k| rough * libm::sqrt(k as f64 / 3.0)).collect();
    depths.extend([1.2, 1.2]);
    let mut want = vec![('r', 28.0, 5.0)];
    for d in depths {
        let x = r3(30.0 + 2.0 * d);
        want.extend([('r', x, 5.0), ('t', x, -22.0), ('r', 29.0, -22.0), ('r', 29.0, 5.0)]);
    }
    assert_eq!(moves(&c), want);
}

/// IANG < 0: the passes alternate between the flanks; the last passes are central.
#[test]
fn cycle97_alternating_flanks() {
    let cfg = machine();
    let a = c97([2.0, 0.0, 0.0, -20.0, 30.0, 30.0, 4.0, 2.0, 1.2, 0.0, -30.0, 0.0], 4, 1, 1, 1, 0.0);
    let c = call("CYCLE97", &a, &at(&cfg, 40.0, 20.0), &cfg).unwrap();
    let starts: Vec<f64> = moves(&c).iter().filter(|m| m.0 == 'r' && m.1 < 30.0).map(|m| m.2).collect();
    let tan = libm::tan(30f64.to_radians());
    let want: Vec<f64> = [(0.3, -1.0), (0.6, 1.0), (0.9, -1.0), (1.2, 1.0), (1.2, -1.0)]
        .iter()
        .map(|&(d, side)| r3(4.0 + side * (1.2 - d) * tan))
        .collect();
    assert_eq!(starts, want);
}

/// NUMT 2 with NSP 45: the whole sequence for the first start at 45°, then for the
/// second at 225°.
#[test]
fn cycle97_two_starts() {
    let cfg = machine();
    let a = c97([3.0, 0.0, 0.0, -20.0, 30.0, 30.0, 4.0, 2.0, 1.0, 0.0, 0.0, 45.0], 2, 0, 1, 2, 0.0);
    let c = call("CYCLE97", &a, &at(&cfg, 40.0, 20.0), &cfg).unwrap();
    let angles: Vec<f64> = threads(&c).iter().map(|t| t.3).collect();
    assert_eq!(angles, [45.0, 45.0, 225.0, 225.0]);
    let dia: Vec<f64> = threads(&c).iter().map(|t| t.0).collect();
    assert_eq!(dia, [29.0, 28.0, 29.0, 28.0]);
}

/// A taper steeper than 45° is a face thread: the long axis is X, the passes go
/// deeper along -Z (outside: infeed in the negative direction).
#[test]
fn cycle97_face_thread() {
    let cfg = machine();
    let a = c97([2.0, 0.0, 0.0, -2.0, 20.0, 60.0, 3.0, 3.0, 1.0, 0.0, 0.0, 0.0], 1, 0, 1, 1, 0.0);
    let c = call("CYCLE97", &a, &at(&cfg, 80.0, 20.0), &cfg).unwrap();
    // Run-in 3 mm of X radius before X20 (diameter 14, Z +0.3), run-out to X 66.
    let t = threads(&c);
    assert_eq!(t.len(), 1);
    assert_eq!((t[0].0, t[0].1), (66.0, -3.3));
    let m = moves(&c);
    // Start point 1 mm in front of the run-in start (Z +1.3), the pass 1 mm deeper.
    assert_eq!(m[0], ('r', 14.0, 1.3));
    assert_eq!(m[1], ('r', 14.0, -0.7));
    // Retract 1 mm (_VRT) in front of the thread's highest point (the run-in's
    // Z0.3), back to the start's X.
    assert_eq!(m[3..5], [('r', 66.0, 1.3), ('r', 14.0, 1.3)]);
}

/// CYCLE98's example (lines 11414–11437): the chain Z0/Ø30 → Z-30/Ø30 → Z-60/Ø36 →
/// Z-80/Ø50 with pitches 1.5, 2, 2; APP 10, ROP 10, TDEP 0.92, 5 rough passes of
/// constant cross-section (VARI 3), 1 idle pass. Every pass: the first segment waits
/// for the index, the others continue at their own pitch.
#[test]
fn cycle98_example_pitches_per_segment() {
    let cfg = machine();
    let a = reals(&[
        Some(0.0),
        Some(30.0),
        Some(-30.0),
        Some(30.0),
        Some(-60.0),
        Some(36.0),
        Some(-80.0),
        Some(50.0),
        Some(10.0),
        Some(10.0),
        Some(0.92),
        None,
        None,
        None,
    ]);
    let mut a = a;
    a.extend([Arg::Int(5), Arg::Int(1), Arg::Real(1.5), Arg::Real(2.0), Arg::Real(2.0), Arg::Int(3), Arg::Int(1)]);
    let c = call("CYCLE98", &a, &at(&cfg, 40.0, 10.0), &cfg).unwrap();
    let t = threads(&c);
    assert_eq!(t.len(), 6 * 3);
    for (k, pass) in t.chunks(3).enumerate() {
        let d = if k < 5 { 0.92 * libm::sqrt((k + 1) as f64 / 5.0) } else { 0.92 };
        // Run-out 10 mm on along the last segment (7 mm of radius per 20 mm): Z-90, Ø57.
        let want = [(30.0, -30.0, 1.5, true), (36.0, -60.0, 2.0, false), (57.0, -90.0, 2.0, false)];
        for (got, w) in pass.iter().zip(want) {
            assert_eq!((got.0, got.1, got.2, got.4), (r3(w.0 - 2.0 * d), w.1, w.2, w.3), "pass {k}");
        }
    }
    // Start: 1 mm above Ø30 at Z10 (APP before PO1); retract 1 mm above the largest Ø.
    let m = moves(&c);
    assert_eq!(m[0], ('r', 32.0, 10.0));
    assert_eq!(m[5], ('r', 59.0, -90.0));
    assert_eq!(m[6], ('r', 59.0, 10.0));
}

#[test]
fn thread_alarms_move_nothing() {
    let cfg = machine();
    let st = at(&cfg, 60.0, 100.0);
    // "M42x2": MPIT 42 has the pitch 4.5, PIT 2 contradicts it (line 11142).
    let mut a = example(3);
    a[0] = Arg::Real(2.0);
    assert_eq!(call("CYCLE97", &a, &st, &cfg).unwrap_err(), AlarmKind::SiemensCycle(CycleAlarm::ThreadPitchWrong));
    assert_eq!(AlarmKind::SiemensCycle(CycleAlarm::ThreadPitchWrong).code(), 61001);
    // No pitch at all, and a size outside M3–M60.
    let mut a = example(3);
    a[1] = Arg::Empty;
    assert_eq!(call("CYCLE97", &a, &st, &cfg).unwrap_err(), AlarmKind::SiemensCycle(CycleAlarm::ThreadPitchWrong));
    a[1] = Arg::Real(64.0);
    assert_eq!(call("CYCLE97", &a, &st, &cfg).unwrap_err(), AlarmKind::SiemensCycle(CycleAlarm::ThreadPitchWrong));
    // VARI outside 1–4: 61002 (the section's 61102 is the table's "no spindle direction").
    for vari in [0, 5] {
        assert_eq!(
            call("CYCLE97", &example(vari), &st, &cfg).unwrap_err(),
            AlarmKind::SiemensCycle(CycleAlarm::MachiningTypeWrong)
        );
    }
    assert_eq!(AlarmKind::SiemensCycle(CycleAlarm::MachiningTypeWrong).code(), 61002);
    let mut a = reals(&[Some(0.0), Some(30.0), Some(-30.0), Some(30.0), Some(-60.0), Some(36.0), Some(-80.0)]);
    a.extend(reals(&[Some(50.0), Some(10.0), Some(10.0), Some(0.92), None, None, None]));
    a.extend([Arg::Int(5), Arg::Int(1), Arg::Real(1.5), Arg::Real(2.0), Arg::Real(2.0), Arg::Int(7)]);
    assert_eq!(call("CYCLE98", &a, &st, &cfg).unwrap_err(), AlarmKind::SiemensCycle(CycleAlarm::MachiningTypeWrong));
    // Outside the ZX plane.
    let mut g17 = st;
    g17.modal.plane = interp_core::canon::Plane::Xy;
    assert_eq!(call("CYCLE97", &example(3), &g17, &cfg).unwrap_err(), AlarmKind::CycleNotInZxPlane);
}

/// Thread re-cutting (4.9): synchronised at Z-10.5 at 90° after the index, the
/// thread that starts its passes at Z10 (20.5 mm = 4.555… turns of 4.5 mm before)
/// starts at 90° − 0.555…·360° = −110° = 250°. A point off the thread: 61612.
#[test]
fn cycle97_recut_start_angle() {
    let cfg = machine();
    let mut st = at(&cfg, 60.0, 100.0);
    let mut a = example(3);
    a[10] = Arg::Real(0.0);
    st.cycle.recut = Some(interp_core::modal::ThreadRecut { z: mm(-10.5), angle_udeg: 90_000_000 });
    let c = call("CYCLE97", &a, &st, &cfg).unwrap();
    let frac = 20.5 / 4.5 - libm::floor(20.5 / 4.5);
    let want = r3((90.0 - frac * 360.0).rem_euclid(360.0));
    assert!(threads(&c).iter().all(|t| r3(t.3) == want), "{:?}", threads(&c)[0]);
    st.cycle.recut = Some(interp_core::modal::ThreadRecut { z: mm(-50.0), angle_udeg: 0 });
    assert_eq!(call("CYCLE97", &a, &st, &cfg).unwrap_err(), AlarmKind::SiemensCycle(CycleAlarm::RecutImpossible));
    assert_eq!(AlarmKind::SiemensCycle(CycleAlarm::RecutImpossible).code(), 61612);
}

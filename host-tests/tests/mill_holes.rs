//! A machining centre's hole cycles G73–G89 with G98/G99 (seed 004 @6390–@10300):
//! the six actions of a hole, the initial level remembered across the G99 holes
//! of one cycle mode, R and Z under G90 and G91, K repeats, which blocks drill,
//! G00–G03 cancelling the mode and its data, tapping (floating and M29 rigid),
//! the boring cycles, and the alarms. Levels are work Z in mm.

mod mill_common;

use host_tests::{Run, kind_names};
use interp_core::canon::{Action, Canon, SpindleDir};
use mill_common::{alarms, go};

/// Moves as (kind, X, Y, Z) mm work, kind r rapid, l linear, p tap.
fn moves(r: &Run) -> Vec<(char, f64, f64, f64)> {
    r.actions
        .iter()
        .filter_map(|c: &Canon| {
            let k = match c.action {
                Action::Rapid(_) => 'r',
                Action::Linear(_) => 'l',
                Action::Tap(_) => 'p',
                Action::Arc(_) => 'a',
                _ => return None,
            };
            let e = c.action.endpoint()?;
            Some((k, e.work.0[0] as f64 / 1e6, e.work.0[1] as f64 / 1e6, e.work.0[2] as f64 / 1e6))
        })
        .collect()
}

const START: &str = "G00 X0 Y0 Z50.\nM03 S1000\n";

/// G81 (@7893): position in XY, rapid to R, feed to Z, rapid out — to the initial
/// level under G98, to R under G99. The seed's rule @7537: G99 between the holes,
/// G98 on the last brings the tool back to the initial level (Z50), which the mode
/// remembered.
#[test]
fn g98_g99_levels_and_the_remembered_initial_level() {
    let r = go(&format!("{START}G99 G81 X10. Y10. Z-5. R2. F100\nX20.\nG98 X30.\nG80\nM30\n"));
    assert_eq!(
        moves(&r)[1..],
        [
            ('r', 10.0, 10.0, 50.0),
            ('r', 10.0, 10.0, 2.0),
            ('l', 10.0, 10.0, -5.0),
            ('r', 10.0, 10.0, 2.0),
            ('r', 20.0, 10.0, 2.0),
            ('l', 20.0, 10.0, -5.0),
            ('r', 20.0, 10.0, 2.0),
            ('r', 30.0, 10.0, 2.0),
            ('l', 30.0, 10.0, -5.0),
            ('r', 30.0, 10.0, 2.0),
            ('r', 30.0, 10.0, 50.0),
        ]
    );
}

/// Under G91 R is measured from the initial level and Z from R (FANUC): from Z50,
/// R-48 is Z2 and Z-7 is Z-5. K3 with G91 X10 Y5 drills three holes, each X10 Y5
/// from the last.
#[test]
fn g91_r_and_z_and_k_repeats() {
    let r = go(&format!("{START}G91 G99 G81 X10. Y5. Z-7. R-48. K3 F100\nG90 G80\nM30\n"));
    let m = moves(&r);
    let holes: Vec<(f64, f64)> = m.iter().filter(|v| v.0 == 'l').map(|v| (v.1, v.2)).collect();
    assert_eq!(holes, vec![(10.0, 5.0), (20.0, 10.0), (30.0, 15.0)]);
    assert!(m.iter().filter(|v| v.0 == 'l').all(|v| v.3 == -5.0));
    assert!(m[2..].iter().filter(|v| v.0 == 'r').all(|v| v.3 == 2.0), "G99: everything after on R: {m:?}");
}

/// @10120: a block in the mode drills only with X, Y, Z or R; K0 stores the data
/// only; @10250: G00–G03 cancel the mode and its data (a new G81 needs Z and R
/// again); G80 too.
#[test]
fn which_blocks_drill_and_what_cancels() {
    let r = go(&format!("{START}G81 Z-5. R2. F100\nX10.\nF200\nM08\nX20. K0\nX30.\nG00 X0\nM30\n"));
    let feeds: Vec<f64> = moves(&r).iter().filter(|v| v.0 == 'l').map(|v| v.1).collect();
    assert_eq!(feeds, vec![0.0, 10.0, 30.0], "the G81 block itself (Z, R), X10, X30; not F, M, K0");
    assert_eq!(alarms(&format!("{START}G81 X1. Z-5. R2. F100\nG00 X5.\nG81 X10.\nM30\n")), vec![(5, 4006)]);
    assert_eq!(alarms(&format!("{START}G81 X1. Z-5. R2. F100\nG80\nG81 X10.\nM30\n")), vec![(5, 4006)]);
    // A cycle block without R (the alarm) and without Z.
    assert_eq!(alarms(&format!("{START}G81 X10. Z-5. F100\nM30\n")), vec![(3, 4006)]);
    assert_eq!(alarms(&format!("{START}G81 X10. R2. F100\nM30\n")), vec![(3, 4006)]);
    // G28 in the mode (FANUC 0i-M PS0044).
    assert_eq!(alarms(&format!("{START}G81 X10. Z-5. R2. F100\nG28 Z0\nM30\n")), vec![(4, 44)]);
}

/// G82 dwells at the bottom, G81 not; G89 bores with a dwell and feeds out, G85
/// without one.
#[test]
fn dwell_cycles_and_boring_with_feed_out() {
    let r = go(&format!("{START}G82 X10. Z-5. R2. P500 F100\nG81 X20.\nG89 X30.\nG85 X40.\nG80\nM30\n"));
    let k = kind_names(&r);
    assert_eq!(k.iter().filter(|n| *n == "dwell 500").count(), 2, "G82 and G89 dwell: {k:?}");
    let m = moves(&r);
    let out_of_30: Vec<_> = m.iter().filter(|v| v.1 == 30.0).collect();
    assert_eq!(out_of_30[2..4], [&('l', 30.0, 0.0, -5.0), &('l', 30.0, 0.0, 2.0)], "G89 feeds out");
}

/// G73: pecks of Q, back by d (parameter 5113 = 1 mm here) between them; G83:
/// back to R after each peck, then rapid to d above the depth reached.
#[test]
fn peck_drilling_g73_and_g83() {
    let r = go(&format!("{START}G73 X10. Z-10. R2. Q5. F100\nG80\nM30\n"));
    let z: Vec<(char, f64)> = moves(&r)[2..].iter().map(|v| (v.0, v.3)).collect();
    assert_eq!(
        z,
        vec![('r', 2.0), ('l', -3.0), ('r', -2.0), ('l', -8.0), ('r', -7.0), ('l', -10.0), ('r', 2.0), ('r', 50.0)]
    );
    let r = go(&format!("{START}G83 X10. Z-10. R2. Q5. F100\nG80\nM30\n"));
    let z: Vec<(char, f64)> = moves(&r)[2..].iter().map(|v| (v.0, v.3)).collect();
    assert_eq!(
        z,
        vec![
            ('r', 2.0),
            ('l', -3.0),
            ('r', 2.0),
            ('r', -2.0),
            ('l', -8.0),
            ('r', 2.0),
            ('r', -7.0),
            ('l', -10.0),
            ('r', 2.0),
            ('r', 50.0)
        ]
    );
    assert_eq!(alarms(&format!("{START}G83 X10. Z-10. R2. F100\nM30\n")), vec![(3, 45)]);
    assert_eq!(alarms(&format!("{START}G73 X10. Z-10. R2. Q0 F100\nM30\n")), vec![(3, 45)]);
}

/// Spindle commands of a run, in order.
fn spindle(r: &Run) -> Vec<SpindleDir> {
    r.actions
        .iter()
        .filter_map(|c| match c.action {
            Action::Spindle(s) => Some(s.dir),
            _ => None,
        })
        .collect()
}

/// G84 (@8119): forward into the hole, reverse at the bottom, feed out to R, forward
/// again; G74 the other way round; the feed follows the spindle (F/S per rev).
#[test]
fn floating_tapping_g84_and_g74() {
    let r = go("G00 X0 Y0 Z50.\nM03 S500\nG84 X10. Z-10. R5. F750\nG80\nM04\nG74 X20.  Z-10. R5. F750\nG80\nM30\n");
    assert_eq!(
        spindle(&r),
        vec![SpindleDir::Cw, SpindleDir::Ccw, SpindleDir::Cw, SpindleDir::Ccw, SpindleDir::Cw, SpindleDir::Ccw]
    );
    let feeds: Vec<i64> = r
        .actions
        .iter()
        .filter_map(|c| match c.action {
            Action::Linear(m) => Some(m.feed.value),
            _ => None,
        })
        .collect();
    assert_eq!(feeds, vec![1_500_000; 4], "F750 / S500 = 1.5 mm per rev");
}

/// Rigid tapping (@8320): M29 stops the spindle; G84 taps locked to the spindle at
/// the S in force, lead F/S; a dwell P at the bottom and at R; the spindle stays
/// stopped between holes; G80 ends rigid mode.
#[test]
fn rigid_tapping_with_m29() {
    let r = go("G00 X0 Y0 Z50.\nM03 S600\nM29\nG84 X10. Y0 Z-12. R3. P200 F900\nX20.\nG80\nM30\n");
    let taps: Vec<(i64, SpindleDir, f64)> = r
        .actions
        .iter()
        .filter_map(|c| match c.action {
            Action::Tap(t) => Some((t.lead, t.dir, t.to.work.0[2] as f64 / 1e6)),
            _ => None,
        })
        .collect();
    assert_eq!(
        taps,
        vec![
            (1_500_000, SpindleDir::Cw, -12.0),
            (1_500_000, SpindleDir::Ccw, 3.0),
            (1_500_000, SpindleDir::Cw, -12.0),
            (1_500_000, SpindleDir::Ccw, 3.0)
        ]
    );
    assert_eq!(kind_names(&r).iter().filter(|n| *n == "dwell 200").count(), 4);
    assert_eq!(spindle(&r)[..2], [SpindleDir::Cw, SpindleDir::Stop], "M03, then M29 stops it");
    assert_eq!(r.interp.state().cycle.rigid, interp_core::modal::RigidTap::Off);
    assert_eq!(alarms("G00 X0 Y0 Z50.\nM29\nM30\n"), vec![(2, 200)], "no S at all");
}

/// G86 (@8976): spindle stop at the bottom, rapid out, spindle on again. G88
/// (@9577): dwell, spindle stop, a stop for the operator, rapid out, spindle on.
#[test]
fn g86_and_g88() {
    let r = go(&format!("{START}G86 X10. Z-5. R2. F100\nG80\nM30\n"));
    let k = kind_names(&r);
    let i = k.iter().position(|n| n == "spindle Stop None").unwrap();
    assert!(k[i + 1].starts_with("rapid") && k[i + 2].starts_with("spindle Cw"), "{k:?}");
    let r = go(&format!("{START}G88 X10. Z-5. R2. P300 F100\nG80\nM30\n"));
    let k = kind_names(&r);
    let i = k.iter().position(|n| n == "dwell 300").unwrap();
    assert_eq!(k[i + 1..i + 4], ["spindle Stop None", "stop false", "rapid"]);
}

/// G76 fine boring: at the bottom an oriented stop (M19) and a shift of Q away from
/// the wall (parameter 5149 = 2: −X here), out shifted, back, spindle on. G87 back
/// boring (@9225): shifted down to R below the part, cut upwards to Z, always back
/// to the initial level.
#[test]
fn g76_fine_boring_and_g87_back_boring() {
    let r = go(&format!("{START}G76 X10. Z-5. R2. Q0.5 F100\nG80\nM30\n"));
    assert_eq!(
        moves(&r)[3..],
        [('l', 10.0, 0.0, -5.0), ('r', 9.5, 0.0, -5.0), ('r', 9.5, 0.0, 50.0), ('r', 10.0, 0.0, 50.0)]
    );
    assert!(kind_names(&r).contains(&"M19".to_string()));
    let r = go(&format!("{START}G99 G87 X10. Z-5. R-20. Q0.5 F100\nG80\nM30\n"));
    assert_eq!(
        moves(&r)[1..],
        [
            ('r', 10.0, 0.0, 50.0),
            ('r', 9.5, 0.0, 50.0),
            ('r', 9.5, 0.0, -20.0),
            ('r', 10.0, 0.0, -20.0),
            ('l', 10.0, 0.0, -5.0),
            ('r', 9.5, 0.0, -5.0),
            ('r', 9.5, 0.0, 50.0),
            ('r', 10.0, 0.0, 50.0)
        ]
    );
}

/// Under scaling the hole positions and levels scale, Q does not (FANUC).
#[test]
fn holes_under_scaling() {
    let r = go(&format!("{START}G51 X0 Y0 Z0 P2000\nG81 X10. Y5. Z-5. R2. F100\nG80\nG50\nM30\n"));
    assert_eq!(moves(&r)[1..4], [('r', 20.0, 10.0, 50.0), ('r', 20.0, 10.0, 4.0), ('l', 20.0, 10.0, -10.0)]);
}

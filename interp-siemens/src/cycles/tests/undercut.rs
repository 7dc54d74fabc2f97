//! CYCLE94 and CYCLE96 against DIN 509 / DIN 76 and the document's examples.

use super::*;
use interp_core::alarm::CycleAlarm;

/// The state of the examples: tool offset 3 with cutting edge position `tip`.
fn with_tool(cfg: &mut MachineConfig, tip: u8, radius: f64, x: f64, z: f64) -> State {
    *cfg.tools.get_mut(3).unwrap() = interp_core::config::ToolOffset { tip, radius: mm(radius), ..Default::default() };
    let mut st = at(cfg, x, z);
    st.tool.offset_number = 3;
    st.tool.tip = tip;
    st.tool.nose_radius = mm(radius);
    st.feed.per_rev = mm(0.3);
    st
}

fn args(d: f64, spl: f64, form: &'static [u8], vari: i64) -> Vec<Arg<'static>> {
    vec![Arg::Real(d), Arg::Real(spl), Arg::Str(form), Arg::Int(vari)]
}

/// The document's example (lines 10558–10594): CYCLE94 (20, 60, "E") from X50 Z100
/// with edge position 3 (a nose radius of 0 here so the tip runs on the contour):
/// DIN 509 E for Ø20 (over 18 to 80 mm) is R0.6 × 0.3, f 2.5, flank 15°.
#[test]
fn cycle94_form_e_example() {
    let mut cfg = machine();
    let st = with_tool(&mut cfg, 3, 0.0, 50.0, 100.0);
    let c = call("CYCLE94", &args(20.0, 60.0, b"E", 0), &st, &cfg).unwrap();
    let run = 0.3 / libm::tan(15f64.to_radians());
    assert_eq!(
        moves(&c),
        [
            ('r', 24.0, 70.0),
            ('l', 24.0, 70.0),
            ('l', 20.0, 62.5),
            ('l', 19.4, r3(62.5 - run)),
            ('l', 19.4, 60.6),
            ('a', 20.6, 60.0),
            ('r', 24.0, 70.0),
        ]
        .into_iter()
        .filter(|m| *m != ('l', 24.0, 70.0))
        .collect::<Vec<_>>()
    );
    // At the feed in force (F0.3).
    assert!(c.actions.iter().all(|a| match a.action {
        interp_core::canon::Action::Linear(m) => m.feed.value == mm(0.3),
        _ => true,
    }));
}

/// Form F relieves the face by t2 = 0.2 and returns to it at 8°.
#[test]
fn cycle94_form_f() {
    let mut cfg = machine();
    let st = with_tool(&mut cfg, 3, 0.0, 50.0, 100.0);
    let c = call("CYCLE94", &args(20.0, 60.0, b"F", 0), &st, &cfg).unwrap();
    let m = moves(&c);
    assert_eq!(
        m[3..6],
        [('l', 19.4, 60.4), ('a', 20.6, 59.8), ('l', r3(20.6 + 2.0 * 0.2 / libm::tan(8f64.to_radians())), 60.0)]
    );
}

/// _VARI 4 (or edge position 4): the diameter runs towards -Z from the face; the
/// small diameters take DIN 509's R0.4 × 0.2.
#[test]
fn cycle94_position_4_small_diameter() {
    let mut cfg = machine();
    let st = with_tool(&mut cfg, 3, 0.0, 50.0, 0.0);
    let c = call("CYCLE94", &args(8.0, 20.0, b"E", 4), &st, &cfg).unwrap();
    let run = 0.2 / libm::tan(15f64.to_radians());
    let m = moves(&c);
    assert_eq!(m[0], ('r', 12.0, 10.0));
    assert_eq!(m[1..5], [('l', 8.0, 18.0), ('l', 7.6, r3(18.0 + run)), ('l', 7.6, 19.6), ('a', 8.4, 20.0)]);
}

/// The document's example (lines 11049–11061): CYCLE96 (10, 60, "A"): M10 has the
/// pitch 1.5; DIN 76-1 form A: d_g = 10 − 2.3, g2 5.2, r 0.8, flank 30°.
#[test]
fn cycle96_form_a_example() {
    let mut cfg = machine();
    let st = with_tool(&mut cfg, 3, 0.0, 50.0, 100.0);
    let c = call("CYCLE96", &args(10.0, 60.0, b"A", 0), &st, &cfg).unwrap();
    let run = (10.0 - 7.7) / 2.0 / libm::tan(30f64.to_radians());
    assert_eq!(
        moves(&c),
        [
            ('r', 14.0, 70.0),
            ('l', 10.0, 65.2),
            ('l', 7.7, r3(65.2 - run)),
            ('l', 7.7, 60.8),
            ('a', 9.3, 60.0),
            ('r', 14.0, 70.0),
        ]
    );
}

/// An inside thread undercut (form C, M20: pitch 2.5, d_g = 20.5, g2 13, r 1.2),
/// position 2 (inside, the bore running towards +Z from the face).
#[test]
fn cycle96_form_c_inside() {
    let mut cfg = machine();
    let st = with_tool(&mut cfg, 2, 0.0, 10.0, 100.0);
    let c = call("CYCLE96", &args(20.0, 0.0, b"C", 0), &st, &cfg).unwrap();
    let run = 0.25 / libm::tan(30f64.to_radians());
    let m = moves(&c);
    assert_eq!(m[0], ('r', 16.0, 14.0));
    assert_eq!(m[1..5], [('l', 20.0, 13.0), ('l', 20.5, r3(13.0 - run)), ('l', 20.5, 1.2), ('a', 18.1, 0.0)]);
}

/// With a nose radius the path is compensated: the tip of edge position 3 runs on
/// the cylinder's start point as programmed (tip vector −r, −r from the centre).
#[test]
fn cycle94_nose_radius() {
    let mut cfg = machine();
    let st = with_tool(&mut cfg, 3, 0.4, 50.0, 100.0);
    let c = call("CYCLE94", &args(20.0, 60.0, b"E", 0), &st, &cfg).unwrap();
    let m = moves(&c);
    // The bottom (X19.4 on the diameter) keeps the tip on it.
    assert!(m.iter().any(|&(k, x, _)| k == 'l' && x == 19.4), "{m:?}");
    // The arc of the bottom radius shrinks by the nose: its end on the face, the
    // nose centre 0.4 off it and the tip 0.4 behind the centre.
    assert!(m.iter().any(|&(k, _, z)| k == 'a' && z == 60.0), "{m:?}");
}

/// A clearance angle of 10° (below the 15° flank) flattens the flank.
#[test]
fn cycle94_flank_flattened_by_the_clearance_angle() {
    let mut cfg = machine();
    let st = with_tool(&mut cfg, 3, 0.0, 50.0, 100.0);
    cfg.tools.get_mut(3).unwrap().clearance_udeg = 10_000_000;
    let c = call("CYCLE94", &args(20.0, 60.0, b"E", 0), &st, &cfg).unwrap();
    let (run15, run10) = (0.3 / libm::tan(15f64.to_radians()), 0.3 / libm::tan(10f64.to_radians()));
    let m = moves(&c);
    let start = 62.5 + run10 - run15;
    assert_eq!(m[1..3], [('l', 20.0, r3(start)), ('l', 19.4, r3(start - run10))]);
}

#[test]
fn undercut_alarms_move_nothing() {
    let mut cfg = machine();
    let st = with_tool(&mut cfg, 3, 0.0, 50.0, 100.0);
    let err = |name: &str, a: &[Arg<'_>], st: &State| call(name, a, st, &cfg).unwrap_err();
    // No D offset: 61000.
    let mut no_d = st;
    no_d.tool.offset_number = 0;
    assert_eq!(err("CYCLE94", &args(20.0, 60.0, b"E", 0), &no_d), AlarmKind::SiemensCycle(CycleAlarm::NoToolOffset));
    assert_eq!(err("CYCLE96", &args(10.0, 60.0, b"A", 0), &no_d), AlarmKind::SiemensCycle(CycleAlarm::NoToolOffset));
    assert_eq!(AlarmKind::SiemensCycle(CycleAlarm::NoToolOffset).code(), 61000);
    // Finished diameter under 3 mm: 61601 (M4 form A: 4 − 1.1 = 2.9).
    assert_eq!(
        err("CYCLE94", &args(2.8, 60.0, b"E", 0), &st),
        AlarmKind::SiemensCycle(CycleAlarm::FinishedDiameterTooSmall)
    );
    assert_eq!(
        err("CYCLE96", &args(4.0, 60.0, b"A", 0), &st),
        AlarmKind::SiemensCycle(CycleAlarm::FinishedDiameterTooSmall)
    );
    assert_eq!(AlarmKind::SiemensCycle(CycleAlarm::FinishedDiameterTooSmall).code(), 61601);
    // Not a form of the standard: 61609.
    assert_eq!(err("CYCLE94", &args(20.0, 60.0, b"G", 0), &st), AlarmKind::SiemensCycle(CycleAlarm::FormWrong));
    assert_eq!(err("CYCLE96", &args(10.0, 60.0, b"E", 0), &st), AlarmKind::SiemensCycle(CycleAlarm::FormWrong));
    assert_eq!(AlarmKind::SiemensCycle(CycleAlarm::FormWrong).code(), 61609);
    // Not an ISO coarse size (M13): 61001.
    assert_eq!(err("CYCLE96", &args(13.0, 60.0, b"A", 0), &st), AlarmKind::SiemensCycle(CycleAlarm::ThreadPitchWrong));
    // Cutting edge position 5 with _VARI 0: 61608; _VARI 7: 61613.
    let mut sl5 = st;
    sl5.tool.tip = 5;
    assert_eq!(
        err("CYCLE94", &args(20.0, 60.0, b"E", 0), &sl5),
        AlarmKind::SiemensCycle(CycleAlarm::WrongEdgePosition)
    );
    assert_eq!(AlarmKind::SiemensCycle(CycleAlarm::WrongEdgePosition).code(), 61608);
    assert_eq!(
        err("CYCLE94", &args(20.0, 60.0, b"E", 7), &st),
        AlarmKind::SiemensCycle(CycleAlarm::UndercutPositionWrong)
    );
    assert_eq!(AlarmKind::SiemensCycle(CycleAlarm::UndercutPositionWrong).code(), 61613);
    // An outside thread undercut with an inside position.
    assert_eq!(
        err("CYCLE96", &args(10.0, 60.0, b"A", 1), &st),
        AlarmKind::SiemensCycle(CycleAlarm::UndercutPositionWrong)
    );
}

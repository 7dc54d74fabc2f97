//! CYCLE93 against the document's example (lines 10377–10451) and its alarms.

use super::*;
use interp_core::alarm::CycleAlarm;
use interp_core::canon::Action;

/// A grooving tool 4 mm wide, T1: edge D1 the left corner (position 3, row 1), D2
/// the right one (position 4, row 1 + tool count) 4 mm towards -Z in its offset
/// (+Z on the part), nose `r`.
fn grooving_tool(cfg: &mut MachineConfig, r: f64) -> State {
    *cfg.tools.get_mut(1).unwrap() = interp_core::config::ToolOffset { tip: 3, radius: mm(r), ..Default::default() };
    *cfg.tools.get_mut(d2(cfg)).unwrap() =
        interp_core::config::ToolOffset { z: mm(-4.0), tip: 4, radius: mm(r), ..Default::default() };
    let mut st = at(cfg, 50.0, 65.0);
    st.tool.offset_number = 1;
    st.tool.tip = 3;
    st.tool.nose_radius = mm(r);
    st
}

/// T1 D2's offset row.
fn d2(cfg: &MachineConfig) -> u16 {
    1 + cfg.tool_count
}

/// The example: SPD 35, SPL 60, WIDG 30, DIAG 25, STA1 5, ANG1 10, ANG2 20, RCO 0,
/// RCI -2 (chamfers), FAL 1, IDEP 10, DTB 1, VARI 5.
fn example(vari: i64) -> Vec<Arg<'static>> {
    let mut a: Vec<Arg<'static>> =
        [35.0, 60.0, 30.0, 25.0, 5.0, 10.0, 20.0, 0.0, 0.0, -2.0, -2.0, 1.0, 1.0, 10.0, 1.0].map(Arg::Real).to_vec();
    a.push(Arg::Int(vari));
    a
}

/// Points on the example's groove: its frame turned 5° (the surface falls towards
/// -Z), depth 12.5 of radius (DIAG 25 on the diameter), returned as (X diameter, Z).
fn groove_point(p: f64, q: f64) -> (f64, f64) {
    let s = 5f64.to_radians();
    let (pz, px) = (-libm::cos(s), -libm::sin(s));
    let (qz, qx) = (libm::sin(s), -libm::cos(s));
    (2.0 * (17.5 + p * px + q * qx), 60.0 + p * pz + q * qz)
}

/// The example's plunges: across the rough bottom, from foot to foot of the
/// flanks (1 mm in, 1 mm up: 11.5 deep), 21.625 mm along Z; a 4 mm tool moving at
/// most 95 % of (4 − 0.2) = 3.61 between plunges needs 6 of them; each pecks IDEP
/// (5 mm of radius) with 1 mm chip-breaking retracts, dwells 1 s at the bottom and
/// never goes under the contour less its allowance.
#[test]
fn cycle93_example_plunges() {
    let mut cfg = machine();
    let st = grooving_tool(&mut cfg, 0.2);
    let c = call("CYCLE93", &example(5), &st, &cfg).unwrap();
    // Plunges: the dwells at their bottoms.
    let dwells = c.actions.iter().filter(|a| matches!(a.action, Action::Dwell { ms: 1000 })).count();
    let (t10, t20) = (libm::tan(10f64.to_radians()), libm::tan(20f64.to_radians()));
    let e1 = 1.0 / libm::cos(10f64.to_radians());
    let e2 = 1.0 / libm::cos(20f64.to_radians());
    let foot1 = groove_point(e1 + 11.5 * t10, 11.5);
    let foot2 = groove_point(30.0 - e2 - 11.5 * t20, 11.5);
    let across = foot1.1 - foot2.1;
    let plunges = 1 + libm::ceil((across - 4.0) / (0.95 * 3.8)) as usize;
    assert_eq!(plunges, 6);
    assert_eq!(dwells, plunges);
    // The first plunge: edge D (the left corner) 4 mm left of the start side's foot.
    let m = moves(&c);
    assert_eq!(m[..2], [('r', 50.0, r3(foot1.1 - 4.0)), ('r', m[1].1, r3(foot1.1 - 4.0))]);
    // The bottom with its allowance: 11.5 deep; no plunge goes deeper there.
    let (x0, z0) = groove_point(12.5 * libm::tan(10f64.to_radians()), 11.5);
    let (x1, z1) = groove_point(30.0 - 12.5 * libm::tan(20f64.to_radians()), 11.5);
    let bottom_x = |z: f64| x0 + (x1 - x0) * (z - z0) / (z1 - z0);
    for w in m.windows(2) {
        if w[1].0 == 'l' && w[0].2 == w[1].2 {
            let (x, z) = (w[1].1, w[1].2);
            if (z1..=z0).contains(&z) {
                assert!(x >= bottom_x(z) - 0.003 || x >= bottom_x(z + 4.0) - 0.003, "{w:?} below {}", bottom_x(z));
            }
        }
    }
    // Pecks of 5 mm (radius): the first plunge feeds from above the surface to
    // 5 mm deeper, retracts 1 mm, feeds on.
    let first_feed = m.iter().position(|x| x.0 == 'l').unwrap();
    assert_eq!(r3(m[first_feed - 1].1 - m[first_feed].1), 10.0);
    assert_eq!(m[first_feed + 1], ('r', r3(m[first_feed].1 + 2.0), m[first_feed].2));
}

/// The finishing passes run through the finished contour's points: the start side
/// (the right one, at Z60) with its right corner, edge D + 1 (so edge D's positions
/// are 4 mm to -Z), from the surface over edge 1 (Z60 Ø35) down its flank, the
/// chamfer CHF 2 at its foot (legs 1/cos 40°: the corner turns by 80°), the bottom
/// to its middle; the far side with edge D, the same from edge 2.
#[test]
fn cycle93_example_finishing() {
    let mut cfg = machine();
    let st = grooving_tool(&mut cfg, 0.0);
    let c = call("CYCLE93", &example(5), &st, &cfg).unwrap();
    let m = moves(&c);
    let near = |p: (f64, f64)| m.iter().any(|&(_, x, z)| (x - p.0).abs() < 0.003 && (z - p.1).abs() < 0.003);
    let d2 = |p: (f64, f64)| (p.0, p.1 - 4.0);
    let t10 = libm::tan(10f64.to_radians());
    let leg = 1.0 / libm::cos(40f64.to_radians());
    let flank = |d: f64| (d * t10, d);
    assert!(near(d2(groove_point(0.0, 0.0))), "edge 1");
    let foot = flank(12.5);
    let up = leg / libm::hypot(t10, 1.0);
    assert!(near(d2(groove_point(foot.0 - up * t10, foot.1 - up))), "chamfer start on the flank");
    assert!(near(d2(groove_point(foot.0 + leg, 12.5))), "chamfer end on the bottom");
    assert!(near(groove_point(30.0, 0.0)), "edge 2 with edge D");
    // The flanks were cut along their slope down to the rough contour: flank 1
    // (10°, 2.03 mm across) in one pass, flank 2 (20°, 4.19 across) in two.
    let slanted = m.windows(2).filter(|w| w[1].0 == 'l' && w[0].0 == 'r' && w[0].2 != w[1].2).count();
    assert_eq!(slanted, 1 + 2);
    // It ends back at its start point.
    assert_eq!(m.last().map(|x| (x.1, x.2)), Some((m[1].1, m[1].2)));
}

#[test]
fn cycle93_alarms_move_nothing() {
    let mut cfg = machine();
    let st = grooving_tool(&mut cfg, 0.2);
    let err = |a: &[Arg<'_>], st: &State, cfg: &MachineConfig| call("CYCLE93", a, st, cfg).unwrap_err();
    for vari in [0, 9, 10, 19, 21] {
        assert_eq!(err(&example(vari), &st, &cfg), AlarmKind::SiemensCycle(CycleAlarm::MachiningTypeWrong), "{vari}");
    }
    let mut no_d = st;
    no_d.tool.offset_number = 0;
    assert_eq!(err(&example(5), &no_d, &cfg), AlarmKind::SiemensCycle(CycleAlarm::NoToolOffset));
    // A groove 3 mm wide for a 4 mm tool; a tool of no width: 61602.
    let mut narrow = example(5);
    narrow[2] = Arg::Real(3.0);
    assert_eq!(err(&narrow, &st, &cfg), AlarmKind::SiemensCycle(CycleAlarm::ToolWidthWrong));
    let mut flat = cfg.clone();
    let row = d2(&flat);
    flat.tools.get_mut(row).unwrap().z = 0;
    assert_eq!(err(&example(5), &st, &flat), AlarmKind::SiemensCycle(CycleAlarm::ToolWidthWrong));
    assert_eq!(AlarmKind::SiemensCycle(CycleAlarm::ToolWidthWrong).code(), 61602);
    // Bottom chamfers longer than the bottom; a face groove on a cylinder: 61603.
    let mut wide = example(5);
    wide[9] = Arg::Real(-20.0);
    assert_eq!(err(&wide, &st, &cfg), AlarmKind::SiemensCycle(CycleAlarm::GrooveFormWrong));
    let mut face = example(6);
    face[4] = Arg::Real(0.0);
    assert_eq!(err(&face, &st, &cfg), AlarmKind::SiemensCycle(CycleAlarm::GrooveFormWrong));
    assert_eq!(AlarmKind::SiemensCycle(CycleAlarm::GrooveFormWrong).code(), 61603);
}

//! The machining-centre profile (seed 004, FANUC 0i-M): the M-series table and
//! its letters, the power-on modes, G00–G03 in the three planes with helical
//! arcs, G04, G28/G29, G10 and G54.1, tool length compensation, T/M06, and the
//! alarms of bad input. Expected values are computed here from the seed's
//! formats, independently of the interpreter's code. Transformations, hole
//! cycles and cutter compensation are in `mill_frames.rs`, `mill_holes.rs` and
//! `mill_comp.rs`.

mod mill_common;

use host_tests::{Run, kind_names, run_with};
use interp_core::canon::{Action, Canon, Plane, ToolChange};
use interp_core::codes::GCode;
use interp_core::config::{MachineKind, ToolChanger};
use interp_core::{Axis, Panel};
use mill_common::{alarms, go, mill};

/// Work end point (X, Y, Z) mm of a motion action.
fn work(c: &Canon) -> Option<[f64; 3]> {
    c.action.endpoint().map(|e| [0, 1, 2].map(|i| e.work.0[i] as f64 / 1e6))
}

/// Machine end point (X, Y, Z) mm of a motion action.
fn machine(c: &Canon) -> Option<[f64; 3]> {
    c.action.endpoint().map(|e| [0, 1, 2].map(|i| e.machine.0[i] as f64 / 1e6))
}

fn path(r: &Run) -> Vec<[f64; 3]> {
    r.actions.iter().filter_map(work).collect()
}

fn machine_path(r: &Run) -> Vec<[f64; 3]> {
    r.actions.iter().filter_map(machine).collect()
}

#[test]
fn the_mill_machine_file_and_power_on_modes() {
    let cfg = mill();
    assert_eq!(cfg.kind, MachineKind::Mill);
    assert!(!cfg.diameter_x, "X is a radius coordinate on a mill");
    assert_eq!(cfg.tool_changer, ToolChanger::Manual);
    assert!(cfg.axis(Axis::Y).present);
    let r = go("M30\n");
    let st = r.interp.state();
    // G17 G90 G94 G21 G40 G49 G80 G50 G69 G15 G98 G54 (seed 004 §5, FANUC 0i-M).
    assert_eq!(st.modal.plane, Plane::Xy);
    assert!(!st.modal.incremental);
    assert_eq!(st.modal.feed_mode, interp_core::canon::FeedMode::PerMin);
    assert_eq!(st.modal.units, interp_core::units::Units::Metric);
    assert_eq!(st.modal.nose_comp, GCode::NoseCompOff);
    assert_eq!(st.mill.length_sign, 0);
    assert_eq!(st.modal.drilling, GCode::DrillCancel);
    assert_eq!(st.mill.frame.active, 0, "G50 G69 G15: no transformation");
    assert!(!st.modal.return_to_r, "G98");
    assert_eq!(st.modal.work_frame, 0, "G54");
}

/// A lathe's codes are not G codes of the M series (0010); the numbers the M
/// series uses for something else mean its own code; U/V/W are no addresses of a
/// mill (0009).
#[test]
fn lathe_codes_and_letters_are_refused() {
    for (text, code) in [
        ("G71 U1 R0.5\n", 10),
        ("G70 P10 Q20\n", 10),
        ("G96 S200\n", 10),
        ("G32 Z-10 F1\n", 10),
        ("G12.1\n", 10),
        ("G51.2 P1 Q2\n", 10),
        ("G02.1 X1 Y1 A1 B1\n", 10),
        ("G00 U10\n", 9),
        ("G01 W-5 F100\n", 9),
    ] {
        assert_eq!(alarms(&format!("G00 X-10 Y-10\n{text}M30\n")), vec![(2, code)], "{text}");
    }
    // G90 is absolute, not the lathe's turning cycle; G92 sets coordinates.
    let r = go("G00 X0\nG91 G00 X-10\nG90 G00 X-5\nG92 X0 Y0\nG00 X5\nM30\n");
    assert_eq!(path(&r).iter().map(|p| p[0]).collect::<Vec<_>>(), vec![0.0, -10.0, -5.0, 5.0]);
    assert_eq!(machine_path(&r)[3][0], -300.0, "G92 X0 made machine X-305 work X0");
}

/// Seed 004 @3103: G90 G00 X70. Y50. and G91 G00 X50. Y40.; @3228 O101's square.
#[test]
fn absolute_incremental_and_the_o101_square() {
    let r = go("G90 G00 X70. Y50.\nG91 G00 X50. Y40.\nM30\n");
    assert_eq!(path(&r), vec![[70.0, 50.0, 250.0], [120.0, 90.0, 250.0]]);
    // G54 is machine X-300 Y-200 Z-250: the reference (machine 0) is work Z250.
    assert_eq!(machine_path(&r), vec![[-230.0, -150.0, 0.0], [-180.0, -110.0, 0.0]]);
    let r = go("O101\nG00 X0 Y0 Z10.\nN60 G90 G01 X10. Y50. F100\nN70 X60.\nN80 Y10.\nN90 X10.\nM30\n");
    let p = path(&r);
    assert_eq!(p[1..], [[10.0, 50.0, 10.0], [60.0, 50.0, 10.0], [60.0, 10.0, 10.0], [10.0, 10.0, 10.0]]);
    assert!(r.actions.iter().skip(1).all(|c| match c.action {
        Action::Linear(m) => m.feed.value == 100_000_000,
        _ => true,
    }));
}

/// The arc centre of a motion action, work mm.
fn centre(c: &Canon) -> Option<[f64; 3]> {
    match c.action {
        Action::Arc(a) => Some([0, 1, 2].map(|i| a.center.work.0[i] as f64 / 1e6)),
        _ => None,
    }
}

/// Seed 004 @3328–@3560: G02/G03 with R or I/J/K in G17, G18, G19. The centre is
/// computed here: for R, on the perpendicular bisector of the chord at distance
/// √(R² − (c/2)²), on the right of start→end for G02 with R > 0 (G03: left).
#[test]
fn arcs_in_the_three_planes() {
    fn r_centre(s: (f64, f64), e: (f64, f64), r: f64, cw: bool) -> (f64, f64) {
        let (mx, my) = ((s.0 + e.0) / 2.0, (s.1 + e.1) / 2.0);
        let (dx, dy) = (e.0 - s.0, e.1 - s.1);
        let c = (dx * dx + dy * dy).sqrt();
        let h = (r * r - c * c / 4.0).sqrt();
        // Left normal of the chord.
        let (nx, ny) = (-dy / c, dx / c);
        let side = if cw == (r > 0.0) { -1.0 } else { 1.0 };
        (mx + side * h * nx, my + side * h * ny)
    }
    let r = go("G00 X0 Y0 Z0\nG17 G02 X20. Y0 R15. F200\nM30\n");
    let (cx, cy) = r_centre((0.0, 0.0), (20.0, 0.0), 15.0, true);
    let c = centre(&r.actions[1]).unwrap();
    assert!((c[0] - cx).abs() < 1e-6 && (c[1] - cy).abs() < 1e-6, "{c:?} vs {cx} {cy}");
    let r = go("G00 X0 Y0 Z0\nG18 G03 X20. Z0 R15. F200\nM30\n");
    // G18's plane axes are (Z, X): the centre in (Z, X).
    let (cz, cx) = r_centre((0.0, 0.0), (0.0, 20.0), 15.0, false);
    let c = centre(&r.actions[1]).unwrap();
    assert!((c[2] - cz).abs() < 1e-6 && (c[0] - cx).abs() < 1e-6, "{c:?}");
    assert!(matches!(r.actions[1].action, Action::Arc(a) if a.plane == Plane::Zx && !a.cw));
    let r = go("G00 X0 Y0 Z0\nG19 G02 Y20. Z0 J10. K0 F200\nM30\n");
    assert_eq!(centre(&r.actions[1]), Some([0.0, 10.0, 0.0]));
    assert_eq!(work(&r.actions[1]), Some([0.0, 20.0, 0.0]));
    let r = go("G00 X0 Y0 Z0\nG17 G03 X10. Y10. I0 J10. F200\nM30\n");
    assert_eq!(centre(&r.actions[1]), Some([0.0, 10.0, 0.0]));
}

/// Helical interpolation (FANUC): the axis normal to the plane moves linearly with
/// the arc; the lathe's rule (2.3 note 7) does not hold on a mill.
#[test]
fn helical_arc_moves_the_third_axis_linearly() {
    let r = go("G00 X10. Y0 Z0\nG17 G03 X-10. Y0 Z-4. I-10. J0 F300\nG03 X10. Y0 Z-8. R10.\nM30\n");
    assert_eq!(work(&r.actions[1]), Some([-10.0, 0.0, -4.0]));
    assert_eq!(centre(&r.actions[1]).map(|c| [c[0], c[1]]), Some([0.0, 0.0]));
    assert_eq!(work(&r.actions[2]), Some([10.0, 0.0, -8.0]));
    assert!(matches!(r.actions[2].action, Action::Arc(a) if !a.cw && a.plane == Plane::Xy));
}

/// Seed 004 @3847, @3952: G04 X30. is 30 s, G04 P100 is 0.1 s; P with a decimal
/// point is alarm 0007.
#[test]
fn dwell_x_in_seconds_p_in_milliseconds() {
    let r = go("G04 X30.\nG04 P100\nM30\n");
    assert_eq!(kind_names(&r)[..2], ["dwell 30000", "dwell 100"]);
    assert_eq!(alarms("G04 P1.5\nM30\n"), vec![(1, 7)]);
}

/// Seed 004 @5400–@6000: G28 rapids through the intermediate point (remembered
/// per axis, work coordinates) to the reference position; G29 rapids through the
/// remembered point to the commanded one (G90 work coordinates, G91 displacement
/// from the intermediate point). G29 without G28 is alarm 4048.
#[test]
fn g28_remembers_the_intermediate_point_and_g29_returns_through_it() {
    let r = go("G00 X10. Y20. Z30.\nG91 G28 Z10.\nG90 G28 X50. Y60.\nG29 X70. Y80. Z5.\nG91 G29 X-5.\nM30\n");
    let p = path(&r);
    // G28 Z: Z40 (G91 +10), then machine Z0 = work Z250.
    assert_eq!(p[1..3], [[10.0, 20.0, 40.0], [10.0, 20.0, 250.0]]);
    // G28 X50 Y60: the intermediate point, then the reference (work X300 Y200).
    assert_eq!(p[3..5], [[50.0, 60.0, 250.0], [300.0, 200.0, 250.0]]);
    // G29: to the intermediate points X50 Y60 Z40, then to X70 Y80 Z5.
    assert_eq!(p[5..7], [[50.0, 60.0, 40.0], [70.0, 80.0, 5.0]]);
    // G91 G29 X-5: X to its intermediate X50, then 5 short of it.
    assert_eq!(p[7..9], [[50.0, 80.0, 5.0], [45.0, 80.0, 5.0]]);
    assert!(
        r.actions
            .iter()
            .filter(|c| c.line >= 2)
            .all(|c| matches!(c.action, Action::Rapid(m) if m.independent) || !matches!(c.action, Action::Rapid(_)))
    );
    assert_eq!(alarms("G00 X10.\nG29 X0 Y0\nM30\n"), vec![(2, 4048)]);
    assert_eq!(alarms("G91 G28 Z0\nG29 X0 Y0\nM30\n"), vec![(2, 4048)], "G28 Z gave X no point");
}

/// Seed 004 @10669: T08 M06 — T selects, M06 changes; the action carries the tool
/// and whether the operator changes it (machine file `tool_changer`).
#[test]
fn t_selects_and_m06_changes() {
    let r = go("T08\nG00 X10.\nM06\nT03 M06\nM06\nM30\n");
    let changes: Vec<ToolChange> = r
        .actions
        .iter()
        .filter_map(|c| match c.action {
            Action::ToolChange(t) => Some(t),
            _ => None,
        })
        .collect();
    assert_eq!(
        changes,
        vec![ToolChange { tool: 8, previous: 0, manual: true }, ToolChange { tool: 3, previous: 8, manual: true }],
        "the second M06 finds T03 in the spindle already"
    );
    assert_eq!(r.interp.state().tool.tool, 3);
    let mut cfg = mill();
    cfg.tool_changer = ToolChanger::Automatic;
    let r = run_with("T2 M06\nM30\n", cfg, Panel::default());
    assert!(matches!(r.actions[0].action, Action::ToolChange(ToolChange { tool: 2, manual: false, .. })));
    assert_eq!(alarms("T25 M06\nM30\n"), vec![(1, 30)], "tool_count is 24");
}

/// Tool length compensation, FANUC type B: G43 adds H's length along the axis
/// normal to the plane, G44 subtracts it, G49 and H0 cancel; the block that
/// carries it moves that axis by the change even without a Z word.
#[test]
fn g43_g44_g49_apply_h_along_the_tool_axis_from_their_block() {
    // H1 = 100 mm, H2 = 120 − 0.05 (wear). G54 Z-250.
    let r = go("G00 X0 Y0 Z50.\nG43 Z50. H1\nG44 H2\nG91 G43 Z-10. H2\nG90 G49\nM30\n");
    let m = machine_path(&r);
    assert_eq!(m[0][2], -200.0);
    assert_eq!(m[1][2], -100.0, "Z50 + G54 Z-250 + H1 100");
    assert!((m[2][2] - (-200.0 - 119.95)).abs() < 1e-9, "G44 H2 alone moves Z by −(120 − 0.05)");
    assert!((m[3][2] - (-200.0 + 119.95 - 10.0)).abs() < 1e-9, "G91 Z-10 with +H2");
    assert_eq!(m[4][2], -210.0, "G49 alone takes the length away");
    assert!(path(&r).iter().all(|p| p[0] == 0.0 && p[1] == 0.0));
    // G18: the tool axis is Y.
    let r = go("G18 G00 X0 Y10. Z0\nG43 H1\nM30\n");
    assert_eq!(machine_path(&r)[1][1], -200.0 + 10.0 + 100.0);
    assert_eq!(alarms("G43 H33\nM30\n"), vec![(1, 30)]);
    assert_eq!(alarms("G41 D40 X1\nM30\n"), vec![(1, 30)]);
}

/// Seed 004 @2086–@2152: G10 L2 P1–P6 (G54–G59), L20 P1–P48 (G54.1), L10–L13
/// (length and radius, geometry and wear); G90 sets, G91 adds; the new offsets
/// are in effect for the next block.
#[test]
fn g10_sets_work_offsets_and_the_offset_pages() {
    let r = go("G10 L2 P1 X-100. Y-50. Z-200.\nG00 X0 Y0 Z0\nG91 G10 L2 P1 X5.\nG90 G00 X0 Y0\n\
         G10 L20 P3 X-10. Y-20. Z-30.\nG54.1 P3 G00 X1. Y2. Z3.\nG54 G00 X0 Y0 Z0\nM30\n");
    let m = machine_path(&r);
    assert_eq!(m[0], [-100.0, -50.0, -200.0]);
    assert_eq!(m[1], [-95.0, -50.0, -200.0], "G91 G10 added 5 to G54's X");
    assert_eq!(m[2], [-9.0, -18.0, -27.0], "G54.1 P3 set by G10 L20");
    assert_eq!(r.interp.config().work_offsets[0].0[0], -95_000_000);
    assert_eq!(r.interp.config().extra_offsets.get(3).map(|p| p.0[1]), Some(-20_000_000));
    // L10–L13: H3 length and wear, D3 radius and wear; the length counts from the
    // next H.
    let r = go("G10 L10 P3 R90.\nG10 L11 P3 R-0.1\nG91 G10 L11 P3 R0.03\nG90 G00 X0 Y0 Z10.\nG43 H3\nM30\n");
    let row = *r.interp.config().tools.get(3).unwrap();
    assert_eq!((row.length(), row.z_wear), (89_930_000, -70_000));
    assert!((machine_path(&r)[1][2] - (10.0 - 250.0 + 89.93)).abs() < 1e-9);
    let r = go("G10 L12 P4 R6.\nG10 L13 P4 R-0.05\nM30\n");
    assert_eq!(r.interp.config().tools.get(4).unwrap().cutter_radius(), 5_950_000);
    assert_eq!(alarms("G10 L2 P7 X0\nM30\n"), vec![(1, 4011)]);
    assert_eq!(alarms("G10 L12 P40 R1.\nM30\n"), vec![(1, 30)]);
    assert_eq!(alarms("G10 L10 P1 R1000.\nM30\n"), vec![(1, 32)]);
    assert_eq!(alarms("G10 L12 P1\nM30\n"), vec![(1, 4006)]);
    assert_eq!(alarms("G10 L5 P1 R1.\nM30\n"), vec![(1, 4011)]);
}

/// G54.1 P1 (seed 004 @2112): the machine file's extra offset; P out of 1–48 or
/// missing is an alarm.
#[test]
fn g54_1_selects_an_additional_work_frame() {
    let r = go("G54.1 P1\nG00 X10. Y10. Z10.\nM30\n");
    assert_eq!(machine_path(&r), vec![[-390.0, -90.0, -250.0]]);
    assert_eq!((r.interp.state().modal.work_frame, r.interp.state().modal.extra_frame), (0, 1));
    assert_eq!(alarms("G54.1 P49\nM30\n"), vec![(1, 4011)]);
    assert_eq!(alarms("G54.1 G00 X1\nM30\n"), vec![(1, 4006)]);
}

/// Seed 004 @2559: three contours with G52 local frames and M98 P100 (P100 drawn
/// by a subprogram); M98 P L repeats it (@10730).
#[test]
fn g52_local_frames_with_a_subprogram_and_m98_l() {
    let sub = "O0100\nG00 X0 Y0\nG01 X1. F100\nM99\n";
    let main =
        "G90 G52 X6.0 Y6.0\nM98 P100\nG90 G52 X10.5 Y4.8\nM98 P100\nG90 G52 X14.5 Y8.3\nM98 P100 L2\nG52 X0 Y0\nM30\n";
    let r = host_tests::run_programs(main, &[sub], mill(), Panel::default());
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    let m: Vec<[f64; 2]> = r
        .actions
        .iter()
        .filter_map(|c| c.action.endpoint())
        .map(|e| [0, 1].map(|i| (e.machine.0[i] as f64 + [300e6, 200e6][i]) / 1e6))
        .collect();
    assert_eq!(
        m,
        vec![[6.0, 6.0], [7.0, 6.0], [10.5, 4.8], [11.5, 4.8], [14.5, 8.3], [15.5, 8.3], [14.5, 8.3], [15.5, 8.3]]
    );
}

#[test]
fn bad_offset_words_and_lathe_t_words() {
    assert_eq!(alarms("H1.5\nM30\n"), vec![(1, 7)]);
    assert_eq!(alarms("G04 X1 H1\nM30\n"), vec![(1, 4005)]);
    // A mill's T is a tool number: T0101 is tool 101.
    assert_eq!(alarms("T0101\nM30\n"), vec![(1, 30)]);
}

/// The simulated machine cuts a helix within one step plus the chord tolerance of
/// the programmed one (the motion core moves Z with the arc's progress) and ends
/// exactly at its end point.
#[test]
fn helix_on_the_simulated_machine() {
    let cfg = mill();
    let mut s = sim::Sim::new(cfg.clone(), sim::SimOptions::default()).unwrap();
    let r = s.run_program(
        "G00 X10. Y0 Z5.\nM03 S1000\nG03 X-10. Y0 Z-4. I-10. J0 F300\nG03 X10. Y0 Z-8. R10.\nG00 Z50.\nM30\n",
    );
    assert!(r.alarms.is_empty() && r.ended, "{r:?}");
    let step = cfg.axes.iter().filter(|a| a.present).map(|a| a.drive.per_nm as f64 / a.drive.steps as f64);
    let bound = step.fold(0.0, f64::max) + cfg.motion.chord_tolerance as f64;
    assert!(r.max_dev_nm <= bound, "deviation {} nm on line {}", r.max_dev_nm, r.max_dev_line);
}

/// A reset cancels tool length and cutter compensation (G49, G40) and the
/// transformations; the tool in the spindle and the one selected stay.
#[test]
fn reset_cancels_the_offsets_and_keeps_the_tools() {
    let mut r = go("T3 M06\nT5\nG00 X0 Y0 Z50.\nG43 H1\nG68 X0 Y0 R10.\nM30\n");
    assert_ne!(r.interp.state().tool.offset, interp_core::Pos::ZERO);
    r.interp.reset();
    let st = r.interp.state();
    assert_eq!(st.tool.offset, interp_core::Pos::ZERO);
    assert_eq!((st.tool.tool, st.mill.selected, st.mill.length_sign), (3, 5, 0));
    assert_eq!(st.mill.frame.active, 0);
    assert_eq!(st.modal.plane, Plane::Xy);
}

//! Work coordinate systems (2.12), reference returns (2.11), machine coordinates
//! and tool offsets.

use host_tests::{Run, kind_names, machine_xz, mm, path, run_with};
use interp_core::canon::Action;
use interp_core::config::{Param, ToolOffset};
use interp_core::{Axis, MachineConfig, Panel, Pos};

/// A machine with G54 at X-100 (dia) Z-300 and G56 at X-80 Z-250, G55 offset from
/// G54 by Z+40, and tool offsets 1 and 2.
fn machine() -> MachineConfig {
    let mut cfg = MachineConfig::default();
    cfg.axes[Axis::X.index()].min = mm(-200.0);
    cfg.axes[Axis::Z.index()].min = mm(-700.0);
    cfg.work_offsets[0] = Pos::xz(mm(-50.0), mm(-300.0));
    cfg.work_offsets[1] = Pos::xz(mm(-50.0), mm(-260.0));
    cfg.work_offsets[2] = Pos::xz(mm(-40.0), mm(-250.0));
    *cfg.tools.get_mut(1).unwrap() = ToolOffset { x: mm(-0.5), z: mm(2.0), x_wear: mm(0.005), ..Default::default() };
    *cfg.tools.get_mut(2).unwrap() = ToolOffset { x: mm(1.5), z: mm(-4.0), ..Default::default() };
    cfg.reference = [
        Pos::xz(mm(100.0), mm(200.0)),
        Pos::xz(mm(90.0), mm(180.0)),
        Pos::xz(mm(80.0), mm(160.0)),
        Pos::xz(mm(70.0), mm(140.0)),
    ];
    cfg
}

fn go(text: &str) -> Run {
    let r = run_with(text, machine(), Panel::default());
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    r
}

fn machine_path(r: &Run) -> Vec<(f64, f64)> {
    r.actions.iter().filter_map(machine_xz).collect()
}

#[test]
fn figure_2_15_work_frame_3_positions_at_x60_z20() {
    let r = go("G56 G00 X60 Z20\nM30\n");
    // G56 origin at machine X-80 (dia), Z-250: X60 Z20 is machine X-20, Z-230.
    assert_eq!(machine_path(&r), vec![(-20.0, -230.0)]);
    assert_eq!(path(&r), vec![(60.0, 20.0)]);
    assert_eq!(r.interp.state().modal.work_frame, 2);
}

#[test]
fn figure_2_17_g50_sets_the_current_point_and_2_18_shifts_every_frame() {
    let r = go("G54 G00 X100 Z50\nG50 X200 Z100\nG00 X150 Z80\nG55 G00 X150 Z80\nM30\n");
    // Before G50 the tool is at machine X0 (dia 100 - 100), Z-250. After G50 the
    // same point is work X200 Z100: G54 moves by (-100 dia, -50).
    assert_eq!(
        machine_path(&r),
        vec![(0.0, -250.0), (-50.0, -270.0), (-50.0, -230.0)],
        "G55 is shifted alike: its Z origin is 40 mm above G54's"
    );
    let r = go("G00 X100 Z50\nG50 U10 W-5\nM30\n");
    assert_eq!(path(&r), vec![(100.0, 50.0)], "G50 does not move the axes");
    let here = r.interp.state().work_pos(r.interp.config());
    assert_eq!((2 * here[Axis::X], here[Axis::Z]), (mm(110.0), mm(45.0)), "U10 W-5 add to the current point");
}

#[test]
fn g50_can_be_disabled_by_parameter_5152() {
    let mut cfg = machine();
    cfg.params.set(Param::DisableCoordinateSetting, 1);
    let r = run_with("G50 X10 Z10\nG50 S2000\nM30\n", cfg, Panel::default());
    assert_eq!(r.alarm_codes(), vec![(1, 4012)]);
}

#[test]
fn figure_2_19_local_frame_and_its_cancellation() {
    let r = go("G52 X50 Z50\nG00 X0 Z0\nG52 U0 W0\nG00 X0 Z0\nM30\n");
    // Work end points are given in the coordinates the program uses (local here).
    assert_eq!(path(&r), vec![(0.0, 0.0), (0.0, 0.0)]);
    assert_eq!(machine_path(&r), vec![(-50.0, -250.0), (-100.0, -300.0)]);
}

#[test]
fn g52_note_3_g50_cancels_the_local_frame_of_its_axes_only() {
    let r = go("G52 X50 Z50\nG00 X10 Z10\nG50 X100\nG00 X100 Z0\nM30\n");
    // After G50 X100 the local frame of X is gone; Z keeps its local origin 50.
    let st = r.interp.state();
    assert_eq!(st.frames.local[Axis::X], 0);
    assert_eq!(st.frames.local[Axis::Z], mm(50.0));
    assert_eq!(machine_path(&r)[1].1, -250.0, "Z0 local = Z50 work = machine -250");
    assert_eq!(machine_path(&r)[1].0, machine_path(&r)[0].0, "X100 is where G50 put the tool");
}

#[test]
fn g52_note_4_local_frame_moves_with_the_work_frame() {
    let r = go("G52 Z10\nG00 X0 Z0\nG55 G00 X0 Z0\nM30\n");
    assert_eq!(machine_path(&r), vec![(-100.0, -290.0), (-100.0, -250.0)]);
}

#[test]
fn g53_moves_in_machine_coordinates_without_tool_offset() {
    let r = go("T0101\nG53 X-20 Z-100\nG00 X0 Z0\nM30\n");
    assert_eq!(machine_path(&r), vec![(-20.0, -100.0), (-101.0 + 0.01, -298.0)]);
    let r = run_with("G53 U10\nM30\n", machine(), Panel::default());
    assert_eq!(r.alarm_codes(), vec![(1, 4015)]);
}

#[test]
fn g28_goes_through_the_intermediate_point_to_reference_1() {
    let r = go("G00 X20 Z10\nG28 U10 W5\nM30\n");
    let rapids: Vec<_> = r
        .actions
        .iter()
        .filter_map(|c| match c.action {
            Action::Rapid(m) => Some(m.independent),
            _ => None,
        })
        .collect();
    assert_eq!(rapids, vec![false, true, true], "2.11.1 note 1: axes move independently");
    assert_eq!(path(&r)[1], (30.0, 15.0));
    assert_eq!(machine_path(&r)[2], (200.0, 200.0));
}

#[test]
fn g28_moves_only_the_named_axes() {
    let r = go("G00 X20 Z10\nG28 W0\nM30\n");
    assert_eq!(machine_path(&r), vec![(-80.0, -290.0), (-80.0, 200.0)]);
}

#[test]
fn g30_selects_references_2_to_4_and_defaults_to_2() {
    let r = go("G30 U0 W0\nG30 P3 U0 W0\nG30 P4 U0\nG30 P1 W0\nM30\n");
    assert_eq!(machine_path(&r), vec![(180.0, 180.0), (160.0, 160.0), (140.0, 160.0), (140.0, 200.0)]);
    let r = run_with("G30 P5 U0\nG30 P2.0 U0\nG30\nM30\n", machine(), Panel::default());
    assert_eq!(r.alarm_codes(), vec![(1, 46), (2, 46), (3, 4006)]);
}

#[test]
fn reference_return_needs_a_referenced_axis() {
    let panel = Panel { referenced: 1 << Axis::Z.index(), ..Panel::default() };
    let r = run_with("G28 W0\nG28 U0\nM30\n", machine(), panel);
    assert_eq!(r.alarm_codes(), vec![(2, 224)]);
}

#[test]
fn tool_offset_shifts_the_programmed_point_from_the_next_move() {
    let r = go("G00 X0 Z0\nT0101\nG00 X0 Z0\nT0202\nG00 X0\nT0200\nG00 X0 Z0\nM30\n");
    assert_eq!(
        machine_path(&r),
        vec![(-100.0, -300.0), (-100.99, -298.0), (-97.0, -298.0), (-100.0, -300.0)],
        "geometry + wear; an axis not commanded keeps its position; T0200 cancels"
    );
    assert_eq!(kind_names(&r)[1], "tool 1 1");
    let st = r.interp.state();
    assert_eq!((st.tool.tool, st.tool.offset_number), (2, 0));
}

#[test]
fn tool_and_offset_numbers_must_exist() {
    let r = run_with("T1301\nT0133\nT01.5\nM30\n", machine(), Panel::default());
    assert_eq!(r.alarm_codes(), vec![(1, 30), (2, 30), (3, 7)]);
    let mut cfg = machine();
    cfg.params.set(Param::OffsetDigits, 1);
    let r = run_with("T121\nM30\n", cfg, Panel::default());
    assert!(r.alarms.is_empty());
    assert_eq!(kind_names(&r)[0], "tool 12 1");
}

#[test]
fn soft_limits_stop_the_block_before_motion() {
    let r = run_with("G00 X600\nG00 Z-900\nG00 X10 Z5\nM30\n", machine(), Panel::default());
    assert_eq!(r.alarm_codes(), vec![(1, 500), (2, 501)]);
    assert_eq!(path(&r), vec![(10.0, 5.0)]);
}

//! A machining centre's part of a block (seed 004, FANUC 0i-M where it is
//! silent): T selects and M06 changes the tool; H with G43/G44/G49 puts the tool
//! length on the axis normal to the plane (FANUC's type B) from the block that
//! carries it; D gives the cutter radius compensation its radius; G10 writes work
//! offsets and the offset pages; the transformations ([`crate::moves::frame`])
//! turn a move into work coordinates before the move helpers see it.

use crate::alarm::AlarmKind;
use crate::axis::{Axis, Pos};
use crate::canon::{Action, ToolChange};
use crate::codes::{GCode, MFunction};
use crate::command::{AxisWord, Command, CycleArgs};
use crate::config::{EXTRA_FRAMES, MAX_OFFSET_VALUE, MachineConfig, MillPage, ToolChanger};
use crate::modal::State;
use crate::modal::mill::on;
use crate::moves::frame;
use crate::stage::{Setting, Staged};

/// What [`prepare`] did that matters once the block has run.
pub(super) struct Prepared {
    /// The programmed target of a move planned under a transformation: the
    /// programmed position once the block has succeeded.
    pub prog: Option<[i64; 3]>,
    /// The transformations mirror the plane: G02/G03 and G41/G42 swap.
    pub mirrored: bool,
}

/// Before the block's motion (after its modal codes): the transformations it
/// switches, D, H with G43/G44/G49; `adapted` (a copy of `cmd`) becomes the block
/// the move helpers execute: a transformed move in absolute work coordinates, the
/// axis of a changed tool length moving by the change.
pub(super) fn prepare(
    cmd: &Command,
    st: &mut State,
    cfg: &MachineConfig,
    adapted: &mut Command,
) -> Result<Prepared, AlarmKind> {
    st.refresh_extra_frame(cfg);
    frame::switch(cmd, st, cfg)?;
    let f = &st.mill.frame;
    if f.active & on::ROTATE != 0 && f.rot_plane != st.modal.plane {
        // The plane of a G68 rotation stays until G69 (FANUC).
        return Err(AlarmKind::RotationPlaneChange);
    }
    if cmd.g.frame.is_some() {
        // G51, G51.1, G68: the axis words were their centre.
        adapted.axes = [None; crate::axis::AXIS_COUNT];
    }
    if let Some(d) = cmd.d {
        let radius = cfg.tools.get(d).map_or(0, |r| r.cutter_radius());
        st.mill.d = d;
        st.tool.nose_radius = radius;
        st.tool.tip = 0;
    }
    let before = st.work_pos(cfg);
    let length_changed = length(cmd, st, cfg);
    let user = cmd.axis_user(st);
    let is_move = cmd.g.frame.is_none()
        && cmd.g.one_shot.is_none()
        && matches!(user, GCode::Rapid | GCode::Linear | GCode::ArcCw | GCode::ArcCcw);
    let arc = matches!(user, GCode::ArcCw | GCode::ArcCcw);
    let arc_words = arc && (cmd.radius.is_some() || cmd.center.iter().any(Option::is_some));
    let mut prog = None;
    if is_move && st.mill.frame.active != 0 && (cmd.has_axes() || arc_words) {
        prog = Some(frame::adapt(cmd, st, arc, adapted)?);
    }
    if length_changed && is_move && !arc {
        // The block that carries the change moves the axis by it (FANUC): an axis
        // word left out keeps the work position of before, an incremental one adds
        // to it.
        let a = st.mill.length_axis;
        let value = match cmd.axes[a.index()] {
            None => before[a],
            Some(w) if w.incremental && prog.is_none() => before[a].checked_add(w.value).ok_or(AlarmKind::Overflow)?,
            Some(_) => adapted.axes[a.index()].map_or(before[a], |w| w.value),
        };
        adapted.axes[a.index()] = Some(AxisWord { value, incremental: false });
    }
    Ok(Prepared { prog, mirrored: st.mill.frame.active != 0 && st.mill.frame.mirrors(st.modal.plane) })
}

/// H and G43/G44/G49: the tool length of row H, + (G43) or − (G44), along the axis
/// normal to the plane of the G43/G44 block; G49 or H0 cancel it. The value is
/// taken when H or G43/G44 is given (a later G10 takes effect with the next one).
/// Returns whether the tool length in force changed.
fn length(cmd: &Command, st: &mut State, cfg: &MachineConfig) -> bool {
    if cmd.g.length.is_none() && cmd.h.is_none() {
        return false;
    }
    let m = &mut st.mill;
    if let Some(h) = cmd.h {
        m.h = h;
    }
    match cmd.g.length {
        Some(GCode::LengthPlus) => (m.length_sign, m.length_axis) = (1, st.modal.plane.normal()),
        Some(GCode::LengthMinus) => (m.length_sign, m.length_axis) = (-1, st.modal.plane.normal()),
        Some(_) => m.length_sign = 0,
        None => {}
    }
    let length = cfg.tools.get(m.h).map_or(0, |r| r.length());
    let mut offset = Pos::ZERO;
    offset[m.length_axis] = length * i64::from(m.length_sign);
    let changed = offset != st.tool.offset;
    st.tool.offset = offset;
    st.sum_own_offsets();
    changed
}

/// T selects the tool for the next M06; M06 puts it in the spindle: a
/// [`ToolChange`] for the tool changer or the operator (machine file
/// `tool_changer`). Nothing happens when the tool is already in the spindle.
pub(super) fn tool(cmd: &Command, st: &mut State, cfg: &MachineConfig, out: &mut Staged<'_>) -> Result<(), AlarmKind> {
    if let Some((t, _)) = cmd.tool {
        st.mill.selected = t;
    }
    if !cmd.m.iter().any(|&(_, f)| f == MFunction::ToolChange) {
        return Ok(());
    }
    if st.contour.comp.side.is_some() {
        return Err(AlarmKind::ToolChangeInNoseComp);
    }
    let (tool, previous) = (st.mill.selected, st.tool.tool);
    if tool == previous {
        return Ok(());
    }
    st.tool.tool = tool;
    let manual = cfg.tool_changer == ToolChanger::Manual;
    out.emit(Action::ToolChange(ToolChange { tool, previous, manual }))
}

/// G10 (seed 004 @2086–@2152): L2 P0–P6 work offsets (P0 the external one, P1–P6
/// G54–G59), L20 P1–P48 the G54.1 offsets, both from the block's X/Y/Z (machine
/// coordinates); L10/L11 tool length geometry/wear, L12/L13 cutter radius
/// geometry/wear of row P, from R. G90 sets, G91 adds. The values are written when
/// the block has succeeded and act from the next block (offsets in force) or with
/// the next H/D (offset pages).
pub(super) fn data(cmd: &Command, st: &State, cfg: &MachineConfig, out: &mut Staged<'_>) -> Result<(), AlarmKind> {
    let CycleArgs::Data { l, p, r } = cmd.cycle else { return Ok(()) };
    let add = st.modal.incremental;
    let mut write = |s: Setting, v: i64| out.writes.push((s, v)).map_err(|_| AlarmKind::Overflow);
    if let (10..=13, Some(r)) = (l, r) {
        let page = match l {
            10 => MillPage::Length,
            11 => MillPage::LengthWear,
            12 => MillPage::Radius,
            _ => MillPage::RadiusWear,
        };
        let old = cfg.tools.get(p).map_or(0, |row| row.mill_value(page));
        let v = if add { old.checked_add(r).ok_or(AlarmKind::OffsetValueOutOfRange)? } else { r };
        if v.abs() > MAX_OFFSET_VALUE {
            return Err(AlarmKind::OffsetValueOutOfRange);
        }
        return write(Setting::Offset { row: p, page }, v);
    }
    if !cmd.has_axes() {
        return Err(AlarmKind::MissingWord { letter: b'X', context: "G10 L2/L20" });
    }
    let (frame, old) = match (l, p) {
        (2, 0) => (Setting::EXTERNAL, cfg.external_offset),
        (2, p) => (p as u8 - 1, cfg.work_offsets[usize::from(p - 1)]),
        (_, p) if usize::from(p) <= EXTRA_FRAMES => (5 + p as u8, cfg.work_offset(5 + p as u8)),
        _ => return Err(AlarmKind::ValueOutOfRange { letter: b'P' }),
    };
    for a in Axis::ALL {
        let Some(w) = cmd.axes[a.index()] else { continue };
        let v = if add || w.incremental { old[a].checked_add(w.value) } else { Some(w.value) };
        let v = v.ok_or(AlarmKind::OffsetValueOutOfRange)?;
        // G54.1's offsets are kept in ±2,147 mm (config::ExtraOffsets).
        if l == 20 && (a == Axis::C || i32::try_from(v).is_err()) {
            return Err(AlarmKind::OffsetValueOutOfRange);
        }
        write(Setting::WorkOffset { frame, axis: a }, v)?;
    }
    Ok(())
}

/// After the block: the programmed position of a transformation in force — the
/// planned target of a move, else again from where the tool is.
pub(super) fn after(st: &mut State, cfg: &MachineConfig, prepared: &Prepared) {
    if st.mill.frame.active == 0 {
        return;
    }
    match prepared.prog {
        Some(p) => {
            // Checked in frame::adapt: within ±2,147 mm.
            let _ = st.mill.frame.set_prog(p);
        }
        None => frame::resync(st, cfg),
    }
}

//! Polygon turning, G51.2/G50.2 (2.8), in the interpreter: the mode, its words and
//! alarms, and what the block emits. The C axis drive is the tool spindle; the
//! motion core (`motion_core::motion::polygon`) locks it to the spindle encoder.
//!
//! G51.2 P Q R S starts the work spindle (M03) at S if it stands (the manual's
//! EX3 has no M03), turns C forward to the phase angle R (modulo a turn: C's
//! machine angle at the work spindle's index, 2.8 note 14), then emits
//! [`Action::Polygon`]: from the next index C turns Q/P times the spindle. In the
//! mode G51.2 again changes the ratio and S (note 4); G50.2 ends it and C comes to
//! rest on a whole turn from where it locked, so its position is the one before.
//! M02/M30 end it too. Alarms: a C move in the mode (0220, note 11); G12.1, M29 or
//! G51.2 in G12.1 (0221: the spindle or C in position control for something else,
//! notes 6 and 9); no C axis (4047).

use crate::alarm::AlarmKind;
use crate::axis::Axis;
use crate::canon::{Action, Endpoint, Move, PolygonSync, SpindleCommand, SpindleDir};
use crate::command::Command;
use crate::command::cycle::CycleArgs;
use crate::config::MachineConfig;
use crate::modal::State;
use crate::moves::{motion, spindle_speed};
use crate::stage::Staged;

/// One turn of C, µdeg.
const TURN_UDEG: i64 = 360_000_000;

/// The block checked against the polygon mode (2.8 notes 6, 9, 11).
pub(super) fn check_block(cmd: &Command, st: &State) -> Result<(), AlarmKind> {
    if cmd.g.polygon == Some(true) && st.polar.is_some() {
        return Err(AlarmKind::PolygonModeConflict { what: "G51.2 during polar interpolation (G12.1)" });
    }
    if st.modal.polygon.is_none() {
        return Ok(());
    }
    if cmd.axes[Axis::C.index()].is_some() {
        return Err(AlarmKind::PolygonAxisCommanded);
    }
    if cmd.g.polar == Some(true) {
        return Err(AlarmKind::PolygonModeConflict { what: "G12.1 polar interpolation" });
    }
    if cmd.m.iter().any(|&(m, _)| m == 29) {
        return Err(AlarmKind::PolygonModeConflict { what: "M29 rigid tapping" });
    }
    Ok(())
}

/// G51.2 or G50.2 (each in a block of its own, note 1).
pub(super) fn switch(
    cmd: &Command,
    st: &mut State,
    cfg: &MachineConfig,
    out: &mut Staged<'_>,
) -> Result<(), AlarmKind> {
    match cmd.g.polygon {
        Some(true) => {
            let CycleArgs::Polygon { p, q, phase_udeg } = cmd.cycle else { return Ok(()) };
            if st.modal.polygon.is_none() {
                start_spindle(st, cfg, out)?;
                to_phase(st, cfg, phase_udeg, out)?;
            }
            let sync = PolygonSync { p, q };
            st.modal.polygon = Some(sync);
            out.emit(Action::Polygon(Some(sync)))
        }
        Some(false) => stop(st, out),
        None => Ok(()),
    }
}

/// G50.2, M02/M30: the mode ends (nothing if it is off).
pub(super) fn stop(st: &mut State, out: &mut Staged<'_>) -> Result<(), AlarmKind> {
    if st.modal.polygon.take().is_some() {
        out.emit(Action::Polygon(None))?;
    }
    Ok(())
}

/// The work spindle turns M03 at the speed in force if it stands.
fn start_spindle(st: &mut State, cfg: &MachineConfig, out: &mut Staged<'_>) -> Result<(), AlarmKind> {
    if st.spindle.dir != SpindleDir::Stop {
        return Ok(());
    }
    st.spindle.dir = SpindleDir::Cw;
    let now = spindle_speed(st, cfg, st.work_pos(cfg)[Axis::X]);
    out.emit(Action::Spindle(SpindleCommand { dir: SpindleDir::Cw, rpm: now.rpm, css: now.css }))
}

/// C forward (at rapid) to the machine angle `phase` modulo a turn.
fn to_phase(st: &mut State, cfg: &MachineConfig, phase: i64, out: &mut Staged<'_>) -> Result<(), AlarmKind> {
    let c = Axis::C;
    let d = (phase - st.pos[c]).rem_euclid(TURN_UDEG);
    if d == 0 {
        return Ok(());
    }
    let mut machine = st.pos;
    machine[c] = machine[c].checked_add(d).ok_or(AlarmKind::Overflow)?;
    motion::check_limits(&machine, cfg)?;
    let mut work = st.work_pos(cfg);
    work[c] = work[c].saturating_add(d);
    let feed = crate::canon::Feed { mode: st.modal.feed_mode, value: st.feed.get(st.modal.feed_mode) };
    let spindle = spindle_speed(st, cfg, work[Axis::X]);
    let to = Endpoint { machine, work };
    out.emit(Action::Rapid(Move { to, feed, spindle, exact_stop: true, independent: false }))?;
    st.pos = machine;
    Ok(())
}

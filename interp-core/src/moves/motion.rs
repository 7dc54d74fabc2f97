//! G00, G01, G02, G03: targets, soft limits, feeds and arc geometry.

use super::spindle_speed;
use crate::alarm::AlarmKind;
use crate::axis::{Axis, Pos};
use crate::canon::{Action, ArcMove, Endpoint, Feed, FeedMode, Move, Plane, SpindleDir};
use crate::codes::GCode;
use crate::command::Command;
use crate::config::{MachineConfig, Param};
use crate::geom::{P2, arc_extents, center_from_offsets, center_from_radius};
use crate::modal::State;
use crate::stage::Staged;

/// Executes the block's motion in the modal motion mode, if it has axis words
/// (or is an arc, which may omit them: 2.3 note 1). G02.1/G03.1 and G02.2/G03.2
/// are cycles (`exec` sends them to [`crate::cycles::curve_block`]).
pub(crate) fn execute(
    cmd: &Command,
    st: &mut State,
    cfg: &MachineConfig,
    out: &mut Staged<'_>,
) -> Result<(), AlarmKind> {
    let code = st.modal.motion;
    let is_arc = matches!(code, GCode::ArcCw | GCode::ArcCcw);
    let arc_words = || cmd.radius.is_some() || cmd.center.iter().any(Option::is_some);
    if !(cmd.has_axes() || is_arc && arc_words()) {
        return Ok(());
    }
    // The work frame once per block (it sums five offsets).
    let at = At::of(st, cfg);
    let work = target_from(cmd, at.here)?;
    let exact = cmd.g.one_shot == Some(GCode::ExactStopOnce) || st.modal.exact_stop_mode;
    match code {
        GCode::Rapid => rapid_to(at.endpoint(work)?, st, cfg, out, cfg.rapid_independent),
        GCode::Linear => linear(work, at, st, cfg, out, exact),
        _ => arc(cmd, work, at, st, cfg, out, exact),
    }
}

/// Where a move starts: the work position and what turns work into machine
/// coordinates.
#[derive(Clone, Copy)]
struct At {
    /// The current position, work coordinates.
    here: Pos,
    /// Work to machine ([`State::work_to_machine`]).
    shift: Pos,
}

impl At {
    fn of(st: &State, cfg: &MachineConfig) -> At {
        let shift = st.work_to_machine(cfg);
        At { here: st.pos - shift, shift }
    }

    /// Both coordinates of a work target.
    fn endpoint(&self, work: Pos) -> Result<Endpoint, AlarmKind> {
        shifted(work, self.shift)
    }
}

/// Work-coordinate target of the block: commanded axes absolute or incremental,
/// the others where they are.
pub(crate) fn target(cmd: &Command, st: &State, cfg: &MachineConfig) -> Result<Pos, AlarmKind> {
    target_from(cmd, st.work_pos(cfg))
}

/// [`target`] from the work position `here`.
fn target_from(cmd: &Command, here: Pos) -> Result<Pos, AlarmKind> {
    let mut work = here;
    for axis in Axis::ALL {
        if let Some(w) = cmd.axes[axis.index()] {
            work[axis] =
                if w.incremental { work[axis].checked_add(w.value).ok_or(AlarmKind::Overflow)? } else { w.value };
        }
    }
    Ok(work)
}

/// Both coordinates of a work target.
pub(crate) fn endpoint(work: Pos, st: &State, cfg: &MachineConfig) -> Result<Endpoint, AlarmKind> {
    shifted(work, st.work_to_machine(cfg))
}

/// The end point of `work` whose machine position is `work + shift` (alarm on
/// overflow).
fn shifted(work: Pos, shift: Pos) -> Result<Endpoint, AlarmKind> {
    let machine = work.checked_add(shift).ok_or(AlarmKind::Overflow)?;
    Ok(Endpoint { machine, work })
}

/// Alarm 0500/0501 if `machine` is outside an axis's travel.
pub(crate) fn check_limits(machine: &Pos, cfg: &MachineConfig) -> Result<(), AlarmKind> {
    for a in Axis::ALL {
        check_axis_range(a, machine[a], machine[a], cfg)?;
    }
    Ok(())
}

fn check_axis_range(a: Axis, lo: i64, hi: i64, cfg: &MachineConfig) -> Result<(), AlarmKind> {
    let ax = cfg.axis(a);
    if !ax.present || a.is_rotary() {
        return Ok(());
    }
    if hi > ax.max {
        return Err(AlarmKind::OvertravelPositive { letter: a.letter() });
    }
    if lo < ax.min {
        return Err(AlarmKind::OvertravelNegative { letter: a.letter() });
    }
    Ok(())
}

/// A rapid to a resolved end point.
pub(crate) fn rapid_to(
    to: Endpoint,
    st: &mut State,
    cfg: &MachineConfig,
    out: &mut Staged<'_>,
    independent: bool,
) -> Result<(), AlarmKind> {
    check_limits(&to.machine, cfg)?;
    if to.machine == st.pos {
        return Ok(());
    }
    let spindle = spindle_speed(st, cfg, to.work[Axis::X]);
    let feed = Feed { mode: st.modal.feed_mode, value: st.feed.get(st.modal.feed_mode) };
    // Rapids always stop exactly at their end (2.14 item 4).
    out.emit(Action::Rapid(Move { to, feed, spindle, exact_stop: true, independent }))?;
    arrive(st, to.machine);
    Ok(())
}

fn linear(
    work: Pos,
    at: At,
    st: &mut State,
    cfg: &MachineConfig,
    out: &mut Staged<'_>,
    exact_stop: bool,
) -> Result<(), AlarmKind> {
    let to = at.endpoint(work)?;
    check_limits(&to.machine, cfg)?;
    let feed = cutting_feed(st, cfg, at.here[Axis::X])?;
    if to.machine == st.pos {
        return Ok(());
    }
    let spindle = spindle_speed(st, cfg, to.work[Axis::X]);
    out.emit(Action::Linear(Move { to, feed, spindle, exact_stop, independent: false }))?;
    arrive(st, to.machine);
    Ok(())
}

fn arrive(st: &mut State, machine: Pos) {
    st.pos = machine;
    st.moved = true;
}

/// The F in force for a cutting move starting at work X `x`; alarms for F0 and
/// feed per rev without spindle.
fn cutting_feed(st: &State, cfg: &MachineConfig, x: i64) -> Result<Feed, AlarmKind> {
    let mode = st.modal.feed_mode;
    let value = st.feed.get(mode);
    if value <= 0 {
        return Err(AlarmKind::FeedZero);
    }
    if mode == FeedMode::PerRev && (st.spindle.dir == SpindleDir::Stop || spindle_speed(st, cfg, x).rpm == Some(0)) {
        return Err(AlarmKind::FeedPerRevSpindleStopped);
    }
    Ok(Feed { mode, value })
}

/// G02/G03 in the selected plane, with R or I/J/K (2.3 and its notes).
#[inline(never)]
fn arc(
    cmd: &Command,
    work: Pos,
    at: At,
    st: &mut State,
    cfg: &MachineConfig,
    out: &mut Staged<'_>,
    exact_stop: bool,
) -> Result<(), AlarmKind> {
    let plane = st.modal.plane;
    // A machining centre's arc may move the axis normal to its plane: helical
    // interpolation (FANUC); a lathe's may not (2.3 note 7).
    let helical = crate::is_mill(cfg);
    reject_axes_outside(cmd, plane, helical)?;
    let cw = st.modal.motion == GCode::ArcCw;
    let (pa, pb) = plane.axes();
    let start: P2 = (at.here[pa], at.here[pb]);
    let end: P2 = (work[pa], work[pb]);
    let tol = cfg.params.get(Param::ArcRadiusTolerance);
    let (center, full) = if let Some(r) = cmd.radius {
        // 2.3 note 4: R wins over I/J/K. Note 5: start = end with R is a 0° arc.
        if start == end {
            return Ok(());
        }
        (center_from_radius(start, end, r, cw, tol)?, false)
    } else if let Some(off) = center_offsets(cmd, plane) {
        if off == (0, 0) {
            // 2.3 note 3: I = K = 0 moves in a straight line.
            return linear(work, at, st, cfg, out, exact_stop);
        }
        (center_from_offsets(start, end, off, tol)?, start == end)
    } else if cfg.params.flag(Param::ArcWithoutCenterIsLine) {
        return linear(work, at, st, cfg, out, exact_stop);
    } else {
        return Err(AlarmKind::ArcCenterMissing);
    };
    let to = at.endpoint(work)?;
    let shift = at.shift;
    // The centre is the end point but in the plane's two axes.
    let mut center_ep = to;
    for (axis, c) in [(pa, center.0), (pb, center.1)] {
        center_ep.work[axis] = c;
        center_ep.machine[axis] = c.checked_add(shift[axis]).ok_or(AlarmKind::Overflow)?;
    }
    check_limits(&to.machine, cfg)?;
    let ext = arc_extents(start, end, center, cw, full);
    check_axis_range(pa, ext.a.0 + shift[pa], ext.a.1 + shift[pa], cfg)?;
    check_axis_range(pb, ext.b.0 + shift[pb], ext.b.1 + shift[pb], cfg)?;
    let feed = cutting_feed(st, cfg, at.here[Axis::X])?;
    let spindle = spindle_speed(st, cfg, to.work[Axis::X]);
    out.emit(Action::Arc(ArcMove { to, center: center_ep, plane, cw, full_circle: full, feed, spindle, exact_stop }))?;
    arrive(st, to.machine);
    Ok(())
}

/// 2.3 note 7 / 2.13 note 5: an arc block may move only the plane's axes (and,
/// `helical`, the normal one).
fn reject_axes_outside(cmd: &Command, plane: Plane, helical: bool) -> Result<(), AlarmKind> {
    for a in Axis::ALL {
        if !plane.contains(a) {
            if cmd.axes[a.index()].is_some() && !(helical && a == plane.normal()) {
                return Err(AlarmKind::ArcAxisOutsidePlane { letter: a.letter() });
            }
            if let (Some(l), Some(_)) = (a.center_letter(), cmd.center[a.index()]) {
                return Err(AlarmKind::ArcAxisOutsidePlane { letter: l });
            }
        }
    }
    Ok(())
}

/// I/J/K of the plane's axes; a missing one of the pair is 0. `None` if neither.
fn center_offsets(cmd: &Command, plane: Plane) -> Option<P2> {
    let (pa, pb) = plane.axes();
    let (a, b) = (cmd.center[pa.index()], cmd.center[pb.index()]);
    (a.is_some() || b.is_some()).then(|| (a.unwrap_or(0), b.unwrap_or(0)))
}

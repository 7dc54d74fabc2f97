//! Polar coordinate interpolation, G12.1/G13.1 (2.7): the program moves in a
//! Cartesian plane of X (diameter) and the C address as a length (mm, radius
//! value), whose origin is the work origin on the spindle axis; the machine turns
//! the spindle (C, degrees) and moves X to the radius.
//!
//! A block's G01/G02/G03 in the polar plane is executed as a *virtual* move in the
//! G17 plane — X the virtual first axis, the Y slot of the position the second —
//! so the contour layer (chamfers, nose compensation) works on it unchanged. What
//! comes out of the contour layer is then cut as short real moves
//! ([`crate::cycles::polar`]): X = √(x² + c²), C = atan2(c, x), each short enough
//! that the real path stays within the chord tolerance of the Cartesian one, each
//! with the feed that makes the Cartesian (tangential) speed F (note 5).

use crate::alarm::{AlarmKind, GNum};
use crate::axis::Axis;
use crate::canon::{Action, ArcMove, Endpoint, Feed, FeedMode, Move, Plane, SpindleDir};
use crate::codes::GCode;
use crate::command::Command;
use crate::config::MachineConfig;
use crate::geom::center_from_radius;
use crate::modal::{Polar, State};
use crate::stage::Staged;

/// G12.1 / G13.1 of the block (they stand alone, note 4 lists what may follow):
/// returns true when the block was one of them.
pub(crate) fn mode_change(cmd: &Command, st: &mut State, cfg: &MachineConfig) -> Result<bool, AlarmKind> {
    let Some(on) = cmd.g.polar else { return Ok(false) };
    if st.modal.nose_comp != GCode::NoseCompOff || st.contour.comp.side.is_some() {
        // Note 8: only in G40.
        return Err(AlarmKind::NoseCompPlaneChange);
    }
    match (on, st.polar) {
        (true, None) => {
            if !cfg.axis(Axis::C).present {
                return Err(AlarmKind::AxisNotConfigured { letter: b'C' });
            }
            let w = st.work_pos(cfg);
            let (r, th) = (w[Axis::X] as f64, (w[Axis::C] as f64 / 1e6).to_radians());
            let (s, c) = crate::geom::sin_cos(th);
            st.polar = Some(Polar {
                plane: st.modal.plane,
                x: crate::geom::round_i64(r * c),
                c: crate::geom::round_i64(r * s),
                z: w[Axis::Z],
            });
            st.modal.plane = Plane::Xy;
        }
        (false, Some(p)) => {
            st.modal.plane = p.plane;
            st.polar = None;
        }
        _ => {}
    }
    Ok(true)
}

/// Note 4: in polar mode only G01, G02, G03, G04, G40–G42, G98/G99 (and G13.1).
pub(crate) fn check_codes(cmd: &Command, st: &State) -> Result<(), AlarmKind> {
    if st.polar.is_none() {
        return Ok(());
    }
    use GCode::*;
    let g = &cmd.g;
    let bad = |t: u16| Err(AlarmKind::PolarCodeNotAllowed { code: GNum(t) });
    match g.one_shot {
        None | Some(Dwell) => {}
        Some(_) => return bad(0),
    }
    if g.plane.is_some() {
        return bad(170);
    }
    if g.units.is_some() || g.work_frame.is_some() || g.incremental.is_some() || g.drilling.is_some() {
        return bad(0);
    }
    match g.motion.unwrap_or(st.modal.motion) {
        Linear | ArcCw | ArcCcw => Ok(()),
        _ if !cmd.has_axes() && g.motion.is_none() => Ok(()),
        _ => bad(0),
    }
}

/// A G01/G02/G03 block in the polar plane: the virtual move, staged for the
/// contour layer; the programmed point moves on.
pub(crate) fn execute(
    cmd: &Command,
    st: &mut State,
    cfg: &MachineConfig,
    out: &mut Staged<'_>,
) -> Result<(), AlarmKind> {
    let Some(p) = st.polar else { return Ok(()) };
    if !cmd.has_axes() {
        return Ok(());
    }
    let target = |axis: Axis, now: i64| match cmd.axes[axis.index()] {
        Some(w) if w.incremental => now.checked_add(w.value).ok_or(AlarmKind::Overflow),
        Some(w) => Ok(w.value),
        None => Ok(now),
    };
    let to = Polar { x: target(Axis::X, p.x)?, c: target(Axis::C, p.c)?, z: target(Axis::Z, p.z)?, ..p };
    if to == p {
        return Ok(());
    }
    let feed = feed(st)?;
    let ep = |q: &Polar| Endpoint { machine: q.virtual_pos(), work: q.virtual_pos() };
    let spindle = super::spindle_speed(st, cfg, to.x);
    let exact_stop = cmd.g.one_shot == Some(GCode::ExactStopOnce) || st.modal.exact_stop_mode;
    let action = match st.modal.motion {
        GCode::Linear => Action::Linear(Move { to: ep(&to), feed, spindle, exact_stop, independent: false }),
        code => {
            // Note 6: arcs in the polar plane take R only.
            if cmd.center.iter().any(Option::is_some) {
                return Err(AlarmKind::PolarArcNeedsR);
            }
            let Some(r) = cmd.radius else {
                // No R: as any arc without its centre (2.3 note 2, parameter 3403).
                if cfg.params.flag(crate::config::Param::ArcWithoutCenterIsLine) {
                    let m = Move { to: ep(&to), feed, spindle, exact_stop, independent: false };
                    out.emit(Action::Linear(m))?;
                    st.polar = Some(to);
                    st.moved = true;
                    return Ok(());
                }
                return Err(AlarmKind::ArcCenterMissing);
            };
            let tol = cfg.params.get(crate::config::Param::ArcRadiusTolerance);
            let cw = code == GCode::ArcCw;
            let c = center_from_radius((p.x, p.c), (to.x, to.c), r, cw, tol)?;
            let centre = Polar { x: c.0, c: c.1, ..to };
            Action::Arc(ArcMove {
                to: ep(&to),
                center: ep(&centre),
                plane: Plane::Xy,
                cw,
                full_circle: false,
                feed,
                spindle,
                exact_stop,
            })
        }
    };
    out.emit(action)?;
    st.polar = Some(to);
    st.moved = true;
    Ok(())
}

/// The feed in force, with the alarms of a cutting move.
fn feed(st: &State) -> Result<Feed, AlarmKind> {
    let mode = st.modal.feed_mode;
    let value = st.feed.get(mode);
    if value <= 0 {
        return Err(AlarmKind::FeedZero);
    }
    if mode == FeedMode::PerRev && st.spindle.dir == SpindleDir::Stop {
        return Err(AlarmKind::FeedPerRevSpindleStopped);
    }
    Ok(Feed { mode, value })
}

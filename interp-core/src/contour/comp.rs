//! Tool-nose radius compensation, G40/G41/G42 (2.18).
//!
//! The programmed points are the part contour. With G41 (tool left of the path) or
//! G42 (right) the nose centre runs on the contour offset by the nose radius R;
//! the machine positions the imaginary tip, which sits at the nose centre plus
//! R times the tip direction's vector (figure 2.63: 1 = +X+Z, 2 = +X−Z, 3 = −X−Z,
//! 4 = −X+Z, 5 = +Z, 6 = +X, 7 = −Z, 8 = −X, 0 and 9 = the centre itself).
//!
//! Corners follow 2.18.3 by the angle α on the work side: 180° ≤ α (the tool inside
//! the corner) shortens both offset elements to their crossing; 90° ≤ α < 180°
//! lengthens them along their tangents to where those cross; α < 90° inserts a
//! line between the two elements each extended by R. Start-up (the first move
//! after G41/G42, a line from the uncompensated point) and cancel (the G40 move, a
//! line to the uncompensated point) use the same corner rules with the offset of
//! the start-up or cancel line. A G40 or a temporary cancel without a move ends
//! the held move on its normal.

use super::{Buffer, in_plane, moved_to};
use crate::alarm::AlarmKind;
use crate::axis::Pos;
use crate::canon::{Action, ArcMove, Canon, Move, Plane, SpindleSpeed};
use crate::geom::path::{Elem, V2, intersect, nearest, tip_vector, wrap_tau};
use crate::modal::lookahead::Waiting;
pub use crate::modal::lookahead::{Comp, Side};
use crate::stage::Staged;

/// Most vertices one corner inserts between two elements.
const MIDS: usize = 3;

/// A corner resolved: where the incoming element's offset ends, the points of the
/// lines inserted after it, and where the outgoing element's offset starts.
#[derive(Debug)]
struct Join {
    end1: V2,
    mids: heapless::Vec<V2, MIDS>,
    start2: V2,
}

/// Below this work-side angle the corner alarms (2.18.4 note 1: 0.1°).
const MIN_ALPHA_DEG: f64 = 0.1;

impl Comp {
    /// Signed offset: positive to the left of travel.
    fn d(&self) -> f64 {
        let r = self.radius as f64;
        if self.side == Some(Side::Left) { r } else { -r }
    }

    /// The vector from the nose centre to the imaginary tip in plane coordinates
    /// (tips 1–8 only in G18, 2.18.1 note).
    fn tip_vector(&self) -> V2 {
        if self.plane != Plane::Zx {
            return V2::new(0.0, 0.0);
        }
        tip_vector(self.tip, self.radius)
    }

    /// The corner between `e1` and `e2` (2.18.3).
    fn join(&self, e1: &Elem, e2: &Elem) -> Result<Join, AlarmKind> {
        let d = self.d();
        let (o1, o2) = (offset(e1, d)?, offset(e2, d)?);
        let (t1, t2) = (e1.end_tangent(), e2.start_tangent());
        let turn = libm::atan2(t1.cross(t2), t1.dot(t2));
        let mut mids = heapless::Vec::new();
        if libm::fabs(turn) < 1e-9 {
            return Ok(Join { end1: o1.end(), mids, start2: o2.start() });
        }
        let inner = turn * d > 0.0;
        let outer_deg = libm::fabs(turn).to_degrees();
        // The path turning (almost) straight back: no corner angle left.
        if 180.0 - outer_deg < MIN_ALPHA_DEG {
            return Err(AlarmKind::NoseCompCornerAngle);
        }
        let line1 = matches!(e1, Elem::Line { .. });
        let line2 = matches!(e2, Elem::Line { .. });
        if inner {
            let x = nearest(&intersect(&o1, &o2), e1.end()).ok_or(AlarmKind::NoseCompGouge)?;
            return Ok(Join { end1: x, mids, start2: x });
        }
        let (p1, p2) = (o1.end(), o2.start());
        let (a, b) = if outer_deg <= 90.0 {
            // Lengthening: the tangents at the offset points, crossed.
            let l1 = Elem::Line { start: p1, end: p1.plus(t1) };
            let l2 = Elem::Line { start: p2, end: p2.plus(t2) };
            let x = intersect(&l1, &l2).first().copied().ok_or(AlarmKind::NoseCompGouge)?;
            (x, x)
        } else {
            // Insertion: each extended by R along its tangent, joined by a line.
            let r = libm::fabs(d);
            (p1.plus(t1.scale(r)), p2.minus(t2.scale(r)))
        };
        let end1 = if line1 { a } else { p1 };
        if !line1 {
            let _ = mids.push(a);
        }
        if b != a {
            let _ = mids.push(b);
        }
        if !line2 {
            let _ = mids.push(p2);
        }
        let start2 = if line2 { b } else { p2 };
        Ok(Join { end1, mids, start2 })
    }
}

/// The offset of `e` (alarm 3605 if an arc's radius would vanish: the nose does
/// not fit inside it).
#[inline(never)]
fn offset(e: &Elem, d: f64) -> Result<Elem, AlarmKind> {
    e.offset(d).ok_or(AlarmKind::NoseCompGouge)
}

/// The path element of a motion action from `start` in `plane`.
pub(super) fn elem(a: &Action, start: Pos, plane: Plane) -> Result<Elem, AlarmKind> {
    let s = in_plane(&start, plane);
    let Some(to) = a.endpoint() else { return Err(AlarmKind::NoseCompGouge) };
    let e = match a {
        Action::Arc(m) if m.plane != plane => return Err(AlarmKind::NoseCompPlaneChange),
        Action::Arc(m) => Elem::Arc {
            start: s,
            end: in_plane(&to.machine, plane),
            center: in_plane(&m.center.machine, plane),
            ccw: !m.cw,
        },
        _ => Elem::Line { start: s, end: in_plane(&to.machine, plane) },
    };
    // A move with no length in the plane has no direction to offset from.
    if e.length() < 1.0 {
        return Err(AlarmKind::NoseCompGouge);
    }
    Ok(e)
}

/// Starts compensating with the move `c` from `start`: the tool's tip is still on
/// the programmed start point. Arcs cannot start up (2.18.3).
pub(super) fn start_up(buf: &mut Buffer, comp: &mut Comp, c: Canon, start: Pos) -> Result<(), AlarmKind> {
    let e = elem(&c.action, start, comp.plane)?;
    if matches!(e, Elem::Arc { .. }) {
        return Err(AlarmKind::NoseCompArc);
    }
    let centre = in_plane(&start, comp.plane).minus(comp.tip_vector());
    comp.engaged = true;
    comp.starting = true;
    comp.off_path = false;
    comp.centre = centre.round();
    buf.hold(c, start);
    Ok(())
}

/// The held move meets the next compensated move `next` (from `from`): the held
/// move is emitted to its corner point, then the corner's lines and the actions
/// waiting behind it; `next` becomes the held move.
pub(super) fn advance(
    buf: &mut Buffer,
    comp: &mut Comp,
    next: Canon,
    from: Pos,
    out: &mut Staged<'_>,
) -> Result<(), AlarmKind> {
    let e2 = elem(&next.action, from, comp.plane)?;
    let start2 = emit_to_corner(buf, comp, Some(&e2), out)?;
    comp.centre = start2.round();
    comp.starting = false;
    buf.hold(next, from);
    Ok(())
}

/// The cancel move `last` (G40 with a line, from `from`): the held move ends at
/// its corner with the cancel line's offset, then `last` runs to its programmed
/// point uncompensated. Arcs cannot cancel (2.18.3).
pub(super) fn cancel_with(
    buf: &mut Buffer,
    comp: &mut Comp,
    last: Canon,
    from: Pos,
    out: &mut Staged<'_>,
) -> Result<(), AlarmKind> {
    let e = elem(&last.action, from, comp.plane)?;
    if matches!(e, Elem::Arc { .. }) {
        return Err(AlarmKind::NoseCompArc);
    }
    if buf.is_holding() {
        emit_to_corner(buf, comp, Some(&e), out)?;
    }
    put(out, last)
}

/// Ends the held move on its normal (G40 or a temporary cancel without a move),
/// and emits what waits behind it. The tool then stands off the programmed path,
/// at the held move's offset end point (`comp.centre`, `comp.off_path`).
pub(super) fn end_here(buf: &mut Buffer, comp: &mut Comp, out: &mut Staged<'_>) -> Result<(), AlarmKind> {
    if buf.is_holding() {
        let end = emit_to_corner(buf, comp, None, out)?;
        comp.centre = end.round();
        comp.off_path = true;
    }
    comp.engaged = false;
    Ok(())
}

/// Whether move `a` from `start` moves in `plane` (else it moves only along the
/// other axes: a plunge or retract of a mill).
pub(super) fn in_plane_move(a: &Action, start: Pos, plane: Plane) -> bool {
    let Some(to) = a.endpoint() else { return false };
    matches!(a, Action::Arc(_)) || in_plane(&to.machine, plane).minus(in_plane(&start, plane)).len() >= 1.0
}

/// A move along the plane's normal while compensating: behind the held move (made
/// at its corner), or — with the tool off the path after a temporary cancel or a
/// G40 — where the tool stands; before start-up as it is. Returns false for a move
/// that changes another axis too (the caller alarms as for a move without length).
pub(super) fn plunge(
    buf: &mut Buffer,
    comp: &Comp,
    c: Canon,
    start: Pos,
    out: &mut Staged<'_>,
) -> Result<bool, AlarmKind> {
    // Only a mill plunges (this leaves the code out of a build without the profile).
    if !crate::MILL {
        return Ok(false);
    }
    let Some(to) = c.action.endpoint() else { return Ok(false) };
    let normal = comp.plane.normal();
    let only_normal = crate::axis::Axis::ALL.into_iter().all(|a| a == normal || to.machine[a] == start[a]);
    if !only_normal {
        return Ok(false);
    }
    if comp.engaged && buf.is_holding() {
        return buf.push_plunge(c, normal);
    }
    if !comp.off_path {
        put(out, c)?;
        return Ok(true);
    }
    let to = moved_to(*to, comp.plane, V2::of(comp.centre).plus(comp.tip_vector()));
    let action = match c.action {
        Action::Rapid(m) => Action::Rapid(Move { to, ..m }),
        Action::Linear(m) => Action::Linear(Move { to, ..m }),
        _ => return Ok(false),
    };
    put(out, Canon { line: c.line, action })?;
    Ok(true)
}

/// Emits the held move to its corner point with `e2` (or to its offset end point
/// without one), the corner's lines and the waiting actions; returns where the
/// next element's offset starts.
fn emit_to_corner(buf: &mut Buffer, comp: &Comp, e2: Option<&Elem>, out: &mut Staged<'_>) -> Result<V2, AlarmKind> {
    let start = buf.start;
    let (held, after) = buf.take();
    let Some(held) = held else { return Ok(V2::of(comp.centre)) };
    let e1 = elem(&held.action, start, comp.plane)?;
    let join = match e2 {
        Some(e2) => comp.join(&e1, e2)?,
        None => {
            let o1 = offset(&e1, comp.d())?;
            Join { end1: o1.end(), mids: heapless::Vec::new(), start2: o1.end() }
        }
    };
    if let Err(e) = check_direction(&e1, comp, V2::of(comp.centre), join.end1) {
        out.faulty_move = Some(held.line);
        return Err(e);
    }
    let tip = comp.tip_vector();
    // Nothing is emitted for a piece of no length (a corner point on top of the last).
    let mut last = V2::of(comp.centre);
    if matches!(e1, Elem::Arc { .. }) || join.end1.minus(last).len() >= 0.5 {
        put(out, Canon { line: held.line, action: shifted(held.action, comp.plane, join.end1, tip) })?;
        last = join.end1;
    }
    for m in &join.mids {
        if m.minus(last).len() >= 0.5 {
            put(out, Canon { line: held.line, action: line_from(&held.action, comp.plane, m.plus(tip)) })?;
            last = *m;
        }
    }
    emit_waiting(after, &held.action, comp, last.plus(tip), out)?;
    Ok(join.start2)
}

/// Emits what waited behind `held` once the tool stands at `tool` (in the plane):
/// a mill's plunge moves from there along the plane's normal.
fn emit_waiting(
    after: impl Iterator<Item = Waiting>,
    held: &Action,
    comp: &Comp,
    tool: V2,
    out: &mut Staged<'_>,
) -> Result<(), AlarmKind> {
    if !crate::MILL {
        // Without the mill profile nothing but non-motion actions wait.
        return after.into_iter().try_for_each(|c| put(out, c.plain()));
    }
    let at = moved_to(*held.endpoint().ok_or(AlarmKind::NoseCompGouge)?, comp.plane, tool);
    let spindle = spindle_of(held);
    for c in after {
        put(out, c.canon(&at, comp.plane.normal(), spindle))?;
    }
    Ok(())
}

/// The spindle speed a move runs at (what a plunge behind it runs at too).
fn spindle_of(a: &Action) -> SpindleSpeed {
    match a {
        Action::Rapid(m) | Action::Linear(m) => m.spindle,
        Action::Arc(m) => m.spindle,
        Action::Thread(t) => t.spindle,
        Action::Tap(t) => t.spindle,
        _ => SpindleSpeed { rpm: None, css: None, max_rpm: 0 },
    }
}

/// Alarm 3605 when the offset element from `from` to `to` runs against the
/// programmed one (2.18.4 criterion 1): the nose would cut back into the part.
fn check_direction(e: &Elem, comp: &Comp, from: V2, to: V2) -> Result<(), AlarmKind> {
    if !comp.engaged || comp.starting {
        return Ok(());
    }
    match *e {
        Elem::Line { start, end } => {
            let (p, q) = (end.minus(start), to.minus(from));
            if q.len() > 1.0 && p.dot(q) < 0.0 {
                return Err(AlarmKind::NoseCompGouge);
            }
        }
        Elem::Arc { start, end, center, ccw } => {
            let sweep = |a: V2, b: V2| {
                let t = b.minus(center).angle() - a.minus(center).angle();
                wrap_tau(if ccw { t } else { -t })
            };
            let programmed = sweep(start, end);
            if to.minus(from).len() > 1.0 && programmed > 0.0 {
                let travelled = sweep(from, to);
                // The offset arc turns the other way round (or nearly all the way).
                if travelled - programmed > core::f64::consts::PI {
                    return Err(AlarmKind::NoseCompGouge);
                }
            }
        }
    }
    Ok(())
}

/// The held action ending at nose-centre point `p` (+ the tip vector); an arc's
/// centre moves by the tip vector.
fn shifted(a: Action, plane: Plane, p: V2, tip: V2) -> Action {
    let moved = super::corner::retarget(a, plane, p.plus(tip));
    match moved {
        Action::Arc(m) => {
            let c = in_plane(&m.center.machine, plane).plus(tip);
            Action::Arc(ArcMove { center: moved_to(m.center, plane, c), ..m })
        }
        Action::Thread(t) => {
            let to = moved_to(t.to, plane, p.plus(tip));
            Action::Thread(crate::canon::ThreadMove { to, ..t })
        }
        Action::Tap(t) => {
            let to = moved_to(t.to, plane, p.plus(tip));
            Action::Tap(crate::canon::TapMove { to, ..t })
        }
        other => other,
    }
}

/// A straight corner move to `p` in the style of `held` (rapid stays rapid).
fn line_from(held: &Action, plane: Plane, p: V2) -> Action {
    match *held {
        Action::Rapid(m) => Action::Rapid(Move { to: moved_to(m.to, plane, p), ..m }),
        Action::Linear(m) => Action::Linear(Move { to: moved_to(m.to, plane, p), ..m }),
        Action::Arc(m) => Action::Linear(Move {
            to: moved_to(m.to, plane, p),
            feed: m.feed,
            spindle: m.spindle,
            exact_stop: m.exact_stop,
            independent: false,
        }),
        Action::Thread(t) => Action::Thread(crate::canon::ThreadMove { to: moved_to(t.to, plane, p), ..t }),
        Action::Tap(t) => Action::Tap(crate::canon::TapMove { to: moved_to(t.to, plane, p), ..t }),
        other => other,
    }
}

fn put(out: &mut Staged<'_>, c: Canon) -> Result<(), AlarmKind> {
    out.actions.push_back(c).map_err(|_| AlarmKind::Overflow)
}

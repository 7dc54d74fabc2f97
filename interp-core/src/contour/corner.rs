//! Chamfer and corner R between two moves (2.23): where each move is cut back, and
//! the inserted straight or circular block.

use super::{Corner, in_plane, leaves_plane, moved_to};
use crate::alarm::AlarmKind;
use crate::axis::{Axis, Pos};
use crate::canon::{Action, ArcMove, Canon, Endpoint, Feed, Move, Plane, SpindleSpeed};
use crate::geom::path::{Elem, V2, intersect, nearest};

/// Two moves meeting within this angle need no corner block (2.23 note 5: ±1°).
const STRAIGHT_DEG: f64 = 1.0;

/// How far (nm) a cut-back point may fall outside its move before it is an alarm:
/// the rounding of the programmed points.
const SLACK: f64 = 0.5;

/// The corner shaped: the first move cut back (`None` if nothing is left of it),
/// the inserted block, and where the second move now starts.
pub(super) struct Shaped {
    pub trimmed: Option<Canon>,
    pub insert: Option<Canon>,
    pub next_start: Pos,
}

/// Shapes `corner` between `first` (from `start`) and `next` in `plane`.
pub(super) fn shape(corner: Corner, plane: Plane, start: Pos, first: Canon, next: Canon) -> Result<Shaped, AlarmKind> {
    let (Some(p_ep), Some(n_ep)) = (first.action.endpoint().copied(), next.action.endpoint().copied()) else {
        return Err(AlarmKind::ChamferNoMove { what: "a block without a G01/G02/G03 move" });
    };
    let p = p_ep.machine;
    if leaves_plane(&start, &p, plane) || leaves_plane(&p, &n_ep.machine, plane) {
        return Err(AlarmKind::ChamferPlaneChange);
    }
    let e1 = elem(&first.action, start, plane)?;
    let e2 = elem(&next.action, p, plane)?;
    let (t1, t2) = (e1.end_tangent(), e2.start_tangent());
    let turn = libm::atan2(t1.cross(t2), t1.dot(t2));
    let unchanged = Shaped { trimmed: Some(first), insert: None, next_start: p };
    if libm::fabs(turn) <= STRAIGHT_DEG.to_radians() {
        return Ok(unchanged);
    }
    let (k1, k2, round) = match corner {
        Corner::Chamfer(c) => {
            let c = c as f64;
            (e1.back_from_end(c), e2.forward_from_start(c), None)
        }
        Corner::ChamferLength(h) => {
            // The chord between two points c from the corner, where the path turns
            // by `turn`, is 2·c·cos(turn/2).
            let c = h as f64 / (2.0 * crate::geom::sin_cos(turn / 2.0).1);
            if !c.is_finite() {
                return Err(AlarmKind::ChamferTooLarge);
            }
            (e1.back_from_end(c), e2.forward_from_start(c), None)
        }
        Corner::Round(r) => {
            let f = fillet_center(&e1, &e2, r as f64, turn > 0.0).ok_or(AlarmKind::ChamferTooLarge)?;
            (Some(e1.foot(f)), Some(e2.foot(f)), Some((f, turn < 0.0)))
        }
    };
    let (k1, k2) = (k1.ok_or(AlarmKind::ChamferTooLarge)?, k2.ok_or(AlarmKind::ChamferTooLarge)?);
    let left1 = e1.along(k1);
    let used2 = e2.along(k2);
    if !(-SLACK..=e1.length() + SLACK).contains(&left1) || !(-SLACK..=e2.length() + SLACK).contains(&used2) {
        return Err(AlarmKind::ChamferTooLarge);
    }
    let style = Style::of(&first.action);
    let trimmed = (left1 > SLACK).then(|| Canon { line: first.line, action: retarget(first.action, plane, k1) });
    let to = moved_to(p_ep, plane, k2);
    let spindle = style.spindle_at(to.work[Axis::X]);
    let action = match round {
        None => {
            Action::Linear(Move { to, feed: style.feed, spindle, exact_stop: style.exact_stop, independent: false })
        }
        Some((f, cw)) => Action::Arc(ArcMove {
            to,
            center: moved_to(to, plane, f),
            plane,
            cw,
            full_circle: false,
            feed: style.feed,
            spindle,
            exact_stop: style.exact_stop,
        }),
    };
    Ok(Shaped { trimmed, insert: Some(Canon { line: first.line, action }), next_start: to.machine })
}

/// Centre of the circle of radius `r` tangent to both elements on the inside of
/// the corner (`left` when the path turns left), nearest to the corner.
fn fillet_center(e1: &Elem, e2: &Elem, r: f64, left: bool) -> Option<V2> {
    let d = if left { r } else { -r };
    let (o1, o2) = (e1.offset(d)?, e2.offset(d)?);
    nearest(&intersect(&o1, &o2), e1.end())
}

/// The path element of a feed move starting at `start`.
fn elem(a: &Action, start: Pos, plane: Plane) -> Result<Elem, AlarmKind> {
    let s = in_plane(&start, plane);
    match a {
        Action::Linear(m) => Ok(Elem::Line { start: s, end: in_plane(&m.to.machine, plane) }),
        Action::Arc(arc) if arc.plane != plane => Err(AlarmKind::ChamferPlaneChange),
        Action::Arc(arc) if arc.full_circle => Err(AlarmKind::ChamferTooLarge),
        Action::Arc(arc) => Ok(Elem::Arc {
            start: s,
            end: in_plane(&arc.to.machine, plane),
            center: in_plane(&arc.center.machine, plane),
            ccw: !arc.cw,
        }),
        _ => Err(AlarmKind::ChamferNoMove { what: "a code other than G01/G02/G03" }),
    }
}

/// The feed, spindle and exact stop of the chamfered block, which the inserted
/// block inherits.
struct Style {
    feed: Feed,
    spindle: SpindleSpeed,
    exact_stop: bool,
}

impl Style {
    fn of(a: &Action) -> Style {
        match a {
            Action::Arc(m) => Style { feed: m.feed, spindle: m.spindle, exact_stop: m.exact_stop },
            Action::Linear(m) | Action::Rapid(m) => {
                Style { feed: m.feed, spindle: m.spindle, exact_stop: m.exact_stop }
            }
            _ => Style {
                feed: Feed { mode: crate::canon::FeedMode::PerMin, value: 0 },
                spindle: SpindleSpeed { rpm: None, css: None, max_rpm: 0 },
                exact_stop: false,
            },
        }
    }

    /// The commanded speed with the tool at work X radius `x` (G96 follows X).
    fn spindle_at(&self, x: i64) -> SpindleSpeed {
        respeed(self.spindle, x)
    }
}

fn respeed(s: SpindleSpeed, x: i64) -> SpindleSpeed {
    match (s.rpm, s.css) {
        (Some(_), Some(_)) => SpindleSpeed { rpm: s.rpm_at(x), ..s },
        _ => s,
    }
}

/// The move `a` ending at plane point `p` instead (an arc keeps its centre).
pub(super) fn retarget(a: Action, plane: Plane, p: V2) -> Action {
    let to_of = |to: Endpoint| moved_to(to, plane, p);
    match a {
        Action::Linear(m) => {
            let to = to_of(m.to);
            Action::Linear(Move { to, spindle: respeed(m.spindle, to.work[Axis::X]), ..m })
        }
        Action::Rapid(m) => Action::Rapid(Move { to: to_of(m.to), ..m }),
        Action::Arc(m) => {
            let to = to_of(m.to);
            Action::Arc(ArcMove { to, spindle: respeed(m.spindle, to.work[Axis::X]), ..m })
        }
        other => other,
    }
}

//! The real moves of polar coordinate interpolation (2.7): the virtual moves of a
//! block in the polar plane (after the contour layer) cut into short moves of X
//! (radius) and C (angle) whose path stays within the chord tolerance of the
//! Cartesian one, found by halving a piece while the polar move's points at ¼, ½
//! and ¾ stray from the Cartesian path. Each piece gets the feed that makes its
//! Cartesian speed F (2.7 note 5), the planner measuring C in µdeg as it does.

use super::Step;
use crate::alarm::AlarmKind;
use crate::axis::{Axis, Pos};
use crate::canon::{Action, Canon};
use crate::geom::path::to_polar;
use crate::geom::path::{Elem, V2};

/// Most virtual moves one block hands over (its own, a chamfer, the compensation's
/// corner lines and the move released from before).
pub const MOVES: usize = 6;

/// Deepest halving of one piece (a piece 2⁻¹⁶ of its move is always accepted).
const DEPTH: usize = 16;

/// One virtual move, kept small: where it ends, its arc centre, Z, feed and line;
/// it starts where the one before it ends.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct VMove {
    line: u32,
    end: (i64, i64),
    /// Arc centre and direction (counter-clockwise), `None` for a line.
    arc: Option<((i64, i64), bool)>,
    z: i64,
    feed: i64,
}

/// Cuts the virtual moves of one block into real ones.
#[derive(Clone, Debug, PartialEq)]
pub struct PolarGen {
    moves: heapless::Vec<VMove, MOVES>,
    at: usize,
    /// Where the current move starts (x, c, z), nm.
    from: (i64, i64, i64),
    /// Parameter reached along the current move, and the pieces' ends still to do.
    t: f64,
    stack: heapless::Vec<f64, DEPTH>,
    /// The last real point: X radius, C µdeg, Z (work), for continuity and feeds.
    last: (f64, f64, f64),
    tol: f64,
}

impl PolarGen {
    /// The generator for the virtual motion actions `acts`, starting at the real
    /// work position `start` (X radius, C µdeg).
    pub fn new(acts: &[Canon], start: Pos, tol: i64) -> Result<Self, AlarmKind> {
        let (r, c) = (start[Axis::X] as f64, start[Axis::C] as f64);
        let th = (c / 1e6).to_radians();
        let (sin, cos) = crate::geom::sin_cos(th);
        let from = (crate::geom::round_i64(r * cos), crate::geom::round_i64(r * sin), start[Axis::Z]);
        let mut moves = heapless::Vec::new();
        for a in acts {
            let Some(to) = a.action.endpoint() else { continue };
            let end = (to.work[Axis::X], to.work[Axis::Y]);
            let (arc, feed) = match a.action {
                Action::Arc(m) => (Some(((m.center.work[Axis::X], m.center.work[Axis::Y]), !m.cw)), m.feed),
                Action::Linear(m) | Action::Rapid(m) => (None, m.feed),
                _ => return Err(AlarmKind::PolarCodeNotAllowed { code: crate::alarm::GNum(0) }),
            };
            let v = VMove { line: a.line, end, arc, z: to.work[Axis::Z], feed: feed.value };
            moves.push(v).map_err(|_| AlarmKind::ContourBufferFull)?;
        }
        Ok(PolarGen {
            moves,
            at: 0,
            from,
            t: 0.0,
            stack: heapless::Vec::new(),
            last: (r, c, start[Axis::Z] as f64),
            tol: tol.max(1) as f64,
        })
    }

    /// Queues the next real moves; false when all are queued.
    pub fn fill(&mut self, queue: &mut super::StepQueue) -> Result<bool, AlarmKind> {
        while !queue.is_full() {
            let Some(m) = self.moves.get(self.at).copied() else { return Ok(false) };
            let path = Path::of(self.from, &m);
            if self.stack.is_empty() {
                let _ = self.stack.push(1.0);
            }
            let Some(&t1) = self.stack.last() else { continue };
            let mid = (self.t + t1) / 2.0;
            if self.stack.len() < DEPTH && self.strays(&path, self.t, t1) {
                let _ = self.stack.push(mid);
                continue;
            }
            self.stack.pop();
            if let Some(step) = self.piece(&path, &m, self.t, t1) {
                queue.push_back(step).map_err(|_| AlarmKind::Overflow)?;
            }
            self.t = t1;
            if t1 >= 1.0 {
                self.at += 1;
                self.t = 0.0;
                self.stack.clear();
                self.from = (m.end.0, m.end.1, m.z);
            }
        }
        Ok(self.at < self.moves.len())
    }

    /// Whether the straight polar move from `t0` to `t1` leaves the Cartesian path
    /// by more than the tolerance.
    fn strays(&self, path: &Path, t0: f64, t1: f64) -> bool {
        let (p0, p1) = (path.at(t0), path.at(t1));
        let q0 = to_polar(p0, self.last.1);
        let q1 = to_polar(p1, q0.1);
        [0.25, 0.5, 0.75].into_iter().any(|f| {
            let r = q0.0 + f * (q1.0 - q0.0);
            let th = ((q0.1 + f * (q1.1 - q0.1)) / 1e6).to_radians();
            let (s, c) = crate::geom::sin_cos(th);
            let real = V2::new(r * c, r * s);
            real.minus(path.at(t0 + f * (t1 - t0))).len() > self.tol
        })
    }

    /// The real move to parameter `t1` of `m`, with its Cartesian feed; `None` when
    /// it goes nowhere.
    fn piece(&mut self, path: &Path, m: &VMove, t0: f64, t1: f64) -> Option<Step> {
        let p1 = path.at(t1);
        let (r, c) = to_polar(p1, self.last.1);
        let z = path.z.0 + t1 * (path.z.1 - path.z.0);
        let (lr, lc, lz) = self.last;
        let planner = libm::sqrt((r - lr) * (r - lr) + (c - lc) * (c - lc) + (z - lz) * (z - lz));
        let cart = {
            let d = p1.minus(path.at(t0));
            libm::sqrt(d.dot(d) + (z - lz) * (z - lz))
        };
        self.last = (r, c, z);
        if planner < 0.5 || cart <= 0.0 {
            return None;
        }
        let feed = libm::round(m.feed as f64 * planner / cart).max(1.0) as i64;
        let round = |v: f64| crate::geom::round_i64(v);
        Some(Step::PolarFeed { x: round(r), c: round(c), z: round(z), feed, line: m.line })
    }
}

/// A virtual move as a path element with its Z.
struct Path {
    elem: Elem,
    z: (f64, f64),
}

impl Path {
    fn of(from: (i64, i64, i64), m: &VMove) -> Path {
        let v = |p: (i64, i64)| V2::new(p.0 as f64, p.1 as f64);
        let (start, end) = (v((from.0, from.1)), v(m.end));
        let elem = match m.arc {
            Some((c, ccw)) => Elem::Arc { start, end, center: v(c), ccw },
            None => Elem::Line { start, end },
        };
        Path { elem, z: (from.2 as f64, m.z as f64) }
    }

    /// The Cartesian point at parameter `t`.
    #[inline(never)]
    fn at(&self, t: f64) -> V2 {
        self.elem.point_at(t * self.elem.length())
    }
}

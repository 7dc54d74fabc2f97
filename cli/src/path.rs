//! The motion actions of a run as path segments with their start points, and the
//! geometry the summary, the cycle time and the drawing share: lengths, points
//! along a move, arc angles and bounding boxes. Work coordinates, internal units
//! (nm, X as a radius), as `f64` where geometry needs it.

use std::f64::consts::{PI, TAU};

use interp_core::canon::{Action, ArcMove, Canon, Endpoint, Move, Plane, TapMove, ThreadMove};
use interp_core::geom::arc_extents;
use interp_core::{Axis, MachineConfig, Pos};

/// A motion action.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Motion {
    /// G00 positioning.
    Rapid(Move),
    /// G01 cutting.
    Linear(Move),
    /// G02/G03 cutting.
    Arc(ArcMove),
    /// Spindle-synchronised thread cutting.
    Thread(ThreadMove),
    /// Rigid tapping.
    Tap(TapMove),
}

impl Motion {
    /// The motion of an action, if it is one.
    pub fn of(action: &Action) -> Option<Motion> {
        match *action {
            Action::Rapid(m) => Some(Motion::Rapid(m)),
            Action::Linear(m) => Some(Motion::Linear(m)),
            Action::Arc(a) => Some(Motion::Arc(a)),
            Action::Thread(t) => Some(Motion::Thread(t)),
            Action::Tap(t) => Some(Motion::Tap(t)),
            _ => None,
        }
    }

    /// Where the motion ends.
    pub fn to(&self) -> &Endpoint {
        match self {
            Motion::Rapid(m) | Motion::Linear(m) => &m.to,
            Motion::Arc(a) => &a.to,
            Motion::Thread(t) => &t.to,
            Motion::Tap(t) => &t.to,
        }
    }
}

/// A motion with where it starts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    /// Source line of the block.
    pub line: u32,
    /// Start point in the work coordinates of the move (the frame and tool offset
    /// the move runs in, so a tool change between moves shows where the tip was).
    pub from: Pos,
    /// The motion.
    pub motion: Motion,
}

/// The motions of `actions` as segments; the axes stand at machine position `start` before the first.
pub fn segments(start: Pos, actions: &[Canon]) -> Vec<Segment> {
    let mut machine = start;
    let mut out = Vec::new();
    for c in actions {
        if let Some(motion) = Motion::of(&c.action) {
            let to = motion.to();
            let shift = to.machine - to.work;
            out.push(Segment { line: c.line, from: machine - shift, motion });
            machine = to.machine;
        }
    }
    out
}

/// Components of a position used for lengths: X (radius), Y, Z in nm.
const LINEAR_AXES: [Axis; 3] = [Axis::X, Axis::Y, Axis::Z];

impl Segment {
    /// End point, work coordinates.
    pub fn to(&self) -> Pos {
        self.motion.to().work
    }

    /// The corners of a straight move: start, end, and between them, for a rapid
    /// with independent axes, each point where an axis arrives (the dog-leg).
    pub fn vertices(&self, cfg: &MachineConfig) -> Vec<Pos> {
        let mut v = vec![self.from];
        if let Motion::Rapid(m) = &self.motion
            && m.independent
        {
            v.extend(dogleg_corners(self.from, self.to(), cfg));
        }
        v.push(self.to());
        v
    }

    /// Path length in nm (X, Y, Z; a move of C alone counts its micro-degrees).
    pub fn length(&self, cfg: &MachineConfig) -> f64 {
        if let Motion::Arc(a) = &self.motion {
            return ArcPath::new(self.from, a).length();
        }
        let v = self.vertices(cfg);
        let linear: f64 = v.windows(2).map(|w| distance(w[0], w[1])).sum();
        if linear > 0.0 { linear } else { ((self.to() - self.from)[Axis::C] as f64).abs() }
    }

    /// The point at fraction `t` (0 = start, 1 = end) of a cutting move (straight
    /// or arc). A dog-leg rapid's corners are not followed: rapids need no points.
    pub fn point(&self, t: f64) -> Pos {
        match &self.motion {
            Motion::Arc(a) => ArcPath::new(self.from, a).point(t),
            _ => lerp(self.from, self.to(), t),
        }
    }

    /// The box of X (radius) and Z the move sweeps through, nm.
    pub fn bounds(&self) -> Bounds {
        let mut b = Bounds::point(self.from);
        b.add(self.to());
        if let Motion::Arc(a) = &self.motion {
            b.add_arc(self.from, a);
        }
        b
    }
}

/// Straight-line distance of X (radius), Y and Z, nm.
fn distance(p: Pos, q: Pos) -> f64 {
    let d = q - p;
    LINEAR_AXES.iter().map(|&a| d[a] as f64).map(|v| v * v).sum::<f64>().sqrt()
}

/// Where a rapid with independent axes turns: every axis runs at its own rapid
/// rate, so the path bends each time one arrives before the last.
fn dogleg_corners(from: Pos, to: Pos, cfg: &MachineConfig) -> Vec<Pos> {
    let d = to - from;
    let rate = |a: Axis| cfg.axis(a).rapid_per_min as f64;
    let moving = || Axis::ALL.into_iter().filter(|&a| d[a] != 0 && rate(a) > 0.0);
    let mut times: Vec<f64> = moving().map(|a| d[a].unsigned_abs() as f64 / rate(a)).collect();
    times.sort_by(f64::total_cmp);
    times.dedup();
    times.pop(); // the last axis to arrive ends the move
    let at = |t: f64| {
        let mut p = to;
        for a in moving() {
            let travel = ((rate(a) * t).round() as i64).min(d[a].saturating_abs());
            p[a] = from[a].saturating_add(d[a].signum() * travel);
        }
        p
    };
    times.into_iter().map(at).collect()
}

/// A straight-line interpolation between two positions.
fn lerp(p: Pos, q: Pos, t: f64) -> Pos {
    Pos(core::array::from_fn(|i| p.0[i].saturating_add(((q.0[i] as f64 - p.0[i] as f64) * t).round() as i64)))
}

/// An arc in its plane: coordinates `(a, b)` of [`Plane::axes`], where G02 runs
/// clockwise (negative angles) with `a` to the right and `b` up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArcPath {
    /// The start point (axes outside the plane keep its values).
    pub from: Pos,
    /// The plane.
    pub plane: Plane,
    /// Centre `(a, b)`, nm.
    pub center: (f64, f64),
    /// Radius, nm (from the start point).
    pub radius: f64,
    /// Angle of the start point, radians.
    pub start: f64,
    /// Signed sweep, radians: negative clockwise; ±2π for a full circle.
    pub sweep: f64,
}

impl ArcPath {
    /// The geometry of `arc` starting at work position `from`.
    pub fn new(from: Pos, arc: &ArcMove) -> Self {
        let (pa, pb) = arc.plane.axes();
        let center = (arc.center.work[pa] as f64, arc.center.work[pb] as f64);
        let angle = |p: &Pos| (p[pb] as f64 - center.1).atan2(p[pa] as f64 - center.0);
        let (s, e) = (angle(&from), angle(&arc.to.work));
        let mut sweep = if arc.cw { (s - e).rem_euclid(TAU) } else { (e - s).rem_euclid(TAU) };
        if arc.full_circle || sweep == 0.0 {
            sweep = TAU;
        }
        let radius = (from[pa] as f64 - center.0).hypot(from[pb] as f64 - center.1);
        ArcPath { from, plane: arc.plane, center, radius, start: s, sweep: if arc.cw { -sweep } else { sweep } }
    }

    /// Arc length, nm.
    pub fn length(&self) -> f64 {
        self.radius * self.sweep.abs()
    }

    /// Whether the arc turns through more than half a circle.
    pub fn large(&self) -> bool {
        self.sweep.abs() > PI
    }

    /// The point at fraction `t` of the sweep.
    pub fn point(&self, t: f64) -> Pos {
        let (pa, pb) = self.plane.axes();
        let ang = self.start + self.sweep * t;
        let mut p = self.from;
        p[pa] = (self.center.0 + self.radius * ang.cos()).round() as i64;
        p[pb] = (self.center.1 + self.radius * ang.sin()).round() as i64;
        p
    }
}

/// A box in X (radius) and Z, nm.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Bounds {
    /// Least and greatest X (radius).
    pub x: (i64, i64),
    /// Least and greatest Z.
    pub z: (i64, i64),
}

impl Bounds {
    /// The box of a single point.
    pub fn point(p: Pos) -> Self {
        Bounds { x: (p[Axis::X], p[Axis::X]), z: (p[Axis::Z], p[Axis::Z]) }
    }

    /// Grows the box to hold `p`.
    pub fn add(&mut self, p: Pos) {
        self.x = (self.x.0.min(p[Axis::X]), self.x.1.max(p[Axis::X]));
        self.z = (self.z.0.min(p[Axis::Z]), self.z.1.max(p[Axis::Z]));
    }

    /// Grows the box to hold `o`.
    pub fn union(&mut self, o: &Bounds) {
        self.x = (self.x.0.min(o.x.0), self.x.1.max(o.x.1));
        self.z = (self.z.0.min(o.z.0), self.z.1.max(o.z.1));
    }

    /// Grows the box to hold the quadrant points an arc passes.
    fn add_arc(&mut self, from: Pos, arc: &ArcMove) {
        let (pa, pb) = arc.plane.axes();
        let p2 = |p: &Pos| (p[pa], p[pb]);
        let center = p2(&arc.center.work);
        let e = arc_extents(p2(&from), p2(&arc.to.work), center, arc.cw, arc.full_circle);
        for (axis, range) in [(pa, e.a), (pb, e.b)] {
            for v in [range.0, range.1] {
                let mut p = from;
                p[axis] = v;
                self.add(p);
            }
        }
    }

    /// The box of every segment, or `None` without segments.
    pub fn of(segments: &[Segment]) -> Option<Bounds> {
        let mut it = segments.iter().map(Segment::bounds);
        let mut b = it.next()?;
        for s in it {
            b.union(&s);
        }
        Some(b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use interp_core::canon::{Feed, FeedMode, SpindleSpeed};

    const MM: i64 = 1_000_000;

    fn ep(x: i64, z: i64) -> Endpoint {
        Endpoint { machine: Pos::xz(x, z), work: Pos::xz(x, z) }
    }

    fn arc(to: Endpoint, center: Endpoint, cw: bool) -> ArcMove {
        ArcMove {
            to,
            center,
            plane: Plane::Zx,
            cw,
            full_circle: false,
            feed: Feed { mode: FeedMode::PerMin, value: 100 * MM },
            spindle: SpindleSpeed { rpm: None, css: None, max_rpm: 3000 },
            exact_stop: false,
        }
    }

    #[test]
    fn a_clockwise_quarter_passes_below_and_left_of_its_centre() {
        // G02 from (X0 Z0) to (X20 Z-10) R10: centre at X radius 10, Z 0.
        let a = arc(ep(10 * MM, -10 * MM), ep(10 * MM, 0), true);
        let p = ArcPath::new(Pos::xz(0, 0), &a);
        assert!((p.sweep + PI / 2.0).abs() < 1e-12);
        assert!((p.length() - 10.0 * MM as f64 * PI / 2.0).abs() < 1.0);
        let mid = p.point(0.5);
        assert!(mid[Axis::Z] < 0 && mid[Axis::X] < 10 * MM);
        let b = Segment { line: 1, from: Pos::xz(0, 0), motion: Motion::Arc(a) }.bounds();
        assert_eq!(b, Bounds { x: (0, 10 * MM), z: (-10 * MM, 0) });
    }

    #[test]
    fn a_counter_clockwise_half_circle_bulges_to_plus_x() {
        // G03 from Z10 to Z-10 at X radius 0 around Z0: passes X radius +10.
        let a = arc(ep(0, -10 * MM), ep(0, 0), false);
        let s = Segment { line: 1, from: Pos::xz(0, 10 * MM), motion: Motion::Arc(a) };
        assert_eq!(s.bounds(), Bounds { x: (0, 10 * MM), z: (-10 * MM, 10 * MM) });
        assert_eq!(s.point(0.5), Pos::xz(10 * MM, 0));
    }

    #[test]
    fn an_independent_rapid_bends_where_the_quicker_axis_arrives() {
        // X radius 60 mm at 6 m/min arrives after 0.6 s; Z has run 80 mm at 8 m/min by then.
        let cfg = MachineConfig::default();
        let to = ep(0, 0);
        let m = Move {
            to,
            feed: Feed { mode: FeedMode::PerMin, value: 0 },
            spindle: SpindleSpeed { rpm: None, css: None, max_rpm: 3000 },
            exact_stop: true,
            independent: true,
        };
        let s = Segment { line: 1, from: Pos::xz(60 * MM, 200 * MM), motion: Motion::Rapid(m) };
        assert_eq!(s.vertices(&cfg), [Pos::xz(60 * MM, 200 * MM), Pos::xz(0, 120 * MM), Pos::xz(0, 0)]);
        let leg = (60.0f64.powi(2) + 80.0f64.powi(2)).sqrt() + 120.0;
        assert!((s.length(&cfg) - leg * MM as f64).abs() < 1e-6);
    }

    #[test]
    fn segments_start_where_the_machine_stood_in_the_new_frame() {
        let to = Endpoint { machine: Pos::xz(30 * MM, 10 * MM), work: Pos::xz(20 * MM, 0) };
        let m = Move {
            to,
            feed: Feed { mode: FeedMode::PerMin, value: 0 },
            spindle: SpindleSpeed { rpm: None, css: None, max_rpm: 3000 },
            exact_stop: true,
            independent: false,
        };
        let s = segments(Pos::xz(50 * MM, 60 * MM), &[Canon { line: 3, action: Action::Rapid(m) }]);
        assert_eq!(s[0].from, Pos::xz(40 * MM, 50 * MM));
        let cfg = MachineConfig::default();
        assert_eq!(s[0].length(&cfg), ((20.0f64).powi(2) + 50.0f64.powi(2)).sqrt() * MM as f64);
    }
}

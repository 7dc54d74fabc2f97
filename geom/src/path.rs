//! Plane path elements in f64 nanometres — lines and arcs with their tangents,
//! points at a distance, offsets and intersections — for the contour layer
//! (chamfers, corner rounding, tool-nose compensation). Coordinates are the
//! plane's `(a, b)` axes ([`canon::Plane::axes`]): G03 is counter-clockwise.
//!
//! The vector helpers marked `#[inline(never)]` (as are a few small helpers of the
//! cycles) stay out of line for flash: each is a handful of soft-f64 calls (the
//! Cortex-M4F has no f64 unit), and inlined at every use in the contour and cycle
//! code they cost the firmware ~12 KB. None runs for a plain motion block (the
//! m4-tests `bench_interp`/`bench_macro` counts are the same either way).

/// A point or vector in the plane, nm.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct V2 {
    /// First plane axis (Z in G18).
    pub a: f64,
    /// Second plane axis (X in G18).
    pub b: f64,
}

impl V2 {
    /// The point `(a, b)`.
    pub const fn new(a: f64, b: f64) -> V2 {
        V2 { a, b }
    }

    /// From integer nanometres.
    pub fn of(p: (i64, i64)) -> V2 {
        V2 { a: p.0 as f64, b: p.1 as f64 }
    }

    /// Rounded to integer nanometres.
    #[inline(never)]
    pub fn round(self) -> (i64, i64) {
        (libm::round(self.a) as i64, libm::round(self.b) as i64)
    }

    /// Sum.
    #[inline(never)]
    pub fn plus(self, o: V2) -> V2 {
        V2::new(self.a + o.a, self.b + o.b)
    }

    /// Difference.
    #[inline(never)]
    pub fn minus(self, o: V2) -> V2 {
        V2::new(self.a - o.a, self.b - o.b)
    }

    /// Scaled.
    #[inline(never)]
    pub fn scale(self, k: f64) -> V2 {
        V2::new(self.a * k, self.b * k)
    }

    /// Dot product.
    #[inline(never)]
    pub fn dot(self, o: V2) -> f64 {
        self.a * o.a + self.b * o.b
    }

    /// Cross product (positive when `o` is counter-clockwise of `self`).
    #[inline(never)]
    pub fn cross(self, o: V2) -> f64 {
        self.a * o.b - self.b * o.a
    }

    /// Length.
    pub fn len(self) -> f64 {
        libm::hypot(self.a, self.b)
    }

    /// Unit vector (zero stays zero).
    #[inline(never)]
    pub fn unit(self) -> V2 {
        let l = self.len();
        if l == 0.0 { self } else { self.scale(1.0 / l) }
    }

    /// Turned 90° counter-clockwise (the left normal of a direction).
    pub fn left(self) -> V2 {
        V2::new(-self.b, self.a)
    }

    /// Angle from the `a` axis, radians.
    pub fn angle(self) -> f64 {
        libm::atan2(self.b, self.a)
    }

    /// Rotated counter-clockwise by `t` radians.
    #[inline(never)]
    pub fn rotate(self, t: f64) -> V2 {
        let (s, c) = super::sin_cos(t);
        V2::new(self.a * c - self.b * s, self.a * s + self.b * c)
    }
}

/// A line or arc from `start` to `end`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Elem {
    /// Straight.
    Line {
        /// Start.
        start: V2,
        /// End.
        end: V2,
    },
    /// Circular around `center`; `ccw` for G03.
    Arc {
        /// Start.
        start: V2,
        /// End.
        end: V2,
        /// Centre.
        center: V2,
        /// Counter-clockwise (G03).
        ccw: bool,
    },
}

/// `x` wrapped into `[0, 2π)`.
#[inline(never)]
pub fn wrap_tau(x: f64) -> f64 {
    let tau = core::f64::consts::TAU;
    let r = super::fmod(x, tau);
    if r < 0.0 { r + tau } else { r }
}

impl Elem {
    /// Start point.
    pub fn start(&self) -> V2 {
        match *self {
            Elem::Line { start, .. } | Elem::Arc { start, .. } => start,
        }
    }

    /// End point.
    pub fn end(&self) -> V2 {
        match *self {
            Elem::Line { end, .. } | Elem::Arc { end, .. } => end,
        }
    }

    /// Unit direction of travel at point `p` (on the element).
    #[inline(never)]
    pub fn tangent_at(&self, p: V2) -> V2 {
        match *self {
            Elem::Line { start, end } => end.minus(start).unit(),
            Elem::Arc { center, ccw, .. } => {
                let r = p.minus(center).unit().left();
                if ccw { r } else { r.scale(-1.0) }
            }
        }
    }

    /// Direction of travel at the start.
    pub fn start_tangent(&self) -> V2 {
        self.tangent_at(self.start())
    }

    /// Direction of travel at the end.
    pub fn end_tangent(&self) -> V2 {
        self.tangent_at(self.end())
    }

    /// Arc radius (0 for a line).
    #[inline(never)]
    pub fn radius(&self) -> f64 {
        match *self {
            Elem::Line { .. } => 0.0,
            Elem::Arc { start, center, .. } => start.minus(center).len(),
        }
    }

    /// Angle travelled along an arc from `from` to `to` in its direction, `[0, 2π)`.
    #[inline(never)]
    fn travel(center: V2, ccw: bool, from: V2, to: V2) -> f64 {
        let d = to.minus(center).angle() - from.minus(center).angle();
        wrap_tau(if ccw { d } else { -d })
    }

    /// Length of the element along its path (a closed arc is a full circle).
    #[inline(never)]
    pub fn length(&self) -> f64 {
        match *self {
            Elem::Line { start, end } => end.minus(start).len(),
            Elem::Arc { start, end, center, ccw } => {
                let mut t = Self::travel(center, ccw, start, end);
                if t == 0.0 {
                    t = core::f64::consts::TAU;
                }
                t * self.radius()
            }
        }
    }

    /// How far along the element (0 at the start, path length) the point `p` lies,
    /// `p` being on the element's line or circle.
    #[inline(never)]
    pub fn along(&self, p: V2) -> f64 {
        match *self {
            Elem::Line { start, end } => p.minus(start).dot(end.minus(start).unit()),
            Elem::Arc { start, center, ccw, .. } => Self::travel(center, ccw, start, p) * self.radius(),
        }
    }

    /// The point `s` along the element from its start (path length).
    pub fn point_at(&self, s: f64) -> V2 {
        match *self {
            Elem::Line { start, end } => start.plus(end.minus(start).unit().scale(s)),
            Elem::Arc { start, center, ccw, .. } => {
                let r = self.radius();
                let t = if r > 0.0 { s / r } else { 0.0 };
                center.plus(start.minus(center).rotate(if ccw { t } else { -t }))
            }
        }
    }

    /// The points of the element's circle (arcs only) whose `a` (`on_a`) or `b`
    /// coordinate equals `v`.
    pub fn crossings_at(&self, on_a: bool, v: f64) -> heapless::Vec<V2, 2> {
        let mut out = heapless::Vec::new();
        let Elem::Arc { center, .. } = *self else { return out };
        let r = self.radius();
        let (c, o) = if on_a { (center.a, center.b) } else { (center.b, center.a) };
        let d = v - c;
        if d.abs() > r {
            return out;
        }
        let h = libm::sqrt(r * r - d * d);
        for k in [o - h, o + h] {
            let _ = out.push(if on_a { V2::new(v, k) } else { V2::new(k, v) });
        }
        out
    }

    /// The point at straight-line distance `d` from the end, back along the element
    /// (`None` if the element's circle has no such point).
    pub fn back_from_end(&self, d: f64) -> Option<V2> {
        match *self {
            Elem::Line { start, end } => Some(end.minus(end.minus(start).unit().scale(d))),
            Elem::Arc { end, center, ccw, .. } => {
                let phi = chord_angle(d, self.radius())?;
                Some(center.plus(end.minus(center).rotate(if ccw { -phi } else { phi })))
            }
        }
    }

    /// The point at straight-line distance `d` from the start, forward.
    pub fn forward_from_start(&self, d: f64) -> Option<V2> {
        match *self {
            Elem::Line { start, end } => Some(start.plus(end.minus(start).unit().scale(d))),
            Elem::Arc { start, center, ccw, .. } => {
                let phi = chord_angle(d, self.radius())?;
                Some(center.plus(start.minus(center).rotate(if ccw { phi } else { -phi })))
            }
        }
    }

    /// The element moved sideways by `d` (positive to the left of the direction of
    /// travel): a parallel line, or a concentric arc. `None` when an arc's radius
    /// would vanish or turn negative.
    pub fn offset(&self, d: f64) -> Option<Elem> {
        match *self {
            Elem::Line { start, end } => {
                let n = end.minus(start).unit().left().scale(d);
                Some(Elem::Line { start: start.plus(n), end: end.plus(n) })
            }
            Elem::Arc { start, end, center, ccw } => {
                let r = self.radius();
                // Left of a counter-clockwise arc is towards its centre.
                let nr = if ccw { r - d } else { r + d };
                if nr <= 0.0 {
                    return None;
                }
                let k = nr / r;
                Some(Elem::Arc {
                    start: center.plus(start.minus(center).scale(k)),
                    end: center.plus(end.minus(center).scale(k)),
                    center,
                    ccw,
                })
            }
        }
    }

    /// The point of the element's line or circle nearest to `p`.
    pub fn foot(&self, p: V2) -> V2 {
        match *self {
            Elem::Line { start, end } => {
                let u = end.minus(start).unit();
                start.plus(u.scale(p.minus(start).dot(u)))
            }
            Elem::Arc { center, .. } => center.plus(p.minus(center).unit().scale(self.radius())),
        }
    }
}

/// Angle an arc of radius `r` turns through for a chord of length `d`.
fn chord_angle(d: f64, r: f64) -> Option<f64> {
    let s = d / (2.0 * r);
    (r > 0.0 && s <= 1.0).then(|| 2.0 * libm::asin(s))
}

/// The crossings of the lines or circles of `e` and `f` (up to two).
pub fn intersect(e: &Elem, f: &Elem) -> heapless::Vec<V2, 2> {
    match (e, f) {
        (Elem::Line { start: p, end: q }, Elem::Line { start: r, end: s }) => line_line(*p, *q, *r, *s),
        (Elem::Line { start, end }, Elem::Arc { center, .. })
        | (Elem::Arc { center, .. }, Elem::Line { start, end }) => {
            let rad = if matches!(e, Elem::Arc { .. }) { e.radius() } else { f.radius() };
            line_circle(*start, *end, *center, rad)
        }
        (Elem::Arc { center: c1, .. }, Elem::Arc { center: c2, .. }) => circle_circle(*c1, e.radius(), *c2, f.radius()),
    }
}

fn line_line(p: V2, q: V2, r: V2, s: V2) -> heapless::Vec<V2, 2> {
    let mut out = heapless::Vec::new();
    let (d1, d2) = (q.minus(p), s.minus(r));
    let den = d1.cross(d2);
    if den.abs() > 1e-12 * d1.len() * d2.len() {
        let t = r.minus(p).cross(d2) / den;
        let _ = out.push(p.plus(d1.scale(t)));
    }
    out
}

fn line_circle(p: V2, q: V2, c: V2, r: f64) -> heapless::Vec<V2, 2> {
    let mut out = heapless::Vec::new();
    let u = q.minus(p).unit();
    let foot = p.plus(u.scale(c.minus(p).dot(u)));
    let h2 = r * r - foot.minus(c).dot(foot.minus(c));
    if h2 < 0.0 {
        return out;
    }
    let h = libm::sqrt(h2);
    let _ = out.push(foot.minus(u.scale(h)));
    let _ = out.push(foot.plus(u.scale(h)));
    out
}

fn circle_circle(c1: V2, r1: f64, c2: V2, r2: f64) -> heapless::Vec<V2, 2> {
    let mut out = heapless::Vec::new();
    let d = c2.minus(c1).len();
    if d == 0.0 || d > r1 + r2 + 1e-6 || d < (r1 - r2).abs() - 1e-6 {
        return out;
    }
    let a = (r1 * r1 - r2 * r2 + d * d) / (2.0 * d);
    let h = libm::sqrt((r1 * r1 - a * a).max(0.0));
    let u = c2.minus(c1).scale(1.0 / d);
    let m = c1.plus(u.scale(a));
    let _ = out.push(m.plus(u.left().scale(h)));
    let _ = out.push(m.minus(u.left().scale(h)));
    out
}

/// The one of `pts` nearest to `p`.
pub fn nearest(pts: &[V2], p: V2) -> Option<V2> {
    pts.iter().copied().min_by(|x, y| x.minus(p).len().total_cmp(&y.minus(p).len()))
}

/// The vector (G18 plane coordinates: Z, X) from the nose centre to the
/// imaginary tip of direction `tip` for a nose of `radius` nm (figure 2.63).
#[inline(never)]
pub fn tip_vector(tip: u8, radius: i64) -> V2 {
    let (x, z) = match tip {
        1 => (1.0, 1.0),
        2 => (1.0, -1.0),
        3 => (-1.0, -1.0),
        4 => (-1.0, 1.0),
        5 => (0.0, 1.0),
        6 => (1.0, 0.0),
        7 => (0.0, -1.0),
        8 => (-1.0, 0.0),
        _ => (0.0, 0.0),
    };
    V2::new(z, x).scale(radius as f64)
}

/// The polar point (X radius, C µdeg) of a virtual point, C taken nearest to `near`.
#[inline(never)]
pub fn to_polar(v: V2, near_udeg: f64) -> (f64, f64) {
    let r = libm::hypot(v.a, v.b);
    let raw = libm::atan2(v.b, v.a).to_degrees() * 1e6;
    let turn = 360.0e6;
    let k = libm::round((near_udeg - raw) / turn);
    (r, raw + k * turn)
}

#[cfg(test)]
mod tests {
    use super::*;

    const MM: f64 = 1e6;

    #[test]
    fn arcs_give_tangents_offsets_and_chord_points() {
        // G03 quarter circle from (10, 0) to (0, 10) around the origin.
        let arc = Elem::Arc {
            start: V2::new(10.0 * MM, 0.0),
            end: V2::new(0.0, 10.0 * MM),
            center: V2::new(0.0, 0.0),
            ccw: true,
        };
        let t = arc.start_tangent();
        assert!((t.a - 0.0).abs() < 1e-12 && (t.b - 1.0).abs() < 1e-12);
        assert!((arc.length() - core::f64::consts::FRAC_PI_2 * 10.0 * MM).abs() < 1e-6);
        // Left of a CCW arc is inside: radius 8.
        assert!((arc.offset(2.0 * MM).unwrap().radius() - 8.0 * MM).abs() < 1e-6);
        // The point 10 mm (chord) back from the end is at 60° from the a axis.
        let p = arc.back_from_end(10.0 * MM).unwrap();
        assert!((p.minus(arc.end()).len() - 10.0 * MM).abs() < 1e-6);
        assert!((p.angle().to_degrees() - 30.0).abs() < 1e-9);
    }

    #[test]
    fn intersections() {
        let l = Elem::Line { start: V2::new(-20.0 * MM, 5.0 * MM), end: V2::new(20.0 * MM, 5.0 * MM) };
        let c = Elem::Arc {
            start: V2::new(10.0 * MM, 0.0),
            end: V2::new(0.0, 10.0 * MM),
            center: V2::new(0.0, 0.0),
            ccw: true,
        };
        let x = intersect(&l, &c);
        assert_eq!(x.len(), 2);
        for p in &x {
            assert!((p.len() - 10.0 * MM).abs() < 1e-6 && (p.b - 5.0 * MM).abs() < 1e-6);
        }
    }
}

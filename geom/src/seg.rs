//! Points and segments of the ZX plane in work coordinates (X as a radius, nm):
//! what the turning cycles plan their paths with, and what a front end hands them
//! (a cycle's finishing shape, an undercut's contour). Points along a segment,
//! crossings with a level and extents are the geometry the roughing cycles need.

use canon::axis::Axis;

/// A point of the ZX plane in work coordinates: X as a radius, nm.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Pt {
    /// X (radius).
    pub x: i64,
    /// Z.
    pub z: i64,
}

impl Pt {
    /// A point.
    pub const fn new(x: i64, z: i64) -> Self {
        Pt { x, z }
    }

    /// Coordinate of `axis` (X or Z).
    pub fn get(self, axis: Axis) -> i64 {
        if axis == Axis::X { self.x } else { self.z }
    }

    /// The point with `axis` set to `v`.
    pub fn with(mut self, axis: Axis, v: i64) -> Self {
        if axis == Axis::X {
            self.x = v;
        } else {
            self.z = v;
        }
        self
    }
}

/// How a segment of the shape moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SegKind {
    /// G00.
    Rapid,
    /// G01.
    Line,
    /// G02/G03 around `center`.
    Arc {
        /// Centre.
        center: Pt,
        /// G02.
        cw: bool,
    },
}

/// One move of the shape, start to end.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Seg {
    /// Kind.
    pub kind: SegKind,
    /// Start.
    pub a: Pt,
    /// End.
    pub b: Pt,
}

impl Seg {
    /// The segment moved by `d`.
    #[inline(never)]
    pub fn shifted(self, d: Pt) -> Seg {
        let mv = |p: Pt| Pt::new(p.x + d.x, p.z + d.z);
        let kind = match self.kind {
            SegKind::Arc { center, cw } => SegKind::Arc { center: mv(center), cw },
            k => k,
        };
        Seg { kind, a: mv(self.a), b: mv(self.b) }
    }

    /// Signed sweep of an arc in radians, counter-clockwise positive in the (Z, X) plane.
    fn sweep(&self, center: Pt, cw: bool) -> f64 {
        let tau = core::f64::consts::TAU;
        let d = super::path::wrap_tau(angle(center, self.b) - angle(center, self.a));
        if cw {
            if d == 0.0 { -tau } else { d - tau }
        } else if d == 0.0 {
            tau
        } else {
            d
        }
    }

    /// The point at parameter `t` ∈ [0, 1] (by length for lines, by angle for arcs), f64 nm.
    pub fn point_at(&self, t: f64) -> (f64, f64) {
        match self.kind {
            SegKind::Arc { center, cw } => {
                let r = radius(center, self.a);
                let th = angle(center, self.a) + t * self.sweep(center, cw);
                let (s, c) = super::sin_cos(th);
                (center.x as f64 + r * s, center.z as f64 + r * c)
            }
            _ => {
                let (ax, az) = (self.a.x as f64, self.a.z as f64);
                (ax + t * (self.b.x - self.a.x) as f64, az + t * (self.b.z - self.a.z) as f64)
            }
        }
    }

    /// Parameters t ∈ (0, 1) where the segment's `axis` coordinate equals `v`.
    pub fn crossings(&self, axis: Axis, v: f64) -> heapless::Vec<f64, 2> {
        let mut out = heapless::Vec::new();
        let coord = |p: Pt| if axis == Axis::X { p.x as f64 } else { p.z as f64 };
        match self.kind {
            SegKind::Arc { center, cw } => {
                let r = radius(center, self.a);
                let c = coord(center);
                let s = (v - c) / r;
                if !(-1.0..=1.0).contains(&s) {
                    return out;
                }
                // x = cx + r·sin θ, z = cz + r·cos θ.
                let (t1, t2) = if axis == Axis::X {
                    let a = libm::asin(s);
                    (a, core::f64::consts::PI - a)
                } else {
                    let a = libm::acos(s);
                    (a, -a)
                };
                let sweep = self.sweep(center, cw);
                let start = angle(center, self.a);
                for th in [t1, t2] {
                    let d = if sweep >= 0.0 {
                        super::path::wrap_tau(th - start)
                    } else {
                        super::path::wrap_tau(start - th)
                    };
                    let t = d / sweep.abs();
                    if t > 0.0 && t < 1.0 && !out.iter().any(|o: &f64| (o - t).abs() < 1e-12) {
                        let _ = out.push(t);
                    }
                }
                if out.len() == 2 && out[0] > out[1] {
                    out.swap(0, 1);
                }
            }
            _ => {
                let (a, b) = (coord(self.a), coord(self.b));
                if a != b {
                    let t = (v - a) / (b - a);
                    if t > 0.0 && t < 1.0 {
                        let _ = out.push(t);
                    }
                }
            }
        }
        out
    }

    /// Smallest and largest value of `axis` along the segment.
    #[inline(never)]
    pub fn extent(&self, axis: Axis) -> (i64, i64) {
        match self.kind {
            SegKind::Arc { center, cw } => {
                let e = crate::arc_extents((self.a.z, self.a.x), (self.b.z, self.b.x), (center.z, center.x), cw, false);
                if axis == Axis::X { e.b } else { e.a }
            }
            _ => {
                let (a, b) = (self.a.get(axis), self.b.get(axis));
                (a.min(b), a.max(b))
            }
        }
    }
}

fn angle(c: Pt, p: Pt) -> f64 {
    libm::atan2((p.x - c.x) as f64, (p.z - c.z) as f64)
}

fn radius(c: Pt, p: Pt) -> f64 {
    libm::hypot((p.x - c.x) as f64, (p.z - c.z) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    const MM: i64 = 1_000_000;

    #[test]
    fn arc_points_and_crossings() {
        // Quarter circle from (x0, z10) around (x0, z0) counter-clockwise in (Z, X):
        // angle 0 at +Z, 90° at +X: ends at (x10, z0).
        let s = Seg {
            kind: SegKind::Arc { center: Pt::new(0, 0), cw: false },
            a: Pt::new(0, 10 * MM),
            b: Pt::new(10 * MM, 0),
        };
        let (x, z) = s.point_at(0.5);
        assert!((x - 7.0710678e6).abs() < 1.0 && (z - 7.0710678e6).abs() < 1.0);
        let c = s.crossings(Axis::X, 5.0 * MM as f64);
        assert_eq!(c.len(), 1);
        let (x, _) = s.point_at(c[0]);
        assert!((x - 5.0e6).abs() < 1e-3);
        assert_eq!(s.extent(Axis::X), (0, 10 * MM));
        // Clockwise the long way round passes x = -10.
        let s2 = Seg { kind: SegKind::Arc { center: Pt::new(0, 0), cw: true }, ..s };
        assert_eq!(s2.extent(Axis::X), (-10 * MM, 10 * MM));
        assert_eq!(s2.crossings(Axis::X, 5.0 * MM as f64).len(), 1);
    }
}

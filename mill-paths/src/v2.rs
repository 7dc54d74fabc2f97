//! Plane vectors in f64 nm (tuples), shared by CYCLE72's contour offset and
//! CYCLE73's island pocket.

// Each user takes what it needs; a build with only one of them leaves some out.
#![cfg_attr(not(all(feature = "contour", feature = "island")), allow(dead_code))]

use crate::Elem;
use crate::rot::round as nm;

pub(crate) type V = (f64, f64);

pub(crate) fn sub(a: V, b: V) -> V {
    (a.0 - b.0, a.1 - b.1)
}
pub(crate) fn add(a: V, b: V) -> V {
    (a.0 + b.0, a.1 + b.1)
}
pub(crate) fn mul(a: V, k: f64) -> V {
    (a.0 * k, a.1 * k)
}
pub(crate) fn dot(a: V, b: V) -> f64 {
    a.0 * b.0 + a.1 * b.1
}
pub(crate) fn cross(a: V, b: V) -> f64 {
    a.0 * b.1 - a.1 * b.0
}
pub(crate) fn len(a: V) -> f64 {
    libm::hypot(a.0, a.1)
}
pub(crate) fn unit(a: V) -> V {
    let l = len(a);
    if l > 0.0 { mul(a, 1.0 / l) } else { (0.0, 0.0) }
}
/// `a` turned 90° counterclockwise.
pub(crate) fn left(a: V) -> V {
    (-a.1, a.0)
}
pub(crate) fn fv(p: (i64, i64)) -> V {
    (p.0 as f64, p.1 as f64)
}
pub(crate) fn iv(p: V) -> (i64, i64) {
    (nm(p.0), nm(p.1))
}

/// The tangent of `e` at its start (`end` false) or end, unit.
pub(crate) fn tangent(e: &Elem, end: bool) -> V {
    let p = fv(if end { e.to } else { e.from });
    match e.arc {
        None => unit(sub(fv(e.to), fv(e.from))),
        Some((c, cw)) => {
            let u = unit(sub(p, fv(c)));
            if cw { mul(left(u), -1.0) } else { left(u) }
        }
    }
}

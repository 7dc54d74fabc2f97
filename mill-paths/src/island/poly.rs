//! Polygons of the plane in nm (f64) and what CYCLE73 does with them: Boolean
//! operations and offsets by i_overlay on a 10 nm integer grid, point and
//! segment tests, distances.

extern crate alloc;

use alloc::vec;
use alloc::vec::Vec;
use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::float::overlay::{FloatOverlay, OverlayOptions};
use i_overlay::mesh::float::outline::offset::OutlineOffset;
use i_overlay::mesh::float::stroke::offset::StrokeOffset;
use i_overlay::mesh::float::style::{LineCap, LineJoin, OutlineStyle, StrokeStyle};

/// A point (nm).
pub type Pt = [f64; 2];
/// A closed contour (the last point not repeated).
pub type Ring = Vec<Pt>;
/// One connected shape: its outer contour (counterclockwise) and its holes
/// (clockwise), i_overlay's convention.
pub type Shape = Vec<Ring>;
/// Several shapes.
pub type Shapes = Vec<Shape>;

/// Float → integer scale of i_overlay: a 10 nm grid (i32 engine: ±5 m).
const SCALE: f64 = 0.1;
/// The round joins' step angle (the smallest i_overlay takes, 0.01 π): a chord
/// of a join of radius ρ is ρ·(1 − cos(0.005 π)) = 1.23e-4 ρ inside the arc
/// (0.8 µm at 6.5 mm). Offsets add this much so that no chord comes closer.
pub const JOIN_STEP: f64 = 0.01 * core::f64::consts::PI;

/// What a shrinking adds to its distance to keep every join chord out of the
/// true offset (and 20 nm for the grid).
pub fn join_slack(d: f64) -> f64 {
    d.abs() * (1.0 - libm::cos(JOIN_STEP / 2.0)) + 20.0
}

/// The geometry did not fit i_overlay's integer grid (coordinates beyond ±5 m).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TooLarge;

fn opts() -> OverlayOptions<f64> {
    let mut o = OverlayOptions::<f64>::default();
    o.clean_result = true;
    o
}

/// Shapes of `subj` `rule` `clip` (NonZero: overlapping inputs unite).
pub fn boolean(subj: &Shapes, clip: &Shapes, rule: OverlayRule) -> Result<Shapes, TooLarge> {
    if subj.is_empty() && clip.is_empty() {
        return Ok(Vec::new());
    }
    let s: Vec<&Ring> = subj.iter().flatten().collect();
    let c: Vec<&Ring> = clip.iter().flatten().collect();
    let s: Vec<Ring> = s.into_iter().cloned().collect();
    let c: Vec<Ring> = c.into_iter().cloned().collect();
    let mut o = FloatOverlay::with_subj_and_clip_fixed_scale_custom(&s, &c, opts(), Default::default(), SCALE)
        .map_err(|_| TooLarge)?;
    Ok(clean(o.overlay(rule, FillRule::NonZero)))
}

/// `a` grown by `d` (shrunk for `d` < 0), round joins.
pub fn offset(a: &Shapes, d: f64) -> Result<Shapes, TooLarge> {
    if a.is_empty() {
        return Ok(Vec::new());
    }
    // Shrinking, the joins (about the walls' reflex corners) must stay out of
    // the true offset: their chords are pushed away by the slack.
    let d = if d < 0.0 { d - join_slack(d) } else { d };
    let style = OutlineStyle::new(d).line_join(LineJoin::Round(JOIN_STEP));
    let r = a.outline_custom_fixed_scale(&style, opts(), SCALE).map_err(|_| TooLarge)?;
    Ok(clean(r))
}

/// The area the open polylines `paths` sweep with a disc of radius `r`.
pub fn sweep(paths: &[Ring], r: f64) -> Result<Shapes, TooLarge> {
    let mut all: Shapes = Vec::new();
    let style = StrokeStyle::new(2.0 * r)
        .line_join(LineJoin::Round(JOIN_STEP))
        .start_cap(LineCap::Round(JOIN_STEP))
        .end_cap(LineCap::Round(JOIN_STEP));
    let mut dots: Vec<Ring> = Vec::new();
    for p in paths {
        if p.len() == 1 {
            dots.push(circle(p[0], r, 64));
            continue;
        }
        let s = p.stroke_fixed_scale(style.clone(), false, SCALE).map_err(|_| TooLarge)?;
        all.extend(s);
    }
    for d in dots {
        all.push(vec![d]);
    }
    boolean(&all, &Vec::new(), OverlayRule::Subject)
}

/// A regular `n`-gon about `c` whose edges lie outside the circle of radius `r`.
pub fn circle(c: Pt, r: f64, n: usize) -> Ring {
    let k = r / libm::cos(core::f64::consts::PI / n as f64);
    (0..n)
        .map(|i| {
            let a = 2.0 * core::f64::consts::PI * i as f64 / n as f64;
            [c[0] + k * libm::cos(a), c[1] + k * libm::sin(a)]
        })
        .collect()
}

/// Drops contours of fewer than three points.
fn clean(mut s: Shapes) -> Shapes {
    for sh in &mut s {
        sh.retain(|c| c.len() >= 3);
    }
    s.retain(|sh| !sh.is_empty());
    s
}

/// Signed area (counterclockwise positive).
pub fn area(c: &[Pt]) -> f64 {
    let n = c.len();
    let mut a = 0.0;
    for i in 0..n {
        let (p, q) = (c[i], c[(i + 1) % n]);
        a += p[0] * q[1] - q[0] * p[1];
    }
    a / 2.0
}

/// Whether `p` is inside the contours of `s` (nonzero winding over all of them).
pub fn inside(s: &[Shape], p: Pt) -> bool {
    s.iter().any(|sh| inside_shape(sh, p))
}

/// Whether `p` is inside shape `sh` (in its outer contour, outside its holes).
pub fn inside_shape(sh: &Shape, p: Pt) -> bool {
    let mut w = 0i32;
    for c in sh {
        w += winding(c, p);
    }
    w != 0
}

fn winding(c: &[Pt], p: Pt) -> i32 {
    let n = c.len();
    let mut w = 0;
    for i in 0..n {
        let (a, b) = (c[i], c[(i + 1) % n]);
        if a[1] <= p[1] {
            if b[1] > p[1] && cross3(a, b, p) > 0.0 {
                w += 1;
            }
        } else if b[1] <= p[1] && cross3(a, b, p) < 0.0 {
            w -= 1;
        }
    }
    w
}

fn cross3(a: Pt, b: Pt, p: Pt) -> f64 {
    (b[0] - a[0]) * (p[1] - a[1]) - (p[0] - a[0]) * (b[1] - a[1])
}

/// The point of segment `a`–`b` nearest `p`, and its parameter.
pub fn nearest_on_seg(a: Pt, b: Pt, p: Pt) -> (Pt, f64) {
    let d = [b[0] - a[0], b[1] - a[1]];
    let l2 = d[0] * d[0] + d[1] * d[1];
    let t = if l2 > 0.0 { (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / l2).clamp(0.0, 1.0) } else { 0.0 };
    ([a[0] + t * d[0], a[1] + t * d[1]], t)
}

/// Distance between points.
pub fn dist(a: Pt, b: Pt) -> f64 {
    libm::hypot(a[0] - b[0], a[1] - b[1])
}

/// The point of contour `c` nearest `p`: (segment index, point, distance).
pub fn nearest_on_ring(c: &[Pt], p: Pt) -> (usize, Pt, f64) {
    let n = c.len();
    let mut best = (0, c[0], f64::INFINITY);
    for i in 0..n {
        let (q, _) = nearest_on_seg(c[i], c[(i + 1) % n], p);
        let d = dist(p, q);
        if d < best.2 {
            best = (i, q, d);
        }
    }
    best
}

/// Distance from `p` to the nearest boundary of `s`.
pub fn boundary_dist(s: &[Shape], p: Pt) -> f64 {
    s.iter().flatten().map(|c| nearest_on_ring(c, p).2).fold(f64::INFINITY, f64::min)
}

/// Whether segments `a`–`b` and `c`–`d` cross properly (each one's ends strictly
/// on both sides of the other's line, by more than `tol` nm).
pub fn crosses(a: Pt, b: Pt, c: Pt, d: Pt, tol: f64) -> bool {
    let side = |p: Pt, q: Pt, r: Pt| {
        let l = dist(p, q);
        if l == 0.0 { 0.0 } else { cross3(p, q, r) / l }
    };
    let (d1, d2) = (side(a, b, c), side(a, b, d));
    let (d3, d4) = (side(c, d, a), side(c, d, b));
    ((d1 > tol && d2 < -tol) || (d1 < -tol && d2 > tol)) && ((d3 > tol && d4 < -tol) || (d3 < -tol && d4 > tol))
}

/// Whether segment `a`–`b` stays in `s` (within `tol` nm of it): it crosses no
/// contour and its midpoint is inside or on the boundary.
pub fn seg_inside(s: &[Shape], a: Pt, b: Pt, tol: f64) -> bool {
    for c in s.iter().flatten() {
        let n = c.len();
        for i in 0..n {
            if crosses(a, b, c[i], c[(i + 1) % n], tol) {
                return false;
            }
        }
    }
    let m = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
    inside(s, m) || boundary_dist(s, m) <= tol
}

/// Where the ray from `p` along unit `u` first meets a contour of `s`.
pub fn ray(s: &[Shape], p: Pt, u: Pt) -> f64 {
    let mut best = f64::INFINITY;
    for c in s.iter().flatten() {
        let n = c.len();
        for i in 0..n {
            let (a, b) = (c[i], c[(i + 1) % n]);
            let e = [b[0] - a[0], b[1] - a[1]];
            let den = u[0] * e[1] - u[1] * e[0];
            if den.abs() < 1e-12 {
                continue;
            }
            let w = [a[0] - p[0], a[1] - p[1]];
            let t = (w[0] * e[1] - w[1] * e[0]) / den;
            let v = (w[0] * u[1] - w[1] * u[0]) / den;
            if t >= 0.0 && (0.0..=1.0).contains(&v) {
                best = best.min(t);
            }
        }
    }
    best
}

/// A point well inside shape `sh`: its centroid if inside, else the middle of
/// the longest horizontal chord through the centroid's ordinate.
pub fn interior_point(sh: &Shape) -> Pt {
    let outer = &sh[0];
    let a = area(outer);
    let (mut cx, mut cy) = (0.0, 0.0);
    let n = outer.len();
    for i in 0..n {
        let (p, q) = (outer[i], outer[(i + 1) % n]);
        let k = p[0] * q[1] - q[0] * p[1];
        cx += (p[0] + q[0]) * k;
        cy += (p[1] + q[1]) * k;
    }
    let c = if a.abs() > 0.0 { [cx / (6.0 * a), cy / (6.0 * a)] } else { outer[0] };
    if inside_shape(sh, c) {
        return c;
    }
    // Horizontal chords through the ordinate of the centroid (or a vertex).
    for y in [c[1], outer[0][1] * 0.5 + outer[n / 2][1] * 0.5] {
        let mut xs: Vec<f64> = Vec::new();
        for r in sh {
            let m = r.len();
            for i in 0..m {
                let (p, q) = (r[i], r[(i + 1) % m]);
                if (p[1] <= y) != (q[1] <= y) {
                    xs.push(p[0] + (y - p[1]) * (q[0] - p[0]) / (q[1] - p[1]));
                }
            }
        }
        xs.sort_by(f64::total_cmp);
        let mut best: Option<(f64, Pt)> = None;
        for w in xs.chunks(2) {
            if let [x0, x1] = w {
                let m = [(x0 + x1) / 2.0, y];
                if best.is_none_or(|b| x1 - x0 > b.0) && inside_shape(sh, m) {
                    best = Some((x1 - x0, m));
                }
            }
        }
        if let Some((_, m)) = best {
            return m;
        }
    }
    outer[0]
}

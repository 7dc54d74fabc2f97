//! Elliptical (G02.1/G03.1, 2.4) and parabolic (G02.2/G03.2, 2.5) interpolation in
//! the ZX plane, as short straight cuts whose points lie on the analytic curve and
//! whose chords stay within the motion chord tolerance of it. The cuts are
//! generated a few at a time like a cycle's passes (bounded work per step, the
//! whole curve dry-run before the first move, soft limits and stroke check 2 on
//! every cut), and the last one ends exactly on the programmed end point.
//!
//! Ellipse: semi-axes A (along the long axis) and B, the long axis turned Q from +Z
//! clockwise as seen from +Y — the program's view, Z right and X up. Rotating by Q
//! and stretching the short axis by A/B makes the ellipse a circle of radius A:
//! its centre follows from the start and end points like an arc's with R = A (the
//! arc of up to 180°), and the cuts are even steps of the circle's angle.
//!
//! Parabola: Y² = 2PX with its axis (X) turned Q from +Z the same way. With the
//! axis direction and P given, the start and end points fix the vertex; of the two
//! parabolas through them (opening one way or the other along the axis) G02.2 takes
//! the one that turns clockwise from start to end, G03.2 the counter-clockwise one.
//! The cuts are even steps along the axis's normal, √(8·tol·P) apart, which keeps
//! every chord within tol of the curve.
//!
//! An end point no curve of the given size reaches raises alarm 0020.

use super::Step;
use crate::alarm::AlarmKind;
use crate::step::Pt;

/// The curve of a G02.1/G03.1/G02.2/G03.2 block, in a frame turned by Q.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurveGen {
    kind: Kind,
    /// cos Q, sin Q.
    rot: (f64, f64),
    /// Steps in all, and the next one (1-based).
    steps: u32,
    next: u32,
    /// The programmed end point (exact).
    end: Pt,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    /// Circle of radius `a` around `c` in the stretched frame; angle from `from` by
    /// `sweep` (negative clockwise); `k` = B / A shrinks the stretched axis back.
    Ellipse { c: (f64, f64), a: f64, from: f64, sweep: f64, k: f64 },
    /// s = s0 + σ (t − t0)² / 2P, t from `t1` to `t2`.
    Parabola { s0: f64, t0: f64, sigma: f64, p: f64, t1: f64, t2: f64 },
}

/// Most cuts one curve may have (alarm 4037 beyond).
const MAX_STEPS: f64 = 1.0e6;

impl CurveGen {
    /// An ellipse from `start` to `end` (work coordinates, X radius), semi-axes `a`,
    /// `b` (nm), long axis turned `q_udeg` clockwise from +Z, within chord tolerance `tol`.
    pub fn ellipse(start: Pt, end: Pt, a: i64, b: i64, q_udeg: i64, cw: bool, tol: i64) -> Result<Self, AlarmKind> {
        if a <= 0 || b <= 0 {
            return Err(AlarmKind::ValueOutOfRange { letter: if a <= 0 { b'A' } else { b'B' } });
        }
        let rot = rotation(q_udeg);
        let (a, k) = (a as f64, b as f64 / a as f64);
        let to_circle = |p: Pt| {
            let (s, t) = turn(rot, p);
            (s, t / k)
        };
        let (s1, s2) = (to_circle(start), to_circle(end));
        let c = centre(s1, s2, a, cw)?;
        let from = libm::atan2(s1.1 - c.1, s1.0 - c.0);
        let to = libm::atan2(s2.1 - c.1, s2.0 - c.0);
        let tau = core::f64::consts::TAU;
        let mut sweep = crate::geom::fmod(to - from, tau);
        if cw && sweep > 0.0 {
            sweep -= tau;
        } else if !cw && sweep < 0.0 {
            sweep += tau;
        }
        let dphi = 2.0 * libm::acos((1.0 - tol.max(1) as f64 / a).max(-1.0));
        let steps = count(libm::fabs(sweep) / dphi)?;
        Ok(CurveGen { kind: Kind::Ellipse { c, a, from, sweep, k }, rot, steps, next: 1, end })
    }

    /// A parabola y² = 2px (`p` nm) from `start` to `end`, axis turned `q_udeg`.
    pub fn parabola(start: Pt, end: Pt, p: i64, q_udeg: i64, cw: bool, tol: i64) -> Result<Self, AlarmKind> {
        if p <= 0 {
            return Err(AlarmKind::ValueOutOfRange { letter: b'P' });
        }
        let rot = rotation(q_udeg);
        let p = p as f64;
        let ((s1, t1), (s2, t2)) = (turn(rot, start), turn(rot, end));
        if libm::fabs(t2 - t1) < 0.5 {
            // Both points on one normal of the axis: no such parabola unless they coincide.
            return Err(AlarmKind::CurveEndOff { excess_nm: libm::fabs(s2 - s1) as i64 });
        }
        // The turning sign of s(t) = s0 + σ(t − t0)²/2P walked from t1 to t2 is −σ·δ.
        let delta = if t2 > t1 { 1.0 } else { -1.0 };
        let sigma = if cw { delta } else { -delta };
        let t0 = (t1 * t1 - t2 * t2 - 2.0 * p * sigma * (s1 - s2)) / (2.0 * (t1 - t2));
        let s0 = s1 - sigma * (t1 - t0) * (t1 - t0) / (2.0 * p);
        let dt = libm::sqrt(8.0 * tol.max(1) as f64 * p);
        let steps = count(libm::fabs(t2 - t1) / dt)?;
        Ok(CurveGen { kind: Kind::Parabola { s0, t0, sigma, p, t1, t2 }, rot, steps, next: 1, end })
    }

    /// The point at fraction `f` ∈ [0, 1] of the curve, work coordinates (f64 nm).
    pub fn point(&self, f: f64) -> (f64, f64) {
        let (s, t) = match self.kind {
            Kind::Ellipse { c, a, from, sweep, k } => {
                let th = from + f * sweep;
                let (s, co) = crate::geom::sin_cos(th);
                (c.0 + a * co, (c.1 + a * s) * k)
            }
            Kind::Parabola { s0, t0, sigma, p, t1, t2 } => {
                let t = t1 + f * (t2 - t1);
                (s0 + sigma * (t - t0) * (t - t0) / (2.0 * p), t)
            }
        };
        unturn(self.rot, s, t)
    }

    /// Queues the next cuts; false when the last (ending exactly on the end point)
    /// has been queued.
    pub fn fill(&mut self, queue: &mut super::StepQueue) -> Result<bool, AlarmKind> {
        while !queue.is_full() && self.next <= self.steps {
            let p = if self.next == self.steps {
                self.end
            } else {
                let (z, x) = self.point(f64::from(self.next) / f64::from(self.steps));
                Pt::new(crate::geom::round_i64(x), crate::geom::round_i64(z))
            };
            queue.push_back(Step::Feed(p)).map_err(|_| AlarmKind::Overflow)?;
            self.next += 1;
        }
        Ok(self.next <= self.steps)
    }
}

/// Number of cuts for `n` tolerance steps (at least one).
#[inline(never)]
fn count(n: f64) -> Result<u32, AlarmKind> {
    if !n.is_finite() || n > MAX_STEPS {
        return Err(AlarmKind::CycleTooLong);
    }
    Ok((libm::ceil(n) as u32).max(1))
}

/// cos and sin of Q (µdeg; out of line: the parabola and the ellipse).
#[inline(never)]
fn rotation(q_udeg: i64) -> (f64, f64) {
    let q = (q_udeg as f64 / 1e6).to_radians();
    let (s, c) = crate::geom::sin_cos(q);
    (c, s)
}

/// A work point (X radius) in the frame whose first axis is +Z turned clockwise by
/// Q (in the Z-right, X-up view): (s along the turned axis, t across it).
#[inline(never)]
fn turn(rot: (f64, f64), p: Pt) -> (f64, f64) {
    let (z, x) = (p.z as f64, p.x as f64);
    let (c, s) = rot;
    // Turning the point counter-clockwise by Q maps the axis (cos Q, −sin Q) onto +s.
    (z * c - x * s, z * s + x * c)
}

/// Back from the turned frame to (Z, X).
fn unturn(rot: (f64, f64), s: f64, t: f64) -> (f64, f64) {
    let (c, sn) = rot;
    (s * c + t * sn, -s * sn + t * c)
}

/// Centre of the circle of radius `r` through `p` and `q` travelled clockwise
/// (`cw`) on the arc of up to 180°; alarm 0020 when the points are too far apart.
fn centre(p: (f64, f64), q: (f64, f64), r: f64, cw: bool) -> Result<(f64, f64), AlarmKind> {
    let (dx, dy) = (q.0 - p.0, q.1 - p.1);
    let chord = libm::hypot(dx, dy);
    let half = chord / 2.0;
    if half > r + 1.0 {
        return Err(AlarmKind::CurveEndOff { excess_nm: (half - r) as i64 });
    }
    if chord == 0.0 {
        return Err(AlarmKind::CurveEndOff { excess_nm: 0 });
    }
    let h = libm::sqrt((r * r - half * half).max(0.0));
    // Clockwise arcs of up to 180° have their centre to the right of the chord.
    let s = if cw { 1.0 } else { -1.0 };
    let (ux, uy) = (dy / chord, -dx / chord);
    Ok((p.0 + dx / 2.0 + s * h * ux, p.1 + dy / 2.0 + s * h * uy))
}

//! CYCLE72 contour milling (seed 001 lines 5450-5764): the cutter runs along the
//! programmed contour offset by its radius (+ the allowance `_FAL` roughing) to
//! the left (G41) or right (G42), or on it (G40), level by level per `_MID`, with
//! a soft approach and departure (straight, quarter or semicircle, in the plane
//! or in space) and the retract of `_VARI`'s hundreds digit between levels.
//!
//! The offset path: each element shifted by `off` to the side; at a convex
//! corner (the tool outside the turn) an arc about the programmed vertex joins
//! the two, at a concave one both are cut back to their intersection (the one
//! nearest the vertex). An element shorter than what the concave corners take
//! from it is not removed (a real control's look-ahead would): program such
//! contours with fillets. Everything is computed per element from the contour
//! store on each step; the generator itself holds only its indices.

use crate::infeed::Levels;
use crate::{Contour, CycleAlarm, Elem, Move, P3};

use crate::v2::{V, add, cross, dot, fv, iv, left, len, mul, sub, tangent, unit};
/// An arc's centre and sense (G2).
type ArcOf = ((i64, i64), bool);

/// How the cutter reaches (`_AS1`) or leaves (`_AS2`) the contour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Soft {
    /// Units digit: 1 straight along the tangent, 2 quarter circle, 3 semicircle.
    pub path: u8,
    /// Tens digit 1: in space (the move also covers the safety distance).
    pub space: bool,
    /// `_LP`: the straight move's length (from the cutter's edge; from its centre
    /// under G40) or the arc's radius (of the centre's path), nm.
    pub lp: i64,
}

/// A CYCLE72 call as the generator needs it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ContourSpec {
    /// Side of the cutter: 1 left (G41), -1 right (G42), 0 on the contour (G40).
    pub side: i8,
    /// Distance of the centre path from the contour: cutter radius (+ `_FAL`).
    pub off: i64,
    /// Cutter radius.
    pub r: i64,
    /// Depth levels (from the infeed start to the last level).
    pub levels: Levels,
    /// Retract plane.
    pub rtp: i64,
    /// RFP + SDIS.
    pub safe: i64,
    /// SDIS towards RTP: `dir` is −1 or +1 into the material.
    pub sdis: i64,
    /// Into the material along the applicate.
    pub dir: i64,
    /// `_VARI` tens digit 1: intermediate moves at `_FF3` (G1), else rapid.
    pub g1: bool,
    /// `_VARI` hundreds digit: 0 retract to RTP, 1 to RFP + SDIS, 2 by SDIS.
    pub lift: u8,
    /// Approach and departure.
    pub soft: [Soft; 2],
    /// Feeds: depth `_FFD`, plane `_FFP1`, intermediate `_FF3`.
    pub feeds: [i64; 3],
}

/// The CYCLE72 generator.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContourMill {
    spec: ContourSpec,
    /// Level (1-based once started).
    level: u32,
    /// Step within the level.
    step: u32,
}

impl ContourMill {
    /// The generator of `spec`.
    pub fn new(spec: ContourSpec) -> Self {
        ContourMill { spec, level: 1, step: 0 }
    }

    fn off(&self) -> f64 {
        f64::from(self.spec.side) * self.spec.off as f64
    }

    /// Element `i` offset to the side: (start, end), and the offset arc's centre.
    fn shifted(&self, e: &Elem) -> (V, V) {
        let d = self.off();
        let f = |p: (i64, i64), end| add(fv(p), mul(left(tangent(e, end)), d));
        (f(e.from, false), f(e.to, true))
    }

    /// Where offset elements `i` and `i + 1` meet: `None` at a convex corner
    /// (or a tangent one), else their intersection nearest the vertex.
    fn meet(&self, k: &dyn Contour, i: usize) -> Option<V> {
        if self.spec.side == 0 || i + 1 >= k.len() {
            return None;
        }
        let (a, b) = (k.elem(i), k.elem(i + 1));
        let turn = cross(tangent(&a, true), tangent(&b, false));
        if turn.abs() < 1e-9 || turn * f64::from(self.spec.side) < 0.0 {
            return None;
        }
        let v = fv(a.to);
        let (x, y) = (self.carrier(&a), self.carrier(&b));
        let mut best: Option<V> = None;
        for p in intersect(x, y).into_iter().flatten() {
            if best.is_none_or(|q| len(sub(p, v)) < len(sub(q, v))) {
                best = Some(p);
            }
        }
        best
    }

    /// The offset element's carrier: a line (point, direction) or a circle
    /// (centre, radius as (r, NaN)).
    fn carrier(&self, e: &Elem) -> Carrier {
        let (s, t) = self.shifted(e);
        match e.arc {
            None => Carrier::Line(s, sub(t, s)),
            Some((c, _)) => Carrier::Circle(fv(c), len(sub(s, fv(c)))),
        }
    }

    /// Offset element `i` cut to its corners: start, end.
    fn trimmed(&self, k: &dyn Contour, i: usize) -> (V, V) {
        let (mut s, mut t) = self.shifted(&k.elem(i));
        if i > 0
            && let Some(p) = self.meet(k, i - 1)
        {
            s = p;
        }
        if let Some(p) = self.meet(k, i) {
            t = p;
        }
        (s, t)
    }

    /// The approach (`dep` false) or departure: the point off the contour and,
    /// for an arc, its centre and sense.
    fn soft(&self, k: &dyn Contour, dep: bool) -> (V, Option<ArcOf>) {
        let n = k.len();
        let (p, t) = if dep {
            (self.trimmed(k, n - 1).1, tangent(&k.elem(n - 1), true))
        } else {
            (self.trimmed(k, 0).0, tangent(&k.elem(0), false))
        };
        let s = &self.spec.soft[usize::from(dep)];
        let sign = if dep { 1.0 } else { -1.0 };
        let side = f64::from(self.spec.side);
        let lp = s.lp as f64;
        if s.path == 1 || self.spec.side == 0 {
            let l = if self.spec.side == 0 { lp } else { lp + self.spec.r as f64 };
            return (add(p, mul(t, sign * l)), None);
        }
        let nrm = mul(left(t), side);
        let q = add(p, mul(nrm, lp));
        let far = if s.path == 3 { add(p, mul(nrm, 2.0 * lp)) } else { add(q, mul(t, sign * lp)) };
        (far, Some((iv(q), side < 0.0)))
    }

    fn level_at(&self) -> i64 {
        self.spec.levels.level(self.level)
    }

    /// The height the cutter leaves a level to.
    fn lifted(&self) -> i64 {
        let s = &self.spec;
        if self.level >= s.levels.count {
            return s.rtp;
        }
        match s.lift {
            1 => s.safe,
            2 => self.level_at().saturating_sub(s.dir.saturating_mul(s.sdis)),
            _ => s.rtp,
        }
    }

    fn inter(&self, to: P3) -> Move {
        if self.spec.g1 { Move::Line { to, feed: self.spec.feeds[2] } } else { Move::Rapid(to) }
    }

    /// The move of step `k` of the current level, `None` for a step it skips.
    fn at(&self, c: &dyn Contour, k: u32) -> Option<Move> {
        let s = &self.spec;
        let n = c.len() as u32;
        let z = self.level_at();
        let above = z.saturating_sub(s.dir.saturating_mul(s.sdis));
        let (a, arc_in) = self.soft(c, false);
        let a = iv(a);
        let [ffd, ffp, _] = s.feeds;
        let p3 = |p: (i64, i64), d| P3::new(p.0, p.1, d);
        let from_h = if self.level == 1 { s.rtp } else { self.prev_lifted() };
        let space_in = s.soft[0].space;
        match k {
            0 => Some(self.inter(p3(a, from_h))),
            1 => Some(self.inter(p3(a, above))),
            2 if !space_in => Some(Move::Line { to: p3(a, z), feed: ffd }),
            3 => {
                let to = p3(iv(self.trimmed(c, 0).0), z);
                let feed = if space_in { ffd } else { ffp };
                Some(match arc_in {
                    None => Move::Line { to, feed },
                    Some((centre, cw)) => Move::Arc { to, centre, cw, feed },
                })
            }
            k if k >= 4 && k < 4 + 2 * n => {
                let i = ((k - 4) / 2) as usize;
                let e = c.elem(i);
                if (k - 4) % 2 == 0 {
                    let to = p3(iv(self.trimmed(c, i).1), z);
                    return Some(match e.arc {
                        None => Move::Line { to, feed: ffp },
                        Some((centre, cw)) => Move::Arc { to, centre, cw, feed: ffp },
                    });
                }
                // A convex corner: an arc about the vertex to the next element.
                if i + 1 >= c.len() || s.side == 0 || self.meet(c, i).is_some() {
                    return None;
                }
                let to = self.shifted(&c.elem(i + 1)).0;
                if len(sub(to, self.shifted(&e).1)) < 1.0 {
                    return None;
                }
                Some(Move::Arc { to: p3(iv(to), z), centre: e.to, cw: s.side > 0, feed: ffp })
            }
            k if k == 4 + 2 * n => {
                let (b, arc) = self.soft(c, true);
                let to = p3(iv(b), if s.soft[1].space { above } else { z });
                Some(match arc {
                    None => Move::Line { to, feed: ffp },
                    Some((centre, cw)) => Move::Arc { to, centre, cw, feed: ffp },
                })
            }
            k if k == 5 + 2 * n => {
                let b = iv(self.soft(c, true).0);
                Some(self.inter(p3(b, self.lifted())))
            }
            _ => None,
        }
    }

    fn prev_lifted(&self) -> i64 {
        let prev = ContourMill { level: self.level - 1, ..*self };
        prev.lifted()
    }

    /// The next move, `None` when done.
    pub fn next(&mut self, c: &dyn Contour) -> Result<Option<Move>, CycleAlarm> {
        let n = c.len() as u32;
        if n == 0 {
            return Err(CycleAlarm::ContourPreparation { cause: 10933 });
        }
        // An arc offset to or through its centre: the cutter does not fit.
        for i in 0..if self.level == 1 && self.step == 0 { c.len() } else { 0 } {
            if let Some((ctr, cw)) = c.elem(i).arc {
                let r0 = len(sub(fv(c.elem(i).from), fv(ctr)));
                if r0 + if cw { self.off() } else { -self.off() } < 1.0 {
                    return Err(CycleAlarm::CutterRadiusTooLarge);
                }
            }
        }
        while self.level <= self.spec.levels.count {
            let k = self.step;
            self.step += 1;
            if k > 5 + 2 * n {
                self.level += 1;
                self.step = 0;
                continue;
            }
            if let Some(m) = self.at(c, k) {
                return Ok(Some(m));
            }
        }
        Ok(None)
    }
}

/// A line (point, direction) or a circle (centre, radius).
#[derive(Clone, Copy)]
enum Carrier {
    Line(V, V),
    Circle(V, f64),
}

/// Up to two intersections of two carriers.
fn intersect(x: Carrier, y: Carrier) -> [Option<V>; 2] {
    use Carrier::*;
    match (x, y) {
        (Line(p, d), Line(q, e)) => {
            let den = cross(d, e);
            if den.abs() < 1e-12 {
                return [None, None];
            }
            [Some(add(p, mul(d, cross(sub(q, p), e) / den))), None]
        }
        (Line(p, d), Circle(c, r)) | (Circle(c, r), Line(p, d)) => {
            let u = unit(d);
            let f = sub(p, c);
            let b = dot(f, u);
            let disc = b * b - (dot(f, f) - r * r);
            if disc < 0.0 {
                return [None, None];
            }
            let h = libm::sqrt(disc);
            [Some(add(p, mul(u, -b - h))), Some(add(p, mul(u, -b + h)))]
        }
        (Circle(c, r), Circle(c2, r2)) => {
            let dv = sub(c2, c);
            let dd = len(dv);
            if dd < 1e-9 || dd > r + r2 || dd < (r - r2).abs() {
                return [None, None];
            }
            let a = (r * r - r2 * r2 + dd * dd) / (2.0 * dd);
            let h = libm::sqrt((r * r - a * a).max(0.0));
            let m = add(c, mul(dv, a / dd));
            let w = mul(left(dv), h / dd);
            [Some(add(m, w)), Some(sub(m, w))]
        }
    }
}

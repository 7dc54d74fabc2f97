//! The path a contour cycle's tool positions run on: the programmed contour moved
//! away from the part by the finishing allowances and the nose radius, then by the
//! imaginary tip's vector (the machine positions the tip, 2.18.1), element by
//! element as the cycle walks it (nothing stored: the contour is kept once).
//!
//! The axis allowances move the contour as a whole, as G71's Δu/Δw do (so its
//! elements stay joined), except the elements that face along the machining
//! direction — an undercut's descending side — which move the other way along
//! the cutting axis (a translation towards the start would cut into them). The
//! contour-parallel allowance and the nose radius move every element along its
//! normal on the tool's side. Where two moved elements meet at a corner the tool
//! is inside (concave) they are cut back to their crossing; where it is outside
//! (convex) the tool turns round the corner on an arc (or goes straight across
//! where the two moved differently).

use crate::alarm::AlarmKind;
use crate::geom::path::{Elem, V2, intersect, nearest};
use crate::geom::{Pt, Seg, SegKind};

/// How far a contour's elements move, and to which side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Offsets {
    /// +1 when the tool is left of the contour's direction of travel in the (Z, X)
    /// plane, −1 when right.
    pub side: f64,
    /// Distance every element moves along its normal: nose radius plus the
    /// contour-parallel allowance, nm.
    pub equi: f64,
    /// The axis allowances as a move (Z, X) of the elements facing against the
    /// machining direction or outward …
    pub front: V2,
    /// … and of those facing along it (an undercut's descent).
    pub back: V2,
    /// The machining direction (unit, Z, X): which elements face along it.
    pub along: V2,
    /// The imaginary tip's vector from the nose centre (Z, X), nm.
    pub tip: V2,
}

impl Offsets {
    /// The move of the axis allowances for element `e`.
    fn shift(&self, e: &Elem) -> V2 {
        let chord = e.end().minus(e.start()).unit().left().scale(self.side);
        if chord.dot(self.along) > 1e-9 { self.back } else { self.front }
    }
}

/// The element of a segment in the (Z, X) plane.
pub fn elem(s: &Seg) -> Elem {
    let v = |p: Pt| V2::new(p.z as f64, p.x as f64);
    match s.kind {
        SegKind::Arc { center, cw } => Elem::Arc { start: v(s.a), end: v(s.b), center: v(center), ccw: !cw },
        _ => Elem::Line { start: v(s.a), end: v(s.b) },
    }
}

/// The segment of an element (lines keep `kind`), rounded to nm.
fn seg(e: &Elem, kind: SegKind) -> Seg {
    let p = |v: V2| {
        let (z, x) = v.round();
        Pt::new(x, z)
    };
    match *e {
        Elem::Line { start, end } => Seg { kind, a: p(start), b: p(end) },
        Elem::Arc { start, end, center, ccw } => {
            Seg { kind: SegKind::Arc { center: p(center), cw: !ccw }, a: p(start), b: p(end) }
        }
    }
}

/// The element moved by `v`.
fn moved(e: Elem, v: V2) -> Elem {
    match e {
        Elem::Line { start, end } => Elem::Line { start: start.plus(v), end: end.plus(v) },
        Elem::Arc { start, end, center, ccw } => {
            Elem::Arc { start: start.plus(v), end: end.plus(v), center: center.plus(v), ccw }
        }
    }
}

/// Calls `f` with each element of the path `o` makes of `raw`, in order (the
/// contour's own elements and the pieces inserted at corners), while it returns
/// true. Alarm 3605 when the nose does not fit inside an arc of the contour.
#[inline]
#[cfg_attr(not(feature = "siemens"), allow(dead_code))] // its callers are SINUMERIK's (CYCLE95)
pub fn walk(raw: &[Seg], o: &Offsets, mut f: impl FnMut(Seg) -> Result<bool, AlarmKind>) -> Result<(), AlarmKind> {
    walk_dyn(raw, o, &mut f)
}

/// [`walk`] with the visitor behind a reference: one copy of the walk in flash
/// instead of one per caller's closure (the walk runs a few times per roughing pass,
/// not per block).
#[inline(never)]
fn walk_dyn(raw: &[Seg], o: &Offsets, f: &mut dyn FnMut(Seg) -> Result<bool, AlarmKind>) -> Result<(), AlarmKind> {
    let off = |s: &Seg| -> Result<(Elem, V2, SegKind), AlarmKind> {
        let e = elem(s);
        let shift = o.shift(&e);
        Ok((moved(e.offset(o.side * o.equi).ok_or(AlarmKind::NoseCompGouge)?, shift), shift, s.kind))
    };
    let Some(first) = raw.first() else { return Ok(()) };
    let (mut cur, mut shift, mut kind) = off(first)?;
    let mut start = cur.start();
    for (i, s) in raw.iter().enumerate() {
        let next = raw.get(i + 1).map(&off).transpose()?;
        let (end, mid, next_start) = match next {
            Some((n, ns, _)) => corner(&elem(s), &elem(&raw[i + 1]), &cur, &n, shift == ns, o),
            None => (cur.end(), None, cur.end()),
        };
        if !f(seg(&moved(with_ends(cur, start, end), o.tip), kind))? {
            return Ok(());
        }
        if let Some(m) = mid
            && !f(seg(&moved(m, o.tip), SegKind::Line))?
        {
            return Ok(());
        }
        if let Some((n, ns, k)) = next {
            (cur, shift, kind, start) = (n, ns, k, next_start);
        }
    }
    Ok(())
}

/// Element `k` of the path `o` makes of `raw` (the passes and the roughing's
/// sections look elements up by number: one copy of the search).
#[inline(never)]
pub fn nth(raw: &[Seg], o: &Offsets, k: u16) -> Result<Option<Seg>, AlarmKind> {
    let mut i = 0u16;
    let mut found = None;
    walk_dyn(raw, o, &mut |s| {
        if i == k {
            found = Some(s);
            return Ok(false);
        }
        i += 1;
        Ok(true)
    })?;
    Ok(found)
}

/// `e` from `start` to `end` (points on its line or circle).
fn with_ends(e: Elem, start: V2, end: V2) -> Elem {
    match e {
        Elem::Line { .. } => Elem::Line { start, end },
        Elem::Arc { center, ccw, .. } => Elem::Arc { start, end, center, ccw },
    }
}

/// Where the moved `o1` ends and the moved `o2` starts at the corner of the
/// contour's `e1` → `e2` (`same`: both moved by the same axis allowances), and
/// what goes between them.
fn corner(e1: &Elem, e2: &Elem, o1: &Elem, o2: &Elem, same: bool, o: &Offsets) -> (V2, Option<Elem>, V2) {
    let (p, q) = (o1.end(), o2.start());
    if q.minus(p).len() < 0.5 {
        return (p, None, p);
    }
    let c = e1.end();
    let (t1, t2) = (e1.end_tangent(), e2.start_tangent());
    let turn = libm::atan2(t1.cross(t2), t1.dot(t2));
    let line = Elem::Line { start: p, end: q };
    if libm::fabs(turn) < 1e-9 {
        return (p, Some(line), q);
    }
    if turn * o.side > 0.0 {
        // The tool inside the corner: both cut back to their crossing.
        return match nearest(&intersect(o1, o2), c) {
            Some(x) => (x, None, x),
            None => (p, Some(line), q),
        };
    }
    if same {
        // Round the corner moved as the elements were.
        let c = c.plus(o1.end().minus(e1.end().plus(e1.end_tangent().left().scale(o.side * o.equi))));
        (p, Some(Elem::Arc { start: p, end: q, center: c, ccw: turn > 0.0 }), q)
    } else {
        (p, Some(line), q)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec::Vec;

    const MM: i64 = 1_000_000;

    fn line(x0: f64, z0: f64, x1: f64, z1: f64) -> Seg {
        let p = |x: f64, z: f64| Pt::new((x * 1e6) as i64, (z * 1e6) as i64);
        Seg { kind: SegKind::Line, a: p(x0, z0), b: p(x1, z1) }
    }

    fn all(raw: &[Seg], o: &Offsets) -> Vec<Seg> {
        let mut v = Vec::new();
        walk(raw, o, |s| {
            v.push(s);
            Ok(true)
        })
        .unwrap();
        v
    }

    /// An outside shoulder: cylinder X10 from Z0 to Z-10, face up to X20, cylinder
    /// X20 to Z-20 (radius values), cut towards -Z with the tool above (+X: right of
    /// travel in the (Z, X) plane). Allowances X 0.5, Z 0.2: the whole contour moves
    /// by (+0.5, +0.2), then a descent back to X10 moves by (+0.5, -0.2).
    #[test]
    fn axis_allowances_move_cylinders_and_faces() {
        let raw = [
            line(10.0, 0.0, 10.0, -10.0),
            line(10.0, -10.0, 20.0, -10.0),
            line(20.0, -10.0, 20.0, -20.0),
            line(20.0, -20.0, 10.0, -25.0),
        ];
        let o = Offsets {
            side: -1.0,
            equi: 0.0,
            front: V2::new(0.2e6, 0.5e6),
            back: V2::new(-0.2e6, 0.5e6),
            along: V2::new(-1.0, 0.0),
            tip: V2::new(0.0, 0.0),
        };
        let got = all(&raw, &o);
        let pt = |x: f64, z: f64| Pt::new((x * 1e6) as i64, (z * 1e6) as i64);
        assert_eq!(got.len(), 5);
        assert_eq!((got[0].a, got[0].b), (pt(10.5, 0.2), pt(10.5, -9.8)));
        assert_eq!((got[1].a, got[1].b), (pt(10.5, -9.8), pt(20.5, -9.8)));
        assert_eq!((got[2].a, got[2].b), (pt(20.5, -9.8), pt(20.5, -19.8)));
        // The descent moved the other way along Z: a straight piece across the top.
        assert_eq!((got[3].a, got[3].b), (pt(20.5, -19.8), pt(20.5, -20.2)));
        assert_eq!((got[4].a, got[4].b), (pt(20.5, -20.2), pt(10.5, -25.2)));
    }

    /// The nose alone (radius 1, tip 3: the tip 1 mm below and 1 mm towards -Z of
    /// the centre): cylinders run as programmed, the convex corner becomes an arc
    /// round it.
    #[test]
    fn nose_radius_with_tip_three() {
        let raw = [line(10.0, 0.0, 20.0, -10.0), line(20.0, -10.0, 20.0, -20.0)];
        let zero = V2::new(0.0, 0.0);
        let o = Offsets {
            side: -1.0,
            equi: MM as f64,
            front: zero,
            back: zero,
            along: V2::new(-1.0, 0.0),
            tip: V2::new(-1e6, -1e6),
        };
        let got = all(&raw, &o);
        assert_eq!(got.len(), 3);
        assert!(matches!(got[1].kind, SegKind::Arc { .. }));
        assert_eq!(got[2].b, Pt::new(20 * MM, -21 * MM));
        assert_eq!(got[2].a.x, 20 * MM);
    }
}

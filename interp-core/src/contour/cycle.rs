//! Nose radius compensation inside the G90/G94 single cycles (2.15) while G41 or
//! G42 is in force.
//!
//! The manual describes the cycles' four moves (① approach, ② cut, ③ retract at
//! feed, ④ return) but not how 2.18 applies to them; this follows FANUC's rule for
//! canned cycles: the offset side inside the cycle does not depend on G41/G42. The
//! nose centre runs one radius inside the cycle's closed path A→B→C→D→A (the stock
//! the cycle removes lies inside it, for outside and inside, straight and taper
//! cycles alike), so the cut ② and the retract ③ — the two moves that touch the
//! part — are offset parallel to their programmed lines and meet at their crossing.
//! The approach ① and the return ④ stay moves of their own axis from and to the
//! start point A, which the imaginary tip keeps (the next pass of a modal cycle
//! starts there). The machine positions the imaginary tip (centre + tip vector), so
//! with the tip that fits the cycle (3 for an outside G90 on a rear post) straight
//! cycles run exactly as programmed and only a taper moves.
//!
//! A cut or retract whose offset runs against its programmed move (a cut shorter
//! than the nose reaches) is alarm 3605, before the cycle moves.

use crate::alarm::AlarmKind;
use crate::geom::path::V2;

/// A point of the ZX plane in work coordinates (X as a radius, Z), nm.
pub type Xz = (i64, i64);

/// The nose the cycle is compensated for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Nose {
    /// Nose radius, nm.
    pub radius: i64,
    /// Imaginary tip direction 0–9 (figure 2.63).
    pub tip: u8,
}

/// The points B, C, D (tip positions) of a single cycle from start `a` through the
/// programmed `b`, `c`, `d`, compensated for `nose`. `turning` is G90 (approach and
/// retract along X); G94 approaches and retracts along Z. A cycle with no area (no
/// cut length or depth) runs as programmed.
pub fn single(a: Xz, b: Xz, c: Xz, d: Xz, turning: bool, nose: Nose) -> Result<[Xz; 3], AlarmKind> {
    let p = [a, b, c, d].map(|(x, z)| V2::new(z as f64, x as f64));
    let area2: f64 = (0..4).map(|i| p[i].cross(p[(i + 1) % 4])).sum();
    let r = nose.radius as f64;
    if r <= 0.0 || libm::fabs(area2) < 1.0 {
        return Ok([b, c, d]);
    }
    let inside = |from: V2, to: V2| inside(from, to, area2 > 0.0);
    let tip = crate::geom::path::tip_vector(nose.tip, nose.radius);
    let (x_axis, z_axis) = (V2::new(0.0, 1.0), V2::new(1.0, 0.0));
    let (approach, back) = if turning { (x_axis, z_axis) } else { (z_axis, x_axis) };
    let ac = p[0].minus(tip);
    let cut = (p[1].plus(inside(p[1], p[2]).scale(r)), p[2].minus(p[1]));
    let retract = (p[2].plus(inside(p[2], p[3]).scale(r)), p[3].minus(p[2]));
    let bc = cross((ac, approach), cut)?;
    let cc = cross(cut, retract)?;
    let dc = cross(retract, (ac, back))?;
    for (from, to, pf, pt) in [(bc, cc, p[1], p[2]), (cc, dc, p[2], p[3])] {
        let programmed = pt.minus(pf);
        if programmed.len() > 0.5 && to.minus(from).dot(programmed) < 0.0 {
            return Err(AlarmKind::NoseCompGouge);
        }
    }
    Ok([bc, cc, dc].map(|q| tip_point(q, tip)))
}

/// The unit normal of `from` → `to` towards the inside of the loop: left of travel
/// when it runs counter-clockwise (`ccw`). Out of line, as [`tip_point`]: each was
/// inlined at every use.
#[inline(never)]
fn inside(from: V2, to: V2, ccw: bool) -> V2 {
    let n = to.minus(from).unit().left();
    if ccw { n } else { n.scale(-1.0) }
}

/// The tip position (X, Z) of nose centre `q` (Z, X) with tip vector `tip`, rounded.
#[inline(never)]
fn tip_point(q: V2, tip: V2) -> Xz {
    let (z, x) = q.plus(tip).round();
    (x, z)
}

/// Where the line through `l.0` along `l.1` crosses the one through `m.0` along
/// `m.1` (alarm 3605 for parallel lines: no corner to run to).
#[inline(never)]
fn cross(l: (V2, V2), m: (V2, V2)) -> Result<V2, AlarmKind> {
    let den = l.1.cross(m.1);
    if libm::fabs(den) < 1e-9 * l.1.len() * m.1.len() {
        return Err(AlarmKind::NoseCompGouge);
    }
    let s = m.0.minus(l.0).cross(m.1) / den;
    Ok(l.0.plus(l.1.scale(s)))
}

#[cfg(test)]
mod tests {
    use super::*;

    const R: i64 = 800_000;

    #[test]
    fn straight_od_turning_with_tip_3_runs_as_programmed() {
        let (a, b, c, d) =
            ((25_000_000, 2_000_000), (20_000_000, 2_000_000), (20_000_000, -20_000_000), (25_000_000, -20_000_000));
        assert_eq!(single(a, b, c, d, true, Nose { radius: R, tip: 3 }), Ok([b, c, d]));
    }

    #[test]
    fn tip_0_puts_the_centre_one_radius_inside() {
        let (a, b, c, d) =
            ((25_000_000, 2_000_000), (20_000_000, 2_000_000), (20_000_000, -20_000_000), (25_000_000, -20_000_000));
        let got = single(a, b, c, d, true, Nose { radius: R, tip: 0 }).unwrap();
        assert_eq!(
            got,
            [(20_000_000 + R, 2_000_000), (20_000_000 + R, -20_000_000 + R), (25_000_000, -20_000_000 + R)]
        );
    }
}

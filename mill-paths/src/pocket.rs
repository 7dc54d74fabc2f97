//! Rectangular and circular pockets (SINUMERIK POCKET1/POCKET2, seed 001 lines
//! 4421-4712): one generator for both. A pocket is a rectangle of half length
//! `hl`, half width `hw` with corner radius `cr` about its centre, its length
//! turned by STA1 from the abscissa; a circle of radius R is the rectangle
//! 2R × 2R with corner radius R, so the same ring path cuts both.
//!
//! The tool centre runs on *rings*: the pocket wall offset inwards by the cutter
//! radius plus an allowance, and further inwards by `d`. A ring of offset `d` has
//! half sides `A − d`, `B − d` and corner radius `max(q − d, 0)` (A, B, q: the
//! outermost ring's); the innermost ring (`d` = the smaller half side) is a
//! line along the longer side (a point for a square or a circle). Roughing cuts,
//! level by level (plunged at the centre, line 4486), the rings from the inside
//! out, `n` + 1 of them at equal steps of at most the width infeed; finishing
//! cuts the wall ring at allowance 0, level by level per MIDF. Moves of zero
//! length (a degenerate ring's sides and corners) are left out.

use crate::infeed::{Levels, parts};
use crate::rot::Rot;
use crate::{Move, P3};

/// What a pocket call cuts, in the pocket's own axes (nm; the centre and the
/// angle in `rot`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PocketSpec {
    /// Centre and angle of the length (STA1).
    pub rot: Rot,
    /// Half length, half width, corner radius of the wall.
    pub hl: i64,
    /// Half width.
    pub hw: i64,
    /// Corner radius (a circle: `hl` = `hw` = `cr`).
    pub cr: i64,
    /// Cutter radius.
    pub r: i64,
    /// Wall allowance left by roughing (FAL).
    pub fal: i64,
    /// Largest step between rings in the plane.
    pub step: i64,
    /// Retract plane, and the safety level above the reference plane.
    pub rtp: i64,
    /// RFP + SDIS.
    pub safe: i64,
    /// Roughing levels (MID); `count` 0: no roughing.
    pub rough: Levels,
    /// Finishing levels (MIDF); `count` 0: no finishing.
    pub finish: Levels,
    /// Feeds: into the depth (FFD), roughing (FFP1), finishing (FFP2).
    pub feeds: [i64; 3],
    /// Finishing spindle speed (SSF), 0: the speed in force.
    pub ssf: u32,
    /// Rings clockwise (G2).
    pub cw: bool,
}

/// The pocket generator: its spec and where it is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pocket {
    s: PocketSpec,
    /// Stage: 0 rapid to RTP, 1 to the safety level, 2 roughing, 3 back to the
    /// safety level, 4 the finishing speed, 5 finishing, 6 rapid to RTP, 7 done.
    stage: u8,
    /// Element of the ring or level being cut.
    el: u8,
    /// Level (1-based) and ring of the pass.
    level: u32,
    ring: u32,
    /// The last point handed out (zero-length moves are left out).
    last: P3,
}

impl Pocket {
    /// The generator of `s`.
    pub fn new(s: PocketSpec) -> Self {
        Pocket { s, stage: 0, el: 0, level: 1, ring: 0, last: P3::new(i64::MIN, i64::MIN, i64::MIN) }
    }

    /// The move at the cursor (`Some(None)`: nothing here), and the cursor on.
    #[inline(never)]
    fn step(&mut self) -> Option<Option<Move>> {
        let s = self.s;
        let centre = |d| {
            let (a, o) = s.rot.at;
            P3::new(a, o, d)
        };
        let m = match self.stage {
            0 | 6 => Move::Rapid(centre(s.rtp)),
            1 | 3 => Move::Rapid(centre(s.safe)),
            2 | 5 => return Some(self.pass()),
            4 if s.ssf > 0 && s.finish.count > 0 => Move::Speed(s.ssf),
            4 => {
                self.stage += 1;
                return Some(None);
            }
            _ => return None,
        };
        self.stage += 1;
        Some(Some(m))
    }

    /// The move of a roughing (stage 2) or finishing (stage 5) pass at the
    /// cursor: per level, the plunge at the centre, then each ring reached by a
    /// line along the length from the last ring's start, then back to the centre.
    fn pass(&mut self) -> Option<Move> {
        let s = self.s;
        let finish = self.stage == 5;
        let (levels, fal, feed) = if finish { (s.finish, 0, s.feeds[2]) } else { (s.rough, s.fal, s.feeds[1]) };
        // The outermost ring: half sides and corner radius of the tool centre.
        let off = s.r + fal;
        let (a, b) = ((s.hl - off).max(0), (s.hw - off).max(0));
        let q = (s.cr - off).clamp(0, a.min(b));
        let m = a.min(b);
        let n = if finish { 0 } else { parts(m, s.step) };
        if self.level > levels.count {
            (self.stage, self.level, self.el) = (self.stage + 1, 1, 0);
            return None;
        }
        let lvl = levels.level(self.level);
        let d = if finish { 0 } else { m - m * i64::from(self.ring) / i64::from(n.max(1)) };
        let (a, b, q) = (a - d, b - d, (q - d).max(0));
        let el = self.el;
        self.el += 1;
        // The move in the pocket's axes: its end, an arc's centre, its feed.
        let (mut to, mut arc, mut f) = ((a, 0), None, feed);
        match el {
            0 => (to, f) = ((0, 0), s.feeds[0]),
            1 => {}
            2..=9 => (to, arc) = ring_el(a, b, q, el),
            10 => {
                if self.ring < n {
                    (self.ring, self.el) = (self.ring + 1, 1);
                }
            }
            _ => {
                (self.level, self.ring, self.el) = (self.level + 1, 0, 0);
                to = (0, 0);
            }
        }
        Some(self.plane(to, arc, lvl, f))
    }

    /// A move of the pocket's axes in the plane (G2 rings mirror the ordinate).
    fn plane(&self, to: (i64, i64), arc: Option<(i64, i64)>, d: i64, feed: i64) -> Move {
        plane_move(&self.s.rot, self.s.cw, to, arc.map(|c| (c, false)), d, feed)
    }
}

/// Element `el` (2..=10) of the ring of half sides `a`, `b` and corner radius `q`
/// that starts at (`a`, 0) and runs counterclockwise: quadrant `(el − 2) / 2`'s
/// side up to its corner (even `el`), the corner's arc (odd: its centre
/// returned), and at 10 the half side back to the start. Its end.
pub(crate) fn ring_el(a: i64, b: i64, q: i64, el: u8) -> ((i64, i64), Option<(i64, i64)>) {
    if !(2..=9).contains(&el) {
        return ((a, 0), None);
    }
    // Quadrant i: a side up to the corner, then the corner's arc: its centre C,
    // from C + q·u(i) to C + q·u(i + 1).
    let i = usize::from((el - 2) / 2);
    let unit = |k: usize| [(1, 0), (0, 1), (-1, 0), (0, -1)][k & 3];
    let c = ([1, -1, -1, 1][i & 3] * (a - q), [1, 1, -1, -1][i & 3] * (b - q));
    let u = unit(i + usize::from(el % 2));
    ((c.0 + q * u.0, c.1 + q * u.1), if el % 2 == 1 { Some(c) } else { None })
}

/// A move in turned axes `rot` in the plane: a line to `to`, or an arc about the
/// centre of `arc` (its bool: clockwise in those axes), at applicate `d`; `mirror`
/// mirrors the ordinate (and so every arc's sense: a G2 ring drawn as a G3 one).
#[inline(never)]
pub(crate) fn plane_move(
    rot: &Rot,
    mirror: bool,
    to: (i64, i64),
    arc: Option<((i64, i64), bool)>,
    d: i64,
    feed: i64,
) -> Move {
    let at = |(u, v): (i64, i64)| {
        let (x, y) = rot.point(u as f64, if mirror { -v } else { v } as f64);
        P3::new(x, y, d)
    };
    match arc {
        None => Move::Line { to: at(to), feed },
        Some((c, cw)) => {
            let c = at(c);
            Move::Arc { to: at(to), centre: (c.a, c.o), cw: cw != mirror, feed }
        }
    }
}

impl Iterator for Pocket {
    type Item = Move;

    /// The next move, `None` when the pocket is done.
    fn next(&mut self) -> Option<Move> {
        loop {
            let m = self.step()?;
            let Some(m) = m else { continue };
            let Some(to) = crate::end_of(&m) else { return Some(m) };
            if to != self.last {
                self.last = to;
                return Some(m);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec::Vec;

    fn spec(hl: i64, hw: i64, cr: i64) -> PocketSpec {
        PocketSpec {
            rot: Rot::new((0, 0), 0.0),
            hl,
            hw,
            cr,
            r: 5_000_000,
            fal: 0,
            step: 8_000_000,
            rtp: 5_000_000,
            safe: 1_000_000,
            rough: Levels::new(1_000_000, -10_000_000, 6_000_000),
            finish: Levels::new(1_000_000, -10_000_000, 0),
            feeds: [100, 200, 300],
            ssf: 0,
            cw: false,
        }
    }

    fn moves(s: PocketSpec) -> Vec<Move> {
        let mut g = Pocket::new(s);
        core::iter::from_fn(|| g.next()).collect()
    }

    /// A circle: the rings are full circles of four quarter arcs, every arc's
    /// end at its radius from the centre, the last at R − r.
    #[test]
    fn a_circle_is_cut_in_quarter_arcs() {
        let m = moves(spec(20_000_000, 20_000_000, 20_000_000));
        let arcs: Vec<_> =
            m.iter().filter_map(|m| if let Move::Arc { to, .. } = m { Some(*to) } else { None }).collect();
        assert!(!arcs.is_empty());
        let rmax = arcs.iter().map(|p| libm::hypot(p.a as f64, p.o as f64) as i64).max().unwrap();
        assert_eq!(rmax, 15_000_000);
        assert_eq!(m.first(), Some(&Move::Rapid(P3::new(0, 0, 5_000_000))));
        assert_eq!(m.last(), Some(&Move::Rapid(P3::new(0, 0, 5_000_000))));
    }

    /// A rectangle 60 × 40 with a 5 mm cutter: the tool centre's half sides are
    /// 25 × 15, the rings 7.5 mm apart (15 mm in the fewest steps of at most 8):
    /// each starts (and closes) on the length axis, at 10, 17.5 and 25 mm from the centre.
    #[test]
    fn rectangle_rings_step_outwards() {
        let s = PocketSpec {
            finish: Levels { count: 0, ..spec(0, 0, 0).finish },
            ..spec(30_000_000, 20_000_000, 8_000_000)
        };
        let first = s.rough.level(1);
        let mut starts: Vec<i64> = moves(s)
            .iter()
            .filter_map(|m| match m {
                Move::Line { to, .. } if to.o == 0 && to.a > 0 && to.d == first => Some(to.a),
                _ => None,
            })
            .collect();
        // Each ring is reached there and closed there.
        starts.dedup();
        assert_eq!(starts, [10_000_000, 17_500_000, 25_000_000]);
    }

    /// The generator is pure: two runs give the same moves.
    #[test]
    fn two_runs_agree() {
        let s = spec(30_000_000, 20_000_000, 8_000_000);
        assert_eq!(moves(s), moves(s));
    }
}

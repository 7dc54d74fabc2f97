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
//!
//! POCKET3/POCKET4 (lines 4714-5258, any cutter) add: the insertion ([`Insert`]:
//! G0, G1, a helix in whole turns, an oscillation along the length), a
//! pre-machined pocket whose air is not cut again, the wall finish reached and
//! left on quarter arcs, and the floor finish (one level of rings).

use crate::infeed::{Levels, parts};
use crate::rot::Rot;
use crate::{Move, P3};

/// Whether the parts only POCKET3/POCKET4 use are built (mill-paths' feature
/// `pocket34`): without them a pre-machined pocket, a finishing approach arc and
/// full turns are never cut, and the helix and oscillation do not exist.
const P34: bool = cfg!(feature = "pocket34");

/// How a pass gets down to its level at the pocket's centre.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Insert {
    /// G0 straight down (POCKET3/4 `_VARI` 0x: into a pre-drilled hole).
    Rapid,
    /// G1 at the depth feed straight down (POCKET1/2; POCKET3/4 `_VARI` 1x).
    Feed,
    /// On a helix of radius `rad` about the centre in the rings' direction, in
    /// whole turns of at most `pitch`, then one flat turn (`_VARI` 2x).
    #[cfg(feature = "pocket34")]
    Helix {
        /// Helix radius (tool centre, `_RAD1`).
        rad: i64,
        /// Largest depth per turn (`_DP1`).
        pitch: i64,
    },
    /// Oscillating along the length (centre → +L → centre → −L → centre) at a
    /// slope of at most `tan`, then one flat oscillation (`_VARI` 3x). L is the
    /// outermost roughing ring's half length.
    #[cfg(feature = "pocket34")]
    Swing {
        /// Tangent of the largest insertion angle (`_RAD1`).
        tan: f64,
    },
}

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
    /// Finishing levels of the wall (MIDF); `count` 0: no finishing.
    pub finish: Levels,
    /// Floor finishing (POCKET3/4): one level, from the applicate the tool is
    /// taken to at G0 (`from`) down to the floor (`to`); `count` 0: none.
    pub floor: Levels,
    /// How roughing gets down to each level.
    pub insert: Insert,
    /// Finishing approach (POCKET3/4): the wall ring is reached on a quarter arc
    /// of this radius, tangentially, and left on another; the levels are reached
    /// at G0. 0: plunged at FFD and reached on a line (POCKET1/2).
    pub arc_in: i64,
    /// Pre-machined pocket (POCKET3/4 `_AP1`, `_AP2`, `_AD`): its half length,
    /// half width (wall, not tool centre) and the applicate of its floor; a half
    /// length of 0: none. Roughing leaves out the rings that would cut only its
    /// air above its floor.
    pub blank: [i64; 3],
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
    /// safety level, 4 the finishing speed, 5 finishing the wall, 6 the floor,
    /// 7 rapid to RTP, 8 done.
    stage: u8,
    /// Element of the ring or level being cut.
    el: u8,
    /// Level (1-based) and ring of the pass.
    level: u32,
    ring: u32,
    /// Move of the insertion (element 0).
    sub: u32,
    /// The last point handed out (zero-length moves are left out).
    last: P3,
}

impl Pocket {
    /// The generator of `s`.
    pub fn new(s: PocketSpec) -> Self {
        Pocket { s, stage: 0, el: 0, level: 1, ring: 0, sub: 0, last: P3::new(i64::MIN, i64::MIN, i64::MIN) }
    }

    /// The move at the cursor (`Some(None)`: nothing here), and the cursor on.
    #[inline(never)]
    fn step(&mut self) -> Option<Option<Move>> {
        let s = self.s;
        let m = match self.stage {
            0 | 7 => Move::Rapid(self.pt((0, 0), s.rtp)),
            1 | 3 => Move::Rapid(self.pt((0, 0), s.safe)),
            2 | 5 | 6 => return Some(self.pass()),
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

    /// The move of a roughing (stage 2), wall finishing (5) or floor (6) pass at
    /// the cursor: per level, the insertion at the centre, then each ring reached
    /// by a line along the length from the last ring's start (finishing with an
    /// approach arc: one ring, reached and left on quarter arcs), then back to the
    /// centre.
    fn pass(&mut self) -> Option<Move> {
        let s = self.s;
        let stage = self.stage;
        let (levels, fal, feed) = match stage {
            2 => (s.rough, s.fal, s.feeds[1]),
            5 => (s.finish, 0, s.feeds[2]),
            _ => (s.floor, 0, s.feeds[2]),
        };
        let arc_in = if P34 && stage == 5 { s.arc_in } else { 0 };
        // The outermost ring: half sides and corner radius of the tool centre.
        let off = s.r + fal;
        let (a, b) = ((s.hl - off).max(0), (s.hw - off).max(0));
        let q = (s.cr - off).clamp(0, a.min(b));
        let m = a.min(b);
        let n = if stage == 5 { 0 } else { parts(m, s.step) };
        if self.level > levels.count {
            (self.stage, self.level, self.el, self.sub) = (stage + 1, 1, 0, 0);
            return None;
        }
        let (prev, lvl) = (levels.level(self.level - 1), levels.level(self.level));
        // Above the pre-machined pocket's floor only air is inside it.
        let blank = s.blank;
        let in_blank = P34 && stage == 2 && blank[0] > 0 && (lvl - blank[2]) * (levels.to - levels.from).signum() <= 0;
        if self.el == 0 {
            let how = match stage {
                // Room at the centre: straight down in the air (line 4923).
                2 if in_blank && blank[0].min(blank[1]) >= s.r => Insert::Feed,
                2 => s.insert,
                5 if arc_in > 0 => Insert::Rapid,
                _ => Insert::Feed,
            };
            return self.plunge(how, prev, lvl, a);
        }
        let d = if n == 0 { 0 } else { m - m * i64::from(self.ring) / i64::from(n) };
        let (a, b, q) = (a - d, b - d, (q - d).max(0));
        let rho = arc_in.min(a).min(b);
        let el = self.el;
        self.el += 1;
        // The move in the pocket's axes: its end, an arc's centre, its feed.
        let (mut to, mut arc) = ((a, 0), None);
        match el {
            1 if arc_in > 0 => return Some(Move::Rapid(self.pt((a - rho, -rho), lvl))),
            1 if in_blank && self.ring < n && a + s.r <= blank[0] && b + s.r <= blank[1] => {
                // This ring cuts only air: on to the next.
                (self.ring, self.el) = (self.ring + 1, 1);
                return None;
            }
            1 => {}
            2 if arc_in > 0 => arc = Some((a - rho, 0)),
            2 => return None,
            // The ring (main's elements 2..=10, one on here): sides and corners,
            // and at 11 the half side back to where it started.
            3..=11 => (to, arc) = ring_el(a, b, q, el - 1),
            12 if arc_in > 0 => (to, arc) = ((a - rho, rho), Some((a - rho, 0))),
            12 => {
                if self.ring < n {
                    (self.ring, self.el) = (self.ring + 1, 1);
                }
                return None;
            }
            _ => {
                (self.level, self.ring, self.el) = (self.level + 1, 0, 0);
                to = (0, 0);
            }
        }
        Some(self.plane(to, arc, lvl, feed))
    }

    /// Move `sub` of the insertion from `prev` down to `lvl` at the centre (`len`:
    /// the oscillation's half length): first G0 to the centre at `prev` (left out
    /// when the tool is there), then `how`'s moves; element 1 follows.
    #[cfg_attr(not(feature = "pocket34"), allow(unused_variables))]
    fn plunge(&mut self, how: Insert, prev: i64, lvl: i64, len: i64) -> Option<Move> {
        let k = self.sub;
        self.sub = k.saturating_add(1);
        if k == 0 {
            return Some(Move::Rapid(self.pt((0, 0), prev)));
        }
        // The applicate `t`/`n` of the way down.
        #[cfg(feature = "pocket34")]
        let at = |t: u32, count: u32| Levels { from: prev, to: lvl, count }.level(t);
        let f = self.s.feeds[0];
        let (last, m) = match how {
            Insert::Rapid => (true, Move::Rapid(self.pt((0, 0), lvl))),
            Insert::Feed => (true, self.plane((0, 0), None, lvl, f)),
            #[cfg(feature = "pocket34")]
            Insert::Helix { rad, pitch } => {
                // The start on the length at G1, whole turns, one flat turn.
                // (Capped so that the flat turn still comes after the last one.)
                let n = parts(lvl - prev, pitch).min(u32::MAX - 2);
                let t = k - 1;
                let d = if t == 0 { prev } else { at(t.min(n), n) };
                (t > n, self.plane((rad, 0), (t > 0).then_some((0, 0)), d, f))
            }
            #[cfg(feature = "pocket34")]
            Insert::Swing { tan } => {
                let n = parts(lvl - prev, libm::round(4.0 * len as f64 * tan) as i64).saturating_mul(4);
                let u = [len, 0, -len, 0][(k as usize - 1) & 3];
                (k >= n.saturating_add(4), self.plane((u, 0), None, at(k.min(n), n), f))
            }
        };
        if last {
            (self.sub, self.el) = (0, 1);
        }
        Some(m)
    }

    /// The plane point of the pocket's axes `(u, v)` at applicate `d` (G2 rings
    /// mirror the pocket's ordinate).
    fn pt(&self, uv: (i64, i64), d: i64) -> P3 {
        plane_pt(&self.s.rot, self.s.cw, uv, d)
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

/// The point `(u, v)` of turned axes `rot` at applicate `d`; `mirror` mirrors the
/// ordinate.
fn plane_pt(rot: &Rot, mirror: bool, (u, v): (i64, i64), d: i64) -> P3 {
    let (x, y) = rot.point(u as f64, if mirror { -v } else { v } as f64);
    P3::new(x, y, d)
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
    let at = |uv| plane_pt(rot, mirror, uv, d);
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
            // Moves of zero length (and arcs of radius 0) are left out; an arc
            // back to where it starts is a full turn.
            let turn = P34 && matches!(m, Move::Arc { centre, .. } if centre != (to.a, to.o));
            if turn || to != self.last {
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
            floor: Levels { count: 0, ..Levels::new(0, 0, 0) },
            insert: Insert::Feed,
            arc_in: 0,
            blank: [0; 3],
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

    /// A helix insertion: whole turns of at most the pitch (a 7 mm infeed at
    /// 3 mm a turn: three turns of 7/3 mm), full circles kept, one flat turn.
    #[test]
    #[cfg(feature = "pocket34")]
    fn helix_turns_are_whole_and_end_flat() {
        let s = PocketSpec {
            rough: Levels::new(1_000_000, -6_000_000, 0),
            finish: Levels { count: 0, ..spec(0, 0, 0).finish },
            insert: Insert::Helix { rad: 3_000_000, pitch: 3_000_000 },
            ..spec(20_000_000, 20_000_000, 20_000_000)
        };
        let turns: Vec<P3> = moves(s)
            .iter()
            .filter_map(|m| match m {
                Move::Arc { to, centre: (0, 0), .. } if to.a == 3_000_000 && to.o == 0 => Some(*to),
                _ => None,
            })
            .collect();
        let d: Vec<i64> = turns.iter().map(|p| p.d).collect();
        assert_eq!(d, [-1_333_333, -3_666_667, -6_000_000, -6_000_000]);
    }

    /// The generator is pure: two runs give the same moves.
    #[test]
    fn two_runs_agree() {
        let s = spec(30_000_000, 20_000_000, 8_000_000);
        assert_eq!(moves(s), moves(s));
    }
}

//! Rectangular and circular spigots (SINUMERIK CYCLE76, CYCLE77, seed 001 lines
//! 5766-6111): one generator for both. A spigot is the rounded rectangle of the
//! pockets ([`crate::pocket`]: half length `hl`, half width `hw`, corner radius
//! `cr` about its centre, turned by `_STA`); a circle of diameter D is the square
//! of side D with corner radius D/2.
//!
//! The tool centre runs once round the spigot per level, outside it at the
//! cutter radius plus the wall allowance, starting and ending on the spigot's
//! length axis (0°, lines 5822, 6004). It is reached and left by semicircles
//! tangent to that ring, on the plus side of the length axis: the plunge point
//! `S` lies a semicircle's diameter beyond the ring, clear of the blank (`_AP1`)
//! by a cutter radius, so the semicircle's radius follows from the blank (lines
//! 5917, 6079). Per level: the infeed at `S` at FFD (the first from RFP + SDIS,
//! reached in G0, lines 5824, 6006), the approach semicircle, the ring, the
//! retreating semicircle back to `S`; then G0 to RTP over `S`.
//!
//! Rings run counterclockwise (G3) in the spigot's axes; a G2 spigot mirrors the
//! ordinate (the semicircles always turn the other way from the ring).

use crate::infeed::Levels;
use crate::pocket::{plane_move, ring_el};
use crate::rot::Rot;
use crate::{Move, P3};

/// What a CYCLE76/CYCLE77 call cuts (nm; centre and angle in `rot`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpigotSpec {
    /// Centre and angle of the length (`_STA`).
    pub rot: Rot,
    /// Half length of the spigot.
    pub hl: i64,
    /// Half width.
    pub hw: i64,
    /// Corner radius (a circle: `hl` = `hw` = `cr`).
    pub cr: i64,
    /// Cutter radius.
    pub r: i64,
    /// Wall allowance of the pass (roughing `_FAL`, finishing 0).
    pub fal: i64,
    /// Half the blank's length along the spigot's length (`_AP1` / 2).
    pub blank: i64,
    /// Where the tool is at the call (abscissa, ordinate): it goes up to RTP there.
    pub here: (i64, i64),
    /// Retract plane.
    pub rtp: i64,
    /// RFP + SDIS.
    pub safe: i64,
    /// The levels cut.
    pub levels: Levels,
    /// Feeds: into the depth (`_FFD`), on the contour (`_FFP1`).
    pub feeds: [i64; 2],
    /// Rings clockwise (G2).
    pub cw: bool,
}

/// The spigot generator.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spigot {
    s: SpigotSpec,
    /// 0 up to RTP, 1 over `S`, 2 down to RFP + SDIS, 3 the levels, 4 RTP, 5 done.
    stage: u8,
    el: u8,
    level: u32,
    last: P3,
}

impl Spigot {
    /// The generator of `s`.
    pub fn new(s: SpigotSpec) -> Self {
        Spigot { s, stage: 0, el: 0, level: 1, last: P3::new(i64::MIN, i64::MIN, i64::MIN) }
    }

    /// The ring's half sides and corner radius, and the abscissa of `S`.
    pub fn ring(&self) -> (i64, i64, i64, i64) {
        let s = &self.s;
        let off = s.r.saturating_add(s.fal);
        let (a, b, q) = (s.hl.saturating_add(off), s.hw.saturating_add(off), s.cr.saturating_add(off));
        let start = s.blank.saturating_add(s.r).max(a).saturating_add(s.r);
        (a, b, q, start)
    }

    /// The move at the cursor (`Some(None)`: nothing here), and the cursor on.
    #[inline(never)]
    fn step(&mut self) -> Option<Option<Move>> {
        let s = self.s;
        let (a, b, q, sx) = self.ring();
        let start = |d| plane_move(&s.rot, s.cw, (sx, 0), None, d, 0);
        let m = match self.stage {
            0 => Move::Rapid(P3::new(s.here.0, s.here.1, s.rtp)),
            1 | 4 => start(s.rtp),
            2 => start(s.safe),
            3 => {
                if self.level > s.levels.count {
                    self.stage = 4;
                    return Some(None);
                }
                let d = s.levels.level(self.level);
                let el = self.el;
                self.el += 1;
                // The semicircles' centre, between the ring and S.
                let mid = (a + (sx - a) / 2, 0);
                let (to, arc, feed) = match el {
                    0 => ((sx, 0), None, s.feeds[0]),
                    1 => ((a, 0), Some((mid, true)), s.feeds[1]),
                    2..=10 => {
                        let (to, c) = ring_el(a, b, q, el);
                        (to, c.map(|c| (c, false)), s.feeds[1])
                    }
                    _ => {
                        (self.level, self.el) = (self.level + 1, 0);
                        ((sx, 0), Some((mid, true)), s.feeds[1])
                    }
                };
                return Some(Some(plane_move(&s.rot, s.cw, to, arc, d, feed)));
            }
            _ => return None,
        };
        self.stage += 1;
        Some(Some(match m {
            Move::Line { to, .. } => Move::Rapid(to),
            m => m,
        }))
    }
}

impl Iterator for Spigot {
    type Item = Move;

    /// The next move, `None` when the spigot is done.
    fn next(&mut self) -> Option<Move> {
        loop {
            let Some(m) = self.step()? else { continue };
            if let Some(m) = crate::moved(&mut self.last, m) {
                return Some(m);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec::Vec;

    fn spec(hl: i64, hw: i64, cr: i64) -> SpigotSpec {
        SpigotSpec {
            rot: Rot::new((0, 0), 0.0),
            hl,
            hw,
            cr,
            r: 5_000_000,
            fal: 1_000_000,
            blank: 40_000_000,
            here: (0, 0),
            rtp: 10_000_000,
            safe: 2_000_000,
            levels: Levels::new(2_000_000, -10_000_000, 6_000_000),
            feeds: [100, 200],
            cw: false,
        }
    }

    fn moves(s: SpigotSpec) -> Vec<Move> {
        let mut g = Spigot::new(s);
        core::iter::from_fn(|| g.next()).collect()
    }

    /// A circle of radius 25: every ring arc 31 mm from the centre (r 5 + FAL
    /// 1), the semicircles from S (the blank's 40 + 2 · 5 = 50) to the ring.
    #[test]
    fn a_circular_spigot() {
        let m = moves(spec(25_000_000, 25_000_000, 25_000_000));
        let arcs: Vec<(P3, (i64, i64), bool)> = m
            .iter()
            .filter_map(|m| if let Move::Arc { to, centre, cw, .. } = m { Some((*to, *centre, *cw)) } else { None })
            .collect();
        // Per level: approach, four quarters, retreat.
        assert_eq!(arcs.len(), 6 * 2);
        for (to, c, cw) in &arcs[1..5] {
            assert_eq!((*c, *cw), ((0, 0), false));
            assert_eq!(libm::round(libm::hypot(to.a as f64, to.o as f64)) as i64, 31_000_000);
        }
        assert_eq!((arcs[0].1, arcs[0].2), ((40_500_000, 0), true));
        assert_eq!(arcs[5].0, P3::new(50_000_000, 0, -4_000_000));
        assert_eq!(m.last(), Some(&Move::Rapid(P3::new(50_000_000, 0, 10_000_000))));
    }

    #[test]
    fn two_runs_agree() {
        let s = SpigotSpec { cw: true, ..spec(30_000_000, 20_000_000, 8_000_000) };
        assert_eq!(moves(s), moves(s));
    }
}

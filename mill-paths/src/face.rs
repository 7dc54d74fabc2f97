//! Face milling (SINUMERIK CYCLE71, seed 001 lines 5260-5448): a rectangle of the
//! plane — a corner, a signed length and width, turned by `_STA` about the corner
//! — is cut level by level in straight paths parallel to its length or its width,
//! all in one direction or alternating.
//!
//! In the cut's own coordinates `s` runs along a path (0 to the face's extent
//! `ls` in that direction) and `t` across the paths (0 to `wt`):
//! - a path runs from `−(r + FDP)` to `ls + r + FDP`: the cutter clears the face
//!   by the overrun `_FDP` at both ends, where the depth infeeds are made in G0
//!   (lines 5314, 5365);
//! - the first path engages exactly `_MIDA` of the width (its centre at
//!   `_MIDA − r`, so the cutter runs `2r − _MIDA` outside the edge, lines 5315-5317),
//!   the last lies at `wt + FDP1 − r` (line 5369), the paths between at equal
//!   steps of at most `_MIDA`; when `wt + FDP1 ≤ _MIDA` the first path is the
//!   only one (line 5317).
//!
//! Between paths in one direction the cutter lifts (roughing: the infeed + the
//! safety distance, i.e. to the level above + SDIS; finishing: `_FALD` + SDIS,
//! lines 5325-5327) and returns in G0; alternating, it steps across at the end
//! of a path at the feed. Each level starts at the first path's start (line
//! 5327); after the last level the cutter goes up to RTP where it is (5329).

use crate::infeed::{Levels, parts};
use crate::rot::Rot;
use crate::{Move, P3};

/// What a CYCLE71 call cuts (nm).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceSpec {
    /// The corner (`_PA`, `_PO`) and the angle of the length (`_STA`).
    pub rot: Rot,
    /// Length along the face's first axis and width along its second, signed:
    /// the side of the corner the face lies on.
    pub leng: i64,
    /// Width (signed).
    pub wid: i64,
    /// Paths parallel to the face's second axis (`_VARI` tens 2, 4).
    pub along_wid: bool,
    /// Alternating directions (`_VARI` tens 3, 4).
    pub zigzag: bool,
    /// Cutter radius.
    pub r: i64,
    /// Largest width infeed (`_MIDA`, or 80 % of the diameter).
    pub step: i64,
    /// Overrun in the cutting direction (`_FDP`) and across (`_FDP1`).
    pub fdp: i64,
    /// Overrun across.
    pub fdp1: i64,
    /// Applicate of the tool at the call (the approach runs at it).
    pub from: i64,
    /// Retract plane, RFP + SDIS, SDIS.
    pub rtp: i64,
    /// RFP + SDIS.
    pub safe: i64,
    /// Safety distance.
    pub sdis: i64,
    /// Into the material: −1 down the applicate, +1 up.
    pub dir: i64,
    /// The levels cut (roughing per `_MID` to `_DP` + `_FALD`; finishing `_DP`).
    pub levels: Levels,
    /// Finishing: the lift between one-direction paths is `_FALD` + SDIS.
    pub finish: bool,
    /// `_FALD`.
    pub fald: i64,
    /// `_FFP1`.
    pub feed: i64,
}

/// The face generator: its spec and where it is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Face {
    s: FaceSpec,
    /// 0 approach at the call's height, 1 down to RFP + SDIS, 2 the levels, 3 RTP.
    stage: u8,
    el: u8,
    level: u32,
    path: u32,
    last: P3,
}

impl Face {
    /// The generator of `s`.
    pub fn new(s: FaceSpec) -> Self {
        Face { s, stage: 0, el: 0, level: 1, path: 0, last: P3::new(i64::MIN, i64::MIN, i64::MIN) }
    }

    /// Extent along the paths and across them.
    fn extents(&self) -> (i64, i64) {
        let (l, w) = (self.s.leng.unsigned_abs() as i64, self.s.wid.unsigned_abs() as i64);
        if self.s.along_wid { (w, l) } else { (l, w) }
    }

    /// Number of paths and the across position of path `j`.
    fn paths(&self) -> (u32, i64, i64) {
        let s = &self.s;
        let (_, wt) = self.extents();
        let first = s.step - s.r;
        let last = wt.saturating_add(s.fdp1) - s.r;
        if last <= first {
            return (1, first, first);
        }
        (parts(last - first, s.step).saturating_add(1), first, last)
    }

    /// The plane point of cut coordinates (`s` along, `t` across) at `d`.
    fn at(&self, s: i64, t: i64, d: i64) -> P3 {
        let f = &self.s;
        let (u, v) = if f.along_wid { (t, s) } else { (s, t) };
        let (u, v) = (if f.leng < 0 { -u } else { u }, if f.wid < 0 { -v } else { v });
        let (a, o) = f.rot.point(u as f64, v as f64);
        P3::new(a, o, d)
    }

    /// Start and end (along) of path `j`.
    fn ends(&self, j: u32) -> (i64, i64) {
        let (ls, _) = self.extents();
        let over = self.s.r.saturating_add(self.s.fdp);
        let (a, b) = (-over, ls.saturating_add(over));
        if self.s.zigzag && j % 2 == 1 { (b, a) } else { (a, b) }
    }

    /// Where the cutter lifts to after level `k`.
    fn lift(&self, k: u32) -> i64 {
        let s = &self.s;
        let lvl = s.levels.level(k);
        if s.finish { lvl - s.dir * (s.fald + s.sdis) } else { s.levels.level(k - 1) - s.dir * s.sdis }
    }

    /// The move at the cursor (`Some(None)`: nothing here), and the cursor on.
    #[inline(never)]
    fn step(&mut self) -> Option<Option<Move>> {
        let s = self.s;
        let (n, first, last) = self.paths();
        // In f64: (last − first) · j overflows i64 for a 10 m face cut in 1 nm steps.
        let t = |j: u32| {
            first + crate::rot::round((last - first) as f64 * f64::from(j) / f64::from(n.saturating_sub(1).max(1)))
        };
        let (a0, _) = self.ends(0);
        match self.stage {
            0 => {
                self.stage = 1;
                return Some(Some(Move::Rapid(self.at(a0, first, s.from))));
            }
            1 => {
                self.stage = 2;
                return Some(Some(Move::Rapid(self.at(a0, first, s.safe))));
            }
            2 => {}
            3 => {
                self.stage = 4;
                return Some(Some(Move::Rapid(self.last.at(s.rtp))));
            }
            _ => return None,
        }
        let (k, j) = (self.level, self.path);
        if k > s.levels.count {
            self.stage = 3;
            return Some(None);
        }
        let lvl = s.levels.level(k);
        let (from, to) = self.ends(j);
        let tj = t(j);
        let el = self.el;
        self.el += 1;
        let m = match el {
            // To the path's start: across at the level (alternating), else in G0
            // above it.
            0 if s.zigzag && j > 0 => Move::Line { to: self.at(from, tj, lvl), feed: s.feed },
            0 => {
                let hover = match (j, k) {
                    (0, 1) => s.safe,
                    (0, _) => self.lift(k - 1),
                    _ => self.lift(k),
                };
                Move::Rapid(self.at(from, tj, hover))
            }
            1 => Move::Rapid(self.at(from, tj, lvl)),
            2 => Move::Line { to: self.at(to, tj, lvl), feed: s.feed },
            _ => {
                self.el = 0;
                let end = j + 1 >= n;
                if end {
                    (self.level, self.path) = (k + 1, 0);
                } else {
                    self.path = j + 1;
                }
                // Alternating, the next path is reached at the level; after the
                // last level the cutter goes straight up to RTP.
                if (s.zigzag && !end) || (end && k >= s.levels.count) {
                    return Some(None);
                }
                Move::Rapid(self.at(to, tj, self.lift(k)))
            }
        };
        Some(Some(m))
    }
}

impl Iterator for Face {
    type Item = Move;

    /// The next move, `None` when the face is done.
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

    fn spec() -> FaceSpec {
        FaceSpec {
            rot: Rot::new((0, 0), 0.0),
            leng: 60_000_000,
            wid: 40_000_000,
            along_wid: false,
            zigzag: true,
            r: 10_000_000,
            step: 10_000_000,
            fdp: 5_000_000,
            fdp1: 2_000_000,
            from: 20_000_000,
            rtp: 10_000_000,
            safe: 2_000_000,
            sdis: 2_000_000,
            dir: -1,
            levels: Levels::new(2_000_000, -11_000_000, 6_000_000),
            finish: false,
            fald: 0,
            feed: 4_000,
        }
    }

    fn moves(s: FaceSpec) -> Vec<Move> {
        let mut g = Face::new(s);
        core::iter::from_fn(|| g.next()).collect()
    }

    /// The document's example (without the angle): paths from 0 to 32 mm across
    /// (the first at MIDA − r = 0, the last at WID + FDP1 − r = 32) in 4 steps of
    /// 8 mm, each from −15 to 75 mm along, alternating.
    #[test]
    fn paths_step_across_by_at_most_mida() {
        let m = moves(spec());
        let cuts: Vec<P3> = m
            .iter()
            .filter_map(|m| match m {
                Move::Line { to, .. } if to.d == -11_000_000 => Some(*to),
                _ => None,
            })
            .collect();
        let along: Vec<(i64, i64)> = cuts.iter().map(|p| (p.a, p.o)).collect();
        assert_eq!(
            along,
            [
                (75_000_000, 0),
                (75_000_000, 8_000_000),
                (-15_000_000, 8_000_000),
                (-15_000_000, 16_000_000),
                (75_000_000, 16_000_000),
                (75_000_000, 24_000_000),
                (-15_000_000, 24_000_000),
                (-15_000_000, 32_000_000),
                (75_000_000, 32_000_000),
            ]
        );
        assert_eq!(m.last(), Some(&Move::Rapid(P3::new(75_000_000, 32_000_000, 10_000_000))));
        assert_eq!(m.first(), Some(&Move::Rapid(P3::new(-15_000_000, 0, 20_000_000))));
    }

    /// A face narrower than MIDA − FDP1 is one path at MIDA − r.
    #[test]
    fn a_narrow_face_is_one_path() {
        let s = FaceSpec { wid: -5_000_000, levels: Levels::new(2_000_000, -1_000_000, 0), ..spec() };
        let m = moves(s);
        let cuts: Vec<_> = m.iter().filter(|m| matches!(m, Move::Line { .. })).collect();
        assert_eq!(cuts.len(), 1);
        assert_eq!(cuts[0], &Move::Line { to: P3::new(75_000_000, 0, -1_000_000), feed: 4_000 });
    }

    #[test]
    fn two_runs_agree() {
        let s = FaceSpec { zigzag: false, along_wid: true, ..spec() };
        assert_eq!(moves(s), moves(s));
    }
}

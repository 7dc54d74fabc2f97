//! Slots on a circle (SINUMERIK LONGHOLE, SLOT1, SLOT2, seed 001 lines
//! 3774-4419): one generator for the three. NUM slots lie on a circle about
//! `centre` of radius `rad`, slot k at STA1 + k·INDA degrees. A slot is an
//! *axis* — the path of the centres of its two end caps, A to B — widened by
//! WID/2 on either side:
//! - LONGHOLE, SLOT1: a straight axis along the radius, its middle on the circle,
//!   `e` either side of it (LENG − WID over two; LONGHOLE's width is the cutter's);
//! - SLOT2: an arc of the circle itself, AFSL degrees from the slot's angle.
//!
//! The tool centre runs on *rings* about the axis: a ring of offset ρ is the
//! axis widened by ρ (two sides and two half-circle caps, cut as quarter arcs).
//! Per depth level: the infeed at A (vertical, or oscillating along the axis at
//! most `_STA2` steep), the axis A → B, the rings from the inside out (each
//! reached from the last along the axis beyond B), back to B and along the axis
//! to A. A slot whose roughing offset is 0 (the width is the cutter's:
//! LONGHOLE, or a FAL that leaves no room, lines 4107-4113) is cut as LONGHOLE's
//! oscillation: the infeed alternately at either end, the axis traversed between
//! (lines 3815-3817, 4382-4385). Each slot is entered at its end nearer the tool
//! (LONGHOLE's shortest path, lines 3812-3818); moves of zero length are left out.

use crate::infeed::{Levels, parts};
use crate::rot::round;
use crate::{Move, P3};

/// What a slot call cuts (nm, degrees).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlotSpec {
    /// Centre of the circle (CPA, CPO) and its radius (RAD).
    pub centre: (i64, i64),
    /// Radius of the circle.
    pub rad: i64,
    /// Angle of the first slot (STA1) and from slot to slot (INDA, resolved).
    pub sta: f64,
    /// Increment angle.
    pub inda: f64,
    /// Number of slots (≥ 1).
    pub num: u32,
    /// SLOT2: the axis is an arc of the circle over `afsl` degrees; else a
    /// straight radial axis of half length `e`.
    pub arc: bool,
    /// Half length of a straight axis (nm).
    pub e: i64,
    /// Angle of an arc axis (AFSL, degrees).
    pub afsl: f64,
    /// Tool-centre offset of the outermost roughing ring (WID/2 − r − FAL), and
    /// of the finishing ring (WID/2 − r); 0: the LONGHOLE oscillation.
    pub rho: i64,
    /// Finishing ring offset.
    pub rho_f: i64,
    /// Largest step between rings.
    pub step: i64,
    /// Retract plane; RFP + SDIS.
    pub rtp: i64,
    /// RFP + SDIS.
    pub safe: i64,
    /// Tool position at the call (the nearest end of the first slot).
    pub here: P3,
    /// Roughing levels (`to`: the rough floor, also when `count` is 0).
    pub rough: Levels,
    /// Finishing levels (`count` 0: no finishing).
    pub finish: Levels,
    /// FFD, FFP1, FFP2, and `_FFCP` (0: slot to slot with G0 in a straight line).
    pub feeds: [i64; 4],
    /// Finishing speed (0: the speed in force), and the call's (set back).
    pub ssf: u32,
    /// The call's spindle speed.
    pub rpm: u32,
    /// Rings clockwise (G2).
    pub cw: bool,
    /// Insertion (VARI tens): 0 vertical G0 down to the floor already cut, then
    /// G1; 1 vertical G1 from where the tool is; 3 oscillating.
    pub insert: u8,
    /// tan of the largest insertion angle `_STA2` (oscillation).
    pub tan2: f64,
    /// Finishing cuts the whole floor at its last level (a floor allowance
    /// `_FALD` was left); otherwise only the wall ring.
    pub floor: bool,
}

/// A slot's axis in the plane (nm as f64): ends, unit tangents there in the
/// A → B sense, and for an arc axis its direction (G2) from A to B.
#[derive(Clone, Copy)]
struct Geo {
    a: [f64; 2],
    b: [f64; 2],
    ta: [f64; 2],
    tb: [f64; 2],
    cw: Option<bool>,
}

/// A ring's seven moves (counterclockwise; a G2 ring mirrors the normal): the
/// end it is at (A 0, B 1), its point's offset along the tangent and the normal
/// there in ring offsets, and how it gets there: 0 a line, 1 about the end (a
/// quarter cap), 2 a side back along the axis, 3 a side forwards (an arc about
/// the circle's centre on SLOT2, else a line).
const RING: [(u8, i8, i8, u8); 7] =
    [(1, 1, 0, 0), (1, 0, 1, 1), (0, 0, 1, 2), (0, -1, 0, 1), (0, 0, -1, 1), (1, 0, -1, 3), (1, 1, 0, 1)];

/// The slots generator.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Slots {
    s: SlotSpec,
    /// The slot being cut, and whether it is entered at B (nearer the tool).
    slot: u32,
    flip: bool,
    /// Stage within the slot (see [`Slots::step`]), level and element.
    stage: u8,
    level: u32,
    el: u32,
    /// The last point handed out.
    last: P3,
}

fn add(p: [f64; 2], k: f64, v: [f64; 2]) -> [f64; 2] {
    [p[0] + k * v[0], p[1] + k * v[1]]
}

/// `v` turned 90° counterclockwise.
fn left(v: [f64; 2]) -> [f64; 2] {
    [-v[1], v[0]]
}

fn dir(deg: f64) -> [f64; 2] {
    let (s, c) = libm::sincos(deg.to_radians());
    [c, s]
}

impl Slots {
    /// The generator of `s`.
    pub fn new(s: SlotSpec) -> Self {
        Slots { s, slot: 0, flip: false, stage: 0, level: 1, el: 0, last: s.here }
    }

    /// The axis of slot `k` (entered at B when `flip`: the ends swapped).
    fn geo(&self, k: u32, flip: bool) -> Geo {
        let s = &self.s;
        let c = [s.centre.0 as f64, s.centre.1 as f64];
        let rad = s.rad as f64;
        let th = s.sta + f64::from(k) * s.inda;
        let g = if s.arc {
            let (ua, ub) = (dir(th), dir(th + s.afsl));
            Geo { a: add(c, rad, ua), b: add(c, rad, ub), ta: left(ua), tb: left(ub), cw: Some(false) }
        } else {
            let u = dir(th);
            let m = add(c, rad, u);
            let e = s.e as f64;
            Geo { a: add(m, -e, u), b: add(m, e, u), ta: u, tb: u, cw: None }
        };
        if flip {
            let neg = |v: [f64; 2]| [-v[0], -v[1]];
            Geo { a: g.b, b: g.a, ta: neg(g.tb), tb: neg(g.ta), cw: g.cw.map(|w| !w) }
        } else {
            g
        }
    }

    fn pt(p: [f64; 2], d: i64) -> P3 {
        P3::new(round(p[0]), round(p[1]), d)
    }

    /// Along the axis to `to` (B when `fwd`, else A) at depth `d`: a line, or an
    /// arc about the circle's centre.
    fn along(&self, g: &Geo, fwd: bool, d: i64, feed: i64) -> Move {
        let to = Self::pt(if fwd { g.b } else { g.a }, d);
        match g.cw {
            None => Move::Line { to, feed },
            Some(cw) => Move::Arc { to, centre: self.s.centre, cw: cw == fwd, feed },
        }
    }

    #[inline(never)]
    /// Element `el` of level `j` of the roughing (`finish` false) or finishing
    /// pass; `None` past the level's last.
    fn level_move(&self, finish: bool, j: u32, el: u32) -> Option<Move> {
        let s = &self.s;
        let (levels, rho, feed) = if finish { (&s.finish, s.rho_f, s.feeds[2]) } else { (&s.rough, s.rho, s.feeds[1]) };
        // LONGHOLE's path (no room for a ring): the infeed at the end reached,
        // alternately A and B — on even levels the axis runs the other way.
        let alt = rho <= 0;
        let g = self.geo(self.slot, self.flip != (alt && j.is_multiple_of(2)));
        let depth = levels.level(j);
        let cur = if j == 1 { s.safe } else { levels.level(j - 1) };
        let sign = if s.rough.to < s.safe { -1 } else { 1 };
        let deeper = |x: i64, y: i64| if (x - y) * sign > 0 { x } else { y };
        let shallower = |x: i64, y: i64| if (x - y) * sign > 0 { y } else { x };
        // The floor already cut under the plunge point: down to it at G0.
        let floor = match (s.insert, finish) {
            (1, _) => cur,
            (_, true) => s.rough.to,
            _ => levels.level(j - 1),
        };
        let f = deeper(cur, shallower(floor, depth));
        let ffd = s.feeds[0];
        if el == 0 {
            return Some(Move::Rapid(Self::pt(g.a, f)));
        }
        // Oscillating insertion (roughing): 2m strokes along the axis from A,
        // back at A at the level, each at most `_STA2` steep.
        let len = match s.arc {
            true => s.rad as f64 * s.afsl.to_radians(),
            false => 2.0 * s.e as f64,
        };
        let strokes = if s.insert == 3 && !finish && !alt && len > 0.0 && s.tan2 > 0.0 {
            let m = libm::ceil((depth - f).unsigned_abs() as f64 / (2.0 * len * s.tan2));
            2 * (m.clamp(1.0, 1e6) as u32)
        } else {
            1
        };
        let el = el - 1;
        if el < strokes {
            if strokes == 1 {
                return Some(Move::Line { to: Self::pt(g.a, depth), feed: ffd });
            }
            let d = f + round((depth - f) as f64 * f64::from(el + 1) / f64::from(strokes));
            return Some(self.along(&g, el.is_multiple_of(2), d, ffd));
        }
        let el = el - strokes;
        if el == 0 || alt {
            return (el == 0).then(|| self.along(&g, true, depth, feed));
        }
        // Rings lo..=n of offsets rho·i/n, seven moves each.
        let n = parts(rho, s.step).min(1 << 16);
        let all = !finish || (s.floor && j == levels.count);
        let lo = if all { 1 } else { n };
        let rings = n - lo + 1;
        let el = el - 1;
        if el < rings.saturating_mul(7) {
            let i = lo + el / 7;
            let r = (rho as f64) * f64::from(i) / f64::from(n);
            let (end, kt, kn, turn) = RING[(el % 7) as usize];
            let (p, t) = if end == 1 { (g.b, g.tb) } else { (g.a, g.ta) };
            let n = left(t);
            let (kt, kn) = (f64::from(kt) * r, f64::from(kn) * if s.cw { -r } else { r });
            let to = Self::pt([p[0] + kt * t[0] + kn * n[0], p[1] + kt * t[1] + kn * n[1]], depth);
            return Some(match (turn, g.cw) {
                (1, _) => Move::Arc { to, centre: (round(p[0]), round(p[1])), cw: s.cw, feed },
                (2 | 3, Some(w)) => Move::Arc { to, centre: s.centre, cw: w == (turn == 3), feed },
                _ => Move::Line { to, feed },
            });
        }
        match el - rings.saturating_mul(7) {
            0 => Some(Move::Line { to: Self::pt(g.b, depth), feed }),
            1 => Some(self.along(&g, false, depth, feed)),
            _ => None,
        }
    }

    /// The move at the cursor (`Some(None)`: nothing here), and the cursor on.
    /// Stages per slot: 0 up to RTP where the tool is, 1 over to the slot's
    /// nearer end at RTP, 2 down to RFP + SDIS, 3 roughing, 4 up to RFP + SDIS,
    /// 5 the finishing speed, 6 over the slot's entry at RFP + SDIS, 7 finishing,
    /// 8 up to RTP, 9 the call's speed back before the next slot's roughing.
    fn step(&mut self) -> Option<Option<Move>> {
        let s = &self.s;
        if self.slot >= s.num {
            return None;
        }
        let here = self.last;
        let speeds = s.ssf > 0 && s.finish.count > 0;
        let m = match self.stage {
            0 => Some(Move::Rapid(here.at(s.rtp))),
            1 => {
                let h = [here.a as f64, here.o as f64];
                let dist = |p: [f64; 2]| {
                    let (x, y) = (p[0] - h[0], p[1] - h[1]);
                    x * x + y * y
                };
                let g = self.geo(self.slot, false);
                self.flip = dist(g.b) < dist(g.a);
                let a = Self::pt(self.geo(self.slot, self.flip).a, s.rtp);
                Some(if self.slot > 0 && s.feeds[3] > 0 {
                    // SLOT2 VARI 1x: along the circle at _FFCP, the shorter way
                    // (clockwise when the target lies to the right).
                    let v = |p: P3| [(p.a - s.centre.0) as f64, (p.o - s.centre.1) as f64];
                    let (u, w) = (v(here), v(a));
                    Move::Arc { to: a, centre: s.centre, cw: u[0] * w[1] < u[1] * w[0], feed: s.feeds[3] }
                } else {
                    Move::Rapid(a)
                })
            }
            2 | 6 => Some(Move::Rapid(Self::pt(self.geo(self.slot, self.flip).a, s.safe))),
            3 | 7 => {
                let finish = self.stage == 7;
                let count = if finish { s.finish.count } else { s.rough.count };
                if self.level <= count {
                    let m = self.level_move(finish, self.level, self.el);
                    self.el += 1;
                    if m.is_none() {
                        (self.level, self.el) = (self.level + 1, 0);
                    }
                    return Some(m);
                }
                (self.level, self.el) = (1, 0);
                None
            }
            4 => Some(Move::Rapid(here.at(s.safe))),
            5 if speeds => Some(Move::Speed(s.ssf)),
            8 => Some(Move::Rapid(here.at(s.rtp))),
            9 if speeds && s.rough.count > 0 && self.slot + 1 < s.num => Some(Move::Speed(s.rpm)),
            _ => None,
        };
        if self.stage >= 9 {
            (self.slot, self.stage) = (self.slot + 1, 0);
        } else {
            self.stage += 1;
        }
        Some(m)
    }
}

impl Iterator for Slots {
    type Item = Move;

    /// The next move, `None` when the last slot is done.
    #[inline(never)]
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

    fn spec(arc: bool, rho: i64) -> SlotSpec {
        SlotSpec {
            centre: (0, 0),
            rad: 30_000_000,
            sta: 0.0,
            inda: 90.0,
            num: 2,
            arc,
            e: 10_000_000,
            afsl: 60.0,
            rho,
            rho_f: rho + 500_000,
            step: 8_000_000,
            rtp: 5_000_000,
            safe: 1_000_000,
            here: P3::new(0, 0, 20_000_000),
            rough: Levels::new(1_000_000, -9_000_000, 4_000_000),
            finish: Levels::new(1_000_000, -10_000_000, 0),
            feeds: [100, 200, 300, 0],
            ssf: 900,
            rpm: 600,
            cw: false,
            insert: 1,
            tan2: 0.1,
            floor: false,
        }
    }

    fn moves(s: SlotSpec) -> Vec<Move> {
        let mut g = Slots::new(s);
        core::iter::from_fn(|| g.next()).collect()
    }

    /// The generator is pure, and every arc's end lies at its start's distance
    /// from its centre (caps about the ends, sides about the circle's centre).
    #[test]
    fn arcs_are_round_and_runs_agree() {
        for (arc, rho) in [(false, 2_000_000), (true, 2_000_000), (true, 0), (false, 0)] {
            let s = spec(arc, rho);
            let m = moves(s);
            assert_eq!(m, moves(s));
            let mut at = s.here;
            for mv in &m {
                match *mv {
                    Move::Arc { to, centre, .. } => {
                        let r = |p: P3| libm::hypot((p.a - centre.0) as f64, (p.o - centre.1) as f64);
                        assert!((r(at) - r(to)).abs() < 2.0, "{at:?} {mv:?}");
                        at = to;
                    }
                    Move::Rapid(p) | Move::Line { to: p, .. } => at = p,
                    _ => {}
                }
            }
            assert_eq!(at.d, s.rtp, "ends at RTP");
            // The finishing speed and the call's back before the second slot.
            assert_eq!(m.iter().filter(|x| matches!(x, Move::Speed(_))).count(), 3);
        }
    }
}

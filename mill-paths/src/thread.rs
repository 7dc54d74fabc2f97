//! Thread milling (SINUMERIK CYCLE90, seed 001 lines 3538-3772): the tool centre
//! runs a helix about the thread's centre at the pitch per turn, from the start
//! level to the end level, entered and left on tangent arcs that ramp the depth
//! on at the same rate.
//!
//! Geometry, in a frame where the helix runs counterclockwise (a G2 thread is
//! this mirrored in the ordinate) and starts on the positive abscissa:
//! - the helix radius is DIATH/2 − r (internal) or DIATH/2 + r (external);
//! - internal (SW 6.3, lines 3672-3692): a G1 from the thread's centre to `S`,
//!   then a semicircle of radius ρ in the helix's direction to the helix's
//!   start `E` = (R, 0). ρ = R/2 (`S` is the centre) for a cutter diameter below
//!   2/3 DIATH, else ρ = KDIAM/2 − r (the cutting edge on the core diameter);
//!   the same semicircle turned to the end angle leaves the thread;
//! - external (lines 3605-3625): a quarter circle of radius ρ = R/2 against the
//!   helix's direction from `S` = (R + ρ, −ρ) (the 4th quadrant for G3, the 1st
//!   for G2, line 3609) to `E`, and the same quarter turned to the end angle out;
//! - the arcs in and out change the depth by Δz, the pitch times the cutting
//!   edge's path on the arc over the thread's circumference π·DIATH: p·(ρ + r)/DIATH
//!   for the semicircle, half that for the quarter — the document's overrun
//!   formulas (lines 3660-3692): the helix itself starts and ends exactly on the
//!   programmed levels;
//! - the helix is cut in half turns (each a 180° arc, depth PIT/2), the last arc
//!   up to the end angle.
//!
//! Feeds (line 3672, "the feed converted to the tool radius"): FFR is the feed
//! at the cutting edge, on the thread's diameter; the centre runs at
//! FFR·R/(DIATH/2) on the helix and at FFR·ρ/(ρ + r) on the arcs in and out (the
//! document's reduced feed) and on the G1 to `S`.

use crate::rot::{Rot, round};
use crate::{Move, P3};
use core::f64::consts::PI;

/// What a thread milling call cuts (nm, feeds in the feed unit in force).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThreadSpec {
    /// Centre of the thread in the plane (CPA, CPO).
    pub centre: (i64, i64),
    /// Nominal (outer) diameter DIATH and core diameter KDIAM.
    pub diath: i64,
    /// Core diameter.
    pub kdiam: i64,
    /// Cutter radius.
    pub r: i64,
    /// Pitch (> 0).
    pub pit: i64,
    /// Internal thread (TYPTH 0).
    pub internal: bool,
    /// The helix runs clockwise (G2).
    pub cw: bool,
    /// Retract plane, safety level (RFP advanced by SDIS against the travel).
    pub rtp: i64,
    /// Safety level.
    pub safe: i64,
    /// Where the helix starts (RFP) and ends (DP).
    pub from: i64,
    /// End level.
    pub to: i64,
    /// FFR, the feed at the cutting edge.
    pub feed: i64,
}

/// The helix and its arcs in and out, computed once from a [`ThreadSpec`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Helix {
    /// Radius of the helix (tool centre).
    pub radius: f64,
    /// Radius of the arcs in and out (tool centre).
    pub rho: f64,
    /// Depth change on each arc in and out (≥ 0).
    pub dz: i64,
    /// Angle the helix turns, radians.
    pub angle: f64,
    /// Feeds of the tool centre: on the helix, on the arcs and the G1 in.
    pub feeds: [i64; 2],
}

impl ThreadSpec {
    /// The helix of this thread.
    pub fn helix(&self) -> Helix {
        let (d, r) = (self.diath as f64, self.r as f64);
        let (radius, rho, k) = if !self.internal {
            let rc = d / 2.0 + r;
            (rc, rc / 2.0, 0.5)
        } else {
            let rc = d / 2.0 - r;
            (rc, if 3.0 * r < d { rc / 2.0 } else { self.kdiam as f64 / 2.0 - r }, 1.0)
        };
        // (The front end has checked DIATH, PIT > 0 and r > 0; a division by 0
        // would be a NaN that rounds to 0, never a panic.)
        let p = self.pit as f64;
        let f = self.feed as f64 / d;
        let feed = |v: f64| round(v).max(1);
        Helix {
            radius,
            rho,
            dz: round(k * p * (rho + r) / d),
            angle: 2.0 * PI * (self.to - self.from).unsigned_abs() as f64 / p,
            feeds: [feed(2.0 * f * radius), feed(f * d * rho / (rho + r))],
        }
    }
}

/// The thread milling generator: the moves before and after the helix laid out
/// once, the helix's half turns counted out between them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Thread {
    /// G1 to `S`, arc in, last helix arc, arc out.
    moves: [Move; 4],
    /// The rapids' ends: two in (RTP, safety level), two out.
    rapids: [P3; 4],
    /// The helix's points on the start ray and opposite it.
    ends: [(i64, i64); 2],
    /// Centre, start level, travel (±1), pitch, helix feed, G2.
    centre: (i64, i64),
    from: i64,
    dir: i64,
    pit: i64,
    feed: i64,
    cw: bool,
    /// Half turns of the helix before its last arc, and the next move.
    halves: u64,
    k: u64,
    at: u8,
}

impl Thread {
    /// The generator of `s`.
    #[inline(never)]
    pub fn new(s: ThreadSpec) -> Self {
        let h = s.helix();
        let dir = if s.to >= s.from { 1 } else { -1 };
        let (before, after) = (s.from - dir * h.dz, s.to + dir * h.dz);
        // A point `along` the ray `u` (the thread's centre turned to the ray's
        // angle, mirrored for G2) and `across` it in the helix's direction.
        let m = if s.cw { -1.0 } else { 1.0 };
        let at = |u: &Rot, along: f64, across: f64, d: i64| {
            let (a, o) = u.point(along, m * across);
            P3::new(a, o, d)
        };
        // `S` or the end of the arc out, and the arc's centre, on the ray `u`:
        // internal on the ray, external across it.
        let ends = |u: &Rot, d: i64, k: f64| {
            let (along, c, across) = if s.internal {
                (h.radius - 2.0 * h.rho, h.radius - h.rho, 0.0)
            } else {
                (h.radius + h.rho, h.radius + h.rho, k * h.rho)
            };
            (at(u, along, across, d), at(u, c, 0.0, d))
        };
        let centre = |d| P3::new(s.centre.0, s.centre.1, d);
        let arc_cw = s.cw == s.internal;
        let arc = |to: P3, c: P3, cw: bool, feed: i64| Move::Arc { to, centre: (c.a, c.o), cw, feed };
        let u0 = Rot { at: s.centre, cs: (1.0, 0.0) };
        let (sn, cs) = libm::sincos(h.angle);
        let uf = Rot { at: s.centre, cs: (cs, m * sn) };
        let (sp, sc) = ends(&u0, before, -1.0);
        let first = if s.internal { centre(0) } else { sp };
        let rn = round(h.radius);
        let e = [P3::new(s.centre.0 + rn, s.centre.1, s.from), P3::new(s.centre.0 - rn, s.centre.1, s.from)];
        // Whole half turns before the last arc; a last arc that would end where
        // its half turn ends (a remainder below a nm) is folded into it.
        let f = at(&uf, h.radius, 0.0, s.to);
        let mut halves = (h.angle / PI) as u64;
        let on = |n: u64| (e[(n % 2) as usize].a, e[(n % 2) as usize].o) == (f.a, f.o);
        if halves > 0 && on(halves) {
            halves -= 1;
        }
        // A last arc shorter than a nm in the plane is a straight feed.
        let last =
            if on(halves) { Move::Line { to: f, feed: h.feeds[0] } } else { arc(f, centre(0), s.cw, h.feeds[0]) };
        let (x, xc) = ends(&uf, after, 1.0);
        let out = if s.internal { centre(after) } else { x };
        Thread {
            moves: [
                Move::Line { to: sp, feed: h.feeds[1] },
                arc(e[0], sc, arc_cw, h.feeds[1]),
                last,
                arc(x, xc, arc_cw, h.feeds[1]),
            ],
            rapids: [first.at(s.rtp), first.at(s.safe), out, out.at(s.rtp)],
            ends: [(e[0].a, e[0].o), (e[1].a, e[1].o)],
            centre: s.centre,
            from: s.from,
            dir,
            pit: s.pit,
            feed: h.feeds[0],
            cw: s.cw,
            halves,
            k: 0,
            at: 0,
        }
    }
}

impl Iterator for Thread {
    type Item = Move;

    /// The next move, `None` when the thread is done. A move that goes nowhere
    /// (the rapid back to the centre where the semicircle out ends there) is
    /// left to the emitter, which emits nothing for it.
    fn next(&mut self) -> Option<Move> {
        if self.at == 4 && self.k < self.halves {
            // Half turn k + 1: to the other end of the diameter, PIT/2 on.
            self.k += 1;
            let (a, o) = self.ends[(self.k % 2) as usize];
            let d = self.from + self.dir * (self.k as i64).saturating_mul(self.pit) / 2;
            return Some(Move::Arc { to: P3::new(a, o, d), centre: self.centre, cw: self.cw, feed: self.feed });
        }
        let i = usize::from(self.at);
        self.at += 1;
        match i {
            2..=5 => self.moves.get(i - 2).copied(),
            _ => self.rapids.get(if i < 2 { i } else { i - 4 }).map(|&p| Move::Rapid(p)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec::Vec;

    const MM: i64 = 1_000_000;

    /// The document's internal example (lines 3749-3772): M60 × 2 at X60 Y50,
    /// 40 mm deep from RFP 40, G2; a 5 mm cutter.
    fn internal() -> ThreadSpec {
        ThreadSpec {
            centre: (60 * MM, 50 * MM),
            diath: 60 * MM,
            kdiam: 50 * MM,
            r: 5 * MM,
            pit: 2 * MM,
            internal: true,
            cw: true,
            rtp: 48 * MM,
            safe: 45 * MM,
            from: 40 * MM,
            to: 0,
            feed: 500 * MM,
        }
    }

    /// The moves, less those that go nowhere (the emitter leaves them out).
    fn moves(s: ThreadSpec) -> Vec<Move> {
        let mut at = P3::new(i64::MIN, 0, 0);
        Thread::new(s)
            .filter(|m| {
                let (Move::Rapid(p) | Move::Line { to: p, .. } | Move::Arc { to: p, .. }) = *m else { return true };
                core::mem::replace(&mut at, p) != p
            })
            .collect()
    }

    fn dist(p: P3, c: (i64, i64)) -> f64 {
        libm::hypot((p.a - c.0) as f64, (p.o - c.1) as f64)
    }

    /// The helix arcs: (start, end, cw) of every arc about the thread's centre.
    fn helix(s: ThreadSpec) -> Vec<(P3, P3, bool)> {
        let m = moves(s);
        let mut out = Vec::new();
        let mut at = P3::default();
        for m in m {
            match m {
                Move::Arc { to, centre, cw, .. } if centre == s.centre => out.push((at, to, cw)),
                _ => {}
            }
            if let Move::Rapid(p) | Move::Line { to: p, .. } | Move::Arc { to: p, .. } = m {
                at = p;
            }
        }
        out
    }

    /// Angle swept from `a` to `b` about `c` in the direction `cw`, radians (0..2π].
    fn sweep(a: P3, b: P3, c: (i64, i64), cw: bool) -> f64 {
        let t = |p: P3| libm::atan2((p.o - c.1) as f64, (p.a - c.0) as f64);
        let mut d = t(b) - t(a);
        if cw {
            d = -d;
        }
        while d <= 1e-9 {
            d += 2.0 * PI;
        }
        d
    }

    /// Internal: every helix point at DIATH/2 − r from the centre, the depth
    /// changing by PIT per 360°, from RFP to DP exactly, all G2 (CDIR 2).
    #[test]
    fn internal_helix_radius_and_pitch() {
        let s = internal();
        let arcs = helix(s);
        assert_eq!(arcs.len(), 40, "20 turns in half turns");
        let want = (s.diath / 2 - s.r) as f64;
        let mut turned = 0.0;
        for &(a, b, cw) in &arcs {
            assert!(cw);
            assert!((dist(a, s.centre) - want).abs() < 1.0 && (dist(b, s.centre) - want).abs() < 1.0);
            let sw = sweep(a, b, s.centre, cw);
            turned += sw;
            // Depth per radian × 2π = the pitch (down: the depth falls).
            let per_turn = (a.d - b.d) as f64 / sw * 2.0 * PI;
            assert!((per_turn - s.pit as f64).abs() < 2.0, "{per_turn}");
        }
        assert!((turned - 40.0 * PI).abs() < 1e-6);
        assert_eq!((arcs[0].0.d, arcs[39].1.d), (s.from, s.to));
        // The helix starts on the positive abscissa.
        assert_eq!(arcs[0].0, P3::new(s.centre.0 + 25 * MM, s.centre.1, s.from));
    }

    /// Internal: in at the centre, a semicircle of radius (DIATH/2 − r)/2 in and
    /// out, the document's overrun Δz = p/2·(r + DIATH/2)/DIATH on each, back to
    /// the centre and up to RTP.
    #[test]
    fn internal_semicircles_and_overrun() {
        let s = internal();
        let m = moves(s);
        let dz = 2.0 / 2.0 * (5.0 + 30.0) / 60.0;
        let dz = (dz * 1e6) as i64;
        let c = |d| P3::new(s.centre.0, s.centre.1, d);
        assert_eq!(&m[..2], &[Move::Rapid(c(s.rtp)), Move::Rapid(c(s.safe))]);
        let h = s.helix();
        let Move::Line { to, feed } = m[2] else { panic!("{:?}", m[2]) };
        assert_eq!((to, feed), (c(s.from + dz), h.feeds[1]));
        let Move::Arc { to, centre, cw, .. } = m[3] else { panic!() };
        assert_eq!(
            (to, centre, cw),
            (P3::new(s.centre.0 + 25 * MM, s.centre.1, s.from), (s.centre.0 + 12_500_000, s.centre.1), true)
        );
        let n = m.len();
        let Move::Arc { to, cw, .. } = m[n - 2] else { panic!("{:?}", m[n - 2]) };
        // 20 whole turns: the helix ends where it began; out on the same ray.
        assert_eq!((to, cw), (c(s.to - dz), true));
        assert_eq!(&m[n - 1..], &[Move::Rapid(c(s.rtp))]);
        // Feeds: FFR at the cutting edge — the centre runs at FFR·25/30 on the
        // helix, FFR·12.5/17.5 on the semicircles.
        assert_eq!(h.feeds, [round(500e6 * 25.0 / 30.0), round(500e6 * 12.5 / 17.5)]);
    }

    /// A cutter of at least 2/3 DIATH: the semicircle's edge on the core
    /// diameter, Δz = p/2·KDIAM/DIATH (line 3690).
    #[test]
    fn a_large_cutter_enters_on_the_core_diameter() {
        let s = ThreadSpec { r: 10 * MM, diath: 30 * MM, kdiam: 26 * MM, pit: 3 * MM, ..internal() };
        let h = s.helix();
        assert_eq!(h.rho, 3e6);
        assert_eq!(h.dz, 1_300_000);
        // S lies beyond the centre (R − 2ρ = −1 mm), the cutter inside the core.
        let Move::Line { to, .. } = moves(s)[2] else { panic!() };
        assert_eq!((to.a, to.o), (s.centre.0 - MM, s.centre.1));
    }

    /// External, G3 (CDIR 3): the start in the 4th quadrant, quarter circles
    /// in and out against the helix's direction, radius DIATH/2 + r, Δz =
    /// p/4·(2r + RDIFF)/DIATH with RDIFF = DIATH/2 + r (line 3664); a thread of
    /// 2.5 turns ends half a turn round.
    #[test]
    fn external_quarter_circles() {
        let s = ThreadSpec {
            internal: false,
            cw: false,
            kdiam: 0,
            from: 0,
            to: -5 * MM,
            safe: 2 * MM,
            rtp: 10 * MM,
            ..internal()
        };
        let m = moves(s);
        let rc = 35.0e6;
        let Move::Rapid(p) = m[0] else { panic!() };
        assert!(p.a > s.centre.0 && p.o < s.centre.1, "4th quadrant: {p:?}");
        assert_eq!(p, P3::new(s.centre.0 + 52_500_000, s.centre.1 - 17_500_000, s.rtp));
        let dz = round(2e6 / 4.0 * (10e6 + 35e6) / 60e6);
        assert_eq!(s.helix().dz, dz);
        let arcs = helix(s);
        let mut turned = 0.0;
        for &(a, b, cw) in &arcs {
            assert!(!cw);
            assert!((dist(b, s.centre) - rc).abs() < 1.0);
            turned += sweep(a, b, s.centre, cw);
        }
        assert!((turned - 5.0 * PI).abs() < 1e-6, "{turned}");
        let n = m.len();
        let Move::Arc { to, centre, cw, .. } = m[n - 2] else { panic!() };
        // Half a turn round: the exit's quarter about (−52.5, 0), G2, ends at
        // (−52.5, −17.5) relative to the centre (across = the helix's direction).
        assert!(cw);
        assert_eq!(centre, (s.centre.0 - 52_500_000, s.centre.1));
        assert_eq!(to, P3::new(s.centre.0 - 52_500_000, s.centre.1 - 17_500_000, s.to - dz));
        assert_eq!(m[n - 1], Move::Rapid(to.at(s.rtp)));
        // G2: the mirror image, the start in the 1st quadrant.
        let Move::Rapid(p) = moves(ThreadSpec { cw: true, ..s })[0] else { panic!() };
        assert_eq!((p.a - s.centre.0, p.o - s.centre.1), (52_500_000, 17_500_000));
    }

    /// Upwards (the document's bottom-up example): the depth rises by the pitch
    /// per turn; a thread shorter than a nm of arc is a straight feed; two runs agree.
    #[test]
    fn upwards_tiny_and_pure() {
        let s = ThreadSpec { from: -20 * MM, to: 0, safe: -20 * MM, rtp: 8 * MM, pit: 3 * MM, ..internal() };
        let arcs = helix(s);
        assert!(arcs.iter().all(|(a, b, _)| b.d > a.d));
        assert_eq!(arcs.last().map(|a| a.1.d), Some(0));
        assert_eq!(moves(s), moves(s));
        let tiny = ThreadSpec { to: s.from + 1, pit: 2000 * MM, ..s };
        let mt = moves(tiny);
        assert!(mt.iter().any(|m| matches!(m, Move::Line { to, .. } if to.d == s.from + 1)), "{mt:?}");
    }
}

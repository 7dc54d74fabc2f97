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

use crate::rot::round;
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
        let p = self.pit as f64;
        let f = self.feed as f64;
        let feed = |v: f64| round(v).max(1);
        Helix {
            radius,
            rho,
            dz: round(k * p * (rho + r) / d.max(1.0)),
            angle: 2.0 * PI * (self.to - self.from).unsigned_abs() as f64 / p.max(1.0),
            feeds: [feed(f * radius / (d / 2.0).max(1.0)), feed(f * rho / (rho + r).max(1.0))],
        }
    }
}

/// The thread milling generator.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Thread {
    s: ThreadSpec,
    h: Helix,
    /// Half turns of the helix before its last arc.
    halves: u64,
    /// Stage: 0, 1 rapids in, 2 G1 to S, 3 arc in, 4 helix, 5 arc out, 6, 7
    /// rapids out, 8 done.
    stage: u8,
    /// Half turn being cut (stage 4).
    k: u64,
    /// The last point handed out (zero-length moves are left out).
    last: P3,
}

impl Thread {
    /// The generator of `s`.
    pub fn new(s: ThreadSpec) -> Self {
        let h = s.helix();
        let mut t = Thread { s, h, halves: 0, stage: 0, k: 0, last: P3::new(i64::MIN, i64::MIN, i64::MIN) };
        // Whole half turns before the last arc; a last arc that would end where
        // its half turn ends (a remainder below a nm) is folded into it.
        let mut n = libm::floor(h.angle / PI) as u64;
        if n > 0 && t.at(h.radius, h.angle) == t.at(h.radius, n as f64 * PI) {
            n -= 1;
        }
        t.halves = n;
        t
    }

    /// The point at `radius` and `angle` (radians, the helix's direction) about
    /// the thread's centre, in the plane.
    fn at(&self, radius: f64, angle: f64) -> (i64, i64) {
        let (s, c) = libm::sincos(angle);
        let o = if self.s.cw { -radius * s } else { radius * s };
        (self.s.centre.0 + round(radius * c), self.s.centre.1 + round(o))
    }

    /// A point of the helix's frame: `along` the ray at `angle`, `across` it
    /// (the helix's direction), at applicate `d`.
    fn frame(&self, angle: f64, along: f64, across: f64, d: i64) -> P3 {
        let r = libm::hypot(along, across);
        let (a, o) = self.at(r, angle + libm::atan2(across, along));
        P3::new(a, o, d)
    }

    /// Travel along the applicate: +1 or −1.
    fn dir(&self) -> i64 {
        if self.s.to >= self.s.from { 1 } else { -1 }
    }

    /// The move at the cursor (`Some(None)`: nothing here), and the cursor on.
    fn step(&mut self) -> Option<Option<Move>> {
        let (s, h) = (self.s, self.h);
        let dir = self.dir();
        let (before, after) = (s.from - dir * h.dz, s.to.saturating_add(dir * h.dz));
        let end = h.angle;
        // S (the start of the arc in) and the arc's centre at angle `a`, in the
        // helix's frame: internal on the ray, external across it.
        let ends = |a: f64, d: i64, leaving: bool| {
            let k = if leaving { 1.0 } else { -1.0 };
            if s.internal {
                (self.frame(a, h.radius - 2.0 * h.rho, 0.0, d), self.frame(a, h.radius - h.rho, 0.0, d))
            } else {
                let c = h.radius + h.rho;
                (self.frame(a, c, k * h.rho, d), self.frame(a, c, 0.0, d))
            }
        };
        let centre = |d| P3::new(s.centre.0, s.centre.1, d);
        let arc_cw = s.cw == s.internal;
        let arc = |to: P3, c: P3, cw: bool, feed: i64| Move::Arc { to, centre: (c.a, c.o), cw, feed };
        let m = match self.stage {
            0 | 1 => {
                let d = if self.stage == 0 { s.rtp } else { s.safe };
                Move::Rapid(if s.internal { centre(d) } else { ends(0.0, d, false).0 })
            }
            2 => Move::Line { to: ends(0.0, before, false).0, feed: h.feeds[1] },
            3 => {
                let (e, _) = self.helix_point(0);
                arc(e, ends(0.0, before, false).1, arc_cw, h.feeds[1])
            }
            4 => {
                self.k += 1;
                if self.k <= self.halves {
                    let (p, _) = self.helix_point(self.k);
                    return Some(Some(arc(p, centre(0), s.cw, h.feeds[0])));
                }
                let (a, o) = self.at(h.radius, end);
                let to = P3::new(a, o, s.to);
                self.stage += 1;
                // A last arc shorter than a nm in the plane is a straight feed.
                if (a, o) == (self.last.a, self.last.o) {
                    return Some(Some(Move::Line { to, feed: h.feeds[0] }));
                }
                return Some(Some(arc(to, centre(0), s.cw, h.feeds[0])));
            }
            5 => {
                let (x, c) = ends(end, after, true);
                arc(x, c, arc_cw, h.feeds[1])
            }
            6 if s.internal => Move::Rapid(centre(after)),
            6 => {
                self.stage += 1;
                return Some(None);
            }
            7 => {
                let p = self.last;
                Move::Rapid(P3::new(p.a, p.o, s.rtp))
            }
            _ => return None,
        };
        self.stage += 1;
        Some(Some(m))
    }

    /// The helix's point after `k` half turns, and its angle.
    fn helix_point(&self, k: u64) -> (P3, f64) {
        let (s, h) = (self.s, self.h);
        let a = k as f64 * PI;
        let span = (s.to - s.from) as f64 * a / h.angle.max(f64::MIN_POSITIVE);
        let (x, y) = self.at(h.radius, a);
        (P3::new(x, y, s.from + round(span)), a)
    }
}

impl Iterator for Thread {
    type Item = Move;

    /// The next move, `None` when the thread is done.
    fn next(&mut self) -> Option<Move> {
        loop {
            let Some(m) = self.step()? else { continue };
            let to = match m {
                Move::Rapid(p) | Move::Line { to: p, .. } | Move::Arc { to: p, .. } => p,
                _ => return Some(m),
            };
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

    fn moves(s: ThreadSpec) -> Vec<Move> {
        let mut g = Thread::new(s);
        core::iter::from_fn(|| g.next()).collect()
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
        let h = Thread::new(s).h;
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
        assert_eq!(Thread::new(s).h.dz, dz);
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

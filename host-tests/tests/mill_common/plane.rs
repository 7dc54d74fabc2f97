//! The moves of a milling cycle's run as the tests measure them: segments in work
//! mm in the G17 plane (X, Y) with the applicate Z, sampled along lines and arcs,
//! and the document's division of a depth into infeeds (seed 001 lines 3864-3876).

use host_tests::{Run, run_with};
use interp_core::canon::{Action, Canon};
use interp_core::config::Language;
use interp_core::{MachineConfig, Panel};

/// The mill (`examples/machines/mill.toml`) in SINUMERIK mode.
pub fn cfg() -> MachineConfig {
    MachineConfig { language: Language::Siemens, ..super::mill() }
}

/// Runs a SINUMERIK program on the mill.
pub fn siemens(text: &str) -> Run {
    run_with(text, cfg(), Panel::default())
}

/// Runs a SINUMERIK program on the mill and asserts it raised no alarm.
pub fn go(text: &str) -> Run {
    let r = siemens(text);
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    r
}

/// A move in work mm: start, end, arc centre and direction, feed mm/min (0: G0),
/// spindle rev/min (0: G0).
#[derive(Clone, Copy, Debug)]
pub struct Seg {
    pub from: [f64; 3],
    pub to: [f64; 3],
    pub arc: Option<([f64; 2], bool)>,
    pub feed: f64,
    pub rpm: u32,
}

/// A work position in mm.
pub fn mm3(p: &interp_core::axis::Pos) -> [f64; 3] {
    [p.0[0] as f64 / 1e6, p.0[1] as f64 / 1e6, p.0[2] as f64 / 1e6]
}

/// Every move of the run, rapids with feed 0, in order.
pub fn moves(actions: &[Canon]) -> Vec<Seg> {
    let mut out = Vec::new();
    let mut at: Option<[f64; 3]> = None;
    for c in actions {
        let Some(e) = c.action.endpoint() else { continue };
        let to = mm3(&e.work);
        if let Some(from) = at {
            match c.action {
                Action::Rapid(_) => out.push(Seg { from, to, arc: None, feed: 0.0, rpm: 0 }),
                Action::Linear(m) => out.push(Seg {
                    from,
                    to,
                    arc: None,
                    feed: m.feed.value as f64 / 1e6,
                    rpm: m.spindle.rpm.unwrap_or(0),
                }),
                Action::Arc(a) => {
                    let cc = mm3(&a.center.work);
                    out.push(Seg {
                        from,
                        to,
                        arc: Some(([cc[0], cc[1]], a.cw)),
                        feed: a.feed.value as f64 / 1e6,
                        rpm: a.spindle.rpm.unwrap_or(0),
                    })
                }
                _ => {}
            }
        }
        at = Some(to);
    }
    out
}

/// The cutting moves of the run (no rapids), in order.
pub fn cuts(actions: &[Canon]) -> Vec<Seg> {
    moves(actions).into_iter().filter(|s| s.feed > 0.0).collect()
}

/// Points along a move in the plane (X, Y), 65 of them.
pub fn samples(s: &Seg) -> Vec<[f64; 2]> {
    let n = 64;
    match s.arc {
        None => (0..=n)
            .map(|k| {
                let t = k as f64 / n as f64;
                [s.from[0] + t * (s.to[0] - s.from[0]), s.from[1] + t * (s.to[1] - s.from[1])]
            })
            .collect(),
        Some((c, cw)) => {
            let a0 = (s.from[1] - c[1]).atan2(s.from[0] - c[0]);
            let a1 = (s.to[1] - c[1]).atan2(s.to[0] - c[0]);
            let mut sweep = a1 - a0;
            if cw && sweep > 0.0 {
                sweep -= std::f64::consts::TAU;
            }
            if !cw && sweep < 0.0 {
                sweep += std::f64::consts::TAU;
            }
            let r = (s.from[0] - c[0]).hypot(s.from[1] - c[1]);
            (0..=n)
                .map(|k| {
                    let a = a0 + sweep * k as f64 / n as f64;
                    [c[0] + r * a.cos(), c[1] + r * a.sin()]
                })
                .collect()
        }
    }
}

/// Distance from `p` to the segment `a`–`b` in the plane (a point if `a` = `b`).
pub fn seg_dist(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let l2 = dx * dx + dy * dy;
    let t = if l2 == 0.0 { 0.0 } else { ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2 };
    let t = t.clamp(0.0, 1.0);
    (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
}

/// Equal within 1.5 µm.
pub fn near(a: f64, b: f64) -> bool {
    (a - b).abs() < 0.0015
}

/// `v` mm rounded to the µm.
pub fn um(v: f64) -> f64 {
    (v * 1000.0).round() / 1000.0
}

/// The depths the document divides a depth into: the fewest equal infeeds of at
/// most `mid` from `from` to `to` (lines 3864-3876).
pub fn levels(from: f64, to: f64, mid: f64) -> Vec<f64> {
    let n = if mid == 0.0 { 1.0 } else { ((from - to) / mid - 1e-9).ceil() };
    (1..=n as u32).map(|k| um(from + (to - from) * f64::from(k) / n)).collect()
}

/// A pocket's or spigot's wall: a rectangle of half sides `hl` × `hw` with corner
/// radius `cr` about `c`, its length at `sta` degrees (a circle: hl = hw = cr).
pub struct Wall {
    pub c: [f64; 2],
    pub sta: f64,
    pub hl: f64,
    pub hw: f64,
    pub cr: f64,
}

impl Wall {
    /// Signed distance of a point from the wall, positive outside.
    pub fn outside(&self, p: [f64; 2]) -> f64 {
        let (s, c) = self.sta.to_radians().sin_cos();
        let (x, y) = (p[0] - self.c[0], p[1] - self.c[1]);
        let (u, v) = ((x * c + y * s).abs(), (-x * s + y * c).abs());
        let (qx, qy) = (u - (self.hl - self.cr), v - (self.hw - self.cr));
        qx.max(0.0).hypot(qy.max(0.0)) + qx.max(qy).min(0.0) - self.cr
    }
}

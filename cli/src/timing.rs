//! Cycle time without acceleration: rapids at the axes' rapid rates, cutting moves
//! at their feed (per revolution: times the spindle speed, which under G96 follows
//! |X| along the move), capped by the maximum cutting feed (parameter 6023).

use interp_core::canon::{FeedMode, SpindleSpeed};
use interp_core::config::Param;
use interp_core::{Axis, MachineConfig};

use crate::path::{Motion, Segment};

/// Sub-steps over which the spindle speed of a G96 move is averaged.
const CSS_STEPS: u32 = 16;

/// Seconds the move of `seg` takes.
pub fn seconds(seg: &Segment, cfg: &MachineConfig) -> f64 {
    match &seg.motion {
        Motion::Rapid(_) => rapid_seconds(seg, cfg),
        Motion::Linear(m) => feed_seconds(seg, m.feed.mode, m.feed.value, &m.spindle, cfg),
        Motion::Arc(a) => feed_seconds(seg, a.feed.mode, a.feed.value, &a.spindle, cfg),
        Motion::Thread(t) => thread_seconds(seg, t.lead, t.lead_delta, &t.spindle),
        Motion::Tap(t) => per_rev_seconds(seg.length(cfg), t.lead as f64, t.spindle.rpm),
    }
}

/// A rapid: each axis at its own rate, the slowest decides (with interpolation the
/// others are slowed to arrive together, which takes as long).
fn rapid_seconds(seg: &Segment, cfg: &MachineConfig) -> f64 {
    let d = seg.to() - seg.from;
    let minutes = Axis::ALL
        .iter()
        .map(|&a| (d[a].unsigned_abs() as f64, cfg.axis(a).rapid_per_min as f64))
        .filter(|&(dist, rate)| dist > 0.0 && rate > 0.0)
        .map(|(dist, rate)| dist / rate)
        .fold(0.0, f64::max);
    minutes * 60.0
}

/// A cutting move at feed `value` (nm/min or nm/rev).
fn feed_seconds(seg: &Segment, mode: FeedMode, value: i64, sp: &SpindleSpeed, cfg: &MachineConfig) -> f64 {
    let cap = cfg.params.get(Param::MaxCuttingFeed) as f64;
    let speed = |rpm: f64| {
        let per_min = match mode {
            FeedMode::PerMin => value as f64,
            FeedMode::PerRev => value as f64 * rpm,
        };
        if cap > 0.0 { per_min.min(cap) } else { per_min }
    };
    let len = seg.length(cfg);
    match (mode, sp.css) {
        (FeedMode::PerRev, Some(css)) => {
            // G96: average the time over sub-steps at their mid-point radius.
            let step = len / f64::from(CSS_STEPS);
            (0..CSS_STEPS)
                .map(|i| seg.point((f64::from(i) + 0.5) / f64::from(CSS_STEPS))[Axis::X])
                .map(|x| minutes(step, speed(css_rpm(css, x, sp.max_rpm))))
                .sum::<f64>()
                * 60.0
        }
        _ => minutes(len, speed(sp.rpm.map_or(0.0, f64::from))) * 60.0,
    }
}

/// Minutes to cover `len` at `speed` per minute; 0 when there is no speed (a
/// per-revolution move with the spindle stopped, which the interpreter rejects).
fn minutes(len: f64, speed: f64) -> f64 {
    if speed > 0.0 { len / speed } else { 0.0 }
}

/// Spindle speed under G96 for surface speed `css` (mm/min) at radius `x` (nm),
/// capped at `max_rpm`: the interpreter's own formula.
fn css_rpm(css: u32, x: i64, max_rpm: u32) -> f64 {
    f64::from(interp_core::canon::css_rpm(css, x).min(max_rpm))
}

/// A thread move: revolutions needed along the long axis at `lead` (growing by
/// `delta` per revolution for G34), over the spindle speed.
fn thread_seconds(seg: &Segment, lead: i64, delta: i64, sp: &SpindleSpeed) -> f64 {
    let d = seg.to() - seg.from;
    let long = d[Axis::X].unsigned_abs().max(d[Axis::Z].unsigned_abs()) as f64;
    let (lead, delta) = (lead as f64, delta as f64);
    // Distance after n revolutions: lead·n + delta·n²/2.
    let disc = lead * lead + 2.0 * delta * long;
    let revs = if delta != 0.0 && disc >= 0.0 { (disc.sqrt() - lead) / delta } else { long / lead };
    revolutions_seconds(revs, sp.rpm)
}

/// A move locked to the spindle at `lead` nm per revolution.
fn per_rev_seconds(len: f64, lead: f64, rpm: Option<u32>) -> f64 {
    revolutions_seconds(if lead > 0.0 { len / lead } else { 0.0 }, rpm)
}

/// Seconds for `revs` spindle revolutions at `rpm`.
fn revolutions_seconds(revs: f64, rpm: Option<u32>) -> f64 {
    match rpm {
        Some(r) if r > 0 && revs.is_finite() => revs / f64::from(r) * 60.0,
        _ => 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn css_speed_matches_the_interpreter_and_its_cap() {
        assert_eq!(css_rpm(300_000, 50_000_000, 3000).round(), 955.0);
        assert_eq!(css_rpm(300_000, 0, 3000), 3000.0);
        assert_eq!(css_rpm(300_000, 1_000_000, 2500), 2500.0);
    }

    #[test]
    fn spindle_locked_moves_take_revolutions_over_speed() {
        assert_eq!(per_rev_seconds(30e6, 1.5e6, Some(600)), 2.0);
        assert_eq!(per_rev_seconds(30e6, 1.5e6, None), 0.0);
        assert_eq!(revolutions_seconds(100.0, Some(1000)), 6.0);
    }
}

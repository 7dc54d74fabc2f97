//! Look-ahead: how fast the path may pass each junction (G64 blending), and the
//! backward pass that makes every block able to brake in time for what follows.
//!
//! Junction speed is the smallest of
//! - the junction-deviation speed `v² = a·δ·cos(φ/2) / (1 − cos(φ/2))` (φ the angle
//!   between the two directions: the speed at which a circle of deviation δ
//!   through the corner needs no more than the axes' acceleration);
//! - each axis's allowed instantaneous speed jump `J / |u₂ − u₁|`;
//! - the chord limit `2·tol / sin(φ/2)` per period: the interpolation point before
//!   and after the corner are joined by a straight step path that must stay within
//!   the chord tolerance of the corner;
//! - the programmed speeds of both blocks;
//! - once settled, the curvature of the chain around it ([`bend`](super::bend)).
//!
//! The first three model a corner between blocks longer than a period's travel.
//! Where the shorter block `L` is too short for that, each applies only if the
//! corner is still one: the deviation circle only if its tangent
//! `δ·sin(φ/2) / (1 − cos(φ/2))` fits in `L/2`; the chord limit only if the corner
//! strays more than the tolerance from a chord within the two blocks,
//! `2·L·sin(φ/2) > tol`; an axis's jump only if the corner moves that axis off its
//! line by more than one period's jump, `L·|u₂ − u₁| > J`. Otherwise the corner is
//! a sample of a curve (CAM output, whose points are rounded to the input
//! increment: a 0.5 µm rounding turns a 0.02 mm block by 0.025 rad), and the
//! curvature limit of the chain takes over.
//!
//! The backward pass plans the interpolator's discrete profile exactly. A speed is
//! the distance of one period; braking by `a` a period from `v` to `e`, the period
//! at `e` ending on the boundary, takes `B(v) = (v² − e² + a·(v + e)) / 2a`. A block
//! of length `L` entered at `e₀` can brake to its exit `e₁` when
//! `(e₀ − a/2)² ≤ (e₁ − a/2)² + 2·a·L`, and that relation chains: the interpolator
//! that can brake for one boundary at this block's acceleration can brake for every
//! later one (its test in [`crate::interpolator`]). So a block gives up nothing of
//! its entry speed to the discrete profile — before, each block gave up one period
//! of acceleration, which capped a chain of short blocks at about one block a
//! period. An entry below one period of acceleration is 0 (the block before ends
//! at rest), so an entry only ever rises as blocks arrive. (The f32 rounding of
//! the entries and their Q8 form can break the chain by a fraction of a nanometre
//! a block; the interpolator's test leaves a quarter of a micrometre for it.)
//!
//! The backward pass works with `(e − a/2)²` (one root per changed entry) from the
//! newest block back to the first one whose entry speed it does not change.

use super::block::{Block, Dir};
use super::machine::MotionParams;
use crate::fixed::{PATH_FRAC, minf, sqrtf};

/// Highest speed (nm/period) through the junction from direction `a` into `b`;
/// `short` is the length (nm) of the shorter of the two blocks.
pub fn junction_speed(a: &Dir, b: &Dir, short: f32, p: &MotionParams) -> f32 {
    let cos_phi: f32 = a.iter().zip(b).map(|(x, y)| x * y).sum::<f32>().clamp(-1.0, 1.0);
    if cos_phi <= -0.999_999 {
        return 0.0;
    }
    let mut v = f32::MAX;
    if cos_phi < 0.999_999 {
        let cos_half = sqrtf((1.0 + cos_phi) / 2.0);
        let sin_half = sqrtf((1.0 - cos_phi) / 2.0);
        let one_minus = 1.0 - cos_half;
        if 2.0 * p.junction_deviation * sin_half <= short * one_minus {
            v = sqrtf(p.accel_min * p.junction_deviation * cos_half / one_minus);
        }
        if 2.0 * short * sin_half > p.chord_tolerance {
            v = minf(v, 2.0 * p.chord_tolerance / sin_half);
        }
    }
    for ((x, y), lim) in a.iter().zip(b).zip(&p.limits) {
        let jump = (y - x).abs();
        if lim.present && jump > 1e-7 && short * jump > lim.jump {
            v = minf(v, lim.jump / jump);
        }
    }
    v
}

/// Sets the highest entry speed `v` (nm/period) the junction into `block` allows:
/// below one period of acceleration the block starts from rest.
pub fn set_max_entry(block: &mut Block, v: f32) {
    block.entry_at_max = false;
    let plan = &mut block.plan;
    if v < plan.accel {
        (plan.max_entry, plan.max_reach) = (0.0, 0.0);
        return;
    }
    plan.max_entry = v;
    // The reach at which the braking-bound entry gets to `v`.
    let k = v - plan.accel * 0.5;
    plan.max_reach = k * k;
}

/// Sets `block`'s entry from the planned entry `exit` of the block after it: the
/// highest entry from which the interpolator's profile brakes to `exit` by the
/// block's end, at most the junction's limit. Returns whether the entry changed.
///
/// An entry already at the junction's limit stays there when the exit still
/// reaches it: the same `max_entry` as before, not computed again.
fn set_entry(block: &mut Block, exit: f32) -> bool {
    let plan = &mut block.plan;
    let h = plan.accel * 0.5;
    let d = exit - h;
    let reach = d * d + plan.two_a_len;
    let at_max = reach >= plan.max_reach;
    if at_max && block.entry_at_max {
        return false;
    }
    block.entry_at_max = at_max;
    let entry = if at_max {
        plan.max_entry
    } else {
        // Below `max_entry` but for rounding (reach < (max_entry − h)²).
        let e = h + sqrtf(reach);
        if e < plan.accel {
            0.0
        } else if e > plan.max_entry {
            plan.max_entry
        } else {
            e
        }
    };
    let changed = entry != plan.entry;
    plan.entry = entry;
    // `entry` is 0 or positive (a negative or NaN would become 0).
    plan.entry_q8 = (entry * (1u32 << PATH_FRAC) as f32) as u32;
    changed
}

/// Re-plans the entry speeds of `blocks` (oldest first; the last one ends at
/// rest, and the first one is the next to run). Stops at the first block whose
/// entry does not change: nothing before it can change either.
pub fn backward_pass<'a, I>(newest_first: I)
where
    I: Iterator<Item = Option<&'a mut Block>>,
{
    let mut exit = 0.0f32;
    for (k, item) in newest_first.enumerate() {
        let Some(block) = item else { return };
        if !set_entry(block, exit) && k >= 1 {
            return;
        }
        exit = block.plan.entry;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::MachineConfig;

    fn params() -> MotionParams {
        MotionParams::new(&MachineConfig::default()).unwrap()
    }

    fn dir(deg: f32) -> Dir {
        let r = deg.to_radians();
        [libm::sinf(r), 0.0, libm::cosf(r), 0.0]
    }

    #[test]
    fn straight_on_is_unlimited_and_reversal_stops() {
        let p = params();
        assert_eq!(junction_speed(&dir(30.0), &dir(30.0), 1e9, &p), f32::MAX);
        assert_eq!(junction_speed(&dir(0.0), &dir(180.0), 1e9, &p), 0.0);
    }

    #[test]
    fn right_angle_follows_the_formulas() {
        let p = params();
        let v = junction_speed(&dir(0.0), &dir(90.0), 1e9, &p);
        // δ = 10 µm, a = 500 nm/ms²: v² = a·δ·0.7071/0.2929 → 3474 nm/ms;
        // chord: 2 × 1 µm / sin 45° = 2828 nm/ms; jump: 5000 nm/ms / 1.
        assert!((v - 2_828.4).abs() < 1.0, "{v}");
        let mut loose = p;
        loose.chord_tolerance = 1e6;
        let v = junction_speed(&dir(0.0), &dir(90.0), 1e9, &loose);
        assert!((v - 3_474.3).abs() < 1.0, "{v}");
    }

    #[test]
    fn small_angles_take_the_smallest_limit() {
        let mut p = params();
        // 2°: X speed jumps by v·sin 2°; the jump limit is 5 µm/ms.
        let jump = 5_000.0 / libm::sinf(2f32.to_radians());
        let chord = 2.0 * 1_000.0 / libm::sinf(1f32.to_radians());
        let v = junction_speed(&dir(0.0), &dir(2.0), 1e9, &p);
        assert!((v - chord.min(jump)).abs() < 2.0, "{v}");
        p.chord_tolerance = 1e6;
        let v = junction_speed(&dir(0.0), &dir(2.0), 1e9, &p);
        assert!((v - jump).abs() < 2.0, "{v} vs {jump}");
    }
}

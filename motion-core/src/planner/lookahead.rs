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
//! period. The pass works with `u = (e − a/2)²` in Q16 integers ([`Plan`]): a
//! braking-bound entry is `u = u' + 2aL`, an addition, exact (one root only where
//! the acceleration changes from one block to the next). An entry below the
//! larger acceleration of the two blocks at its junction is 0 (the block before
//! ends at rest), so an entry only ever rises as blocks arrive.
//!
//! The backward pass runs from the newest block back to the first one whose entry
//! it does not change.

use super::Item;
use super::block::{Block, Dir, Plan};
use super::machine::MotionParams;
use crate::fixed::{PATH_FRAC, minf, sqrtf};
use canon::units::f32_of_u64;

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
        // sin²(φ/2): both limits are compared and taken as squares (every term is
        // positive), and one root gives the smaller of them.
        let sin_half_sq = (1.0 - cos_phi) / 2.0;
        let one_minus = 1.0 - cos_half;
        let half_short = 0.5 * short;
        let (jd, tol) = (p.junction_deviation, p.chord_tolerance);
        let mut v_sq = f32::MAX;
        // Where the deviation's arc fits the shorter block's half
        // (jd·sin(φ/2) ≤ short/2·(1 − cos(φ/2))): √(a·jd·cos(φ/2) / (1 − cos(φ/2))).
        let fits = half_short * one_minus;
        if jd * jd * sin_half_sq <= fits * fits {
            v_sq = p.accel_min * jd * cos_half / one_minus;
        }
        // Where the corner would cut more than the chord tolerance
        // (short/2·sin(φ/2) > tol/4): 2·tol / sin(φ/2).
        if half_short * half_short * sin_half_sq > 0.0625 * tol * tol {
            v_sq = minf(v_sq, 4.0 * tol * tol / sin_half_sq);
        }
        if v_sq < f32::MAX {
            v = sqrtf(v_sq);
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

/// `u` of a junction limit `v` (nm/period) into a block with `plan`: 0 below the
/// junction's floor (the block then starts from rest).
pub fn max_u(plan: &Plan, v: f32) -> u64 {
    let v_q8 = (v * (1u32 << PATH_FRAC) as f32) as u32;
    if v_q8 < plan.accel_q8 {
        return 0;
    }
    let u = square(v_q8 - plan.accel_q8 / 2);
    if u < plan.floor_u { 0 } else { u }
}

/// `x²` of a 32-bit `x`: one 32 × 32 → 64-bit multiply.
#[inline(always)]
fn square(x: u32) -> u64 {
    u64::from(x) * u64::from(x)
}

/// Sets the junction's floor into a block with `plan` from the acceleration
/// `prev_q8` (Q8) of the block before: the larger of the two accelerations.
#[inline]
pub fn set_floor(plan: &mut Plan, prev_q8: u32) {
    // The block's own acceleration is the floor `plan` starts with.
    if prev_q8 > plan.accel_q8 {
        plan.floor_u = square(prev_q8 - plan.accel_q8 / 2);
    }
}

/// Sets the highest entry speed `v` (nm/period) the junction into `block` allows.
pub fn set_max_entry(block: &mut Block, v: f32) {
    block.entry_at_max = false;
    block.plan.max_u = max_u(&block.plan, v);
}

/// `(e − h)²` for the entry `u_next` (0: at rest) of a block whose half
/// acceleration is `h_next`, seen from a block whose half acceleration is `h`.
fn exit_term(u_next: u64, h_next: u32, h: u32) -> u64 {
    if u_next == 0 {
        return square(h);
    }
    if h_next == h {
        return u_next;
    }
    // The entry rounded down (f32 root, less one): the next entry is at least
    // this block's acceleration (the junction's floor), so a smaller estimate
    // only lowers `(e − h)²` and the entry planned from it.
    let e = h_next + (sqrtf(f32_of_u64(u_next)) as u32).saturating_sub(1);
    square(e.saturating_sub(h))
}

/// Sets `block`'s entry from the entry `u_next` (half acceleration `h_next`) of
/// the block after it: the highest entry from which the interpolator's profile
/// brakes to it by the block's end, at most the junction's limit. Returns whether
/// the entry changed.
///
/// An entry at the junction's limit stays there: exits only rise as blocks
/// arrive, and a raised limit clears `entry_at_max`.
fn set_entry(block: &mut Block, u_next: u64, h_next: u32) -> bool {
    if block.entry_at_max {
        return false;
    }
    let plan = &mut block.plan;
    let h = plan.accel_q8 / 2;
    let reach = exit_term(u_next, h_next, h) + plan.two_a_len;
    let at_max = reach >= plan.max_u;
    block.entry_at_max = at_max;
    let mut u = if at_max { plan.max_u } else { reach };
    // Below the junction's floor: from rest.
    if u < plan.floor_u {
        u = 0;
    }
    let changed = u != plan.entry_u;
    plan.entry_u = u;
    changed
}

/// Re-plans the entry speeds of the queue given as its two contiguous parts
/// (`front` then `back`, oldest first; the last block ends at rest, the first is
/// the next to run), newest first. Stops at the first block whose entry does not
/// change (nothing before it can change either) or at a command (a barrier).
#[inline]
pub fn backward_pass(front: &mut [Item], back: &mut [Item]) {
    let mut pass = Pass { u_next: 0, h_next: 0, first: true };
    if pass.run(back) {
        pass.run(front);
    }
}

/// The backward pass's state between the queue's two parts.
struct Pass {
    /// The entry of the block after (as `u`, 0: at rest) and its half acceleration.
    u_next: u64,
    h_next: u32,
    /// No block visited yet (the newest is always re-planned).
    first: bool,
}

impl Pass {
    /// Re-plans `items` newest first; false where the pass stops.
    #[inline(always)]
    fn run(&mut self, items: &mut [Item]) -> bool {
        for item in items.iter_mut().rev() {
            let Item::Motion(block) = item else { return false };
            if !set_entry(block, self.u_next, self.h_next) && !self.first {
                return false;
            }
            self.first = false;
            (self.u_next, self.h_next) = (block.plan.entry_u, block.plan.accel_q8 / 2);
        }
        true
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

    /// CYCLE832's tolerance is both the junction deviation and the chord
    /// tolerance; 0 puts the machine's back.
    #[test]
    fn a_path_tolerance_replaces_both_and_goes_back() {
        let mut p = params();
        // 10°: jump limit 5 µm/ms / sin 10° = 28.8 µm/ms, above both others.
        let (c, s) = (libm::cosf(5f32.to_radians()), libm::sinf(5f32.to_radians()));
        let v0 = junction_speed(&dir(0.0), &dir(10.0), 1e9, &p);
        assert!((v0 - 2.0 * 1_000.0 / s).abs() < 2.0, "{v0}");
        p.set_tolerance(2_000);
        assert_eq!((p.junction_deviation, p.chord_tolerance), (2_000.0, 2_000.0));
        let v = junction_speed(&dir(0.0), &dir(10.0), 1e9, &p);
        // √(a·δ·cos / (1 − cos)) = 16.2 µm/ms against the chord's 45.9.
        let want = libm::sqrtf(500.0 * 2_000.0 * c / (1.0 - c));
        assert!((v - want).abs() < 2.0, "{v} vs {want}");
        p.set_tolerance(0);
        assert_eq!(p, params());
    }
}

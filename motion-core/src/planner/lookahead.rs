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
//! - the programmed speeds of both blocks.
//!
//! The backward pass works with squared speeds (no roots) from the newest block
//! back to the first one whose entry speed it does not change.

use super::block::{Block, Dir};
use super::machine::MotionParams;
use crate::fixed::{PATH_FRAC, maxf, minf, sqrtf, u64_of};

/// Highest speed (nm/period) through the junction from direction `a` into `b`.
pub fn junction_speed(a: &Dir, b: &Dir, p: &MotionParams) -> f32 {
    let cos_phi: f32 = a.iter().zip(b).map(|(x, y)| x * y).sum::<f32>().clamp(-1.0, 1.0);
    if cos_phi <= -0.999_999 {
        return 0.0;
    }
    let mut v = f32::MAX;
    if cos_phi < 0.999_999 {
        let cos_half = sqrtf((1.0 + cos_phi) / 2.0);
        let sin_half = sqrtf((1.0 - cos_phi) / 2.0);
        let jd = p.accel_min * p.junction_deviation * cos_half / (1.0 - cos_half);
        v = minf(sqrtf(jd), 2.0 * p.chord_tolerance / sin_half);
    }
    for ((x, y), lim) in a.iter().zip(b).zip(&p.limits) {
        let jump = (y - x).abs();
        if lim.present && jump > 1e-7 {
            v = minf(v, lim.jump / jump);
        }
    }
    v
}

/// Sets `block`'s entry from the square of the highest entry that still lets the
/// block brake to `exit_sq` by its end. The discrete profile brakes one period
/// late at worst, so a braking-bound entry gives up one period of acceleration.
/// Returns whether the entry changed.
///
/// An entry already at the junction's limit stays there when the exit still
/// reaches it: the same `sqrtf(max_entry_sq)` as before, not computed again.
fn set_entry(block: &mut Block, exit_sq: f32) -> bool {
    let plan = &mut block.plan;
    let reach = exit_sq + plan.two_a_len;
    let at_max = reach >= plan.max_entry_sq;
    if at_max && block.entry_at_max {
        return false;
    }
    block.entry_at_max = at_max;
    let entry = if at_max { sqrtf(plan.max_entry_sq) } else { maxf(sqrtf(reach) - plan.accel, 0.0) };
    let entry_sq = entry * entry;
    let changed = entry_sq != plan.entry_sq;
    plan.entry_sq = entry_sq;
    plan.entry_q8 = u64_of(entry * (1u32 << PATH_FRAC) as f32);
    changed
}

/// Re-plans the entry speeds of `blocks` (oldest first; the last one ends at
/// rest, and the first one is the next to run). Stops at the first block whose
/// entry does not change: nothing before it can change either.
pub fn backward_pass<'a, I>(newest_first: I)
where
    I: Iterator<Item = Option<&'a mut Block>>,
{
    let mut exit_sq = 0.0f32;
    for (k, item) in newest_first.enumerate() {
        let Some(block) = item else { return };
        if !set_entry(block, exit_sq) && k >= 1 {
            return;
        }
        exit_sq = block.plan.entry_sq;
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
        assert_eq!(junction_speed(&dir(30.0), &dir(30.0), &p), f32::MAX);
        assert_eq!(junction_speed(&dir(0.0), &dir(180.0), &p), 0.0);
    }

    #[test]
    fn right_angle_follows_the_formulas() {
        let p = params();
        let v = junction_speed(&dir(0.0), &dir(90.0), &p);
        // δ = 10 µm, a = 500 nm/ms²: v² = a·δ·0.7071/0.2929 → 3474 nm/ms;
        // chord: 2 × 1 µm / sin 45° = 2828 nm/ms; jump: 5000 nm/ms / 1.
        assert!((v - 2_828.4).abs() < 1.0, "{v}");
        let mut loose = p;
        loose.chord_tolerance = 1e6;
        let v = junction_speed(&dir(0.0), &dir(90.0), &loose);
        assert!((v - 3_474.3).abs() < 1.0, "{v}");
    }

    #[test]
    fn small_angles_take_the_smallest_limit() {
        let mut p = params();
        // 2°: X speed jumps by v·sin 2°; the jump limit is 5 µm/ms.
        let jump = 5_000.0 / libm::sinf(2f32.to_radians());
        let chord = 2.0 * 1_000.0 / libm::sinf(1f32.to_radians());
        let v = junction_speed(&dir(0.0), &dir(2.0), &p);
        assert!((v - chord.min(jump)).abs() < 2.0, "{v}");
        p.chord_tolerance = 1e6;
        let v = junction_speed(&dir(0.0), &dir(2.0), &p);
        assert!((v - jump).abs() < 2.0, "{v} vs {jump}");
    }
}

//! Fixed-point arithmetic for the motion layers: the formats, a widening multiply
//! and a multiply-only reciprocal. Nothing here divides, so the per-tick and
//! per-step paths that use it stay free of division (and of the slow `i64`
//! division library call on the Cortex-M4).
//!
//! Formats used by the motion core:
//! - path lengths and speeds: nanometres with [`PATH_FRAC`] fraction bits (Q8 nm,
//!   Q8 nm per tick, Q8 nm per tick²);
//! - axis positions: steps with [`STEP_FRAC`] fraction bits (Q16 steps);
//! - block progress: a fraction of the block with [`FRAC_BITS`] bits (1.0 = 2^32);
//! - angles: turns with 32 fraction bits (a full turn is 2^32).

/// Fraction bits of path lengths and speeds (Q8 nanometres).
pub const PATH_FRAC: u32 = 8;
/// Fraction bits of axis positions (Q16 steps).
pub const STEP_FRAC: u32 = 16;
/// One step in Q16.
pub const STEP_ONE: i64 = 1 << STEP_FRAC;
/// Fraction bits of the progress through a block.
pub const FRAC_BITS: u32 = 32;
/// A whole block (progress 1.0).
pub const FRAC_ONE: u64 = 1 << FRAC_BITS;

/// `(a × b) >> sh`, computed exactly in 128 bits and truncated back to 64
/// (the caller keeps the result in range). About 15 instructions on the M4.
#[inline]
pub fn mul_shr(a: i64, b: i64, sh: u32) -> i64 {
    ((i128::from(a) * i128::from(b)) >> sh) as i64
}

/// `(a × b) >> 32`: a value scaled by a Q32 factor.
#[inline]
pub fn mul_q32(a: i64, b: i64) -> i64 {
    mul_shr(a, b, 32)
}

/// `2^62 / len` (at least 1 for `len`): with it, the progress `s / len` in Q32 is
/// `s × inverse >> 30`, one multiply per period instead of a division.
pub fn inverse62(len: u64) -> i64 {
    (1i64 << 62) / (len.clamp(1, i64::MAX as u64) as i64)
}

/// The nearest whole step of a Q16 position (halves round up).
#[inline]
pub const fn round_steps(q16: i64) -> i64 {
    (q16 + (STEP_ONE >> 1)) >> STEP_FRAC
}

/// `2^63 / d` for `d` in `[2^31, 2^32)`, by Newton–Raphson from a linear seed:
/// three iterations take the seed's 1/17 error below 2^-32. Multiplications only.
fn recip_normalised(d: u32) -> u64 {
    // Seed 48/17 − 32/17·x for x = d / 2^32 in [0.5, 1), scaled by 2^31.
    const C48: u64 = (48u64 << 31) / 17;
    const C32: u64 = (32u64 << 31) / 17;
    let d = u64::from(d);
    let mut x = C48 - ((d * C32) >> 32);
    for _ in 0..3 {
        // e = 1 − x·d in Q63; x ≈ 2^63/d keeps x·d within 2^63·(1 ± 1/17).
        let e = (1u64 << 63).wrapping_sub(x.wrapping_mul(d)) as i64;
        x = x.wrapping_add_signed(((x as i64) * (e >> 31)) >> 32);
    }
    x
}

/// `⌊scale · 2^32 / d⌋` (to within 2^-30 relative) without dividing, for `d ≥ 1`
/// and `scale < 2^31`: how much of `scale` one unit of `d` is worth, in Q32.
/// The step generator uses it to turn a tick's length into time per position unit.
pub fn scaled_reciprocal(scale: u32, d: u32) -> u64 {
    let d = d.max(1);
    let n = d.leading_zeros();
    let x = recip_normalised(d << n);
    // 2^32/d = x · 2^(n+32) / 2^63.
    (u64::from(scale) * x) >> (31 - n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn widening_multiply_and_rounding() {
        assert_eq!(mul_q32(3 << 32, 5 << 32), 15 << 32);
        assert_eq!(mul_q32(-(3 << 32), 1 << 31), -(3 << 31));
        assert_eq!(mul_shr(i64::MAX, 4, 2), i64::MAX);
        assert_eq!(round_steps(STEP_ONE / 2), 1);
        assert_eq!(round_steps(STEP_ONE / 2 - 1), 0);
        assert_eq!(round_steps(-STEP_ONE / 2), 0);
        assert_eq!(round_steps(-STEP_ONE / 2 - 1), -1);
    }

    #[test]
    fn reciprocal_is_accurate_over_the_whole_range() {
        let mut d = 1u32;
        while d < u32::MAX / 3 {
            for scale in [1u32, 1_000, 1_000_000, (1 << 31) - 1] {
                let exact = (u128::from(scale) << 32) / u128::from(d);
                let got = u128::from(scaled_reciprocal(scale, d));
                let err = exact.abs_diff(got);
                assert!(err <= (exact >> 29) + 1, "scale {scale} d {d}: {got} vs {exact}");
            }
            d = d * 3 / 2 + 1;
        }
    }
}

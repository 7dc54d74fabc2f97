//! Fixed-point arithmetic for the motion layers: the formats, a widening multiply
//! and a multiply-only reciprocal. Nothing here divides, so the per-tick and
//! per-step paths that use it stay free of division (and of the slow `i64`
//! division library call on the Cortex-M4) — except [`gcd`], which reduces the step
//! and gear ratios once, when the machine is configured or a thread is set up, and
//! [`sqrtf`], the planner's per-block square root, by FPU divisions.
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

/// `2^62 / len` to within 2^-30 relative, for `len` in `[1, 2^61]`: with it the
/// progress `s / len` in Q32 is `s × inverse >> 30`, one multiply per period. Taken
/// from the top 32 bits of `len` by the multiply-only reciprocal (an error of 2^-30
/// moves a million-step block by a thousandth of a step; its end point is exact).
pub fn inverse62(len: u64) -> i64 {
    let len = len.clamp(1, 1 << 61);
    let z = len.leading_zeros();
    let top = ((len << z) >> 32) as u32;
    // 2^62 / len = (2^63 / top) · 2^(z − 33).
    let x = recip_normalised(top);
    (if z >= 33 { x << (z - 33) } else { x >> (33 - z) }) as i64
}

pub use canon::units::f32_of;

/// `x as u64` (saturating, NaN → 0), by the FPU's 32-bit conversion below 2^32.
#[inline]
pub fn u64_of(x: f32) -> u64 {
    if x < 4_294_967_296.0 { u64::from(x as u32) } else { x as u64 }
}

/// `a.min(b)` (a NaN loses) without the `fminf` call the Cortex-M4 build makes.
#[inline]
pub fn minf(a: f32, b: f32) -> f32 {
    if b < a || a.is_nan() { b } else { a }
}

/// `a.max(b)` (a NaN loses) without the `fmaxf` call.
#[inline]
pub fn maxf(a: f32, b: f32) -> f32 {
    if b > a || a.is_nan() { b } else { a }
}

/// `√x` for `x ≥ 0` (0 for anything else, infinity for infinity) to within 2^-22
/// relative for a normal `x`: a seed from the bit pattern (within 4 %), refined three times by
/// Heron's step `(s + x/s) / 2` on the FPU. For the planner's per-block speeds and
/// lengths (never in an interrupt: it divides); libm's `sqrtf` is a bit-by-bit
/// software loop on the Cortex-M4.
#[inline]
pub fn sqrtf(x: f32) -> f32 {
    // Positive and finite (one integer compare on the bits; denormals included).
    if x.to_bits().wrapping_sub(1) >= 0x7f7f_ffff {
        return if x == f32::INFINITY { x } else { 0.0 };
    }
    // Half the exponent, the mantissa halved linearly.
    let mut s = f32::from_bits((x.to_bits() >> 1) + 0x1fbb_4f2e);
    for _ in 0..3 {
        s = 0.5 * (s + x / s);
    }
    s
}

/// A divisor with its reciprocal: `⌊n / d⌋` by one multiply and a correction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Divisor {
    d: u64,
    /// `⌊2^64 / d⌋` (0 stands for 2^64 when `d` is 1).
    m: u64,
}

impl Divisor {
    /// `d` (at least 1) prepared for division.
    pub const fn new(d: u64) -> Self {
        let d = if d == 0 { 1 } else { d };
        let m = if d == 1 { 0 } else { ((1u128 << 64) / d as u128) as u64 };
        Divisor { d, m }
    }

    /// The divisor.
    pub const fn get(&self) -> u64 {
        self.d
    }

    /// `⌊n / d⌋` exactly, for any `n`.
    pub fn div_floor(&self, n: i64) -> i64 {
        if self.d == 1 {
            return n;
        }
        let a = n.unsigned_abs();
        // A position's steps (|n| and the divisor below 2^32): all in 32 bits, the
        // estimate `⌊a·⌊2^32/d⌋ / 2^32⌋` low by at most two, its remainder below 2^32.
        if let (Ok(a), Ok(d)) = (u32::try_from(a), u32::try_from(self.d)) {
            let mut q = ((u64::from(a) * (self.m >> 32)) >> 32) as u32;
            let mut r = a.wrapping_sub(q.wrapping_mul(d));
            while r >= d {
                q += 1;
                r -= d;
            }
            let q = i64::from(q);
            return if n >= 0 { q } else { -q - i64::from(r != 0) };
        }
        let mut q = match u32::try_from(a) {
            // ⌊a·m / 2^64⌋ from two 32 × 32-bit products (a position's steps,
            // |n| < 2^32): ⌊(a·m_hi + ⌊a·m_lo / 2^32⌋) / 2^32⌋, no 128-bit multiply;
            // the sum stays below 2^64 − 2^32.
            Ok(a) => {
                let a = u64::from(a);
                (a * (self.m >> 32) + ((a * (self.m & 0xffff_ffff)) >> 32)) >> 32
            }
            Err(_) => ((u128::from(a) * u128::from(self.m)) >> 64) as u64,
        };
        // The estimate is low by at most one or two.
        let mut r = a - q * self.d;
        while r >= self.d {
            q += 1;
            r -= self.d;
        }
        if n >= 0 { q as i64 } else { -(q as i64) - i64::from(r != 0) }
    }
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

/// Greatest common divisor of two positive numbers.
pub fn gcd(mut a: i64, mut b: i64) -> i64 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a.abs().max(1)
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
    fn exact_division_by_reciprocal() {
        for d in [1u64, 2, 3, 7, 3_125, 1_000_000, 999_999_937, 1 << 40] {
            let div = Divisor::new(d);
            for n in [0i64, 1, -1, 5, -5, 3_124, 3_125, -3_125, -3_126, 123_456_789_012, -987_654_321_098, i64::MAX / 4]
            {
                assert_eq!(div.div_floor(n), n.div_euclid(d as i64), "{n} / {d}");
            }
        }
    }

    /// Both ways of `div_floor` (below and above 2^32) against `div_euclid`.
    #[test]
    fn division_by_reciprocal_over_random_values() {
        let mut rng = canon::xorshift::XorShift::new(0x2545_f491_4f6c_dd1d);
        for d in [2u64, 3, 10, 3_125, 65_537, (1 << 32) - 1, 1 << 32, (1 << 32) + 1, 999_999_999_989, 1 << 62] {
            let div = Divisor::new(d);
            for i in 0..50_000 {
                let m = [1i64 << 10, 1 << 31, 1 << 32, 1 << 33, 1 << 62][i % 5];
                let n = match i % 101 {
                    0 => u32::MAX as i64,
                    1 => -(u32::MAX as i64),
                    2 => 1 << 32,
                    3 => i64::MIN + 1,
                    _ => rng.signed(m),
                };
                assert_eq!(div.div_floor(n), n.div_euclid(d as i64), "{n} / {d}");
            }
        }
    }

    #[test]
    fn square_root_and_multiply_only_inverse() {
        let mut rng = canon::xorshift::XorShift::new(0x5eed_5eed_5eed_5eed);
        let random = (0..200_000).map(|_| f32::from_bits((rng.next_u64() as u32) & 0x7fff_ffff));
        let fixed = [1e-30f32, 1e-6, 0.5, 1.0, 2.0, 3.0, 1e4, 1.234e10, 3.0e30, f32::MAX, f32::MIN_POSITIVE];
        for x in fixed.into_iter().chain(random).filter(|x| x.is_normal()) {
            let r = sqrtf(x);
            assert!((f64::from(r) / f64::from(x).sqrt() - 1.0).abs() < 2.5e-7, "{x}: {r}");
        }
        assert_eq!(sqrtf(0.0), 0.0);
        assert_eq!(sqrtf(-1.0), 0.0);
        assert_eq!(sqrtf(f32::NAN), 0.0);
        assert_eq!(sqrtf(f32::INFINITY), f32::INFINITY);
        for len in [1u64, 2, 3, 255, 1 << 20, 123_456_789, 1 << 40, (1 << 50) + 12_345] {
            let exact = (1u128 << 62) / u128::from(len);
            let got = inverse62(len) as u128;
            assert!(exact.abs_diff(got) <= (exact >> 29) + 1, "{len}: {got} vs {exact}");
        }
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

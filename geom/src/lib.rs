//! Per-block geometry in a plane: arc centres from R or I/J/K, arc extents, the
//! points and segments of the ZX plane the turning cycles plan with; the numeric
//! functions in degrees both languages share ([`deg`]).
//! Uses f64 (libm) for the computation, returns integer nanometres.

#![no_std]

#[cfg(test)]
extern crate std;

mod arc;
pub mod deg;
pub mod path;
mod seg;
mod sqrt;

pub use arc::{Extents, P2, arc_extents, center_from_offsets, center_from_radius};
pub use seg::{Pt, Seg, SegKind};

/// Sine and cosine of `x` radians. Every sine and cosine in the interpreters goes
/// through libm's `sincos`, which gives bit for bit the values of `libm::sin` and
/// `libm::cos` (the same argument reduction and kernels; `tests::sin_cos_is_sin_and_cos`),
/// so the image carries one routine instead of three.
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    libm::sincos(x)
}

/// The remainder of `x / y` with the sign of `x`, exactly (C's `fmod`): bit for bit
/// `libm::fmod` (`tests::fmod_is_libm_fmod`), in a tenth of its 2.7 KB. From the
/// largest `|y|·2^k ≤ |x|` down to `|y|` it subtracts each multiple that fits; each
/// subtraction is exact (Sterbenz: `t ≤ r < 2t`) and so is each halving of `t`, at
/// most 2,100 steps for the widest exponents, a handful for angles.
#[inline(never)]
pub fn fmod(x: f64, y: f64) -> f64 {
    let (mut r, ay) = (x.abs(), y.abs());
    if !r.is_finite() || y.is_nan() || ay == 0.0 {
        return f64::NAN;
    }
    if r < ay {
        return x;
    }
    let k = libm::ilogb(r) - libm::ilogb(ay);
    let mut t = libm::scalbn(ay, k);
    if t > r {
        t = libm::scalbn(ay, k - 1);
    }
    while t >= ay {
        if r >= t {
            r -= t;
        }
        t *= 0.5;
    }
    libm::copysign(r, x)
}

/// `libm::round(x) as i64`: half away from zero, saturating (NaN gives 0). Out
/// of line: the saturating conversion is ~40 bytes of soft-float calls at every
/// site, and the cold transformations (G68, G51, G16, polar) round at many.
#[inline(never)]
pub fn round_i64(x: f64) -> i64 {
    libm::round(x) as i64
}

#[cfg(test)]
mod tests {
    use super::sin_cos;

    /// `fmod` must be bit for bit `libm::fmod`: angles reduced mod 360 and 2π
    /// (the goldens), macro MOD, random bit patterns (subnormals, the widest
    /// exponent gaps, NaN, the infinities, signed zeros).
    #[test]
    fn fmod_is_libm_fmod() {
        let same = |x: f64, y: f64| {
            let (a, b) = (super::fmod(x, y), libm::fmod(x, y));
            assert!(a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()), "fmod({x:e}, {y:e}): {a:e} {b:e}");
        };
        let tau = core::f64::consts::TAU;
        for udeg in (-7_200_000_000_i64..=7_200_000_000).step_by(9_973) {
            let d = udeg as f64 / 1e6;
            same(d, 360.0);
            same(d.to_radians(), tau);
            same(d / 7.3, 1.0);
        }
        let mut x: u64 = 0x2545_f491_4f6c_dd1d;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        for _ in 0..300_000 {
            let (a, b) = (next(), next());
            same(f64::from_bits(a), f64::from_bits(b));
            let (fa, fb) = ((a >> 11) as f64 / 9e12 - 500.0, (b >> 11) as f64 / 7e14 - 6.0);
            same(fa, fb);
            same(fa * 1e9, fb * 1e-9);
            same(f64::from_bits(a & 0x800f_ffff_ffff_ffff), f64::from_bits(b & 0x000f_ffff_ffff_ffff));
        }
        let special = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            5e-324,
            -5e-324,
            2.2e-308,
            f64::MAX,
            -f64::MAX,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            360.0,
            tau,
        ];
        for a in special {
            for b in special {
                same(a, b);
            }
        }
    }

    /// `sin_cos` must be bit for bit `(libm::sin, libm::cos)`: every golden and every
    /// cycle's geometry was computed with those. Angles as the interpreters make them
    /// (degrees and µdeg to radians, arc sweeps, reduced angles), the reduction's
    /// boundaries (π/4 multiples), tiny and huge arguments, NaN and the infinities.
    #[test]
    fn sin_cos_is_sin_and_cos() {
        let same = |x: f64| {
            let (s, c) = sin_cos(x);
            let (rs, rc) = (libm::sin(x), libm::cos(x));
            assert!(s.to_bits() == rs.to_bits() || (s.is_nan() && rs.is_nan()), "sin {x:e}: {s:e} {rs:e}");
            assert!(c.to_bits() == rc.to_bits() || (c.is_nan() && rc.is_nan()), "cos {x:e}: {c:e} {rc:e}");
        };
        for udeg in (-720_000_000_i64..=720_000_000).step_by(997) {
            same((udeg as f64 / 1e6).to_radians());
        }
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        for _ in 0..1_000_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let v = f64::from_bits(x);
            same(v);
            same((x >> 11) as f64 / (1u64 << 53) as f64 * 200.0 - 100.0);
        }
        for k in -64..=64 {
            let b = f64::from(k) * core::f64::consts::FRAC_PI_4;
            for d in [-2.0, -1.0, 0.0, 1.0, 2.0] {
                same(f64::from_bits((b.to_bits() as i64 + d as i64) as u64));
            }
        }
        for v in [0.0, -0.0, 1e-300, 2e-27, 1.4e-8, 1.5e-8, 1e300, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            same(v);
            same(-v);
        }
    }
}

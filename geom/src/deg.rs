//! Numeric functions in degrees and the other functions both languages share
//! (FANUC macro B, SINUMERIK arithmetic), on `f64` with libm so the board
//! computes the same bits as the host. Domain errors are alarms, never NaN
//! (0112 division by zero, 0119 argument out of range, in both languages).

use canon::alarm::AlarmKind;

/// π/180 split into a double-double: `D2R_HI + D2R_LO` is π/180 to ~1e-34.
const D2R_HI: f64 = 0.017_453_292_519_943_295;
const D2R_LO: f64 = 2.948_652_270_870_168_7e-19;
/// `D2R_HI` split into its upper 26 bits of mantissa and the rest (both exact).
const D2R_HI_1: f64 = {
    let c = 134_217_729.0 * D2R_HI;
    c - (c - D2R_HI)
};
const D2R_HI_2: f64 = D2R_HI - D2R_HI_1;
/// 180/π.
const R2D: f64 = 57.295_779_513_082_32;

/// `x` in degrees reduced exactly to `r` in [-45, 45] and a quadrant `q` (0–3), with
/// `x = r + 90·q (mod 360)`. `fmod` and the subtraction are exact in binary.
/// Out of line: SIN, COS and TAN share one copy.
#[inline(never)]
fn reduce(x: f64) -> (f64, u8) {
    let y = super::fmod(x, 360.0);
    let q = libm::round(y / 90.0);
    let r = y - 90.0 * q;
    (r, (q as i32).rem_euclid(4) as u8)
}

/// sin and cos of `r` degrees, |r| ≤ 45ish, with the argument converted to radians
/// in double-double precision (so SIN[30] is exactly 0.5).
fn sin_cos_reduced(r: f64) -> (f64, f64) {
    if r.abs() == 45.0 {
        // cos(hi) is rounded before the correction: pin the value both share.
        return (core::f64::consts::FRAC_1_SQRT_2.copysign(r), core::f64::consts::FRAC_1_SQRT_2);
    }
    let hi = r * D2R_HI;
    let lo = product_error(r, hi) + r * D2R_LO;
    let (s, c) = super::sin_cos(hi);
    (s + c * lo, c - s * lo)
}

/// `r·D2R_HI − hi` exactly, `hi` being the rounded product: Dekker's two-product
/// with `D2R_HI` split into 26-bit halves (`D2R_HI_1 + D2R_HI_2`). The same bits as
/// `libm::fma(r, D2R_HI, -hi)` for |r| ≤ 45 (no overflow, no underflow above ~1e-290),
/// without the software fma's 1.4 KB (the Cortex-M4's FPU is single precision).
fn product_error(r: f64, hi: f64) -> f64 {
    // Veltkamp's split of r: 2^27 + 1.
    let c = 134_217_729.0 * r;
    let r1 = c - (c - r);
    let r2 = r - r1;
    ((r1 * D2R_HI_1 - hi) + r1 * D2R_HI_2 + r2 * D2R_HI_1) + r2 * D2R_HI_2
}

/// sin and cos of `x` degrees (one copy of the quadrant's signs for both).
#[inline(never)]
fn sin_cos_deg(x: f64) -> (f64, f64) {
    let (r, q) = reduce(x);
    let (s, c) = sin_cos_reduced(r);
    let (s, c) = match q {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    };
    (positive_zero(s), positive_zero(c))
}

/// sin of `x` degrees.
pub fn sin_deg(x: f64) -> f64 {
    sin_cos_deg(x).0
}

/// cos of `x` degrees.
pub fn cos_deg(x: f64) -> f64 {
    sin_cos_deg(x).1
}

/// tan of `x` degrees; alarm 0112 at odd multiples of 90° (2.24.2 (6): "TAN[90]").
pub fn tan_deg(x: f64) -> Result<f64, AlarmKind> {
    let (r, q) = reduce(x);
    if r.abs() == 45.0 {
        // tan ±45° = ±1, negated in the odd quadrants (tan(r + 90) = -1/tan r).
        let t = if q % 2 == 0 { r.signum() } else { -r.signum() };
        return Ok(t);
    }
    let (s, c) = sin_cos_reduced(r);
    if q % 2 == 0 {
        Ok(positive_zero(s / c))
    } else if s == 0.0 {
        Err(AlarmKind::DivideByZero)
    } else {
        Ok(positive_zero(-c / s))
    }
}

/// Radians to degrees, snapped to a whole degree when within a few ulps of it, so
/// ASIN[1], ACOS[0.5] and ATAN[1] give 90, 60 and 45 exactly (out of line: the
/// three inverse functions share it).
#[inline(never)]
pub fn degrees(rad: f64) -> f64 {
    let d = rad * R2D;
    let whole = libm::round(d);
    if (d - whole).abs() <= d.abs() * 1e-15 { positive_zero(whole) } else { d }
}

/// ASIN in degrees, -90..90; alarm 0119 outside -1..1 (2.24.2 (4)).
pub fn asin_deg(x: f64) -> Result<f64, AlarmKind> {
    if !(-1.0..=1.0).contains(&x) {
        return Err(AlarmKind::ArgumentOutOfRange { function: "ASIN" });
    }
    Ok(degrees(libm::asin(x)))
}

/// ACOS in degrees, 0..180; alarm 0119 outside -1..1 (2.24.2 (5)).
pub fn acos_deg(x: f64) -> Result<f64, AlarmKind> {
    if !(-1.0..=1.0).contains(&x) {
        return Err(AlarmKind::ArgumentOutOfRange { function: "ACOS" });
    }
    Ok(degrees(libm::acos(x)))
}

/// One-argument ATAN in degrees, -90..90.
pub fn atan_deg(x: f64) -> f64 {
    degrees(libm::atan(x))
}

/// SQRT; alarm 0119 below zero.
pub fn sqrt(x: f64) -> Result<f64, AlarmKind> {
    if x < 0.0 {
        return Err(AlarmKind::ArgumentOutOfRange { function: "SQRT" });
    }
    Ok(libm::sqrt(x))
}

/// EXP; alarm 0119 beyond ±80 (the manual's range).
pub fn exp(x: f64) -> Result<f64, AlarmKind> {
    if !(-80.0..=80.0).contains(&x) {
        return Err(AlarmKind::ArgumentOutOfRange { function: "EXP" });
    }
    Ok(libm::exp(x))
}

/// FIX: drops the fraction (toward zero): FIX[1.2] = 1, FIX[-1.2] = -1 (out of
/// line: both languages' expressions).
#[inline(never)]
pub fn fix(x: f64) -> f64 {
    positive_zero(libm::trunc(x))
}

/// `j MOD k`: the remainder of j / k with the sign of j; alarm 0112 for k = 0.
pub fn modulo(j: f64, k: f64) -> Result<f64, AlarmKind> {
    if k == 0.0 {
        return Err(AlarmKind::DivideByZero);
    }
    Ok(positive_zero(super::fmod(j, k)))
}

/// -0.0 becomes 0.0, so results never print as "-0".
pub fn positive_zero(x: f64) -> f64 {
    x + 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-14 * b.abs().max(1.0)
    }

    #[test]
    fn sine_and_cosine_are_exact_where_the_value_is_representable() {
        for (x, s) in [
            (0.0, 0.0),
            (30.0, 0.5),
            (90.0, 1.0),
            (150.0, 0.5),
            (180.0, 0.0),
            (210.0, -0.5),
            (270.0, -1.0),
            (360.0, 0.0),
            (-30.0, -0.5),
            (-90.0, -1.0),
            (390.0, 0.5),
            (720.0, 0.0),
        ] {
            assert_eq!(sin_deg(x), s, "SIN[{x}]");
        }
        for (x, c) in [(0.0, 1.0), (60.0, 0.5), (90.0, 0.0), (120.0, -0.5), (180.0, -1.0), (300.0, 0.5), (-60.0, 0.5)] {
            assert_eq!(cos_deg(x), c, "COS[{x}]");
        }
        assert_eq!(sin_deg(45.0), core::f64::consts::FRAC_1_SQRT_2);
        assert_eq!(cos_deg(45.0), core::f64::consts::FRAC_1_SQRT_2);
        assert!(close(sin_deg(60.0), 0.866_025_403_784_438_6));
        assert!(close(sin_deg(12.3456), libm::sin(12.3456_f64.to_radians())));
        assert!(close(cos_deg(1e6 + 60.0), cos_deg(280.0 + 60.0)), "1e6 = 2777 turns + 280");
    }

    #[test]
    fn the_two_product_is_the_fma() {
        // Every reduced argument's error term as libm's fma gives it: a sweep of
        // [-45, 45] in odd steps, the quadrant edges and tiny arguments.
        let mut r = -45.0;
        while r <= 45.0 {
            let hi = r * D2R_HI;
            assert_eq!(product_error(r, hi).to_bits(), libm::fma(r, D2R_HI, -hi).to_bits(), "r = {r}");
            r += 0.000_123_456_789_1;
        }
        for r in [0.0, -0.0, 1e-200, -3e-120, 1e-10, 44.999_999_999, 12.3456, 30.0, 60.0 - 45.0] {
            let hi = r * D2R_HI;
            assert_eq!(product_error(r, hi).to_bits(), libm::fma(r, D2R_HI, -hi).to_bits(), "r = {r}");
        }
    }

    #[test]
    fn tangent_and_its_poles() {
        assert_eq!(tan_deg(0.0), Ok(0.0));
        assert_eq!(tan_deg(45.0), Ok(1.0));
        assert_eq!(tan_deg(-45.0), Ok(-1.0));
        assert_eq!(tan_deg(135.0), Ok(-1.0));
        assert_eq!(tan_deg(225.0), Ok(1.0));
        assert_eq!(tan_deg(180.0), Ok(0.0));
        assert!(close(tan_deg(60.0).unwrap(), 3.0_f64.sqrt()));
        assert!(close(tan_deg(30.0).unwrap(), 1.0 / 3.0_f64.sqrt()));
        for pole in [90.0, 270.0, -90.0, 450.0] {
            assert_eq!(tan_deg(pole), Err(AlarmKind::DivideByZero), "TAN[{pole}]");
        }
        assert!(tan_deg(89.999).unwrap() > 57_000.0);
    }

    #[test]
    fn inverse_functions_in_degrees() {
        assert_eq!(asin_deg(1.0), Ok(90.0));
        assert_eq!(asin_deg(-1.0), Ok(-90.0));
        assert_eq!(asin_deg(0.5), Ok(30.0));
        assert_eq!(asin_deg(0.0), Ok(0.0));
        assert_eq!(acos_deg(0.5), Ok(60.0));
        assert_eq!(acos_deg(-1.0), Ok(180.0));
        assert_eq!(acos_deg(1.0), Ok(0.0));
        assert_eq!(acos_deg(0.0), Ok(90.0));
        assert!(close(asin_deg(0.3).unwrap(), 17.457_603_123_722_095));
        assert_eq!(asin_deg(1.000_001), Err(AlarmKind::ArgumentOutOfRange { function: "ASIN" }));
        assert_eq!(acos_deg(-1.5), Err(AlarmKind::ArgumentOutOfRange { function: "ACOS" }));
        assert_eq!(atan_deg(1.0), 45.0);
    }

    #[test]
    fn fix_sqrt_exp_and_modulo() {
        assert_eq!(sqrt(16.0), Ok(4.0));
        assert_eq!(sqrt(2.0), Ok(core::f64::consts::SQRT_2));
        assert_eq!(sqrt(-0.1), Err(AlarmKind::ArgumentOutOfRange { function: "SQRT" }));
        assert_eq!(exp(0.0), Ok(1.0));
        assert!(close(exp(1.0).unwrap(), core::f64::consts::E));
        assert!(exp(80.0).is_ok() && exp(-80.0).is_ok());
        assert_eq!(exp(80.5), Err(AlarmKind::ArgumentOutOfRange { function: "EXP" }));
        assert_eq!(modulo(7.0, 3.0), Ok(1.0));
        assert_eq!(modulo(-7.0, 3.0), Ok(-1.0));
        assert_eq!(modulo(7.5, 2.0), Ok(1.5));
        assert_eq!(modulo(1.0, 0.0), Err(AlarmKind::DivideByZero));
        assert_eq!((fix(1.2), fix(-1.2), fix(3.0)), (1.0, -1.0, 3.0));
    }
}

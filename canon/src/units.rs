//! Internal units and the conversion of program numbers into them.
//!
//! Every length inside the controller is an integer number of nanometres (`i64`),
//! every angle an integer number of micro-degrees. Nanometres make both metric
//! (0.001 mm = 1000 nm) and inch (0.0001 in = 2540 nm) increments exact. The X axis is
//! held as a *radius* internally; diameter values exist only at the program and
//! display boundary.

/// Nanometres per millimetre.
pub const NM_PER_MM: i64 = 1_000_000;
/// Nanometres per inch (exact).
pub const NM_PER_INCH: i64 = 25_400_000;
/// Micro-degrees per degree.
pub const UDEG_PER_DEG: i64 = 1_000_000;

/// `v as f32`, the same value, by the FPU's 32-bit conversion when `v` fits an
/// `i32` (the `i64` conversion is a software routine on the Cortex-M4). For the
/// per-block geometry of the interpreter and the planner that works in f32.
#[inline]
pub fn f32_of(v: i64) -> f32 {
    match i32::try_from(v) {
        Ok(v) => v as f32,
        // Written so that the compiler cannot fold both arms into the i64 routine:
        // below 2^53 the f64 sum is exact and rounds once, as `v as f32` does.
        Err(_) if v.unsigned_abs() < 1 << 53 => ((v >> 32) as f64 * 4_294_967_296.0 + (v as u32) as f64) as f32,
        Err(_) => v as f32,
    }
}

/// `v as f64`, by the 64-bit conversion when `v` fits a `u64` (the usual case in
/// per-block geometry: squared lengths in nm²); the 128-bit routine otherwise.
#[inline]
pub fn f64_of_u128(v: u128) -> f64 {
    match u64::try_from(v) {
        Ok(x) => x as f64,
        Err(_) => wide_f64(v),
    }
}

/// `v as f64` out of line, so that the compiler keeps the 64-bit conversion of
/// [`f64_of_u128`] instead of folding both arms into the 128-bit routine.
#[cold]
#[inline(never)]
fn wide_f64(v: u128) -> f64 {
    v as f64
}

/// `v as f32` by the FPU's 32-bit conversions (the 64-bit one is a software
/// routine on the Cortex-M4): the high and low halves converted and summed, within
/// 2^-23 relative. For per-block geometry in f32, never for positions.
#[inline]
pub fn f32_of_u64(v: u64) -> f32 {
    ((v >> 32) as u32) as f32 * 4_294_967_296.0 + (v as u32) as f32
}

/// `round(√x)` exactly (never a tie: `(n + ½)²` is not an integer) and `√x` in
/// f32 (within 2^-22 relative), without soft-float arithmetic: the f32 reciprocal
/// root from the bit pattern, refined by Newton's method, seeds `f ≈ √x`; one
/// Newton step with the exact integer residue `x − f²` gives `⌊√x⌋` or one off, and
/// integer compares settle it and the rounding. The radii of arcs are such roots of
/// exact integer sums of squares (nm², below 2^64 for radii up to 4.29 m); on the
/// Cortex-M4 this is about a tenth of an f64 root.
pub fn sqrt_u64(x: u64) -> (u64, f32) {
    if x == 0 {
        return (0, 0.0);
    }
    let xf = f32_of_u64(x);
    let mut y = f32::from_bits(0x5f37_5a86 - (xf.to_bits() >> 1));
    for _ in 0..3 {
        y *= 1.5 - 0.5 * xf * y * y;
    }
    // `f` within 2^-21 relative of √x < 2^32 (about 2,000 at most), so x − f² is
    // below 2^44 in size: the wrapping difference is the true one.
    let root = xf * y;
    let f = (root as u32).max(1);
    let e = x.wrapping_sub(u64::from(f) * u64::from(f)) as i64;
    // The Newton step √x − f ≈ (x − f²)/2f: its error δ²/2f is below 2^-11 for
    // large roots and below ½ for small ones (δ < 1 there).
    let c = f32_of(e) * (0.5 * y);
    // ⌊c⌋ for c > −2^14 (a truncation of the shifted value); anything outside
    // is caught by the check below.
    let fc = i64::from((c + 16_384.0) as u32) - 16_384;
    // Squares of u32 roots fit a u64 (one multiply on the M4): `g` is ⌊√x⌋ when
    // g² ≤ x and x − g² ≤ 2g, i.e. x < (g + 1)².
    let sq = |g: u32| u64::from(g) * u64::from(g);
    let mut g = (i64::from(f) + fc).clamp(0, i64::from(u32::MAX)) as u32;
    if sq(g) > x {
        g -= 1;
    } else if x - sq(g) > 2 * u64::from(g) {
        g = g.saturating_add(1);
    }
    let rem = match x.checked_sub(sq(g)) {
        Some(r) if r <= 2 * u64::from(g) => r,
        _ => {
            // Not reached (the seed is never that far off); exact all the same.
            g = x.isqrt() as u32;
            x - sq(g)
        }
    };
    // √x rounds up when x ≥ (g + ½)², i.e. x − g² > g.
    (u64::from(g) + u64::from(rem > u64::from(g)), root)
}

/// A decimal number exactly as written in a program word: `mantissa × 10^-frac_digits`.
///
/// Keeping the decimal form (instead of a float) makes every conversion exact and
/// remembers whether the programmer wrote a decimal point, which decides how
/// least-increment input and words like `G04 P` are read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Number {
    /// Digits of the number with the decimal point removed, signed.
    pub mantissa: i64,
    /// How many of those digits follow the decimal point.
    pub frac_digits: u8,
    /// Whether a decimal point was written (`X10.` has one, `X10` has not).
    pub has_point: bool,
}

/// Most fraction digits a [`Number`] keeps (a value from a macro expression is
/// rounded to this many).
pub const MAX_FRAC_DIGITS: u8 = 9;

impl Number {
    /// An integer written without a decimal point.
    #[inline]
    pub const fn int(value: i64) -> Self {
        Number { mantissa: value, frac_digits: 0, has_point: false }
    }

    /// The exact integer value, if the number has no non-zero fraction.
    #[inline]
    pub fn as_integer(&self) -> Option<i64> {
        let p = pow10(self.frac_digits)?;
        if self.mantissa % p == 0 { Some(self.mantissa / p) } else { None }
    }

    /// The value multiplied by `10^shift`, rounded half away from zero.
    /// `None` if the result does not fit in an `i64`.
    #[inline]
    pub fn scaled(&self, shift: u8) -> Option<i64> {
        if shift >= self.frac_digits {
            mul_i64(self.mantissa, pow10(shift - self.frac_digits)?)
        } else {
            Some(div_round(self.mantissa, pow10(self.frac_digits - shift)?))
        }
    }

    /// The value as a float (for geometry and macro arithmetic only).
    #[inline]
    pub fn to_f64(&self) -> f64 {
        times_pow10(self.mantissa as f64, -i32::from(self.frac_digits))
    }

    /// The number nearest to `value` with [`MAX_FRAC_DIGITS`] fraction digits,
    /// marked as having a decimal point (macro values are real numbers).
    /// `None` for NaN, infinities and values beyond ±9.2e9.
    #[inline]
    pub fn from_f64(value: f64) -> Option<Self> {
        let m = libm::round(value * 1e9);
        if !m.is_finite() || m.abs() >= 9.2e18 {
            return None;
        }
        let mut n = Number { mantissa: m as i64, frac_digits: MAX_FRAC_DIGITS, has_point: true };
        while n.frac_digits > 0 && n.mantissa % 10 == 0 {
            n.mantissa /= 10;
            n.frac_digits -= 1;
        }
        Some(n)
    }

    /// True if the value is negative.
    #[inline]
    pub fn is_negative(&self) -> bool {
        self.mantissa < 0
    }
}

/// Powers of ten that fit an `i64`.
const POW10: [i64; 19] = {
    let mut t = [1i64; 19];
    let mut i = 1;
    while i < 19 {
        t[i] = t[i - 1] * 10;
        i += 1;
    }
    t
};

/// The powers of ten a `f64` holds exactly (`10^22` is the last).
const POW10_F64: [f64; 23] = {
    let mut t = [1.0f64; 23];
    let mut i = 1;
    while i < 23 {
        t[i] = t[i - 1] * 10.0;
        i += 1;
    }
    t
};

/// `x × 10^e`, multiplying or dividing by exact powers of ten (one rounding for
/// |e| ≤ 22, the range of every number a program can write with its fraction
/// digits). Instead of `libm::pow(10, e)`: the same values there (`pow` is exact
/// where the power is representable) without 1.2 KB of `pow` in the image.
pub fn times_pow10(mut x: f64, mut e: i32) -> f64 {
    while e > 22 {
        x *= 1e22;
        e -= 22;
    }
    while e < -22 {
        x /= 1e22;
        e += 22;
    }
    let p = POW10_F64[e.unsigned_abs() as usize];
    if e < 0 { x / p } else { x * p }
}

/// `10^n` as an `i64`, `None` above `10^18`.
#[inline]
pub const fn pow10(n: u8) -> Option<i64> {
    if n > 18 { None } else { Some(POW10[n as usize]) }
}

/// Integer division rounding half away from zero (`d > 0`).
#[inline]
pub const fn div_round(n: i64, d: i64) -> i64 {
    let q = n / d;
    let r = n - q * d;
    if 2 * r.abs() >= d { if n < 0 { q - 1 } else { q + 1 } } else { q }
}

/// Round `v` to the nearest multiple of `step` (half away from zero).
#[inline]
pub const fn round_to(v: i64, step: i64) -> i64 {
    div_round(v, step) * step
}

/// Inch or metric program input (G20/G21).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Units {
    /// G21: millimetres.
    Metric,
    /// G20: inches.
    Inch,
}

impl Units {
    /// Nanometres in one program unit (1 mm or 1 in).
    #[inline]
    pub const fn nm_per_unit(self) -> i64 {
        match self {
            Units::Metric => NM_PER_MM,
            Units::Inch => NM_PER_INCH,
        }
    }

    /// One program unit as a [`Scale`] of nanometres.
    #[inline]
    const fn scale(self) -> Scale {
        match self {
            Units::Metric => Scale { factor: 1, exp: 6 },
            Units::Inch => Scale { factor: 254, exp: 5 },
        }
    }
}

/// An internal-unit multiple `factor × 10^exp` (1 mm = 1·10⁶ nm, 1 in = 254·10⁵ nm),
/// so conversions multiply or divide by table powers of ten instead of dividing
/// 128-bit products (a library call costing ~2000 instructions on the Cortex-M4).
#[derive(Clone, Copy)]
struct Scale {
    factor: i64,
    exp: u8,
}

/// Micro-degrees in one degree.
const DEGREES: Scale = Scale { factor: 1, exp: 6 };

/// How a number without a decimal point is read (FANUC parameter DPI, No.3401#0).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum InputMode {
    /// Calculator-type input: `X60` is 60 mm, as every example of the manual is written.
    Calculator,
    /// Least-increment input: `X60` is 60 least increments (0.060 mm in IS-B metric).
    LeastIncrement,
}

/// Increment system: the least input increment of linear and angular words.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum IncrementSystem {
    /// IS-B: 0.001 mm, 0.0001 in, 0.001°.
    IsB,
    /// IS-C: 0.0001 mm, 0.00001 in, 0.0001°.
    IsC,
}

impl IncrementSystem {
    /// Fraction digits a value may have and still be a whole number of increments
    /// (IS-B metric: 3, i.e. 0.001 mm).
    #[inline]
    const fn linear_digits(self, units: Units) -> u8 {
        match (self, units) {
            (IncrementSystem::IsB, Units::Metric) => 3,
            (IncrementSystem::IsC, Units::Metric) | (IncrementSystem::IsB, Units::Inch) => 4,
            (IncrementSystem::IsC, Units::Inch) => 5,
        }
    }

    /// Least input increment of a linear word, in nanometres.
    #[inline]
    pub const fn linear_nm(self, units: Units) -> i64 {
        match (self, units) {
            (IncrementSystem::IsB, Units::Metric) => 1_000,
            (IncrementSystem::IsC, Units::Metric) => 100,
            (IncrementSystem::IsB, Units::Inch) => 2_540,
            (IncrementSystem::IsC, Units::Inch) => 254,
        }
    }

    /// Least input increment of an angle, in micro-degrees.
    #[inline]
    pub const fn angle_udeg(self) -> i64 {
        match self {
            IncrementSystem::IsB => 1_000,
            IncrementSystem::IsC => 100,
        }
    }
}

/// Everything needed to turn a program number into internal units.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NumberFormat {
    /// G20/G21 in force.
    pub units: Units,
    /// Calculator or least-increment input.
    pub input: InputMode,
    /// IS-B or IS-C.
    pub increments: IncrementSystem,
}

impl NumberFormat {
    /// A length word (`X Z U W I K R …`) in nanometres, rounded to the least input
    /// increment as the manual requires for macro values (2.24.1). `None` on overflow.
    #[inline]
    pub fn length_nm(&self, n: &Number) -> Option<i64> {
        let inc = self.increments.linear_nm(self.units);
        if !n.has_point && self.input == InputMode::LeastIncrement {
            return mul_i64(n.mantissa, inc);
        }
        let nm = scale_to(n, self.units.scale())?;
        // A value with no more fraction digits than the increment is already whole.
        Some(if n.frac_digits <= self.increments.linear_digits(self.units) { nm } else { round_to(nm, inc) })
    }

    /// An angle word (`C`, degrees) in micro-degrees, rounded to the least increment.
    #[inline]
    pub fn angle_udeg(&self, n: &Number) -> Option<i64> {
        let inc = self.increments.angle_udeg();
        let u = if n.has_point || self.input == InputMode::Calculator {
            scale_to(n, DEGREES)?
        } else {
            mul_i64(n.mantissa, inc)?
        };
        Some(round_to(u, inc))
    }

    /// A time in seconds written with X/U in `G04` (0.001 s least increment), in ms.
    #[inline]
    pub fn seconds_ms(&self, n: &Number) -> Option<i64> {
        if n.has_point || self.input == InputMode::Calculator { n.scaled(3) } else { Some(n.mantissa) }
    }

    /// A feed value (`F`) in nanometres per minute or per revolution. F is always read
    /// as written (F500 = 500 mm/min, F0.15 = 0.15 mm/rev) in both input modes.
    #[inline]
    pub fn feed_nm(&self, n: &Number) -> Option<i64> {
        scale_to(n, self.units.scale())
    }
}

/// `n × scale`, rounded half away from zero; `None` on overflow.
#[inline]
fn scale_to(n: &Number, s: Scale) -> Option<i64> {
    let m = mul_i64(n.mantissa, s.factor)?;
    if n.frac_digits <= s.exp {
        mul_i64(m, POW10[usize::from(s.exp - n.frac_digits)])
    } else {
        Some(div_round(m, pow10(n.frac_digits - s.exp)?))
    }
}

/// `a.checked_mul(b)`, by one 32 × 32 → 64-bit multiply when both fit an `i32`
/// (program numbers mostly do): the checked 64-bit product is ~25 instructions on
/// the Cortex-M4.
#[inline]
fn mul_i64(a: i64, b: i64) -> Option<i64> {
    match (i32::try_from(a), i32::try_from(b)) {
        (Ok(x), Ok(y)) => Some(i64::from(x) * i64::from(y)),
        _ => a.checked_mul(b),
    }
}

/// Internal nanometres to millimetres, for presentation only.
pub fn nm_to_mm(nm: i64) -> f64 {
    nm as f64 / NM_PER_MM as f64
}

#[cfg(test)]
mod tests {
    /// `to_f64` divides by an exact power of ten: the same bits as dividing by
    /// `libm::pow(10, k)` for every fraction length a number can have.
    #[test]
    fn to_f64_as_pow() {
        let mut m: i64 = 0x2545_f491_4f6c_dd1d;
        for _ in 0..200_000 {
            m ^= m << 13;
            m ^= ((m as u64) >> 7) as i64;
            m ^= m << 17;
            for f in 0..=22u8 {
                let n = super::Number { mantissa: m >> (f % 40), frac_digits: f, has_point: true };
                let old = n.mantissa as f64 / libm::pow(10.0, f64::from(f));
                assert_eq!(n.to_f64().to_bits(), old.to_bits(), "{n:?}");
            }
        }
        // A decimal `m × 10^k` (SINUMERIK's `EX` exponent computes it so) comes out
        // as exactly that decimal whenever it has at most nine fraction digits and
        // fits 2^50 units of 10^-9 (`from_f64` rounds `v × 1e9`, a second
        // rounding): one rounding here, no error a `Number` can show.
        let mut m: u64 = 0x9e37_79b9_7f4a_7c15;
        for _ in 0..200_000 {
            m ^= m << 13;
            m ^= m >> 7;
            m ^= m << 17;
            let k = (m % 41) as i32 - 20;
            let mant = (((m >> 8) % 1_000_000_000_000_000) >> (m % 50)) as i64;
            let exact = match i128::from(mant).checked_mul(10i128.pow((k + 9).max(0) as u32)) {
                Some(x) if k >= -9 && x < 1i128 << 50 => x,
                _ => continue,
            };
            let n = super::Number::from_f64(super::times_pow10(mant as f64, k)).unwrap();
            assert_eq!(n.scaled(9), Some(exact as i64), "{mant}e{k}");
        }
        assert_eq!(super::times_pow10(1.5, 3), 1500.0);
        assert_eq!(super::times_pow10(1.0, 30), 1e30);
        assert_eq!(super::times_pow10(25.0, -1), 2.5);
        assert_eq!(super::times_pow10(5.0, 24 - 16), 5e8);
    }

    use super::*;
    use crate::xorshift::XorShift;

    #[test]
    fn f64_of_u128_equals_the_u128_conversion() {
        for v in [0u128, 1, u128::from(u64::MAX), u128::from(u64::MAX) + 1, 1 << 100, u128::MAX] {
            assert_eq!(f64_of_u128(v).to_bits(), (v as f64).to_bits(), "{v}");
        }
    }

    #[test]
    fn f32_of_equals_the_i64_conversion() {
        let mut rng = XorShift::new(0x2545_f491_4f6c_dd1d);
        for i in 0..100_000 {
            let seed = rng.next_u64();
            let v = (seed as i64) >> (i % 64);
            assert_eq!(f32_of(v).to_bits(), (v as f32).to_bits(), "{v}");
        }
        for v in [0, 1, -1, i64::from(i32::MAX) + 1, (1 << 53) - 1, 1 << 53, -(1 << 53) - 3, i64::MIN, i64::MAX] {
            assert_eq!(f32_of(v).to_bits(), (v as f32).to_bits(), "{v}");
        }
    }

    fn num(m: i64, f: u8, p: bool) -> Number {
        Number { mantissa: m, frac_digits: f, has_point: p }
    }

    const METRIC_CALC: NumberFormat =
        NumberFormat { units: Units::Metric, input: InputMode::Calculator, increments: IncrementSystem::IsB };

    #[test]
    fn calculator_input_reads_integers_as_millimetres() {
        assert_eq!(METRIC_CALC.length_nm(&num(60, 0, false)), Some(60_000_000));
        assert_eq!(METRIC_CALC.length_nm(&num(60, 0, true)), Some(60_000_000));
        assert_eq!(METRIC_CALC.length_nm(&num(-1235, 3, true)), Some(-1_235_000));
    }

    #[test]
    fn least_increment_input_reads_integers_as_increments() {
        let f = NumberFormat { input: InputMode::LeastIncrement, ..METRIC_CALC };
        assert_eq!(f.length_nm(&num(60, 0, false)), Some(60_000));
        assert_eq!(f.length_nm(&num(60, 0, true)), Some(60_000_000));
        let inch = NumberFormat { units: Units::Inch, ..f };
        assert_eq!(inch.length_nm(&num(1, 0, false)), Some(2_540));
    }

    #[test]
    fn values_round_to_the_least_increment() {
        // 2.24.1: #1=1.23456, least increment 0.001 -> X#1 positions to 1.235.
        assert_eq!(METRIC_CALC.length_nm(&num(123456, 5, true)), Some(1_235_000));
        assert_eq!(METRIC_CALC.length_nm(&num(-123456, 5, true)), Some(-1_235_000));
        let inch = NumberFormat { units: Units::Inch, ..METRIC_CALC };
        assert_eq!(inch.length_nm(&num(1, 0, true)), Some(25_400_000));
        assert_eq!(inch.length_nm(&num(12345, 4, true)), Some(31_356_300));
    }

    #[test]
    fn scaling_matches_exact_rational_arithmetic() {
        // Reference: i128 product and rounded division.
        let exact = |m: i64, f: u8, per: i128| {
            let v = i128::from(m) * per;
            let d = 10i128.pow(u32::from(f));
            let q = v / d;
            let r = v % d;
            i64::try_from(if 2 * r.abs() >= d { q + v.signum() } else { q }).ok()
        };
        for m in [0, 1, -1, 5, -5, 15, 123_456_789, -987_654_321, 999_999_999_999_999] {
            for f in 0..=9u8 {
                let n = num(m, f, true);
                assert_eq!(scale_to(&n, Units::Metric.scale()), exact(m, f, 1_000_000), "{m}e-{f} mm");
                assert_eq!(scale_to(&n, Units::Inch.scale()), exact(m, f, 25_400_000), "{m}e-{f} in");
            }
        }
        assert_eq!(scale_to(&num(999_999_999_999_999_999, 0, true), Units::Metric.scale()), None);
    }

    #[test]
    fn number_helpers() {
        assert_eq!(num(2500, 3, true).as_integer(), None);
        assert_eq!(num(2000, 3, true).as_integer(), Some(2));
        assert_eq!(num(25, 1, true).scaled(0), Some(3));
        assert_eq!(num(-25, 1, true).scaled(0), Some(-3));
        assert_eq!(Number::from_f64(1.5), Some(num(15, 1, true)));
        assert_eq!(Number::from_f64(f64::NAN), None);
        assert_eq!(div_round(-7, 2), -4);
        assert_eq!(round_to(1_234_567, 1000), 1_235_000);
    }

    /// The integer root against the exact one and the f32 root against f64 over
    /// random squares of every size up to 2^64, the edges included.
    #[test]
    fn sqrt_u64_rounds_exactly() {
        let mut rng = XorShift::new(0x2545_f491_4f6c_dd1d);
        let mut next = || rng.next_u64();
        let check = |x: u64| {
            let (n, r) = sqrt_u64(x);
            let lo = |k: u64| (2 * u128::from(k)).saturating_sub(1).pow(2);
            // (n − ½)² ≤ x < (n + ½)², times four.
            assert!(n == 0 || lo(n) <= 4 * u128::from(x), "{x}: {n}");
            assert!(4 * u128::from(x) < (2 * u128::from(n) + 1).pow(2), "{x}: {n}");
            let exact = (x as f64).sqrt();
            assert!((f64::from(r) - exact).abs() <= exact * 2.4e-7, "{x}: {r} vs {exact}");
        };
        for _ in 0..200_000 {
            let v = next();
            check(v >> (v % 64));
            let k = v >> 32;
            check(k * k);
            check((k * k).saturating_sub(1));
            check(k * k + k);
            check(k * k + k + 1);
        }
        for x in [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, u64::MAX, u64::MAX - 1, 1 << 63, (1 << 32) - 1, 1 << 32] {
            check(x);
        }
        assert_eq!(sqrt_u64(0), (0, 0.0));
        assert_eq!(sqrt_u64(25).0, 5);
        assert_eq!(sqrt_u64(2).0, 1);
        assert_eq!(sqrt_u64(8).0, 3);
        assert_eq!(sqrt_u64(u64::MAX).0, 1 << 32);
    }

    #[test]
    fn f32_of_u64_is_close() {
        for v in [0, 1, 12_345, u64::from(u32::MAX), 1 << 40, u64::MAX, 0x1234_5678_9abc_def0] {
            let f = f32_of_u64(v);
            assert!((f64::from(f) - v as f64).abs() <= v as f64 * 1.2e-7, "{v}");
        }
    }
}

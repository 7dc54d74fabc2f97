//! Cosine and sine of a binary angle by CORDIC: shifts, adds and a 30-entry table,
//! so arcs are interpolated without floating point or division in the tick.

/// `atan(2^-i)` in turns × 2^32, i = 0..30.
const ATAN: [i32; 30] = [
    536_870_912,
    316_933_406,
    167_458_907,
    85_004_756,
    42_667_331,
    21_354_465,
    10_679_838,
    5_340_245,
    2_670_163,
    1_335_087,
    667_544,
    333_772,
    166_886,
    83_443,
    41_722,
    20_861,
    10_430,
    5_215,
    2_608,
    1_304,
    652,
    326,
    163,
    81,
    41,
    20,
    10,
    5,
    3,
    1,
];

/// The CORDIC gain's reciprocal (0.6072529350…) in Q30: the start vector's length
/// so the result has length 1.
const INV_GAIN_Q30: i32 = 652_032_874;

/// Fraction bits of the results.
pub const TRIG_FRAC: u32 = 30;

/// `(cos, sin)` of `angle` (a full turn is 2^32), each in Q30, within about 2^-25.
pub fn cos_sin(angle: u32) -> (i32, i32) {
    let quadrant = angle >> 30;
    // The angle within its quadrant, [0°, 90°): CORDIC converges up to ~99.9°.
    let mut z = (angle & 0x3FFF_FFFF) as i32;
    let (mut x, mut y) = (INV_GAIN_Q30, 0i32);
    for (i, &a) in ATAN.iter().enumerate() {
        let (dx, dy) = (y >> i, x >> i);
        if z >= 0 {
            x -= dx;
            y += dy;
            z -= a;
        } else {
            x += dx;
            y -= dy;
            z += a;
        }
    }
    match quadrant {
        0 => (x, y),
        1 => (-y, x),
        2 => (-x, -y),
        _ => (y, -x),
    }
}

/// CORDIC steps of [`angle`] before the rest is taken by a series: after them the
/// vector is within `atan(2^-5)` (< 2^-5 rad) of the x axis.
const ANGLE_STEPS: usize = 6;

/// Turns × 2^32 per radian, `2^32 / 2π`.
const UNITS_PER_RAD: f32 = 683_565_275.6;

/// The angle of the vector `(x, y)` in turns × 2^32 (`atan2` as a binary angle).
/// The vector is first scaled so its larger component has 29 bits; CORDIC
/// vectoring (shifts, adds and the table) then turns it towards the x axis in
/// [`ANGLE_STEPS`] steps (30 before: 16 units), and the remaining angle `φ`
/// (|φ| < 2^-5 rad) is `atan(y/x) = t − t³/3 + t⁵/5` (− t⁷/7 < 2^-37 rad, left out)
/// in f32, whose rounding is a few units of 2^-32 turn at that size. The result is
/// within 8 units of the exact angle (6 in the test's 20,000 vectors: 9e-9 rad,
/// 0.9 nm at R100). `(0, 0)` gives 0.
pub fn angle(x: i64, y: i64) -> u32 {
    let m = x.unsigned_abs().max(y.unsigned_abs());
    if m == 0 {
        return 0;
    }
    let bits = 64 - m.leading_zeros();
    let (x, y) = if bits > 29 {
        let k = bits - 29;
        ((x >> k) as i32, (y >> k) as i32)
    } else {
        let k = 29 - bits;
        ((x << k) as i32, (y << k) as i32)
    };
    // Into the right half plane (CORDIC converges up to ~99.9°).
    let (mut x, mut y, base) = if x < 0 { (-x, -y, 1u32 << 31) } else { (x, y, 0) };
    let mut z = 0i32;
    for (i, &a) in ATAN.iter().take(ANGLE_STEPS).enumerate() {
        let (dx, dy) = (y >> i, x >> i);
        if y > 0 {
            x += dx;
            y -= dy;
            z += a;
        } else {
            x -= dx;
            y += dy;
            z -= a;
        }
    }
    // x only grew (each step adds |y| >> i to it): x ≥ 2^28 > 0.
    base.wrapping_add(z.wrapping_add(small_atan(y, x)) as u32)
}

/// `atan(y/x)` in turns × 2^32, rounded, for `|y/x| < 2^-5` and `x > 0`, in f32.
fn small_atan(y: i32, x: i32) -> i32 {
    let t = y as f32 / x as f32;
    let t2 = t * t;
    let u = (t - t * t2 * (1.0 / 3.0 - t2 * (1.0 / 5.0))) * UNITS_PER_RAD;
    // Rounded half away from zero (`as` truncates; it saturates, never panics).
    (u + if u < 0.0 { -0.5 } else { 0.5 }) as i32
}

#[cfg(test)]
mod tests {
    use super::*;
    use canon::xorshift::XorShift;

    #[test]
    fn angle_matches_atan2() {
        let mut rng = XorShift::new(0x9e37_79b9_7f4a_7c15);
        let mut next = |m: u64| rng.signed(m as i64);
        let mut worst = 0i64;
        for i in 0..20_000 {
            let m = [1_000, 1_000_000, 100_000_000, 2_000_000_000_000][i % 4];
            let (x, y) = (next(m), next(m));
            if (x, y) == (0, 0) {
                continue;
            }
            let want = libm::atan2(y as f64, x as f64) / core::f64::consts::TAU * 4_294_967_296.0;
            let got = f64::from(angle(x, y) as i32);
            let mut d = (got - want) as i64;
            if d.abs() > 1 << 31 {
                d -= d.signum() << 32;
            }
            worst = worst.max(d.abs());
        }
        assert!(worst <= 8, "worst {worst} units of 2^-32 turn");
        for ((x, y), want) in [((1, 0), 0u32), ((0, 5), 1 << 30), ((-7, 0), 1 << 31), ((0, -3), 3 << 30)] {
            let d = angle(x, y).wrapping_sub(want) as i32;
            assert!(d.abs() <= 4, "({x}, {y}): {d}");
        }
    }

    #[test]
    fn matches_the_float_functions_around_the_circle() {
        let one = f64::from(1u32 << TRIG_FRAC);
        let mut worst = 0.0f64;
        for k in 0..4096u32 {
            let angle = k.wrapping_mul(1_048_573).wrapping_add(k * 7);
            let rad = f64::from(angle) / 4_294_967_296.0 * core::f64::consts::TAU;
            let (c, s) = cos_sin(angle);
            worst = worst.max((f64::from(c) / one - libm::cos(rad)).abs());
            worst = worst.max((f64::from(s) / one - libm::sin(rad)).abs());
        }
        assert!(worst < 3e-8, "worst error {worst}");
    }
}

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

#[cfg(test)]
mod tests {
    use super::*;

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

//! Presentation units: the interpreter's nanometres, micro-degrees and X radii as
//! the millimetres, degrees and X diameters users read.
//!
//! An integer divided by a power of ten is correctly rounded in `f64`, and the
//! shortest representation that reads back as the same float is then the exact
//! decimal, so values print as `60.0` or `0.15`, never with float noise. Values are
//! exact to the nanometre up to about 9 × 10⁹ mm.

/// Nanometres (or nm/min, nm/rev) to millimetres (mm/min, mm/rev).
pub fn mm(nm: i64) -> f64 {
    nm as f64 / 1e6
}

/// An X radius in nanometres as a diameter in millimetres.
pub fn dia(radius_nm: i64) -> f64 {
    radius_nm as f64 / 5e5
}

/// Micro-degrees (or µdeg/min) to degrees (deg/min).
pub fn deg(udeg: i64) -> f64 {
    udeg as f64 / 1e6
}

/// A surface speed in mm/min as m/min.
pub fn m_per_min(mm_per_min: u32) -> f64 {
    f64::from(mm_per_min) / 1e3
}

/// A length for display with three decimals (0.001 mm), as in the control's position display.
pub fn fixed3(mm: f64) -> String {
    format!("{mm:.3}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conversions_print_without_float_noise() {
        assert_eq!(mm(60_000_000).to_string(), "60");
        assert_eq!(mm(150_000).to_string(), "0.15");
        assert_eq!(dia(25_000_000), 50.0);
        assert_eq!(dia(1).to_string(), "0.000002");
        assert_eq!(dia(43_978_535).to_string(), "87.95707");
        assert_eq!(deg(-90_000_000), -90.0);
        assert_eq!(m_per_min(300_000), 300.0);
        assert_eq!(fixed3(-30.0), "-30.000");
    }
}

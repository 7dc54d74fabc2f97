//! Number formatting for the wire: millimetres with 3 decimals from integer
//! nanometres (no floating point for positions), X as a diameter.

use core::fmt;

use interp_core::MachineConfig;
use interp_core::axis::{Axis, Pos};

/// A length in nm shown in mm with 3 decimals (rounded to the micrometre).
#[derive(Clone, Copy, Debug)]
pub struct Mm(pub i64);

impl fmt::Display for Mm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // Rounded half away from zero, in i64 (no overflow: |nm / 1000| + 1 fits);
        // u64 digits, not u128 (whose formatting and division cost 2 KB of flash).
        let (whole, rest) = (self.0 / 1000, self.0 % 1000);
        let um = whole + i64::from(rest >= 500) - i64::from(rest <= -500);
        let sign = if um < 0 { "-" } else { "" };
        let um = um.unsigned_abs();
        write!(f, "{sign}{}.{:03}", um / 1000, um % 1000)
    }
}

/// A position as the wire shows it: `x,y,z`, always three axes as grbl senders
/// expect (X a diameter on a diameter machine; Y 0 on a lathe without one, the
/// real Y on a mill).
#[derive(Clone, Copy, Debug)]
pub struct Xyz {
    /// X, nm, radius.
    pub x: i64,
    /// Y, nm.
    pub y: i64,
    /// Z, nm.
    pub z: i64,
    /// Show X doubled.
    pub diameter: bool,
}

impl Xyz {
    /// `pos` for machine `cfg`.
    pub fn of(pos: &Pos, cfg: &MachineConfig) -> Self {
        Xyz { x: pos[Axis::X], y: pos[Axis::Y], z: pos[Axis::Z], diameter: cfg.diameter_x }
    }
}

impl fmt::Display for Xyz {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = if self.diameter { self.x.saturating_mul(2) } else { self.x };
        write!(f, "{},{},{}", Mm(x), Mm(self.y), Mm(self.z))
    }
}

/// A setting or parameter value: up to 4 decimals, trailing zeros dropped
/// (`400`, `0.01`, `640.5`).
#[derive(Clone, Copy, Debug)]
pub struct Value(pub f64);

impl fmt::Display for Value {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let scaled = libm::round(self.0 * 10_000.0);
        if !scaled.is_finite() || scaled.abs() > 9.0e18 {
            return write!(f, "0");
        }
        let v = scaled as i64;
        let sign = if v < 0 { "-" } else { "" };
        let (int, mut frac) = (v.unsigned_abs() / 10_000, v.unsigned_abs() % 10_000);
        write!(f, "{sign}{int}")?;
        if frac == 0 {
            return Ok(());
        }
        let mut digits = 4;
        while frac % 10 == 0 {
            frac /= 10;
            digits -= 1;
        }
        write!(f, ".{frac:0digits$}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::format;

    #[test]
    fn lengths_and_values_print_exactly() {
        assert_eq!(format!("{}", Mm(12_345_678)), "12.346");
        assert_eq!(format!("{}", Mm(-1_499)), "-0.001");
        assert_eq!(format!("{}", Mm(-400)), "0.000");
        assert_eq!(format!("{}", Mm(500)), "0.001");
        assert_eq!(format!("{}", Mm(-500)), "-0.001");
        assert_eq!(format!("{}", Mm(-499)), "0.000");
        assert_eq!(format!("{}", Mm(i64::MAX)), "9223372036854.776");
        assert_eq!(format!("{}", Mm(i64::MIN)), "-9223372036854.776");
        assert_eq!(format!("{}", Xyz { x: 10_000_000, y: 0, z: -5_000_000, diameter: true }), "20.000,0.000,-5.000");
        assert_eq!(format!("{}", Xyz { x: -1_000, y: 25_400_000, z: -3, diameter: false }), "-0.001,25.400,0.000");
        assert_eq!(format!("{}", Value(640.5)), "640.5");
        assert_eq!(format!("{}", Value(0.01)), "0.01");
        assert_eq!(format!("{}", Value(400.0)), "400");
    }
}

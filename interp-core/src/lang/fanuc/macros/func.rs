//! The functions of 2.24.2 on `f64` (libm, so the board computes the same bits as
//! the host). Angles are degrees. Domain errors are alarms, never NaN. The ones
//! the SINUMERIK language shares are in [`crate::geom::deg`]; here are FANUC's
//! own: ATAN[j]/[k] (−90..90°), ROUND in a statement, FUP.

use crate::alarm::AlarmKind;
pub(crate) use crate::geom::deg::{acos_deg, asin_deg, atan_deg, cos_deg, exp, fix, modulo, sin_deg, sqrt, tan_deg};
use crate::geom::deg::{degrees, positive_zero};

/// A function of the macro language.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Func {
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Sqrt,
    Abs,
    Round,
    Fix,
    Fup,
    Exp,
    Max,
    Min,
}

impl Func {
    /// The name used in alarm messages.
    pub(crate) const fn name(self) -> &'static str {
        match self {
            Func::Sin => "SIN",
            Func::Cos => "COS",
            Func::Tan => "TAN",
            Func::Asin => "ASIN",
            Func::Acos => "ACOS",
            Func::Atan => "ATAN",
            Func::Sqrt => "SQRT",
            Func::Abs => "ABS",
            Func::Round => "ROUND",
            Func::Fix => "FIX",
            Func::Fup => "FUP",
            Func::Exp => "EXP",
            Func::Max => "MAX",
            Func::Min => "MIN",
        }
    }
}

/// `ATAN[j]/[k]`: the angle whose tangent is j/k, -90..90 degrees, as the manual's
/// example demands (ATAN[-1]/[-1] = 45°, 2.24.2 (6)); k = 0 gives ±90°, j = k = 0
/// alarm 0119.
pub(crate) fn atan2_deg(j: f64, k: f64) -> Result<f64, AlarmKind> {
    if k == 0.0 {
        return if j == 0.0 {
            Err(AlarmKind::ArgumentOutOfRange { function: "ATAN" })
        } else {
            Ok(90.0_f64.copysign(j))
        };
    }
    Ok(degrees(libm::atan(j / k)))
}

/// ROUND in a macro statement: rounds at the first decimal place, half away from
/// zero (2.24.2 (7): ROUND[1.2345] = 1).
pub(crate) fn round_macro(x: f64) -> f64 {
    positive_zero(libm::round(x))
}

/// FUP: raises the fraction to the next whole number away from zero:
/// FUP[1.2] = 2, FUP[-1.2] = -2.
pub(crate) fn fup(x: f64) -> f64 {
    positive_zero(if x < 0.0 { libm::floor(x) } else { libm::ceil(x) })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fanuc_atan_rounding_and_fup() {
        assert_eq!(atan2_deg(-1.0, -1.0), Ok(45.0), "the manual's example");
        assert_eq!(atan2_deg(1.0, -1.0), Ok(-45.0));
        assert_eq!(atan2_deg(1.0, 0.0), Ok(90.0));
        assert_eq!(atan2_deg(-2.0, 0.0), Ok(-90.0));
        assert_eq!(atan2_deg(0.0, 0.0), Err(AlarmKind::ArgumentOutOfRange { function: "ATAN" }));
        assert_eq!(round_macro(1.2345), 1.0);
        assert_eq!(round_macro(2.5), 3.0);
        assert_eq!(round_macro(-2.5), -3.0);
        assert!(round_macro(-0.4).is_sign_positive());
        assert_eq!((fup(1.2), fup(-1.2), fup(3.0), fup(-3.0)), (2.0, -2.0, 3.0, -3.0));
    }
}

//! A pattern's or a pocket's own axes in the plane: its reference point and the
//! angle its length makes with the abscissa (STA1, `_STA`), counterclockwise.
//! Points are laid out in these axes (along, across) and turned into the plane's.

/// Axes in the plane turned by an angle about a reference point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rot {
    /// Reference point (abscissa, ordinate), nm.
    pub at: (i64, i64),
    /// Cosine and sine of the angle.
    pub cs: (f64, f64),
}

impl Rot {
    /// Axes at `at` turned by `deg` degrees.
    pub fn new(at: (i64, i64), deg: f64) -> Self {
        let (s, c) = libm::sincos(deg.to_radians());
        Rot { at, cs: (c, s) }
    }

    /// The plane point `along` nm along the turned abscissa and `across` nm along
    /// the turned ordinate from the reference point, rounded to the nm.
    pub fn point(&self, along: f64, across: f64) -> (i64, i64) {
        let (c, s) = self.cs;
        (self.at.0 + round(along * c - across * s), self.at.1 + round(along * s + across * c))
    }
}

/// `v` nm rounded to the nearest nm (halves away from zero), saturating.
pub fn round(v: f64) -> i64 {
    libm::round(v) as i64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn turned_axes() {
        let r = Rot::new((10_000_000, 20_000_000), 90.0);
        assert_eq!(r.point(5_000_000.0, 0.0), (10_000_000, 25_000_000));
        assert_eq!(r.point(0.0, 5_000_000.0), (5_000_000, 20_000_000));
        let r = Rot::new((0, 0), 30.0);
        let (a, o) = r.point(10_000_000.0, 0.0);
        assert_eq!((a, o), (8_660_254, 5_000_000));
    }
}

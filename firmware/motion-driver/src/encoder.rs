//! The spindle encoder count: TIM5 counts quadrature edges in 32 bits and wraps; the
//! motion core wants a signed count since power-on. [`Encoder`] widens each reading
//! by the signed difference to the previous one (correct while fewer than 2^31 counts
//! pass between two readings: hours at any spindle speed), and places an index
//! capture (a raw count latched by the index interrupt) on the same scale.

/// Widens 32-bit hardware counts to the motion core's 64-bit count.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Encoder {
    raw: u32,
    count: i64,
}

impl Encoder {
    /// An encoder whose current raw reading `raw` is count 0.
    pub const fn new(raw: u32) -> Self {
        Encoder { raw, count: 0 }
    }

    /// The same encoder with its widened count set to `count`.
    pub const fn with_count(self, count: i64) -> Self {
        Encoder { raw: self.raw, count }
    }

    /// Takes a raw reading; returns the widened count.
    #[inline]
    pub fn update(&mut self, raw: u32) -> i64 {
        self.count += i64::from(raw.wrapping_sub(self.raw) as i32);
        self.raw = raw;
        self.count
    }

    /// The last widened count.
    pub const fn count(&self) -> i64 {
        self.count
    }

    /// A raw count latched recently (e.g. at the index) on the widened scale.
    #[inline]
    pub fn widen(&self, latched: u32) -> i64 {
        self.count - i64::from(self.raw.wrapping_sub(latched) as i32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_through_the_wrap_both_ways() {
        let mut e = Encoder::new(u32::MAX - 2);
        assert_eq!(e.update(u32::MAX), 2);
        assert_eq!(e.update(5), 8);
        assert_eq!(e.widen(1), 4);
        assert_eq!(e.widen(u32::MAX - 9), -7);
        assert_eq!(e.update(u32::MAX - 100), -98);
        assert_eq!(e.count(), -98);
    }
}

//! How the milling cycles divide a depth (MID, `_MID`) or a width (`_MIDA`) into
//! infeeds (seed 001 lines 3864-3876, 4889-4897, 4954-4960): "the depth is cut in
//! equal infeeds; from MID and the total depth the cycle computes infeeds between
//! 0.5 × MID and MID, the smallest possible number of them; MID = 0 is one infeed
//! to the final depth." The width in the plane is divided the same way, at most
//! `_MIDA` (80 % of the cutter diameter when `_MIDA` is 0, line 4960).
//!
//! Where the depth infeeds start is the cycle's: the reference plane advanced by
//! the safety distance (RFP + SDIS), or RFP itself with `_ZSD[1]` = 1 (lines
//! 3522-3536).

/// The number of equal parts of at most `max` that `total` divides into: the
/// smallest such number; one when `max` ≤ 0 (MID = 0) or `total` is 0.
pub fn parts(total: i64, max: i64) -> u32 {
    let total = total.unsigned_abs();
    let max = max.unsigned_abs();
    if max == 0 || total == 0 {
        return 1;
    }
    u32::try_from(total.div_ceil(max)).unwrap_or(u32::MAX)
}

/// The levels of a division of `from` → `to` into equal infeeds: level `k` of
/// `1..=count()` is `from + k·(to − from)/count()`, the last exactly `to`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Levels {
    /// Where the first infeed starts (RFP + SDIS, or RFP).
    pub from: i64,
    /// The final level (DP minus the floor allowance …).
    pub to: i64,
    /// Number of infeeds (≥ 1).
    pub count: u32,
}

impl Levels {
    /// `from` → `to` in the fewest equal infeeds of at most `max` (`max` ≤ 0: one).
    #[inline(never)]
    pub fn new(from: i64, to: i64, max: i64) -> Self {
        Levels { from, to, count: parts(to - from, max) }
    }

    /// Level `k` (1 = the first infeed, `count` = `to`); 0 is `from`.
    pub fn level(&self, k: u32) -> i64 {
        let k = k.min(self.count);
        // Rounded to the nearest nm, halves away from zero: the same level whichever
        // way the cycle cuts (exact in f64 for any depth below 9 m in 1000 infeeds).
        let span = (self.to - self.from) as f64 * f64::from(k) / f64::from(self.count.max(1));
        self.from + libm::round(span) as i64
    }
}

/// The largest width infeed in the plane: `_MIDA`, or 80 % of the cutter
/// diameter when it is 0 (line 4960). `radius` is the cutter's, nm.
pub fn max_width(mida: i64, radius: i64) -> i64 {
    if mida > 0 { mida } else { radius * 2 * 4 / 5 }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The document's rule: equal infeeds between MID/2 and MID, as few as can be.
    #[test]
    fn depth_is_divided_into_the_fewest_equal_infeeds() {
        // 23 mm at MID 6: four infeeds of 5.75 mm.
        let l = Levels::new(1_000_000, -22_000_000, 6_000_000);
        assert_eq!(l.count, 4);
        assert_eq!(
            (1..=4).map(|k| l.level(k)).collect::<std::vec::Vec<_>>(),
            [-4_750_000, -10_500_000, -16_250_000, -22_000_000]
        );
        for k in 1..=4 {
            let step = l.level(k - 1) - l.level(k);
            assert!((3_000_000..=6_000_000).contains(&step), "{step}");
        }
        // MID = 0: one infeed to the depth; exact multiples take no extra infeed.
        assert_eq!(Levels::new(0, -10_000_000, 0).count, 1);
        assert_eq!(Levels::new(0, -12_000_000, 4_000_000).count, 3);
        assert_eq!(Levels::new(0, -12_000_001, 4_000_000).count, 4);
        // Upwards (a depth above the reference plane) the same.
        assert_eq!(Levels::new(0, 9_000_000, 4_000_000).level(1), 3_000_000);
        assert_eq!(parts(0, 5), 1);
    }

    #[test]
    fn width_infeed_defaults_to_80_percent_of_the_diameter() {
        assert_eq!(max_width(0, 5_000_000), 8_000_000);
        assert_eq!(max_width(3_000_000, 5_000_000), 3_000_000);
    }
}

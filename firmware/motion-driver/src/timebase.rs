//! The step timer's time base: nanoseconds (the motion core's time) to timer ticks
//! and back by one multiply and a shift each, with factors computed once at start-up,
//! so nothing in an interrupt divides.

/// Why a time base cannot be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum TimeBaseError {
    /// Timer clock or interpolation period is zero.
    Zero,
    /// The interpolation period is not a whole number of timer ticks.
    PeriodNotWhole,
    /// The period is longer than 2^25 timer ticks (0.4 s at 84 MHz).
    PeriodTooLong,
}

/// Conversion between nanoseconds and ticks of a free-running 32-bit timer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct TimeBase {
    /// Timer ticks per second.
    pub timer_hz: u32,
    /// Interpolation period, ns.
    pub period_ns: u32,
    /// Interpolation period, ticks (exact).
    pub period_ticks: u32,
    /// Ticks per ns, Q32.
    ticks_per_ns_q32: u64,
    /// ns per tick, Q32.
    ns_per_tick_q32: u64,
}

impl TimeBase {
    /// A time base for a timer at `timer_hz` and an interpolation period of
    /// `period_ns` (the machine's `[motion] tick_ns`).
    pub fn new(timer_hz: u32, period_ns: u32) -> Result<Self, TimeBaseError> {
        if timer_hz == 0 || period_ns == 0 {
            return Err(TimeBaseError::Zero);
        }
        let product = u64::from(period_ns) * u64::from(timer_hz);
        if product % 1_000_000_000 != 0 {
            return Err(TimeBaseError::PeriodNotWhole);
        }
        let period_ticks = u32::try_from(product / 1_000_000_000).map_err(|_| TimeBaseError::PeriodTooLong)?;
        // Two periods must stay inside `ns`'s range (the encoder path converts up to one).
        if period_ticks > 1 << 25 {
            return Err(TimeBaseError::PeriodTooLong);
        }
        let ticks_per_ns_q32 = ((u128::from(timer_hz) << 32) + 500_000_000) / 1_000_000_000;
        let ns_per_tick_q32 = ((1_000_000_000u128 << 32) + u128::from(timer_hz / 2)) / u128::from(timer_hz);
        Ok(TimeBase {
            timer_hz,
            period_ns,
            period_ticks,
            ticks_per_ns_q32: ticks_per_ns_q32 as u64,
            ns_per_tick_q32: ns_per_tick_q32 as u64,
        })
    }

    /// Ticks in `ns` nanoseconds (rounded down; `ns` < 2^32).
    #[inline]
    pub fn ticks(&self, ns: u32) -> u32 {
        ((u64::from(ns) * self.ticks_per_ns_q32) >> 32) as u32
    }

    /// Nanoseconds in `ticks` timer ticks (rounded down). Meant for spans of a few
    /// periods: `ticks` is capped at 2^26 (0.8 s at 84 MHz) so the product fits 64 bits.
    #[inline]
    pub fn ns(&self, ticks: u32) -> u64 {
        (u64::from(ticks.min(1 << 26)) * self.ns_per_tick_q32) >> 32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_board_timer_at_84_mhz_and_one_millisecond() {
        let tb = TimeBase::new(84_000_000, 1_000_000).unwrap();
        assert_eq!(tb.period_ticks, 84_000);
        assert_eq!(tb.ticks(1_000_000), 84_000);
        assert_eq!(tb.ticks(2_500), 210);
        assert_eq!(tb.ticks(5_000), 420);
        assert_eq!(tb.ticks(11), 0);
        assert_eq!(tb.ticks(12), 1);
        assert_eq!(tb.ns(84_000), 1_000_000);
        assert_eq!(tb.ns(84), 1_000);
        // Round trip within a tick over two periods.
        for ns in (0..2_000_000).step_by(7_919) {
            let back = tb.ns(tb.ticks(ns));
            assert!(u64::from(ns) - back <= 12, "{ns} -> {back}");
        }
    }

    #[test]
    fn periods_that_are_not_whole_ticks_are_refused() {
        assert_eq!(TimeBase::new(84_000_000, 1_000_001), Err(TimeBaseError::PeriodNotWhole));
        assert_eq!(TimeBase::new(0, 1_000_000), Err(TimeBaseError::Zero));
        assert_eq!(TimeBase::new(84_000_000, 0), Err(TimeBaseError::Zero));
        assert_eq!(TimeBase::new(84_000_000, 4_000_000_000), Err(TimeBaseError::PeriodTooLong));
        assert_eq!(TimeBase::new(1_000_000, 250_000).unwrap().period_ticks, 250);
    }
}

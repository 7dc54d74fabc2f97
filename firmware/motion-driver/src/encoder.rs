//! The spindle encoder count: the encoder timer (TIM5 on the board: 32 bits; a
//! 16-bit timer works the same way) counts quadrature edges and wraps; the motion
//! core wants a signed count since power-on. [`Encoder`] widens each reading by the
//! signed difference to the previous one (correct while fewer than half the
//! counter's range pass between two readings: hours at any spindle speed in 32 bits,
//! 32,767 counts — 8 revolutions of 4096 — in 16; the period reads it every
//! millisecond), places an index capture (a raw count latched by the index
//! interrupt) on the same scale, and turns the counts at which the core next needs
//! the encoder ([`Due`]) into the timer's two compare values ([`Window`]).

use motion_core::sync::Due;

/// Widens raw counts of a `bits`-bit counter to the motion core's 64-bit count.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Encoder {
    raw: u32,
    count: i64,
    /// `32 − bits`: a raw difference shifted left by it is signed in 32 bits.
    shift: u32,
    /// The counter's values (`2^bits − 1`), and a quarter of its range: the
    /// farthest a compare value is set from the count.
    mask: u32,
    reach: u32,
}

impl Default for Encoder {
    fn default() -> Self {
        Encoder::new(0)
    }
}

/// The encoder timer's two compare values: an interrupt when the counter reaches
/// `up` counting up or `down` counting down (`None`: that compare's interrupt off).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Window {
    /// Compare value above the count (raw, in the counter's width).
    pub up: Option<u32>,
    /// Compare value below the count.
    pub down: Option<u32>,
}

impl Window {
    /// No compare interrupt.
    pub const OFF: Window = Window { up: None, down: None };
}

impl Encoder {
    /// A 32-bit counter whose current raw reading `raw` is count 0.
    pub const fn new(raw: u32) -> Self {
        Encoder::with_bits(raw, 32)
    }

    /// A `bits`-bit counter (16 to 32) whose current raw reading `raw` is count 0.
    pub const fn with_bits(raw: u32, bits: u32) -> Self {
        let bits = if bits < 16 {
            16
        } else if bits > 32 {
            32
        } else {
            bits
        };
        let shift = 32 - bits;
        let mask = u32::MAX >> shift;
        Encoder { raw: raw & mask, count: 0, shift, mask, reach: 1 << (bits - 2) }
    }

    /// The same encoder with its widened count set to `count`.
    pub const fn with_count(self, count: i64) -> Self {
        Encoder { count, ..self }
    }

    /// The same encoder with its count unchanged and `raw` as its last reading (the
    /// counter was set without counting).
    pub const fn with_raw(self, raw: u32) -> Self {
        Encoder { raw: raw & self.mask, ..self }
    }

    /// The signed number of counts from raw `from` to raw `to`.
    #[inline]
    fn diff(&self, from: u32, to: u32) -> i64 {
        i64::from((to.wrapping_sub(from) << self.shift) as i32 >> self.shift)
    }

    /// Takes a raw reading; returns the widened count.
    #[inline]
    pub fn update(&mut self, raw: u32) -> i64 {
        self.count += self.diff(self.raw, raw);
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
        self.count - self.diff(latched, self.raw)
    }

    /// The compare values for `due` (widened counts) around the last reading. A due
    /// count already reached gives the reading itself (see [`Encoder::reached`]);
    /// one further than a quarter of the counter's range gives a checkpoint a
    /// quarter away (its interrupt finds nothing due and sets the compare again),
    /// so a compare value is never ambiguous across the wrap.
    #[inline]
    pub fn window(&self, due: Due) -> Window {
        let reach = i64::from(self.reach);
        let ahead = |d: i64| d.clamp(0, reach) as u32;
        let up = due.up().map(|u| self.raw.wrapping_add(ahead(u - self.count)) & self.mask);
        let down = due.down().map(|d| self.raw.wrapping_sub(ahead(self.count - d)) & self.mask);
        Window { up, down }
    }

    /// Whether raw reading `raw` has reached either compare value of `w` (after the
    /// compares are set: a count that went past one before it was set would never
    /// match it).
    #[inline(always)]
    pub fn reached(&self, w: &Window, raw: u32) -> bool {
        w.up.is_some_and(|u| self.diff(u, raw) >= 0) || w.down.is_some_and(|d| self.diff(raw, d) >= 0)
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

    #[test]
    fn a_16_bit_counter_wraps_at_65536() {
        let mut e = Encoder::with_bits(65_530, 16);
        assert_eq!(e.update(3), 9);
        assert_eq!(e.widen(65_535), 5);
        assert_eq!(e.update(65_000), -530);
        assert_eq!(e.update(34_000), -31_530);
        // More than half the range between two readings is taken the other way.
        assert_eq!(e.update(1_000), -31_530 - 33_000 + 65_536);
    }

    #[test]
    fn compare_values_around_the_wrap() {
        // 32 bits: count 10 at raw u32::MAX − 1.
        let e = Encoder::new(u32::MAX - 11).with_count(0);
        let mut e = e;
        e.update(u32::MAX - 1);
        assert_eq!(e.count(), 10);
        let w = e.window(Due::new(Some(14), Some(7)));
        assert_eq!(w, Window { up: Some(2), down: Some(u32::MAX - 4) });
        assert!(!e.reached(&w, u32::MAX) && e.reached(&w, 2) && e.reached(&w, 9) && e.reached(&w, u32::MAX - 4));
        // Already reached: the reading itself, reached at once.
        let w = e.window(Due::new(Some(9), None));
        assert_eq!(w.up, Some(u32::MAX - 1));
        assert!(e.reached(&w, u32::MAX - 1));
        // 16 bits: the same around 65535, and a far count as a checkpoint.
        let mut e = Encoder::with_bits(65_530, 16);
        e.update(65_534);
        let w = e.window(Due::new(Some(8), Some(-100_000)));
        assert_eq!(w, Window { up: Some(2), down: Some(65_534 - 16_384) });
        assert!(e.reached(&w, 2) && !e.reached(&w, 65_535) && !e.reached(&w, 65_534 - 16_383));
        assert_eq!(e.window(Due::NONE), Window::OFF);
    }
}

//! A small deterministic random source (Marsaglia's xorshift64) for the crates'
//! randomised tests: every "the integer result equals the f64 one" test draws its
//! inputs from the same generator, seeded per test, so a failure repeats exactly.
//! Nothing on the machine uses it (the firmware's linker drops it).

/// The xorshift64 state (never 0).
#[derive(Clone, Debug)]
pub struct XorShift(u64);

impl XorShift {
    /// A generator from `seed` (0, which would stay 0, is taken as 1).
    pub const fn new(seed: u64) -> Self {
        Self(if seed == 0 { 1 } else { seed })
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        let mut s = self.0;
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        self.0 = s;
        s
    }

    /// A value in `-m..m` (`m` > 0).
    pub fn signed(&mut self, m: i64) -> i64 {
        (self.next_u64() % (2 * m.unsigned_abs())) as i64 - m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_values_are_xorshift64s() {
        let mut r = XorShift::new(1);
        assert_eq!(r.next_u64(), 0x4082_2041);
        assert_eq!(XorShift::new(0).next_u64(), 0x4082_2041);
        let mut r = XorShift::new(7);
        for _ in 0..1000 {
            assert!((-5..5).contains(&r.signed(5)));
        }
    }
}

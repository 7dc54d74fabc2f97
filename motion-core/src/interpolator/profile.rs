//! The speed profile, one interpolation period at a time: a discrete trapezoid
//! that accelerates towards the speed cap, cruises, and brakes just in time to
//! leave the block at its planned exit speed. Integers only (Q8 nm per period),
//! no division: the braking decision compares squares.

/// Distance needed to brake from `v` to `exit` at `a` per period, counting the
/// period about to be run at `v`, times `2a`: `v² − exit² + a·(v + exit)`.
/// (Braking by `a` per period from `v` covers `(v² − exit²)/2a − (v − exit)/2`.)
fn braking_2a(v: u64, exit: u64, a: u64) -> u64 {
    (v.saturating_mul(v) - exit * exit).saturating_add(a.saturating_mul(v + exit))
}

/// Whether running this period at `v` still lets the path reach a boundary `rem`
/// ahead at `exit` or slower (`v ≤ exit`, or the braking distance fits).
pub fn fits(v: u64, exit: u64, a: u64, rem: u64) -> bool {
    v <= exit || braking_2a(v, exit, a) <= (2 * a).saturating_mul(rem)
}

/// The speed (= distance, Q8 nm) for the next period.
///
/// `v` is the speed of the last period, `cap` the speed wanted now (feed × override,
/// 0 for a feed hold), `exit` the speed the block must end at or below, `a` the
/// acceleration per period and `rem` the distance left in the block. The result
/// differs from `v` by at most `a`; it is never above `max(cap, v − a)`.
pub fn next_speed(v: u64, cap: u64, exit: u64, a: u64, rem: u64) -> u64 {
    let a = a.max(1);
    let floor = v.saturating_sub(a);
    // Towards the cap, at most `a` per period either way.
    let wanted = if cap >= v { (v + a).min(cap) } else { floor.max(cap) };
    let mut next = if fits(wanted, exit, a, rem) {
        wanted
    } else if wanted > v && fits(v, exit, a, rem) {
        v
    } else {
        floor.min(wanted)
    };
    // Creep the last bit of a block that must end at rest (never above the cap:
    // with a slow feed the acceleration per period can exceed it).
    if next == 0 && cap > 0 && rem > 0 {
        next = rem.min(a).min(cap);
    }
    next
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Runs one block from `v0`; returns the speeds of every period and the final
    /// speed (leftover distance stays with the last period).
    fn run(len: u64, v0: u64, cap: u64, exit: u64, a: u64) -> (std::vec::Vec<u64>, u64) {
        let (mut s, mut v) = (0u64, v0);
        let mut speeds = std::vec::Vec::new();
        // At the cap all the way, plus braking and creeping: far fewer periods than this.
        let most = 2 * len / cap.max(1) + 4 * (v0 + cap) / a.max(1) + 1_000;
        while s < len {
            v = next_speed(v, cap, exit, a, len - s);
            speeds.push(v);
            s += v;
            assert!((speeds.len() as u64) < most, "does not finish");
        }
        (speeds, v)
    }

    #[test]
    fn trapezoid_from_rest_to_rest() {
        let (speeds, last) = run(1_000_000, 0, 1000, 0, 10);
        assert_eq!(speeds[..3], [10, 20, 30]);
        assert!(speeds.contains(&1000));
        assert!(last <= 10, "ends at rest: {last}");
        let total: u64 = speeds.iter().sum();
        assert_eq!(total, 1_000_000, "lands exactly on the end");
    }

    #[test]
    fn short_block_is_a_triangle() {
        let (speeds, last) = run(10_000, 0, 100_000, 0, 10);
        let top = *speeds.iter().max().unwrap();
        assert!((300..=330).contains(&top), "v² = a·L: {top}");
        assert!(last <= 10);
    }

    #[test]
    fn feed_hold_brakes_at_the_acceleration() {
        assert_eq!(next_speed(500, 0, 0, 10, u64::MAX), 490);
        assert_eq!(next_speed(5, 0, 0, 10, u64::MAX), 0);
        assert_eq!(next_speed(0, 0, 0, 10, 100), 0, "held: no creeping");
        // proptest's case: braked to rest short of the end, a > cap: creep at the cap.
        assert_eq!(next_speed(0, 183, 16, 194, 1_000), 183);
    }

    proptest! {
        #[test]
        fn limits_hold_for_any_block(
            len in 1u64..5_000_000,
            v0 in 0u64..5_000,
            cap in 1u64..5_000,
            exit in 0u64..5_000,
            a in 1u64..200,
        ) {
            let (speeds, last) = run(len, v0, cap, exit, a);
            let mut prev = v0;
            for &v in &speeds {
                prop_assert!(v.abs_diff(prev) <= a, "acceleration: {prev} -> {v}");
                prop_assert!(v <= cap.max(prev.saturating_sub(a)), "speed above cap");
                prev = v;
            }
            // The exit speed is honoured unless the block was entered too fast to brake.
            let reachable = v0 * v0 <= exit * exit + 2 * a * len;
            if reachable && v0 <= cap {
                prop_assert!(last <= exit.max(a) + a, "exit {last} > {exit}");
            }
        }
    }
}

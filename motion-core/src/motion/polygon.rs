//! Polygon turning (G51.2/G50.2, 2.8): the C axis as the tool spindle, locked to
//! the work spindle's encoder through a gearbox of its own while X and Z move as
//! usual.
//!
//! From the first index after the command the C axis is at `Q·S_rev/(P·CPR)` steps
//! per encoder count from where it stood (`S_rev` its steps per revolution): Q/P
//! tool-spindle turns per work-spindle turn (2.8 note 3). The interpreter has put C
//! on the phase angle R beforehand, so at every index C is R plus whole multiples of
//! `Q/P` turns. Each count adds `Q·S_rev` to a remainder and takes `P·CPR` off it
//! while it can, one C step each time (a rounding DDA, the remainder starting at
//! half): additions only, exact at every count, no division. A count backwards (the
//! spindle turned back) undoes one. G50.2 lets C run on to the next whole turn from
//! where it locked, then C stands and its step count is taken back by the whole
//! turns it made (a rotary axis: the same angle), so the planner's C and the
//! stepper's agree again.

use super::MotionCore;
use crate::alarm::AlarmKind;
use crate::axis::Axis;
use crate::canon::{PolygonSync, SpindleDir};
use crate::fixed::STEP_FRAC;
use crate::sync::Due;

/// The tool-spindle gearbox.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PolygonGear {
    /// `Q · steps per C revolution` and `P · counts per revolution`.
    num: i64,
    den: i64,
    /// C steps per revolution, spindle counts per revolution.
    rev: i64,
    cpr: i64,
    /// Forward count (sign of the spindle direction times the raw count) at which
    /// C locks (an index); `None` once locked.
    lock_at: Option<i64>,
    /// The raw count C locks (or locked) at.
    origin: i64,
    /// Encoder direction of forward rotation.
    sigma: i64,
    /// Last forward count taken.
    last: i64,
    /// DDA remainder, `[0, den)`.
    acc: i64,
    /// C steps since the lock, and the same within the current revolution.
    pos: i64,
    in_rev: i64,
    /// G50.2 given: stop at the next whole revolution.
    stopping: bool,
}

impl PolygonGear {
    /// A gearbox of `q/p` C turns per spindle turn, `rev` C steps per turn, `cpr`
    /// counts per spindle turn, locking at raw count `lock_raw` (an index) with the
    /// spindle turning in count direction `sigma`. `count` is the raw count now.
    pub fn new(p: u16, q: u16, rev: i64, cpr: u32, sigma: i64, lock_raw: i64, count: i64) -> Option<Self> {
        let num = i64::from(q).checked_mul(rev)?;
        let den = i64::from(p).checked_mul(i64::from(cpr))?;
        if num <= 0 || den <= 0 {
            return None;
        }
        let sigma = if sigma < 0 { -1 } else { 1 };
        Some(PolygonGear {
            num,
            den,
            rev,
            cpr: i64::from(cpr),
            lock_at: Some(sigma * lock_raw),
            origin: lock_raw,
            sigma,
            last: sigma * count,
            acc: den / 2,
            pos: 0,
            in_rev: 0,
            stopping: false,
        })
    }

    /// A new ratio (G51.2 again in G51.2 mode, 2.8 note 4): C goes on from where
    /// it is at the new ratio.
    pub fn set_ratio(&mut self, p: u16, q: u16) {
        if let (Some(num), Some(den)) = (i64::from(q).checked_mul(self.rev), i64::from(p).checked_mul(self.cpr))
            && num > 0
            && den > 0
        {
            self.acc = den / 2;
            self.num = num;
            self.den = den;
        }
        self.stopping = false;
    }

    /// G50.2: C stops at the next whole revolution from the lock (at once if it
    /// has not locked yet or stands on one).
    pub fn stop(&mut self) {
        self.stopping = true;
        if self.lock_at.is_some() || self.in_rev == 0 {
            self.lock_at = None;
            self.num = 0;
        }
    }

    /// Whether G50.2 was given.
    pub fn is_stopping(&self) -> bool {
        self.stopping
    }

    /// Whether G50.2 has brought C to rest on a whole revolution.
    pub fn finished(&self) -> bool {
        self.stopping && self.num == 0
    }

    /// Whether C is following the spindle (locked at the index).
    pub fn locked(&self) -> bool {
        self.lock_at.is_none() && self.num != 0
    }

    /// The raw encoder count C locks (or locked) at: an index.
    pub fn origin(&self) -> i64 {
        self.origin
    }

    /// C steps since the lock (whole revolutions included).
    pub fn steps(&self) -> i64 {
        self.pos
    }

    /// Takes raw count `count` (any number of counts after the last); true when C's
    /// position changed. C locks when the count reaches the lock count, even if
    /// that count itself was never given.
    pub fn on_count(&mut self, count: i64) -> bool {
        let f = crate::sync::signed(self.sigma, count);
        if let Some(at) = self.lock_at {
            if f < at {
                self.last = f;
                return false;
            }
            self.lock_at = None;
            self.last = at;
        }
        let before = self.pos;
        while self.last < f && self.num != 0 {
            self.last += 1;
            self.forward();
        }
        while self.last > f && self.num != 0 {
            self.last -= 1;
            self.backward();
        }
        self.last = f;
        self.pos != before
    }

    /// The raw counts at which C next steps either way (or locks), for the encoder
    /// compare: nothing is applied ahead (the spindle may turn back).
    pub fn due(&self) -> Due {
        if self.num == 0 {
            return Due::NONE;
        }
        if let Some(at) = self.lock_at {
            return Due::forward(self.sigma, 0, Some(at), None);
        }
        let (mut up, mut a) = (1, self.acc + self.num);
        while a < self.den {
            a += self.num;
            up += 1;
        }
        let (mut down, mut b) = (1, self.acc - self.num);
        while b >= 0 {
            b -= self.num;
            down += 1;
        }
        Due::forward(self.sigma, 0, Some(self.last + up), Some(self.last - down))
    }

    fn forward(&mut self) {
        self.acc += self.num;
        while self.acc >= self.den {
            self.acc -= self.den;
            self.pos += 1;
            self.in_rev += 1;
            if self.in_rev == self.rev {
                self.in_rev = 0;
                if self.stopping {
                    self.num = 0;
                    return;
                }
            }
        }
    }

    fn backward(&mut self) {
        self.acc -= self.num;
        while self.acc < 0 {
            self.acc += self.den;
            self.pos -= 1;
            self.in_rev -= 1;
            if self.in_rev < 0 {
                self.in_rev += self.rev;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn q_over_p_turns_per_spindle_turn_exactly_at_every_index() {
        // P1 Q2, 1000 C steps per turn, 4096 counts per turn, lock at count 100.
        let mut g = PolygonGear::new(1, 2, 1000, 4096, 1, 100, 0).unwrap();
        for c in 1..=100 {
            assert!(!g.on_count(c));
        }
        for k in 1..=5i64 {
            for c in 100 + (k - 1) * 4096 + 1..=100 + k * 4096 {
                g.on_count(c);
            }
            assert_eq!(g.steps(), 2000 * k);
        }
        // Half a turn back: one C turn back.
        for c in (100 + 5 * 4096 - 2048..100 + 5 * 4096).rev() {
            g.on_count(c);
        }
        assert_eq!(g.steps(), 9000);
    }

    /// Drives `a` with every count of `path` and `b` only at its due counts;
    /// asserts the same C position after every count.
    fn same_as_every_count(a: &mut PolygonGear, b: &mut PolygonGear, path: impl IntoIterator<Item = i64>) -> usize {
        let mut taken = 0;
        for c in path {
            a.on_count(c);
            if b.due().reached(c) {
                b.on_count(c);
                taken += 1;
                assert!(!b.due().reached(c), "count {c}");
            }
            assert_eq!(a.steps(), b.steps(), "count {c}");
        }
        taken
    }

    #[test]
    fn only_the_counts_where_c_steps_are_taken_both_ways() {
        // P2 Q3 on 1000 C steps a turn: 1500 steps per 4096 counts (a count in
        // 2.7 taken); P3 Q1 counting down; and more than a step a count (P1 Q5 on
        // 3600 steps: every count taken).
        for (p, q, rev, sigma, most) in [(2, 3, 1_000, 1, 17_000), (3, 1, 1_000, -1, 6_000), (1, 5, 3_600, 1, 46_000)] {
            let mut a = PolygonGear::new(p, q, rev, 4_096, sigma, sigma * 4_096, 0).unwrap();
            let mut b = a;
            let fwd = |c: i64| sigma * c;
            let path = (1..=30_000).chain((20_000..30_000).rev()).chain(20_000..=26_000).map(fwd);
            let taken = same_as_every_count(&mut a, &mut b, path);
            assert!(a.locked());
            assert!(taken <= most, "P{p} Q{q}: {taken} counts taken");
        }
    }

    #[test]
    fn c_locks_at_the_index_even_when_that_count_comes_late() {
        let mut g = PolygonGear::new(1, 2, 1_000, 4_096, 1, 100, 0).unwrap();
        assert_eq!(g.due(), Due::new(Some(100), None));
        // The interrupt ran at count 103: C locked at 100 and is 3 counts along.
        let mut every = g;
        for c in 1..=103 {
            every.on_count(c);
        }
        assert!(g.on_count(103) || g.steps() == 0);
        assert!(g.locked());
        assert_eq!(g.steps(), every.steps());
        g.stop();
        g.on_count(100 + 4_096);
        assert!(g.finished());
        assert_eq!(g.due(), Due::NONE);
    }

    #[test]
    fn g50_2_stops_on_the_next_whole_turn() {
        let mut g = PolygonGear::new(3, 2, 1000, 4096, -1, -10, 0).unwrap();
        let mut c = 0;
        while !g.locked() {
            c -= 1;
            g.on_count(c);
        }
        for _ in 0..3000 {
            c -= 1;
            g.on_count(c);
        }
        g.stop();
        while !g.finished() {
            c -= 1;
            g.on_count(c);
        }
        assert_eq!(g.steps() % 1000, 0);
        assert!(g.steps() > 0);
        let at = g.steps();
        for _ in 0..5000 {
            c -= 1;
            g.on_count(c);
        }
        assert_eq!(g.steps(), at);
    }
}

/// C's travel per revolution, µdeg.
const TURN_UDEG: i64 = 360_000_000;

/// The core's polygon state: the gearbox once started, a start waiting for the
/// first index, and C's step position when it locked.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct Polygon {
    pub(super) gear: Option<PolygonGear>,
    pub(super) waiting: Option<PolygonSync>,
    pub(super) base: i64,
}

impl Polygon {
    /// Whether C is driven by the polygon gearbox (not by the interpolator).
    pub(super) fn active(&self) -> bool {
        self.gear.is_some()
    }
}

impl<const N: usize> MotionCore<N> {
    /// G51.2 / G50.2 reached in the queue.
    pub(super) fn polygon_command(&mut self, sync: Option<PolygonSync>) {
        match (sync, self.polygon.gear.as_mut()) {
            (Some(s), Some(g)) => g.set_ratio(s.p, s.q),
            (Some(s), None) => {
                if !self.p.limits[Axis::C.index()].present {
                    self.raise(AlarmKind::PolygonNoToolSpindle);
                    return;
                }
                self.polygon.waiting = Some(s);
                self.polygon_start();
            }
            (None, Some(g)) => g.stop(),
            (None, None) => self.polygon.waiting = None,
        }
    }

    /// Starts the gearbox once an index has been seen: it locks at the first index
    /// at least two counts ahead.
    pub(super) fn polygon_start(&mut self) {
        let Some(s) = self.polygon.waiting else { return };
        let Some(index) = self.spindle.index else { return };
        if !self.spindle.at_speed(self.mc.at_speed_pct) {
            // The tool spindle starts with the work spindle at its speed.
            return;
        }
        // The encoder's direction as measured (as for threads), the command's until
        // the spindle turns.
        let rpm = self.spindle.measured_rpm();
        let sigma: i64 = match (rpm.abs() > 0.5, rpm >= 0.0) {
            (true, up) => i64::from(up) * 2 - 1,
            (false, _) if self.spindle.dir == SpindleDir::Ccw => -1,
            (false, _) => 1,
        };
        let cpr = i64::from(self.p.cpr.max(1));
        let (fi, now) = (sigma * index, sigma * self.spindle.count);
        let turns = (now + 2 - fi).max(0).div_euclid(cpr) + 1;
        let lock = sigma * (fi + turns * cpr);
        let c = Axis::C.index();
        let rev = self.p.scale[c].steps(TURN_UDEG);
        let gear = PolygonGear::new(s.p, s.q, rev, self.p.cpr, sigma, lock, self.spindle.count);
        self.polygon.waiting = None;
        match gear {
            Some(g) => {
                self.polygon.gear = Some(g);
                self.polygon.base = self.steppers[c].position();
            }
            None => self.raise(AlarmKind::Overflow),
        }
    }

    /// An encoder count: C to the gearbox's position for it; G50.2 done on a whole
    /// turn. Returns C's bit (`1 << index`) if C was commanded to move, else 0.
    pub(super) fn polygon_count(&mut self, now: u64, count: i64) -> u8 {
        let Some(g) = self.polygon.gear.as_mut() else { return 0 };
        let c = Axis::C.index();
        let moved = g.on_count(count);
        if moved {
            self.steppers[c].jump(now, (self.polygon.base + g.steps()) << STEP_FRAC);
        }
        if g.finished() {
            self.polygon_release();
        }
        u8::from(moved) << c
    }

    /// Lets C go: its step count is taken back by the whole turns it made, so that
    /// the planner's C (where it stood before) and the stepper's agree; a partial
    /// turn (reset before G50.2) is kept as a move the interpolator knows of.
    pub(super) fn polygon_release(&mut self) {
        let Some(g) = self.polygon.gear.take() else { return };
        self.polygon.waiting = None;
        let c = Axis::C.index();
        let rev = self.p.scale[c].steps(TURN_UDEG).max(1);
        let whole = g.steps() - g.steps().rem_euclid(rev);
        self.steppers[c].rebase(-whole);
    }

    /// Whether the queue must wait: G50.2 given and C not yet on its whole turn.
    pub(super) fn polygon_stopping(&self) -> bool {
        self.polygon.gear.is_some_and(|g| g.is_stopping())
    }
}

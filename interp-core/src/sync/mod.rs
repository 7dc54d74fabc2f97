//! Spindle synchronisation: the electronic gearbox of thread passes and rigid
//! tapping. While a pass runs, every axis position is an exact integer function of
//! the spindle encoder count — no speed estimate, no control loop — updated at
//! every encoder count, so the axes lag the spindle by nothing but the interrupt.
//!
//! Long-axis steps per encoder count are the exact ratio `N/D` =
//! `lead × steps / (travel per steps × counts per rev)`, reduced. The long axis
//! follows the count through an integer accumulator (remainders carried exactly,
//! rounded to the nearest step); the other axis of a taper follows the long axis
//! by a rounding DDA.
//!
//! **Thread ramp compensation.** A pass cannot start at full speed. With `m` the
//! counts since the ramp started and `R` (even) the ramp length in counts, the
//! long axis moves `N·m²/(2RD)` steps for `m ≤ R`, then `N·(m − R/2)/D`: the same
//! line as a tool that started at full speed `R/2` counts after the ramp began.
//! The ramp is started `R/2` counts before the synchronisation count (index + Q), so
//! after it the tool is exactly where a tool started at full speed at the index + Q
//! would be — at any speed, because nothing here depends on time. `R` only has to
//! be long enough for the axis's acceleration at the measured speed. The end of the
//! pass mirrors it: the deceleration starts `R/2` counts before the virtual end and
//! ends exactly on the end point `R/2` counts after it.
//!
//! Everything is integer in units of `1/(2RD)` step (threads) or `1/(2D)` step
//! (taps): ramp increments `N·(2m+1)` change by `2N` per count, so a count costs a
//! few additions and compares.

use crate::alarm::AlarmKind;
use crate::axis::AXIS_COUNT;
use crate::planner::machine::gcd;

/// One leg of a locked sequence: whole-step start and end points and the long axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Leg {
    /// Start, whole steps per axis.
    pub start: [i64; AXIS_COUNT],
    /// End, whole steps per axis.
    pub end: [i64; AXIS_COUNT],
    /// Index of the long (lead) axis.
    pub long: usize,
}

/// Long-axis steps per encoder count, `n / d`, reduced.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Ratio {
    /// Numerator.
    pub n: i64,
    /// Denominator.
    pub d: i64,
}

impl Ratio {
    /// `lead` nm per revolution on an axis of `steps` steps per `per_nm` nm, with
    /// `cpr` encoder counts per revolution.
    pub fn new(lead: i64, steps: i64, per_nm: i64, cpr: u32) -> Result<Self, AlarmKind> {
        let n = lead.checked_mul(steps).ok_or(AlarmKind::Overflow)?;
        let d = per_nm.checked_mul(i64::from(cpr)).ok_or(AlarmKind::Overflow)?;
        if n <= 0 || d <= 0 {
            return Err(AlarmKind::FeedZero);
        }
        let g = gcd(n, d);
        Ok(Ratio { n: n / g, d: d / g })
    }

    /// Steps per count as a float (checks and reports only).
    pub fn steps_per_count(&self) -> f64 {
        self.n as f64 / self.d as f64
    }
}

/// A rounding DDA: `pos = round(p · num / den)` kept up to date as `p` steps ±1.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
struct Follower {
    num2: i64,
    den2: i64,
    acc: i64,
    pos: i64,
}

impl Follower {
    fn new(num: i64, den: i64) -> Self {
        let den = den.max(1);
        Follower { num2: 2 * num, den2: 2 * den, acc: den, pos: 0 }
    }

    fn up(&mut self) {
        self.acc += self.num2;
        while self.acc >= self.den2 {
            self.acc -= self.den2;
            self.pos += 1;
        }
    }

    fn down(&mut self) {
        self.acc -= self.num2;
        while self.acc < 0 {
            self.acc += self.den2;
            self.pos -= 1;
        }
    }
}

/// Long-axis steps the deceleration of a ramp of `ramp` counts may need, doubled,
/// plus a margin (computed once: no division per count).
fn ramp_zone(ratio: Ratio, ramp: i64) -> i64 {
    ratio.n.saturating_mul(ramp) / ratio.d.max(1) + 4
}

/// Where a thread pass is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Phase {
    /// Waiting for the encoder to reach the count where the ramp starts.
    Waiting,
    /// Accelerating; `k` ramp counts done.
    RampUp {
        /// Counts done.
        k: i64,
    },
    /// Locked at the lead.
    Locked,
    /// Decelerating onto the end point; `u` counts left.
    RampDown {
        /// Counts left.
        u: i64,
    },
    /// On the end point of the sequence.
    Done,
}

/// Which relation the gearbox follows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
enum Mode {
    /// A thread pass: forward counts only, ramps at both ends.
    Thread,
    /// Rigid tapping: linear in the count, both directions.
    Tap,
}

/// The electronic gearbox.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Gear {
    mode: Mode,
    phase: Phase,
    ratio: Ratio,
    /// Ramp length in counts (even; 0 for taps).
    ramp: i64,
    /// Accumulator unit: one long-axis step is `unit` (2RD, or 2D for taps).
    unit: i64,
    /// Long-axis steps from the end within which the deceleration may start (twice
    /// the ramp's N·R/2D, plus a margin): below it the exact test runs.
    ramp_zone: i64,
    /// Remainder of the long axis's exact position, `[0, unit)` (rounded: starts at half).
    acc: i64,
    /// Long-axis steps from the leg's start, and the leg's length and direction.
    p: i64,
    delta: i64,
    long_sign: i64,
    leg: Leg,
    /// Legs completed in this sequence.
    legs_done: u32,
    /// The leg that follows without re-synchronising, if known, and whether the
    /// sequence ends with it.
    next: Option<(Leg, Ratio)>,
    next_last: bool,
    /// The other moving axis (a taper), its direction and DDA.
    follower: Option<(usize, i64, Follower)>,
    /// Encoder direction of forward rotation (+1 counts up, −1 down).
    sigma: i64,
    /// Forward count where the pass started (ramp start, or tap start).
    origin: i64,
    /// Forward counts since `origin`, and the most reached (threads ignore reversals).
    m: i64,
    m_max: i64,
    /// A tap on its way out.
    way_out: bool,
}

impl Gear {
    fn new(mode: Mode, leg: Leg, ratio: Ratio, ramp: i64, sigma: i64, origin: i64) -> Result<Self, AlarmKind> {
        let unit = 2i64.checked_mul(ramp.max(1)).and_then(|v| v.checked_mul(ratio.d)).ok_or(AlarmKind::Overflow)?;
        // The largest increment (2RN) and a carry must stay far from overflow.
        let top = 2i64.checked_mul(ramp.max(1)).and_then(|v| v.checked_mul(ratio.n)).ok_or(AlarmKind::Overflow)?;
        if top.checked_add(unit).and_then(|v| v.checked_mul(4)).is_none() {
            return Err(AlarmKind::Overflow);
        }
        let mut g = Gear {
            mode,
            phase: if mode == Mode::Thread { Phase::Waiting } else { Phase::Locked },
            ratio,
            ramp,
            unit,
            ramp_zone: ramp_zone(ratio, ramp),
            acc: unit / 2,
            p: 0,
            delta: 0,
            long_sign: 1,
            leg,
            legs_done: 0,
            next: None,
            next_last: true,
            follower: None,
            sigma: if sigma < 0 { -1 } else { 1 },
            origin,
            m: 0,
            m_max: 0,
            way_out: false,
        };
        g.set_leg(leg);
        Ok(g)
    }

    /// A thread pass along `leg` whose acceleration ramp of `ramp` counts (made even,
    /// at least 2) starts at raw encoder count `ramp_start`; forward rotation makes
    /// the count go in direction `sigma`. The tool is where a tool started at full
    /// speed at `ramp_start + sigma·ramp/2` would be once the ramp is over.
    pub fn thread(leg: Leg, ratio: Ratio, ramp: i64, sigma: i64, ramp_start: i64) -> Result<Self, AlarmKind> {
        let ramp = (ramp.max(2) + 1) & !1;
        let sigma = if sigma < 0 { -1 } else { 1 };
        Gear::new(Mode::Thread, leg, ratio, ramp, sigma, sigma * ramp_start)
    }

    /// Rigid tapping along `leg` (the way in), locked from raw count `count` on;
    /// forward rotation (counts in direction `sigma`) moves towards the bottom.
    pub fn tap(leg: Leg, ratio: Ratio, sigma: i64, count: i64) -> Result<Self, AlarmKind> {
        let sigma = if sigma < 0 { -1 } else { 1 };
        Gear::new(Mode::Tap, leg, ratio, 1, sigma, sigma * count)
    }

    fn set_leg(&mut self, leg: Leg) {
        let d = leg.end[leg.long] - leg.start[leg.long];
        self.leg = leg;
        self.delta = d.abs();
        self.long_sign = if d < 0 { -1 } else { 1 };
        self.p = 0;
        self.follower = (0..AXIS_COUNT).rfind(|&i| i != leg.long && leg.end[i] != leg.start[i]).map(|i| {
            let ds = leg.end[i] - leg.start[i];
            (i, ds.signum(), Follower::new(ds.abs(), self.delta))
        });
    }

    /// Announces the thread leg that continues this one without re-synchronising
    /// (2.17.1 note 2); `last` if the sequence ends with it. Without one, the pass
    /// decelerates onto the current leg's end. A last leg on the same axis at the
    /// same lead (a pull-out) shares the deceleration with the leg before it, so a
    /// short pull-out still ends exactly on its end point. Alarm 4507 when the pass is
    /// already decelerating or done, 4502 when what is left cannot hold the ramps.
    pub fn set_next(&mut self, leg: Leg, ratio: Ratio, last: bool) -> Result<(), AlarmKind> {
        if self.mode != Mode::Thread
            || matches!(self.phase, Phase::RampDown { .. } | Phase::Done)
            || leg.start != self.leg.end
            || leg.end[leg.long] == leg.start[leg.long]
        {
            return Err(AlarmKind::SyncSequenceBroken);
        }
        let unit = 2i64.checked_mul(self.ramp).and_then(|v| v.checked_mul(ratio.d)).ok_or(AlarmKind::Overflow)?;
        if unit > i64::MAX / 8 {
            return Err(AlarmKind::Overflow);
        }
        let len = (leg.end[leg.long] - leg.start[leg.long]).abs();
        let shares = ratio == self.ratio && leg.long == self.leg.long;
        let ramp_steps = ratio.n.saturating_mul(self.ramp) / ratio.d.max(1) / 2 + 1;
        let starting = matches!(self.phase, Phase::Waiting | Phase::RampUp { .. });
        let room = if shares { len + self.delta - self.p } else { len };
        let need = if shares && starting { 2 * ramp_steps } else { ramp_steps };
        if last && room < need {
            return Err(AlarmKind::ThreadRampTooLong);
        }
        self.next = Some((leg, ratio));
        self.next_last = last;
        Ok(())
    }

    /// Whether a continuing leg has been announced.
    pub fn has_next(&self) -> bool {
        self.next.is_some()
    }

    /// The rigid tap's way out: `leg` must lead back from the bottom to where the tap
    /// started (alarm 4507 otherwise); the relation to the spindle stays the same.
    pub fn way_out(&mut self, leg: &Leg) -> Result<(), AlarmKind> {
        if self.mode != Mode::Tap || leg.end != self.leg.start || leg.start != self.leg.end {
            return Err(AlarmKind::SyncSequenceBroken);
        }
        self.way_out = true;
        Ok(())
    }

    /// The thread pass's phase.
    pub fn phase(&self) -> Phase {
        self.phase
    }

    /// Ramp length in counts.
    pub fn ramp(&self) -> i64 {
        self.ramp
    }

    /// The ratio in force.
    pub fn ratio(&self) -> Ratio {
        self.ratio
    }

    /// Legs finished so far in this sequence.
    pub fn legs_done(&self) -> u32 {
        self.legs_done
    }

    /// Raw encoder count where the pass started: the ramp start of a thread, the
    /// lock of a tap.
    pub fn origin(&self) -> i64 {
        self.sigma * self.origin
    }

    /// Encoder direction of forward rotation.
    pub fn sigma(&self) -> i64 {
        self.sigma
    }

    /// Forward counts since the pass started (negative while waiting).
    pub fn counts(&self) -> i64 {
        self.m
    }

    /// Whether the sequence is over: the thread on its last end point, the tap back
    /// at its start (or at the bottom, before its way out is known).
    pub fn finished(&self) -> bool {
        match self.mode {
            Mode::Thread => self.phase == Phase::Done,
            Mode::Tap if self.way_out => self.p <= 0,
            Mode::Tap => self.p >= self.delta,
        }
    }

    /// The long axis and the other axis of a taper, if any: the axes the gearbox drives.
    pub fn axes(&self) -> (usize, Option<usize>) {
        (self.leg.long, self.follower.map(|f| f.0))
    }

    /// The leg running.
    pub fn leg(&self) -> &Leg {
        &self.leg
    }

    /// Whether this is a rigid tap (and not a thread pass).
    pub fn is_tap(&self) -> bool {
        self.mode == Mode::Tap
    }

    /// Whether a tap is on its way out.
    pub fn is_way_out(&self) -> bool {
        self.way_out
    }

    /// Long-axis steps left to the end of the leg (tap: to the bottom, or back to
    /// the start on the way out).
    pub fn remaining(&self) -> i64 {
        if self.way_out { self.p } else { self.delta - self.p }
    }

    /// Whole-step position of every axis: the leg's start, with the long axis and
    /// the taper's follower where the spindle has taken them.
    pub fn positions(&self, out: &mut [i64; AXIS_COUNT]) {
        let leg = &self.leg;
        *out = leg.start;
        out[leg.long] = leg.start[leg.long] + self.long_sign * self.p;
        if let Some((i, sign, f)) = &self.follower {
            out[*i] = leg.start[*i] + sign * f.pos;
        }
    }

    /// Processes raw encoder count `c`, one count at a time; true if an axis moved.
    pub fn on_count(&mut self, c: i64) -> bool {
        let fwd = self.sigma * c - self.origin;
        let mut moved = false;
        match self.mode {
            Mode::Tap => {
                while self.m != fwd {
                    let dir = (fwd - self.m).signum();
                    self.m += dir;
                    moved |= self.add(2 * self.ratio.n * dir);
                }
            }
            Mode::Thread => {
                while self.m < fwd {
                    self.m += 1;
                    if self.m > self.m_max {
                        self.m_max = self.m;
                        moved |= self.thread_count();
                    }
                }
                self.m = fwd.min(self.m);
            }
        }
        moved
    }

    /// One forward count of a thread pass.
    fn thread_count(&mut self) -> bool {
        let (n, r) = (self.ratio.n, self.ramp);
        match self.phase {
            Phase::Waiting | Phase::RampUp { .. } => {
                let k = if let Phase::RampUp { k } = self.phase { k } else { 0 };
                self.phase = if k + 1 >= r { Phase::Locked } else { Phase::RampUp { k: k + 1 } };
                self.add(n * (2 * k + 1))
            }
            Phase::Locked => match self.ramp_down_jump() {
                Some(jump) => {
                    self.phase = Phase::RampDown { u: r };
                    self.add(jump)
                }
                None => self.add(2 * r * n),
            },
            Phase::RampDown { u } => {
                let moved = self.add(n * (2 * u - 1));
                if u <= 1 {
                    if let Some((leg, _)) = self.next.take() {
                        // Rounding left the last leg's first step undone: finish on it.
                        self.legs_done += 1;
                        self.set_leg(leg);
                    }
                    self.phase = Phase::Done;
                    self.p = self.delta;
                    self.acc = self.unit / 2;
                } else {
                    self.phase = Phase::RampDown { u: u - 1 };
                }
                moved
            }
            Phase::Done => false,
        }
    }

    /// On the last leg, the increment that lands exactly where the deceleration
    /// starts (`unit·Δ − N·R²` in accumulator terms) if this count gets there.
    fn ramp_down_jump(&self) -> Option<i64> {
        let (n, r) = (self.ratio.n, self.ramp);
        let left = match self.next {
            None => self.delta - self.p,
            Some((leg, ratio)) if self.next_last && ratio == self.ratio && leg.long == self.leg.long => {
                self.delta - self.p + (leg.end[leg.long] - leg.start[leg.long]).abs()
            }
            Some(_) => return None,
        };
        // Far from the end the products below could overflow; the ramp is short.
        if left > self.ramp_zone {
            return None;
        }
        let now = self.acc - self.unit / 2; // position within the step, in units
        let to_start = i128::from(self.unit) * i128::from(left) - i128::from(n) * i128::from(r * r) - i128::from(now);
        (to_start <= i128::from(2 * r * n)).then_some(to_start.max(0) as i64)
    }

    /// Adds `inc` units to the long axis's exact position; moves whole steps.
    fn add(&mut self, inc: i64) -> bool {
        self.acc += inc;
        let mut moved = false;
        while self.acc >= self.unit {
            self.acc -= self.unit;
            self.step(1);
            moved = true;
        }
        while self.acc < 0 {
            self.acc += self.unit;
            self.step(-1);
            moved = true;
        }
        moved
    }

    /// One long-axis step along the leg (or back), with its follower; at the end of
    /// a thread leg the announced next leg takes over.
    fn step(&mut self, dir: i64) {
        self.p += dir;
        if let Some((_, _, f)) = &mut self.follower {
            if dir > 0 { f.up() } else { f.down() }
        }
        if self.mode == Mode::Thread
            && self.p >= self.delta
            && let Some((leg, ratio)) = self.next.take()
        {
            self.legs_done += 1;
            if ratio != self.ratio {
                self.unit = 2 * self.ramp * ratio.d;
                self.acc = self.unit / 2;
                self.ratio = ratio;
                self.ramp_zone = ramp_zone(ratio, self.ramp);
            }
            self.set_leg(leg);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const CPR: u32 = 4_096;

    /// Z from 0 to -`len` steps (the long axis), X from 0 to `x` steps.
    fn leg(len: i64, x: i64) -> Leg {
        Leg { start: [0; AXIS_COUNT], end: [x, 0, -len, 0], long: 2 }
    }

    /// Runs `g` count by count from `from` to `to` (raw counts); returns (count, Z, X)
    /// after every count.
    fn run(g: &mut Gear, from: i64, to: i64) -> std::vec::Vec<(i64, i64, i64)> {
        let mut out = std::vec::Vec::new();
        let mut pos = [0; AXIS_COUNT];
        let step = if to >= from { 1 } else { -1 };
        let mut c = from;
        while c != to {
            c += step;
            g.on_count(c);
            g.positions(&mut pos);
            out.push((c, pos[2], pos[0]));
        }
        out
    }

    #[test]
    fn ratio_is_exact_and_reduced() {
        // 2 mm lead, 320 steps/mm, 4096 counts: 640 steps per 4096 counts = 5/32.
        assert_eq!(Ratio::new(2_000_000, 1, 3_125, CPR).unwrap(), Ratio { n: 5, d: 32 });
        assert!(Ratio::new(0, 1, 3_125, CPR).is_err());
    }

    #[test]
    fn after_the_ramp_the_phase_does_not_depend_on_the_ramp_length() {
        let ratio = Ratio { n: 5, d: 32 };
        let sync = 10_000; // raw count of index + Q
        let mut reference = None;
        for ramp in [100, 2_000, 18_000] {
            let start = sync - ramp / 2;
            let mut g = Gear::thread(leg(6_400, 0), ratio, ramp, 1, start).unwrap();
            let trace = run(&mut g, start - 50, sync + 60_000);
            // Everything after the ramp lies on round((c - sync)·N/D).
            for &(c, z, _) in trace.iter().filter(|t| t.0 > start + ramp && -t.1 < 6_400 - 2_000) {
                let ideal = ((c - sync) as f64 * 5.0 / 32.0).round() as i64;
                assert_eq!(-z, ideal, "ramp {ramp} count {c}");
            }
            // The count at which Z reaches -3000 steps is the same for every ramp.
            let at = trace.iter().find(|t| t.1 == -3_000).unwrap().0;
            assert_eq!(*reference.get_or_insert(at), at, "ramp {ramp}");
            // The pass ends exactly on the end point, at rest.
            assert_eq!(trace.last().unwrap().1, -6_400);
            assert_eq!(g.phase(), Phase::Done);
        }
    }

    #[test]
    fn the_ramp_accelerates_evenly_in_counts() {
        let ratio = Ratio { n: 5, d: 32 };
        let mut g = Gear::thread(leg(6_400, 0), ratio, 1_000, 1, 0).unwrap();
        let trace = run(&mut g, 0, 1_000);
        // z(m) = N m² / (2 R D), rounded.
        for &(m, z, _) in &trace {
            let ideal = (5.0 * (m * m) as f64 / (2.0 * 1_000.0 * 32.0)).round() as i64;
            assert!((-z - ideal).abs() <= 1, "m {m}: {z} vs {ideal}");
        }
        assert_eq!(g.phase(), Phase::Locked);
    }

    #[test]
    fn a_taper_follows_the_long_axis_within_a_step() {
        let ratio = Ratio { n: 5, d: 32 };
        let mut g = Gear::thread(leg(6_400, 1_000), ratio, 400, 1, 0).unwrap();
        let trace = run(&mut g, 0, 50_000);
        for &(_, z, x) in &trace {
            let ideal = -z as f64 * 1_000.0 / 6_400.0;
            assert!((x as f64 - ideal).abs() <= 0.51, "{z} {x}");
        }
        assert_eq!(trace.last().map(|t| (t.1, t.2)), Some((-6_400, 1_000)));
    }

    #[test]
    fn a_continuing_leg_takes_over_without_resynchronising() {
        let ratio = Ratio { n: 5, d: 32 };
        let first = leg(3_200, 0);
        let second = Leg { start: first.end, end: [800, 0, -6_400, 0], long: 2 };
        let mut g = Gear::thread(first, ratio, 200, 1, 0).unwrap();
        g.set_next(second, ratio, true).unwrap();
        let trace = run(&mut g, 0, 60_000);
        assert_eq!(g.legs_done(), 1);
        // The lead is continuous across the junction: Z keeps N/D per count.
        for &(c, z, _) in trace.iter().filter(|t| t.0 > 200 && -t.1 < 6_000) {
            let ideal = ((c - 100) as f64 * 5.0 / 32.0).round() as i64;
            assert_eq!(-z, ideal, "count {c}");
        }
        assert_eq!(trace.last().map(|t| (t.1, t.2)), Some((-6_400, 800)));
    }

    #[test]
    fn a_short_pull_out_shares_the_deceleration_and_ends_exactly() {
        // Ramp of 4000 counts: 5/32 × 4000 / 2 = 312 steps to stop; the pull-out has 100.
        let ratio = Ratio { n: 5, d: 32 };
        let first = leg(400, 0);
        let pull = Leg { start: first.end, end: [80, 0, -500, 0], long: 2 };
        let mut g = Gear::thread(first, ratio, 4_000, 1, 0).unwrap();
        assert_eq!(g.set_next(pull, ratio, true), Err(AlarmKind::ThreadRampTooLong), "ramps need 626 steps");
        let first = leg(6_400, 0);
        let pull = Leg { start: first.end, end: [80, 0, -6_500, 0], long: 2 };
        let mut g = Gear::thread(first, ratio, 4_000, 1, 0).unwrap();
        g.set_next(pull, ratio, true).unwrap();
        let trace = run(&mut g, 0, 80_000);
        assert_eq!(g.phase(), Phase::Done);
        assert_eq!(trace.last().map(|t| (t.1, t.2)), Some((-6_500, 80)));
        // It slowed down smoothly: never more than one step per count, never backwards.
        for w in trace.windows(2) {
            assert!((0..=1).contains(&(w[0].1 - w[1].1)), "{:?}", w);
        }
    }

    #[test]
    fn a_tap_is_locked_both_ways_and_returns_exactly() {
        // 1.5 mm lead on Z at 320 steps/mm: 480 steps per 4096 counts = 15/128.
        let ratio = Ratio::new(1_500_000, 1, 3_125, CPR).unwrap();
        let way_in = leg(3_200, 0);
        let mut g = Gear::tap(way_in, ratio, 1, 500).unwrap();
        let trace = run(&mut g, 500, 500 + 27_400);
        for &(c, z, _) in &trace {
            assert_eq!(-z, ((c - 500) as f64 * 15.0 / 128.0).round() as i64);
        }
        assert!(g.finished(), "at the bottom (and 12 steps past it)");
        let out = Leg { start: way_in.end, end: way_in.start, long: 2 };
        g.way_out(&out).unwrap();
        assert!(!g.finished());
        let back = run(&mut g, 500 + 27_400, 500);
        for &(c, z, _) in &back {
            assert_eq!(-z, ((c - 500) as f64 * 15.0 / 128.0).round() as i64);
        }
        assert!(g.finished());
        assert_eq!(back.last().unwrap().1, 0);
        assert!(g.way_out(&leg(100, 0)).is_err());
    }
}

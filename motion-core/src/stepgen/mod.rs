//! Step generation: turns an axis's commanded position into step and direction
//! events with exact times, honouring the driver's timing (minimum pulse width,
//! direction set-up time, maximum step rate).
//!
//! This is the pure logic of the step interrupt: the firmware programs a timer
//! compare for each event's time and sets the pins; the simulator records them.
//! It never divides: the time per position unit of an interpolation period comes
//! from a multiply-only reciprocal ([`crate::fixed::scaled_reciprocal`]) once per
//! period, and each step costs one multiply.
//!
//! The commanded position is either a straight ramp over an interpolation period
//! ([`AxisStepGen::ramp`], from the interpolator) or a value that holds from a
//! moment on ([`AxisStepGen::jump`], from the spindle gearbox at an encoder edge).
//! A step is due when the commanded position crosses the half-way point to the
//! next whole step, so the axis is always within half a step of its command
//! unless the driver's timing forced a delay.

use crate::alarm::AlarmKind;
use crate::config::Drive;
use crate::fixed::{STEP_FRAC, STEP_ONE, round_steps, scaled_reciprocal};

/// Driver timing in nanoseconds, checked for consistency.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct DriverTiming {
    /// Step pulse high time; also the direction hold time after a step edge.
    pub pulse_ns: u32,
    /// Direction line stable before a step edge.
    pub dir_setup_ns: u32,
    /// Shortest time between two step edges (max step rate, and at least two pulses).
    pub min_period_ns: u32,
}

impl DriverTiming {
    /// The timing of `drive`; alarm 4508 if it cannot be met (no rate, zero pulse).
    pub fn from_drive(drive: &Drive) -> Result<Self, AlarmKind> {
        if drive.max_step_hz == 0 || drive.pulse_ns == 0 {
            return Err(AlarmKind::MotionConfigInvalid { what: "step rate and pulse width must be above zero" });
        }
        let rate_period = 1_000_000_000u32.div_ceil(drive.max_step_hz);
        let min_period_ns = rate_period.max(drive.pulse_ns.saturating_mul(2));
        Ok(DriverTiming { pulse_ns: drive.pulse_ns, dir_setup_ns: drive.dir_setup_ns, min_period_ns })
    }
}

/// What an event does to the axis's pins.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum EdgeKind {
    /// Set the direction line (true = positive).
    Dir(bool),
    /// One step pulse (rising edge at the event time) in the given direction.
    Step(bool),
}

/// One pin event of one axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct StepEvent {
    /// Time of the edge, ns.
    pub t: u64,
    /// Direction change or step.
    pub kind: EdgeKind,
}

/// The step generator of one axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AxisStepGen {
    timing: DriverTiming,
    /// Steps issued so far (the axis's real position, whole steps).
    pos: i64,
    /// Level of the direction line.
    positive: bool,
    /// Commanded position at `t0` and where it ends, Q16 steps.
    p0: i64,
    p1: i64,
    /// The whole step `p1` rounds to.
    target: i64,
    /// Start of the current command.
    t0: u64,
    /// ns per Q16 position unit of the current ramp, Q32 (0: a jump).
    rate: u64,
    /// Ideal time of the next step after `t0`, ns in Q32, and the time between two
    /// steps of the ramp; `fresh` until the first step of a command computes it.
    next_q32: u64,
    interval_q32: u64,
    fresh: bool,
    /// No step edge before this (step rate, direction set-up).
    earliest: u64,
    /// No direction change before this (pulse hold).
    dir_free: u64,
    /// Steps issued later than their ideal time because of the driver timing.
    delayed: u32,
}

impl AxisStepGen {
    /// A generator at whole step `pos`, direction positive, nothing commanded.
    pub const fn new(timing: DriverTiming, pos: i64) -> Self {
        let q = pos << STEP_FRAC;
        AxisStepGen {
            timing,
            pos,
            positive: true,
            p0: q,
            p1: q,
            target: pos,
            t0: 0,
            rate: 0,
            next_q32: 0,
            interval_q32: 0,
            fresh: true,
            earliest: 0,
            dir_free: 0,
            delayed: 0,
        }
    }

    /// Steps issued so far.
    pub const fn position(&self) -> i64 {
        self.pos
    }

    /// The commanded position at the end of the current command, Q16 steps.
    pub const fn command(&self) -> i64 {
        self.p1
    }

    /// Whether every commanded step has been issued.
    pub const fn settled(&self) -> bool {
        self.pos == self.target
    }

    /// Steps that came later than their ideal time because of the driver timing.
    pub const fn delayed(&self) -> u32 {
        self.delayed
    }

    /// The timing this generator honours.
    pub const fn timing(&self) -> DriverTiming {
        self.timing
    }

    /// Commands a straight ramp from the previous command to `p1` (Q16 steps) over
    /// the interpolation period `[t0, t0 + period_ns)`.
    pub fn ramp(&mut self, t0: u64, period_ns: u32, p1: i64) {
        self.p0 = self.p1;
        self.p1 = p1;
        self.t0 = t0;
        self.target = round_steps(p1);
        let dp = p1.abs_diff(self.p0);
        self.rate = if dp == 0 { 0 } else { scaled_reciprocal(period_ns, dp.min(u64::from(u32::MAX)) as u32) };
        self.interval_q32 = self.rate.saturating_mul(STEP_ONE as u64);
        self.fresh = true;
    }

    /// Renumbers the axis by `delta` whole steps without moving it (a rotary axis
    /// that turned whole revolutions is at the same angle).
    pub fn rebase(&mut self, delta: i64) {
        self.pos += delta;
        self.target += delta;
        self.p0 += delta << STEP_FRAC;
        self.p1 += delta << STEP_FRAC;
    }

    /// Commands position `p` (Q16 steps) from time `t` on (the gearbox's output):
    /// any step it needs is due at once.
    pub fn jump(&mut self, t: u64, p: i64) {
        self.p0 = p;
        self.p1 = p;
        self.t0 = t;
        self.target = round_steps(p);
        self.rate = 0;
        self.interval_q32 = 0;
        self.fresh = true;
    }

    /// The next pin event of the current command if it falls before `until`, and
    /// issues it; `None` when the axis is where it was told to be, or the next
    /// event belongs to a later command period.
    pub fn next_event(&mut self, until: u64) -> Option<StepEvent> {
        if self.pos == self.target {
            return None;
        }
        let up = self.target > self.pos;
        if up != self.positive {
            let t = self.dir_free.max(self.t0);
            if t >= until {
                return None;
            }
            self.positive = up;
            self.fresh = true;
            self.earliest = self.earliest.max(t + u64::from(self.timing.dir_setup_ns));
            return Some(StepEvent { t, kind: EdgeKind::Dir(up) });
        }
        if self.fresh {
            self.next_q32 = self.crossing(up);
            self.fresh = false;
        }
        let ideal = self.t0 + (self.next_q32 >> 32);
        let t = ideal.max(self.earliest);
        if t >= until {
            return None;
        }
        if t > ideal {
            self.delayed += 1;
        }
        // The next half-step boundary is one step further along the ramp.
        self.next_q32 = self.next_q32.saturating_add(self.interval_q32);
        Some(self.issue(t, up))
    }

    /// [`AxisStepGen::next_event`] for an axis the gearbox jumps (the encoder
    /// count interrupt): a step in the direction the line already has is due at
    /// the jump's time, or when the driver allows, without the ramp's crossing
    /// and step interval (kept out of `next_event`, which every ramped step runs).
    pub fn next_jump_event(&mut self, until: u64) -> Option<StepEvent> {
        let up = self.target > self.pos;
        if self.rate != 0 || self.pos == self.target || up != self.positive {
            return self.next_event(until);
        }
        let t = self.t0.max(self.earliest);
        if t >= until {
            return None;
        }
        if t > self.t0 {
            self.delayed += 1;
        }
        Some(self.issue(t, up))
    }

    /// Issues a step at `t`: the position, the pulse's direction hold and the step
    /// period the driver needs after it.
    #[inline]
    fn issue(&mut self, t: u64, up: bool) -> StepEvent {
        self.pos += if up { 1 } else { -1 };
        self.dir_free = t + u64::from(self.timing.pulse_ns);
        self.earliest = t + u64::from(self.timing.min_period_ns);
        StepEvent { t, kind: EdgeKind::Step(up) }
    }

    /// When, after `t0` (ns, Q32), the command crosses the half-step boundary
    /// towards the next step.
    fn crossing(&self, up: bool) -> u64 {
        let half = STEP_ONE >> 1;
        let boundary = (self.pos << STEP_FRAC) + if up { half } else { -half };
        let ahead = if up { boundary - self.p0 } else { self.p0 - boundary };
        if ahead <= 0 || self.rate == 0 {
            return 0;
        }
        (ahead as u64).saturating_mul(self.rate)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const T: u32 = 1_000_000;

    fn timing() -> DriverTiming {
        DriverTiming::from_drive(&Drive::per_mm(400)).unwrap()
    }

    fn drain(g: &mut AxisStepGen, until: u64) -> heapless::Vec<StepEvent, 512> {
        let mut v = heapless::Vec::new();
        while let Some(e) = g.next_event(until) {
            v.push(e).unwrap();
        }
        v
    }

    #[test]
    fn timing_from_the_drive() {
        let t = timing();
        assert_eq!(t, DriverTiming { pulse_ns: 2_500, dir_setup_ns: 5_000, min_period_ns: 10_000 });
        let slow = Drive { max_step_hz: 1_000_000, pulse_ns: 4_000, ..Drive::per_mm(1) };
        assert_eq!(DriverTiming::from_drive(&slow).unwrap().min_period_ns, 8_000);
        assert!(DriverTiming::from_drive(&Drive { max_step_hz: 0, ..slow }).is_err());
    }

    #[test]
    fn steps_are_spaced_evenly_at_half_step_crossings() {
        let mut g = AxisStepGen::new(timing(), 0);
        g.ramp(0, T, 10 * STEP_ONE);
        let ev = drain(&mut g, u64::from(T));
        assert_eq!(ev.len(), 10);
        for (k, e) in ev.iter().enumerate() {
            // Crossing k + 1/2 of 10 steps in 1 ms: (k + 0.5) × 100 µs.
            let ideal = (k as u64 * 2 + 1) * 50_000;
            assert!(e.t.abs_diff(ideal) <= 1, "{k}: {} vs {ideal}", e.t);
            assert_eq!(e.kind, EdgeKind::Step(true));
        }
        assert!(g.settled());
        assert_eq!(g.position(), 10);
    }

    #[test]
    fn a_reversal_sets_direction_with_hold_and_setup_time() {
        let mut g = AxisStepGen::new(timing(), 0);
        g.ramp(0, T, 3 * STEP_ONE);
        let last = drain(&mut g, u64::from(T)).last().unwrap().t;
        g.ramp(u64::from(T), T, STEP_ONE);
        let ev = drain(&mut g, 2 * u64::from(T));
        assert_eq!(ev[0].kind, EdgeKind::Dir(false));
        assert!(ev[0].t >= last + 2_500 && ev[0].t >= u64::from(T));
        assert_eq!(ev[1].kind, EdgeKind::Step(false));
        assert!(ev[1].t >= ev[0].t + 5_000);
        assert_eq!(ev.len(), 3);
        assert_eq!(g.position(), 1);
    }

    #[test]
    fn too_fast_a_command_is_limited_to_the_step_rate() {
        let mut g = AxisStepGen::new(timing(), 0);
        // 150 steps in one period would need 150 kHz; the driver takes 100 kHz.
        g.ramp(0, T, 150 * STEP_ONE);
        let ev = drain(&mut g, u64::from(T));
        assert_eq!(ev.len(), 100);
        for w in ev.windows(2) {
            assert!(w[1].t - w[0].t >= 10_000);
        }
        assert!(g.delayed() > 0);
        // The rest follows in the next period.
        g.ramp(u64::from(T), T, 150 * STEP_ONE);
        assert_eq!(drain(&mut g, 2 * u64::from(T)).len(), 50);
        assert_eq!(g.position(), 150);
    }

    #[test]
    fn a_jump_event_is_the_same_as_the_general_one() {
        // Steps after jumps, a direction change, and a step held by the step rate:
        // next_jump_event gives what next_event gives.
        let (mut a, mut b) = (AxisStepGen::new(timing(), 0), AxisStepGen::new(timing(), 0));
        let jumps = [(1_000, 1), (2_000, 2), (4_000, 3), (5_000, 2), (30_000, 1), (31_000, 2), (32_000, 4)];
        for (t, p) in jumps {
            a.jump(t, p * STEP_ONE);
            b.jump(t, p * STEP_ONE);
            loop {
                let (ea, eb) = (a.next_event(u64::MAX), b.next_jump_event(u64::MAX));
                assert_eq!(ea, eb, "jump to {p} at {t}");
                if ea.is_none() {
                    break;
                }
            }
        }
        assert_eq!((a.position(), a.delayed()), (b.position(), b.delayed()));
        assert!(b.delayed() > 0);
    }

    #[test]
    fn a_jump_steps_at_once_and_rounds_to_the_nearest_step() {
        let mut g = AxisStepGen::new(timing(), 5);
        g.jump(1_000, 5 * STEP_ONE + STEP_ONE / 2 - 1);
        assert_eq!(g.next_event(u64::MAX), None);
        g.jump(2_000, 5 * STEP_ONE + STEP_ONE / 2);
        assert_eq!(g.next_event(u64::MAX), Some(StepEvent { t: 2_000, kind: EdgeKind::Step(true) }));
        g.jump(3_000, 7 * STEP_ONE);
        assert_eq!(g.next_event(u64::MAX).map(|e| e.t), Some(12_000));
        assert_eq!(g.position(), 7);
    }
}

//! The motion interrupt's logic: runs the motion core one interpolation period ahead
//! of the step player and queues each axis's step and direction edges on the step
//! timer's clock.
//!
//! Pipeline: while period `j` plays, [`Engine::period`] computes period `j + 1`
//! (`tick` at its start time, then every edge before its end), so every edge is
//! queued before it is due and the first step of a period is never late by the
//! time the core takes. Core time and step-timer time are the same clock: period
//! `j` starts at `j × period_ns` and at timer tick `start + j × period_ticks`.
//!
//! While axes are locked to the spindle, [`Engine::encoder`] runs at each encoder
//! count (same interrupt priority as the period, so they never preempt each other and
//! the rings keep a single producer): it hands the count and its time to the core
//! and queues the steps the gearbox makes, due at once.
//!
//! The e-stop input is read in the period: its rising level calls the core's
//! `emergency_stop` (the step player already raises no STEP pin while it is active).

use motion_core::motion::{Feedback, MotionCore};
use motion_core::stepgen::{EdgeKind, StepEvent};

use crate::encoder::Encoder;
use crate::ring::{Edge, Producer, Timed};
use crate::timebase::TimeBase;

/// Edges per axis ring: two periods of the fastest axis (100 kHz at 1 ms) with
/// direction changes fit.
pub const RING: usize = 256;

/// One period's machine readings, taken at the start of the motion interrupt.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Sample {
    /// Step timer count now.
    pub now: u32,
    /// Raw 32-bit spindle encoder count.
    pub raw_count: u32,
    /// Raw count latched at the last index pulse, if one was seen since power-on.
    pub index: Option<u32>,
    /// E-stop input active.
    pub estop: bool,
}

/// Counters for reports and tests.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct EngineStats {
    /// Periods computed.
    pub periods: u32,
    /// Periods whose interrupt started after the period it computes had begun.
    pub late: u32,
    /// Times an axis ring was full (its edge waits for the next period).
    pub ring_full: u32,
    /// Edges queued.
    pub edges: u32,
    /// Encoder counts handed to the core while locked.
    pub sync_counts: u32,
}

/// One driven axis: the core's axis index, its ring's producer end, and an edge the
/// full ring could not take.
pub struct EngineAxis {
    core_axis: usize,
    tx: Producer<RING>,
    carry: Option<StepEvent>,
}

impl EngineAxis {
    /// Axis `core_axis` of the motion core (`motion_core::canon::Axis as usize`) fed
    /// into ring end `tx`.
    pub fn new(core_axis: usize, tx: Producer<RING>) -> Self {
        EngineAxis { core_axis, tx, carry: None }
    }

    /// Edges waiting to be played.
    pub fn queued(&self) -> u32 {
        self.tx.len()
    }
}

/// The motion interrupt's state for `A` driven axes.
pub struct Engine<const A: usize> {
    tb: TimeBase,
    axes: [EngineAxis; A],
    /// Start of the period computed last (the one after the period playing, between
    /// two period interrupts): core time (ns) and step timer tick.
    base_ns: u64,
    base_ticks: u32,
    encoder: Encoder,
    estop: bool,
    stats: EngineStats,
}

impl<const A: usize> Engine<A> {
    /// An engine whose period 0 starts at timer tick `start` (core time 0), with the
    /// encoder's raw count `raw_count` as count 0.
    pub fn new(tb: TimeBase, axes: [EngineAxis; A], start: u32, raw_count: u32) -> Self {
        Engine {
            tb,
            axes,
            base_ns: 0,
            base_ticks: start,
            encoder: Encoder::new(raw_count),
            estop: false,
            stats: EngineStats::default(),
        }
    }

    /// Makes timer tick `start` the start of the period playing and `raw_count` the
    /// encoder's current reading (once, when the timers start, before the first
    /// period).
    pub fn set_origin(&mut self, start: u32, raw_count: u32) {
        self.base_ticks = start;
        self.encoder = Encoder::new(raw_count).with_count(self.encoder.count());
    }

    /// The time base.
    pub fn time_base(&self) -> &TimeBase {
        &self.tb
    }

    /// Counters.
    pub fn stats(&self) -> EngineStats {
        self.stats
    }

    /// Timer tick at which the period computed last starts.
    pub fn base_ticks(&self) -> u32 {
        self.base_ticks
    }

    /// The spindle count (widened) at the last reading.
    pub fn count(&self) -> i64 {
        self.encoder.count()
    }

    /// The driven axes.
    pub fn axes(&self) -> &[EngineAxis; A] {
        &self.axes
    }

    /// The period interrupt: computes the period after the one playing, queues its
    /// edges, and moves on to it.
    pub fn period<const N: usize>(&mut self, core: &mut MotionCore<N>, s: Sample) {
        let period_ns = u64::from(self.tb.period_ns);
        let next_ticks = self.base_ticks.wrapping_add(self.tb.period_ticks);
        if s.now.wrapping_sub(next_ticks) as i32 >= 0 {
            self.stats.late += 1;
        }
        if s.estop && !self.estop {
            core.emergency_stop();
        }
        self.estop = s.estop;
        let count = self.encoder.update(s.raw_count);
        let index = s.index.map(|raw| self.encoder.widen(raw));
        let next_ns = self.base_ns + period_ns;
        core.tick(next_ns, Feedback { count, index });
        self.drain(core, next_ns + period_ns, |_| true);
        self.stats.periods += 1;
        self.base_ns = next_ns;
        self.base_ticks = next_ticks;
    }

    /// An encoder count interrupt at timer tick `now`: while the core wants counts
    /// one by one, hands it the count with its time and queues the steps it makes.
    pub fn encoder<const N: usize>(&mut self, core: &mut MotionCore<N>, now: u32, raw_count: u32) {
        let count = self.encoder.update(raw_count);
        if !core.wants_encoder_edges() {
            return;
        }
        self.stats.sync_counts += 1;
        let t = self.core_time(now);
        core.on_encoder(t, count);
        // Only the gearbox's axes move at a count.
        let Some((long, follower)) = core.gear().map(|g| g.axes()) else { return };
        let horizon = self.base_ns + 2 * u64::from(self.tb.period_ns);
        self.drain(core, horizon, |a| a == long || Some(a) == follower);
    }

    /// The core time (ns) of step-timer tick `now`, which lies within a few periods
    /// of the last period computed (before it while that period has not started).
    #[inline]
    fn core_time(&self, now: u32) -> u64 {
        let dt = now.wrapping_sub(self.base_ticks) as i32;
        if dt >= 0 {
            self.base_ns + self.tb.ns(dt as u32)
        } else {
            self.base_ns.saturating_sub(self.tb.ns(dt.unsigned_abs()))
        }
    }

    /// Queues the edges before `until` (core time) of every axis `which` selects.
    fn drain<const N: usize>(&mut self, core: &mut MotionCore<N>, until: u64, which: impl Fn(usize) -> bool) {
        let (tb, base_ns, base_ticks) = (self.tb, self.base_ns, self.base_ticks);
        let mut edges = 0;
        for ax in &mut self.axes {
            if which(ax.core_axis) {
                edges += ax.drain(core, until, |ev| timed(&tb, base_ns, base_ticks, ev), &mut self.stats.ring_full);
            }
        }
        self.stats.edges = self.stats.edges.wrapping_add(edges);
    }
}

impl EngineAxis {
    /// Queues this axis's edges before `until` (converted by `at`); returns how many.
    #[inline]
    fn drain<const N: usize>(
        &mut self,
        core: &mut MotionCore<N>,
        until: u64,
        at: impl Fn(&StepEvent) -> Timed,
        ring_full: &mut u32,
    ) -> u32 {
        let mut edges = 0;
        let mut next = self.carry.take();
        while let Some(ev) = next.or_else(|| core.next_step(self.core_axis, until)) {
            if self.tx.push(at(&ev)).is_err() {
                self.carry = Some(ev);
                *ring_full += 1;
                break;
            }
            edges += 1;
            next = None;
        }
        edges
    }
}

/// A step event of the core as an edge on the step timer, where core time `base_ns`
/// is tick `base_ticks` (the event may lie before or after it).
#[inline]
fn timed(tb: &TimeBase, base_ns: u64, base_ticks: u32, ev: &StepEvent) -> Timed {
    let at = if ev.t >= base_ns {
        base_ticks.wrapping_add(tb.ticks((ev.t - base_ns).min(u64::from(u32::MAX)) as u32))
    } else {
        base_ticks.wrapping_sub(tb.ticks((base_ns - ev.t).min(u64::from(u32::MAX)) as u32))
    };
    let edge = match ev.kind {
        EdgeKind::Step(_) => Edge::Step,
        EdgeKind::Dir(positive) => Edge::Dir(positive),
    };
    Timed { at, edge }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::playback::{AxisPins, PlayTiming, Player};
    use crate::ring::EdgeRing;
    use motion_core::canon::axis::Pos;
    use motion_core::canon::config::MachineConfig;
    use motion_core::canon::{Action, Canon, CanonSink as _, Endpoint, Feed, FeedMode, Move, SpindleSpeed};
    use std::boxed::Box;
    use std::vec::Vec;

    const MM: i64 = 1_000_000;

    fn rapid(x: i64, z: i64) -> Canon {
        let p = Pos::xz(x, z);
        let m = Move {
            to: Endpoint { machine: p, work: p },
            feed: Feed { mode: FeedMode::PerMin, value: 0 },
            spindle: SpindleSpeed { rpm: None, css: None, max_rpm: 3_000 },
            exact_stop: true,
            independent: false,
        };
        Canon { line: 1, action: Action::Rapid(m) }
    }

    /// Runs a rapid X 40→41 mm (radius, 400 steps/mm), Z 0→−10 mm through engine and player from
    /// timer tick `start`; returns each axis's STEP rise ticks and the core.
    fn run_rapid(start: u32, rings: &'static [EdgeRing<RING>; 2]) -> ([Vec<u32>; 2], Box<MotionCore<64>>) {
        let cfg = MachineConfig::default();
        let mut core: Box<MotionCore<64>> = Box::new(MotionCore::new(&cfg, Pos::xz(40 * MM, 0)).unwrap());
        core.push(rapid(41 * MM, -10 * MM)).unwrap();
        let tb = TimeBase::new(84_000_000, cfg.motion.tick_ns).unwrap();
        let [(tx, rx), (tz, rz)] = [rings[0].split().unwrap(), rings[1].split().unwrap()];
        let timing = |a: usize| PlayTiming::new(core.stepper(a).unwrap().timing(), &tb);
        let mut player = Player::new([
            (rx, AxisPins { step: 6, dir: 10 }, timing(0)),
            (rz, AxisPins { step: 7, dir: 11 }, timing(2)),
        ]);
        let mut engine = Engine::new(tb, [EngineAxis::new(0, tx), EngineAxis::new(2, tz)], start, 0);
        let mut rises = [Vec::new(), Vec::new()];
        let mut now = start;
        for _ in 0..2_000 {
            let end = engine.base_ticks().wrapping_add(tb.period_ticks);
            engine.period(&mut core, Sample { now, raw_count: 0, index: None, estop: false });
            // Play the period as the step interrupt would, waking at each `next`.
            while end.wrapping_sub(now) as i32 > 0 {
                let out = player.run(now, false);
                for (k, bit) in [(0, 1 << 6), (1, 1 << 7)] {
                    if out.bsrr & bit != 0 {
                        rises[k].push(now);
                    }
                }
                now = match out.next {
                    Some(n) if n.wrapping_sub(now) as i32 > 0 && end.wrapping_sub(n) as i32 > 0 => n,
                    Some(n) if n.wrapping_sub(now) as i32 <= 0 => now.wrapping_add(1),
                    _ => end,
                };
            }
            if core.is_idle() && engine.axes().iter().all(|a| a.queued() == 0) {
                break;
            }
        }
        assert_eq!(engine.stats().late, 0);
        assert_eq!(engine.stats().ring_full, 0);
        (rises, core)
    }

    #[test]
    fn a_rapid_plays_every_step_within_the_driver_timing() {
        static RINGS: [EdgeRing<RING>; 2] = [EdgeRing::new(), EdgeRing::new()];
        let (rises, core) = run_rapid(1_000, &RINGS);
        assert_eq!(core.steps(), [16_400, 0, -3_200, 0]);
        assert_eq!(rises[0].len(), 400);
        assert_eq!(rises[1].len(), 3_200);
        // 100 kHz drivers: rises at least 10 us (840 ticks) apart.
        for r in &rises {
            assert!(r.windows(2).all(|w| w[1].wrapping_sub(w[0]) >= 840));
        }
    }

    #[test]
    fn the_same_rapid_across_the_timer_wrap() {
        static RINGS: [EdgeRing<RING>; 2] = [EdgeRing::new(), EdgeRing::new()];
        let (rises, core) = run_rapid(u32::MAX - 5_000_000, &RINGS);
        assert_eq!(core.steps(), [16_400, 0, -3_200, 0]);
        assert_eq!((rises[0].len(), rises[1].len()), (400, 3_200));
        assert!(rises[1].windows(2).all(|w| w[1].wrapping_sub(w[0]) >= 840));
    }

    /// Cuts a 2 mm-lead G32 from Z 5 to Z −40 mm with the spindle at `rpm` (4096
    /// counts per revolution, index every 4096): periods from the period
    /// interrupt, every count through [`Engine::encoder`] at its time, edges played
    /// at theirs. Returns, for each Z step played, the encoder count at that moment.
    fn thread_at(rpm: u32, rings: &'static [EdgeRing<RING>; 1]) -> (Vec<u32>, Box<MotionCore<64>>) {
        use motion_core::canon::{SpindleCommand, SpindleDir, ThreadMove, ThreadSync};
        let cfg = MachineConfig::default();
        let mut core: Box<MotionCore<64>> = Box::new(MotionCore::new(&cfg, Pos::xz(20 * MM, 5 * MM)).unwrap());
        let on = SpindleCommand { dir: SpindleDir::Cw, rpm: Some(rpm), css: None };
        core.push(Canon { line: 1, action: Action::Spindle(on) }).unwrap();
        let p = Pos::xz(20 * MM, -40 * MM);
        let t = ThreadMove {
            to: Endpoint { machine: p, work: p },
            lead: 2 * MM,
            lead_delta: 0,
            start_udeg: 0,
            sync: ThreadSync::Index,
            spindle: SpindleSpeed { rpm: Some(rpm), css: None, max_rpm: 3_000 },
        };
        core.push(Canon { line: 2, action: Action::Thread(t) }).unwrap();
        let tb = TimeBase::new(84_000_000, cfg.motion.tick_ns).unwrap();
        let (tz, rz) = rings[0].split().unwrap();
        let timing = PlayTiming::new(core.stepper(2).unwrap().timing(), &tb);
        let mut player = Player::new([(rz, AxisPins { step: 7, dir: 11 }, timing)]);
        let mut engine = Engine::new(tb, [EngineAxis::new(2, tz)], 0, 0);
        // Ticks per count, as an exact fraction: 84e6 × 60 / (rpm × 4096).
        let (num, den) = (84_000_000u64 * 60, u64::from(rpm) * 4_096);
        let tick_of = |c: u64| (c * num / den) as u32;
        let (mut count, mut played, mut next_period) = (0u64, 0u32, 0u32);
        let mut z_counts = Vec::new();
        while count < 4_096 * 40 {
            let now = tick_of(count);
            if now.wrapping_sub(next_period) as i32 >= 0 {
                let index = (count >= 4_096).then_some((count as u32) & !4_095);
                engine.period(&mut core, Sample { now, raw_count: count as u32, index, estop: false });
                next_period = next_period.wrapping_add(tb.period_ticks);
            } else {
                engine.encoder(&mut core, now, count as u32);
            }
            // Play up to the next count.
            let until = tick_of(count + 1);
            let mut t = played;
            loop {
                let out = player.run(t, false);
                if out.bsrr & (1 << 7) != 0 {
                    // The count in force at tick t.
                    z_counts.push((u64::from(t) * den / num) as u32);
                }
                match out.next {
                    Some(n) if until.wrapping_sub(n) as i32 > 0 => {
                        t = if n.wrapping_sub(t) as i32 > 0 { n } else { t + 1 };
                    }
                    _ => break,
                }
            }
            played = until;
            count += 1;
        }
        (z_counts, core)
    }

    #[test]
    fn a_thread_cut_at_200_and_2000_rpm_steps_at_the_same_counts() {
        static R200: [EdgeRing<RING>; 1] = [EdgeRing::new()];
        static R2000: [EdgeRing<RING>; 1] = [EdgeRing::new()];
        let (slow, core_slow) = thread_at(200, &R200);
        let (fast, core_fast) = thread_at(2_000, &R2000);
        // Both passes end exactly on Z −40 mm (320 steps/mm).
        assert_eq!(core_slow.steps()[2], -40 * 320);
        assert_eq!(core_fast.steps()[2], -40 * 320);
        assert_eq!(slow.len(), 45 * 320);
        assert_eq!(fast.len(), slow.len());
        // Between the ramps (the faster pass ramps longer) each Z step comes at the
        // same spindle angle at both speeds: the same count modulo 4096 (the faster
        // pass starts whole revolutions later), within the count in progress.
        for k in slow.len() / 2..slow.len() * 5 / 6 {
            let d = (i64::from(fast[k]) - i64::from(slow[k])).rem_euclid(4_096);
            assert!(d <= 1 || d == 4_095, "step {k}: count {} at 200 rpm, {} at 2000 rpm", slow[k], fast[k]);
        }
    }

    #[test]
    fn estop_in_the_period_stops_the_core_and_the_player_raises_no_step() {
        static RINGS: [EdgeRing<RING>; 1] = [EdgeRing::new()];
        let cfg = MachineConfig::default();
        let mut core: Box<MotionCore<64>> = Box::new(MotionCore::new(&cfg, Pos::xz(40 * MM, 0)).unwrap());
        core.push(rapid(40 * MM, -100 * MM)).unwrap();
        let tb = TimeBase::new(84_000_000, cfg.motion.tick_ns).unwrap();
        let (tz, rz) = RINGS[0].split().unwrap();
        let timing = PlayTiming::new(core.stepper(2).unwrap().timing(), &tb);
        let mut player = Player::new([(rz, AxisPins { step: 7, dir: 11 }, timing)]);
        let mut engine = Engine::new(tb, [EngineAxis::new(2, tz)], 0, 0);
        let mut now = 0u32;
        let mut rises = 0;
        for k in 0..400 {
            let estop = k >= 200;
            engine.period(&mut core, Sample { now, raw_count: 0, index: None, estop });
            let end = now.wrapping_add(tb.period_ticks);
            while now != end {
                let out = player.run(now, estop);
                if out.bsrr & (1 << 7) != 0 {
                    assert!(!estop, "a STEP rise during e-stop at period {k}");
                    rises += 1;
                }
                now = match out.next {
                    Some(n) if n.wrapping_sub(now) as i32 > 0 && end.wrapping_sub(n) as i32 > 0 => n,
                    Some(n) if n.wrapping_sub(now) as i32 <= 0 => now + 1,
                    _ => end,
                };
            }
        }
        assert!(rises > 1_000, "the rapid moved before the e-stop ({rises} steps)");
        assert!(core.alarm().is_some());
        assert!(core.is_idle());
    }
}

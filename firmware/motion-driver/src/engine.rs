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
//! While axes are locked to the spindle, [`Engine::encoder`] runs when the encoder
//! count reaches one of the two compare values [`Engine::window`] gives — the counts
//! at which the core's gearbox next makes a step, either way — not at every count
//! (same interrupt priority as the period, so they never preempt each other and the
//! rings keep a single producer): it hands the count and its time to the core and
//! queues the steps the gearbox makes, due at once.
//!
//! The e-stop input is read in the period: its rising level calls the core's
//! `emergency_stop` (the step player already raises no STEP pin while it is active).

use motion_core::motion::{Feedback, MotionCore};
use motion_core::stepgen::{AxisStepGen, EdgeKind, StepEvent};

use crate::encoder::{Encoder, Window};
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
    /// Encoder readings handed to the core at a due count (compare interrupts that
    /// found work; the counts the gearbox skipped are not among them).
    pub sync_counts: u32,
    /// Of those, the ones on which an axis moved.
    pub sync_moves: u32,
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

    /// The motion core's axis this channel drives.
    pub fn core_axis(&self) -> usize {
        self.core_axis
    }
}

/// The motion interrupt's state for `A` driven axes.
pub struct Engine<const A: usize> {
    tb: TimeBase,
    axes: [EngineAxis; A],
    /// For each core axis (bit `i` of what [`MotionCore::on_encoder`] moved), its
    /// index in `axes` (`u8::MAX`: not driven): the count interrupt visits only
    /// the axes that moved.
    slot: [u8; 8],
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
        let mut slot = [u8::MAX; 8];
        for (i, ax) in axes.iter().enumerate() {
            if let (Some(s), Ok(i)) = (slot.get_mut(ax.core_axis), u8::try_from(i)) {
                *s = i;
            }
        }
        Engine {
            tb,
            axes,
            slot,
            base_ns: 0,
            base_ticks: start,
            encoder: Encoder::new(raw_count),
            estop: false,
            stats: EngineStats::default(),
        }
    }

    /// The same engine reading an encoder timer of `bits` bits (16 or 32; 32 by
    /// default) whose current reading is `raw_count`.
    pub fn with_encoder_bits(mut self, raw_count: u32, bits: u32) -> Self {
        self.encoder = Encoder::with_bits(raw_count, bits).with_count(self.encoder.count());
        self
    }

    /// Makes timer tick `start` the start of the period playing and `raw_count` the
    /// encoder's current reading (once, when the timers start, before the first
    /// period).
    pub fn set_origin(&mut self, start: u32, raw_count: u32) {
        self.base_ticks = start;
        self.encoder = self.encoder.with_raw(raw_count);
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

    /// Whether channel `i` may drive the core's axis `core_axis` now: it already
    /// does, or its edges have all been played.
    pub fn can_set_core_axis(&self, i: usize, core_axis: usize) -> bool {
        self.axes.get(i).is_some_and(|ax| ax.core_axis == core_axis || (ax.tx.is_empty() && ax.carry.is_none()))
    }

    /// Makes channel `i` drive the core's axis `core_axis` (a board's third channel
    /// is C on a lathe, Y on a mill: `$311`) if [`Self::can_set_core_axis`];
    /// returns whether it does.
    pub fn set_core_axis(&mut self, i: usize, core_axis: usize) -> bool {
        if !self.can_set_core_axis(i, core_axis) {
            return false;
        }
        if let Some(ax) = self.axes.get_mut(i) {
            ax.core_axis = core_axis;
        }
        true
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

    /// The encoder compare interrupt at step-timer tick `now`, the encoder reading
    /// `raw_count`: the counts up to it go to the core with that time, and the steps
    /// they make are queued, due at once. Returns whether any edge was queued (the
    /// step interrupt should run now). Set the compares from [`Engine::window`]
    /// afterwards.
    pub fn encoder<const N: usize>(&mut self, core: &mut MotionCore<N>, now: u32, raw_count: u32) -> bool {
        let count = self.encoder.update(raw_count);
        self.stats.sync_counts += 1;
        let t = self.core_time(now);
        let moved = core.on_encoder(t, count);
        if moved == 0 {
            return false;
        }
        self.stats.sync_moves += 1;
        // Only the axes the count moved (the gearbox's, C in polygon turning); an
        // edge due now is at tick `now` (no conversion).
        let horizon = self.base_ns + 2 * u64::from(self.tb.period_ns);
        let (mut edges, mut bits) = (0, moved);
        while bits != 0 {
            let core_axis = bits.trailing_zeros() as usize;
            bits &= bits - 1;
            let Some(ax) = self.slot.get(core_axis).and_then(|&i| self.axes.get_mut(usize::from(i))) else {
                continue;
            };
            if ax.carry.is_some() {
                // The ring was full before: the general way.
                let (tb, base_ns, base_ticks) = (self.tb, self.base_ns, self.base_ticks);
                let at = |ev: &StepEvent| timed(&tb, base_ns, base_ticks, ev);
                edges += ax.drain(core, horizon, at, &mut self.stats.ring_full);
                continue;
            }
            while let Some(ev) = core.next_sync_step(ax.core_axis, horizon) {
                let at = if ev.t == t { now } else { timed(&self.tb, self.base_ns, self.base_ticks, &ev).at };
                if ax.tx.push(Timed { at, edge: edge_of(&ev) }).is_err() {
                    ax.carry = Some(ev);
                    self.stats.ring_full += 1;
                    break;
                }
                edges += 1;
                if core.stepper(ax.core_axis).is_none_or(AxisStepGen::settled) {
                    break;
                }
            }
        }
        self.stats.edges = self.stats.edges.wrapping_add(edges);
        edges != 0
    }

    /// The encoder timer's compare values: the counts at which the core next needs
    /// the encoder ([`MotionCore::encoder_due`]), around the last reading; off
    /// while nothing follows the spindle. After the period and after each
    /// [`Engine::encoder`]; then check [`Engine::reached`] with a fresh reading.
    pub fn window<const N: usize>(&mut self, core: &mut MotionCore<N>) -> Window {
        match core.encoder_due() {
            Some(due) => self.encoder.window(due),
            None => Window::OFF,
        }
    }

    /// Whether the encoder reading `raw_count`, taken after the compares were set
    /// to `w`, has already reached one of them: then [`Engine::encoder`] must run
    /// again (the counter went past the compare before it was set).
    /// (Always inlined: the interrupt calls it in the size-built firmware crate.)
    #[inline(always)]
    pub fn reached(&self, w: &Window, raw_count: u32) -> bool {
        self.encoder.reached(w, raw_count)
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

    /// Queues the edges before `until` (core time) of every axis `which` selects;
    /// returns how many.
    fn drain<const N: usize>(&mut self, core: &mut MotionCore<N>, until: u64, which: impl Fn(usize) -> bool) -> u32 {
        let (tb, base_ns, base_ticks) = (self.tb, self.base_ns, self.base_ticks);
        let mut edges = 0;
        for ax in &mut self.axes {
            if which(ax.core_axis) {
                edges += ax.drain(core, until, |ev| timed(&tb, base_ns, base_ticks, ev), &mut self.stats.ring_full);
            }
        }
        self.stats.edges = self.stats.edges.wrapping_add(edges);
        edges
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
    Timed { at, edge: edge_of(ev) }
}

/// The pin edge of a step event.
#[inline]
fn edge_of(ev: &StepEvent) -> Edge {
    match ev.kind {
        EdgeKind::Step(_) => Edge::Step,
        EdgeKind::Dir(positive) => Edge::Dir(positive),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::playback::{AxisPins, PlayTiming, Player};
    use crate::ring::EdgeRing;
    use motion_core::canon::axis::Pos;
    use motion_core::canon::config::MachineConfig;
    use motion_core::canon::{Action, Canon, CanonSink as _, Endpoint, Feed, FeedMode, Move, SpindleDir, SpindleSpeed};
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

    /// How the rig hands the encoder to the engine.
    #[derive(Clone, Copy, Debug, PartialEq)]
    enum Delivery {
        /// Every count to [`Engine::encoder`] (the firmware before issue 22; the
        /// reference).
        EveryCount,
        /// The board's way: a `bits`-bit encoder timer starting at raw `start`, whose
        /// two compare values [`Engine::window`] sets; the count interrupt runs when
        /// the counter becomes equal to an enabled one (and again while a fresh
        /// reading has reached one).
        Compare { bits: u32, start: u32 },
    }

    /// The encoder timer of [`Delivery::Compare`].
    struct EncoderTimer {
        mask: u32,
        cnt: u32,
        window: Window,
        pending: bool,
    }

    impl EncoderTimer {
        /// One count up or down; a match with an enabled compare pends the interrupt.
        fn count(&mut self, up: bool) {
            self.cnt = if up { self.cnt.wrapping_add(1) } else { self.cnt.wrapping_sub(1) } & self.mask;
            if self.window.up == Some(self.cnt) || self.window.down == Some(self.cnt) {
                self.pending = true;
            }
        }

        /// Sets the compares (the flags cleared first, as the interrupt does);
        /// returns whether the count is already past one (run the interrupt again).
        fn arm<const A: usize>(&mut self, engine: &Engine<A>, w: Window) -> bool {
            self.window = w;
            self.pending = false;
            engine.reached(&w, self.cnt)
        }
    }

    /// A run through engine and player: STEP rises per driven axis (tick and the
    /// widened encoder count at that tick), count interrupts that ran, counts, the
    /// core.
    struct SyncRun {
        rises: Vec<Vec<(u32, i64)>>,
        interrupts: u32,
        counts: u64,
        core: Box<MotionCore<64>>,
    }

    /// The count interrupt of the board: hands the reading over, sets the compares,
    /// runs again while the count is already past one.
    fn count_isr(engine: &mut Engine<2>, core: &mut MotionCore<64>, timer: &mut EncoderTimer, now: u32) -> u32 {
        for runs in 1..100 {
            engine.encoder(core, now, timer.cnt);
            let w = engine.window(core);
            if !timer.arm(engine, w) {
                return runs;
            }
        }
        panic!("the count interrupt does not end");
    }

    /// Runs `actions` from X`x0` Z`z0` (mm, radius) with engine and player on the
    /// default machine, driven axes X and Z. The spindle turns at the speed and in
    /// the direction the core commands (M03 counts up), changing at once, 4096
    /// counts a revolution with an index every 4096. Periods come from the period
    /// interrupt, counts as `delivery` says; every edge is played at its time.
    fn run_sync(actions: &[Canon], x0: i64, z0: i64, delivery: Delivery) -> SyncRun {
        let cfg = MachineConfig::default();
        let mut core: Box<MotionCore<64>> = Box::new(MotionCore::new(&cfg, Pos::xz(x0 * MM, z0 * MM)).unwrap());
        for a in actions {
            core.push(*a).unwrap();
        }
        let tb = TimeBase::new(84_000_000, cfg.motion.tick_ns).unwrap();
        let rings: &'static [EdgeRing<RING>; 2] = Box::leak(Box::new([EdgeRing::new(), EdgeRing::new()]));
        let [(tx, rx), (tz, rz)] = [rings[0].split().unwrap(), rings[1].split().unwrap()];
        let timing = |a: usize| PlayTiming::new(core.stepper(a).unwrap().timing(), &tb);
        let mut player = Player::new([
            (rx, AxisPins { step: 6, dir: 10 }, timing(0)),
            (rz, AxisPins { step: 7, dir: 11 }, timing(2)),
        ]);
        let (bits, start) = match delivery {
            Delivery::EveryCount => (32, 0),
            Delivery::Compare { bits, start } => (bits, start),
        };
        let mask = u32::MAX >> (32 - bits);
        let mut timer = EncoderTimer { mask, cnt: start & mask, window: Window::OFF, pending: false };
        let mut engine =
            Engine::new(tb, [EngineAxis::new(0, tx), EngineAxis::new(2, tz)], 0, 0).with_encoder_bits(timer.cnt, bits);
        let (mut rises, mut interrupts, mut counts) = (std::vec![Vec::new(), Vec::new()], 0, 0);
        let (mut now, mut next_period, mut count) = (0u32, 0u32, 0i64);
        let mut index: Option<u32> = None;
        // Time of the next count, ticks (f64: the speed changes as commanded).
        let mut next_count = f64::INFINITY;
        let ticks_per_count = |core: &MotionCore<64>| {
            let (dir, rpm) = core.spindle_output();
            (dir != SpindleDir::Stop && rpm > 0).then(|| 84e6 * 60.0 / (f64::from(rpm) * 4_096.0))
        };
        for _ in 0..50_000_000 {
            let period_due = f64::from(next_period) <= next_count;
            let t = if period_due { next_period } else { next_count as u32 };
            // Play up to `t`, each rise with the count in force.
            loop {
                let out = player.run(now, false);
                for (k, bit) in [(0, 1 << 6), (1, 1 << 7)] {
                    if out.bsrr & bit != 0 {
                        rises[k].push((now, count));
                    }
                }
                match out.next {
                    Some(n) if t.wrapping_sub(n) as i32 > 0 => {
                        now = if n.wrapping_sub(now) as i32 > 0 { n } else { now + 1 };
                    }
                    _ => break,
                }
            }
            now = t;
            if period_due {
                let s = Sample { now, raw_count: timer.cnt, index, estop: false };
                engine.period(&mut core, s);
                next_period = next_period.wrapping_add(tb.period_ticks);
                if matches!(delivery, Delivery::Compare { .. }) {
                    let w = engine.window(&mut core);
                    if timer.arm(&engine, w) {
                        interrupts += count_isr(&mut engine, &mut core, &mut timer, now);
                    }
                }
                if next_count.is_infinite() {
                    next_count = ticks_per_count(&core).map_or(f64::INFINITY, |d| f64::from(now) + d);
                }
                if core.is_idle() && core.ended() {
                    break;
                }
                continue;
            }
            let up = core.spindle_output().0 == SpindleDir::Cw;
            count += if up { 1 } else { -1 };
            counts += 1;
            timer.count(up);
            if count.rem_euclid(4_096) == 0 {
                index = Some(timer.cnt);
            }
            match delivery {
                Delivery::EveryCount => {
                    interrupts += 1;
                    engine.encoder(&mut core, now, timer.cnt);
                }
                Delivery::Compare { .. } if timer.pending => {
                    interrupts += count_isr(&mut engine, &mut core, &mut timer, now);
                }
                Delivery::Compare { .. } => {}
            }
            next_count = ticks_per_count(&core).map_or(f64::INFINITY, |d| next_count + d);
        }
        assert!(core.ended(), "the program did not end: {:?}", core.state());
        assert_eq!(core.alarm(), None);
        assert_eq!(engine.stats().ring_full, 0);
        SyncRun { rises, interrupts, counts, core }
    }

    fn spindle_on(rpm: u32) -> Canon {
        use motion_core::canon::SpindleCommand;
        Canon { line: 1, action: Action::Spindle(SpindleCommand { dir: SpindleDir::Cw, rpm: Some(rpm), css: None }) }
    }

    /// A G32 from where the axes stand to X`x` Z`z` mm (radius) at `lead_um`.
    fn g32(x: i64, z: i64, lead_um: i64, rpm: u32) -> Canon {
        use motion_core::canon::{ThreadMove, ThreadSync};
        let p = Pos::xz(x * MM, z * MM);
        let t = ThreadMove {
            to: Endpoint { machine: p, work: p },
            lead: lead_um * 1_000,
            lead_delta: 0,
            start_udeg: 0,
            sync: ThreadSync::Index,
            spindle: SpindleSpeed { rpm: Some(rpm), css: None, max_rpm: 3_000 },
        };
        Canon { line: 2, action: Action::Thread(t) }
    }

    fn the_end() -> Canon {
        Canon { line: 9, action: Action::End { rewind: false } }
    }

    /// A G32 Z 5 → −40 mm at `lead_um` and `rpm`, both ways; asserts the compare way
    /// steps at exactly the ticks (so the counts) the every-count way does, and
    /// returns the count at each Z step and the count interrupts per count.
    fn thread_both_ways(rpm: u32, lead_um: i64, start: u32, bits: u32) -> (Vec<i64>, f64) {
        let actions = [spindle_on(rpm), g32(20, -40, lead_um, rpm), the_end()];
        let every = run_sync(&actions, 20, 5, Delivery::EveryCount);
        let compare = run_sync(&actions, 20, 5, Delivery::Compare { bits, start });
        assert_eq!(compare.core.steps()[2], -40 * 320);
        assert_eq!(every.rises, compare.rises, "{rpm} rpm: steps differ from every count's");
        let ratio = f64::from(compare.interrupts) / compare.counts as f64;
        (compare.rises[1].iter().map(|r| r.1).collect(), ratio)
    }

    #[test]
    fn the_compare_steps_at_the_counts_every_count_would_and_the_phase_holds_200_to_3000_rpm() {
        // 2 mm at 200 and 2000 rpm; 1.5 mm (the most the default Z allows at 3000:
        // 4,950 mm/min with the 10 % margin) at 200 and 3000, the counter of the
        // faster pass wrapping on the way.
        for (lead, slow_rpm, fast_rpm) in [(2_000, 200, 2_000), (1_500, 200, 3_000)] {
            let (slow, r_slow) = thread_both_ways(slow_rpm, lead, 0, 32);
            let (fast, r_fast) = thread_both_ways(fast_rpm, lead, u32::MAX - 70_000, 32);
            assert_eq!(slow.len(), 45 * 320);
            assert_eq!(fast.len(), slow.len());
            // Between the ramps (the faster pass ramps longer) each Z step comes at
            // the same spindle angle at both speeds: the same count modulo 4096 (the
            // faster pass starts whole revolutions later), within the count in
            // progress.
            for k in slow.len() / 2..slow.len() * 5 / 6 {
                let d = (fast[k] - slow[k]).rem_euclid(4_096);
                assert!(
                    d <= 1 || d == 4_095,
                    "{lead} µm, step {k}: count {} at {slow_rpm}, {} at {fast_rpm}",
                    slow[k],
                    fast[k]
                );
            }
            // About one interrupt a step (a step every 6.4 counts at 2 mm, 8.5 at
            // 1.5 mm; 14,405 for 14,400 steps), not one a count.
            for r in [r_slow, r_fast] {
                assert!(r < 0.2, "{lead} µm: {r} interrupts a count");
            }
        }
    }

    #[test]
    fn a_16_bit_encoder_timer_across_its_wrap_steps_the_same() {
        let (z, ratio) = thread_both_ways(1_200, 2_000, 60_000, 16);
        assert_eq!(z.len(), 45 * 320);
        assert!(ratio < 0.2);
    }

    #[test]
    fn a_rigid_tap_reverses_with_the_spindle_through_both_compares() {
        use motion_core::canon::TapMove;
        let tap = |line: u32, z: i64, dir: SpindleDir| {
            let p = Pos::xz(0, z * MM);
            let spindle = SpindleSpeed { rpm: Some(800), css: None, max_rpm: 3_000 };
            let t = TapMove { to: Endpoint { machine: p, work: p }, lead: 1_500_000, dir, spindle };
            Canon { line, action: Action::Tap(t) }
        };
        let actions = [tap(2, -20, SpindleDir::Cw), tap(3, 5, SpindleDir::Ccw), the_end()];
        let every = run_sync(&actions, 0, 5, Delivery::EveryCount);
        // 25 mm in and out: 8000 Z steps each way.
        assert_eq!(every.rises[1].len(), 16_000);
        for (bits, start) in [(32, 5), (16, 65_530)] {
            let compare = run_sync(&actions, 0, 5, Delivery::Compare { bits, start });
            assert_eq!(every.rises, compare.rises, "{bits}-bit timer");
            assert_eq!(compare.core.steps()[2], 5 * 320, "back at the start");
            // One interrupt a step (a step every 8.5 counts at 1.5 mm).
            assert!(compare.interrupts <= 16_010, "{} interrupts", compare.interrupts);
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

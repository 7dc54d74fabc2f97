//! The motion core: canonical actions in, timed step events and spindle commands
//! out. It is the interpreter's [`CanonSink`] (a full look-ahead queue is
//! back-pressure) and runs the layers below it:
//! [`planner`](crate::planner) → [`interpolator`](crate::interpolator) →
//! [`stepgen`](crate::stepgen), with [`sync`](crate::sync) driving the axes from
//! the spindle encoder during threads and rigid taps.
//!
//! Time is always an argument: [`MotionCore::tick`] runs one interpolation period
//! starting at `now`, [`MotionCore::on_encoder`] takes an encoder count with its
//! time, [`MotionCore::next_step`] hands out the step events of the period. The
//! firmware calls them from its timer interrupts, the simulator from its event
//! loop; both run exactly this code.
//!
//! Commands between blocks run when the motion before them has finished (M03 before
//! the cut starts, M05 after it ends); a cutting block starting from rest waits
//! until the spindle is at its commanded speed. Feed hold brakes on the path and
//! resumes from there; feed and rapid override apply per period; single block
//! stops at the end of every block. Feed hold, override and single block do not act
//! inside a locked thread or tap sequence (2.17.1 notes 3–4, 2.22.2 note 4).
//! Reset and emergency stop brake the axes (a thread pass brakes along its line,
//! 2.17.1 note 5) and drop the queue.

mod locked;
pub mod polygon;
pub mod spindle;

pub use spindle::Spindle;

use crate::alarm::{Alarm, AlarmKind};
use crate::axis::{AXIS_COUNT, Axis, Pos};
use crate::canon::{Action, Canon, CanonSink, Full, SpindleDir};
use crate::config::{MachineConfig, MotionConfig};

use crate::fixed::{STEP_FRAC, round_steps};
use crate::interpolator::{Interpolator, Live, Status};
use crate::planner::{Block, BlockKind, Command, FeedSpec, Item, MotionParams, Planner, PushError};
use crate::stepgen::{AxisStepGen, StepEvent};
use crate::sync::Gear;

/// The look-ahead depth the firmware and the simulator use.
pub const QUEUE: usize = 64;

/// What the machine reports to the motion core each period.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Feedback {
    /// Spindle encoder count (quadrature-decoded, cumulative).
    pub count: i64,
    /// The count latched at the last index pulse, if one has been seen.
    pub index: Option<i64>,
}

/// Something the machine must do or know, in stream order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EventKind {
    /// Spindle direction and commanded speed changed by a command.
    Spindle {
        /// Direction.
        dir: SpindleDir,
        /// rev/min.
        rpm: u32,
    },
    /// Index the turret.
    Tool {
        /// Station.
        tool: u16,
        /// Offset number.
        offset: u16,
    },
    /// Switch the output of an M code.
    Aux {
        /// M number.
        m: u16,
    },
    /// M00/M01 reached: waiting for cycle start.
    Stop {
        /// M01.
        optional: bool,
    },
    /// A machining centre's M06 reached (the motion before it has finished): the
    /// spindle is stopped and the core waits for cycle start as at M00 — the
    /// operator's after a change by hand (`manual`), the controller's when the
    /// tool changer reports done.
    ToolChange(crate::canon::ToolChange),
    /// M02/M30 reached.
    End {
        /// M30.
        rewind: bool,
    },
    /// The queue ran empty while the program was still streaming.
    Starved,
    /// A motion alarm; the axes are stopping.
    Alarm(Alarm),
}

/// An event, when and from which line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Event {
    /// Time of the period it happened in, ns.
    pub t: u64,
    /// Source line.
    pub line: u32,
    /// What.
    pub kind: EventKind,
}

/// Counters for reports and tests.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Interpolation periods run.
    pub ticks: u64,
    /// Motion blocks taken from the queue.
    pub blocks: u64,
    /// Times the queue ran empty while streaming.
    pub starvations: u32,
    /// Most entries queued at once.
    pub max_queued: usize,
    /// Events dropped because nobody collected them.
    pub lost_events: u32,
    /// Periods whose speed the interpolator's braking test allowed no candidate
    /// for (0 unless a block was entered too fast to brake for its end).
    pub overruns: u32,
}

/// Where the core is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum State {
    /// Between entries: takes the next one.
    Idle,
    /// The interpolator runs a block.
    Moving,
    /// Stopped on the path by feed hold; cycle start resumes.
    Held,
    /// A cutting block waits for the spindle to reach its speed.
    WaitSpindle {
        /// Since when.
        since: u64,
    },
    /// Dwelling.
    Dwell {
        /// Until when.
        until: u64,
    },
    /// M00/M01 or single block: waiting for cycle start.
    Stopped,
    /// A thread pass waits for the spindle index and its start count.
    SyncWait {
        /// Since when.
        since: u64,
    },
    /// A thread or tap block runs locked to the spindle.
    Locked,
    /// Reset, emergency stop or alarm: braking, then the queue is dropped.
    Stopping,
    /// M02/M30 done.
    Ended,
}

/// The motion core with a look-ahead queue of `N` entries.
#[derive(Clone, Debug)]
pub struct MotionCore<const N: usize> {
    p: MotionParams,
    mc: MotionConfig,
    planner: Planner<N>,
    interp: Interpolator,
    steppers: [AxisStepGen; AXIS_COUNT],
    spindle: Spindle,
    /// The gearbox while axes are locked to the spindle.
    gear: Option<Gear>,
    /// Polygon turning: C locked to the spindle (G51.2).
    polygon: polygon::Polygon,
    /// The spindle-locked block running (or whose sequence is open, for taps).
    locked: Option<Block>,
    /// Thread legs taken from the queue since the pass started.
    legs_taken: u32,
    /// The largest lead (nm/rev) the running pass's ramps were sized for.
    ramp_lead: i64,
    /// A block waiting for the spindle or the index.
    pending: Option<Block>,
    state: State,
    /// A cutting block from rest must wait for the spindle.
    spindle_wait: bool,
    feed_ovr: u64,
    rapid_ovr: u64,
    /// Spindle override, %; not applied while axes are locked to the spindle.
    spindle_ovr: u16,
    /// The spindle's top speed (the override never commands more).
    spindle_max: u32,
    hold: bool,
    single_block: bool,
    events: heapless::Deque<Event, 32>,
    alarm: Option<Alarm>,
    stats: Stats,
    now: u64,
    /// Actions have arrived and no M02/M30 ran since.
    streaming: bool,
    starved: bool,
    line: u32,
    /// Machine minus work coordinates of the block running or last run.
    offset_memory: Pos,
    css_phase: u8,
    /// The encoder count last seen to change, and when (the encoder watch).
    watch_count: i64,
    watch_since: u64,
    /// The spindle a tool change by hand stopped: restarted at cycle start (the
    /// next cut waits for it to be at speed).
    resume_spindle: Option<(SpindleDir, u32)>,
}

/// Periods between two G96 speed updates.
const CSS_PERIODS: u8 = 4;

impl<const N: usize> MotionCore<N> {
    /// A core for machine `cfg` with the axes at `pos` (machine, nm).
    pub fn new(cfg: &MachineConfig, pos: Pos) -> Result<Self, AlarmKind> {
        let p = MotionParams::new(cfg)?;
        let steps: [i64; AXIS_COUNT] = core::array::from_fn(|i| p.scale[i].steps(pos.0[i]));
        Ok(MotionCore {
            p,
            mc: cfg.motion,
            planner: Planner::new(pos),
            interp: Interpolator::new(steps),
            steppers: core::array::from_fn(|i| AxisStepGen::new(p.timing[i], steps[i])),
            spindle: Spindle::new(&p, cfg.motion.speed_window_ticks),
            gear: None,
            polygon: polygon::Polygon::default(),
            locked: None,
            legs_taken: 0,
            ramp_lead: 0,
            pending: None,
            state: State::Idle,
            spindle_wait: false,
            feed_ovr: 256,
            rapid_ovr: 256,
            spindle_ovr: 100,
            spindle_max: cfg.spindle.max_rpm,
            hold: false,
            single_block: false,
            events: heapless::Deque::new(),
            alarm: None,
            stats: Stats::default(),
            now: 0,
            streaming: false,
            starved: false,
            line: 0,
            offset_memory: Pos::ZERO,
            css_phase: 0,
            watch_count: 0,
            watch_since: 0,
            resume_spindle: None,
        })
    }

    /// Rebuilds the core for machine `cfg` with the axes where they are: what
    /// `*self = MotionCore::new(cfg, self.position())?` does, field by field in
    /// place, so no second ~21 KB core is built on the stack (the board rebuilds
    /// its core when a setting changes, under the controller's deepest frames).
    /// On an error the core is left as it was.
    pub fn rebuild(&mut self, cfg: &MachineConfig) -> Result<(), AlarmKind> {
        let pos = self.position();
        let p = MotionParams::new(cfg)?;
        let steps: [i64; AXIS_COUNT] = core::array::from_fn(|i| p.scale[i].steps(pos.0[i]));
        // Destructured so that a new field cannot be forgotten here.
        let MotionCore {
            p: params,
            mc,
            planner,
            interp,
            steppers,
            spindle,
            gear,
            polygon,
            locked,
            legs_taken,
            ramp_lead,
            pending,
            state,
            spindle_wait,
            feed_ovr,
            rapid_ovr,
            spindle_ovr,
            spindle_max,
            hold,
            single_block,
            events,
            alarm,
            stats,
            now,
            streaming,
            starved,
            line,
            offset_memory,
            css_phase,
            watch_count,
            watch_since,
            resume_spindle,
        } = self;
        *params = p;
        *mc = cfg.motion;
        *planner = Planner::new(pos);
        *interp = Interpolator::new(steps);
        *steppers = core::array::from_fn(|i| AxisStepGen::new(p.timing[i], steps[i]));
        *spindle = Spindle::new(&p, cfg.motion.speed_window_ticks);
        (*gear, *locked, *pending, *alarm) = (None, None, None, None);
        *polygon = polygon::Polygon::default();
        (*legs_taken, *ramp_lead, *state, *spindle_wait) = (0, 0, State::Idle, false);
        (*feed_ovr, *rapid_ovr, *spindle_ovr, *spindle_max) = (256, 256, 100, cfg.spindle.max_rpm);
        (*hold, *single_block, *streaming, *starved) = (false, false, false, false);
        events.clear();
        (*stats, *now, *line, *offset_memory) = (Stats::default(), 0, 0, Pos::ZERO);
        (*css_phase, *watch_count, *watch_since, *resume_spindle) = (0, 0, 0, None);
        Ok(())
    }

    /// The machine in motion units.
    pub fn params(&self) -> &MotionParams {
        &self.p
    }

    /// Where the core is.
    pub fn state(&self) -> State {
        self.state
    }

    /// The alarm in force, if any (cleared by [`MotionCore::reset`]).
    pub fn alarm(&self) -> Option<Alarm> {
        self.alarm
    }

    /// Counters.
    pub fn stats(&self) -> Stats {
        Stats { blocks: self.planner.taken(), overruns: self.interp.overruns(), ..self.stats }
    }

    /// The interpolator's commanded position at the end of the last period, Q16
    /// steps per axis (what the step generators follow).
    pub fn commanded(&self) -> [i64; AXIS_COUNT] {
        *self.interp.position()
    }

    /// Source line of the block running or last run.
    pub fn line(&self) -> u32 {
        self.line
    }

    /// Entries queued.
    pub fn queued(&self) -> usize {
        self.planner.len()
    }

    /// Nothing queued, nothing moving, every step issued.
    pub fn is_idle(&self) -> bool {
        matches!(self.state, State::Idle | State::Ended)
            && self.planner.is_empty()
            && self.gear.is_none()
            && self.steppers.iter().all(AxisStepGen::settled)
    }

    /// M02/M30 has run.
    pub fn ended(&self) -> bool {
        self.state == State::Ended
    }

    /// Polygon turning (G51.2): the C steps the tool spindle has turned since it
    /// locked to the spindle; `None` when C is not locked.
    pub fn polygon_steps(&self) -> Option<i64> {
        self.polygon.gear.map(|g| g.steps())
    }

    /// Polygon turning (G51.2): the raw encoder count (an index) C locks at and
    /// C's step position there; `None` when it is off.
    pub fn polygon_lock(&self) -> Option<(i64, i64)> {
        self.polygon.gear.map(|g| (g.origin(), self.polygon.base))
    }

    /// Steps issued per axis (the axes' real positions).
    pub fn steps(&self) -> [i64; AXIS_COUNT] {
        self.steppers.each_ref().map(AxisStepGen::position)
    }

    /// Where the axes are, machine coordinates, nm.
    pub fn position(&self) -> Pos {
        let s = self.steps();
        Pos(core::array::from_fn(|i| if self.p.limits[i].present { self.p.scale[i].nm(s[i]) } else { 0 }))
    }

    /// Machine minus work coordinates of the block running (or last run).
    pub fn work_offset(&self) -> Pos {
        self.offset_memory
    }

    /// Commanded spindle direction and speed (rev/min) for the spindle drive.
    pub fn spindle_output(&self) -> (SpindleDir, u32) {
        (self.spindle.dir, self.spindle_target())
    }

    /// The speed the drive is told: the command times the spindle override, at
    /// most the spindle's top speed (the command alone while locked).
    fn spindle_target(&self) -> u32 {
        let pct = self.spindle_pct();
        if pct == 100 {
            return self.spindle.rpm;
        }
        let rpm = u64::from(self.spindle.rpm) * u64::from(pct) / 100;
        u32::try_from(rpm).unwrap_or(u32::MAX).min(self.spindle_max.max(self.spindle.rpm))
    }

    /// The spindle override in effect: 100 % while a thread or tap is locked to
    /// the spindle or waiting to start (threading runs at the programmed speed).
    fn spindle_pct(&self) -> u16 {
        let locked = self.gear.is_some() || matches!(self.state, State::SyncWait { .. } | State::Locked);
        if locked { 100 } else { self.spindle_ovr }
    }

    /// Whether the measured speed is within the at-speed band of the speed the
    /// drive is told.
    fn spindle_at_speed(&self) -> bool {
        self.spindle.at_speed_of(self.spindle_target(), self.mc.at_speed_pct)
    }

    /// The spindle as measured.
    pub fn spindle(&self) -> &Spindle {
        &self.spindle
    }

    /// The gearbox, while axes are locked to the spindle.
    pub fn gear(&self) -> Option<&Gear> {
        self.gear.as_ref()
    }

    /// The next event for the machine.
    pub fn pop_event(&mut self) -> Option<Event> {
        self.events.pop_front()
    }

    /// Feed hold: brake on the path (at the end of a locked sequence).
    pub fn feed_hold(&mut self) {
        self.hold = true;
    }

    /// Cycle start: resume after feed hold, M00/M01 or a single-block stop.
    pub fn cycle_start(&mut self) {
        self.hold = false;
        if self.state == State::Stopped {
            self.state = State::Idle;
            if let Some((dir, rpm)) = self.resume_spindle.take() {
                self.set_spindle(dir, rpm);
                self.emit(self.line, EventKind::Spindle { dir, rpm: self.spindle.rpm });
            }
        }
    }

    /// Feed override, 0–200 %.
    pub fn set_feed_override(&mut self, pct: u16) {
        self.feed_ovr = u64::from(pct.min(200)) * 256 / 100;
    }

    /// Spindle override, 50–200 % (not inside threads and rigid taps, which run
    /// at the programmed speed).
    pub fn set_spindle_override(&mut self, pct: u16) {
        self.spindle_ovr = pct.clamp(50, 200);
    }

    /// Rapid override, 0–100 %.
    pub fn set_rapid_override(&mut self, pct: u16) {
        self.rapid_ovr = u64::from(pct.min(100)) * 256 / 100;
    }

    /// Single block on or off.
    pub fn set_single_block(&mut self, on: bool) {
        self.single_block = on;
    }

    /// Reset: clears the alarm, brakes the axes, stops the spindle, drops the queue.
    pub fn reset(&mut self) {
        self.alarm = None;
        self.resume_spindle = None;
        self.begin_stop();
        if self.interp.segment().is_none() && self.gear.is_none() {
            // Nothing to brake: at rest the reset is done at once (a status report
            // right after it shows Idle, not a stop in progress).
            self.run_stopping(&mut false);
        }
    }

    /// Path speed of the last interpolation period, nm/min (0 at rest; for the
    /// status report's `FS:`).
    pub fn path_speed(&self) -> i64 {
        let per_min = u128::from(self.interp.speed()) * 60_000_000_000 / 256 / u128::from(self.p.tick_ns.max(1));
        i64::try_from(per_min).unwrap_or(i64::MAX)
    }

    /// Redefines where the axes are (homing, setting the reference position): the
    /// machine position becomes `pos` without any motion. Only at rest: `false`
    /// (nothing changed) while anything is queued or moving.
    pub fn set_position(&mut self, pos: Pos) -> bool {
        if !self.is_idle() {
            return false;
        }
        let steps: [i64; AXIS_COUNT] = core::array::from_fn(|i| self.p.scale[i].steps(pos.0[i]));
        self.planner.clear(pos);
        self.interp = Interpolator::new(steps);
        let p = &self.p;
        self.steppers = core::array::from_fn(|i| AxisStepGen::new(p.timing[i], steps[i]));
        true
    }

    /// Emergency stop: as reset, with alarm 4509.
    pub fn emergency_stop(&mut self) {
        self.raise(AlarmKind::EmergencyStop);
    }

    /// The next step or direction event of `axis` before `until`, if any.
    pub fn next_step(&mut self, axis: usize, until: u64) -> Option<StepEvent> {
        self.steppers.get_mut(axis)?.next_event(until)
    }

    /// The step generator of `axis`.
    pub fn stepper(&self, axis: usize) -> Option<&AxisStepGen> {
        self.steppers.get(axis)
    }

    /// One interpolation period starting at `now` (ns), with this period's encoder
    /// reading. Afterwards the step events of `[now, now + period)` are ready.
    pub fn tick(&mut self, now: u64, fb: Feedback) {
        self.now = now;
        self.stats.ticks += 1;
        self.stats.max_queued = self.stats.max_queued.max(self.planner.len());
        self.spindle.sample(fb.count, fb.index);
        self.watch_encoder(fb.count);
        self.watch_thread_speed();
        self.polygon_start();
        let mut ticked = false;
        for _ in 0..8 {
            if !self.advance(&mut ticked) {
                break;
            }
        }
        self.spindle_control();
        self.feed_steppers(now);
    }

    /// The encoder watch: while the axes can move only with the spindle encoder
    /// (a locked thread or tap that has not reached its end, a G99 cut) and the
    /// spindle is commanded to turn, a count that does not change for
    /// `encoder_timeout_ms` (and four count intervals at the commanded speed) means
    /// the encoder signal is lost or the spindle stalled: alarm 4503, the axes
    /// (standing with the count) stop where they are, the spindle is stopped.
    fn watch_encoder(&mut self, count: i64) {
        if count != self.watch_count || !self.needs_counts() {
            self.watch_count = count;
            self.watch_since = self.now;
            return;
        }
        let per_min = u64::from(self.spindle.rpm) * u64::from(self.p.cpr);
        let interval = 60_000_000_000u64.checked_div(per_min).unwrap_or(u64::MAX);
        let timeout = (u64::from(self.mc.encoder_timeout_ms) * 1_000_000).max(interval.saturating_mul(4));
        if self.now.saturating_sub(self.watch_since) > timeout {
            self.raise(AlarmKind::SpindleNotTurning);
        }
    }

    /// Whether the motion running now advances only with encoder counts.
    fn needs_counts(&self) -> bool {
        if self.spindle.rpm == 0 || self.spindle.dir == SpindleDir::Stop || self.alarm.is_some() {
            return false;
        }
        match self.state {
            State::Locked => self.gear.is_some_and(|g| !g.finished()),
            State::Moving => self.interp.segment().is_some_and(|s| s.per_rev() && !s.rapid),
            _ => false,
        }
    }

    /// Whether encoder counts must come one by one with their times
    /// ([`MotionCore::on_encoder`]): while axes are locked to the spindle or a thread
    /// pass waits for its start count. Otherwise the count of each period is enough.
    /// (Every count works; [`MotionCore::encoder_due`] names the only ones that
    /// matter, which is what the firmware and the simulator hand over.)
    pub fn wants_encoder_edges(&self) -> bool {
        self.gear.is_some() || self.polygon.active() || matches!(self.state, State::SyncWait { .. })
    }

    /// An encoder count at time `now` (any number of counts after the last one
    /// given): while axes are locked to the spindle they move to the gearbox's
    /// position for it at once. Returns the axes commanded to move, bit `1 << i`
    /// for axis `i` (their step events are due now). The firmware calls it only at
    /// the counts [`MotionCore::encoder_due`] names.
    pub fn on_encoder(&mut self, now: u64, count: i64) -> u8 {
        let mut moved = self.polygon_count(now, count);
        let Some(g) = self.gear.as_mut() else { return moved };
        if g.on_count(count) {
            let (p, follower) = g.driven();
            let long = g.leg().long;
            self.steppers[long].jump(now, p << STEP_FRAC);
            moved |= 1 << long;
            if let Some((f, p)) = follower {
                self.steppers[f].jump(now, p << STEP_FRAC);
                moved |= 1 << f;
            }
        }
        moved
    }

    /// Gives every stepper this period's ramp, unless the axes are locked to the
    /// spindle (then the gearbox moves them, leg after leg, at encoder counts).
    fn feed_steppers(&mut self, now: u64) {
        if self.gear.is_some() {
            return;
        }
        let pos = *self.interp.position();
        let polygon = self.polygon.active();
        for (i, st) in self.steppers.iter_mut().enumerate() {
            if self.p.limits[i].present && !(polygon && i == Axis::C.index()) {
                st.ramp(now, self.p.tick_ns, pos[i]);
            }
        }
    }

    fn emit(&mut self, line: u32, kind: EventKind) {
        if self.events.push_back(Event { t: self.now, line, kind }).is_err() {
            self.stats.lost_events += 1;
        }
    }

    /// Raises a motion alarm: no further motion, the axes brake.
    fn raise(&mut self, kind: AlarmKind) {
        let alarm = Alarm::new(self.line, kind);
        if self.alarm.is_none() {
            self.alarm = Some(alarm);
            self.emit(self.line, EventKind::Alarm(alarm));
        }
        self.begin_stop();
    }

    fn live(&self) -> Live {
        Live {
            feed_ovr: self.feed_ovr,
            rapid_ovr: self.rapid_ovr,
            hold: self.hold || self.state == State::Stopping,
            stop_at_end: self.single_block,
            rev_per_tick: self.spindle.rev_per_tick(),
        }
    }

    /// One state step; true if another may follow in this period.
    fn advance(&mut self, ticked: &mut bool) -> bool {
        match self.state {
            State::Idle => self.next_entry(),
            State::Moving => {
                if *ticked {
                    return false;
                }
                *ticked = true;
                self.run_interpolator()
            }
            State::Held => {
                if self.hold {
                    return false;
                }
                self.state = State::Moving;
                true
            }
            State::WaitSpindle { since } => self.wait_spindle(since),
            State::Dwell { until } => {
                if self.now < until {
                    return false;
                }
                self.state = State::Idle;
                true
            }
            State::SyncWait { since } => self.sync_wait(since),
            State::Locked => self.run_locked(),
            State::Stopping => self.run_stopping(ticked),
            State::Stopped | State::Ended => false,
        }
    }

    /// Takes the next queue entry (Idle).
    #[inline(never)]
    fn next_entry(&mut self) -> bool {
        if self.polygon_stopping() {
            // G50.2: nothing after it before C stands on its whole turn.
            return false;
        }
        if self.hold && self.gear.is_none() {
            self.state = State::Held;
            return false;
        }
        let Some(item) = self.planner.front().copied() else {
            if self.streaming && !self.starved && self.alarm.is_none() {
                self.starved = true;
                self.stats.starvations += 1;
                self.emit(self.line, EventKind::Starved);
            }
            return false;
        };
        self.starved = false;
        self.planner.pop();
        self.line = item.line();
        match item {
            Item::Command { line, cmd } => self.command(line, cmd),
            Item::Motion(b) => self.begin_block(b),
        }
        true
    }

    /// Runs a command whose motion before it has finished.
    fn command(&mut self, line: u32, cmd: Command) {
        match cmd {
            Command::Spindle(s) => {
                self.set_spindle(s.dir, s.rpm.unwrap_or(0));
                self.emit(line, EventKind::Spindle { dir: s.dir, rpm: self.spindle.rpm });
            }
            Command::Tool { tool, offset } => self.emit(line, EventKind::Tool { tool, offset }),
            Command::Aux { m } => self.emit(line, EventKind::Aux { m }),
            Command::Dwell { ms } => {
                if ms > 0 {
                    self.state = State::Dwell { until: self.now + u64::from(ms) * 1_000_000 };
                }
            }
            Command::Stop { optional } => {
                self.emit(line, EventKind::Stop { optional });
                self.state = State::Stopped;
            }
            Command::Polygon(sync) => self.polygon_command(sync),
            // Made only by a machining centre's M06. By hand or by the tool
            // changer, the tool leaves the spindle: the spindle stops, nothing after
            // the M06 moves, and both start again as they were at cycle start (the
            // controller gives it when the changer reports done).
            Command::ToolChange(t) if canon::MILL => {
                self.emit(line, EventKind::ToolChange(t));
                if self.spindle.dir != SpindleDir::Stop {
                    self.resume_spindle = Some((self.spindle.dir, self.spindle.rpm));
                    self.set_spindle(SpindleDir::Stop, 0);
                    self.emit(line, EventKind::Spindle { dir: SpindleDir::Stop, rpm: 0 });
                }
                self.state = State::Stopped;
            }
            Command::ToolChange(_) => {}
            Command::End { rewind } => {
                self.set_spindle(SpindleDir::Stop, 0);
                self.emit(line, EventKind::End { rewind });
                self.streaming = false;
                self.state = State::Ended;
            }
        }
    }

    /// Commands the spindle; a real change makes the next cut wait for it.
    fn set_spindle(&mut self, dir: SpindleDir, rpm: u32) {
        if self.spindle.command(dir, rpm, self.mc.at_speed_pct) && dir != SpindleDir::Stop {
            self.spindle_wait = true;
        }
    }

    /// Starts a motion block.
    fn begin_block(&mut self, b: Block) {
        self.offset_memory = b.offset;
        match b.kind {
            BlockKind::Thread(_) => {
                self.pending = Some(b);
                self.state = State::SyncWait { since: self.now };
            }
            BlockKind::Tap(_) => self.begin_tap(b),
            _ => {
                self.release_tap();
                self.block_spindle(&b);
                if b.feed != FeedSpec::Rapid && self.needs_spindle(&b) {
                    self.pending = Some(b);
                    self.state = State::WaitSpindle { since: self.now };
                } else {
                    self.interp.start(&b, &self.p);
                    self.state = State::Moving;
                }
            }
        }
    }

    /// The spindle speed a block starts with: a rapid's (and a G97 cut's) own, a G96
    /// cut's from where it starts (it then follows X, 2.19).
    fn block_spindle(&mut self, b: &Block) {
        if self.spindle.dir == SpindleDir::Stop {
            return;
        }
        let rpm = match b.feed {
            FeedSpec::PerMin(_) | FeedSpec::PerRev(_) => {
                b.spindle.rpm_at(self.work_x(self.interp.position()[Axis::X.index()], &b.offset))
            }
            FeedSpec::Rapid => b.spindle.rpm,
        };
        if let Some(rpm) = rpm {
            self.set_spindle(self.spindle.dir, rpm);
        }
    }

    /// Work X (nm, radius) of a commanded X position (Q16 steps) under `offset`.
    fn work_x(&self, q16: i64, offset: &Pos) -> i64 {
        self.p.scale[Axis::X.index()].nm_of_q16(q16) - offset[Axis::X]
    }

    /// Whether a cutting block must wait for the spindle to reach its speed.
    fn needs_spindle(&self, b: &Block) -> bool {
        let per_rev = matches!(b.feed, FeedSpec::PerRev(_));
        (self.spindle_wait || per_rev) && !self.spindle_at_speed()
    }

    fn wait_spindle(&mut self, since: u64) -> bool {
        if self.spindle_at_speed() {
            self.spindle_wait = false;
            if let Some(b) = self.pending.take() {
                self.interp.start(&b, &self.p);
                self.state = State::Moving;
            }
            return true;
        }
        if self.now.saturating_sub(since) > u64::from(self.mc.at_speed_timeout_ms) * 1_000_000 {
            let kind = if self.spindle.rpm == 0 { AlarmKind::SpindleNotTurning } else { AlarmKind::SpindleNotAtSpeed };
            self.raise(kind);
            return true;
        }
        false
    }

    /// One period of the interpolator (Moving).
    fn run_interpolator(&mut self) -> bool {
        let live = self.live();
        let status = self.interp.tick(&mut self.planner, &live, &self.p);
        if let Some(s) = self.interp.segment() {
            self.line = s.line;
            self.offset_memory = s.offset;
        }
        match status {
            Status::Moving => false,
            Status::Held => {
                if self.hold {
                    self.state = State::Held;
                }
                false
            }
            Status::Finished | Status::Idle => {
                self.state = if self.single_block { State::Stopped } else { State::Idle };
                true
            }
        }
    }

    /// G96: the speed follows the work X of the cut (2.19); rapids keep the speed
    /// of their end point. Taps: the spindle is run to stop where the tap ends.
    fn spindle_control(&mut self) {
        if self.gear.is_some() {
            self.tap_spindle_control();
            return;
        }
        self.css_phase = (self.css_phase + 1) % CSS_PERIODS;
        let Some(seg) = self.interp.segment() else { return };
        if seg.spindle.css.is_none() || seg.rapid || self.css_phase != 0 || self.spindle.dir == SpindleDir::Stop {
            return;
        }
        let x = self.work_x(self.interp.position()[Axis::X.index()], &seg.offset);
        if let Some(rpm) = seg.spindle.rpm_at(x) {
            self.spindle.command(self.spindle.dir, rpm, 0);
        }
    }

    /// Starts braking for a reset, e-stop or alarm.
    fn begin_stop(&mut self) {
        self.pending = None;
        self.release_thread_for_stop();
        if self.gear.is_none() {
            self.spindle.command(SpindleDir::Stop, 0, 0);
        } else {
            self.spindle.command(self.spindle.dir, 0, 0);
        }
        self.state = State::Stopping;
    }

    /// Braking (Stopping): the interpolator runs with hold until the path speed is
    /// zero; a tap stays locked until the spindle has stopped. Then the queue goes.
    #[inline(never)]
    fn run_stopping(&mut self, ticked: &mut bool) -> bool {
        if self.gear.is_some() {
            if self.spindle.measured_rpm().abs() > 0.5 {
                return false;
            }
            self.release_tap();
        }
        if self.interp.segment().is_some() && !*ticked {
            *ticked = true;
            let live = self.live();
            if self.interp.tick(&mut self.planner, &live, &self.p) == Status::Moving {
                return false;
            }
        }
        self.interp.abandon();
        if self.polygon.active() {
            // Reset in polygon turning: C stops with the spindle, where it is.
            self.polygon_release();
            self.interp = Interpolator::new(self.steps());
        }
        self.planner.clear(self.commanded_position());
        self.p.set_tolerance(0);
        self.streaming = false;
        self.starved = false;
        self.hold = false;
        self.state = State::Idle;
        false
    }

    /// The commanded position, machine nm (where the planner continues from).
    fn commanded_position(&self) -> Pos {
        let s = self.interp.position().map(round_steps);
        Pos(core::array::from_fn(|i| if self.p.limits[i].present { self.p.scale[i].nm(s[i]) } else { 0 }))
    }
}

impl<const N: usize> CanonSink for MotionCore<N> {
    /// Queues an action. A full queue is back-pressure; an action the motion core
    /// cannot run raises its alarm (the action is consumed, nothing moves for it)
    /// and every later action is refused until reset.
    fn push(&mut self, action: Canon) -> Result<(), Full> {
        self.push_ref(&action)
    }

    /// As [`CanonSink::push`], reading the action where it is.
    fn push_ref(&mut self, action: &Canon) -> Result<(), Full> {
        if self.alarm.is_some() {
            return Err(Full);
        }
        if self.state == State::Ended {
            self.state = State::Idle;
        }
        match action.action {
            Action::Tolerance { nm } => {
                self.p.set_tolerance(nm);
                return Ok(());
            }
            // M02/M30 put the machine's tolerance back (for the blocks after it).
            Action::End { .. } => self.p.set_tolerance(0),
            _ => {}
        }
        match self.planner.push(action, &self.p) {
            Ok(()) => {
                self.streaming = true;
                Ok(())
            }
            Err(PushError::Full) => Err(Full),
            Err(PushError::Alarm(kind)) => {
                let alarm = Alarm::new(action.line, kind);
                self.alarm = Some(alarm);
                self.emit(action.line, EventKind::Alarm(alarm));
                Ok(())
            }
        }
    }
}

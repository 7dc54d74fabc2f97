//! The spindle-locked part of the motion core: starting a thread pass on the index
//! (with its checks at the measured speed), continuing thread legs, rigid tapping
//! with the spindle run to stop at the bottom and back, and letting go.

use super::polygon::PolygonGear;
use super::{MotionCore, State};
use crate::alarm::AlarmKind;
use crate::axis::{AXIS_COUNT, Axis};
use crate::canon::{SpindleDir, ThreadSync};
use crate::fixed::PATH_FRAC;
use crate::planner::block::thread_ramp;
use crate::planner::{Block, BlockKind, Item, ThreadSpec};
use crate::stepgen::StepEvent;
use crate::sync::{Due, Gear, Gearing, Leg, Ratio, ramp_up_steps};

impl<const N: usize> MotionCore<N> {
    /// The leg from the current position to `b`'s end.
    fn leg_to(&self, from: &[i64; AXIS_COUNT], b: &Block, long: Axis) -> Leg {
        let end = core::array::from_fn(|i| if self.p.limits[i].present { b.exec.end_steps[i] } else { from[i] });
        Leg { start: *from, end, long: long.index() }
    }

    /// Long-axis steps per encoder count for `lead` on `long`.
    fn ratio(&self, lead: i64, long: Axis) -> Result<Ratio, AlarmKind> {
        let (steps, per_nm) = self.p.scale[long.index()].ratio();
        Ratio::new(lead, steps, per_nm, self.p.cpr)
    }

    /// The gearing of thread block `t` on its long axis.
    fn gearing(&self, t: &ThreadSpec) -> Result<Gearing, AlarmKind> {
        let (steps, per_nm) = self.p.scale[t.long.index()].ratio();
        Gearing::new(t.lead, t.lead_delta, steps, per_nm, self.p.cpr)
    }

    /// The largest lead (nm/rev) at the end of `first` and the continuing thread
    /// blocks queued after it: what the pass's deceleration is sized for.
    fn sequence_lead(&self, first: &ThreadSpec) -> i64 {
        self.planner
            .iter()
            .map_while(|item| match item {
                Item::Motion(b) => match b.kind {
                    BlockKind::Thread(t) if t.sync == ThreadSync::Continue => Some(t.lead.max(t.lead_end)),
                    _ => None,
                },
                Item::Command { .. } => None,
            })
            .fold(first.lead_end.max(first.lead), i64::max)
    }

    /// Length of a leg along each axis, nm.
    fn leg_nm(&self, leg: &Leg) -> [f32; AXIS_COUNT] {
        core::array::from_fn(|i| ((leg.end[i] - leg.start[i]) as f64 * self.p.scale[i].nm_per_step()) as f32)
    }

    /// The raw encoder counts at which [`MotionCore::on_encoder`] must next be
    /// called: when the count reaches `up` (counting up) or `down` (counting down);
    /// nothing moves at the counts between. `None` while no axis follows the
    /// spindle (no thread or tap gearbox, no polygon turning). A thread's counts that
    /// move nothing are applied here, ahead of the spindle ([`Gear::glide`]); a
    /// count given to `on_encoder` anywhere from its last call on is taken
    /// correctly, so every count still works (only slower).
    pub fn encoder_due(&mut self) -> Option<Due> {
        match (self.gear.as_mut(), self.polygon.gear.as_ref()) {
            (Some(g), None) => Some(g.glide()),
            (None, None) => None,
            (g, p) => Some(g.map_or(Due::NONE, |g| g.glide()).merge(p.map_or(Due::NONE, PolygonGear::due))),
        }
    }

    /// The next step or direction event of `axis` before `until` after
    /// [`MotionCore::on_encoder`] moved it (a jump: its step due at once).
    pub fn next_sync_step(&mut self, axis: usize, until: u64) -> Option<StepEvent> {
        self.steppers.get_mut(axis)?.next_jump_event(until)
    }

    /// A thread pass waits for the spindle and its synchronisation count (SyncWait).
    #[inline(never)]
    pub(super) fn sync_wait(&mut self, since: u64) -> bool {
        let Some(b) = self.pending else {
            self.state = State::Idle;
            return true;
        };
        let BlockKind::Thread(t) = b.kind else { return false };
        if t.sync == ThreadSync::Continue {
            // Its pass ended before it arrived (2.17.1 note 2 needs it queued in time).
            self.raise(AlarmKind::SyncSequenceBroken);
            return true;
        }
        let waited = self.now.saturating_sub(since);
        let timeout = u64::from(self.mc.at_speed_timeout_ms) * 1_000_000;
        if !self.steppers.iter().all(|s| s.settled()) {
            return false;
        }
        let turning = self.spindle.counts_per_tick() >= 0.01;
        if !turning || !self.spindle.at_speed(self.mc.at_speed_pct) {
            if waited > timeout {
                let kind = if turning { AlarmKind::SpindleNotAtSpeed } else { AlarmKind::SpindleNotTurning };
                self.raise(kind);
                return true;
            }
            return false;
        }
        match self.plan_pass(&b) {
            Ok(Some((gear, ramp_lead))) => {
                self.gear = Some(gear);
                self.ramp_lead = ramp_lead;
                self.locked = Some(b);
                self.pending = None;
                self.legs_taken = 0;
                self.state = State::Locked;
                true
            }
            Ok(None) => {
                // No index yet: two revolutions at most.
                let counts = 2.0 * self.p.cpr as f32;
                if waited as f32 > counts / self.spindle.counts_per_tick() * self.p.tick_ns as f32 + timeout as f32 {
                    self.raise(AlarmKind::SpindleIndexMissing);
                    return true;
                }
                false
            }
            Err(kind) => {
                self.raise(kind);
                true
            }
        }
    }

    /// Checks a thread pass at the measured speed and sets up its gearbox: the
    /// largest lead of the block (at the end of a G34 whose lead grows) within every
    /// axis's speed, a G34's K acceleration within half the long axis's, the ramps
    /// (sized for the largest lead the queued sequence ends with) inside the thread.
    /// The ramp starts half a ramp before the first index + Q that leaves time to get
    /// there. `None` while no index has been seen. Returns the gearbox and the lead
    /// its ramps were sized for.
    fn plan_pass(&self, b: &Block) -> Result<Option<(Gear, i64)>, AlarmKind> {
        let BlockKind::Thread(t) = b.kind else { return Ok(None) };
        let leg = self.leg_to(self.interp.start_steps(), b, t.long);
        let gearing = self.gearing(&t)?;
        let cpt = self.spindle.counts_per_tick() * self.p.thread_margin;
        let cpr = self.p.cpr as f32;
        // Long-axis speed lead × rev/period, and what it means for every axis.
        let d = self.leg_nm(&leg);
        let long = d[leg.long].abs().max(1.0);
        let v_long = t.lead.max(t.lead_end) as f32 * cpt / cpr;
        for a in Axis::ALL {
            let lim = &self.p.limits[a.index()];
            if lim.present && v_long * d[a.index()].abs() / long > lim.feed {
                return Err(AlarmKind::ThreadTooFast { letter: a.letter() });
            }
        }
        // Ramp: R counts of constant acceleration, R = k·ω²/a along the long axis.
        let len: f32 = libm::sqrtf(d.iter().map(|x| x * x).sum());
        let a_long = b.plan.accel * long / len;
        let continues = matches!(self.planner.front(),
            Some(Item::Motion(n)) if matches!(n.kind, BlockKind::Thread(nt) if nt.sync == ThreadSync::Continue));
        let ramp_lead = if continues { self.sequence_lead(&t) } else { t.lead.max(t.lead_end) };
        let ramp = thread_ramp(&t, ramp_lead, cpt, self.p.cpr, a_long)?;
        let up = ramp_up_steps(&gearing, ramp);
        let down = gearing.steps_per_count() * t.lead_end as f64 / t.lead as f64 * ramp as f64 / 2.0;
        let need = if continues { up } else { up + down };
        if need as f32 > (leg.end[leg.long] - leg.start[leg.long]).abs() as f32 {
            return Err(AlarmKind::ThreadRampTooLong);
        }
        let Some(index) = self.spindle.index else { return Ok(None) };
        let sigma: i64 = if self.spindle.measured_rpm() >= 0.0 { 1 } else { -1 };
        let cpr = i64::from(self.p.cpr);
        let q = ((u64::from(t.start_udeg) * cpr as u64 + 180_000_000) / 360_000_000) as i64 % cpr;
        let first = sigma * index + q;
        let earliest = sigma * self.spindle.count + (2.0 * cpt) as i64 + 4 + ramp / 2;
        let revs = if first >= earliest { 0 } else { (earliest - first + cpr - 1) / cpr };
        let sync = first + revs * cpr;
        Gear::thread(leg, gearing, ramp, sigma, sigma * (sync - ramp / 2)).map(|g| Some((g, ramp_lead)))
    }

    /// A spindle-locked block runs (Locked): continuing legs are announced to the
    /// gearbox and taken from the queue as it reaches them; the end lets go.
    #[inline(never)]
    pub(super) fn run_locked(&mut self) -> bool {
        // (The gearbox is read in place: a copy of it costs more than the rest.)
        let Some(legs_done) = self.gear.as_ref().map(Gear::legs_done) else {
            self.state = State::Idle;
            return true;
        };
        // Legs the gearbox has moved on to since the last period leave the queue
        // first: what is left at its front is what may follow.
        while self.legs_taken < legs_done {
            self.legs_taken += 1;
            if let Some(Item::Motion(b)) = self.planner.pop() {
                self.line = b.line;
                self.offset_memory = b.offset;
                self.locked = Some(b);
            }
        }
        self.announce_next_leg();
        let Some(g) = self.gear.as_ref() else { return true };
        if !g.finished() {
            return false;
        }
        let (tap, way_out) = (g.is_tap(), g.is_way_out());
        if !tap {
            let mut pos = *self.interp.start_steps();
            g.positions(&mut pos);
            self.interp.set_steps(pos);
            self.gear = None;
            self.locked = None;
        } else if way_out {
            self.release_tap();
        }
        self.state = if self.single_block && !tap { State::Stopped } else { State::Idle };
        true
    }

    /// Tells the gearbox about a continuing thread block waiting in the queue. It
    /// starts at its own lead, or at the lead reached when the sequence has a G34 in
    /// it. Alarm 4502 if its lead is larger than the one the running pass's ramps
    /// were sized for (it arrived after the pass started).
    fn announce_next_leg(&mut self) {
        let Some(g) = self.gear.as_ref() else { return };
        if g.is_tap() || g.has_next() {
            return;
        }
        let Some(Item::Motion(b)) = self.planner.front() else { return };
        let BlockKind::Thread(t) = b.kind else { return };
        if t.sync != ThreadSync::Continue {
            return;
        }
        let leg = self.leg_to(&g.leg().end, b, t.long);
        let last = !matches!(self.planner.second(),
            Some(Item::Motion(n)) if matches!(n.kind, BlockKind::Thread(nt) if nt.sync == ThreadSync::Continue));
        let result = if t.lead.max(t.lead_end) > self.ramp_lead {
            Err(AlarmKind::ThreadRampTooLong)
        } else {
            self.gearing(&t).and_then(|r| self.gear.as_mut().map_or(Ok(()), |g| g.set_next(leg, r, last, t.keep_lead)))
        };
        if let Err(kind) = result {
            self.raise(kind);
        }
    }

    /// Starts a rigid-tapping block: the way in locks a new gearbox to the spindle
    /// at the current count; the way out continues the same one.
    pub(super) fn begin_tap(&mut self, b: Block) {
        let BlockKind::Tap(t) = b.kind else { return };
        let from = match self.gear {
            Some(g) if g.is_tap() => g.leg().end,
            _ => *self.interp.start_steps(),
        };
        let leg = self.leg_to(&from, &b, t.long);
        let result = match self.gear.as_mut() {
            Some(g) if g.is_tap() && g.finished() && !g.is_way_out() => g.way_out(&leg),
            _ => {
                self.release_tap();
                let sigma = if t.dir == SpindleDir::Ccw { -1 } else { 1 };
                self.ratio(t.lead, t.long)
                    .and_then(|r| Gear::tap(leg, r, sigma, self.spindle.count))
                    .map(|g| self.gear = Some(g))
            }
        };
        if let Err(kind) = result {
            self.raise(kind);
            return;
        }
        self.spindle.command(t.dir, b.spindle.rpm.unwrap_or(0), 0);
        self.locked = Some(b);
        self.state = State::Locked;
    }

    /// Ends a tap sequence: the axes stay where the gearbox put them.
    pub(super) fn release_tap(&mut self) {
        let Some(g) = self.gear else { return };
        if !g.is_tap() {
            return;
        }
        let mut pos = *self.interp.start_steps();
        g.positions(&mut pos);
        self.interp.set_steps(pos);
        self.gear = None;
        self.locked = None;
        self.spindle.command(SpindleDir::Stop, 0, 0);
    }

    /// The speed watch of a running thread pass: its axes move at lead × the
    /// measured spindle speed, checked against every axis's cutting feed (or step
    /// rate) limit when the pass started (with the ripple margin). A spindle that
    /// speeds up beyond that mid-pass (a drive running away) would drive an axis
    /// faster than it can follow — the step generator falls behind the spindle and
    /// the thread's lead is lost without a sign — so it raises 4501 and the axes
    /// brake along the thread.
    pub(super) fn watch_thread_speed(&mut self) {
        let Some(g) = self.gear.as_ref() else { return };
        if g.is_tap() || self.state != State::Locked || self.alarm.is_some() {
            return;
        }
        let leg = *g.leg();
        let nm_per_count = g.steps_per_count() * self.p.scale[leg.long].nm_per_step();
        let v_long = nm_per_count as f32 * self.spindle.counts_per_tick();
        let d = self.leg_nm(&leg);
        let long = d[leg.long].abs().max(1.0);
        for a in Axis::ALL {
            let lim = &self.p.limits[a.index()];
            if lim.present && v_long * d[a.index()].abs() / long > lim.feed {
                self.raise(AlarmKind::ThreadTooFast { letter: a.letter() });
                return;
            }
        }
    }

    /// On reset during a thread pass: the axes leave the spindle and brake along
    /// the thread's line from where they are, at the speed they had.
    pub(super) fn release_thread_for_stop(&mut self) {
        let (Some(g), Some(b)) = (self.gear, self.locked) else { return };
        if g.is_tap() {
            return;
        }
        let mut pos = *self.interp.start_steps();
        g.positions(&mut pos);
        let leg = g.leg();
        let d = self.leg_nm(leg);
        let len: f32 = libm::sqrtf(d.iter().map(|x| x * x).sum());
        let along = d[leg.long].abs().max(1.0) / len.max(1.0);
        let nm_per_count = g.steps_per_count() * self.p.scale[leg.long].nm_per_step();
        let v_long = nm_per_count as f32 * self.spindle.counts_per_tick();
        let v = (v_long / along * (1u32 << PATH_FRAC) as f32) as u64;
        self.gear = None;
        self.locked = None;
        self.interp.set_steps(pos);
        self.interp.brake_along(&b, &pos, v, &self.p);
    }

    /// While a tap runs, the spindle speed is cut so it can stop where the tap
    /// ends: `rpm ≤ 60·√(2·α·revolutions left)` with 80 % of the spindle's
    /// acceleration; at the end it is commanded to stop.
    #[inline(never)]
    pub(super) fn tap_spindle_control(&mut self) {
        let (Some(g), Some(b)) = (self.gear.as_ref(), self.locked.as_ref()) else { return };
        let BlockKind::Tap(t) = b.kind else { return };
        if !g.is_tap() {
            return;
        }
        if g.finished() || self.state != State::Locked {
            self.spindle.command(self.spindle.dir, 0, 0);
            return;
        }
        let revs_left = g.remaining().max(0) as f32 / g.steps_per_count() as f32 / self.p.cpr as f32;
        let accel = self.p.spindle_accel_rpm_s as f32 / 60.0 * 0.8;
        let stop_rpm = 60.0 * libm::sqrtf(2.0 * accel * revs_left);
        let rpm = b.spindle.rpm.unwrap_or(0);
        let cmd = (stop_rpm as u32).max(rpm / 50 + 2).min(rpm);
        self.spindle.command(t.dir, cmd, 0);
    }
}

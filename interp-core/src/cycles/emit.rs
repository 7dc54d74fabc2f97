//! Turning the moves a cycle plans (work coordinates, X as radius) into canonical
//! actions: end points in both coordinate systems, soft limits, feed, spindle.
//! One emitter serves the dry run that validates a cycle and the real run that
//! delivers it, so both produce the same actions.

use crate::alarm::AlarmKind;
use crate::axis::{Axis, Pos};
use crate::canon::{
    Action, ArcMove, Canon, Feed, FeedMode, Move, Plane, SpindleCommand, SpindleDir, TapMove, ThreadMove, ThreadSync,
};
use crate::config::MachineConfig;
use crate::modal::State;
use crate::moves::motion;

pub use crate::geom::Pt;
pub use cycle_paths::step::Step;

/// The plain blocks' soft-limit check, out of line for the cycles' many moves (inlined
/// at each of them it cost flash; a plain block keeps its inlined copy).
#[inline(never)]
fn check_limits(machine: &Pos, cfg: &MachineConfig) -> Result<(), AlarmKind> {
    motion::check_limits(machine, cfg)
}

/// The plain blocks' spindle speed, out of line for the cycles (as `check_limits`).
#[inline(never)]
fn spindle_speed(st: &State, cfg: &MachineConfig, x: i64) -> crate::canon::SpindleSpeed {
    crate::moves::spindle_speed(st, cfg, x)
}

/// The work position of `st`, out of line for the cycles (the emitter, the hole
/// and polar set-ups, the shape reader): inlined, each of a dozen sites carried
/// the work offsets' arithmetic (~150 B).
#[inline(never)]
pub fn work_pos(st: &State, cfg: &MachineConfig) -> Pos {
    st.work_pos(cfg)
}

/// Where emitted actions go: the block's stage, the interpreter's outbox, or
/// nowhere (dry run).
pub trait Out {
    /// Takes one action; an error if it has no room (a bug: callers check first).
    fn put(&mut self, c: Canon) -> Result<(), AlarmKind>;
    /// How many more actions it takes now.
    fn room(&self) -> usize {
        usize::MAX
    }
}

impl<const N: usize> Out for heapless::Deque<Canon, N> {
    fn put(&mut self, c: Canon) -> Result<(), AlarmKind> {
        self.push_back(c).map_err(|_| AlarmKind::Overflow)
    }
    fn room(&self) -> usize {
        N - self.len()
    }
}

/// The dry-run sink: takes up to the number of actions it holds and forgets them.
#[derive(Debug, Default)]
pub struct Dry(pub u32);

impl Out for Dry {
    fn put(&mut self, _: Canon) -> Result<(), AlarmKind> {
        self.0 = self.0.saturating_sub(1);
        Ok(())
    }

    /// Takes as many actions as it has left: the dry run goes in bounded chunks.
    fn room(&self) -> usize {
        self.0 as usize
    }
}

impl Out for crate::stage::Staged<'_> {
    fn put(&mut self, c: Canon) -> Result<(), AlarmKind> {
        self.actions.push_back(c).map_err(|_| AlarmKind::Overflow)
    }
    fn room(&self) -> usize {
        crate::stage::STAGE - self.actions.len()
    }
}

/// Emits planned steps as canonical actions, tracking the position on its own
/// copy of the state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Emitter {
    /// The state as the cycle runs (position, spindle).
    pub st: State,
    /// Line of the cycle block: every action carries it.
    pub line: u32,
    /// The cycle's cutting feed.
    pub feed: Feed,
    /// The cycle's tapping lead, nm/rev (hole cycles that tap).
    pub lead: i64,
}

impl Emitter {
    /// An emitter for the cycle block on `line`, cutting at the feed in force.
    pub fn new(st: State, line: u32) -> Self {
        let feed = Feed { mode: st.modal.feed_mode, value: st.feed.get(st.modal.feed_mode) };
        Emitter { st, line, feed, lead: 0 }
    }

    /// [`Emitter::new`] out of line, for the cycles' and the language calls'
    /// set-ups (one copy for eleven sites; `curve_block`, which a plain G01 passes
    /// through, keeps its inlined: out of line there it cost the G01 an instruction).
    #[inline(never)]
    pub fn for_block(st: &State, line: u32) -> Self {
        Emitter::new(*st, line)
    }

    /// The current work position in the ZX plane.
    #[inline(never)]
    pub fn here(&self, cfg: &MachineConfig) -> Pt {
        let w = work_pos(&self.st, cfg);
        Pt::new(w[Axis::X], w[Axis::Z])
    }

    /// Emits one step (nothing for a move that goes nowhere).
    pub fn emit(&mut self, step: Step, cfg: &MachineConfig, out: &mut dyn Out) -> Result<(), AlarmKind> {
        let action = match step {
            Step::Arc { to, center, cw } => {
                let mut w = work_pos(&self.st, cfg);
                (w[Axis::X], w[Axis::Z]) = (to.x, to.z);
                self.arc_in(Plane::Zx, w, (center.z, center.x), cw, false, cfg)?
            }
            Step::ArcTo { to, centre, cw } => {
                let plane = self.st.modal.plane;
                let (a, o) = plane.axes();
                let mut w = work_pos(&self.st, cfg);
                (w[a], w[o], w[plane.normal()]) = (to[0], to[1], to[2]);
                self.arc_in(plane, w, centre, cw, true, cfg)?
            }
            Step::Dwell(ms) => Action::Dwell { ms },
            Step::Feedrate(v) => {
                self.feed.value = v;
                return Ok(());
            }
            // M19 and the operator's stop: only the boring works of a machining centre and SINUMERIK.
            Step::Aux(_) | Step::Stop if !super::hole::BORING => return Ok(()),
            Step::Aux(m) => Action::Aux { m },
            Step::Stop => Action::Stop { optional: false },
            Step::Spindle(_) | Step::Speed(_) => {
                match step {
                    Step::Spindle(dir) => self.st.spindle.dir = dir,
                    Step::Speed(rpm) => self.st.spindle.rpm = rpm,
                    _ => {}
                }
                let dir = self.st.spindle.dir;
                let x = work_pos(&self.st, cfg)[Axis::X];
                let s = spindle_speed(&self.st, cfg, x);
                let css = if self.st.modal.css { self.st.spindle.css } else { None };
                Action::Spindle(SpindleCommand { dir, rpm: s.rpm, css: s.css.or(css) })
            }
            _ => match self.motion(step, cfg)? {
                Some(action) => action,
                None => return Ok(()),
            },
        };
        if let Some(area) = self.st.stroke {
            crate::moves::stroke::check_move(&area, self.st.pos, &action)?;
        }
        if let Some(e) = action.endpoint() {
            self.st.pos = e.machine;
            self.st.moved = true;
        }
        let line = if let Step::PolarFeed { line, .. } = step { line } else { self.line };
        out.put(Canon { line, action })
    }

    /// The straight move of a step (rapid, feed, thread, tap); `None` for one that
    /// goes nowhere. Every kind is a work position of all axes, a feed and the
    /// spindle at the end's X: one end point and one spindle speed for all (out of
    /// line: a copy per kind cost ~1 KB of flash).
    #[inline(never)]
    fn motion(&self, step: Step, cfg: &MachineConfig) -> Result<Option<Action>, AlarmKind> {
        /// What the move is, once its end point is known.
        enum Kind {
            Rapid,
            Linear,
            Thread { lead: i64, delta: i64, start_udeg: u32, sync: ThreadSync },
            Tap(SpindleDir),
        }
        let mut w = work_pos(&self.st, cfg);
        let mode_stop = self.st.modal.exact_stop_mode;
        let (kind, feed, exact_stop) = match step {
            Step::Rapid(p) => {
                (w[Axis::X], w[Axis::Z]) = (p.x, p.z);
                (Kind::Rapid, self.feed, true)
            }
            Step::RapidTo(to) => {
                w = to;
                (Kind::Rapid, self.feed, true)
            }
            Step::Feed(p) => {
                let feed = self.cutting_feed(cfg)?;
                (w[Axis::X], w[Axis::Z]) = (p.x, p.z);
                (Kind::Linear, feed, mode_stop)
            }
            Step::FeedTo(to) => {
                let feed = self.cutting_feed(cfg)?;
                w = to;
                (Kind::Linear, feed, mode_stop)
            }
            Step::FeedPerRev(to) => {
                w = to;
                (Kind::Linear, Feed { mode: FeedMode::PerRev, value: self.lead }, true)
            }
            Step::Thread { to: p, lead, delta, start_udeg, sync } => {
                (w[Axis::X], w[Axis::Z]) = (p.x, p.z);
                (Kind::Thread { lead, delta, start_udeg, sync }, self.feed, true)
            }
            Step::Tap { to, dir } => {
                w = to;
                (Kind::Tap(dir), self.feed, true)
            }
            Step::PolarFeed { x, c, z, feed, .. } => {
                (w[Axis::X], w[Axis::C], w[Axis::Z]) = (x, c, z);
                (Kind::Linear, Feed { value: feed, ..self.feed }, mode_stop)
            }
            _ => return Ok(None),
        };
        let Some(to) = self.target_pos(w, cfg)? else { return Ok(None) };
        let spindle = match kind {
            // The spindle is position-controlled in the tapping direction at the M29 speed.
            Kind::Tap(dir) => {
                let mut locked = self.st;
                locked.spindle.dir = dir;
                spindle_speed(&locked, cfg, w[Axis::X])
            }
            _ => spindle_speed(&self.st, cfg, w[Axis::X]),
        };
        let m = Move { to, feed, spindle, exact_stop, independent: false };
        Ok(Some(match kind {
            Kind::Rapid => Action::Rapid(m),
            Kind::Linear => Action::Linear(m),
            Kind::Thread { lead, delta, start_udeg, sync } => {
                // A thread waits for the spindle index: with the spindle stopped it
                // would wait for ever.
                if spindle.rpm.is_none_or(|r| r == 0) {
                    return Err(AlarmKind::FeedPerRevSpindleStopped);
                }
                Action::Thread(ThreadMove { to, lead, lead_delta: delta, start_udeg, sync, spindle })
            }
            Kind::Tap(dir) => Action::Tap(TapMove { to, lead: self.lead, dir, spindle }),
        }))
    }

    /// The end point of a move to work position `w`, soft limits checked; `None` if
    /// already there.
    fn target_pos(&self, w: Pos, cfg: &MachineConfig) -> Result<Option<crate::canon::Endpoint>, AlarmKind> {
        let to = self.endpoint(w, cfg)?;
        check_limits(&to.machine, cfg)?;
        Ok((to.machine != self.st.pos).then_some(to))
    }

    /// Both coordinates of the work position `w` (out of line: the moves' end
    /// points and the arcs' centres share it).
    #[inline(never)]
    fn endpoint(&self, w: Pos, cfg: &MachineConfig) -> Result<crate::canon::Endpoint, AlarmKind> {
        motion::endpoint(w, &self.st, cfg)
    }

    /// The cycle's feed, with the alarms of a cutting move (F0, G99 without spindle).
    #[inline(never)]
    fn cutting_feed(&self, cfg: &MachineConfig) -> Result<Feed, AlarmKind> {
        if self.feed.value <= 0 {
            return Err(AlarmKind::FeedZero);
        }
        if self.feed.mode == FeedMode::PerRev {
            let x = work_pos(&self.st, cfg)[Axis::X];
            if self.st.spindle.dir == SpindleDir::Stop || spindle_speed(&self.st, cfg, x).rpm == Some(0) {
                return Err(AlarmKind::FeedPerRevSpindleStopped);
            }
        }
        Ok(self.feed)
    }

    /// The arc in `plane` from where the tool is to the work position `to` about
    /// `centre` (the plane's two axes), soft limits checked at its end and at the
    /// extremes it sweeps through. Start = end in the plane is a full turn when
    /// `full_allowed` (a milling cycle's circle or helix), else no arc at all.
    #[inline(never)]
    fn arc_in(
        &self,
        plane: Plane,
        to: Pos,
        centre: (i64, i64),
        cw: bool,
        full_allowed: bool,
        cfg: &MachineConfig,
    ) -> Result<Action, AlarmKind> {
        let feed = self.cutting_feed(cfg)?;
        let here = work_pos(&self.st, cfg);
        let (pa, pb) = plane.axes();
        let (start, end) = ((here[pa], here[pb]), (to[pa], to[pb]));
        let full = start == end;
        if full && (!full_allowed || start == centre) {
            return Err(AlarmKind::Overflow);
        }
        let end_ep = self.endpoint(to, cfg)?;
        check_limits(&end_ep.machine, cfg)?;
        let mut c = to;
        (c[pa], c[pb]) = centre;
        let center = self.endpoint(c, cfg)?;
        let ext = crate::geom::arc_extents(start, end, centre, cw, full);
        let shift = self.st.work_to_machine(cfg);
        let (mut lo, mut hi) = (end_ep.machine, end_ep.machine);
        (lo[pa], lo[pb]) = (ext.a.0 + shift[pa], ext.b.0 + shift[pb]);
        (hi[pa], hi[pb]) = (ext.a.1 + shift[pa], ext.b.1 + shift[pb]);
        check_limits(&lo, cfg)?;
        check_limits(&hi, cfg)?;
        let spindle = spindle_speed(&self.st, cfg, to[Axis::X]);
        let exact_stop = self.st.modal.exact_stop_mode;
        Ok(Action::Arc(ArcMove { to: end_ep, center, plane, cw, full_circle: full, feed, spindle, exact_stop }))
    }
}

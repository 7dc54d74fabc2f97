//! Hole cycles: G83/G87 drilling (plain, high-speed peck, deep peck by parameter
//! 5101), G85/G89 boring, G84/G88 tapping — rigid after M29 S (2.22.2) or floating
//! with the M03/M04/M05 sequence of 2.22.3. G83/G84/G85 drill along Z on the face,
//! G87/G88/G89 along X on the side.
//!
//! One hole: rapid to the hole position on the initial level (①), rapid to the R
//! level (②), the work at the hole, back to R, rapid to the initial level (or stay
//! on R with G99 of systems B/C). K repeats the hole, moving by the incremental
//! position words each time.

use super::StepQueue;
use super::emit::Step;
use crate::alarm::AlarmKind;
use crate::axis::{Axis, Pos};
use crate::canon::SpindleDir;

/// What is done at the hole.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HoleWork {
    /// G83/G87: drill, pecking by `q` if non-zero; `deep` = return to R each peck (5101 = 1).
    Drill {
        /// Peck depth (0 = no pecking).
        q: i64,
        /// Deep-hole pecking.
        deep: bool,
        /// Return d (high-speed) or clearance d (deep), parameter 5113.
        d: i64,
    },
    /// G85/G89: feed in, dwell, feed out.
    Bore,
    /// G84/G88 with M29: every move in the hole locked to the spindle.
    RigidTap {
        /// Lead, nm/rev.
        lead: i64,
        /// Peck depth (0 = none).
        q: i64,
        /// Deep peck (5102 = 1): back to R after each peck.
        deep: bool,
        /// Return d, parameter 5114.
        d: i64,
        /// Spindle direction into the hole (M04 with the reverse-thread option 5170).
        dir: SpindleDir,
        /// Dwell at R after tapping, parameter 7013.
        dwell_r_ms: u32,
        /// Spindle direction restored after the hole (⑦).
        restore: SpindleDir,
    },
    /// G84/G88 floating: M03/M04/M05 around feeds that follow the spindle.
    FloatTap {
        /// Lead, nm/rev.
        lead: i64,
        /// Direction into the hole.
        dir: SpindleDir,
        /// Whether the spindle already turns that way (then ③ outputs nothing).
        turning: bool,
    },
}

/// Where a hole cycle is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HoleGen {
    work: HoleWork,
    /// Drilling axis.
    axis: Axis,
    /// Hole position (work) of the first hole, drilling axis on the initial level.
    position: Pos,
    /// Position change per repetition (incremental position words).
    step: Pos,
    initial: i64,
    r_level: i64,
    bottom: i64,
    dwell_ms: u32,
    stay_at_r: bool,
    repeat: u32,
    hole: u32,
    phase: Phase,
    /// Depth reached in the hole.
    reached: i64,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Phase {
    Position,
    Peck,
    Out,
    Done,
}

/// What a hole cycle is asked to do.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HoleSpec {
    /// Work at the hole.
    pub work: HoleWork,
    /// Drilling axis.
    pub axis: Axis,
    /// First hole position (work coordinates, drilling axis = initial level).
    pub position: Pos,
    /// Position change per repetition.
    pub step: Pos,
    /// R level on the drilling axis.
    pub r_level: i64,
    /// Bottom on the drilling axis.
    pub bottom: i64,
    /// Dwell at the bottom.
    pub dwell_ms: u32,
    /// G99 of systems B/C: return to the R level only.
    pub stay_at_r: bool,
    /// K.
    pub repeat: u32,
}

impl HoleGen {
    /// A hole cycle.
    pub fn new(spec: HoleSpec) -> HoleGen {
        HoleGen {
            work: spec.work,
            axis: spec.axis,
            position: spec.position,
            step: spec.step,
            initial: spec.position[spec.axis],
            r_level: spec.r_level,
            bottom: spec.bottom,
            dwell_ms: spec.dwell_ms,
            stay_at_r: spec.stay_at_r,
            repeat: spec.repeat,
            hole: 0,
            phase: if spec.repeat == 0 { Phase::Done } else { Phase::Position },
            reached: spec.r_level,
        }
    }

    #[inline(never)]
    fn at(&self, v: i64) -> Pos {
        let mut p = self.here_pos();
        p[self.axis] = v;
        p
    }

    fn here_pos(&self) -> Pos {
        let mut p = self.position;
        for a in Axis::ALL {
            // Saturating: C has no travel limit to stop a huge K × H first.
            p[a] = p[a].saturating_add(self.step[a].saturating_mul(i64::from(self.hole)));
        }
        p
    }

    /// The next group of steps; `false` when done.
    pub fn fill(&mut self, out: &mut StepQueue) -> Result<bool, AlarmKind> {
        match self.phase {
            Phase::Done => return Ok(false),
            Phase::Position => {
                push(out, Step::RapidTo(self.at(self.initial)))?;
                push(out, Step::RapidTo(self.at(self.r_level)))?;
                if let HoleWork::FloatTap { dir, turning, .. } = self.work
                    && (!turning || self.hole > 0)
                {
                    push(out, Step::Spindle(dir))?;
                }
                self.reached = self.r_level;
                self.phase = Phase::Peck;
            }
            Phase::Peck => self.peck(out)?,
            Phase::Out => {
                self.out(out)?;
                self.hole += 1;
                self.phase = if self.hole >= self.repeat { Phase::Done } else { Phase::Position };
            }
        }
        Ok(true)
    }

    /// One peck (or the whole depth), into the hole and back as the cycle says.
    fn peck(&mut self, out: &mut StepQueue) -> Result<(), AlarmKind> {
        let dir = (self.bottom - self.r_level).signum();
        let (q, deep, d) = match self.work {
            HoleWork::Drill { q, deep, d } => (q, deep, d),
            HoleWork::RigidTap { q, deep, d, .. } => (q, deep, d),
            _ => (0, false, 0),
        };
        let next = if q > 0 { self.reached + dir * q } else { self.bottom };
        let last = (self.bottom - next) * dir <= 0;
        let next = if last { self.bottom } else { next };
        match self.work {
            HoleWork::Drill { .. } if deep && self.reached != self.r_level => {
                // ⑤ back in to d short of the last depth, ⑥ feed q + d.
                push(out, Step::RapidTo(self.at(self.reached - dir * d)))?;
                push(out, Step::Feed(self.pt(next)))?;
            }
            HoleWork::Drill { .. } | HoleWork::Bore => push(out, Step::Feed(self.pt(next)))?,
            HoleWork::RigidTap { lead, dir: sd, .. } => {
                push(out, Step::Tap { axis: self.axis, to: next, lead, dir: sd })?;
            }
            HoleWork::FloatTap { lead, .. } => {
                push(out, Step::FeedPerRev { axis: self.axis, to: next, lead })?;
                push(out, Step::Spindle(SpindleDir::Stop))?;
            }
        }
        self.reached = next;
        if last {
            self.phase = Phase::Out;
            return Ok(());
        }
        let back = if deep { self.r_level } else { next - dir * d };
        match self.work {
            HoleWork::RigidTap { lead, dir: sd, .. } => {
                push(out, Step::Tap { axis: self.axis, to: back, lead, dir: reverse(sd) })?;
                if deep {
                    // Deep rigid peck: back in to the depth reached, locked to the spindle.
                    push(out, Step::Tap { axis: self.axis, to: next, lead, dir: sd })?;
                }
            }
            _ => push(out, Step::RapidTo(self.at(back)))?,
        }
        Ok(())
    }

    /// Dwell at the bottom and the way out.
    fn out(&mut self, out: &mut StepQueue) -> Result<(), AlarmKind> {
        if self.dwell_ms > 0 && !matches!(self.work, HoleWork::FloatTap { .. }) {
            push(out, Step::Dwell(self.dwell_ms))?;
        }
        let r = self.pt(self.r_level);
        match self.work {
            HoleWork::Drill { .. } => push(out, Step::RapidTo(self.at(self.r_level)))?,
            HoleWork::Bore => push(out, Step::Feed(r))?,
            HoleWork::RigidTap { lead, dir, dwell_r_ms, restore, .. } => {
                push(out, Step::Tap { axis: self.axis, to: self.r_level, lead, dir: reverse(dir) })?;
                if dwell_r_ms > 0 {
                    push(out, Step::Dwell(dwell_r_ms))?;
                }
                push(out, Step::Spindle(restore))?;
            }
            HoleWork::FloatTap { lead, dir, .. } => {
                if self.dwell_ms > 0 {
                    push(out, Step::Dwell(self.dwell_ms))?;
                }
                push(out, Step::Spindle(reverse(dir)))?;
                push(out, Step::FeedPerRev { axis: self.axis, to: self.r_level, lead })?;
                push(out, Step::Spindle(SpindleDir::Stop))?;
            }
        }
        if !self.stay_at_r {
            push(out, Step::RapidTo(self.at(self.initial)))?;
        }
        Ok(())
    }

    #[inline(never)]
    fn pt(&self, v: i64) -> super::emit::Pt {
        let p = self.at(v);
        super::emit::Pt::new(p[Axis::X], p[Axis::Z])
    }
}

/// The other direction.
pub fn reverse(d: SpindleDir) -> SpindleDir {
    match d {
        SpindleDir::Cw => SpindleDir::Ccw,
        SpindleDir::Ccw => SpindleDir::Cw,
        SpindleDir::Stop => SpindleDir::Stop,
    }
}

#[inline(never)]
fn push(out: &mut StepQueue, s: Step) -> Result<(), AlarmKind> {
    out.push_back(s).map_err(|_| AlarmKind::Overflow)
}

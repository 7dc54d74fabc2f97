//! The one hole-cycle generator of every language and machine kind: drilling
//! (plain, high-speed peck, deep peck), boring (feed out, spindle stop and rapid
//! out, manual retract, fine boring with an oriented shift, back boring), tapping
//! (rigid after M29, floating with the spindle sequence of the kind).
//!
//! It is told the drilling axis and the positioning plane (whose normal the
//! drilling axis is) and works on whole positions (work coordinates, every axis),
//! so the same generator drills a lathe's face (Z, positioned in X and C) and side
//! (X, positioned in Z and C) — G83–G89 of the ELESY manual —, a machining
//! centre's holes along Z positioned in XY — FANUC 0i-M G73–G89 — and the
//! SINUMERIK CYCLE81–89 in the plane of G17/G18/G19 with the tool axis as
//! drilling axis.
//!
//! One hole: rapid to the hole position at the level the tool is on (①), rapid to
//! the R level (②), the work at the hole, back to R, rapid to the initial level
//! (or stay on R: G99). K repeats the hole, moving by the incremental position
//! words each time; each repetition positions at the level the last one left the
//! tool on.

use super::{StepQueue, sign};
use crate::alarm::AlarmKind;
use crate::axis::{Axis, Pos};
use crate::canon::SpindleDir;
pub use crate::spec::hole::{DeepDrill, Degression, HoleSpec, HoleWork};
use crate::step::Step;
use crate::step::{Full, push};

/// M19: spindle orientation before a boring cycle's shift (seed 004 @10321).
const ORIENT: u16 = 19;

/// Whether this build has a language that asks for the boring works with a
/// spindle stop, an operator stop or an oriented shift (FANUC M G86/G88/G76/G87,
/// SINUMERIK CYCLE86-89): without one their code is left out.
pub const BORING: bool = crate::MILL || crate::SIEMENS;

/// Where a hole cycle is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HoleGen {
    work: HoleWork,
    /// Drilling axis.
    axis: Axis,
    /// Hole position (work) of the first hole; drilling axis = the level the
    /// tool positions on.
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
    /// Strokes drilled in the hole and the length of the last one (deep drilling).
    strokes: u32,
    last_stroke: i64,
    /// The spindle started this way at the first hole's R level (SINUMERIK
    /// CYCLE86–88 SDIR), if it does not turn that way already.
    spindle: Option<SpindleDir>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Phase {
    Position,
    Peck,
    Out,
    Done,
}

impl HoleGen {
    /// A hole cycle (out of line: the FANUC lathe's, the mill's and SINUMERIK's
    /// set-ups).
    #[inline(never)]
    pub fn new(spec: HoleSpec) -> HoleGen {
        debug_assert!(!spec.plane.contains(spec.axis), "the drilling axis is the plane's normal");
        let back_bore = matches!(spec.work, HoleWork::BackBore { .. });
        HoleGen {
            work: spec.work,
            axis: spec.axis,
            position: spec.position,
            step: spec.step,
            initial: spec.initial,
            r_level: spec.r_level,
            bottom: spec.bottom,
            dwell_ms: spec.dwell_ms,
            // Back boring's R level is below the cut: it always returns to the
            // initial level (seed 004 @9419).
            stay_at_r: spec.stay_at_r && !back_bore,
            repeat: spec.repeat,
            hole: 0,
            phase: if spec.repeat == 0 { Phase::Done } else { Phase::Position },
            reached: spec.r_level,
            strokes: 0,
            last_stroke: 0,
            spindle: None,
        }
    }

    /// The same cycle with the spindle turned on `dir` at the first hole's R level.
    pub fn starting(self, dir: SpindleDir) -> HoleGen {
        HoleGen { spindle: Some(dir), ..self }
    }

    /// The lead of a tapping cycle (what the emitter's [`Step::Tap`] and
    /// [`Step::FeedPerRev`] move at), 0 for the others.
    pub fn lead(&self) -> i64 {
        match self.work {
            HoleWork::RigidTap { lead, .. } | HoleWork::FloatTap { lead, .. } => lead,
            _ => 0,
        }
    }

    /// The current hole's position with the drilling axis at `v`.
    #[inline(never)]
    fn at(&self, v: i64) -> Pos {
        let mut p = self.here_pos();
        p[self.axis] = v;
        p
    }

    /// Queues a rapid to the current hole with the drilling axis at `v` (out of
    /// line: a dozen sites, each building its step).
    #[inline(never)]
    fn rapid_at(&self, v: i64, out: &mut StepQueue) -> Result<(), Full> {
        push(out, Step::RapidTo(self.at(v)))
    }

    /// Queues a cutting feed to the current hole with the drilling axis at `v` (as
    /// [`HoleGen::rapid_at`]).
    #[inline(never)]
    fn feed_at(&self, v: i64, out: &mut StepQueue) -> Result<(), Full> {
        push(out, Step::FeedTo(self.at(v)))
    }

    /// [`HoleGen::at`] moved by a boring work's `shift` (out of line: six sites).
    #[inline(never)]
    fn at_shifted(&self, v: i64, shift: Pos) -> Pos {
        self.at(v) + shift
    }

    fn here_pos(&self) -> Pos {
        let mut p = self.position;
        for a in Axis::ALL {
            // Saturating: C has no travel limit to stop a huge K × H first.
            p[a] = p[a].saturating_add(self.step[a].saturating_mul(i64::from(self.hole)));
        }
        p
    }

    /// The level the current hole is positioned on: where the tool is — the
    /// block's level for the first hole, where the last hole left it for the others.
    fn positioning_level(&self) -> i64 {
        match self.hole {
            0 => self.position[self.axis],
            _ if self.stay_at_r => self.r_level,
            _ => self.initial,
        }
    }

    /// The next group of steps; `false` when done.
    pub fn fill(&mut self, out: &mut StepQueue) -> Result<bool, AlarmKind> {
        match self.phase {
            Phase::Done => return Ok(false),
            Phase::Position => {
                self.rapid_at(self.positioning_level(), out)?;
                // The boring works of a machining centre (G86/G88/G76/G87) and of the
                // SINUMERIK CYCLE86-89: without either their code is left out.
                if BORING && let HoleWork::BackBore { shift, restart } = self.work {
                    self.back_bore_in(shift, restart, out)?;
                } else {
                    self.rapid_at(self.r_level, out)?;
                    if let HoleWork::FloatTap { dir, turning, after, .. } = self.work
                        && (if self.hole == 0 { !turning } else { after != dir })
                    {
                        push(out, Step::Spindle(dir))?;
                    }
                    // SINUMERIK's SDIR (only its cycles set it: without them, left out).
                    if crate::SIEMENS
                        && let Some(dir) = self.spindle.take()
                    {
                        push(out, Step::Spindle(dir))?;
                    }
                }
                self.reached = self.r_level;
                self.strokes = 0;
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

    /// Back boring down to R: oriented stop, shift, rapid to R, shift back, spindle on.
    fn back_bore_in(&self, shift: Pos, restart: SpindleDir, out: &mut StepQueue) -> Result<(), AlarmKind> {
        let level = self.positioning_level();
        push(out, Step::Aux(ORIENT))?;
        push(out, Step::RapidTo(self.at_shifted(level, shift)))?;
        push(out, Step::RapidTo(self.at_shifted(self.r_level, shift)))?;
        self.rapid_at(self.r_level, out)?;
        Ok(push(out, Step::Spindle(restart))?)
    }

    /// One peck (or the whole depth), into the hole and back as the cycle says.
    fn peck(&mut self, out: &mut StepQueue) -> Result<(), AlarmKind> {
        // CYCLE83's deep drilling: only the SINUMERIK cycles ask for it (without
        // them its code is left out, as the boring works' without BORING).
        if crate::SIEMENS
            && let HoleWork::DeepDrill(deep) = self.work
        {
            return self.stroke(&deep, out);
        }
        let dir = sign(self.bottom - self.r_level);
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
                self.rapid_at(self.reached - dir * d, out)?;
                self.feed_at(next, out)?;
            }
            HoleWork::RigidTap { dir: sd, .. } => {
                push(out, Step::Tap { to: self.at(next), dir: sd })?;
            }
            HoleWork::FloatTap { stop_at_bottom, .. } => {
                push(out, Step::FeedPerRev(self.at(next)))?;
                if stop_at_bottom {
                    push(out, Step::Spindle(SpindleDir::Stop))?;
                }
            }
            HoleWork::BoreFeeds { feed_in, .. } if crate::SIEMENS => {
                push(out, Step::Feedrate(feed_in))?;
                self.feed_at(next, out)?;
            }
            _ => self.feed_at(next, out)?,
        }
        self.reached = next;
        if last {
            self.phase = Phase::Out;
            return Ok(());
        }
        let back = if deep { self.r_level } else { next - dir * d };
        match self.work {
            HoleWork::RigidTap { dir: sd, .. } => {
                push(out, Step::Tap { to: self.at(back), dir: reverse(sd) })?;
                if deep {
                    // Deep rigid peck: back in to the depth reached, locked to the spindle.
                    push(out, Step::Tap { to: self.at(next), dir: sd })?;
                }
            }
            _ => self.rapid_at(back, out)?,
        }
        Ok(())
    }

    /// One stroke of a deep hole (CYCLE83, seed 001 lines 1752-1772): back in
    /// (chip removal: G0 to the anticipation distance before the depth reached),
    /// G1 to the next depth (the first at its own feed), then dwell and chip
    /// breaking (G1 back by the retract) or chip removal (G0 to R, dwell).
    fn stroke(&mut self, deep: &DeepDrill, out: &mut StepQueue) -> Result<(), AlarmKind> {
        let dir = sign(self.bottom - self.r_level);
        let left = (self.bottom - self.reached) * dir;
        let s = match self.strokes {
            0 => (deep.first + deep.approach).min(left),
            n => deep.stroke(n, self.last_stroke, left),
        };
        let next = if s >= left { self.bottom } else { self.reached + dir * s };
        let depth = (self.reached - self.r_level) * dir;
        if self.strokes == 0 {
            push(out, Step::Feedrate(deep.first_feed))?;
            self.feed_at(next, out)?;
            push(out, Step::Feedrate(deep.feed))?;
        } else {
            if deep.chip_removal {
                let back = deep.anticipation_at(depth).min(depth);
                self.rapid_at(self.reached - dir * back, out)?;
            }
            self.feed_at(next, out)?;
        }
        self.last_stroke = if self.strokes == 0 { deep.first } else { s };
        self.strokes += 1;
        self.reached = next;
        if next == self.bottom {
            self.phase = Phase::Out;
            return Ok(());
        }
        if deep.dwell_depth_ms > 0 {
            push(out, Step::Dwell(deep.dwell_depth_ms))?;
        }
        if deep.chip_removal {
            self.rapid_at(self.r_level, out)?;
            if deep.dwell_start_ms > 0 {
                push(out, Step::Dwell(deep.dwell_start_ms))?;
            }
        } else {
            let back = deep.retract.min((next - self.r_level) * dir);
            self.feed_at(next - dir * back, out)?;
        }
        Ok(())
    }

    /// Dwell at the bottom and the way out.
    fn out(&mut self, out: &mut StepQueue) -> Result<(), AlarmKind> {
        if self.dwell_ms > 0 && !matches!(self.work, HoleWork::FloatTap { .. }) {
            push(out, Step::Dwell(self.dwell_ms))?;
        }
        let r = self.at(self.r_level);
        let leave = if self.stay_at_r { self.r_level } else { self.initial };
        match self.work {
            HoleWork::Drill { .. } | HoleWork::DeepDrill(_) => push(out, Step::RapidTo(r))?,
            HoleWork::Bore => push(out, Step::FeedTo(r))?,
            // CYCLE85's feeds: only the SINUMERIK cycles ask for them.
            HoleWork::BoreFeeds { feed_out, .. } => {
                if crate::SIEMENS {
                    push(out, Step::Feedrate(feed_out))?;
                    push(out, Step::FeedTo(r))?;
                }
            }
            // The boring works below come only from a machining centre's table
            // and the SINUMERIK cycles.
            HoleWork::BoreStop { .. }
            | HoleWork::BoreManual { .. }
            | HoleWork::FineBore { .. }
            | HoleWork::BackBore { .. }
                if !BORING => {}
            HoleWork::BoreStop { restart } | HoleWork::BoreManual { restart } => {
                push(out, Step::Spindle(SpindleDir::Stop))?;
                if matches!(self.work, HoleWork::BoreManual { .. }) {
                    push(out, Step::Stop)?;
                }
                self.rapid_at(leave, out)?;
                return Ok(push(out, Step::Spindle(restart))?);
            }
            HoleWork::FineBore { shift, restart } => {
                push(out, Step::Aux(ORIENT))?;
                push(out, Step::RapidTo(self.at_shifted(self.bottom, shift)))?;
                push(out, Step::RapidTo(self.at_shifted(leave, shift)))?;
                self.rapid_at(leave, out)?;
                return Ok(push(out, Step::Spindle(restart))?);
            }
            HoleWork::BackBore { shift, restart } => {
                push(out, Step::Aux(ORIENT))?;
                push(out, Step::RapidTo(self.at_shifted(self.bottom, shift)))?;
                push(out, Step::RapidTo(self.at_shifted(self.initial, shift)))?;
                self.rapid_at(self.initial, out)?;
                return Ok(push(out, Step::Spindle(restart))?);
            }
            HoleWork::RigidTap { dir, dwell_r_ms, restore, .. } => {
                push(out, Step::Tap { to: r, dir: reverse(dir) })?;
                if dwell_r_ms > 0 {
                    push(out, Step::Dwell(dwell_r_ms))?;
                }
                push(out, Step::Spindle(restore))?;
            }
            HoleWork::FloatTap { dir, after, .. } => {
                if self.dwell_ms > 0 {
                    push(out, Step::Dwell(self.dwell_ms))?;
                }
                push(out, Step::Spindle(reverse(dir)))?;
                push(out, Step::FeedPerRev(r))?;
                push(out, Step::Spindle(after))?;
            }
        }
        if !self.stay_at_r {
            self.rapid_at(self.initial, out)?;
        }
        Ok(())
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::canon::Plane;
    use std::vec::Vec;

    /// Every step of a cycle.
    fn steps(spec: HoleSpec) -> Vec<Step> {
        let mut g = HoleGen::new(spec);
        let mut all = Vec::new();
        let mut q = StepQueue::new();
        while g.fill(&mut q).unwrap() {
            while let Some(s) = q.pop_front() {
                all.push(s);
            }
        }
        all
    }

    const fn xyz(x: i64, y: i64, z: i64) -> Pos {
        Pos([x, y, z, 0])
    }

    /// A machining centre's hole: along Z, positioned in XY.
    fn mill(work: HoleWork) -> HoleSpec {
        HoleSpec {
            work,
            axis: Axis::Z,
            plane: Plane::Xy,
            position: xyz(10, 20, 3),
            step: Pos::ZERO,
            initial: 50,
            r_level: 2,
            bottom: -10,
            dwell_ms: 0,
            stay_at_r: false,
            repeat: 1,
        }
    }

    /// The first hole positions on the level the tool is on (3, left there by a
    /// G99 hole), returns to the remembered initial level (50) under G98; with
    /// G99 and K3 every further hole positions on R.
    #[test]
    fn positions_on_the_current_level_and_returns_to_the_remembered_initial_level() {
        let drill = HoleWork::Drill { q: 0, deep: false, d: 0 };
        assert_eq!(
            steps(mill(drill)),
            [
                Step::RapidTo(xyz(10, 20, 3)),
                Step::RapidTo(xyz(10, 20, 2)),
                Step::FeedTo(xyz(10, 20, -10)),
                Step::RapidTo(xyz(10, 20, 2)),
                Step::RapidTo(xyz(10, 20, 50)),
            ]
        );
        let pattern = HoleSpec { stay_at_r: true, repeat: 3, step: xyz(5, 0, 0), ..mill(drill) };
        let rapids: Vec<_> = steps(pattern).into_iter().filter(|s| matches!(s, Step::RapidTo(_))).collect();
        assert_eq!(
            rapids,
            [
                Step::RapidTo(xyz(10, 20, 3)),
                Step::RapidTo(xyz(10, 20, 2)),
                Step::RapidTo(xyz(10, 20, 2)),
                Step::RapidTo(xyz(15, 20, 2)),
                Step::RapidTo(xyz(15, 20, 2)),
                Step::RapidTo(xyz(15, 20, 2)),
                Step::RapidTo(xyz(20, 20, 2)),
                Step::RapidTo(xyz(20, 20, 2)),
                Step::RapidTo(xyz(20, 20, 2)),
            ]
        );
    }

    /// Fine boring: dwell, oriented stop, shift, out shifted, shift back, spindle on.
    #[cfg_attr(
        not(any(feature = "mill", feature = "siemens")),
        ignore = "the boring works are left out of a build without the mill profile and SINUMERIK"
    )]
    #[test]
    fn fine_boring_shifts_away_from_the_wall_before_it_leaves() {
        let shift = xyz(-1, 0, 0);
        let s = steps(HoleSpec { dwell_ms: 7, ..mill(HoleWork::FineBore { shift, restart: SpindleDir::Cw }) });
        assert_eq!(
            s[2..],
            [
                Step::FeedTo(xyz(10, 20, -10)),
                Step::Dwell(7),
                Step::Aux(ORIENT),
                Step::RapidTo(xyz(9, 20, -10)),
                Step::RapidTo(xyz(9, 20, 50)),
                Step::RapidTo(xyz(10, 20, 50)),
                Step::Spindle(SpindleDir::Cw),
            ]
        );
    }

    /// Back boring goes down shifted to R (below the cut), cuts up to the bottom
    /// level and returns to the initial level even under G99.
    #[cfg_attr(
        not(any(feature = "mill", feature = "siemens")),
        ignore = "the boring works are left out of a build without the mill profile and SINUMERIK"
    )]
    #[test]
    fn back_boring_cuts_upwards_and_always_returns_to_the_initial_level() {
        let shift = xyz(0, 2, 0);
        let spec = HoleSpec {
            r_level: -30,
            bottom: -12,
            stay_at_r: true,
            ..mill(HoleWork::BackBore { shift, restart: SpindleDir::Cw })
        };
        assert_eq!(
            steps(spec),
            [
                Step::RapidTo(xyz(10, 20, 3)),
                Step::Aux(ORIENT),
                Step::RapidTo(xyz(10, 22, 3)),
                Step::RapidTo(xyz(10, 22, -30)),
                Step::RapidTo(xyz(10, 20, -30)),
                Step::Spindle(SpindleDir::Cw),
                Step::FeedTo(xyz(10, 20, -12)),
                Step::Aux(ORIENT),
                Step::RapidTo(xyz(10, 22, -12)),
                Step::RapidTo(xyz(10, 22, 50)),
                Step::RapidTo(xyz(10, 20, 50)),
                Step::Spindle(SpindleDir::Cw),
            ]
        );
    }

    /// A machining centre's floating tap reverses at the bottom without a stop and
    /// turns forward again at R; G86 stops the spindle and rapids out; G88 stops
    /// for the operator before it leaves.
    #[cfg_attr(
        not(any(feature = "mill", feature = "siemens")),
        ignore = "the boring works are left out of a build without the mill profile and SINUMERIK"
    )]
    #[test]
    fn mill_tapping_and_spindle_stop_boring() {
        let tap = HoleWork::FloatTap {
            lead: 1,
            dir: SpindleDir::Ccw,
            turning: true,
            after: SpindleDir::Ccw,
            stop_at_bottom: false,
        };
        assert_eq!(
            steps(mill(tap))[2..],
            [
                Step::FeedPerRev(xyz(10, 20, -10)),
                Step::Spindle(SpindleDir::Cw),
                Step::FeedPerRev(xyz(10, 20, 2)),
                Step::Spindle(SpindleDir::Ccw),
                Step::RapidTo(xyz(10, 20, 50)),
            ]
        );
        let manual = steps(mill(HoleWork::BoreManual { restart: SpindleDir::Cw }));
        assert_eq!(
            manual[2..],
            [
                Step::FeedTo(xyz(10, 20, -10)),
                Step::Spindle(SpindleDir::Stop),
                Step::Stop,
                Step::RapidTo(xyz(10, 20, 50)),
                Step::Spindle(SpindleDir::Cw),
            ]
        );
        let stop = steps(HoleSpec { stay_at_r: true, ..mill(HoleWork::BoreStop { restart: SpindleDir::Cw }) });
        assert_eq!(
            stop[3..],
            [Step::Spindle(SpindleDir::Stop), Step::RapidTo(xyz(10, 20, 2)), Step::Spindle(SpindleDir::Cw)]
        );
    }
}

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

use super::StepQueue;
use super::emit::Step;
use crate::alarm::AlarmKind;
use crate::axis::{Axis, Pos};
use crate::canon::{Plane, SpindleDir};

/// M19: spindle orientation before a boring cycle's shift (seed 004 @10321).
const ORIENT: u16 = 19;

/// What is done at the hole.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HoleWork {
    /// Drill to the bottom, pecking by `q` if non-zero: `deep` = back to R after
    /// each peck (lathe 5101 = 1, FANUC M G83), else back by `d` (high speed:
    /// lathe 5101 = 0, FANUC M G73).
    Drill {
        /// Peck depth (0 = no pecking).
        q: i64,
        /// Deep-hole pecking.
        deep: bool,
        /// Return d (high speed) or clearance d (deep).
        d: i64,
    },
    /// Feed in, dwell, feed out (lathe G85/G89, FANUC M G85/G89).
    Bore,
    /// Feed in, dwell, spindle stop, rapid out, spindle on again in `restart`
    /// (FANUC M G86).
    BoreStop {
        /// Direction the spindle turned in before the hole.
        restart: SpindleDir,
    },
    /// Feed in, dwell, spindle stop, a stop for the operator (who may retract by
    /// hand), then rapid out and the spindle on again (FANUC M G88).
    BoreManual {
        /// Direction the spindle turned in before the hole.
        restart: SpindleDir,
    },
    /// Feed in, dwell, oriented spindle stop (M19), shift away from the wall by
    /// `shift`, rapid out, shift back, spindle on (FANUC M G76).
    FineBore {
        /// The shift, a vector in the positioning plane (work coordinates).
        shift: Pos,
        /// Direction the spindle turned in before the hole.
        restart: SpindleDir,
    },
    /// Back boring (FANUC M G87): at the hole position oriented stop and shift,
    /// rapid down to the R level (below the hole's far end), shift back, spindle
    /// on, feed up to the bottom level, oriented stop, shift, rapid to the initial
    /// level, shift back, spindle on. Always back to the initial level.
    BackBore {
        /// The shift, a vector in the positioning plane (work coordinates).
        shift: Pos,
        /// Direction the spindle turns in while cutting.
        restart: SpindleDir,
    },
    /// Rigid tapping (M29): every move in the hole locked to the spindle.
    RigidTap {
        /// Lead, nm/rev.
        lead: i64,
        /// Peck depth (0 = none).
        q: i64,
        /// Deep peck: back to R after each peck.
        deep: bool,
        /// Return d of pecking.
        d: i64,
        /// Spindle direction into the hole.
        dir: SpindleDir,
        /// Dwell at R after tapping (lathe parameter 7013).
        dwell_r_ms: u32,
        /// Spindle direction after the hole (⑦ of the lathe; stopped on a mill,
        /// whose spindle stays in position control until G80).
        restore: SpindleDir,
    },
    /// Floating tapping: the spindle turns `dir` into the hole and the other way
    /// out; the feed follows the spindle.
    FloatTap {
        /// Lead, nm/rev.
        lead: i64,
        /// Direction into the hole.
        dir: SpindleDir,
        /// Whether the spindle already turns that way (then ① outputs nothing).
        turning: bool,
        /// The spindle after the hole: stopped (lathe, 2.22.3: M05 at R and M03/M04
        /// again before the next hole) or `dir` again (FANUC M G84/G74: forward
        /// again at R).
        after: SpindleDir,
        /// The spindle stops at the bottom before it reverses (lathe 2.22.3); a
        /// mill reverses directly.
        stop_at_bottom: bool,
    },
}

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
    /// Drilling axis: the normal of `plane`.
    pub axis: Axis,
    /// Positioning plane: the plane the hole positions are given in (G17 for a
    /// machining centre's holes; a lathe's face holes are positioned in X and C,
    /// its side holes in Z and C). Rotary axes position along with it.
    pub plane: Plane,
    /// First hole position (work coordinates); on the drilling axis the level the
    /// tool is on when the hole is positioned.
    pub position: Pos,
    /// Position change per repetition.
    pub step: Pos,
    /// Initial level on the drilling axis, where G98 (or a lathe's hole) returns:
    /// on a machining centre the level the cycle mode started on, remembered across
    /// its G99 holes (seed 004 @7537).
    pub initial: i64,
    /// R level on the drilling axis.
    pub r_level: i64,
    /// Bottom on the drilling axis (the far end of the cut: for back boring the
    /// level the cut ends on, above R).
    pub bottom: i64,
    /// Dwell at the bottom.
    pub dwell_ms: u32,
    /// G99: return to the R level only.
    pub stay_at_r: bool,
    /// K.
    pub repeat: u32,
}

impl HoleGen {
    /// A hole cycle.
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
        }
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
                push(out, Step::RapidTo(self.at(self.positioning_level())))?;
                // The boring works of a machining centre (G86/G88/G76/G87) come only
                // from its table: without the profile their code is left out.
                if crate::MILL
                    && let HoleWork::BackBore { shift, restart } = self.work
                {
                    self.back_bore_in(shift, restart, out)?;
                } else {
                    push(out, Step::RapidTo(self.at(self.r_level)))?;
                    if let HoleWork::FloatTap { dir, turning, after, .. } = self.work
                        && (if self.hole == 0 { !turning } else { after != dir })
                    {
                        push(out, Step::Spindle(dir))?;
                    }
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

    /// Back boring down to R: oriented stop, shift, rapid to R, shift back, spindle on.
    fn back_bore_in(&self, shift: Pos, restart: SpindleDir, out: &mut StepQueue) -> Result<(), AlarmKind> {
        let level = self.positioning_level();
        push(out, Step::Aux(ORIENT))?;
        push(out, Step::RapidTo(self.at(level) + shift))?;
        push(out, Step::RapidTo(self.at(self.r_level) + shift))?;
        push(out, Step::RapidTo(self.at(self.r_level)))?;
        push(out, Step::Spindle(restart))
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
                push(out, Step::FeedTo(self.at(next)))?;
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
            _ => push(out, Step::FeedTo(self.at(next)))?,
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
            _ => push(out, Step::RapidTo(self.at(back)))?,
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
            HoleWork::Drill { .. } => push(out, Step::RapidTo(r))?,
            HoleWork::Bore => push(out, Step::FeedTo(r))?,
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
            // The machining centre's boring works, below, come only from its table.
            _ if !crate::MILL => {}
            HoleWork::BoreStop { restart } | HoleWork::BoreManual { restart } => {
                push(out, Step::Spindle(SpindleDir::Stop))?;
                if matches!(self.work, HoleWork::BoreManual { .. }) {
                    push(out, Step::Stop)?;
                }
                push(out, Step::RapidTo(self.at(leave)))?;
                return push(out, Step::Spindle(restart));
            }
            HoleWork::FineBore { shift, restart } => {
                push(out, Step::Aux(ORIENT))?;
                push(out, Step::RapidTo(self.at(self.bottom) + shift))?;
                push(out, Step::RapidTo(self.at(leave) + shift))?;
                push(out, Step::RapidTo(self.at(leave)))?;
                return push(out, Step::Spindle(restart));
            }
            HoleWork::BackBore { shift, restart } => {
                push(out, Step::Aux(ORIENT))?;
                push(out, Step::RapidTo(self.at(self.bottom) + shift))?;
                push(out, Step::RapidTo(self.at(self.initial) + shift))?;
                push(out, Step::RapidTo(self.at(self.initial)))?;
                return push(out, Step::Spindle(restart));
            }
        }
        if !self.stay_at_r {
            push(out, Step::RapidTo(self.at(self.initial)))?;
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

#[inline(never)]
fn push(out: &mut StepQueue, s: Step) -> Result<(), AlarmKind> {
    out.push_back(s).map_err(|_| AlarmKind::Overflow)
}

#[cfg(test)]
mod tests {
    use super::*;
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

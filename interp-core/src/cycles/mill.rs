//! The milling cycles on the engine: a `mill_paths` generator (pocket, slot,
//! spigot, face, contour, thread milling …) yields moves in the working plane —
//! abscissa, ordinate, applicate — and this maps each onto the plane's axes
//! (G17 X/Y/Z, G18 Z/X/Y, G19 Y/Z/X) as a planned [`Step`], so the cycle is
//! emitted, dry-run and limit-checked like every other cycle. The axes outside
//! the plane (C …) stay where they are.
//!
//! The feed of each move is the generator's (FFD into the depth, FFP1 in the
//! plane, FFP2 finishing): a change is planned as [`Step::Feedrate`] before the
//! move. A spindle speed the cycle sets (SSF) is set back to the call's when
//! the cycle ends.

use super::StepQueue;
use super::emit::Step;
use super::profile::Profile;
use crate::alarm::AlarmKind;
use crate::axis::{Axis, Pos};
use crate::canon::Plane;
use crate::geom::SegKind;
use crate::modal::State;
use cycle_paths::step::push;
use mill_paths::{Contour, Elem, MillGen, Move, P3};

/// A milling cycle being run: its generator and the plane it lies in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MillRun {
    path: MillGen,
    map: PlaneMap,
}

/// How a milling cycle's moves become planned steps: the plane's axes and the
/// feed and speed planned so far.
#[derive(Clone, Copy, Debug, PartialEq)]
struct PlaneMap {
    /// Abscissa, ordinate, applicate.
    axes: [Axis; 3],
    /// The feed planned last (nm/min or nm/rev).
    feed: i64,
    /// The spindle speed of the call, and whether the cycle changed it.
    rpm: u32,
    speed_changed: bool,
}

/// The axes of `plane`: abscissa, ordinate, applicate (seed 001 lines 526-543).
pub fn plane_axes(plane: Plane) -> [Axis; 3] {
    let (a, o) = plane.axes();
    [a, o, plane.normal()]
}

impl MillRun {
    /// The run of `path` in the active plane of `st`.
    pub fn new(path: MillGen, st: &State) -> Self {
        MillRun { path, map: PlaneMap::new(st) }
    }

    /// Plans the generator's next moves into `queue` while it has room for a move
    /// and its feed; false when the generator has ended. `here` is the work
    /// position (the axes outside the plane), `profile` the cycle's contour.
    pub fn fill(&mut self, profile: &Profile, here: Pos, queue: &mut StepQueue) -> Result<bool, AlarmKind> {
        let path = &mut self.path;
        self.map.fill(|| Ok(path.next(&Shape(profile))?), here, queue)
    }
}

impl PlaneMap {
    /// The mapping onto the active plane of `st`, from the feed and speed in force.
    fn new(st: &State) -> Self {
        let feed = st.feed.get(st.modal.feed_mode);
        PlaneMap { axes: plane_axes(st.modal.plane), feed, rpm: st.spindle.rpm, speed_changed: false }
    }

    /// `p` as a work position, the axes outside the plane from `here`.
    fn pos(&self, p: P3, here: Pos) -> Pos {
        let mut w = here;
        let [a, o, d] = self.axes;
        (w[a], w[o], w[d]) = (p.a, p.o, p.d);
        w
    }

    /// Plans the moves `next` yields into `queue` while it has room for a move
    /// and its feed; false when `next` has ended (the call's speed set back if the
    /// cycle changed it).
    fn fill(
        &mut self,
        mut next: impl FnMut() -> Result<Option<Move>, AlarmKind>,
        here: Pos,
        queue: &mut StepQueue,
    ) -> Result<bool, AlarmKind> {
        while queue.capacity() - queue.len() >= 2 {
            let Some(m) = next()? else {
                if self.speed_changed {
                    self.speed_changed = false;
                    push(queue, Step::Speed(self.rpm))?;
                }
                return Ok(false);
            };
            let step = match m {
                Move::Rapid(p) => Step::RapidTo(self.pos(p, here)),
                Move::Line { to, feed } => {
                    self.feed_of(feed, queue)?;
                    Step::FeedTo(self.pos(to, here))
                }
                Move::Arc { to, centre, cw, feed } => {
                    self.feed_of(feed, queue)?;
                    Step::ArcTo { to: [to.a, to.o, to.d], centre, cw }
                }
                Move::Dwell(ms) => Step::Dwell(ms),
                Move::Speed(rpm) => {
                    self.speed_changed = true;
                    Step::Speed(rpm)
                }
            };
            push(queue, step)?;
        }
        Ok(true)
    }

    /// Plans a change to `feed` if it is not the feed in force.
    fn feed_of(&mut self, feed: i64, queue: &mut StepQueue) -> Result<(), AlarmKind> {
        if feed != self.feed {
            self.feed = feed;
            push(queue, Step::Feedrate(feed))?;
        }
        Ok(())
    }
}

/// CYCLE73 being run: the path [`mill_paths::island::plan`] laid out when the
/// cycle started (shared by the run and its dry run: a copy is a count), and how
/// far it has been planned.
#[cfg(feature = "mill-island")]
#[derive(Clone, Debug, PartialEq)]
pub struct IslandRun {
    map: PlaneMap,
    moves: alloc::sync::Arc<[Move]>,
    at: usize,
}

#[cfg(feature = "mill-island")]
impl IslandRun {
    /// The run of `moves` in the active plane of `st`.
    pub fn new(moves: alloc::vec::Vec<Move>, st: &State) -> Self {
        IslandRun { map: PlaneMap::new(st), moves: moves.into(), at: 0 }
    }

    /// As [`MillRun::fill`], from the planned moves.
    pub fn fill(&mut self, here: Pos, queue: &mut StepQueue) -> Result<bool, AlarmKind> {
        let (moves, at) = (&self.moves, &mut self.at);
        self.map.fill(
            || {
                let m = moves.get(*at).copied();
                *at = at.saturating_add(1);
                Ok(m)
            },
            here,
            queue,
        )
    }
}

/// A pocket's contours read in the working plane (CYCLE73: its edge, then its
/// islands), as [`mill_paths::island`] takes them.
#[cfg(feature = "mill-island")]
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PocketShape {
    /// The edge (CYCLE74).
    pub edge: alloc::vec::Vec<Elem>,
    /// The islands (CYCLE75), in the order transferred.
    pub islands: alloc::vec::Vec<alloc::vec::Vec<Elem>>,
}

#[cfg(feature = "mill-island")]
impl PocketShape {
    /// The islands as slices.
    pub fn island_refs(&self) -> alloc::vec::Vec<&[Elem]> {
        self.islands.iter().map(|v| v.as_slice()).collect()
    }
}

/// Reads the pocket `edge` and its `islands` in the active plane of `st`, each
/// through `profile` (the cycle's shape store) with the contour reader of
/// CYCLE72 ([`super::profile::read_contour`]). A contour that cannot be
/// prepared is CYCLE73's 61983 (the edge) or 61980 (an island), one of more than
/// the store's 48 elements 61903.
#[cfg(feature = "mill-island")]
pub fn read_pocket<'a, E: crate::env::Environment + ?Sized>(
    edge: &crate::lang::siemens::call::ContourSource<'a>,
    islands: impl Iterator<Item = crate::lang::siemens::call::ContourSource<'a>>,
    st: &State,
    cfg: &crate::config::MachineConfig,
    env: &E,
    execute: super::Execute,
    profile: &mut Profile,
) -> Result<PocketShape, AlarmKind> {
    use crate::alarm::CycleAlarm;
    let mut read = |src: &crate::lang::siemens::call::ContourSource<'_>, code: u16| {
        super::profile::read_contour(src, st.modal.plane, 2, st, cfg, env, execute, profile).map_err(|e| match e {
            AlarmKind::SiemensCycle(CycleAlarm::ContourPreparation { cause: 10934 }) => {
                CycleAlarm::IslandPocket { code: 61903 }.into()
            }
            AlarmKind::SiemensCycle(CycleAlarm::ContourPreparation { .. }) => CycleAlarm::IslandPocket { code }.into(),
            e => e,
        })?;
        let shape = Shape(profile);
        Ok::<_, AlarmKind>((0..shape.len()).map(|i| shape.elem(i)).collect())
    };
    let edge = read(edge, 61983)?;
    let islands = islands.map(|src| read(&src, 61980)).collect::<Result<_, _>>()?;
    Ok(PocketShape { edge, islands })
}

/// The cycle's contour as the generators read it: the shape store's elements in
/// the plane (a shape's point keeps the abscissa in `z`, the ordinate in `x`, as
/// a lathe's G18 ZX shape does).
struct Shape<'a>(&'a Profile);

impl Contour for Shape<'_> {
    fn len(&self) -> usize {
        self.0.segs.len()
    }

    fn elem(&self, i: usize) -> Elem {
        let Some(&s) = self.0.segs.get(i) else { return mill_paths::NoContour.elem(0) };
        let arc = match s.kind {
            SegKind::Arc { center, cw } => Some(((center.z, center.x), cw)),
            _ => None,
        };
        Elem { from: (s.a.z, s.a.x), to: (s.b.z, s.b.x), arc }
    }
}

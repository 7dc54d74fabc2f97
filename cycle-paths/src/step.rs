//! The steps a cycle's generator plans, and the queue it plans them into. The
//! interpreter's emitter (`interp_core::cycles::emit`) turns each into canonical
//! actions: end points in both coordinate systems, soft limits, feed, spindle.

use crate::alarm::AlarmKind;
use crate::axis::Pos;
use crate::canon::{SpindleDir, ThreadSync};

pub use crate::geom::Pt;
use crate::geom::{Seg, SegKind};

/// The step queue was full (a generator's bug: each checks for room first). At a
/// `?` it becomes alarm [`AlarmKind::Overflow`], as the engine's own push says.
#[derive(Debug)]
pub struct Full;

impl From<Full> for AlarmKind {
    fn from(_: Full) -> Self {
        AlarmKind::Overflow
    }
}

/// Queues a planned step for the generators. Its error carries nothing, so each
/// of the generators' ~130 `push(..)?` sites tests one register and shares one
/// exit instead of copying an alarm out (~1 KB of flash).
#[inline(never)]
pub fn push(out: &mut crate::StepQueue, s: Step) -> Result<(), Full> {
    crate::push(out, s).map_err(|_| Full)
}

/// One move (or other action) a cycle plans.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Step {
    /// Rapid to a point.
    Rapid(Pt),
    /// Rapid to a work position of all axes (hole positions with C).
    RapidTo(Pos),
    /// Cutting feed to a point at the cycle's feed.
    Feed(Pt),
    /// Cutting feed at the cycle's feed to a work position of all axes (the hole
    /// cycles).
    FeedTo(Pos),
    /// Cutting feed to a work position at the cycle's lead per revolution
    /// ([`Emitter::lead`]: floating tapping follows the spindle).
    FeedPerRev(Pos),
    /// Arc at the cycle's feed.
    Arc {
        /// End point.
        to: Pt,
        /// Centre.
        center: Pt,
        /// G02.
        cw: bool,
    },
    /// Spindle-synchronised thread move.
    Thread {
        /// End point.
        to: Pt,
        /// Lead along the long axis, nm/rev.
        lead: i64,
        /// Lead change per revolution (G34).
        delta: i64,
        /// Start angle after the index, µdeg.
        start_udeg: u32,
        /// Index or continue.
        sync: ThreadSync,
    },
    /// Rigid tapping move along one axis at the cycle's lead ([`Emitter::lead`]).
    Tap {
        /// End point (work, all axes).
        to: Pos,
        /// Spindle direction during the move.
        dir: SpindleDir,
    },
    /// Cutting feed to a work position of all axes at a given feed (polar
    /// interpolation's X/C moves).
    PolarFeed {
        /// Work X (radius), nm.
        x: i64,
        /// Work C, µdeg.
        c: i64,
        /// Work Z, nm.
        z: i64,
        /// Feed of this move in the cycle's feed mode (nm/min or nm/rev).
        feed: i64,
        /// Source line of the programmed move it belongs to.
        line: u32,
    },
    /// Arc in the active plane at the cycle's feed to `to` about `centre` (the
    /// plane's two axes): a change of the plane's normal axis makes it a helix,
    /// an end on the start in the plane a full turn (the milling cycles,
    /// `cycles::mill`). The axes outside the plane stay where they are.
    ArcTo {
        /// End point: abscissa, ordinate, applicate of the plane (work).
        to: [i64; 3],
        /// Centre (abscissa, ordinate of the plane), work.
        centre: (i64, i64),
        /// G02.
        cw: bool,
    },
    /// Dwell.
    Dwell(u32),
    /// The cycle's cutting feed from here on, in its feed mode (CYCLE95 FF1–FF3).
    Feedrate(i64),
    /// Spindle direction change at the remembered speed.
    Spindle(SpindleDir),
    /// Spindle speed (rev/min, G97) from here on, in the direction in force (a
    /// milling cycle's finishing speed).
    Speed(u32),
    /// A machine output by M code (M19 spindle orientation of the boring cycles).
    Aux(u16),
    /// A stop for the operator: the machine waits for cycle start (G88 at the
    /// bottom of the hole).
    Stop,
}

/// The contour pass move of a shape segment (the shape's G00 stays a rapid; out
/// of line: G71/G72's and G73's contour passes).
#[inline(never)]
pub fn contour_step(s: &Seg) -> Step {
    match s.kind {
        SegKind::Rapid => Step::Rapid(s.b),
        SegKind::Line => Step::Feed(s.b),
        SegKind::Arc { center, cw } => Step::Arc { to: s.b, center, cw },
    }
}

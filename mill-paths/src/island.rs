//! CYCLE73 pocket milling with islands (seed 001 lines 6150-7392): the tool paths
//! of a pocket whose edge (CYCLE74) and islands (CYCLE75) are free contours of
//! lines and arcs in the working plane. A real offsetting of the pocket minus its
//! islands, not a rectangle approximation.
//!
//! INTERFACE (the lead's design commit; the body is the geometry helper's work):
//! the front end (`interp-siemens`' CYCLE73) reads and checks the call, the
//! engine (`interp-core`) reads the contours into [`Elem`] lists in plane nm and
//! calls [`plan`] once when the cycle starts; the moves it returns are emitted one
//! by one (dry run first, then the real run). [`start_points`] gives the insertion
//! points for pre-drilling (`_VARI` units 5): the modal drilling cycle runs at
//! each. Built only with the feature `island` (it needs `alloc`: the host and
//! boards with a heap; the F405 leaves the cycle out, alarm 4007).

extern crate alloc;

use crate::infeed::Levels;
use crate::{CycleAlarm, Elem, Move};
use alloc::vec::Vec;

/// How the cutter gets down to a level at an insertion point (`_VARI` tens).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Plunge {
    /// G1 straight down at `_FFD` (`_VARI` x1x; also the finishing jobs').
    Vertical,
    /// On a helix of centre-path radius `rad` (`_RAD`) in the pocket's milling
    /// direction, in whole turns of at most `pitch` (`_DP1`) per turn, then one
    /// flat full circle (`_VARI` x2x).
    Helix {
        /// Radius of the tool centre's helix.
        rad: i64,
        /// Largest depth per turn.
        pitch: i64,
    },
    /// Oscillating along a straight line at a slope of at most `tan` (the tangent
    /// of `_RAD`, the largest insertion angle), then one flat pass (`_VARI` x3x).
    Swing {
        /// Tangent of the largest insertion angle.
        tan: f64,
    },
}

/// What one CYCLE73 call cuts (`_VARI` units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Job {
    /// 1: clear the pocket from solid down to the allowances `fal`/`fald`.
    Rough,
    /// 2: clear what a previous clearing with the larger cutter radius `prev_r`
    /// left (its corners and narrow places), with this smaller cutter.
    Rest {
        /// Radius of the cutter of the previous clearing (`_TN`'s tool).
        prev_r: i64,
    },
    /// 3: finish the edge and each island once around (per level), reached and
    /// left on tangential arcs.
    Edge,
    /// 4: finish the floor in one level (the front end's `levels`).
    Floor,
}

/// A CYCLE73 call as the geometry needs it; lengths nm, work coordinates of the
/// plane (abscissa, ordinate) and the applicate (infeed axis).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IslandSpec {
    /// What is cut.
    pub job: Job,
    /// Cutter radius (> 0).
    pub r: i64,
    /// Allowance left on the edge and the islands in the plane (`_FAL`; 0 for the
    /// edge finish).
    pub fal: i64,
    /// Largest step between neighbouring paths in the plane (`_MIDA`, or 80 % of
    /// the cutter diameter).
    pub step: i64,
    /// The depth levels (from RFP + SDIS to the job's last level: `_DP` + `_FALD`
    /// roughing, `_DP` finishing; one level for the floor finish).
    pub levels: Levels,
    /// Retract plane `_RTP`.
    pub rtp: i64,
    /// RFP + SDIS.
    pub safe: i64,
    /// `_SDIS`.
    pub sdis: i64,
    /// +1 or −1: into the material along the applicate.
    pub dir: i64,
    /// `_VARI` hundreds: 0 retract to `_RTP`, 1 to RFP + SDIS, between insertion
    /// points and at the end.
    pub lift: u8,
    /// Insertion.
    pub plunge: Plunge,
    /// `_VARI` thousands 2: the manual start point (`_PA`, `_PO`); the cycle adds
    /// its own where the pocket divides. `None`: automatic.
    pub start: Option<(i64, i64)>,
    /// The pocket is cut clockwise (G2) around its edge: from `_CDIR` and the
    /// spindle direction (the front end's).
    pub cw: bool,
    /// Feeds: depth `_FFD`, plane `_FFP1`.
    pub feeds: [i64; 2],
}

/// The moves of one CYCLE73 call: from where the cycle starts (at or above the
/// retract plane) to the retract at the end; `edge` is the pocket's edge, each of
/// `islands` one island, closed contours in the plane (as CYCLE74/CYCLE75 gave
/// them: either sense). Alarms (61901, 61904, 61908-61918, 61980-61983): the
/// call moves nothing.
pub fn plan(spec: &IslandSpec, edge: &[Elem], islands: &[&[Elem]]) -> Result<Vec<Move>, CycleAlarm> {
    let _ = (spec, edge, islands);
    Err(CycleAlarm::IslandPocket { code: 61912 })
}

/// The insertion points the clearing of `spec` would use (pre-drilling,
/// `_VARI` units 5: the front end runs the modal drilling cycle at each), in the
/// order they are cut.
pub fn start_points(spec: &IslandSpec, edge: &[Elem], islands: &[&[Elem]]) -> Result<Vec<(i64, i64)>, CycleAlarm> {
    let _ = (spec, edge, islands);
    Err(CycleAlarm::IslandPocket { code: 61912 })
}

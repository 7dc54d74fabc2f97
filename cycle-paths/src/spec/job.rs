//! What a front end asks the cycle engine to do, in the engine's own terms: the
//! specifications of the shared generators in internal units (nm, X as a radius,
//! µdeg, ms). FANUC's G76 and SINUMERIK's CYCLE97/CYCLE98 both become a
//! [`MultiThreadSpec`] for the one infeed engine (`cycles::thread`); G71/G72 and
//! CYCLE95 a [`RoughSpec`] for the one roughing generator (`cycles::rough`) …
//! The data is defined here, below the languages that fill it in; the generators
//! that run it are in [`crate::cycles`] (data down, logic up).

use crate::geom::Pt;

/// Pull-out of a G92/G76 thread pass: parameter 5130 (tenths of the lead) along the
/// long axis, the short axis at the angle of 5131 from the long axis (0 = 45°).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Pullout {
    /// Tenths of the pitch (5130 / G76 r); 0 = no pull-out.
    pub tenths: i64,
    /// Angle in degrees (5131), 0 = 45°.
    pub angle_deg: i64,
}

/// How the infeed engine splits the thread depth into rough passes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Depths {
    /// G76 (2.17.4): the first pass at Δd, pass n at √n·Δd but at least Δdmin
    /// deeper than the one before, up to the height less the allowance.
    Root {
        /// First depth Δd (radius).
        first: i64,
        /// Minimum depth increase Δdmin (radius).
        min_depth: i64,
    },
    /// CYCLE97/CYCLE98: `passes` rough passes down to the height less the
    /// allowance, with the same infeed each (constant infeed: pass k at k/n of the
    /// depth) or with the same chip cross-section each (a V thread's cut area grows
    /// with the square of the depth: pass k at √(k/n) of the depth).
    Split {
        /// Rough passes (NRC).
        passes: u32,
        /// Constant cross-section (VARI 3/4) instead of constant infeed (VARI 1/2).
        constant_section: bool,
    },
}

/// Where the passes of a thread lie along the long axis as they go deeper.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Flank {
    /// G76: the pass start moves by depth × tan(angle) towards the thread end, the
    /// pass still ends at the thread end (the tool follows one flank; 0 = radial).
    FromStart {
        /// Half the tool angle a (the infeed angle), µdeg.
        angle_udeg: i64,
    },
    /// CYCLE97/CYCLE98 IANG: every pass lies on a flank of the finished thread, which
    /// the last pass cuts at the programmed place: pass at depth d moves by
    /// (height − d) × tan(angle) along the long axis, always to the same side
    /// (`alternate` false, IANG > 0) or to alternate sides (IANG < 0, cylindrical
    /// threads only). 0 = radial infeed.
    ToFinal {
        /// |IANG|, µdeg.
        angle_udeg: i64,
        /// Alternating flanks.
        alternate: bool,
    },
}

/// Most points a thread chain has: start, two intermediate points, end (CYCLE98).
pub const CHAIN_POINTS: usize = 4;

/// What the thread infeed engine cuts (G76; CYCLE97, CYCLE98). All values radius, nm.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MultiThreadSpec {
    /// Where the tool is when the cycle starts, and where a G76 pass returns to.
    pub start: Pt,
    /// The thread's nominal line at depth 0 (the crest of an outside thread, the
    /// bore of an inside one): `points[0]` is where a pass starts (after the run-in),
    /// `points[count - 1]` where it ends (after the run-out).
    pub points: [Pt; CHAIN_POINTS],
    /// How many of `points` are used (2–4).
    pub count: usize,
    /// Lead along the long axis of segment i (points i → i+1), nm/rev.
    pub leads: [i64; CHAIN_POINTS - 1],
    /// The long axis is X (a face thread, taper over 45°) rather than Z.
    pub face: bool,
    /// +1 if going deeper is the positive direction of the infeed axis (an inside
    /// longitudinal thread), −1 if negative.
    pub inward: i64,
    /// Thread height k (TDEP).
    pub height: i64,
    /// Finishing allowance d (FAL): the rough passes stop at `height − allowance`.
    pub allowance: i64,
    /// How the rough passes split the depth.
    pub depths: Depths,
    /// Passes at the full height after the rough passes (G76 m; CYCLE97 the
    /// finishing cut when FAL > 0 plus the NID idle passes).
    pub finish: u32,
    /// Where each pass lies along the long axis.
    pub flank: Flank,
    /// Pull-out at the end of each pass (G76; none for CYCLE97/98).
    pub pull: Pullout,
    /// The infeed-axis value a pass retracts to at its end before the tool returns
    /// along the long axis to `start` (G76: the start point's X; CYCLE97: _VRT
    /// above the thread).
    pub retract: i64,
    /// Number of thread starts, the whole sequence of passes cut for each.
    pub starts: u32,
    /// Spindle angle after the index where the first start begins, µdeg; start i
    /// begins i × 360° / `starts` later.
    pub start_udeg: u32,
}

/// The blank a stock-removal cycle starts from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Blank {
    /// The cylinder (or face) through the contour's highest point.
    Contour,
    /// A cylinder of this radius (a face at this Z for face machining): the point's
    /// coordinate on the infeed axis.
    At(Pt),
    /// The contour with this allowance round it (X radius, Z).
    Allowance(Pt),
}

/// How far a roughing cut follows the contour before it leaves it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pull {
    /// Not at all: the tool leaves the contour where the cut meets it (CYCLE950
    /// `_VARI` thousands 2).
    None,
    /// Up to the previous cut's point (CYCLE95 VARI hundreds 2, CYCLE950 thousands 1).
    Previous,
    /// Over one more cut point, overlapping (CYCLE95 VARI hundreds 0).
    Overlap,
}

/// What the stock-removal generator does with a contour (CYCLE95, seed 001 4.5):
/// axis-parallel roughing in sections of equal infeed, following the contour after
/// every cut, and a finishing pass with the nose compensated. Values radius, nm.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StockSpec {
    /// Face machining: infeed along Z, cuts along X (else longitudinal).
    pub facing: bool,
    /// Inside: infeed in the positive direction (else outside: negative).
    pub internal: bool,
    /// Rough the contour.
    pub rough: bool,
    /// Finish it.
    pub finish: bool,
    /// Most infeed of a roughing pass (MID as a radius for X), nm.
    pub depth: i64,
    /// Allowance in X (FALX, radius), Z (FALZ) and along the contour (FAL), nm.
    pub allow_x: i64,
    /// Allowance in Z.
    pub allow_z: i64,
    /// Allowance along the contour.
    pub allow: i64,
    /// Feeds in the feed mode in force: roughing (FF1), plunging into an undercut
    /// along its contour (FF2), finishing (FF3); 0 = the feed in force.
    pub feeds: [i64; 3],
    /// How far each cut follows the contour before the tool retracts.
    pub pull: Pull,
    /// The passes of a section: equal ones of at most MID (CYCLE95), or full MID
    /// ones until less than two are left, then two halves (CYCLE950).
    pub equal: bool,
    /// Rough the undercuts (CYCLE950 `_VARI` ten-thousands 2: only the main section).
    pub undercuts: bool,
    /// Contour-parallel roughing (CYCLE950 `_VARI` units 3): the passes are copies of
    /// the contour moved out by the blank's allowance `blank` in steps of MID (G73's
    /// pattern) instead of axis-parallel cuts.
    pub parallel: bool,
    /// The blank beyond the contour (CYCLE950 `_APX`/`_APZ`); CYCLE95: the cylinder
    /// through the contour's highest point.
    pub blank: Blank,
    /// The machining direction asked for along the cutting axis (CYCLE950 `_VARI`
    /// hundred-thousands), +1 or −1; 0: from the contour's lower end up.
    pub direction: i64,
    /// Angle the tool leaves the contour at after a cut (CYCLE950 `_ANGB`; 45°), µdeg.
    pub retract_angle_udeg: i64,
    /// Feed on the finishing contour's arcs (CYCLE950 `_FF4`); 0 = the finishing feed.
    pub arc_feed: i64,
    /// Rapids stop this far before the blank, the rest is cut (CYCLE950 `_TOL1`); 0:
    /// _VRT, as CYCLE95.
    pub approach: i64,
    /// Chip breaking: interrupt every roughing cut after this path length (DAM; 0 = never)…
    pub interrupt: i64,
    /// … and dwell this long there (DT), ms.
    pub dwell_ms: u32,
    /// Retract from the contour in both axes after a cut (_VRT), nm.
    pub retract: i64,
}

/// What the grooving generator does (CYCLE93, seed 001 4.3): axis-parallel plunges
/// side by side across the groove with pecks (G74/G75's columns), the flanks cut
/// along their slope, then each side finished along the contour with its own
/// cutting edge. The contours come with the spec as segments (work, X radius):
/// ranges of them are named here.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GrooveSpec {
    /// A face groove: the plunges go along Z and step along X (else along X).
    pub face: bool,
    /// +1 when going deeper is the positive direction of the plunge axis.
    pub inward: i64,
    /// The groove's edges on the surface (start side first): the plunges start on
    /// the line through them, `safety` off it.
    pub edges: [Pt; 2],
    /// Safety distance off the surface and the chip-breaking retract (_VRT), nm.
    pub safety: i64,
    /// Infeed of one peck along the plunge axis (IDEP), nm.
    pub peck: i64,
    /// Dwell at the bottom of each plunge (DTB), ms.
    pub dwell_ms: u32,
    /// Out of each plunge at the cutting feed (`_ZSD[4]` = 0) rather than rapid.
    pub retract_feed: bool,
    /// Where edge D + 1 is when the tool is positioned by edge D (work), nm.
    pub span: Pt,
    /// Nose radius and cutting edge position of edge D and of edge D + 1.
    pub noses: [(i64, u8); 2],
    /// The contour with the allowances (the plunges and flank cuts stop on it).
    pub rough: (u16, u16),
    /// Each flank's line with its allowance, from off the surface down to its foot.
    pub flanks: (u16, u16),
    /// The finished contour of the start side and of the far side, each from the
    /// surface outside its edge to the middle of the bottom.
    pub halves: [(u16, u16); 2],
    /// The tool is left of the start side's finishing path in the (Z, X) plane.
    pub half1_left: bool,
}

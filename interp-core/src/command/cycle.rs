//! The cycle words of a checked block in internal units: what a front end tells
//! the canned cycles ([`crate::cycles`]) about the cycle a block starts, and which
//! G codes are cycles.

use crate::alarm::AlarmKind;
use crate::codes::GCode;
use crate::units::{NM_PER_INCH, Units};

/// Largest thread lead, mm (FANUC's F range for threading in IS-B).
const MAX_LEAD_MM: i64 = 500;

/// The cycle data of a checked block, internal units (nm, X values as radii unless
/// noted, µdeg, ms).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum CycleArgs {
    /// Not a cycle block.
    #[default]
    None,
    /// G51.2 P Q R (2.8): work- and tool-spindle turns (1 when omitted) and the
    /// phase R of the tool spindle at the work spindle's index, µdeg.
    Polygon {
        /// P.
        p: u16,
        /// Q.
        q: u16,
        /// R, µdeg.
        phase_udeg: i64,
    },
    /// G90/G94: taper R (seed 003's I for G90), radius for G90, Z for G94.
    Single {
        /// Taper, if given.
        taper: Option<i64>,
    },
    /// G92: taper R/I, lead (F or E), number of starts H.
    ThreadCycle {
        /// Taper (radius), if given.
        taper: Option<i64>,
        /// Lead along the long axis, nm/rev, if given.
        lead: Option<i64>,
        /// Number of starts (H, 1 when omitted).
        starts: u8,
    },
    /// G32/G34: lead, start angle Q, lead change K.
    Thread {
        /// Lead (F/E), nm/rev, if given.
        lead: Option<i64>,
        /// Start angle in µdeg (Q), if given.
        start_udeg: Option<u32>,
        /// Lead change per revolution (G34 K), nm/rev per rev.
        delta: i64,
    },
    /// First G71/G72 block: depth of cut Δd and retract e.
    RoughSetup {
        /// Δd (U of G71, W of G72), unsigned.
        depth: Option<i64>,
        /// e (R), unsigned.
        retract: Option<i64>,
    },
    /// Second G71/G72/G73 block: the shape ns–nf and the finishing allowances.
    Shape {
        /// First block's sequence number.
        ns: u32,
        /// Last block's sequence number.
        nf: u32,
        /// Δu as a radius (signed).
        du: i64,
        /// Δw (signed).
        dw: i64,
    },
    /// First G73 block: relief Δi (radius), Δk and the number of passes d.
    PatternSetup {
        /// Δi (U), signed radius.
        di: Option<i64>,
        /// Δk (W), signed.
        dk: Option<i64>,
        /// d (R), passes.
        count: Option<u32>,
    },
    /// G70 P Q.
    Finish {
        /// First block's sequence number.
        ns: u32,
        /// Last block's sequence number.
        nf: u32,
    },
    /// First G74/G75 block: retract e.
    GrooveSetup {
        /// e (R), unsigned.
        retract: Option<i64>,
    },
    /// Second G74/G75 block: P(Δi, radius), Q(Δk), R(Δd).
    Groove {
        /// Δi, X step (radius), unsigned.
        p: i64,
        /// Δk, Z step, unsigned.
        q: i64,
        /// Δd, relief at the bottom, unsigned.
        relief: i64,
    },
    /// First G76 block: P(m)(r)(a), Q(Δdmin), R(d).
    ThreadSetup {
        /// m, r, a unpacked from P (note 4).
        packed: Option<(u32, u32, u32)>,
        /// Δdmin (radius).
        min_depth: Option<i64>,
        /// d (radius).
        allowance: Option<i64>,
    },
    /// Second G76 block: R(i), P(k), Q(Δd), F.
    MultiThread {
        /// Taper i (radius), 0 when omitted.
        taper: i64,
        /// Thread height k (radius).
        height: Option<i64>,
        /// First depth Δd (radius).
        first: Option<i64>,
        /// Lead, nm/rev.
        lead: Option<i64>,
    },
    /// G02.1/G03.1 (A, B, Q) and G02.2/G03.2 (P, Q): the curve's size and turn.
    Curve {
        /// Ellipse semi-axis A along the long axis, nm.
        a: Option<i64>,
        /// Ellipse semi-axis B, nm.
        b: Option<i64>,
        /// Parabola parameter P of y² = 2px, nm.
        p: Option<i64>,
        /// Q: the long axis (ellipse) or the axis (parabola) turned clockwise from
        /// +Z, µdeg (0 when omitted).
        q_udeg: i64,
    },
    /// G10 (mill): L, P and R of programmable data input; the axis words are the
    /// block's.
    Data {
        /// L: 2, 10–13 or 20.
        l: u8,
        /// P: frame (L2: 0–6, L20: 1–48) or offset number (L10–L13).
        p: u16,
        /// R: the offset value (L10–L13), nm.
        r: Option<i64>,
    },
    /// G51 (mill): P, or I/J/K per axis, in thousandths (negative = mirror); the
    /// centre is the block's X/Y/Z.
    Scale {
        /// P: one factor for every axis.
        p: Option<i32>,
        /// I, J, K: the factors of X, Y, Z.
        ijk: [Option<i32>; 3],
    },
    /// G68 (mill): the angle R in µdeg; the centre is the block's axis words.
    Rotate {
        /// R, µdeg (counter-clockwise positive).
        r_udeg: Option<i64>,
    },
    /// G83–G89 hole data.
    Hole {
        /// R: initial level → R level, signed radius value.
        r: Option<i64>,
        /// P: dwell at the bottom, ms.
        dwell_ms: Option<u32>,
        /// Q: peck depth.
        q: Option<i64>,
        /// K: repetitions.
        repeat: Option<u32>,
    },
}

/// Whether `code` is one of the canned cycles of this module.
pub fn is_cycle(code: GCode) -> bool {
    is_multiple(code) || is_single(code) || is_thread(code) || is_hole(code)
}

/// G70–G76, and a SINUMERIK cycle call (next to them in [`GCode`], so that the
/// test stays one range compare).
pub fn is_multiple(code: GCode) -> bool {
    use GCode::*;
    matches!(
        code,
        FinishCycle
            | RoughTurnCycle
            | RoughFaceCycle
            | PatternCycle
            | FacePeckCycle
            | GroovePeckCycle
            | MultiThreadCycle
            | CycleCall
    )
}

/// G90, G92, G94.
pub fn is_single(code: GCode) -> bool {
    matches!(code, GCode::TurningCycle | GCode::ThreadCycle | GCode::FacingCycle)
}

/// G32, G34.
pub fn is_thread(code: GCode) -> bool {
    matches!(code, GCode::Thread | GCode::VariableLeadThread)
}

/// The hole cycles: a lathe's G83–G89, a machining centre's G73–G89 (group 10
/// without G80). The mill's codes are listed here again rather than asked of
/// [`is_mill_hole`]: one test of the whole set; the call form cost a plain G01 31
/// instructions (`m4-tests/bench.sh bench_interp`). The same holds for
/// `Command::moves_axes`.
pub fn is_hole(code: GCode) -> bool {
    use GCode::*;
    matches!(
        code,
        FaceDrill
            | FaceTap
            | FaceBore
            | SideDrill
            | SideTap
            | SideBore
            | HighSpeedPeck
            | LeftTap
            | FineBore
            | Drill
            | DrillDwell
            | PeckDrill
            | Tap
            | Bore
            | BoreSpindleStop
            | BackBore
            | BoreManual
            | BoreDwell
    )
}

/// A machining centre's hole cycles (G73–G89 of the M series).
pub fn is_mill_hole(code: GCode) -> bool {
    use GCode::*;
    matches!(
        code,
        HighSpeedPeck
            | LeftTap
            | FineBore
            | Drill
            | DrillDwell
            | PeckDrill
            | Tap
            | Bore
            | BoreSpindleStop
            | BackBore
            | BoreManual
            | BoreDwell
    )
}

/// Whether the F word of `code` is a thread lead rather than a feed.
pub fn f_is_lead(code: GCode) -> bool {
    matches!(code, GCode::Thread | GCode::VariableLeadThread | GCode::ThreadCycle | GCode::MultiThreadCycle)
}

/// Whether the X/Z/U/W words of `code` are an end point (false for G70–G73, whose
/// U/W are depths and allowances).
pub fn axes_are_points(code: GCode) -> bool {
    !matches!(code, GCode::FinishCycle | GCode::RoughTurnCycle | GCode::RoughFaceCycle | GCode::PatternCycle)
}

/// A lead must be positive and at most 500 mm (19.7 in).
pub fn check_lead(lead: i64, units: Units) -> Result<(), AlarmKind> {
    let max = match units {
        Units::Metric => MAX_LEAD_MM * 1_000_000,
        Units::Inch => 19_685 * NM_PER_INCH / 1_000,
    };
    if lead <= 0 || lead > max {
        return Err(AlarmKind::IllegalLead);
    }
    Ok(())
}

//! The checked block: what every language's front end hands the execution layers.
//!
//! A front end ([`crate::lang`]: FANUC words, SINUMERIK words) reads a block of its
//! language, checks it against the machine and the modal state and fills a
//! [`Command`]: G codes by meaning ([`GSet`], [`crate::codes::GCode`]), M codes by
//! function, axis and arc words in internal units (nm, µdeg, X as a radius), the
//! cycle words ([`CycleArgs`]) and what the block asks of the program flow
//! ([`FlowWord`]). From here on nothing depends on the language a program was
//! written in: [`crate::exec::execute`] runs a command on the [`State`].

pub mod cycle;
mod gset;
pub use cycle_paths::spec::{hole, job};

pub use cycle::CycleArgs;
pub use gset::{EXTRA_FRAME, GSet, uses_axes};
// The `,C`/`,R` (FANUC) and `CHF=`/`RND=` (SINUMERIK) request is held by the
// contour look-ahead: defined with it.
pub use crate::modal::Corner;

use crate::axis::AXIS_COUNT;
use crate::codes::{GCode, MFunction};
use crate::modal::State;

/// Most M codes one block may hold (alarm 4010 beyond).
pub const MAX_M: usize = 3;

/// One axis word converted to internal units (X as radius).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AxisWord {
    /// Value in nm (µdeg for C).
    pub value: i64,
    /// Incremental (U/V/W/H, or X/Z under G91 of systems B/C).
    pub incremental: bool,
}

/// How a subprogram call was made.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum CallBy {
    /// M98.
    M98,
    /// A code the language lets call a subprogram (FANUC: an M code of parameters
    /// 6071–6079, or with 6001#5 a T code, whose value the front end passes on).
    Code,
}

/// What an M98, M99, M91 or M92 of the block asks for, with its P (and L), or a
/// subprogram call by an M or T code.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum FlowWord {
    /// M98 P… [L…]: run subprogram `program` `repeats` times (3.1.6, seed 003 2.5.1).
    Call {
        /// O number, 1–9999.
        program: u32,
        /// Repetitions, 1–9999 (`L`, or the digits before the last four of P).
        repeats: u16,
        /// M98 or a code.
        by: CallBy,
    },
    /// M99 [P…]: return to the caller, at sequence `seq` if given (3.1.7).
    Return {
        /// Sequence number to go on at in the caller.
        seq: Option<u32>,
    },
    /// M91/M92 P…: jump to `seq` when the external input is 1 (`high`) or 0 (3.1.5).
    Jump {
        /// Target sequence number, 1–99999.
        seq: u32,
        /// True for M92 (jump on 1), false for M91 (jump on 0).
        high: bool,
    },
}

/// A checked block: everything execution needs, in internal units.
#[derive(Clone, Debug, PartialEq)]
pub struct Command {
    /// Source line.
    pub line: u32,
    /// Sequence number.
    pub seq: Option<u32>,
    /// G codes by group.
    pub g: GSet,
    /// M codes with their functions, in the order written.
    pub m: heapless::Vec<(u16, MFunction), MAX_M>,
    /// Axis words by axis.
    pub axes: [Option<AxisWord>; AXIS_COUNT],
    /// Arc centre offsets I/J/K by axis (radius values, nm).
    pub center: [Option<i64>; AXIS_COUNT],
    /// Arc radius R (nm, negative = more than 180°).
    pub radius: Option<i64>,
    /// G04 dwell time in ms (0 = exact stop).
    pub dwell_ms: Option<u32>,
    /// Reference position number of G28 (1) or G30 P (1–4, default 2).
    pub reference: u8,
    /// F in nm per minute or per revolution (mode decided at execution).
    pub feed: Option<i64>,
    /// S as written (rev/min, surface speed, or G50 clamp).
    pub speed: Option<u32>,
    /// T: turret station and offset number (a machining centre's T selects a tool:
    /// offset 0).
    pub tool: Option<(u16, u16)>,
    /// Mill: H, the tool length offset number.
    pub h: Option<u16>,
    /// Mill: D, the cutter radius offset number.
    pub d: Option<u16>,
    /// M98/M99/M91/M92 with their words.
    pub flow: Option<FlowWord>,
    /// `,C`/`,R`: the corner to insert after the block's move (2.23).
    pub corner: Option<Corner>,
    /// Cycle words (G70–G76, G90/G92/G94, G32/G34, G83–G89), internal units.
    pub cycle: CycleArgs,
}

impl Command {
    /// A command with no words (what [`check_into`] starts from).
    pub const EMPTY: Command = Command {
        line: 0,
        seq: None,
        g: GSet::NONE,
        m: heapless::Vec::new(),
        axes: [None; AXIS_COUNT],
        center: [None; AXIS_COUNT],
        radius: None,
        dwell_ms: None,
        reference: 1,
        feed: None,
        speed: None,
        tool: None,
        h: None,
        d: None,
        flow: None,
        corner: None,
        cycle: CycleArgs::None,
    };

    /// Whether the block commands a move along an axis: it has an axis word and the
    /// code that uses it is a move, a turning, threading or hole cycle, or a
    /// reference or machine-coordinate move (not G04, G22, G50, G52, G12.1 …). A
    /// FANUC G66 modal call follows such blocks. A machining centre's G51, G51.1
    /// and G68 take the axis words as their centre: no move.
    pub fn moves_axes(&self, state: &State) -> bool {
        use GCode::*;
        self.axes.iter().any(Option::is_some)
            && self.g.frame.is_none()
            && matches!(
                self.axis_user(state),
                Rapid
                    | Linear
                    | ArcCw
                    | ArcCcw
                    | EllipseCw
                    | EllipseCcw
                    | ParabolaCw
                    | ParabolaCcw
                    | Thread
                    | VariableLeadThread
                    | TurningCycle
                    | ThreadCycle
                    | FacingCycle
                    | ReferenceReturn
                    | ReferenceReturnN
                    | MachineCoordinates
                    | FacePeckCycle
                    | GroovePeckCycle
                    | MultiThreadCycle
                    | FaceDrill
                    | FaceTap
                    | FaceBore
                    | SideDrill
                    | SideTap
                    | SideBore
                    | ReturnFromReference
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

    /// The code that consumes the block's axis words (a machining centre's G51,
    /// G51.1 and G68 take them too: its checker asks [`GSet::frame`] first).
    pub fn axis_user(&self, state: &State) -> GCode {
        use cycle::{is_hole, is_multiple};
        match (self.g.stroke, self.g.polar) {
            (Some(true), _) => return GCode::StrokeCheckOn,
            (Some(false), _) => return GCode::StrokeCheckOff,
            (_, Some(true)) => return GCode::PolarOn,
            (_, Some(false)) => return GCode::PolarOff,
            _ => {}
        }
        match self.g.polygon {
            Some(true) => return GCode::PolygonOn,
            Some(false) => return GCode::PolygonOff,
            None => {}
        }
        match self.g.one_shot {
            Some(c) if gset::uses_axes(c) || is_multiple(c) => c,
            _ => match self.g.drilling {
                Some(d) if is_hole(d) => d,
                None if self.g.motion.is_none() && is_hole(state.modal.drilling) => state.modal.drilling,
                _ => self.g.motion.unwrap_or(state.modal.motion),
            },
        }
    }

    /// Whether any axis word was given.
    pub fn has_axes(&self) -> bool {
        self.axes.iter().any(Option::is_some)
    }
}

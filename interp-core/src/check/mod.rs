//! Checking: a [`Block`] of words becomes a [`Command`] — G and M codes resolved,
//! every word verified to belong to the block, values converted to internal units.
//! Nothing here changes state; a block that fails never reaches execution.

pub mod cycle_args;
mod gset;
mod words;

pub use gset::GSet;
// The `,C`/`,R` request is held by the contour look-ahead: defined with it.
pub use crate::modal::Corner;

use crate::alarm::AlarmKind;
use crate::axis::{AXIS_COUNT, Axis};
use crate::codes::{GCode, MFunction, m_codes_conflict, m_function};
use crate::config::MachineConfig;
use crate::modal::State;
use crate::parse::{Block, MAX_M};
use crate::units::NumberFormat;

/// One axis word converted to internal units (X as radius).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AxisWord {
    /// Value in nm (µdeg for C).
    pub value: i64,
    /// Incremental (U/V/W/H, or X/Z under G91 of systems B/C).
    pub incremental: bool,
}

/// What an M98, M99, M91 or M92 of the block asks for, with its P (and L).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum FlowWord {
    /// M98 P… [L…]: run subprogram `program` `repeats` times (3.1.6, seed 003 2.5.1).
    Call {
        /// O number, 1–9999.
        program: u32,
        /// Repetitions, 1–9999 (`L`, or the digits before the last four of P).
        repeats: u16,
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
    /// T: turret station and offset number.
    pub tool: Option<(u16, u16)>,
    /// M98/M99/M91/M92 with their words.
    pub flow: Option<FlowWord>,
    /// `,C`/`,R`: the corner to insert after the block's move (2.23).
    pub corner: Option<Corner>,
    /// Cycle words (G70–G76, G90/G92/G94, G32/G34, G83–G89), internal units.
    pub cycle: crate::check::cycle_args::CycleArgs,
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
        flow: None,
        corner: None,
        cycle: crate::check::cycle_args::CycleArgs::None,
    };

    /// The code that consumes the block's axis words.
    pub fn axis_user(&self, state: &State) -> GCode {
        use crate::check::cycle_args::{is_hole, is_multiple};
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

/// Checks `block` against the machine and the current state.
pub fn check(block: &Block, state: &State, cfg: &MachineConfig) -> Result<Command, AlarmKind> {
    let mut cmd = Command::EMPTY;
    check_into(block, state, cfg, &mut cmd)?;
    Ok(cmd)
}

/// [`check`] into a command reused from block to block (nothing ~300 bytes large
/// is returned and copied per block). On an alarm `cmd` holds a partial result.
pub fn check_into(block: &Block, state: &State, cfg: &MachineConfig, cmd: &mut Command) -> Result<(), AlarmKind> {
    cmd.g.resolve_into(block, state, cfg)?;
    let fmt = NumberFormat {
        units: cmd.g.units.unwrap_or(state.modal.units),
        input: cfg.input_mode(),
        increments: cfg.increments,
    };
    cmd.line = block.line;
    cmd.seq = block.seq;
    resolve_m(block, cfg, &mut cmd.m)?;
    cmd.axes = [None; AXIS_COUNT];
    cmd.center = [None; AXIS_COUNT];
    cmd.radius = None;
    cmd.dwell_ms = None;
    cmd.reference = 1;
    cmd.feed = None;
    cmd.speed = None;
    cmd.tool = None;
    cmd.flow = None;
    cmd.corner = None;
    cmd.cycle = crate::check::cycle_args::CycleArgs::None;
    let flow_m = cmd.m.iter().map(|&(_, f)| f).find(|f| f.is_flow());
    let user = cmd.axis_user(state);
    words::check_letters(block, user, flow_m, cfg)?;
    words::convert(block, user, state, cfg, &fmt, cmd)?;
    cmd.flow = flow_m.map(|f| flow_word(block, f)).transpose()?;
    Ok(())
}

/// The P (and L) of M98, M99, M91, M92.
fn flow_word(block: &Block, f: MFunction) -> Result<FlowWord, AlarmKind> {
    let p = |max| block.get(b'P').map(|n| crate::parse::whole(b'P', &n, max)).transpose();
    match f {
        MFunction::Call => {
            let p = p(99_999_999)?.ok_or(AlarmKind::SubprogramNumberMissing)?;
            let (program, repeats) = match block.get(b'L') {
                Some(l) => (p, crate::parse::whole(b'L', &l, 9_999)?),
                // FANUC's packed form: P30012 = 3 times O0012.
                None if p > 9_999 => (p % 10_000, p / 10_000),
                None => (p, 1),
            };
            if !(1..=9_999).contains(&program) {
                return Err(AlarmKind::ValueOutOfRange { letter: b'P' });
            }
            if !(1..=9_999).contains(&repeats) {
                return Err(AlarmKind::ValueOutOfRange { letter: b'L' });
            }
            Ok(FlowWord::Call { program, repeats: repeats as u16 })
        }
        MFunction::Return => {
            let alone = block.g.is_empty()
                && block.m.len() == 1
                && block.letters().all(|l| l == b'P')
                && block.chamfer.is_none()
                && block.corner.is_none();
            if !alone {
                return Err(AlarmKind::M99NotAlone);
            }
            Ok(FlowWord::Return { seq: p(99_999)? })
        }
        _ => {
            let seq = p(99_999)?.ok_or(AlarmKind::MissingWord { letter: b'P', context: "M91/M92" })?;
            if seq == 0 {
                return Err(AlarmKind::ValueOutOfRange { letter: b'P' });
            }
            Ok(FlowWord::Jump { seq, high: f == MFunction::JumpIfHigh })
        }
    }
}

/// Looks up every M code into `out` and rejects contradicting pairs.
fn resolve_m(
    block: &Block,
    cfg: &MachineConfig,
    out: &mut heapless::Vec<(u16, MFunction), MAX_M>,
) -> Result<(), AlarmKind> {
    out.clear();
    for (i, &m) in block.m.iter().enumerate() {
        let f = m_function(m, cfg).ok_or(AlarmKind::UnknownMCode { m })?;
        if let Some(&other) = block.m[..i].iter().find(|&&o| m_codes_conflict(o, m)) {
            return Err(AlarmKind::ConflictingMCodes { first: other, second: m });
        }
        // Capacity equals the reader's, so this push cannot fail.
        let _ = out.push((m, f));
    }
    Ok(())
}

/// The axis addressed by `letter` and whether the letter is incremental.
pub(crate) fn axis_of(letter: u8) -> Option<(Axis, bool)> {
    Axis::ALL.into_iter().find_map(|a| {
        if a.letter() == letter {
            Some((a, false))
        } else if a.incremental_letter() == letter {
            Some((a, true))
        } else {
            None
        }
    })
}

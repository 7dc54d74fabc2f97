//! Checking: a [`Block`] of words becomes a [`Command`] — G and M codes resolved,
//! every word verified to belong to the block, values converted to internal units.
//! Nothing here changes state; a block that fails never reaches execution.

pub mod cycle_args;
mod gset;
mod mill;
#[cfg(feature = "siemens")]
mod sinumerik;
mod words;

#[cfg(feature = "siemens")]
pub use sinumerik::sinumerik_plain;

use crate::alarm::AlarmKind;
use crate::axis::{AXIS_COUNT, Axis};
use crate::codes::{MFunction, m_codes_conflict, m_function};
use crate::command::{CallBy, Command, FlowWord};
use crate::config::MachineConfig;
use crate::lang::fanuc::parse::{Block, MAX_M};
use crate::modal::State;
use crate::units::NumberFormat;

/// Checks `block` against the machine and the current state.
pub fn check(block: &Block, state: &State, cfg: &MachineConfig) -> Result<Command, AlarmKind> {
    let mut cmd = Command::EMPTY;
    check_into(block, state, cfg, &mut cmd)?;
    Ok(cmd)
}

/// [`check`] into a command reused from block to block (nothing ~300 bytes large
/// is returned and copied per block). On an alarm `cmd` holds a partial result.
pub fn check_into(block: &Block, state: &State, cfg: &MachineConfig, cmd: &mut Command) -> Result<(), AlarmKind> {
    check_into_as::<false>(block, state, cfg, cmd)
}

/// [`check_into`]; `GENERAL` (tests only) checks a machining centre's plain moves
/// the general way too.
#[inline(always)]
fn check_into_as<const GENERAL: bool>(
    block: &Block,
    state: &State,
    cfg: &MachineConfig,
    cmd: &mut Command,
) -> Result<(), AlarmKind> {
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
    cmd.cycle = crate::command::cycle::CycleArgs::None;
    let flow_m = cmd.m.iter().map(|&(_, f)| f).find(|f| f.is_flow());
    let user = cmd.axis_user(state);
    if crate::is_mill(cfg) {
        // A machining centre's G51, G51.1 and G68 take the axis words too.
        let user = cmd.g.frame.unwrap_or(user);
        mill::check::<GENERAL>(block, user, flow_m, state, cfg, &fmt, cmd)?;
    } else {
        words::check_letters(block, user, flow_m, cfg)?;
        words::convert(block, user, state, cfg, &fmt, cmd)?;
    }
    cmd.flow = flow_m.map(|f| flow_word(block, f)).transpose()?;
    Ok(())
}

/// The alarm for M codes `first` and `second` that contradict each other; a
/// subprogram call by an M or T code stands in the block as an M98 and is named
/// by its own code.
#[cold]
fn conflict(block: &Block, first: u16, second: u16) -> AlarmKind {
    match block.sub_call() {
        Some(call) if first == 98 && call.t.is_some() => crate::lang::fanuc::parse::T_WITH_FLOW,
        Some(call) if first == 98 => AlarmKind::ConflictingMCodes { first: call.m, second },
        _ => AlarmKind::ConflictingMCodes { first, second },
    }
}

/// The P (and L) of M98, M99, M91, M92, or a subprogram call by an M or T code.
fn flow_word(block: &Block, f: MFunction) -> Result<FlowWord, AlarmKind> {
    let p = |max| block.get(b'P').map(|n| crate::lang::fanuc::parse::whole(b'P', &n, max)).transpose();
    match f {
        // A subprogram call by an M code (6071–6079) or a T code (6001#5), standing
        // in the block as an M98 (FANUC 0i: as M98 P would, without P or L).
        MFunction::Call if let Some(call) = block.sub_call() => {
            Ok(FlowWord::Call { program: call.program, repeats: 1, by: CallBy::Code })
        }
        MFunction::Call => {
            let p = p(99_999_999)?.ok_or(AlarmKind::SubprogramNumberMissing)?;
            let (program, repeats) = match block.get(b'L') {
                Some(l) => (p, crate::lang::fanuc::parse::whole(b'L', &l, 9_999)?),
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
            Ok(FlowWord::Call { program, repeats: repeats as u16, by: CallBy::M98 })
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
            return Err(conflict(block, other, m));
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lang::fanuc::parse::read_block;

    /// A machining centre's plain G00/G01 (the short way through the M-series
    /// checker) gives the command, or the alarm, the general way gives.
    #[test]
    fn mill_plain_moves_check_as_the_general_way() {
        let mut cfg = MachineConfig::mill();
        let blocks: &[&[u8]] = &[
            b"N101 G01 X-99.176 Y-99.424 Z-20.1",
            b"G01 X1. Y2. Z3. F300 S1200",
            b"G00 X10 Y-5",
            b"X5. Y6.",
            b"Z-1. F-3.",
            b"G01 X1. F0",
            b"G91 G01 X1. Y-1.",
            b"G01 X1. M06",
            b"G01 X1. M03 S500",
            b"G01 X1. S123456",
            b"G01 X1. T2",
            b"G01 X1. H2",
            b"G01 X1. D3",
            b"G41 G01 X1. Y1.",
            b"G43 G01 Z1. H1",
            b"G01 X1. C10.",
            b"G01 X1. U2.",
            b"G01 X1. Y2. ,C1.",
            b"G01 X1. Y2. ,R1.",
            b"G01 X999999999. Y1.",
            b"G01 X1. M98 P100",
            b"G53 G00 Z0",
            b"G16 G01 X10. Y30.",
            b"G01 X1. I2.",
            b"G02 X1. Y1. R5.",
            b"G01 X1. Y1. Z1. F1000.",
        ];
        let states = {
            let plain = State::power_on(&cfg, crate::axis::Pos::ZERO);
            let mut g91 = plain;
            g91.modal.incremental = true;
            let mut polar = plain;
            polar.mill.frame.active = crate::modal::mill::on::POLAR;
            [plain, g91, polar]
        };
        for pass in 0..2 {
            if pass == 1 {
                // A mill without Y: its words raise the alarm either way.
                cfg.axes[Axis::Y.index()].present = false;
            }
            for text in blocks {
                let Ok(block) = read_block(text, 1) else { continue };
                for state in &states {
                    let mut short = Command::EMPTY;
                    let mut general = Command::EMPTY;
                    let a = check_into_as::<false>(&block, state, &cfg, &mut short);
                    let b = check_into_as::<true>(&block, state, &cfg, &mut general);
                    let what = core::str::from_utf8(text).unwrap_or("?");
                    assert_eq!(a, b, "{what}");
                    if a.is_ok() {
                        assert_eq!(short, general, "{what}");
                    }
                }
            }
        }
    }
}

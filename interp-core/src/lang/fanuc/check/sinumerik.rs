//! The short check of a SINUMERIK line of plain words (issue 19): a line that
//! [`read_plain_line`](crate::lang::fanuc::parse::read_plain_line) read —
//! `N.. G1 X40.412 Z-0.05 F.2` — checked with SINUMERIK's meanings of its words,
//! on the shared checker's conversions, without the SINUMERIK front end's
//! statement reader and checker (`interp-siemens`, built for size).
//!
//! It gives the command the front end's checker gives for the same line, or
//! declines: a word or G function outside the short way, and every alarm, go the
//! front end's general way (`host-tests/tests/siemens_plain.rs` runs lines both
//! ways and compares).

use super::words::{Letters, length_nm};
use crate::axis::Axis;
use crate::canon::FeedMode;
use crate::codes::{GCode, m_codes_conflict, m_function};
use crate::command::{AxisWord, Command};
use crate::config::MachineConfig;
use crate::lang::fanuc::parse::Block;
use crate::modal::State;
use crate::units::{InputMode, NumberFormat};

/// The words of the short way: axes X/Y/Z, F, S (with G and M). T and D (tool
/// edges), I/J/K, C, H and every other letter go the general way.
const PLAIN: Letters = Letters::of(b"XYZFS");

/// What a SINUMERIK G function of the short way means to the engine.
#[derive(Clone, Copy)]
enum Meaning {
    /// A code of the engine.
    Code(GCode),
    /// G94 (false) / G95 (true): feed per minute / revolution, constant cutting speed off.
    Feed(bool),
    /// G96: constant cutting speed, feed per revolution (the 840D's group 15).
    CssOn,
    /// G97: constant cutting speed off.
    CssOff,
}

/// The G functions of the short way, numbered as SINUMERIK numbers them (G70/G71
/// inch/metric, G94–G97 one group), with the 840D's group; `None` for the others
/// (G4 reads F and S as its dwell, G290/G291 stand alone …): the general way.
fn g_function(n: u16) -> Option<(Meaning, u8)> {
    use GCode::*;
    use Meaning::Code;
    Some(match n {
        0 => (Code(Rapid), 1),
        1 => (Code(Linear), 1),
        2 => (Code(ArcCw), 1),
        3 => (Code(ArcCcw), 1),
        17 => (Code(PlaneXy), 6),
        18 => (Code(PlaneZx), 6),
        19 => (Code(PlaneYz), 6),
        40 => (Code(NoseCompOff), 7),
        41 => (Code(NoseCompLeft), 7),
        42 => (Code(NoseCompRight), 7),
        54..=57 => (Code(WorkFrame((n - 54) as u8)), 8),
        60 => (Code(ExactStopMode), 10),
        64 => (Code(ContinuousMode), 10),
        70 => (Code(Inch), 13),
        71 => (Code(Metric), 13),
        90 => (Code(Absolute), 14),
        91 => (Code(Incremental), 14),
        94 => (Meaning::Feed(false), 15),
        95 => (Meaning::Feed(true), 15),
        96 => (Meaning::CssOn, 15),
        97 => (Meaning::CssOff, 15),
        _ => return None,
    })
}

/// Checks plain line `block` with SINUMERIK's meanings into `cmd`: the command
/// the front end's checker gives, with nothing for the state besides it (no
/// DIAMON/DIAMOF, no LIMS= in a plain line). False (and `cmd` to be overwritten)
/// when the line is not for the short way or would raise an alarm.
#[inline(never)]
pub fn sinumerik_plain(block: &Block, st: &State, cfg: &MachineConfig, cmd: &mut Command) -> bool {
    if block.present() & !PLAIN.0 != 0 {
        return false;
    }
    *cmd = Command::EMPTY;
    cmd.line = block.line;
    cmd.seq = block.seq;
    let (mut groups, mut css) = (0u32, None::<bool>);
    for &tenths in &block.g {
        let Some((meaning, group)) = g_function(tenths / 10) else { return false };
        if groups & (1 << group) != 0 {
            return false;
        }
        groups |= 1 << group;
        match meaning {
            Meaning::Code(c) => cmd.g.assign(c),
            Meaning::Feed(rev) => {
                cmd.g.feed_mode = Some(if rev { FeedMode::PerRev } else { FeedMode::PerMin });
                css = Some(false);
            }
            Meaning::CssOn => {
                cmd.g.feed_mode = Some(FeedMode::PerRev);
                css = Some(true);
            }
            Meaning::CssOff => css = Some(false),
        }
    }
    if css.is_some_and(|on| on != st.modal.css) || css == Some(true) {
        cmd.g.css = css;
    }
    // A number without a point is whole units in SINUMERIK (no least-increment input).
    let fmt = NumberFormat {
        units: cmd.g.units.unwrap_or(st.modal.units),
        input: InputMode::Calculator,
        increments: cfg.increments,
    };
    for (i, &m) in block.m.iter().enumerate() {
        // M6, M17 (return) and the codes SINUMERIK refuses or reads otherwise: the general way.
        if matches!(m, 6 | 17 | 19 | 29 | 91 | 92 | 98 | 99) {
            return false;
        }
        let Some(f) = m_function(m, cfg) else { return false };
        if block.m[..i].iter().any(|&o| m_codes_conflict(o, m)) || cmd.m.push((m, f)).is_err() {
            return false;
        }
    }
    let incremental = cmd.g.incremental.unwrap_or(st.modal.incremental);
    for axis in [Axis::X, Axis::Y, Axis::Z] {
        let Some(n) = block.get(axis.letter()) else { continue };
        if !cfg.axis(axis).present {
            return false;
        }
        let Some(v) = length_nm(&fmt, &n) else { return false };
        // X is a diameter under DIAMON (the state's: a plain line does not switch it).
        let value = if axis == Axis::X && st.modal.diameter { v / 2 } else { v };
        cmd.axes[axis.index()] = Some(AxisWord { value, incremental });
    }
    if let Some(f) = block.get(b'F') {
        let Some(feed) = fmt.feed_nm(&f).filter(|_| !f.is_negative()) else { return false };
        cmd.feed = Some(feed);
    }
    if let Some(s) = block.get(b'S') {
        let rpm = s.scaled(0).filter(|v| !s.is_negative() && *v <= 99_999);
        let Some(rpm) = rpm else { return false };
        cmd.speed = Some(rpm as u32);
    }
    true
}

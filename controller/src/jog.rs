//! `$J=` jog lines: parsed and turned into one straight feed move in machine
//! coordinates, checked against the soft limits. The controller queues the move.

use interp_core::MachineConfig;
use interp_core::axis::{Axis, Pos};
use interp_core::canon::{Action, Canon, Endpoint, Feed, FeedMode, Move, SpindleSpeed};

/// A parsed jog line.
#[derive(Clone, Copy, Debug, Default)]
struct Jog {
    x: Option<f64>,
    z: Option<f64>,
    f: Option<f64>,
    incremental: bool,
    machine: bool,
    inch: bool,
}

fn parse_jog(text: &[u8]) -> Option<Jog> {
    let mut j = Jog::default();
    let mut i = 0;
    while i < text.len() {
        let c = text[i].to_ascii_uppercase();
        i += 1;
        if c == b' ' {
            continue;
        }
        let start = i;
        while i < text.len() && matches!(text[i], b'0'..=b'9' | b'.' | b'-' | b'+') {
            i += 1;
        }
        let v = crate::decimal::decimal(&text[start..i])?;
        match (c, v as i32) {
            (b'G', 20) => j.inch = true,
            (b'G', 21) => j.inch = false,
            (b'G', 90) => j.incremental = false,
            (b'G', 91) => j.incremental = true,
            (b'G', 53) => j.machine = true,
            (b'X', _) => j.x = Some(v),
            (b'Z', _) => j.z = Some(v),
            (b'F', _) if v > 0.0 => j.f = Some(v),
            _ => return None,
        }
    }
    Some(j)
}

/// Where a jog starts and how the interpreter's frame maps work to machine
/// coordinates.
#[derive(Clone, Copy, Debug)]
pub(crate) struct JogFrom {
    /// Machine position the move starts from (the last jog's end while jogging).
    pub base: Pos,
    /// Work to machine offset.
    pub work_to_machine: Pos,
    /// The interpreter is in G20 (inch) mode.
    pub inch_mode: bool,
    /// Soft limits are checked (`$20`).
    pub soft_limits: bool,
}

/// The move of jog line `text`, or the grbl error and its message.
pub(crate) fn jog_move(text: &[u8], from: &JogFrom, cfg: &MachineConfig) -> Result<(Canon, Pos), (u8, &'static str)> {
    let j = parse_jog(text)
        .filter(|j| j.f.is_some() && (j.x.is_some() || j.z.is_some()))
        .ok_or((16, "Jog: G20/G21/G53/G90/G91 X Z and F only, F required"))?;
    let w2m = from.work_to_machine;
    let base = from.base;
    let inch = j.inch || (from.inch_mode && !text.windows(3).any(|w| w == b"G21"));
    let scale = if inch { 25.4e6 } else { 1e6 };
    let mut to = base;
    for (axis, v) in [(Axis::X, j.x), (Axis::Z, j.z)] {
        let Some(v) = v else { continue };
        let radius = if axis == Axis::X && cfg.diameter_x { 0.5 } else { 1.0 };
        let nm = libm::round(v * scale * radius) as i64;
        to[axis] = if j.incremental {
            base[axis].saturating_add(nm)
        } else if j.machine {
            nm
        } else {
            nm.saturating_add(w2m[axis])
        };
        let a = cfg.axis(axis);
        if from.soft_limits && !(a.min..=a.max).contains(&to[axis]) {
            return Err((15, "Jog target beyond the soft limits"));
        }
    }
    let feed = libm::round(j.f.unwrap_or(0.0) * scale) as i64;
    Ok((feed_move(to, to - w2m, feed.max(1), cfg.spindle.max_rpm), to))
}

/// A straight feed move to machine position `to` at `feed` nm/min.
pub(crate) fn feed_move(to: Pos, work: Pos, feed: i64, max_rpm: u32) -> Canon {
    let spindle = SpindleSpeed { rpm: None, css: None, max_rpm };
    let m = Move {
        to: Endpoint { machine: to, work },
        feed: Feed { mode: FeedMode::PerMin, value: feed },
        spindle,
        exact_stop: true,
        independent: false,
    };
    Canon { line: 0, action: Action::Linear(m) }
}

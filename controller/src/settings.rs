//! Settings: grbl's `$n` numbers where they mean the same on a lathe, mapped onto
//! the machine description, plus the controller's own; the interpreter's
//! numbered parameters are `$P<n>`.
//!
//! Axis values of X are per millimetre of **slide travel** (radius), as the
//! drive sees them; positions on the wire are diameters on a lathe. The axis
//! settings of Y (`$101`, `$111`, `$121`, `$131`) exist on a mill only; `$311`
//! selects the machine kind, `$312` and `$313` a mill's tool changer and how long
//! its "done" may take (docs/MILL-BOARD.md).

use interp_core::MachineConfig;
use interp_core::axis::Axis;
use interp_core::config::{AxisConfig, Language, MachineKind, Param, ParamUnit, ToolChanger};

/// The controller's own settings (the rest live in the machine description).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Settings {
    /// `$20`: soft limits checked (the travel is kept in `travel` while off).
    pub soft_limits: bool,
    /// `$21`: a limit switch raises ALARM:1.
    pub hard_limits: bool,
    /// `$22`: home switches fitted; `$H` runs the homing sequence.
    pub homing: bool,
    /// `$23`: homing direction mask, bit 0 X, bit 1 Y, bit 2 Z: set = toward minus.
    pub homing_dir_mask: u8,
    /// `$24`: homing locate feed, mm/min.
    pub homing_feed: u32,
    /// `$25`: homing seek rate, mm/min.
    pub homing_seek: u32,
    /// `$27`: homing pull-off, µm.
    pub homing_pulloff_um: u32,
    /// `$300`: tape mode: 0 auto (punch if the first block is an O number), 1
    /// always store, 2 always run (drip feed).
    pub tape_mode: u8,
    /// `$301`: when a `%` line starts tape mode: 0 while no grbl traffic (`?`, a
    /// real-time byte, a `$` line) came since power-on or reset; 1 always; 2 never
    /// (the `%` is a record mark of the streamed program, answered `ok`).
    pub tape_detect: u8,
    /// `$303`: a streamed line that is only `G4 P<seconds with a decimal point>`
    /// (a grbl sender's sync dwell, e.g. CNCjs's `G4 P0.5` at the end of a job) runs
    /// as `G04 X<seconds>` instead of raising alarm 0007.
    pub grbl_dwell: bool,
    /// `$302`: strip bit 7 (even parity) from tape bytes.
    pub parity_strip: bool,
    /// `$304`: seconds without a byte on the link after which a starved streamed
    /// program (open, its text and motion run out; not lines typed by hand) raises
    /// alarm 4601; 0 never.
    pub starve_timeout_s: u32,
    /// `$305`: how long, ms of link time, a look-ahead (G70–G73 reading ns–nf, a
    /// forward GOTO, WHILE looking for its END) waits for stream lines that have not
    /// come before it is given up as an alarm.
    pub lookahead_wait_ms: u32,
    /// `$306`: seconds without a program line or operator action after which a
    /// starved streamed program with the spindle turning raises alarm 4601 even
    /// while the sender polls `?` (its stream stopped); lines typed by hand (MDI)
    /// never; 0 never.
    pub spindle_stream_timeout_s: u32,
    /// Soft-limit travel (min, max per axis X, Y, Z, nm) while `$20=0`.
    pub travel: [(i64, i64); 3],
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            soft_limits: true,
            hard_limits: true,
            homing: false,
            homing_dir_mask: 0,
            homing_feed: 50,
            homing_seek: 500,
            homing_pulloff_um: 1_000,
            tape_mode: 0,
            tape_detect: 0,
            grbl_dwell: true,
            parity_strip: false,
            starve_timeout_s: 10,
            lookahead_wait_ms: 1_000,
            spindle_stream_timeout_s: 30,
            travel: [(0, 0); 3],
        }
    }
}

/// The grbl-numbered settings, in `$$` order.
pub const NUMBERS: &[u16] = &[
    11, 12, 20, 21, 22, 23, 24, 25, 27, 30, 100, 101, 102, 110, 111, 112, 120, 121, 122, 130, 131, 132, 300, 301, 302,
    303, 304, 305, 306, 310, 311, 312, 313,
];

/// Why a setting write was refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SettingError {
    /// No such setting.
    Unknown,
    /// The value does not suit it.
    BadValue(&'static str),
}

const NM: f64 = 1e6;

/// Longest `$304`, s (a day).
const MAX_STARVE_S: u32 = 86_400;

/// `$305` range, ms.
const MIN_LOOKAHEAD_MS: u32 = 50;
const MAX_LOOKAHEAD_MS: u32 = 60_000;

/// Soft-limit travel with limits "off": ±1000 m.
const UNLIMITED: i64 = 1_000_000_000_000;

/// The axis of a per-axis setting `$1n0`/`$1n1`/`$1n2` (grbl's X, Y, Z).
fn setting_axis(n: u16) -> Axis {
    match n % 10 {
        0 => Axis::X,
        1 => Axis::Y,
        _ => Axis::Z,
    }
}

/// Whether setting `n` belongs to an axis the machine does not have (Y on a
/// lathe), or is a mill's tool changer's (`$312`, `$313`) on a lathe (a build
/// without the mill profile has neither: unknown settings).
pub(crate) fn missing_axis(n: u16, cfg: &MachineConfig) -> bool {
    let mill_only = interp_core::MILL && matches!(n, 312 | 313) && cfg.kind != MachineKind::Mill;
    mill_only || ((100..=132).contains(&n) && !cfg.axis(setting_axis(n)).present)
}

/// The Y axis `$311=1` gives a machine that had none: the built-in machining
/// centre's (`MachineConfig::mill`: travel −400–0 mm, rapid 8 m/min).
const MILL_Y: AxisConfig = AxisConfig::linear(-400, 0, 8_000);

/// `$311`: the machine kind as its number (0 lathe, 1 mill).
fn kind_number(k: MachineKind) -> f64 {
    match k {
        MachineKind::Lathe => 0.0,
        MachineKind::Mill => 1.0,
    }
}

/// `$311`: switches the profile. A mill programs X in radius and has a Y axis (the
/// built-in machining centre's travel and rates until `$101`–`$131` set its own);
/// a lathe programs X as a diameter and has none. The other axes keep their
/// settings. Idempotent: the boot applies the stored value again.
fn set_kind(kind: MachineKind, cfg: &mut MachineConfig, s: &mut Settings) {
    if cfg.kind == kind {
        return;
    }
    cfg.kind = kind;
    let y = &mut cfg.axes[Axis::Y.index()];
    match kind {
        MachineKind::Mill => {
            cfg.diameter_x = false;
            if !y.present {
                *y = MILL_Y;
            }
        }
        MachineKind::Lathe => {
            cfg.diameter_x = true;
            *y = AxisConfig::ABSENT;
        }
    }
    if !s.soft_limits {
        let y = &mut cfg.axes[Axis::Y.index()];
        s.travel[1] = (y.min, y.max);
        if y.present {
            (y.min, y.max) = (-UNLIMITED, UNLIMITED);
        }
    }
}

/// The value of setting `n` (file units: mm, mm/min, mm/s², counts); `None` for a
/// setting the machine does not have (Y's on a lathe).
pub fn get(n: u16, cfg: &MachineConfig, s: &Settings) -> Option<f64> {
    if missing_axis(n, cfg) {
        return None;
    }
    if interp_core::MILL && matches!(n, 312 | 313) {
        return Some(tool_changer_setting(n, cfg));
    }
    let a = cfg.axis(setting_axis(n));
    Some(match n {
        11 => cfg.motion.junction_deviation as f64 / NM,
        12 => cfg.motion.chord_tolerance as f64 / NM,
        20 => f64::from(u8::from(s.soft_limits)),
        21 => f64::from(u8::from(s.hard_limits)),
        22 => f64::from(u8::from(s.homing)),
        23 => f64::from(s.homing_dir_mask),
        24 => f64::from(s.homing_feed),
        25 => f64::from(s.homing_seek),
        27 => f64::from(s.homing_pulloff_um) / 1e3,
        30 => f64::from(cfg.spindle.max_rpm),
        100..=102 => a.drive.steps as f64 * NM / a.drive.per_nm.max(1) as f64,
        110..=112 => a.rapid_per_min as f64 / NM,
        120..=122 => a.accel_per_s2 as f64 / NM,
        130..=132 => {
            let (lo, hi) = if s.soft_limits { (a.min, a.max) } else { s.travel[usize::from(n % 10)] };
            (hi - lo) as f64 / NM
        }
        300 => f64::from(s.tape_mode),
        301 => f64::from(s.tape_detect),
        303 => f64::from(u8::from(s.grbl_dwell)),
        302 => f64::from(u8::from(s.parity_strip)),
        304 => f64::from(s.starve_timeout_s),
        305 => f64::from(s.lookahead_wait_ms),
        306 => f64::from(s.spindle_stream_timeout_s),
        310 => match cfg.language {
            Language::Fanuc => 0.0,
            Language::Siemens => 1.0,
        },
        311 => kind_number(cfg.kind),
        _ => return None,
    })
}

/// Writes setting `n` into `cfg`/`s` (on copies: the caller commits them once the
/// motion core accepted the machine description).
pub fn set(n: u16, v: f64, cfg: &mut MachineConfig, s: &mut Settings) -> Result<(), SettingError> {
    let bad = SettingError::BadValue;
    if !v.is_finite() || !(0.0..=1e9).contains(&v) {
        return Err(bad("must be a number from 0 to 1e9"));
    }
    let flag = |v: f64| if v == 0.0 || v == 1.0 { Ok(v == 1.0) } else { Err(bad("must be 0 or 1")) };
    let whole = |v: f64| if libm::trunc(v) == v { Ok(v as u32) } else { Err(bad("must be a whole number")) };
    let positive = |v: f64| if v > 0.0 { Ok(libm::round(v * NM) as i64) } else { Err(bad("must be above 0")) };
    if missing_axis(n, cfg) {
        return Err(if interp_core::MILL && n > 132 {
            bad("a mill's tool changer setting ($311=1 makes a mill)")
        } else {
            bad("no Y axis on a lathe ($311=1 makes a mill)")
        });
    }
    if interp_core::MILL && matches!(n, 312 | 313) {
        return set_tool_changer(n, v, cfg);
    }
    let ax = setting_axis(n);
    match n {
        11 => cfg.motion.junction_deviation = positive(v)?,
        12 => cfg.motion.chord_tolerance = positive(v)?,
        20 => set_soft_limits(flag(v)?, cfg, s),
        21 => s.hard_limits = flag(v)?,
        22 => s.homing = flag(v)?,
        23 => s.homing_dir_mask = u8::try_from(whole(v)?).map_err(|_| bad("is a bit mask 0-255"))?,
        24 => s.homing_feed = whole(v)?.max(1),
        25 => s.homing_seek = whole(v)?.max(1),
        27 => s.homing_pulloff_um = libm::round(v * 1e3) as u32,
        30 => cfg.spindle.max_rpm = whole(v)?.max(1),
        100..=102 => {
            let d = &mut cfg.axes[ax.index()].drive;
            // Exact ratio: steps per metre over a metre.
            d.steps = libm::round(v * 1000.0) as i64;
            d.per_nm = 1_000_000_000;
            if d.steps <= 0 {
                return Err(bad("must be above 0"));
            }
        }
        110..=112 => cfg.axes[ax.index()].rapid_per_min = positive(v)?,
        120..=122 => cfg.axes[ax.index()].accel_per_s2 = positive(v)?,
        130..=132 => {
            let travel = positive(v)?;
            let t = &mut s.travel[usize::from(n % 10)];
            let a = &mut cfg.axes[ax.index()];
            if s.soft_limits {
                a.min = a.max - travel;
            } else {
                t.0 = t.1 - travel;
            }
        }
        300 => s.tape_mode = u8::try_from(whole(v)?).ok().filter(|m| *m <= 2).ok_or(bad("is 0, 1 or 2"))?,
        301 => s.tape_detect = u8::try_from(whole(v)?).ok().filter(|m| *m <= 2).ok_or(bad("is 0, 1 or 2"))?,
        303 => s.grbl_dwell = flag(v)?,
        302 => s.parity_strip = flag(v)?,
        304 => s.starve_timeout_s = whole(v)?.min(MAX_STARVE_S),
        305 => {
            let ms = whole(v)?;
            if !(MIN_LOOKAHEAD_MS..=MAX_LOOKAHEAD_MS).contains(&ms) {
                return Err(bad("is 50 to 60000 ms"));
            }
            s.lookahead_wait_ms = ms;
        }
        306 => s.spindle_stream_timeout_s = whole(v)?.min(MAX_STARVE_S),
        310 => {
            cfg.language = match whole(v)? {
                0 => Language::Fanuc,
                1 => Language::Siemens,
                _ => return Err(bad("is 0 (FANUC) or 1 (SINUMERIK)")),
            }
        }
        311 => match whole(v)? {
            0 => set_kind(MachineKind::Lathe, cfg, s),
            1 if !interp_core::MILL => {
                return Err(bad("is 0: this firmware has no mill profile (built without feature mill)"));
            }
            1 => set_kind(MachineKind::Mill, cfg, s),
            _ => return Err(bad("is 0 (lathe) or 1 (mill)")),
        },
        _ => return Err(SettingError::Unknown),
    }
    Ok(())
}

/// `$312` (0 manual, 1 automatic) and `$313` (s) of a mill: its tool changer.
/// Apart from [`get`], so that a build without the mill profile has none of it.
fn tool_changer_setting(n: u16, cfg: &MachineConfig) -> f64 {
    if n == 312 {
        f64::from(u8::from(cfg.tool_changer == ToolChanger::Automatic))
    } else {
        f64::from(cfg.tool_change_timeout.seconds())
    }
}

/// Writes `$312` or `$313` (see [`tool_changer_setting`]).
fn set_tool_changer(n: u16, v: f64, cfg: &mut MachineConfig) -> Result<(), SettingError> {
    if n == 312 {
        cfg.tool_changer = match v {
            0.0 => ToolChanger::Manual,
            1.0 => ToolChanger::Automatic,
            _ => return Err(SettingError::BadValue("is 0 (manual) or 1 (automatic)")),
        };
    } else if libm::trunc(v) != v || !cfg.tool_change_timeout.set(v.min(65_535.0) as u16) {
        return Err(SettingError::BadValue("is 1 to 3600 s"));
    }
    Ok(())
}

/// `$20`: switching soft limits off keeps the travel aside and opens the limits.
fn set_soft_limits(on: bool, cfg: &mut MachineConfig, s: &mut Settings) {
    if on == s.soft_limits {
        return;
    }
    for (i, a) in [Axis::X, Axis::Y, Axis::Z].into_iter().enumerate() {
        let ax = &mut cfg.axes[a.index()];
        if !ax.present {
            continue;
        }
        if on {
            (ax.min, ax.max) = s.travel[i];
        } else {
            s.travel[i] = (ax.min, ax.max);
            (ax.min, ax.max) = (-UNLIMITED, UNLIMITED);
        }
    }
    s.soft_limits = on;
}

/// A numbered parameter's value in file units.
pub fn param_value(p: Param, cfg: &MachineConfig) -> f64 {
    let v = cfg.params.get(p) as f64;
    match p.def().unit {
        ParamUnit::Mm | ParamUnit::MmPerMin => v / NM,
        _ => v,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settings_map_onto_the_machine_and_read_back() {
        let mut cfg = MachineConfig::default();
        let mut s = Settings::default();
        assert_eq!(get(100, &cfg, &s), Some(400.0));
        assert_eq!(get(102, &cfg, &s), Some(320.0));
        assert_eq!(get(130, &cfg, &s), Some(165.0));
        set(102, 640.5, &mut cfg, &mut s).unwrap();
        assert_eq!(get(102, &cfg, &s), Some(640.5));
        set(20, 0.0, &mut cfg, &mut s).unwrap();
        assert_eq!(get(132, &cfg, &s), Some(900.0));
        assert!(cfg.axis(Axis::Z).max > 1_000_000_000);
        set(20, 1.0, &mut cfg, &mut s).unwrap();
        assert_eq!((cfg.axis(Axis::Z).min, cfg.axis(Axis::Z).max), (-600_000_000, 300_000_000));
        assert_eq!(set(22, 2.0, &mut cfg, &mut s), Err(SettingError::BadValue("must be 0 or 1")));
        assert_eq!(set(7, 1.0, &mut cfg, &mut s), Err(SettingError::Unknown));
    }
}

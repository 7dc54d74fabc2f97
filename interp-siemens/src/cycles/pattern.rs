//! SINUMERIK drilling patterns (seed 001 chapter 2.3, lines 3084-3397): HOLES1
//! (row), HOLES2 (circle) and CYCLE801 (grid). Their parameters are read and
//! checked here; the positions come from `interp_core::cycles::holes`, and the
//! driver positions to each with G0 in the plane and calls the modal drilling
//! cycle (MCALL CYCLE81–89/840, or a subprogram) there.
//!
//! - **Plane**: the pattern lies in the active plane (abscissa, ordinate: G17 X/Y,
//!   G18 Z/X, G19 Y/Z, lines 3268, 3178-3212); the plane's two axes and its
//!   drilling axis (the third) must exist, else 61005 "3rd geometry axis not
//!   present" (the document's alarm for a lathe's G18 without Y, line 2721): a
//!   lathe without Y has no plane to lay a pattern in.
//! - **Counts**: HOLES1/HOLES2 NUM ≤ 0 (or left out): 61103 "孔数为零" (line 3107).
//!   CYCLE801 _NUM1 or _NUM2 ≤ 0: message 62105 "列数或者行数为零" (table 12279,
//!   where "循环800" is a misprint for CYCLE801): the cycle does nothing.
//! - **Circle**: (NUM − 1)·|INDA| ≥ 360° puts holes on top of each other: 61106
//!   "圆弧单元个数或者间距" (table 12221, HOLES2).
//! - **Signs and ranges**: FDIS, DBH, RAD, _DIS1, _DIS2 are "without sign"
//!   (lengths ≥ 0) and STA1 lies in −180 < STA1 ≤ 180 (lines 3121-3126, 3254-3259):
//!   the document says the pattern cycles check no other values (line 3109), an
//!   840D would lay a negative spacing out backwards; this board refuses such a
//!   value with 12160 "value out of range" (no motion) rather than drill a
//!   mirrored pattern.
//! - **Without a modal drilling cycle** (lines 3095-3101): message 62100 "没有钻削
//!   循环有效"; the program stops; NC start (cycle start) continues and the pattern
//!   is only positioned, nothing drilled.

use super::Params;
use interp_core::MachineConfig;
use interp_core::alarm::{AlarmKind, CycleAlarm, SiemensAlarm};
use interp_core::cycles::holes::HolePattern;
use interp_core::lang::siemens::call::Arg;
use interp_core::modal::State;

/// A message of the drilling patterns (62xxx: shown, acknowledged, the program
/// goes on at NC start), with the document's number and text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Notice {
    /// 62100 "没有钻削循环有效": no drilling cycle active (lines 3099, 12277).
    NoDrillingCycle,
    /// 62105 "列数或者行数为零": number of columns or rows is zero (line 12279).
    NoColumnsOrRows,
}

impl Notice {
    /// The message number.
    pub fn code(self) -> u16 {
        match self {
            Notice::NoDrillingCycle => 62100,
            Notice::NoColumnsOrRows => 62105,
        }
    }

    /// The message text (the document's, in English).
    pub fn text(self) -> &'static str {
        interp_core::alarm::cycle_message(self.code()).unwrap_or("")
    }
}

/// Whether `name` is a drilling pattern cycle.
pub fn is_pattern(name: &str) -> bool {
    matches!(name, "HOLES1" | "HOLES2" | "CYCLE801")
}

/// The pattern `name` called on `line` with `args`: its positions in order, or
/// `Ok(None)` with 62105 for a grid of no points. Nothing moves on an error.
pub fn hole_pattern(
    name: &str,
    args: &[Arg<'_>],
    st: &State,
    cfg: &MachineConfig,
    line: u32,
) -> Result<Result<HolePattern, Notice>, AlarmKind> {
    let p = Params::new(args, st);
    let [a, o, third] = super::drill::plane_axes(st.modal.plane);
    if [a, o, third].iter().any(|x| !cfg.axes[x.index()].present) {
        return Err(CycleAlarm::NoThirdAxis.into());
    }
    let work = st.work_pos(cfg);
    let here = (work[a], work[o]);
    let range = AlarmKind::Siemens(SiemensAlarm::ValueRange);
    let angle = |i: usize| {
        let v = p.real(i);
        if v > -180.0 && v <= 180.0 { Ok(v) } else { Err(range) }
    };
    let length = |i: usize| {
        let v = p.nm(p.real(i));
        if v >= 0 { Ok(v) } else { Err(range) }
    };
    let pattern = match name {
        "HOLES1" => {
            let num = count(p.int(5))?;
            let at = (p.nm(p.real(0)), p.nm(p.real(1)));
            Ok(HolePattern::row(at, angle(2)?, length(3)?, length(4)?, num, here, line))
        }
        "HOLES2" => {
            let num = count(p.int(5))?;
            let inda = p.real(4);
            if !inda.is_finite() || (f64::from(num) - 1.0) * libm::fabs(inda) >= 360.0 {
                return Err(CycleAlarm::CircleElements.into());
            }
            let centre = (p.nm(p.real(0)), p.nm(p.real(1)));
            Ok(HolePattern::circle(centre, length(2)?, angle(3)?, inda, num, line))
        }
        _ => {
            let (n1, n2) = (p.int(5), p.int(6));
            let (at, sta, d1, d2) = ((p.nm(p.real(0)), p.nm(p.real(1))), angle(2)?, length(3)?, length(4)?);
            if n1 <= 0 || n2 <= 0 {
                Err(Notice::NoColumnsOrRows)
            } else if n1.saturating_mul(n2) > i64::from(MAX_HOLES) {
                return Err(range);
            } else {
                Ok(HolePattern::grid(at, sta, d1, d2, n1 as u32, n2 as u32, here, line))
            }
        }
    };
    p.ok()?;
    Ok(pattern)
}

/// Most holes one pattern call positions to.
const MAX_HOLES: u32 = 100_000;

/// NUM of HOLES1/HOLES2: 61103 when zero, negative or left out (line 3107).
fn count(num: i64) -> Result<u32, AlarmKind> {
    if num <= 0 {
        Err(CycleAlarm::HoleCountZero.into())
    } else if num > i64::from(MAX_HOLES) {
        Err(AlarmKind::Siemens(SiemensAlarm::ValueRange))
    } else {
        Ok(num as u32)
    }
}

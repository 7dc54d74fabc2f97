//! The setting cycles of the milling chapter, which move nothing: CYCLE800
//! (swivel, lines 7391-7790, alarms 9188-9260).
//!
//! **CYCLE800** `(_FR, _TC, _ST, _MODE, _X0, _Y0, _Z0, _A, _B, _C, _X1, _Y1, _Z1,
//! _DIR, _FR_I)`. This board has no swivel kinematics: no swivel data record
//! (TOOLCARRIER) is set up ($MN_MM_NUM_TOOL_CARRIER = 0). Every call that would
//! swivel — whatever its mode, angles or `_DIR` (0 "compute only" needs the
//! record's kinematics too) — raises 61180 "no name assigned to the swivel data
//! record", the alarm table 5.3 (line 12241) gives for exactly this case ("或者没有
//! 约定回转文件程序段 ($MN_MM_NUM_TOOL_CARRIER=0)"); 61182 "swivel data record
//! name unknown" is for a machine that has records but not the named one. It
//! moves nothing (not even the `_FR` retract, which runs inside the swivel).
//! `CYCLE800()` and `_TC = "0"` deselect the swivel data record (lines 7517,
//! 7633): there is none, so they are accepted and do nothing.

use super::super::Params;
use interp_core::alarm::CycleAlarm;

/// CYCLE800: accepted when it deselects (no argument, or `_TC` = "0"), else
/// 61180 (no swivel data records on this board).
pub(in crate::cycles) fn cycle800(p: &Params<'_, '_>) -> Result<(), CycleAlarm> {
    let deselect = p.text(1) == b"0" || p.args.iter().all(|a| matches!(a, super::super::Arg::Empty));
    if deselect { Ok(()) } else { Err(CycleAlarm::SwivelDataNoName) }
}

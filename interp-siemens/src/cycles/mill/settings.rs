//! The setting cycles of the milling chapter, which move nothing: CYCLE800
//! (swivel, lines 7391-7790, alarms 9188-9260) and CYCLE832 (high-speed
//! settings, lines 9261-9797).
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

use super::super::{Arg, Engine, Params};
use interp_core::alarm::{AlarmKind, CycleAlarm};
use interp_core::canon::Action;
use interp_core::modal::State;

/// CYCLE800: accepted when it deselects (no argument, or `_TC` = "0"), else
/// 61180 (no swivel data records on this board).
pub(in crate::cycles) fn cycle800(p: &Params<'_, '_>) -> Result<(), CycleAlarm> {
    let deselect = p.text(1) == b"0" || p.args.iter().all(|a| matches!(a, Arg::Empty));
    if deselect { Ok(()) } else { Err(CycleAlarm::SwivelDataNoName) }
}

/// CYCLE832 `_TOLM`, one decimal digit each from the units up, and the largest
/// value each takes: machining (0 deselect, 1 finishing, 2 semi-finishing, 3
/// roughing), 5-axis transformation (0 none, 1 TRAORI, 2 TRAORI(2)), compressor
/// (0 COMPOF, 1 COMPCAD, 2 COMPCURV, 3 B spline), path control (0 G64, 1 G642,
/// 2 G641), feedforward and jerk (0 FFWOF SOFT, 1 FFWON SOFT, 2 FFWOF BRISK),
/// technology adaptation (0 no, 1 yes).
const TOLM_MAX: [u8; 6] = [3, 2, 3, 2, 2, 1];

/// The tolerance each machining type starts with (lines 9434-9439), nm: deselect,
/// finishing, semi-finishing, roughing.
const PRESET_NM: [u32; 4] = [10_000, 10_000, 50_000, 100_000];

/// The widest tolerance band accepted, nm (10 mm).
const TOL_MAX_NM: i64 = 10_000_000;

/// CYCLE832 `(_TOL, _TOLM)`: the path tolerance `_TOL` the motion core plans
/// the following blocks with (G64 junctions, arc chords: [`Action::Tolerance`])
/// and the blending mode of `_TOLM`'s machining type — deselect (0, and
/// `CYCLE832()`) exact stop G60 and the machine's own tolerance, finishing,
/// semi-finishing and roughing continuous path with `_TOL` (0: the type's
/// preset). `CYCLE832(_TOL)` sets the tolerance alone (line 9395). Alarms:
/// 61019 a negative or too wide `_TOL`, a `_TOLM` digit outside its values;
/// 61191/61192 TRAORI, 61194 B spline (this board has neither). The
/// compressor, feedforward, jerk and adaptation digits have no effect here.
pub(in crate::cycles) fn cycle832(p: &Params<'_, '_>, st: &mut State, ctx: &mut dyn Engine) -> Result<(), AlarmKind> {
    let wrong = AlarmKind::from(CycleAlarm::ParameterWrong);
    let tol = p.len(0);
    p.ok()?;
    if !(0..=TOL_MAX_NM).contains(&tol) {
        return Err(wrong);
    }
    let mut nm = tol as u32;
    let tol_only = matches!(p.arg(1), Arg::Empty) && !matches!(p.arg(0), Arg::Empty);
    if !tol_only {
        let mut rest = u32::try_from(p.int(1)).map_err(|_| wrong)?;
        let mut d = [0u8; 6];
        for (digit, max) in d.iter_mut().zip(TOLM_MAX) {
            *digit = (rest % 10) as u8;
            rest /= 10;
            if *digit > max {
                return Err(wrong);
            }
        }
        if rest != 0 {
            return Err(wrong);
        }
        match (d[1], d[2]) {
            (1, _) => return Err(CycleAlarm::FiveAxisNotSetUp.into()),
            (2, _) => return Err(CycleAlarm::SecondFiveAxisNotSetUp.into()),
            (_, 3) => return Err(CycleAlarm::SplineNotSetUp.into()),
            _ => {}
        }
        let deselect = d[0] == 0;
        st.modal.exact_stop_mode = deselect;
        if deselect {
            nm = 0;
        } else if nm == 0 {
            nm = PRESET_NM[usize::from(d[0])];
        }
    }
    ctx.emit(Action::Tolerance { nm })
}

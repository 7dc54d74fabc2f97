//! Macro and subprogram calls of custom macro B as FANUC 0i has them (the manual
//! names G65, G66 and G67 as macro statements, 2.24.2 note 7, and describes no
//! more): the simple call G65, the modal call G66 with its cancel G67, macros
//! called by G codes (parameters 6050–6059 → O9010–O9019) and M codes (6080–6089
//! → O9020–O9029), subprograms called by M codes (6071–6079 → O9001–O9009) and
//! by T codes (6001#5 → O9000, the T value in #149).
//!
//! The reader recognises a call by the codes of a [`CallCodes`] table; what a call
//! block holds comes out as a [`CallBlock`] with its arguments in a
//! [`Locals`]; the interpreter keeps the modal calls in force in [`ModalCalls`].

use crate::config::{CALL_G, CALL_M, Param, Parameters, SUB_M};
use crate::lang::fanuc::macros::Locals;

/// How a program level was called: what the codes in it may still call (FANUC 0i:
/// a program called by a code treats some codes in it as ordinary codes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Caller {
    /// M98, G65, G66: every code calls as in the main program.
    Program,
    /// A G code of parameters 6050–6059.
    GCode,
    /// An M code of parameters 6080–6089.
    MCodeMacro,
    /// An M code of parameters 6071–6079, or a T code (6001#5).
    Subprogram,
}

/// Kinds of code call, as bits of a mask of those switched off.
pub mod off {
    /// G codes of 6050–6059.
    pub const G_MACRO: u8 = 1;
    /// M codes of 6080–6089.
    pub const M_MACRO: u8 = 2;
    /// M codes of 6071–6079.
    pub const M_SUB: u8 = 4;
    /// T codes (6001#5).
    pub const T_SUB: u8 = 8;
}

impl Caller {
    /// The code calls a program called this way does not make: they are ordinary
    /// codes in it (FANUC 0i). In a macro called by a G code: G-code macro calls
    /// and M/T-code subprogram calls; in one called by an M code: M-code macro
    /// calls; in a subprogram called by an M or T code: all of them. The mask is
    /// inherited by everything such a program calls.
    pub const fn switches_off(self) -> u8 {
        match self {
            Caller::Program => 0,
            Caller::GCode => off::G_MACRO | off::M_SUB | off::T_SUB,
            Caller::MCodeMacro => off::M_MACRO,
            Caller::Subprogram => off::G_MACRO | off::M_MACRO | off::M_SUB | off::T_SUB,
        }
    }
}

/// What an M code that calls does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MCall {
    /// Calls macro `program` with the block's other words as arguments (6080–6089).
    Macro(u32),
    /// Calls subprogram `program` after the block's other codes, as M98 would (6071–6079).
    Subprogram(u32),
}

/// The codes that call programs, from the parameters, with the kinds the program
/// level in force switches off left out. The reader looks at every G word through
/// [`CallCodes::g_may_call`] (one subtraction and one compare), and at M and T
/// words only when some M or T code calls.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CallCodes {
    /// G codes in tenths (as the reader keeps them) calling O9010 + i; 0 = none.
    g: [u16; 10],
    /// The lowest G code (tenths) that calls, G65 included.
    g_lo: u16,
    /// From `g_lo` to the highest G code that calls, G67 included.
    g_span: u16,
    /// M codes calling macro O9020 + i; 0 = none.
    m_macro: [u16; 10],
    /// M codes calling subprogram O9001 + i; 0 = none.
    m_sub: [u16; 9],
    /// Some M code calls.
    any_m: bool,
    /// T codes call O9000.
    t: bool,
}

/// G65, G66, G67 in tenths.
const G65: u16 = 650;
const G66: u16 = 660;
const G67: u16 = 670;

/// `out[i]` = the code parameter `params[i]` names, times `scale` (0 where the
/// parameter is 0, over `max`, or past the reader's G codes in tenths, G6553.5). Out of line and over slices: one short loop
/// instead of 29 unrolled lookups (it runs only when parameters change).
#[inline(never)]
fn fill(params: &Parameters, list: &[Param], max: u16, scale: u16, out: &mut [u16]) {
    for (slot, &p) in out.iter_mut().zip(list) {
        *slot = u16::try_from(params.get(p)).ok().filter(|&v| v <= max).and_then(|v| v.checked_mul(scale)).unwrap_or(0);
    }
}

impl CallCodes {
    /// No code calls but G65, G66 and G67 (the machine's defaults; MDI; a shape's blocks).
    pub const BUILT_IN: CallCodes =
        CallCodes { g: [0; 10], g_lo: G65, g_span: G67 - G65, m_macro: [0; 10], m_sub: [0; 9], any_m: false, t: false };

    /// The codes parameters 6001#5 and 6050–6089 make calls, but those `off`
    /// (bits of [`off`]) switches off. Of two parameters naming one code, the lower
    /// number wins; an M code in both 6080–6089 and 6071–6079 calls the macro.
    #[inline(never)]
    pub fn of(params: &Parameters, off: u8) -> CallCodes {
        let mut c = CallCodes::BUILT_IN;
        if off & off::G_MACRO == 0 {
            fill(params, &CALL_G, 9_999, 10, &mut c.g);
        }
        if off & off::M_MACRO == 0 {
            fill(params, &CALL_M, 999, 1, &mut c.m_macro);
        }
        if off & off::M_SUB == 0 {
            fill(params, &SUB_M, 999, 1, &mut c.m_sub);
        }
        c.t = off & off::T_SUB == 0 && params.flag(Param::TCodeCall);
        c.any_m = c.m_macro.iter().chain(&c.m_sub).any(|&m| m != 0);
        let (lo, hi) = c.g.iter().filter(|&&g| g != 0).fold((G65, G67), |(lo, hi), &g| (lo.min(g), hi.max(g)));
        (c.g_lo, c.g_span) = (lo, hi - lo);
        c
    }

    /// Whether the G code `tenths` may call (cheap; [`CallCodes::g_call`] tells).
    #[inline(always)]
    pub fn g_may_call(&self, tenths: u16) -> bool {
        tenths.wrapping_sub(self.g_lo) <= self.g_span
    }

    /// What the G code `tenths` calls, if anything.
    pub fn g_call(&self, tenths: u16) -> Option<CallCode> {
        match tenths {
            G65 => Some(CallCode::G65),
            G66 => Some(CallCode::G66),
            G67 => Some(CallCode::G67),
            0 => None,
            _ => self.g.iter().position(|&g| g == tenths).map(|i| CallCode::G { program: 9_010 + i as u32 }),
        }
    }

    /// Whether some M code calls.
    #[inline(always)]
    pub fn m_may_call(&self) -> bool {
        self.any_m
    }

    /// What the M code `m` calls, if anything.
    pub fn m_call(&self, m: u16) -> Option<MCall> {
        if m == 0 {
            return None;
        }
        if let Some(i) = self.m_macro.iter().position(|&c| c == m) {
            return Some(MCall::Macro(9_020 + i as u32));
        }
        self.m_sub.iter().position(|&c| c == m).map(|i| MCall::Subprogram(9_001 + i as u32))
    }

    /// Whether a T code calls O9000.
    #[inline(always)]
    pub fn t_calls(&self) -> bool {
        self.t
    }
}

/// The code a call block begins with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CallCode {
    /// Simple call.
    G65,
    /// Modal call.
    G66,
    /// Modal call cancel.
    G67,
    /// A G code of 6050–6059, calling `program`.
    G {
        /// O9010–O9019.
        program: u32,
    },
    /// An M code of 6080–6089, calling `program`.
    M {
        /// O9020–O9029.
        program: u32,
    },
}

/// What a macro call block asks for, read and checked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum MacroCall {
    /// G65 P… L…, or a G or M code that calls: run `program` `repeats` times at a
    /// new macro level whose `#1–#33` are the arguments.
    Simple {
        /// O number, 1–9999.
        program: u32,
        /// Repetitions, 1–9999 (L).
        repeats: u16,
        /// How it was called (what codes it switches off).
        by: Caller,
    },
    /// G66 P… L…: call `program` (`repeats` times) with the arguments after every
    /// block that moves an axis, until G67.
    Modal {
        /// O number, 1–9999.
        program: u32,
        /// Repetitions per call, 1–9999 (L).
        repeats: u16,
    },
    /// G67: the last G66 in force ends.
    Cancel,
}

/// A macro call block (2.24.2 note 7: a macro statement), with what may stand
/// before it; its arguments are read into a [`Locals`] beside it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CallBlock {
    /// 1-based source line.
    pub line: u32,
    /// Optional block skip level.
    pub skip_level: Option<u8>,
    /// Sequence number `N`.
    pub seq: Option<u32>,
    /// The call.
    pub call: MacroCall,
}

/// A macro call block as the reader leaves it: the block and its arguments.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CallRead {
    /// What the block asks for.
    pub block: CallBlock,
    /// `#1–#33` as the arguments set them (vacant where not given).
    pub args: Locals,
}

impl CallRead {
    /// Nothing read yet.
    pub const EMPTY: CallRead = CallRead {
        block: CallBlock { line: 0, skip_level: None, seq: None, call: MacroCall::Cancel },
        args: Locals::VACANT,
    };
}

/// What the reader of a program's blocks needs for macro calls: the codes that
/// call, and where a call block goes. (One place, so the per-block path passes one
/// pointer.)
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Calls {
    /// The codes that call programs at the level in force.
    pub codes: CallCodes,
    /// The macro call block just read, with its arguments.
    pub read: CallRead,
}

/// A subprogram call by an M code (6071–6079) or a T code (6001#5): an NC block's
/// program-flow word, like M98 (the block's other codes run first).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SubCall {
    /// O9001–O9009, or O9000.
    pub program: u32,
    /// The M code (for messages), or 0 for a T code.
    pub m: u16,
    /// A T code's value, for #149.
    pub t: Option<u32>,
}

/// The variable a T code that calls O9000 leaves its value in (FANUC 0i).
pub const T_CODE_VARIABLE: u16 = 149;

/// Most G66 modal calls in force at once: FANUC 0i raises alarm 0122 at a fourth.
pub const MAX_MODAL_CALLS: usize = 3;

/// A G66 in force.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Modal {
    program: u32,
    repeats: u16,
    /// Its arguments: every call starts its level with them.
    args: Locals,
    /// Its program is running (called by a move): the moves there do not call it.
    busy: bool,
}

/// The G66 modal calls in force, oldest first. After a block that moves an axis
/// the newest one not running is called (so moves in a modally called program do
/// not call it again, but call an older G66 if one is in force, as FANUC's nested
/// modal calls do); G67 ends the newest.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ModalCalls {
    calls: heapless::Vec<Modal, MAX_MODAL_CALLS>,
    /// The one a move calls now, if any (kept up to date: the per-block test is
    /// one compare).
    next: Option<u8>,
}

impl ModalCalls {
    /// G66: `program` with `args` from now on; alarm 0122 at a fourth.
    pub fn start(&mut self, program: u32, repeats: u16, args: &Locals) -> Result<(), crate::alarm::AlarmKind> {
        self.calls
            .push(Modal { program, repeats, args: *args, busy: false })
            .map_err(|_| crate::alarm::AlarmKind::ModalCallsTooDeep)?;
        self.update();
        Ok(())
    }

    /// Whether G66 may start another modal call.
    pub fn is_full(&self) -> bool {
        self.calls.is_full()
    }

    /// G67: the newest modal call ends (nothing happens with none in force).
    pub fn cancel(&mut self) {
        self.calls.pop();
        self.update();
    }

    /// Every modal call ends (reset, a new run).
    pub fn clear(&mut self) {
        self.calls.clear();
        self.next = None;
    }

    /// The modal call a move calls now: its index, program, repetitions and arguments.
    #[inline]
    pub fn due(&self) -> Option<(u8, u32, u16, &Locals)> {
        let i = self.next?;
        let m = self.calls.get(usize::from(i))?;
        Some((i, m.program, m.repeats, &m.args))
    }

    /// Whether a move calls a macro now.
    #[inline(always)]
    pub fn any_due(&self) -> bool {
        self.next.is_some()
    }

    /// Modal call `i` starts (`true`) or ends running its program.
    pub fn set_busy(&mut self, i: u8, busy: bool) {
        if let Some(m) = self.calls.get_mut(usize::from(i)) {
            m.busy = busy;
        }
        self.update();
    }

    /// How many are in force.
    pub fn len(&self) -> usize {
        self.calls.len()
    }

    /// Whether none is in force.
    pub fn is_empty(&self) -> bool {
        self.calls.is_empty()
    }

    /// The arguments of modal call `i`.
    pub fn args(&self, i: u8) -> Option<&Locals> {
        self.calls.get(usize::from(i)).map(|m| &m.args)
    }

    fn update(&mut self) {
        self.next = self.calls.iter().rposition(|m| !m.busy).map(|i| i as u8);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn code_tables_follow_the_parameters_and_what_is_switched_off() {
        let mut p = Parameters::default();
        let c = CallCodes::of(&p, 0);
        assert_eq!(c, CallCodes::BUILT_IN);
        assert!(c.g_may_call(650) && c.g_may_call(670) && !c.g_may_call(10) && !c.g_may_call(1000));
        assert_eq!(c.g_call(660), Some(CallCode::G66));
        assert_eq!((c.m_call(6), c.t_calls(), c.m_may_call()), (None, false, false));
        p.set(Param::CallG9010, 100);
        p.set(Param::CallG9013, 81);
        p.set(Param::CallG9014, 81);
        p.set(Param::CallM9021, 50);
        p.set(Param::SubM9001, 6);
        p.set(Param::SubM9002, 50);
        p.set(Param::TCodeCall, 1);
        let c = CallCodes::of(&p, 0);
        assert!(c.g_may_call(810) && c.g_may_call(1000) && !c.g_may_call(640) && !c.g_may_call(1010));
        assert_eq!(c.g_call(1000), Some(CallCode::G { program: 9010 }));
        assert_eq!(c.g_call(810), Some(CallCode::G { program: 9013 }), "the lower parameter wins");
        assert_eq!(c.g_call(820), None);
        assert_eq!(c.m_call(50), Some(MCall::Macro(9021)), "the macro call wins");
        assert_eq!(c.m_call(6), Some(MCall::Subprogram(9001)));
        assert!(c.t_calls() && c.m_may_call());
        // Inside a macro called by a G code: G calls and M/T subprogram calls are off.
        let c = CallCodes::of(&p, Caller::GCode.switches_off());
        assert_eq!(
            (c.g_call(1000), c.m_call(50), c.m_call(6), c.t_calls()),
            (None, Some(MCall::Macro(9021)), None, false)
        );
        assert!(!c.g_may_call(1000) && c.g_call(650) == Some(CallCode::G65), "G65 always calls");
        // Inside a macro called by an M code: M macro calls are off.
        let c = CallCodes::of(&p, Caller::MCodeMacro.switches_off());
        assert_eq!(
            (c.g_call(1000), c.m_call(50), c.m_call(6)),
            (Some(CallCode::G { program: 9010 }), Some(MCall::Subprogram(9002)), Some(MCall::Subprogram(9001)))
        );
        // Inside a subprogram called by an M or T code: all are off.
        assert_eq!(CallCodes::of(&p, Caller::Subprogram.switches_off()), CallCodes::BUILT_IN);
    }

    #[test]
    fn a_g_code_past_the_readers_range_calls_nothing_and_wraps_to_nothing() {
        let mut p = Parameters::default();
        // G7000 in tenths does not fit a u16: it must not wrap to G446.4.
        p.set(Param::CallG9011, 7000);
        let c = CallCodes::of(&p, 0);
        assert_eq!((c.g_call(4464), c.g_call(7000)), (None, None));
        assert_eq!(c, CallCodes::BUILT_IN);
    }

    #[test]
    fn the_newest_modal_call_not_running_is_due() {
        let mut m = ModalCalls::default();
        assert!(!m.any_due());
        m.cancel();
        let args = Locals::VACANT;
        m.start(100, 1, &args).unwrap();
        assert_eq!(m.due().map(|d| d.1), Some(100));
        m.set_busy(0, true);
        assert!(!m.any_due(), "its own moves call nothing");
        m.set_busy(0, false);
        m.start(200, 2, &args).unwrap();
        assert_eq!(m.due().map(|d| (d.1, d.2)), Some((200, 2)));
        m.set_busy(1, true);
        assert_eq!(m.due().map(|d| d.1), Some(100), "moves in O200 call the older O100");
        m.set_busy(0, true);
        assert!(!m.any_due());
        m.set_busy(0, false);
        m.set_busy(1, false);
        m.start(300, 1, &args).unwrap();
        assert_eq!(m.start(400, 1, &args), Err(crate::alarm::AlarmKind::ModalCallsTooDeep));
        m.cancel();
        assert_eq!(m.due().map(|d| d.1), Some(200));
        m.clear();
        assert!(m.is_empty() && !m.any_due());
    }
}

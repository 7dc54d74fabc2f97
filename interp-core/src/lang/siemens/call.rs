//! Calls with parameter lists: a standard cycle (`CYCLE95("KONTUR_1", 5, …)`) or a
//! subprogram (`ZYKL1(2.5)`), as the 840D passes them (seed 001 1.3.3, lines
//! 567–701).
//!
//! The front end evaluates the arguments as written into [`CallArgs`] — values,
//! strings, empty slots `a, , b` — and binds them to the parameter types of the
//! callee ([`CallArgs::bind`]): more arguments than parameters is alarm 12340,
//! an argument whose type does not convert is alarm 12330, a parameter left out
//! (an empty slot or a list closed early) is [`Arg::Empty`], which the cycles read
//! as zero. Binding happens before the call's block changes anything.
//!
//! A standard cycle reaches the engine as a [`Command`](crate::command::Command)
//! whose group-00 code is [`GCode::CycleCall`](crate::codes::GCode::CycleCall):
//! the driver hands the bound call ([`CycleCall`]) to the block's stage
//! (`cycles::CycleStage::call`), `cycles::execute` sends the block to
//! `Executor::cycle_call` (implemented by `exec`), which calls
//! [`crate::lang::siemens::cycles::start`] with the arguments as [`Arg`]s. The
//! block is then validated (dry run), committed or undone like any cycle block.

use crate::alarm::{AlarmKind, SiemensAlarm as S};
use crate::lang::ProgramText;
use crate::lang::siemens::vars::Vars;
use crate::program::Cursor;

/// Most arguments a call may pass: the longest parameter list of the document
/// (CYCLE950 and SLOT1, 24 parameters). A longer list is alarm 12340 whatever
/// the callee.
pub const MAX_ARGS: usize = 24;

/// Bytes of string arguments one call may pass in all (a contour name
/// `"/_N_SPF_DIR/_N_KONTUR_1_SPF:N130:N210"` is 37).
pub const ARG_TEXT: usize = 96;

/// An evaluated argument of a cycle call.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Arg<'a> {
    /// Left out (`a, , b`, or after the list was closed early): zero for the cycle.
    Empty,
    /// A REAL value.
    Real(f64),
    /// An INT value.
    Int(i64),
    /// A STRING or CHAR value (a CHAR is one byte).
    Str(&'a [u8]),
}

impl Arg<'_> {
    /// The value as a number: `Empty` is zero (seed 001 line 590), a string is
    /// `None`.
    pub fn num(&self) -> Option<f64> {
        match *self {
            Arg::Empty => Some(0.0),
            Arg::Real(v) => Some(v),
            Arg::Int(n) => Some(n as f64),
            Arg::Str(_) => None,
        }
    }

    /// Whether the argument was left out.
    pub fn is_empty(&self) -> bool {
        matches!(self, Arg::Empty)
    }
}

/// The type a cycle parameter is declared with in the manual (REAL, INT, STRING,
/// CHAR/BYTE).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Ty {
    /// REAL.
    Real,
    /// INT.
    Int,
    /// STRING[n].
    Str,
    /// CHAR (the manual's "字节"/BYTE of a FORM parameter: one character in quotes).
    Char,
}

/// A cycle's parameter list as the manual gives it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Signature {
    /// The cycle's name (`"CYCLE95"`); calls match it case-insensitively.
    pub name: &'static str,
    /// The parameters in order, with their names as the manual spells them.
    pub params: &'static [(&'static str, Ty)],
}

/// Parameter names that name a contour (CYCLE95 `NPP`, CYCLE72/74/75 `_KNAME`,
/// CYCLE950 `_NP1`): the driver resolves their string into a [`ContourSource`].
const CONTOUR_PARAMS: [&str; 3] = ["NPP", "_KNAME", "_NP1"];

impl Signature {
    /// Whether `name` (as written in the program) calls this cycle.
    pub fn is(&self, name: &[u8]) -> bool {
        self.name.as_bytes().eq_ignore_ascii_case(name)
    }

    /// The index of the parameter that names the cycle's contour, if it has one.
    pub fn contour_param(&self) -> Option<usize> {
        self.params.iter().position(|(n, t)| *t == Ty::Str && CONTOUR_PARAMS.iter().any(|c| c == n))
    }

    /// The parameter called `name` (case-insensitive), by index.
    pub fn param(&self, name: &str) -> Option<usize> {
        self.params.iter().position(|(n, _)| n.eq_ignore_ascii_case(name))
    }
}

/// What one stored argument is; values are in [`CallArgs::nums`], strings in
/// [`CallArgs::text`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Tag {
    Empty,
    Real,
    Int,
    Str { at: u8, len: u8 },
}

/// The arguments of one call, evaluated, in fixed capacity (nothing refers into
/// the program text: a modal call `MCALL CYCLE81(…)` keeps them for later blocks).
/// Before [`CallArgs::bind`] they are as written; after it they have the
/// parameters' types and one entry per parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct CallArgs {
    count: u8,
    tags: [Tag; MAX_ARGS],
    nums: [f64; MAX_ARGS],
    text: heapless::Vec<u8, ARG_TEXT>,
}

impl Default for CallArgs {
    fn default() -> Self {
        Self::new()
    }
}

impl CallArgs {
    /// No arguments.
    pub const fn new() -> Self {
        CallArgs { count: 0, tags: [Tag::Empty; MAX_ARGS], nums: [0.0; MAX_ARGS], text: heapless::Vec::new() }
    }

    /// Forgets every argument.
    pub fn clear(&mut self) {
        self.count = 0;
        self.text.clear();
    }

    /// Number of arguments (after binding: of parameters).
    pub fn len(&self) -> usize {
        usize::from(self.count)
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// Appends an argument as written: alarm 12340 beyond [`MAX_ARGS`]; a string
    /// that does not fit [`ARG_TEXT`] is alarm 12160 (value range).
    pub fn push(&mut self, arg: Arg<'_>) -> Result<(), AlarmKind> {
        let i = self.len();
        if i >= MAX_ARGS {
            return Err(S::TooManyParameters.into());
        }
        let (tag, num) = match arg {
            Arg::Empty => (Tag::Empty, 0.0),
            Arg::Real(v) => (Tag::Real, v),
            Arg::Int(n) => (Tag::Int, n as f64),
            Arg::Str(s) => {
                let at = self.text.len();
                let len = u8::try_from(s.len()).map_err(|_| S::StringTooLong)?;
                self.text.extend_from_slice(s).map_err(|_| S::StringTooLong)?;
                (Tag::Str { at: at as u8, len }, 0.0)
            }
        };
        self.tags[i] = tag;
        self.nums[i] = num;
        self.count += 1;
        Ok(())
    }

    /// Argument `i` (`Empty` past the end: a list closed early).
    pub fn get(&self, i: usize) -> Arg<'_> {
        if i >= self.len() {
            return Arg::Empty;
        }
        match self.tags[i] {
            Tag::Empty => Arg::Empty,
            Tag::Real => Arg::Real(self.nums[i]),
            Tag::Int => Arg::Int(self.nums[i] as i64),
            Tag::Str { at, len } => {
                let (at, len) = (usize::from(at), usize::from(len));
                Arg::Str(self.text.get(at..at + len).unwrap_or(&[]))
            }
        }
    }

    /// Every argument, into `buf`.
    pub fn args<'s>(&'s self, buf: &'s mut [Arg<'s>; MAX_ARGS]) -> &'s [Arg<'s>] {
        for (i, b) in buf.iter_mut().enumerate().take(self.len()) {
            *b = self.get(i);
        }
        &buf[..self.len()]
    }

    /// Binds the arguments as written to parameters of types `params`: alarm 12340
    /// if there are more arguments than parameters (seed 001 line 596), 12330 if
    /// an argument's type does not convert to its parameter's (line 649). Missing
    /// arguments become [`Arg::Empty`]. The conversions are the 840D's: INT to REAL;
    /// REAL to INT rounded to the nearest whole number (an R parameter may pass a
    /// cycle's INT parameter, line 641); a one-character string to CHAR. A number
    /// never becomes a string or a character, nor a string a number.
    pub fn bind(&mut self, params: impl ExactSizeIterator<Item = Ty>) -> Result<(), AlarmKind> {
        let n = params.len();
        if self.len() > n {
            return Err(S::TooManyParameters.into());
        }
        if n > MAX_ARGS {
            return Err(S::TooManyParameters.into());
        }
        for (i, ty) in params.enumerate() {
            let tag = if i < self.len() { self.tags[i] } else { Tag::Empty };
            let (tag, num) = match (ty, tag) {
                (_, Tag::Empty) => (Tag::Empty, 0.0),
                (Ty::Real, Tag::Real | Tag::Int) => (Tag::Real, self.nums[i]),
                (Ty::Int, Tag::Int) => (Tag::Int, self.nums[i]),
                (Ty::Int, Tag::Real) => {
                    let v = libm::round(self.nums[i]);
                    if !(-2_147_483_648.0..=2_147_483_647.0).contains(&v) {
                        return Err(S::ParameterType { index: i as u8 + 1 }.into());
                    }
                    (Tag::Int, v)
                }
                (Ty::Str, t @ Tag::Str { .. }) => (t, 0.0),
                (Ty::Char, t @ Tag::Str { len: 1, .. }) => (t, 0.0),
                _ => return Err(S::ParameterType { index: i as u8 + 1 }.into()),
            };
            self.tags[i] = tag;
            self.nums[i] = num;
        }
        self.count = n as u8;
        Ok(())
    }
}

/// Where the contour of a cycle is (CYCLE95 `NPP`, CYCLE72 `_KNAME` …): a
/// subprogram by name (`"KONTUR_1"`: its blocks after the `PROC` line up to `M17`/
/// `RET` or its end) or a range of the calling program between two labels
/// (`"ANFANG:ENDE"`, also after `M02`) or block numbers, resolved by the driver
/// before the cycle starts. The cycle reads the blocks with
/// [`crate::lang::siemens::contour`], in the SINUMERIK language.
#[derive(Clone, Copy, Debug)]
pub struct ContourSource<'a> {
    /// The program the contour is in (its text; the cursors index into it).
    pub program: ProgramText<'a>,
    /// The first block of the contour (for a label range, the block of the start label).
    pub start: Cursor,
    /// The block of the end label (read as the contour's last block); `None`: the
    /// contour runs to the subprogram's `M17`/`RET` or the end of its text.
    pub end: Option<Cursor>,
    /// The variables the contour's words may use.
    pub vars: &'a Vars,
}

/// A standard cycle call as the engine receives it: the cycle, its bound
/// arguments and its contour, if it names one.
#[derive(Clone, Copy, Debug)]
pub struct CycleCall<'a> {
    /// The cycle.
    pub sig: &'static Signature,
    /// Its arguments, bound to `sig` (one per parameter).
    pub args: &'a CallArgs,
    /// The contour, if the cycle has a contour parameter and it names one.
    pub contour: Option<ContourSource<'a>>,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The document's fictitious CYCLE100 (lines 598–616).
    const CYCLE100: Signature = Signature {
        name: "CYCLE100",
        params: &[("FORM", Ty::Char), ("MID", Ty::Real), ("FFR", Ty::Real), ("VARI", Ty::Int), ("FAL", Ty::Real)],
    };

    fn bind(args: &[Arg<'_>]) -> Result<CallArgs, AlarmKind> {
        let mut c = CallArgs::new();
        for a in args {
            c.push(*a)?;
        }
        c.bind(CYCLE100.params.iter().map(|p| p.1))?;
        Ok(c)
    }

    #[test]
    fn constants_variables_and_r_parameters_bind_with_conversions() {
        // CYCLE100 ("E", 5, 0.1, 1, 0) and CYCLE100 (FORM, R1, R2, R3, R4): the R
        // parameters are REAL, VARI is INT.
        let c = bind(&[Arg::Str(b"E"), Arg::Int(5), Arg::Real(0.1), Arg::Real(1.0), Arg::Real(0.0)]).unwrap();
        let mut buf = [Arg::Empty; MAX_ARGS];
        assert_eq!(c.args(&mut buf), &[Arg::Str(b"E"), Arg::Real(5.0), Arg::Real(0.1), Arg::Int(1), Arg::Real(0.0)]);
    }

    #[test]
    fn left_out_parameters_are_empty_and_read_as_zero() {
        // CYCLE100 ("F", 3, 0.3, , 1) and CYCLE100 ("F", 3, 0.3).
        let c = bind(&[Arg::Str(b"F"), Arg::Real(3.0), Arg::Real(0.3), Arg::Empty, Arg::Int(1)]).unwrap();
        assert_eq!(c.get(3), Arg::Empty);
        assert_eq!(c.get(3).num(), Some(0.0));
        assert_eq!(c.get(4), Arg::Real(1.0));
        let c = bind(&[Arg::Str(b"F"), Arg::Real(3.0), Arg::Real(0.3)]).unwrap();
        assert_eq!(c.len(), 5);
        assert_eq!((c.get(3), c.get(4)), (Arg::Empty, Arg::Empty));
    }

    #[test]
    fn too_many_arguments_is_12340_and_a_wrong_type_12330() {
        let six = [Arg::Str(b"E"), Arg::Real(5.0), Arg::Real(0.1), Arg::Int(1), Arg::Real(0.0), Arg::Real(1.0)];
        assert_eq!(bind(&six).unwrap_err(), AlarmKind::from(S::TooManyParameters));
        assert_eq!(AlarmKind::from(S::TooManyParameters).code(), 12340);
        // A number for the CHAR FORM, a string for the REAL MID, a long string for a CHAR.
        assert_eq!(bind(&[Arg::Real(5.0)]).unwrap_err(), AlarmKind::from(S::ParameterType { index: 1 }));
        assert_eq!(
            bind(&[Arg::Str(b"E"), Arg::Str(b"5")]).unwrap_err(),
            AlarmKind::from(S::ParameterType { index: 2 })
        );
        assert_eq!(bind(&[Arg::Str(b"EF")]).unwrap_err(), AlarmKind::from(S::ParameterType { index: 1 }));
        assert_eq!(AlarmKind::from(S::ParameterType { index: 1 }).code(), 12330);
        // REAL to INT rounds.
        let c = bind(&[Arg::Str(b"E"), Arg::Empty, Arg::Empty, Arg::Real(1.5)]).unwrap();
        assert_eq!(c.get(3), Arg::Int(2));
        let mut c = CallArgs::new();
        for _ in 0..MAX_ARGS {
            c.push(Arg::Empty).unwrap();
        }
        assert_eq!(c.push(Arg::Empty), Err(AlarmKind::from(S::TooManyParameters)));
    }

    #[test]
    fn contour_parameters_are_found_by_name() {
        const C95: Signature = Signature { name: "CYCLE95", params: &[("NPP", Ty::Str), ("MID", Ty::Real)] };
        assert_eq!(C95.contour_param(), Some(0));
        assert_eq!(CYCLE100.contour_param(), None);
        assert!(C95.is(b"cycle95"));
        assert_eq!(C95.param("mid"), Some(1));
    }
}

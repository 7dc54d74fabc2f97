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
//! `Executor::cycle_call` (implemented by `exec`), which calls the plugged front
//! end's [`Front::cycle_start`] with the arguments as [`Arg`]s. The
//! block is then validated (dry run), committed or undone like any cycle block.

use crate::alarm::{AlarmKind, SiemensAlarm as S};
use crate::lang::siemens::vars::Vars;
use crate::lang::{Front, ProgramText};
use crate::program::Cursor;

/// Most arguments a call may pass: the longest parameter list of the document
/// (CYCLE950 and SLOT1, 24 parameters). A longer list is alarm 12340 whatever
/// the callee.
pub const MAX_ARGS: usize = 24;

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

/// A cycle's parameter list as the manual gives it: names and types as two
/// strings (12 bytes a parameter as a table of `(&str, Ty)` pairs, 1 and its
/// name's here: the document's 37 cycles have ~560 parameters). Written with
/// [`signature!`](crate::signature).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Signature {
    /// The cycle's name (`"CYCLE95"`); calls match it case-insensitively.
    pub name: &'static str,
    /// The parameters' names in order, as the manual spells them, each followed
    /// by a blank.
    pub names: &'static str,
    /// The parameters' types in order, a letter each: `R` REAL, `I` INT, `S`
    /// STRING, `C` CHAR.
    pub types: &'static str,
}

/// A [`Signature`]: `signature!("CYCLE81" (RTP: R, RFP: R, SDIS: R, DP: R, DPR: R))`,
/// each parameter's type `R` REAL, `I` INT, `S` STRING or `C` CHAR.
#[macro_export]
macro_rules! signature {
    ($name:literal ($($param:ident: $ty:ident),* $(,)?)) => {
        $crate::lang::siemens::call::Signature {
            name: $name,
            names: concat!($(stringify!($param), " "),*),
            types: concat!($(stringify!($ty)),*),
        }
    };
}

/// Parameter names that name a contour (CYCLE95 `NPP`, CYCLE72/74/75 `_KNAME`,
/// CYCLE950 `_NP1`): the driver resolves their string into a [`ContourSource`].
const CONTOUR_PARAMS: [&str; 3] = ["NPP", "_KNAME", "_NP1"];

impl Ty {
    /// The type a [`Signature`] letter stands for.
    fn of_letter(c: u8) -> Ty {
        match c {
            b'I' => Ty::Int,
            b'S' => Ty::Str,
            b'C' => Ty::Char,
            _ => Ty::Real,
        }
    }
}

impl Signature {
    /// Whether `name` (as written in the program) calls this cycle.
    pub fn is(&self, name: &[u8]) -> bool {
        self.name.as_bytes().eq_ignore_ascii_case(name)
    }

    /// Number of parameters.
    pub fn len(&self) -> usize {
        self.types.len()
    }

    /// No parameters.
    pub fn is_empty(&self) -> bool {
        self.types.is_empty()
    }

    /// The parameters' types in order.
    pub fn types(&self) -> impl ExactSizeIterator<Item = Ty> + use<> {
        self.types.bytes().map(Ty::of_letter)
    }

    /// The parameters' names in order.
    pub fn names(&self) -> impl Iterator<Item = &'static str> + use<> {
        self.names.split(' ').filter(|n| !n.is_empty())
    }

    /// The index of the first parameter whose name (bytes) and type satisfy `f`.
    fn find(&self, f: impl Fn(&[u8], Ty) -> bool) -> Option<usize> {
        let names = self.names.as_bytes().split(|&b| b == b' ');
        names.zip(self.types()).position(|(n, t)| f(n, t))
    }

    /// The index of the parameter that names the cycle's contour, if it has one.
    pub fn contour_param(&self) -> Option<usize> {
        self.find(|n, t| t == Ty::Str && CONTOUR_PARAMS.iter().any(|c| c.as_bytes() == n))
    }

    /// The parameter called `name` (case-insensitive), by index.
    pub fn param(&self, name: &str) -> Option<usize> {
        self.find(|n, _| n.eq_ignore_ascii_case(name.as_bytes()))
    }
}

/// Bytes one call's arguments take when stored: a tag byte each, 8 bytes a
/// number, a length byte and the bytes a string. The document's longest call
/// (CYCLE950: 24 arguments, 6 strings) fits.
pub const ARG_BYTES: usize = 256;

/// The tags of stored arguments.
const EMPTY: u8 = 0;
const REAL: u8 = 1;
const INT: u8 = 2;
const STR: u8 = 3;

/// The arguments of one call, evaluated, encoded in fixed capacity (nothing
/// refers into the program text: a modal call `MCALL CYCLE81(…)` keeps them for
/// later blocks). Before [`CallArgs::bind`] they are as written; after it they
/// have the parameters' types and one entry per parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct CallArgs {
    count: u8,
    bytes: heapless::Vec<u8, ARG_BYTES>,
}

impl Default for CallArgs {
    fn default() -> Self {
        Self::new()
    }
}

impl CallArgs {
    /// No arguments.
    pub const fn new() -> Self {
        CallArgs { count: 0, bytes: heapless::Vec::new() }
    }

    /// Forgets every argument.
    pub fn clear(&mut self) {
        self.count = 0;
        self.bytes.clear();
    }

    /// Number of arguments (after binding: of parameters).
    pub fn len(&self) -> usize {
        usize::from(self.count)
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// Appends an argument as written: alarm 12340 beyond [`MAX_ARGS`]; arguments
    /// that do not fit [`ARG_BYTES`] are alarm 12160.
    pub fn push<'b, A: Into<Arg<'b>>>(&mut self, arg: A) -> Result<(), AlarmKind> {
        let arg = arg.into();
        if self.len() >= MAX_ARGS {
            return Err(S::TooManyParameters.into());
        }
        let full = |_| AlarmKind::from(S::StringTooLong);
        match arg {
            Arg::Empty => self.bytes.push(EMPTY).map_err(full)?,
            Arg::Real(v) => {
                self.bytes.push(REAL).map_err(full)?;
                self.bytes.extend_from_slice(&v.to_le_bytes()).map_err(|_| S::StringTooLong)?;
            }
            Arg::Int(n) => {
                self.bytes.push(INT).map_err(full)?;
                self.bytes.extend_from_slice(&n.to_le_bytes()).map_err(|_| S::StringTooLong)?;
            }
            Arg::Str(s) => {
                let len = u8::try_from(s.len()).map_err(|_| S::StringTooLong)?;
                self.bytes.push(STR).map_err(full)?;
                self.bytes.push(len).map_err(full)?;
                self.bytes.extend_from_slice(s).map_err(|_| S::StringTooLong)?;
            }
        }
        self.count += 1;
        Ok(())
    }

    /// The argument at byte `at` and where the next one begins. Out of line:
    /// one copy for its four callers.
    #[inline(never)]
    fn decode(&self, at: usize) -> (Arg<'_>, usize) {
        let b = &self.bytes;
        let eight = |k: usize| -> [u8; 8] {
            let mut a = [0u8; 8];
            if let Some(s) = b.get(k..k + 8) {
                a.copy_from_slice(s);
            }
            a
        };
        match b.get(at).copied() {
            Some(REAL) => (Arg::Real(f64::from_le_bytes(eight(at + 1))), at + 9),
            Some(INT) => (Arg::Int(i64::from_le_bytes(eight(at + 1))), at + 9),
            Some(STR) => {
                let len = usize::from(b.get(at + 1).copied().unwrap_or(0));
                (Arg::Str(b.get(at + 2..at + 2 + len).unwrap_or(&[])), at + 2 + len)
            }
            _ => (Arg::Empty, at + 1),
        }
    }

    /// Argument `i` (`Empty` past the end: a list closed early).
    pub fn get(&self, i: usize) -> Arg<'_> {
        if i >= self.len() {
            return Arg::Empty;
        }
        let mut at = 0;
        for _ in 0..i {
            at = self.decode(at).1;
        }
        self.decode(at).0
    }

    /// Every argument, into `buf`.
    pub fn args<'s>(&'s self, buf: &'s mut [Arg<'s>; MAX_ARGS]) -> &'s [Arg<'s>] {
        let mut at = 0;
        for b in buf.iter_mut().take(self.len()) {
            let (a, next) = self.decode(at);
            *b = a;
            at = next;
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
    pub fn bind(&mut self, mut params: impl ExactSizeIterator<Item = Ty>) -> Result<(), AlarmKind> {
        self.bind_dyn::<dyn ExactSizeIterator<Item = Ty>>(&mut params)
    }

    /// [`CallArgs::bind`] on a trait object: one copy of the binding in flash
    /// for every kind of parameter list (a cycle's signature, a PROC's). Generic
    /// (over `dyn ExactSizeIterator` only) so that it is compiled with the front
    /// end that calls it, built for size on the board, like `push`.
    #[inline(never)]
    fn bind_dyn<I: ExactSizeIterator<Item = Ty> + ?Sized>(&mut self, params: &mut I) -> Result<(), AlarmKind> {
        let n = params.len();
        if self.len() > n || n > MAX_ARGS {
            return Err(S::TooManyParameters.into());
        }
        let mut out = CallArgs::new();
        let mut at = 0;
        for (i, ty) in params.enumerate() {
            let (arg, next) = if i < self.len() { self.decode(at) } else { (Arg::Empty, at) };
            at = next;
            let bad = || AlarmKind::from(S::ParameterType { index: i as u8 + 1 });
            let bound = match (ty, arg) {
                (_, Arg::Empty) => Arg::Empty,
                (Ty::Real, Arg::Real(v)) => Arg::Real(v),
                (Ty::Real, Arg::Int(v)) => Arg::Real(v as f64),
                (Ty::Int, Arg::Int(v)) => Arg::Int(v),
                (Ty::Int, Arg::Real(v)) => {
                    let v = libm::round(v);
                    if !(-2_147_483_648.0..=2_147_483_647.0).contains(&v) {
                        return Err(bad());
                    }
                    Arg::Int(v as i64)
                }
                (Ty::Str, Arg::Str(s)) => Arg::Str(s),
                (Ty::Char, Arg::Str(s)) if s.len() == 1 => Arg::Str(s),
                _ => return Err(bad()),
            };
            out.push(bound)?;
        }
        *self = out;
        Ok(())
    }
}

/// Where the contour of a cycle is (CYCLE95 `NPP`, CYCLE72 `_KNAME` …): a
/// subprogram by name (`"KONTUR_1"`: its blocks after the `PROC` line up to `M17`/
/// `RET` or its end) or a range of the calling program between two labels
/// (`"ANFANG:ENDE"`, also after `M02`) or block numbers, resolved by the driver
/// before the cycle starts. The engine reads the blocks through `front`
/// ([`Front::contour_command`]), in the language of the program.
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
    /// The front end that reads the contour's blocks.
    pub front: &'a dyn Front,
}

/// Where a cycle's contour is, before the variables and the front end that
/// read it are attached ([`ContourSource`]).
#[derive(Clone, Copy, Debug)]
pub struct ContourAt<'c> {
    /// The program the contour is in.
    pub program: ProgramText<'c>,
    /// Its first block.
    pub start: Cursor,
    /// Its last block (`None`: to the subprogram's end).
    pub end: Option<Cursor>,
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
    /// The front end whose cycle it is ([`Front::cycle_start`]).
    pub front: &'a dyn Front,
    /// CYCLE73: the islands CYCLE75 transferred (`contour` is the pocket's edge,
    /// CYCLE74's), read by the engine ([`CycleCall::island`]).
    #[cfg(feature = "mill-island")]
    pub islands: &'a [ContourAt<'a>],
}

impl<'a> CycleCall<'a> {
    /// Island `i` of a CYCLE73 call, read with the edge contour's variables and
    /// front end; `None` past the last (or without an edge).
    #[cfg(feature = "mill-island")]
    pub fn island(&self, i: usize) -> Option<ContourSource<'a>> {
        let edge = self.contour?;
        let at = self.islands.get(i)?;
        Some(ContourSource { program: at.program, start: at.start, end: at.end, ..edge })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The document's fictitious CYCLE100 (lines 598–616).
    const CYCLE100: Signature = crate::signature!("CYCLE100" (FORM: C, MID: R, FFR: R, VARI: I, FAL: R));

    fn bind(args: &[Arg<'_>]) -> Result<CallArgs, AlarmKind> {
        let mut c = CallArgs::new();
        for a in args {
            c.push(*a)?;
        }
        c.bind(CYCLE100.types())?;
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
        const C95: Signature = crate::signature!("CYCLE95" (NPP: S, MID: R));
        assert_eq!(C95.contour_param(), Some(0));
        assert_eq!(CYCLE100.contour_param(), None);
        assert!(C95.is(b"cycle95"));
        assert_eq!(C95.param("mid"), Some(1));
    }
}

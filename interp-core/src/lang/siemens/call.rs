//! A SINUMERIK cycle call as the front end hands it to the cycles: the evaluated
//! arguments, the parameter list the manual gives each cycle, and where a cycle's
//! contour is (document lines 569–701: positional parameters of declared types,
//! empty slots and a list closed early meaning zero).

use crate::lang::ProgramText;
use crate::program::Cursor;

/// An evaluated argument of a cycle call.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Arg<'a> {
    /// Left out (`a, , b` or the list closed early): the value zero.
    Empty,
    /// A REAL value.
    Real(f64),
    /// An INT value.
    Int(i64),
    /// A STRING or CHAR value, without its quotes.
    Str(&'a [u8]),
}

/// The type a cycle parameter is declared with in the manual (REAL, INT, STRING, CHAR/BYTE).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ty {
    /// REAL (实数).
    Real,
    /// INT (整数).
    Int,
    /// STRING (字符串).
    Str,
    /// CHAR / BYTE (字节): one character, like CYCLE94's FORM "E".
    Char,
}

/// A cycle's parameter list as the manual gives it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Signature {
    /// The cycle's name (upper case).
    pub name: &'static str,
    /// Its parameters in order, with their declared types.
    pub params: &'static [(&'static str, Ty)],
}

/// Where a cycle's contour is (CYCLE95 `NPP`): a contour subprogram by name
/// (`"KONTUR_1"`: its blocks up to M17/RET) or a section of a program between two
/// labels (`"ANFANG:ENDE"`, also after M02), read in the program's language.
#[derive(Clone, Copy, Debug)]
pub struct ContourSource<'a> {
    /// The program the contour is in.
    pub program: ProgramText<'a>,
    /// Its first block.
    pub start: Cursor,
    /// Its last block (the block of the end label); `None`: up to the end of the
    /// subprogram (M17, RET, M2/M30).
    pub end: Option<Cursor>,
}

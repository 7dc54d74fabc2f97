//! SINUMERIK variables: R parameters and the variables a program defines with
//! `DEF` (local user data, one set per program level). The cycle setting data
//! `_ZSD[…]` of GUD7 live in the modal state (`State::cycle`), where the cycles
//! read them.
//!
//! Everything is in fixed capacity, sized for the document's programs (the CYCLE93
//! example defines 17 variables, the CYCLE83 one 14) and the board's RAM: R0–R99
//! (the 840D's default of 100), of which 32 may be other than zero at a time; 32
//! DEF variables in all levels together with 192 bytes of names and 96 bytes of
//! STRING contents. More is alarm 12460. A level's variables go when the level
//! returns (LIFO, as the 840D's LUD).
//!
//! Names are compared without regard to case (the 840D reads them in capitals).

use crate::alarm::{AlarmKind, SiemensAlarm as S};

/// R parameters R0–R99.
pub const R_PARAMS: usize = 100;
/// R parameters that may hold a value other than zero at a time.
pub const R_SLOTS: usize = 32;
/// DEF variables of all program levels together.
pub const LOCALS: usize = 32;
/// Bytes of variable names of all levels together.
pub const NAME_BYTES: usize = 192;
/// Bytes of STRING contents of all levels together.
pub const STRING_BYTES: usize = 96;
/// Longest name (the 840D allows 31 characters after the first).
pub const MAX_NAME: usize = 32;
/// Longest STRING the 840D allows (`STRING[200]`).
pub const MAX_STRING: usize = 200;

/// The type a variable was defined with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum VarTy {
    /// REAL.
    Real,
    /// INT (32 bits on the 840D).
    Int,
    /// BOOL.
    Bool,
    /// CHAR.
    Char,
    /// STRING[cap].
    Str {
        /// Most characters.
        cap: u8,
    },
}

/// A variable's value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value<'a> {
    /// REAL.
    Real(f64),
    /// INT.
    Int(i64),
    /// BOOL.
    Bool(bool),
    /// CHAR.
    Char(u8),
    /// STRING.
    Str(&'a [u8]),
}

impl Value<'_> {
    /// The value as a number, if it is one (BOOL 0/1, CHAR its code). Out of
    /// line: one copy for the expressions' and the variables' callers.
    #[inline(never)]
    pub fn num(&self) -> Option<f64> {
        match *self {
            Value::Real(v) => Some(v),
            Value::Int(n) => Some(n as f64),
            Value::Bool(b) => Some(if b { 1.0 } else { 0.0 }),
            Value::Char(c) => Some(f64::from(c)),
            Value::Str(_) => None,
        }
    }
}

/// One DEF variable.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Local {
    /// Name: `names[name_at..name_at + name_len]`.
    name_at: u16,
    name_len: u8,
    /// Program level that defined it.
    level: u8,
    ty: VarTy,
    /// REAL/INT/BOOL/CHAR value; for a STRING the contents' offset in `strings`.
    value: f64,
    /// Length of a STRING's contents.
    len: u8,
}

/// The SINUMERIK variables of one channel.
#[derive(Clone, PartialEq)]
pub struct Vars {
    /// Which R parameters have a value (their numbers), …
    r_used: heapless::Vec<u8, R_SLOTS>,
    /// … and the values, by the same index.
    r_values: [f64; R_SLOTS],
    locals: heapless::Vec<Local, LOCALS>,
    names: heapless::Vec<u8, NAME_BYTES>,
    strings: heapless::Vec<u8, STRING_BYTES>,
    /// The program level DEF defines in and names are looked up in (0 = main).
    level: u8,
}

impl core::fmt::Debug for Vars {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "Vars {{ level {}, {} defined }}", self.level, self.locals.len())
    }
}

impl Default for Vars {
    fn default() -> Self {
        Self::new()
    }
}

/// The number of R parameter `n`, 0–99 (alarm 17020 beyond).
fn r_index(n: i64) -> Result<u8, AlarmKind> {
    u8::try_from(n).ok().filter(|&n| usize::from(n) < R_PARAMS).ok_or(S::IndexOutOfRange.into())
}

/// Whether two names are the same name.
fn same(a: &[u8], b: &[u8]) -> bool {
    a.eq_ignore_ascii_case(b)
}

/// The methods the front end calls per statement (`get`, `set`, `define`,
/// `type_of`, `convert_to`) are generic over the name's type: they are compiled
/// with the front end that instantiates them (`interp-siemens`, built for size on
/// the board), not at this crate's opt-level 2 for the FANUC per-block budget.
impl Vars {
    /// All R parameters zero, nothing defined, level 0.
    pub const fn new() -> Self {
        Vars {
            r_used: heapless::Vec::new(),
            r_values: [0.0; R_SLOTS],
            locals: heapless::Vec::new(),
            names: heapless::Vec::new(),
            strings: heapless::Vec::new(),
            level: 0,
        }
    }

    /// R parameter `n` (alarm 12160 past R99, as the 840D's value-range alarm).
    pub fn r(&self, n: i64) -> Result<f64, AlarmKind> {
        let n = r_index(n)?;
        Ok(self.r_used.iter().position(|&u| u == n).map_or(0.0, |i| self.r_values[i]))
    }

    /// Whether R parameter `n` holds a slot (a value other than zero was set).
    pub fn has_r(&self, n: i64) -> bool {
        r_index(n).is_ok_and(|n| self.r_used.contains(&n))
    }

    /// How many more R parameters may get a value.
    pub fn r_free(&self) -> usize {
        R_SLOTS - self.r_used.len()
    }

    /// Sets R parameter `n` (alarm 17020 past R99, 12460 when 32 others hold values).
    pub fn set_r(&mut self, n: i64, v: f64) -> Result<(), AlarmKind> {
        let n = r_index(n)?;
        match self.r_used.iter().position(|&u| u == n) {
            Some(i) => self.r_values[i] = v,
            None if v == 0.0 => {}
            None => {
                let i = self.r_used.len();
                self.r_used.push(n).map_err(|_| S::TooManySymbols)?;
                self.r_values[i] = v;
            }
        }
        Ok(())
    }

    /// The program level names are defined and looked up in.
    pub fn level(&self) -> u8 {
        self.level
    }

    /// A subprogram level begins: names defined from now on are its own, the
    /// caller's are out of sight until [`Vars::leave`].
    pub fn enter(&mut self) {
        self.level = self.level.saturating_add(1);
    }

    /// The current level returns: its variables go.
    pub fn leave(&mut self) {
        self.drop_level(self.level);
        self.level = self.level.saturating_sub(1);
    }

    /// Back to level 0 with nothing defined (a new run). R parameters keep their
    /// values, as on the 840D.
    pub fn clear_locals(&mut self) {
        self.locals.clear();
        self.names.clear();
        self.strings.clear();
        self.level = 0;
    }

    /// A mark to go back to with [`Vars::undo_to`] (a DEF that fails halfway).
    pub fn mark(&self) -> usize {
        self.locals.len()
    }

    /// Forgets the variables defined since `mark`. Out of line: one copy for
    /// the level's end and a failed DEF.
    #[inline(never)]
    pub fn undo_to(&mut self, mark: usize) {
        if let Some(first) = self.locals.get(mark).copied() {
            self.names.truncate(usize::from(first.name_at));
            if let Some(s) = self.locals[mark..].iter().find(|l| matches!(l.ty, VarTy::Str { .. })) {
                self.strings.truncate(s.value as usize);
            }
            self.locals.truncate(mark);
        }
    }

    /// Forgets the variables of levels `level` and deeper.
    fn drop_level(&mut self, level: u8) {
        let keep = self.locals.iter().position(|l| l.level >= level).unwrap_or(self.locals.len());
        self.undo_to(keep);
    }

    fn name_of(&self, l: &Local) -> &[u8] {
        let at = usize::from(l.name_at);
        self.names.get(at..at + usize::from(l.name_len)).unwrap_or(&[])
    }

    fn find(&self, name: &[u8]) -> Option<usize> {
        let level = self.level;
        self.locals.iter().rposition(|l| l.level == level && same(self.name_of(l), name))
    }

    /// Whether `name` is defined in the current level.
    pub fn is_defined(&self, name: &[u8]) -> bool {
        self.find(name).is_some()
    }

    /// The type of `name` in the current level.
    pub fn type_of<N: AsRef<[u8]> + ?Sized>(&self, name: &N) -> Option<VarTy> {
        self.find(name.as_ref()).map(|i| self.locals[i].ty)
    }

    /// Defines `name` of type `ty` in the current level, zero (empty) at first:
    /// alarm 12170 if the level has it already, 12460 when the storage is full.
    pub fn define<N: AsRef<[u8]> + ?Sized>(&mut self, name: &N, ty: VarTy) -> Result<(), AlarmKind> {
        let name = name.as_ref();
        if name.is_empty() || name.len() > MAX_NAME {
            return Err(S::SyntaxError { what: "variable name longer than 32 characters" }.into());
        }
        if self.find(name).is_some() {
            return Err(S::NameDefinedTwice.into());
        }
        if self.locals.is_full() || self.names.len() + name.len() > NAME_BYTES {
            return Err(S::TooManySymbols.into());
        }
        let value = match ty {
            VarTy::Str { cap } => {
                let at = self.strings.len();
                if at + usize::from(cap) > STRING_BYTES {
                    return Err(S::TooManySymbols.into());
                }
                self.strings.resize(at + usize::from(cap), 0).map_err(|_| S::TooManySymbols)?;
                at as f64
            }
            _ => 0.0,
        };
        let name_at = self.names.len() as u16;
        self.names.extend_from_slice(name).map_err(|_| S::TooManySymbols)?;
        let local = Local { name_at, name_len: name.len() as u8, level: self.level, ty, value, len: 0 };
        self.locals.push(local).map_err(|_| AlarmKind::from(S::TooManySymbols))
    }

    /// The value of `name` in the current level.
    pub fn get<N: AsRef<[u8]> + ?Sized>(&self, name: &N) -> Option<Value<'_>> {
        let l = &self.locals[self.find(name.as_ref())?];
        Some(match l.ty {
            VarTy::Real => Value::Real(l.value),
            VarTy::Int => Value::Int(l.value as i64),
            VarTy::Bool => Value::Bool(l.value != 0.0),
            VarTy::Char => Value::Char(l.value as u8),
            VarTy::Str { .. } => {
                let at = l.value as usize;
                Value::Str(self.strings.get(at..at + usize::from(l.len)).unwrap_or(&[]))
            }
        })
    }

    /// Assigns `value` to `name` with the 840D's conversions to the variable's type
    /// (REAL→INT rounded, a number to BOOL ≠ 0, a one-character string to CHAR):
    /// alarm 12550 if `name` is not defined, 12150 if the value does not convert,
    /// 12160 if a STRING would exceed its length.
    pub fn set<N: AsRef<[u8]> + ?Sized>(&mut self, name: &N, value: Value<'_>) -> Result<(), AlarmKind> {
        let i = self.find(name.as_ref()).ok_or(AlarmKind::from(S::NameNotDefined))?;
        let l = self.locals[i];
        let (v, len) = match (l.ty, value) {
            (VarTy::Str { cap }, Value::Str(s)) => {
                if s.len() > usize::from(cap) {
                    return Err(S::StringTooLong.into());
                }
                let at = l.value as usize;
                self.strings[at..at + s.len()].copy_from_slice(s);
                (l.value, s.len() as u8)
            }
            (VarTy::Str { cap }, Value::Char(c)) if cap >= 1 => {
                self.strings[l.value as usize] = c;
                (l.value, 1)
            }
            (ty, v) => (convert(ty, v)?, 0),
        };
        self.locals[i].value = v;
        self.locals[i].len = len;
        Ok(())
    }
}

/// `v` converted to type `ty` as an assignment converts it: alarm 12150 if it does
/// not convert, 12160 if it is out of the type's range (a STRING longer than its
/// length).
pub fn convert_to<'a, V: Into<Value<'a>>>(ty: VarTy, v: V) -> Result<Value<'a>, AlarmKind> {
    Ok(match (ty, v.into()) {
        (VarTy::Str { cap }, Value::Str(s)) => {
            if s.len() > usize::from(cap) {
                return Err(S::StringTooLong.into());
            }
            Value::Str(s)
        }
        (VarTy::Str { cap }, Value::Char(c)) if cap >= 1 => Value::Char(c),
        (ty, v) => {
            let x = convert(ty, v)?;
            match ty {
                VarTy::Real => Value::Real(x),
                VarTy::Int => Value::Int(x as i64),
                VarTy::Bool => Value::Bool(x != 0.0),
                VarTy::Char => Value::Char(x as u8),
                VarTy::Str { .. } => return Err(S::TypeMismatch.into()),
            }
        }
    })
}

/// A scalar value as a variable of type `ty` stores it (alarm 12150 if it does
/// not convert).
fn convert<'a, V: Into<Value<'a>>>(ty: VarTy, v: V) -> Result<f64, AlarmKind> {
    let v = v.into();
    let bad = Err(AlarmKind::from(S::TypeMismatch));
    match (ty, v) {
        (_, Value::Str(s)) if ty == VarTy::Char && s.len() == 1 => Ok(f64::from(s[0])),
        (VarTy::Bool, Value::Str(s)) => Ok(if s.is_empty() { 0.0 } else { 1.0 }),
        (_, Value::Str(_)) => bad,
        (VarTy::Real, v) => v.num().ok_or(AlarmKind::from(S::TypeMismatch)),
        (VarTy::Int, v) => {
            let x = libm::round(v.num().ok_or(AlarmKind::from(S::TypeMismatch))?);
            if !(-2_147_483_648.0..=2_147_483_647.0).contains(&x) {
                return Err(S::ValueRange.into());
            }
            Ok(x)
        }
        (VarTy::Bool, v) => Ok(if v.num().unwrap_or(0.0) != 0.0 { 1.0 } else { 0.0 }),
        (VarTy::Char, v) => {
            let x = libm::round(v.num().ok_or(AlarmKind::from(S::TypeMismatch))?);
            if !(0.0..=255.0).contains(&x) {
                return Err(S::ValueRange.into());
            }
            Ok(x)
        }
        (VarTy::Str { .. }, _) => bad,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn def_variables_belong_to_their_level() {
        let mut v = Vars::new();
        v.define(b"MID", VarTy::Real).unwrap();
        v.set(b"mid", Value::Int(7)).unwrap();
        assert_eq!(v.get(b"MID"), Some(Value::Real(7.0)));
        assert_eq!(v.define(b"Mid", VarTy::Int), Err(AlarmKind::from(S::NameDefinedTwice)));
        v.enter();
        assert_eq!(v.get(b"MID"), None);
        v.define(b"MID", VarTy::Int).unwrap();
        v.set(b"MID", Value::Real(2.5)).unwrap();
        assert_eq!(v.get(b"MID"), Some(Value::Int(3)));
        v.define(b"NAME", VarTy::Str { cap: 8 }).unwrap();
        v.set(b"NAME", Value::Str(b"KONTUR_1")).unwrap();
        assert_eq!(v.get(b"NAME"), Some(Value::Str(b"KONTUR_1")));
        assert_eq!(v.set(b"NAME", Value::Str(b"KONTUR_10")), Err(AlarmKind::from(S::StringTooLong)));
        assert_eq!(v.set(b"NAME", Value::Real(1.0)), Err(AlarmKind::from(S::TypeMismatch)));
        v.leave();
        assert_eq!(v.get(b"MID"), Some(Value::Real(7.0)));
        assert_eq!(v.set(b"NAME", Value::Real(1.0)), Err(AlarmKind::from(S::NameNotDefined)));
        // The level's storage is free again.
        assert_eq!(v.locals.len(), 1);
        assert_eq!((v.names.len(), v.strings.len()), (3, 0));
    }

    #[test]
    fn storage_is_bounded() {
        let mut v = Vars::new();
        for i in 0..LOCALS {
            let name = [b'V', b'0' + (i / 10) as u8, b'0' + (i % 10) as u8];
            v.define(&name, VarTy::Real).unwrap();
        }
        assert_eq!(v.define(b"ONE_MORE", VarTy::Real), Err(AlarmKind::from(S::TooManySymbols)));
        assert_eq!(v.r(100), Err(AlarmKind::from(S::IndexOutOfRange)));
        v.set_r(99, 1.5).unwrap();
        assert_eq!(v.r(99), Ok(1.5));
        assert_eq!(v.r(98), Ok(0.0));
        for n in 0..31 {
            v.set_r(n, 1.0).unwrap();
        }
        assert_eq!(v.r_free(), 0);
        assert_eq!(v.set_r(50, 1.0), Err(AlarmKind::from(S::TooManySymbols)));
        assert_eq!(v.set_r(50, 0.0), Ok(()), "zero needs no slot");
        v.set_r(3, 2.0).unwrap();
        assert_eq!(v.r(3), Ok(2.0));
        let mut v = Vars::new();
        assert_eq!(v.define(b"S", VarTy::Str { cap: 90 }), Ok(()));
        assert_eq!(v.define(b"T", VarTy::Str { cap: 7 }), Err(AlarmKind::from(S::TooManySymbols)));
    }
}

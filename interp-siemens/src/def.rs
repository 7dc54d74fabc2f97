//! `DEF` statements and `PROC` parameter lists: variables of a program level.
//!
//! `DEF REAL RTP=155, RFP=150, SDIS=1, DP` (seed 001 line 1936) defines every
//! name with its initial value (zero without one), all or none: the initial
//! values are evaluated first (they may use variables defined before), then the
//! names are defined. `PROC ZYKL1 (REAL PAR1)` (line 1416) gives a subprogram's
//! parameters, defined in the called level with the caller's arguments.

use crate::expr::eval;
use crate::lex::{Src, syntax, which};
use crate::read::Scope;
use interp_core::alarm::{AlarmKind, SiemensAlarm as S};
use interp_core::config::MachineConfig;
use interp_core::lang::siemens::call::{Arg, CallArgs, MAX_ARGS, Ty};
use interp_core::lang::siemens::vars::{MAX_STRING, Value, VarTy, Vars, convert_to};
use interp_core::modal::State;

/// Most names one DEF may define (the CYCLE83 example defines 14).
pub const MAX_DEF_NAMES: usize = 24;

/// Reads a type: `REAL`, `INT`, `BOOL`, `CHAR`, `STRING[n]`.
fn var_type(src: &mut Src<'_>) -> Result<VarTy, AlarmKind> {
    let t = src.name();
    Ok(match which(t, &[b"REAL", b"INT", b"BOOL", b"CHAR", b"STRING", b"AXIS", b"FRAME"]) {
        Some(0) => VarTy::Real,
        Some(1) => VarTy::Int,
        Some(2) => VarTy::Bool,
        Some(3) => VarTy::Char,
        Some(4) => {
            src.expect(b'[', "STRING needs its length: STRING[n]")?;
            let n = src.number()?;
            src.expect(b']', "']' missing")?;
            let cap =
                n.as_integer().filter(|c| (1..=MAX_STRING as i64).contains(c)).ok_or(AlarmKind::from(S::ValueRange))?;
            VarTy::Str { cap: cap as u8 }
        }
        Some(_) => return Err(AlarmKind::NotSupportedYet { what: "AXIS and FRAME variables" }),
        None if t.is_empty() => return Err(syntax("type expected (REAL, INT, BOOL, CHAR, STRING[n])")),
        None => return Err(syntax("unknown type (REAL, INT, BOOL, CHAR, STRING[n])")),
    })
}

/// A value owned by the DEF being carried out (strings in its buffer).
#[derive(Clone, Copy)]
enum Init {
    Zero,
    Scalar(Value<'static>),
    Str { at: usize, len: usize },
}

/// Carries out `DEF` with `body` (the text after the keyword) in the current
/// level of `vars`, evaluating initial values against the variables, `state` and
/// `cfg` as they are. A name the level has with the same type (the DEF run again
/// after a jump back) gets its initial value again; with another type it is alarm
/// 12170.
pub fn define(body: &[u8], vars: &mut Vars, state: &State, cfg: &MachineConfig) -> Result<(), AlarmKind> {
    let env = Scope { vars: &*vars, state, cfg };
    let env = &env;
    let mut src = Src::new(body);
    let ty = var_type(&mut src)?;
    let mut names: heapless::Vec<(&[u8], Init), MAX_DEF_NAMES> = heapless::Vec::new();
    let mut text: heapless::Vec<u8, MAX_STRING> = heapless::Vec::new();
    loop {
        if !src.at_name() {
            return Err(syntax("variable name expected"));
        }
        let name = src.name();
        if name.first() == Some(&b'$') || crate::expr::r_number(name).is_some() || name.len() < 2 {
            return Err(syntax("not a name for a variable"));
        }
        if src.peek() == Some(b'[') {
            return Err(AlarmKind::NotSupportedYet { what: "array variables" });
        }
        let init = if src.eat(b'=') {
            match convert_to(ty, eval(&mut src, env)?)? {
                Value::Str(s) => {
                    let at = text.len();
                    text.extend_from_slice(s).map_err(|_| S::StringTooLong)?;
                    Init::Str { at, len: s.len() }
                }
                Value::Real(x) => Init::Scalar(Value::Real(x)),
                Value::Int(x) => Init::Scalar(Value::Int(x)),
                Value::Bool(x) => Init::Scalar(Value::Bool(x)),
                Value::Char(x) => Init::Scalar(Value::Char(x)),
            }
        } else {
            Init::Zero
        };
        names.push((name, init)).map_err(|_| S::TooManySymbols)?;
        if !src.eat(b',') {
            break;
        }
    }
    if !src.done() {
        return Err(syntax("',' or the end of the DEF expected"));
    }
    let mark = vars.mark();
    for &(name, init) in &names {
        let r = define_one(vars, name, ty, init, &text);
        if r.is_err() {
            vars.undo_to(mark);
            return r;
        }
    }
    Ok(())
}

fn define_one(vars: &mut Vars, name: &[u8], ty: VarTy, init: Init, text: &[u8]) -> Result<(), AlarmKind> {
    match vars.type_of(name) {
        Some(t) if t == ty => {}
        Some(_) => return Err(S::NameDefinedTwice.into()),
        None => vars.define(name, ty)?,
    }
    let v = match init {
        Init::Zero => match ty {
            VarTy::Str { .. } => Value::Str(b""),
            _ => Value::Int(0),
        },
        Init::Scalar(v) => v,
        Init::Str { at, len } => Value::Str(text.get(at..at + len).unwrap_or(&[])),
    };
    vars.set(name, v)
}

/// One parameter of a PROC.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Param<'t> {
    /// Its name.
    pub name: &'t [u8],
    /// Its type.
    pub ty: VarTy,
}

/// A PROC statement: its parameters and whether it SAVEs the modal state.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Proc<'t> {
    /// The parameters in order.
    pub params: heapless::Vec<Param<'t>, MAX_ARGS>,
    /// `SAVE`: the modal G functions in force at the call come back at the return.
    pub save: bool,
}

/// Reads a PROC statement's text after `PROC`: `NAME [(TYPE NAME, …)] [SAVE]
/// [DISPLOF]`. VAR parameters (call by reference) are not supported.
pub fn proc_params(body: &[u8]) -> Result<Proc<'_>, AlarmKind> {
    let mut src = Src::new(crate::lex::strip_comment(body));
    src.name();
    let mut p = Proc { params: heapless::Vec::new(), save: false };
    if src.eat(b'(') && !src.eat(b')') {
        loop {
            if src.keyword(b"VAR") {
                return Err(AlarmKind::NotSupportedYet { what: "VAR parameters (call by reference)" });
            }
            let ty = var_type(&mut src)?;
            let name = src.name();
            if name.is_empty() {
                return Err(syntax("parameter name expected"));
            }
            if src.peek() == Some(b'[') {
                return Err(AlarmKind::NotSupportedYet { what: "array parameters" });
            }
            p.params.push(Param { name, ty }).map_err(|_| S::TooManyParameters)?;
            if src.eat(b',') {
                continue;
            }
            src.expect(b')', "',' or ')' expected in the PROC's parameters")?;
            break;
        }
    }
    loop {
        if src.keyword(b"SAVE") {
            p.save = true;
        } else if !src.keyword(b"DISPLOF") && !src.keyword(b"DISPLON") && !src.keyword(b"SBLOF") {
            break;
        }
    }
    if !src.done() {
        return Err(syntax("text after the PROC statement"));
    }
    Ok(p)
}

impl Proc<'_> {
    /// The parameter types for binding arguments ([`CallArgs::bind`]).
    pub fn types(&self) -> impl ExactSizeIterator<Item = Ty> + '_ {
        self.params.iter().map(|p| match p.ty {
            VarTy::Real => Ty::Real,
            VarTy::Int | VarTy::Bool => Ty::Int,
            VarTy::Char => Ty::Char,
            VarTy::Str { .. } => Ty::Str,
        })
    }

    /// Defines the parameters in the current (new) level of `vars` with the bound
    /// arguments `args` (a left-out one is zero or empty).
    pub fn define_params(&self, vars: &mut Vars, args: &CallArgs) -> Result<(), AlarmKind> {
        for (i, p) in self.params.iter().enumerate() {
            vars.define(p.name, p.ty)?;
            let v = match args.get(i) {
                Arg::Empty => match p.ty {
                    VarTy::Str { .. } => Value::Str(b""),
                    _ => Value::Int(0),
                },
                Arg::Real(x) => Value::Real(x),
                Arg::Int(n) => Value::Int(n),
                Arg::Str(s) => {
                    if p.ty == VarTy::Char {
                        Value::Char(s.first().copied().unwrap_or(0))
                    } else {
                        Value::Str(s)
                    }
                }
            };
            vars.set(p.name, v)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn def(vars: &mut Vars, body: &str) -> Result<(), AlarmKind> {
        let cfg = MachineConfig::default();
        let st = State::power_on(&cfg, interp_core::axis::Pos::ZERO);
        define(body.as_bytes(), vars, &st, &cfg)
    }

    #[test]
    fn def_lists_with_and_without_values() {
        let mut v = Vars::new();
        // CYCLE83's example (lines 1936-1939), one block.
        def(
            &mut v,
            " REAL RTP=155, RFP=150, SDIS=1, DP=5, DPR=145, FDEP=100, FDPR=50, DAM=20, DTB=1, FRF=1, VARI=0, _VRT=0.8, _MDEP=10, _DIS1=0.4",
        )
        .unwrap();
        assert_eq!(v.get(b"RFP"), Some(Value::Real(150.0)));
        assert_eq!(v.get(b"_DIS1"), Some(Value::Real(0.4)));
        def(&mut v, " INT ZAEHL=1").unwrap();
        def(&mut v, " STRING[8] UPNAME").unwrap();
        assert_eq!(v.get(b"UPNAME"), Some(Value::Str(b"")));
        def(&mut v, " CHAR FORM=\"E\"").unwrap();
        assert_eq!(v.get(b"FORM"), Some(Value::Char(b'E')));
        def(&mut v, " REAL MID=RFP/10, FFR").unwrap();
        assert_eq!((v.get(b"MID"), v.get(b"FFR")), (Some(Value::Real(15.0)), Some(Value::Real(0.0))));
        // Run again after a jump back: the values come back.
        v.set(b"ZAEHL", Value::Int(5)).unwrap();
        def(&mut v, " INT ZAEHL=1").unwrap();
        assert_eq!(v.get(b"ZAEHL"), Some(Value::Int(1)));
        assert_eq!(def(&mut v, " REAL ZAEHL"), Err(S::NameDefinedTwice.into()));
        // All or nothing.
        assert_eq!(def(&mut v, " REAL NEW1, NEW2=\"x\""), Err(S::TypeMismatch.into()));
        assert!(!v.is_defined(b"NEW1"));
        assert_eq!(def(&mut v, " REAL A1 B"), Err(syntax("',' or the end of the DEF expected")));
        assert_eq!(def(&mut v, " FLOAT X"), Err(syntax("unknown type (REAL, INT, BOOL, CHAR, STRING[n])")));
        assert_eq!(def(&mut v, " REAL R1"), Err(syntax("not a name for a variable")));
    }

    #[test]
    fn proc_parameter_lists() {
        let p = proc_params(b" ZYKL1 (REAL PAR1)").unwrap();
        assert_eq!(p.params.as_slice(), &[Param { name: b"PAR1", ty: VarTy::Real }]);
        let p = proc_params(b" CYCLE100(CHAR FORM, REAL MID, REAL FFR, INT VARI, REAL FAL) SAVE DISPLOF").unwrap();
        assert_eq!(p.params.len(), 5);
        assert!(p.save);
        assert!(proc_params(b" KONTUR_1 ; contour").unwrap().params.is_empty());
        assert_eq!(
            proc_params(b" CYC_832T(INT _ASVS,VAR INT _FACTOR)"),
            Err(AlarmKind::NotSupportedYet { what: "VAR parameters (call by reference)" })
        );
        let mut args = CallArgs::new();
        args.push(Arg::Str(b"E")).unwrap();
        args.push(Arg::Real(3.5)).unwrap();
        let p = proc_params(b" CYCLE100(CHAR FORM, REAL MID, REAL FFR)").unwrap();
        args.bind(p.types()).unwrap();
        let mut v = Vars::new();
        v.enter();
        p.define_params(&mut v, &args).unwrap();
        assert_eq!(v.get(b"FORM"), Some(Value::Char(b'E')));
        assert_eq!(v.get(b"MID"), Some(Value::Real(3.5)));
        assert_eq!(v.get(b"FFR"), Some(Value::Real(0.0)));
    }
}

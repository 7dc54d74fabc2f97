//! Reading one SINUMERIK line into what it asks for: NC words ([`Words`]) with
//! the assignments written among them ([`Pending`]), or a statement ([`Stmt`]):
//! DEF, IF…GOTO, GOTOF/GOTOB, REPEAT, a subprogram or cycle call with its
//! arguments, MCALL, PROC, RET.
//!
//! A line is `[/n] [N…] [LABEL:] items`. Expressions are evaluated as the line is
//! read, left to right, against the variables as they stand plus the assignments
//! made earlier in the same line (`N10 G0 FFR=300 RFF=1.5*FFR`, seed 001 line
//! 2607); the assignments themselves wait in [`Pending`] until the block has
//! succeeded, so a block that raises an alarm changes no variable.
//!
//! Words: `G1`, `M3`, `X40.824`, `X=expr`, `X=AC(expr)`, `Z=IC(expr)`, `F0.2`,
//! `S500`, `T1`, `D1`, `I…`/`K…`, and the named ones `CR=`, `RND=`, `CHF=`,
//! `CHR=`, `ANG=`, `LIMS=`, `SPOS=`; `DIAMON`/`DIAMOF`/`DIAM90`. A single letter
//! is always an address (SINUMERIK names begin with two letters or `_`).

use super::expr::{self, Env, MAX_INDICES, eval, r_number, whole};
use super::lex::{Src, is, strip_comment, syntax, which};
use interp_core::alarm::{AlarmKind, SiemensAlarm as S};
use interp_core::config::MachineConfig;
use interp_core::lang::siemens::call::{Arg, CallArgs};
use interp_core::lang::siemens::vars::{MAX_STRING, Value, VarTy, Vars, convert_to};
use interp_core::modal::State;
use interp_core::units::Number;

/// Most G functions in one block.
pub const MAX_G: usize = 10;
/// Most M functions in one block (the 840D's 5; the engine executes 3).
pub const MAX_M: usize = 5;
/// Most assignments in one block.
pub const MAX_ASSIGN: usize = 10;
/// Bytes of strings the assignments of one block may hold.
const PENDING_TEXT: usize = MAX_STRING;

/// The address words of a block, one slot each.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum Addr {
    /// X.
    X,
    /// Y.
    Y,
    /// Z.
    Z,
    /// C.
    C,
    /// A (a rotary axis this controller does not have).
    A,
    /// B.
    B,
    /// I (arc centre, X).
    I,
    /// J (arc centre, Y).
    J,
    /// K (arc centre, Z; thread lead of G33).
    K,
    /// F.
    F,
    /// S.
    S,
    /// T.
    T,
    /// D.
    D,
    /// H (auxiliary function).
    H,
    /// `CR=`: arc radius.
    Cr,
    /// `RND=`: rounding to the next block.
    Rnd,
    /// `CHF=`: chamfer, its length.
    Chf,
    /// `CHR=`: chamfer, its leg.
    Chr,
    /// `ANG=`: angle of a line.
    Ang,
    /// `LIMS=`: spindle speed limit under G96.
    Lims,
    /// `SPOS=`: spindle positioning.
    Spos,
}

/// Most address words in one block.
pub const MAX_WORDS: usize = 12;

impl Addr {
    /// The single-letter address `c` (uppercase).
    fn of_letter(c: u8) -> Option<Addr> {
        Some(match c {
            b'X' => Addr::X,
            b'Y' => Addr::Y,
            b'Z' => Addr::Z,
            b'C' => Addr::C,
            b'A' => Addr::A,
            b'B' => Addr::B,
            b'I' => Addr::I,
            b'J' => Addr::J,
            b'K' => Addr::K,
            b'F' => Addr::F,
            b'S' => Addr::S,
            b'T' => Addr::T,
            b'D' => Addr::D,
            b'H' => Addr::H,
            _ => return None,
        })
    }

    /// A named address `NAME=`.
    fn of_name(n: &[u8]) -> Option<Addr> {
        const NAMED: [Addr; 7] = [Addr::Cr, Addr::Rnd, Addr::Chf, Addr::Chr, Addr::Ang, Addr::Lims, Addr::Spos];
        which(n, &[b"CR", b"RND", b"CHF", b"CHR", b"ANG", b"LIMS", b"SPOS"]).map(|k| NAMED[k])
    }

    /// The letter or name, for messages.
    pub const fn letter(self) -> u8 {
        [
            b'X', b'Y', b'Z', b'C', b'A', b'B', b'I', b'J', b'K', b'F', b'S', b'T', b'D', b'H', b'R', b'R', b'C', b'C',
            b'A', b'L', b'S',
        ][self as usize]
    }

    const fn bit(self) -> u32 {
        1 << self as u32
    }
}

/// A jump's direction: GOTOF forward, GOTOB backward, GOTO/GOTOC forward then
/// backward (GOTOC without an alarm when the label is missing).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dir {
    /// GOTOF.
    Forward,
    /// GOTOB.
    Backward,
    /// GOTO.
    Both,
    /// GOTOC.
    BothQuiet,
}

/// A jump to a label (or a block number `N100`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Jump<'t> {
    /// Which way the label is searched.
    pub dir: Dir,
    /// The label, as written.
    pub label: &'t [u8],
}

/// The NC words of one block (cheap to make: nothing is cleared but lengths).
#[derive(Clone, Debug, PartialEq)]
pub struct Words {
    /// 1-based source line.
    pub line: u32,
    /// Block number `N`.
    pub seq: Option<u32>,
    /// G functions, in order.
    pub g: heapless::Vec<u16, MAX_G>,
    /// M functions, in order.
    pub m: heapless::Vec<u16, MAX_M>,
    present: u32,
    /// Given as `=AC(…)`.
    ac: u32,
    /// Given as `=IC(…)`.
    ic: u32,
    values: heapless::Vec<(Addr, Number), MAX_WORDS>,
    /// DIAMON (`Some(true)`), DIAMOF (`Some(false)`); DIAM90 counts as DIAMON.
    pub diam: Option<bool>,
}

impl Default for Words {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl Words {
    /// No words.
    pub const EMPTY: Words = Words {
        line: 0,
        seq: None,
        g: heapless::Vec::new(),
        m: heapless::Vec::new(),
        present: 0,
        ac: 0,
        ic: 0,
        values: heapless::Vec::new(),
        diam: None,
    };

    /// Empties the words for the block on `line`.
    #[inline]
    pub fn clear(&mut self, line: u32) {
        self.line = line;
        self.seq = None;
        self.g.clear();
        self.m.clear();
        self.present = 0;
        self.ac = 0;
        self.ic = 0;
        self.values.clear();
        self.diam = None;
    }

    /// The value of `a`, if given.
    #[inline]
    pub fn get(&self, a: Addr) -> Option<Number> {
        if self.present & a.bit() == 0 {
            return None;
        }
        self.values.iter().find(|(b, _)| *b == a).map(|&(_, n)| n)
    }

    /// Whether `a` was written `=AC(…)` (`Some(false)`) or `=IC(…)` (`Some(true)`).
    #[inline]
    pub fn explicit(&self, a: Addr) -> Option<bool> {
        if self.ic & a.bit() != 0 {
            Some(true)
        } else if self.ac & a.bit() != 0 {
            Some(false)
        } else {
            None
        }
    }

    /// Whether any address word was given.
    pub fn any(&self, mask: u32) -> bool {
        self.present & mask != 0
    }

    /// Whether the block has no word at all.
    pub fn is_empty(&self) -> bool {
        self.g.is_empty() && self.m.is_empty() && self.present == 0 && self.diam.is_none()
    }

    fn set(&mut self, a: Addr, n: Number) -> Result<(), AlarmKind> {
        if self.present & a.bit() != 0 {
            return Err(match a {
                Addr::X | Addr::Y | Addr::Z | Addr::C | Addr::A | Addr::B => {
                    S::AxisProgrammedTwice { letter: a.letter() }.into()
                }
                _ => AlarmKind::DuplicateAddress { letter: a.letter() },
            });
        }
        self.present |= a.bit();
        self.values.push((a, n)).map_err(|_| syntax("more than 12 address words in one block"))
    }
}

/// Masks of [`Addr`] groups.
pub mod mask {
    use super::Addr;
    /// The axes.
    pub const AXES: u32 = Addr::X.bit() | Addr::Y.bit() | Addr::Z.bit() | Addr::C.bit() | Addr::A.bit() | Addr::B.bit();
    /// Arc centre words.
    pub const CENTRE: u32 = Addr::I.bit() | Addr::J.bit() | Addr::K.bit();
}

/// What an assignment writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target<'t> {
    /// R parameter.
    R(i64),
    /// A DEF variable of the current level.
    Var(&'t [u8]),
    /// Cycle setting datum `_ZSD[i]`.
    Zsd(usize),
    /// Tool data `$TC_DPn[t,d]`: offset row and which datum.
    Tool {
        /// Offset row (T t D d: t + (d−1) × tool count).
        row: u16,
        /// The `n` of `$TC_DPn`.
        param: u8,
    },
}

/// A value an assignment stores, owning nothing (strings are in [`Pending`]).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Stored {
    Real(f64),
    Int(i64),
    Bool(bool),
    Char(u8),
    Str { at: u8, len: u8 },
}

/// The assignments of a block, in order, until the block has succeeded.
#[derive(Debug, Default)]
pub struct Pending<'t> {
    items: heapless::Vec<(Target<'t>, Stored), MAX_ASSIGN>,
    text: heapless::Vec<u8, PENDING_TEXT>,
}

impl<'t> Pending<'t> {
    /// No assignments.
    pub const fn new() -> Self {
        Pending { items: heapless::Vec::new(), text: heapless::Vec::new() }
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    fn value(&self, s: Stored) -> Value<'_> {
        match s {
            Stored::Real(v) => Value::Real(v),
            Stored::Int(v) => Value::Int(v),
            Stored::Bool(v) => Value::Bool(v),
            Stored::Char(v) => Value::Char(v),
            Stored::Str { at, len } => {
                let (at, len) = (usize::from(at), usize::from(len));
                Value::Str(self.text.get(at..at + len).unwrap_or(&[]))
            }
        }
    }

    /// The last value assigned to `t` in this block.
    fn latest(&self, t: &Target<'_>) -> Option<Value<'_>> {
        let same = |x: &Target<'_>| match (x, t) {
            (Target::Var(a), Target::Var(b)) => a.eq_ignore_ascii_case(b),
            (a, b) => a == b,
        };
        self.items.iter().rev().find(|(x, _)| same(x)).map(|&(_, s)| self.value(s))
    }

    fn push(&mut self, t: Target<'t>, v: Value<'_>) -> Result<(), AlarmKind> {
        let stored = match v {
            Value::Real(x) => Stored::Real(x),
            Value::Int(x) => Stored::Int(x),
            Value::Bool(x) => Stored::Bool(x),
            Value::Char(x) => Stored::Char(x),
            Value::Str(s) => {
                let at = self.text.len();
                self.text.extend_from_slice(s).map_err(|_| S::StringTooLong)?;
                Stored::Str { at: at as u8, len: s.len() as u8 }
            }
        };
        self.items.push((t, stored)).map_err(|_| syntax("more than 10 assignments in one block"))
    }

    /// Every assignment in order, with its value.
    pub fn each(&self) -> impl Iterator<Item = (Target<'t>, Value<'_>)> + '_ {
        self.items.iter().map(|&(t, s)| (t, self.value(s)))
    }
}

/// What a line asks for besides its NC words.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stmt<'t> {
    /// NC words and assignments (either may be empty: a label alone, a comment).
    Nc {
        /// A GOTOF/GOTOB/GOTO written after the words.
        jump: Option<Jump<'t>>,
    },
    /// `DEF type name[=value], …`: the text after `DEF`.
    Def(&'t [u8]),
    /// `IF cond GOTOx label`, the condition evaluated.
    If {
        /// The condition held.
        holds: bool,
        /// The jump.
        jump: Jump<'t>,
    },
    /// `GOTOF`/`GOTOB`/`GOTO`/`GOTOC label`.
    Goto(Jump<'t>),
    /// `REPEAT start [end] [P=n]`, `REPEATB label [P=n]`.
    Repeat {
        /// Start label.
        start: &'t [u8],
        /// End label (`None`: up to ENDLABEL, or the block before the REPEAT).
        end: Option<&'t [u8]>,
        /// How often (P, 1 when omitted).
        count: u32,
        /// REPEATB: only the labelled block.
        single: bool,
    },
    /// A subprogram or cycle call `NAME`, `NAME(args…)` (arguments in the call
    /// arguments given to [`read`]), run `passes` times (`P`).
    Call {
        /// The name.
        name: &'t [u8],
        /// Whether a parameter list `(…)` was written.
        list: bool,
        /// Number of passes.
        passes: u32,
    },
    /// `MCALL name(args…)` (arguments read), or `MCALL` alone (`None`): cancel.
    MCall {
        /// The called name.
        name: Option<&'t [u8]>,
        /// Whether a parameter list was written.
        list: bool,
    },
    /// `PROC name(params…)`: the text after `PROC`.
    Proc(&'t [u8]),
    /// `RET`.
    Ret,
}

/// What expressions are evaluated against: the variables, the state (`_ZSD`)
/// and the machine (tool data).
#[derive(Clone, Copy)]
pub struct Scope<'x> {
    /// R parameters and DEF variables.
    pub vars: &'x Vars,
    /// The modal state (cycle setting data).
    pub state: &'x State,
    /// The machine (tool offsets, tool count).
    pub cfg: &'x MachineConfig,
}

impl Env for Scope<'_> {
    fn var(&self, name: &[u8]) -> Option<Value<'_>> {
        self.vars.get(name)
    }

    fn r(&self, n: i64) -> Result<f64, AlarmKind> {
        self.vars.r(n)
    }

    fn indexed(&self, name: &[u8], idx: &[i64]) -> Result<Value<'_>, AlarmKind> {
        View { scope: self, pending: &Pending::new() }.indexed(name, idx).map(|v| match v {
            Value::Str(_) => Value::Int(0),
            Value::Real(x) => Value::Real(x),
            Value::Int(x) => Value::Int(x),
            Value::Bool(x) => Value::Bool(x),
            Value::Char(x) => Value::Char(x),
        })
    }
}

/// The scope seen through the block's own assignments.
struct View<'a, 'x, 't> {
    scope: &'a Scope<'x>,
    pending: &'a Pending<'t>,
}

impl Env for View<'_, '_, '_> {
    fn var(&self, name: &[u8]) -> Option<Value<'_>> {
        self.pending.latest(&Target::Var(name)).or_else(|| self.scope.vars.get(name))
    }

    fn r(&self, n: i64) -> Result<f64, AlarmKind> {
        if let Some(v) = self.pending.latest(&Target::R(n)) {
            return expr::num(&v);
        }
        self.scope.vars.r(n)
    }

    fn indexed(&self, name: &[u8], idx: &[i64]) -> Result<Value<'_>, AlarmKind> {
        let t = indexed_target(name, idx, self.scope.cfg)?;
        if let Some(v) = self.pending.latest(&t) {
            return Ok(v);
        }
        Ok(match t {
            Target::Zsd(i) => Value::Real(f64::from(self.scope.state.cycle.zsd[i])),
            Target::Tool { row, param } => Value::Real(tool_datum(self.scope.cfg, row, param)?),
            _ => return Err(S::NameNotDefined.into()),
        })
    }
}

/// The target of `name[idx…]` (`_ZSD[i]`, `$TC_DPn[t,d]`).
fn indexed_target(name: &[u8], idx: &[i64], cfg: &MachineConfig) -> Result<Target<'static>, AlarmKind> {
    let range = || AlarmKind::from(S::IndexOutOfRange);
    if is(name, b"_ZSD") {
        let [i] = idx else { return Err(range()) };
        let i = usize::try_from(*i).ok().filter(|&i| i < 8).ok_or_else(range)?;
        return Ok(Target::Zsd(i));
    }
    if let Some(n) = name.get(..6).filter(|p| is(p, b"$TC_DP")).and(name.get(6..)) {
        let param =
            n.iter().try_fold(0u8, |a, &d| d.is_ascii_digit().then(|| a.saturating_mul(10).saturating_add(d - b'0')));
        let param = param.filter(|p| matches!(p, 1..=25)).ok_or(AlarmKind::from(S::NameNotDefined))?;
        let [t, d] = idx else { return Err(range()) };
        let row = tool_row(cfg, *t, *d).ok_or_else(range)?;
        return Ok(Target::Tool { row, param });
    }
    if name.first() == Some(&b'$') {
        return Err(AlarmKind::NotSupportedYet { what: "this system variable" });
    }
    Err(S::NameNotDefined.into())
}

/// The offset row of tool `t` cutting edge `d`: `t + (d − 1) × tool count`
/// (edges 1 of every tool first, then edges 2 …); `None` outside the table.
pub fn tool_row(cfg: &MachineConfig, t: i64, d: i64) -> Option<u16> {
    let count = i64::from(cfg.tool_count);
    if !(1..=count).contains(&t) || d < 1 {
        return None;
    }
    let row = t.checked_add((d - 1).checked_mul(count)?)?;
    (row <= interp_core::config::MAX_OFFSETS as i64).then_some(row as u16)
}

/// `$TC_DPn` of offset row `row`, in program units (mm): 2 edge position (tip
/// direction), 3 length 1 (X), 4 length 2 (Z), 6 radius, 12/13 wear of the
/// lengths; 1 (tool type) and 24 (clearance angle) read as 0, the others too.
fn tool_datum(cfg: &MachineConfig, row: u16, param: u8) -> Result<f64, AlarmKind> {
    let o = cfg.tools.get(row).ok_or(AlarmKind::from(S::IndexOutOfRange))?;
    let mm = |nm: i64| nm as f64 / 1e6;
    Ok(match param {
        2 => f64::from(o.tip),
        3 => mm(o.x),
        4 => mm(o.z),
        6 => mm(o.radius),
        12 => mm(o.x_wear),
        13 => mm(o.z_wear),
        _ => 0.0,
    })
}

/// Reads line `text` (without its LF) of source line `line`: the NC words go to
/// `words`, the assignments to `pending`, call arguments to `args`.
pub fn read<'t>(
    text: &'t [u8],
    line: u32,
    scope: &Scope<'_>,
    words: &mut Words,
    pending: &mut Pending<'t>,
    args: &mut CallArgs,
) -> Result<Stmt<'t>, AlarmKind> {
    words.clear(line);
    let mut src = Src::new(strip_comment(text));
    // A skip mark was looked at by the driver before reading.
    if src.eat(b'/') && src.at(0).is_some_and(|c| c.is_ascii_digit()) {
        src.i += 1;
    }
    if matches!(src.peek(), Some(b'N' | b'n' | b':')) && src.at(1).is_some_and(|c| c.is_ascii_digit()) {
        src.i += 1;
        let n = src.number()?;
        words.seq = Some(u32::try_from(n.mantissa).map_err(|_| AlarmKind::from(S::ValueRange))?);
    }
    skip_label(&mut src);
    let mut r = Reader { src, scope, pending, words };
    r.statement(args)
}

/// Passes a label `NAME:` at the start of the statement.
pub fn skip_label(src: &mut Src<'_>) -> Option<usize> {
    let save = src.i;
    if src.at_name() {
        let n = src.name();
        if src.at(0) == Some(b':') && !n.is_empty() && n.first() != Some(&b'$') {
            src.i += 1;
            return Some(save);
        }
    }
    src.i = save;
    None
}

struct Reader<'r, 't, 'x> {
    src: Src<'t>,
    scope: &'r Scope<'x>,
    pending: &'r mut Pending<'t>,
    words: &'r mut Words,
}

impl<'t> Reader<'_, 't, '_> {
    fn statement(&mut self, args: &mut CallArgs) -> Result<Stmt<'t>, AlarmKind> {
        if self.src.at_name() {
            let save = self.src.i;
            let name = self.src.name();
            // Statements that take the whole line.
            // DEF, PROC, IF, RET, REPEAT, REPEATB, MCALL, MSG.
            let stmt = match which(name, &STATEMENTS) {
                Some(0) => Some(Stmt::Def(self.src.rest())),
                Some(1) => Some(Stmt::Proc(self.src.rest())),
                Some(2) => Some(self.if_goto()?),
                Some(3) => Some(Stmt::Ret),
                Some(k @ (4 | 5)) => Some(self.repeat(k == 5)?),
                Some(6) => Some(self.mcall(args)?),
                Some(_) => {
                    // MSG: a message for the operator: nothing to do on this board.
                    self.skip_parenthesised()?;
                    Some(Stmt::Nc { jump: None })
                }
                None => {
                    if let Some(dir) = goto_dir(name) {
                        Some(Stmt::Goto(self.jump_target(dir)?))
                    } else if unsupported(name) {
                        return Err(AlarmKind::NotSupportedYet { what: "this control structure (only IF…GOTO)" });
                    } else {
                        None
                    }
                }
            };
            if let Some(s) = stmt {
                return self.end(s);
            }
            self.src.i = save;
        }
        self.items(args)
    }

    /// Nothing may follow a statement.
    fn end(&mut self, s: Stmt<'t>) -> Result<Stmt<'t>, AlarmKind> {
        if matches!(s, Stmt::Def(_) | Stmt::Proc(_)) || self.src.done() {
            Ok(s)
        } else {
            Err(syntax("text after the statement"))
        }
    }

    fn skip_parenthesised(&mut self) -> Result<(), AlarmKind> {
        self.src.expect(b'(', "'(' expected")?;
        let mut depth = 1u32;
        let mut quoted = false;
        while let Some(&c) = self.src.t.get(self.src.i) {
            self.src.i += 1;
            match c {
                b'"' if crate::lex::quote_at(self.src.t, self.src.i - 1) => quoted = !quoted,
                b'(' if !quoted => depth += 1,
                b')' if !quoted => {
                    depth -= 1;
                    if depth == 0 {
                        return Ok(());
                    }
                }
                _ => {}
            }
        }
        Err(syntax("')' missing"))
    }

    fn jump_target(&mut self, dir: Dir) -> Result<Jump<'t>, AlarmKind> {
        let label = if self.src.at_name() {
            self.src.name()
        } else {
            // A block number: GOTOF N100 is written with the N; bare digits too.
            let s = self.src.i;
            while self.src.at(0).is_some_and(|c| c.is_ascii_digit()) {
                self.src.i += 1;
            }
            &self.src.t[s..self.src.i]
        };
        if label.is_empty() {
            return Err(syntax("jump without a label"));
        }
        Ok(Jump { dir, label })
    }

    fn if_goto(&mut self) -> Result<Stmt<'t>, AlarmKind> {
        let v = {
            let view = View { scope: self.scope, pending: self.pending };
            expr::truth(&eval(&mut self.src, &view)?)?
        };
        let kw = self.src.name();
        let dir = goto_dir(kw).ok_or(AlarmKind::NotSupportedYet { what: "IF without GOTO (IF…ENDIF)" })?;
        let jump = self.jump_target(dir)?;
        Ok(Stmt::If { holds: v, jump })
    }

    fn repeat(&mut self, single: bool) -> Result<Stmt<'t>, AlarmKind> {
        if !self.src.at_name() {
            return Err(syntax("REPEAT without a label"));
        }
        let start = self.src.name();
        let mut end = None;
        if !single && self.src.at_name() && !self.at_p() {
            end = Some(self.src.name());
        }
        let count = self.passes()?;
        Ok(Stmt::Repeat { start, end, count, single })
    }

    /// Whether `P` (a number of passes) comes next.
    fn at_p(&mut self) -> bool {
        matches!(self.src.peek(), Some(b'P' | b'p'))
            && self.src.at(1).is_some_and(|c| c.is_ascii_digit() || c == b'=' || c == b' ')
    }

    /// `P=n` / `Pn`: 1 when not given; 1–9999 (alarm 12160 beyond).
    fn passes(&mut self) -> Result<u32, AlarmKind> {
        if !self.at_p() {
            return Ok(1);
        }
        self.src.i += 1;
        let v = if self.src.eat(b'=') {
            let view = View { scope: self.scope, pending: self.pending };
            whole(&eval(&mut self.src, &view)?)?
        } else {
            let n = self.src.number()?;
            n.as_integer().ok_or(AlarmKind::from(S::ValueRange))?
        };
        u32::try_from(v).ok().filter(|n| (1..=9999).contains(n)).ok_or(S::ValueRange.into())
    }

    fn mcall(&mut self, args: &mut CallArgs) -> Result<Stmt<'t>, AlarmKind> {
        if self.src.done() {
            return Ok(Stmt::MCall { name: None, list: false });
        }
        if !self.src.at_name() {
            return Err(syntax("MCALL without a subprogram name"));
        }
        let name = self.src.name();
        let list = self.args(args)?;
        Ok(Stmt::MCall { name: Some(name), list })
    }

    /// A parameter list `(a, , "s", expr)` into `args`, if one follows.
    fn args(&mut self, args: &mut CallArgs) -> Result<bool, AlarmKind> {
        args.clear();
        if !self.src.eat(b'(') {
            return Ok(false);
        }
        if self.src.eat(b')') {
            return Ok(true);
        }
        loop {
            match self.src.peek() {
                Some(b',' | b')') => args.push(Arg::Empty)?,
                _ => {
                    let view = View { scope: self.scope, pending: self.pending };
                    let one;
                    args.push(match eval(&mut self.src, &view)? {
                        Value::Real(v) => Arg::Real(v),
                        Value::Int(v) => Arg::Int(v),
                        Value::Bool(b) => Arg::Int(i64::from(b)),
                        Value::Char(c) => {
                            one = [c];
                            Arg::Str(&one)
                        }
                        Value::Str(s) => Arg::Str(s),
                    })?;
                }
            }
            if !self.list_next()? {
                return Ok(true);
            }
        }
    }

    /// After an argument: `,` (true: another follows) or `)` (false).
    fn list_next(&mut self) -> Result<bool, AlarmKind> {
        if self.src.eat(b',') {
            return Ok(true);
        }
        self.src.expect(b')', "',' or ')' expected in the parameter list")?;
        Ok(false)
    }

    /// The NC items of the line, or a call.
    fn items(&mut self, args: &mut CallArgs) -> Result<Stmt<'t>, AlarmKind> {
        loop {
            let Some(c) = self.src.peek() else { return Ok(Stmt::Nc { jump: None }) };
            let up = c.to_ascii_uppercase();
            let next = self.src.at(1);
            let digit_next = next.is_some_and(|d| d.is_ascii_digit() || d == b'.');
            // Address + number: the common case (G1 X40.824 Z-0.1).
            if up.is_ascii_alphabetic() && up != b'R' && (digit_next || matches!(next, Some(b'-' | b'+'))) {
                self.address_word(up)?;
                continue;
            }
            if !self.src.at_name() {
                return Err(syntax("unexpected character"));
            }
            let save = self.src.i;
            let name = self.src.name();
            if let Some(dir) = goto_dir(name) {
                let jump = self.jump_target(dir)?;
                return self.end(Stmt::Nc { jump: Some(jump) });
            }
            if name.len() == 1 {
                // `X=…`, `F=…`; a lone letter is no word.
                if self.src.eat(b'=') {
                    self.address_expr(name[0].to_ascii_uppercase())?;
                    continue;
                }
                return Err(S::NameNotDefined.into());
            }
            if is(name, b"DIAMON") || is(name, b"DIAM90") || is(name, b"DIAMOF") {
                if self.words.diam.is_some() {
                    return Err(syntax("DIAMON/DIAMOF twice in one block"));
                }
                self.words.diam = Some(!is(name, b"DIAMOF"));
                continue;
            }
            if let Some(a) = Addr::of_name(name) {
                self.src.expect(b'=', "'=' expected after the address")?;
                let n = self.number_expr()?;
                self.words.set(a, n)?;
                continue;
            }
            if let Some(n) = r_number(name) {
                self.src.expect(b'=', "'=' expected after the R parameter")?;
                self.r_room(n)?;
                self.assign(Target::R(n), None)?;
                continue;
            }
            match self.src.peek() {
                Some(b'=') if self.src.at(1) != Some(b'=') => {
                    self.src.i += 1;
                    let ty = self.scope.vars.type_of(name).ok_or(AlarmKind::from(S::NameNotDefined))?;
                    self.assign(Target::Var(name), Some(ty))?;
                }
                Some(b'[') => {
                    self.src.i += 1;
                    let mut idx = [0i64; MAX_INDICES];
                    let mut k = 0;
                    loop {
                        let v = {
                            let view = View { scope: self.scope, pending: self.pending };
                            whole(&eval(&mut self.src, &view)?)?
                        };
                        *idx.get_mut(k).ok_or(AlarmKind::from(S::IndexOutOfRange))? = v;
                        k += 1;
                        if !self.src.eat(b',') {
                            break;
                        }
                    }
                    self.src.expect(b']', "']' missing")?;
                    self.src.expect(b'=', "'=' expected after the variable")?;
                    let target = if is(name, b"R") {
                        self.r_room(idx[0])?;
                        Target::R(idx[0])
                    } else {
                        indexed_target(name, &idx[..k], self.scope.cfg)?
                    };
                    self.assign(target, None)?;
                }
                _ => {
                    // A name alone: a subprogram or cycle call, in a block of its own.
                    self.src.i = save;
                    return self.call(args);
                }
            }
        }
    }

    /// Whether R parameter `n` exists and can take a value with the block's other
    /// new R parameters (alarm 17020, 12460).
    fn r_room(&self, n: i64) -> Result<(), AlarmKind> {
        let vars = self.scope.vars;
        vars.r(n)?;
        if vars.has_r(n) || self.pending.latest(&Target::R(n)).is_some() {
            return Ok(());
        }
        let mut fresh = 0;
        for (i, (t, _)) in self.pending.items.iter().enumerate() {
            if let Target::R(m) = *t
                && !vars.has_r(m)
                && !self.pending.items[..i].iter().any(|(u, _)| *u == Target::R(m))
            {
                fresh += 1;
            }
        }
        if fresh >= vars.r_free() {
            return Err(S::TooManySymbols.into());
        }
        Ok(())
    }

    fn call(&mut self, args: &mut CallArgs) -> Result<Stmt<'t>, AlarmKind> {
        let has_words = !self.words.is_empty() || !self.pending.is_empty();
        let name = self.src.name();
        if self.scope.vars.is_defined(name) {
            return Err(syntax("a variable without '='"));
        }
        let list = self.args(args)?;
        let passes = self.passes()?;
        if has_words {
            return Err(syntax("a subprogram or cycle call needs a block of its own"));
        }
        self.end(Stmt::Call { name, list, passes })
    }

    /// `target=expr`, converted to `ty` (a DEF variable's type) or to REAL.
    fn assign(&mut self, target: Target<'t>, ty: Option<VarTy>) -> Result<(), AlarmKind> {
        // A string is copied out (it may lie in the block's own assignments)
        // before it is stored with them.
        let mut buf = [0u8; MAX_STRING];
        let scalar = {
            let view = View { scope: self.scope, pending: self.pending };
            let v = eval(&mut self.src, &view)?;
            let v = match ty {
                Some(ty) => convert_to(ty, v)?,
                None => Value::Real(expr::num(&v)?),
            };
            match v {
                Value::Str(s) => {
                    let n = s.len().min(MAX_STRING);
                    buf[..n].copy_from_slice(&s[..n]);
                    Err(n)
                }
                Value::Real(x) => Ok(Value::Real(x)),
                Value::Int(x) => Ok(Value::Int(x)),
                Value::Bool(x) => Ok(Value::Bool(x)),
                Value::Char(x) => Ok(Value::Char(x)),
            }
        };
        match scalar {
            Ok(v) => self.pending.push(target, v),
            Err(n) => self.pending.push(target, Value::Str(&buf[..n])),
        }
    }

    /// An address with a number: `X40.824`, `Z-0.1`, `G1`, `M30`, `T1`.
    fn address_word(&mut self, letter: u8) -> Result<(), AlarmKind> {
        self.src.i += 1;
        let neg = self.src.eat(b'-');
        if !neg {
            self.src.eat(b'+');
        }
        let mut n = self.src.number()?;
        if neg {
            n.mantissa = -n.mantissa;
        }
        self.put(letter, n)
    }

    /// `X=expr`, `X=AC(expr)`, `X=IC(expr)`, `G=…`, `M=…`.
    fn address_expr(&mut self, letter: u8) -> Result<(), AlarmKind> {
        let save = self.src.i;
        let mode = if self.src.keyword(b"AC") && self.src.peek() == Some(b'(') {
            Some(false)
        } else {
            self.src.i = save;
            if self.src.keyword(b"IC") && self.src.peek() == Some(b'(') {
                Some(true)
            } else {
                self.src.i = save;
                None
            }
        };
        if letter == b'T' && self.src.peek() == Some(b'"') {
            return Err(AlarmKind::NotSupportedYet { what: "tool names (T=\"…\"): use T numbers" });
        }
        let n = self.number_expr()?;
        if let Some(inc) = mode {
            let a = Addr::of_letter(letter).filter(|a| a.bit() & (mask::AXES | mask::CENTRE) != 0);
            let a = a.ok_or(syntax("AC()/IC() only for axes and arc centres"))?;
            if inc {
                self.words.ic |= a.bit();
            } else {
                self.words.ac |= a.bit();
            }
        }
        self.put(letter, n)
    }

    /// An expression's value as a word's number.
    fn number_expr(&mut self) -> Result<Number, AlarmKind> {
        let v = {
            let view = View { scope: self.scope, pending: self.pending };
            expr::num(&eval(&mut self.src, &view)?)?
        };
        Number::from_f64(v).ok_or(S::ValueRange.into())
    }

    fn put(&mut self, letter: u8, n: Number) -> Result<(), AlarmKind> {
        match letter {
            b'G' => {
                let g = integer(&n, b'G')?;
                self.words.g.push(g).map_err(|_| syntax("more than 10 G functions in one block"))
            }
            b'M' => {
                let m = integer(&n, b'M')?;
                self.words.m.push(m).map_err(|_| AlarmKind::TooManyMCodes)
            }
            b'N' => Err(syntax("block number N only at the start of the block")),
            b'R' => Err(syntax("R parameter without '='")),
            b'L' | b'P' | b'O' | b'Q' | b'E' | b'U' | b'V' | b'W' => Err(S::NameNotDefined.into()),
            _ => {
                let a = Addr::of_letter(letter).ok_or(AlarmKind::from(S::NameNotDefined))?;
                self.words.set(a, n)
            }
        }
    }
}

/// A G or M number: whole, 0–9999.
fn integer(n: &Number, letter: u8) -> Result<u16, AlarmKind> {
    n.as_integer()
        .filter(|v| (0..=9999).contains(v) && !n.has_point)
        .map(|v| v as u16)
        .ok_or(AlarmKind::ValueOutOfRange { letter })
}

/// The jump keyword `kw`.
fn goto_dir(kw: &[u8]) -> Option<Dir> {
    const DIRS: [Dir; 4] = [Dir::Forward, Dir::Backward, Dir::Both, Dir::BothQuiet];
    which(kw, &[b"GOTOF", b"GOTOB", b"GOTO", b"GOTOC"]).map(|k| DIRS[k])
}

/// The statements that take the whole line, in the order `Reader::statement` matches them.
const STATEMENTS: [&[u8]; 8] = [b"DEF", b"PROC", b"IF", b"RET", b"REPEAT", b"REPEATB", b"MCALL", b"MSG"];

/// The 840D's structured control statements this controller does not run.
fn unsupported(kw: &[u8]) -> bool {
    const WORDS: [&[u8]; 14] = [
        b"ELSE",
        b"ENDIF",
        b"WHILE",
        b"ENDWHILE",
        b"FOR",
        b"ENDFOR",
        b"LOOP",
        b"ENDLOOP",
        b"CASE",
        b"UNTIL",
        b"CALL",
        b"PCALL",
        b"EXTCALL",
        b"SETAL",
    ];
    which(kw, &WORDS).is_some()
}

#[cfg(test)]
mod tests {
    use super::*;
    use interp_core::lang::siemens::call::Arg;

    struct Fixture {
        vars: Vars,
        state: State,
        cfg: MachineConfig,
    }

    impl Fixture {
        fn new() -> Self {
            let cfg = MachineConfig::default();
            let state = State::power_on(&cfg, interp_core::axis::Pos::ZERO);
            let mut vars = Vars::new();
            vars.define(b"FFR", VarTy::Real).unwrap();
            vars.define(b"RFF", VarTy::Real).unwrap();
            vars.define(b"UPNAME", VarTy::Str { cap: 8 }).unwrap();
            vars.define(b"VARI", VarTy::Int).unwrap();
            Fixture { vars, state, cfg }
        }

        fn read<'t>(
            &self,
            text: &'t str,
            words: &mut Words,
            pending: &mut Pending<'t>,
            args: &mut CallArgs,
        ) -> Result<Stmt<'t>, AlarmKind> {
            let scope = Scope { vars: &self.vars, state: &self.state, cfg: &self.cfg };
            read(text.as_bytes(), 7, &scope, words, pending, args)
        }
    }

    #[test]
    fn nc_words_numbers_and_expressions() {
        let f = Fixture::new();
        let (mut w, mut p, mut a) = (Words::default(), Pending::new(), CallArgs::new());
        let s = f.read("N101 G01 X40.824 Z-0.1 F0.2 ; finish", &mut w, &mut p, &mut a).unwrap();
        assert_eq!(s, Stmt::Nc { jump: None });
        assert_eq!((w.line, w.seq, w.g.as_slice()), (7, Some(101), &[1u16][..]));
        assert_eq!(w.get(Addr::X), Some(Number { mantissa: 40_824, frac_digits: 3, has_point: true }));
        assert_eq!(w.get(Addr::Z).map(|n| n.to_f64()), Some(-0.1));
        assert_eq!(w.get(Addr::F).map(|n| n.to_f64()), Some(0.2));
        let mut p = Pending::new();
        f.read("N200 Z=AC(70) ANG=150 X=IC(10) RND=2.5", &mut w, &mut p, &mut a).unwrap();
        assert_eq!((w.explicit(Addr::Z), w.explicit(Addr::X)), (Some(false), Some(true)));
        assert_eq!(w.get(Addr::Ang).map(|n| n.to_f64()), Some(150.0));
        assert_eq!(w.get(Addr::Rnd).map(|n| n.to_f64()), Some(2.5));
        let mut p = Pending::new();
        f.read("G18 DIAMOF G90 G96 F0.8 S500 M3 LIMS=3000 T11 D1", &mut w, &mut p, &mut a).unwrap();
        assert_eq!((w.diam, w.g.as_slice(), w.m.as_slice()), (Some(false), &[18u16, 90, 96][..], &[3u16][..]));
        assert_eq!(w.get(Addr::Lims).map(|n| n.to_f64()), Some(3000.0));
        let mut p = Pending::new();
        assert_eq!(f.read("G1 X10 X20", &mut w, &mut p, &mut a), Err(S::AxisProgrammedTwice { letter: b'X' }.into()));
        let mut p = Pending::new();
        assert_eq!(f.read("U10", &mut w, &mut p, &mut a), Err(S::NameNotDefined.into()));
    }

    #[test]
    fn assignments_wait_and_are_seen_by_later_words() {
        // Seed 001 line 2607: N10 G0 FFR=300 RFF=1.5*FFR S500 M4.
        let f = Fixture::new();
        let (mut w, mut p, mut a) = (Words::default(), Pending::new(), CallArgs::new());
        f.read("N10 G0 FFR=300 RFF=1.5*FFR S500 M4 R1=RFF+1 X=R1", &mut w, &mut p, &mut a).unwrap();
        let got: heapless::Vec<_, 4> = p.each().collect();
        assert_eq!(got[0], (Target::Var(b"FFR"), Value::Real(300.0)));
        assert_eq!(got[1], (Target::Var(b"RFF"), Value::Real(450.0)));
        assert_eq!(got[2], (Target::R(1), Value::Real(451.0)));
        assert_eq!(w.get(Addr::X).map(|n| n.to_f64()), Some(451.0));
        assert_eq!(f.vars.get(b"FFR"), Some(Value::Real(0.0)), "nothing written yet");
        let mut p = Pending::new();
        f.read("UPNAME=\"KONTUR_1\" VARI=2.6", &mut w, &mut p, &mut a).unwrap();
        let got: heapless::Vec<_, 4> = p.each().collect();
        assert_eq!(got[0], (Target::Var(b"UPNAME"), Value::Str(b"KONTUR_1")));
        assert_eq!(got[1], (Target::Var(b"VARI"), Value::Int(3)));
        let mut p = Pending::new();
        assert_eq!(f.read("NOPE=1", &mut w, &mut p, &mut a), Err(S::NameNotDefined.into()));
        let mut p = Pending::new();
        assert_eq!(f.read("UPNAME=\"KONTUR_10\"", &mut w, &mut p, &mut a), Err(S::StringTooLong.into()));
        let mut p = Pending::new();
        f.read("_ZSD[2]=1 $TC_DP6[3,1]=0.8", &mut w, &mut p, &mut a).unwrap();
        let got: heapless::Vec<_, 4> = p.each().collect();
        assert_eq!(got[0], (Target::Zsd(2), Value::Real(1.0)));
        assert_eq!(got[1], (Target::Tool { row: 3, param: 6 }, Value::Real(0.8)));
    }

    #[test]
    fn statements_labels_and_calls() {
        let f = Fixture::new();
        let (mut w, mut p, mut a) = (Words::default(), Pending::new(), CallArgs::new());
        assert_eq!(
            f.read("N70 IF 3<6 GOTOB MA1", &mut w, &mut p, &mut a),
            Ok(Stmt::If { holds: true, jump: Jump { dir: Dir::Backward, label: b"MA1" } })
        );
        assert_eq!(f.read("N50 MA1: G91 Z20", &mut w, &mut p, &mut a), Ok(Stmt::Nc { jump: None }));
        assert_eq!((w.seq, w.g.as_slice()), (Some(50), &[91u16][..]));
        assert_eq!(f.read("ANFANG:", &mut w, &mut p, &mut a), Ok(Stmt::Nc { jump: None }));
        assert!(w.is_empty());
        assert_eq!(f.read("N500 _ENDE:M2", &mut w, &mut p, &mut a), Ok(Stmt::Nc { jump: None }));
        assert_eq!(w.m.as_slice(), &[2]);
        assert_eq!(
            f.read("GOTOF _ENDE", &mut w, &mut p, &mut a),
            Ok(Stmt::Goto(Jump { dir: Dir::Forward, label: b"_ENDE" }))
        );
        assert_eq!(
            f.read("N210 REPEAT 孔圆弧1", &mut w, &mut p, &mut a),
            Ok(Stmt::Repeat { start: "孔圆弧1".as_bytes(), end: None, count: 1, single: false })
        );
        assert_eq!(
            f.read("REPEAT A_B ENDLABEL P=3", &mut w, &mut p, &mut a),
            Ok(Stmt::Repeat { start: b"A_B", end: Some(b"ENDLABEL"), count: 3, single: false })
        );
        // Call with empty slots, a list closed early, strings, expressions.
        let mut p = Pending::new();
        let s = f.read("N20 CYCLE95 (\"KONTUR_1\", 5, 1.2, 0.6, , 0.2, 0.1, 0.2, 9, , , 0.5)", &mut w, &mut p, &mut a);
        assert_eq!(s, Ok(Stmt::Call { name: b"CYCLE95", list: true, passes: 1 }));
        assert_eq!(a.len(), 12);
        assert_eq!(
            (a.get(0), a.get(1), a.get(4), a.get(8)),
            (Arg::Str(b"KONTUR_1"), Arg::Int(5), Arg::Empty, Arg::Int(9))
        );
        assert_eq!(a.get(2), Arg::Real(1.2));
        let mut p = Pending::new();
        assert_eq!(
            f.read("MCALL CYCLE81(110, 100, 2, 35)", &mut w, &mut p, &mut a),
            Ok(Stmt::MCall { name: Some(b"CYCLE81"), list: true })
        );
        assert_eq!(a.len(), 4);
        assert_eq!(f.read("MCALL", &mut w, &mut p, &mut a), Ok(Stmt::MCall { name: None, list: false }));
        assert_eq!(
            f.read("KONTUR_1", &mut w, &mut p, &mut a),
            Ok(Stmt::Call { name: b"KONTUR_1", list: false, passes: 1 })
        );
        assert_eq!(
            f.read("KONTUR_1 P3", &mut w, &mut p, &mut a),
            Ok(Stmt::Call { name: b"KONTUR_1", list: false, passes: 3 })
        );
        assert_eq!(
            f.read("G1 X1 CYCLE81(1,2)", &mut w, &mut p, &mut a),
            Err(syntax("a subprogram or cycle call needs a block of its own"))
        );
        assert_eq!(f.read("N1 DEF REAL A=1, B", &mut w, &mut p, &mut a), Ok(Stmt::Def(b" REAL A=1, B")));
        assert_eq!(
            f.read("WHILE R1<3", &mut w, &mut p, &mut a),
            Err(AlarmKind::NotSupportedYet { what: "this control structure (only IF…GOTO)" })
        );
        assert_eq!(
            f.read("N10 G1 X1 GOTOF END", &mut w, &mut p, &mut a),
            Ok(Stmt::Nc { jump: Some(Jump { dir: Dir::Forward, label: b"END" }) })
        );
        assert!(f.read("CYCLE95(\"A\",", &mut w, &mut p, &mut a).is_err());
    }
}

//! Expression evaluation by recursive descent straight over the block text: no
//! tokens, no tree, no allocation. Recursion only happens through brackets, whose
//! nesting is limited to 5 levels (alarm 0118), so the stack depth is bounded.
//!
//! Grammar (priorities of the table in 2.24.2, higher binds tighter):
//!
//! ```text
//! sum      = product { ("+" | "-" | "OR" | "XOR") product }
//! product  = unary { ("*" | "/" | "AND" | "AN" | "MOD") unary }
//! unary    = { "+" | "-" } primary
//! primary  = constant | "#" varnum | bracket | function
//! bracket  = "[" sum [ relop sum ] "]"          (a relop makes it a condition)
//! varnum   = digits | bracket
//! function = NAME bracket | "ATAN" bracket [ "/" bracket ] | ("MAX"|"MIN") "[" sum "," sum "]"
//! relop    = EQ NE GT GE LT LE == <> > >= < <=
//! ```
//!
//! A `/` inside an expression is always division (2.24.2 (2)): the caller decides
//! where an expression may stand.

use super::func::{self, Func};
use super::vars::{MAX_VARIABLE, Value, Variables, out_of_range};
use crate::alarm::AlarmKind;
use crate::units::{Number, round_to};

/// Most nested bracket levels, function brackets included (FANUC: 5, alarm 0118).
pub const MAX_BRACKET_DEPTH: u8 = 5;

/// What a (sub)expression evaluates to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Val {
    /// A number, or null (a bare `#i` that is undefined; any operation makes it 0).
    Num(Value),
    /// The truth of a comparison.
    Bool(bool),
}

/// How ROUND rounds (2.24.2 (7)).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Rounding {
    /// In a macro statement: at the first decimal place, to a whole number.
    Macro,
    /// In an NC word: to the address's least input increment, in 1e-9 program units.
    Nc { step_e9: i64 },
    /// In an NC word read without a number format ([`crate::lang::fanuc::parse::read_block`]).
    Unknown,
}

/// Comparison operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Rel {
    Eq,
    Ne,
    Gt,
    Ge,
    Lt,
    Le,
}

/// Operators between two operands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Op {
    Add,
    Sub,
    Or,
    Xor,
    Mul,
    Div,
    And,
    Mod,
}

/// Function names, full and abbreviated as the manual lists them (2.24.2).
const FUNCTIONS: &[(&[u8], Func)] = &[
    (b"ROUND", Func::Round),
    (b"ASIN", Func::Asin),
    (b"ACOS", Func::Acos),
    (b"ATAN", Func::Atan),
    (b"SQRT", Func::Sqrt),
    (b"SIN", Func::Sin),
    (b"COS", Func::Cos),
    (b"TAN", Func::Tan),
    (b"ABS", Func::Abs),
    (b"FIX", Func::Fix),
    (b"FUP", Func::Fup),
    (b"EXP", Func::Exp),
    (b"MAX", Func::Max),
    (b"MIN", Func::Min),
    (b"SI", Func::Sin),
    (b"AS", Func::Asin),
    (b"CO", Func::Cos),
    (b"AC", Func::Acos),
    (b"TA", Func::Tan),
    (b"AT", Func::Atan),
    (b"SQ", Func::Sqrt),
    (b"AB", Func::Abs),
    (b"RO", Func::Round),
    (b"FI", Func::Fix),
];

/// Operators of the sum level.
const SUM_OPS: &[(&[u8], Op)] = &[(b"XOR", Op::Xor), (b"OR", Op::Or), (b"+", Op::Add), (b"-", Op::Sub)];
/// Operators of the product level.
const PRODUCT_OPS: &[(&[u8], Op)] =
    &[(b"AND", Op::And), (b"MOD", Op::Mod), (b"AN", Op::And), (b"*", Op::Mul), (b"/", Op::Div)];
/// Comparison operators and their symbol forms (2.24.2 table, note 9).
const RELATIONS: &[(&[u8], Rel)] = &[
    (b"EQ", Rel::Eq),
    (b"NE", Rel::Ne),
    (b"GT", Rel::Gt),
    (b"GE", Rel::Ge),
    (b"LT", Rel::Lt),
    (b"LE", Rel::Le),
    (b"==", Rel::Eq),
    (b"<>", Rel::Ne),
    (b">=", Rel::Ge),
    (b"<=", Rel::Le),
    (b">", Rel::Gt),
    (b"<", Rel::Lt),
];

/// Most digits of a constant before and after the point.
const MAX_CONSTANT_DIGITS: u8 = 9;

/// Exact powers of ten for constants.
const POW10: [f64; 10] = [1.0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9];

/// Alarm 0114 with a reason.
pub(crate) const fn format(what: &'static str) -> AlarmKind {
    AlarmKind::MacroFormat { what }
}

/// An expression evaluator positioned in a block's text.
pub(crate) struct Eval<'t, 'v> {
    /// The block text.
    pub text: &'t [u8],
    /// Where evaluation stands.
    pub pos: usize,
    /// The variable table; `None` where variables are not available.
    vars: Option<&'v Variables>,
    /// False while parsing a part that is not executed (the THEN or GOTO of a false
    /// IF): syntax is checked, values are not computed and raise no alarms.
    pub live: bool,
    /// Open brackets.
    depth: u8,
    /// What ROUND does here.
    rounding: Rounding,
}

impl<'t, 'v> Eval<'t, 'v> {
    /// An evaluator at `pos` of `text`.
    pub(crate) fn new(text: &'t [u8], pos: usize, vars: Option<&'v Variables>, rounding: Rounding) -> Self {
        Eval { text, pos, vars, live: true, depth: 0, rounding }
    }

    pub(crate) fn peek(&self) -> Option<u8> {
        self.text.get(self.pos).copied()
    }

    /// Skips blanks (not comments: they end an expression).
    pub(crate) fn skip_blanks(&mut self) {
        while matches!(self.peek(), Some(b' ' | b'\t' | b'\r')) {
            self.pos += 1;
        }
    }

    /// The longest entry of `table` spelled at the current position (any case).
    fn find<K: Copy>(&self, table: &[(&[u8], K)]) -> Option<(K, usize)> {
        let (i, len) = self.longest(&mut table.iter().map(|(w, _)| *w))?;
        table.get(i).map(|(_, k)| (*k, len))
    }

    /// The index and length of the longest of `words` spelled at the current position
    /// (any case; the last of equally long ones). Not generic: one copy in flash for
    /// every table [`find`](Self::find) searches.
    #[inline(never)]
    fn longest(&self, words: &mut dyn Iterator<Item = &[u8]>) -> Option<(usize, usize)> {
        let rest = self.text.get(self.pos..).unwrap_or(&[]);
        let mut best: Option<(usize, usize)> = None;
        for (i, w) in words.enumerate() {
            let spelled = rest.get(..w.len()).is_some_and(|r| r.eq_ignore_ascii_case(w));
            if spelled && best.is_none_or(|(_, len)| w.len() >= len) {
                best = Some((i, w.len()));
            }
        }
        best
    }

    /// Consumes an entry of `table` at the current position (after blanks).
    pub(crate) fn take<K: Copy>(&mut self, table: &[(&[u8], K)]) -> Option<K> {
        self.skip_blanks();
        let (k, len) = self.find(table)?;
        self.pos += len;
        Some(k)
    }

    /// Consumes `c` after blanks, or raises alarm 0114 with `what`.
    pub(crate) fn expect(&mut self, c: u8, what: &'static str) -> Result<(), AlarmKind> {
        self.skip_blanks();
        if self.peek() == Some(c) {
            self.pos += 1;
            Ok(())
        } else {
            Err(format(what))
        }
    }

    /// `sum` of the grammar: an arithmetic expression (no comparison).
    pub(crate) fn expression(&mut self) -> Result<Val, AlarmKind> {
        let mut a = self.product()?;
        while let Some(op) = self.take(SUM_OPS) {
            let b = self.product()?;
            a = self.binary(op, a, b)?;
        }
        Ok(a)
    }

    fn product(&mut self) -> Result<Val, AlarmKind> {
        let mut a = self.unary()?;
        while let Some(op) = self.take(PRODUCT_OPS) {
            let b = self.unary()?;
            a = self.binary(op, a, b)?;
        }
        Ok(a)
    }

    /// Signs before a primary, counted in a loop (no recursion). A `-` is an
    /// operation, so it turns null into 0; `+` alone changes nothing.
    pub(crate) fn unary(&mut self) -> Result<Val, AlarmKind> {
        let mut negate = None;
        loop {
            self.skip_blanks();
            match self.peek() {
                Some(b'+') => {}
                Some(b'-') => negate = Some(!negate.unwrap_or(false)),
                _ => break,
            }
            self.pos += 1;
        }
        let v = self.primary()?;
        match negate {
            None => Ok(v),
            Some(n) => {
                let x = number(v)?;
                Ok(Val::Num(Some(if n { -x } else { x } + 0.0)))
            }
        }
    }

    /// A constant, a variable, a bracket or a function call.
    pub(crate) fn primary(&mut self) -> Result<Val, AlarmKind> {
        self.skip_blanks();
        match self.peek() {
            Some(b'#') => {
                self.pos += 1;
                let n = self.variable_number()?;
                self.read_variable(n).map(Val::Num)
            }
            Some(b'[') => self.bracket(),
            Some(b'0'..=b'9' | b'.') => self.constant(),
            Some(c) if c.is_ascii_alphabetic() => {
                let f = self.take(FUNCTIONS).ok_or(format("unknown function or operator"))?;
                self.function(f)
            }
            Some(_) => Err(format("operand expected")),
            None => Err(format("expression ends too early")),
        }
    }

    /// The value of `#n` (null while not live).
    fn read_variable(&self, n: u16) -> Result<Value, AlarmKind> {
        if !self.live {
            return Ok(None);
        }
        self.vars.ok_or(format("variables are not available here (use read_statement)"))?.get(n)
    }

    /// The number after `#`: digits, or a bracketed expression (`#[#20+#30/4]`),
    /// rounded to a whole number. Alarm 0115 outside 0–999.
    pub(crate) fn variable_number(&mut self) -> Result<u16, AlarmKind> {
        self.skip_blanks();
        let n: i64 = match self.peek() {
            Some(b'[') => {
                let v = number(self.bracket()?)?;
                if !self.live {
                    return Ok(0);
                }
                libm::round(v).clamp(-1e12, 1e12) as i64
            }
            Some(b'0'..=b'9') => {
                let mut n: i64 = 0;
                while let Some(d @ b'0'..=b'9') = self.peek() {
                    n = (n * 10 + i64::from(d - b'0')).min(1_000_000_000);
                    self.pos += 1;
                }
                n
            }
            _ => return Err(format("'#' needs a variable number")),
        };
        if !self.live {
            return Ok(0);
        }
        u16::try_from(n).ok().filter(|n| *n <= MAX_VARIABLE).ok_or(out_of_range(n))
    }

    /// `[ … ]`, possibly a comparison.
    pub(crate) fn bracket(&mut self) -> Result<Val, AlarmKind> {
        self.open()?;
        let a = self.expression()?;
        let v = match self.take(RELATIONS) {
            Some(rel) => {
                let b = self.expression()?;
                Val::Bool(compare(rel, nullable(a)?, nullable(b)?))
            }
            None => a,
        };
        self.close()?;
        Ok(v)
    }

    /// Consumes `[`, counting the nesting.
    fn open(&mut self) -> Result<(), AlarmKind> {
        self.expect(b'[', "'[' expected")?;
        self.depth += 1;
        if self.depth > MAX_BRACKET_DEPTH {
            return Err(AlarmKind::TooManyBrackets);
        }
        Ok(())
    }

    /// Consumes `]`.
    fn close(&mut self) -> Result<(), AlarmKind> {
        self.expect(b']', "']' expected")?;
        self.depth -= 1;
        Ok(())
    }

    /// An unsigned decimal constant; no point needed (`123` is 123.000, 2.24.1).
    fn constant(&mut self) -> Result<Val, AlarmKind> {
        let (mut mantissa, mut int_digits, mut frac_digits, mut point) = (0i64, 0u8, 0u8, false);
        while let Some(c) = self.peek() {
            match c {
                b'0'..=b'9' => {
                    if point {
                        frac_digits += 1;
                    } else if mantissa != 0 || c != b'0' {
                        int_digits += 1;
                    }
                    if int_digits > MAX_CONSTANT_DIGITS || frac_digits > MAX_CONSTANT_DIGITS {
                        return Err(format("constant with more than 9 digits before or after the point"));
                    }
                    mantissa = mantissa * 10 + i64::from(c - b'0');
                }
                b'.' if !point => point = true,
                b'.' => return Err(format("second decimal point in a constant")),
                _ => break,
            }
            self.pos += 1;
        }
        // mantissa < 10^18 and the power of ten is exact: one rounding only while
        // mantissa < 2^53 (any constant of up to 15 digits).
        Ok(Val::Num(Some(mantissa as f64 / POW10[usize::from(frac_digits)])))
    }

    /// A function call after its name.
    fn function(&mut self, f: Func) -> Result<Val, AlarmKind> {
        self.skip_blanks();
        if self.peek() != Some(b'[') {
            return Err(format("a function needs its argument in [ ]"));
        }
        match f {
            Func::Max | Func::Min => {
                self.open()?;
                let a = number(self.expression()?)?;
                self.expect(b',', "MAX/MIN need two arguments [a, b]")?;
                let b = number(self.expression()?)?;
                self.close()?;
                self.result(|| Ok(if f == Func::Max { a.max(b) } else { a.min(b) }))
            }
            Func::Atan => {
                let j = number(self.argument()?)?;
                if self.second_atan_argument() {
                    self.pos += 1;
                    let k = number(self.argument()?)?;
                    self.result(|| func::atan2_deg(j, k))
                } else {
                    self.result(|| Ok(func::atan_deg(j)))
                }
            }
            _ => {
                let x = number(self.argument()?)?;
                self.result(|| self.apply(f, x))
            }
        }
    }

    /// One bracketed argument (no comparison).
    fn argument(&mut self) -> Result<Val, AlarmKind> {
        self.open()?;
        let v = self.expression()?;
        self.close()?;
        Ok(v)
    }

    /// Whether `/[` follows (the second argument of `ATAN[j]/[k]`); leaves the
    /// position on the `/`.
    fn second_atan_argument(&mut self) -> bool {
        self.skip_blanks();
        if self.peek() != Some(b'/') {
            return false;
        }
        let mut i = self.pos + 1;
        while matches!(self.text.get(i), Some(b' ' | b'\t' | b'\r')) {
            i += 1;
        }
        self.text.get(i) == Some(&b'[')
    }

    /// A one-argument function.
    fn apply(&self, f: Func, x: f64) -> Result<f64, AlarmKind> {
        Ok(match f {
            Func::Sin => func::sin_deg(x),
            Func::Cos => func::cos_deg(x),
            Func::Tan => func::tan_deg(x)?,
            Func::Asin => func::asin_deg(x)?,
            Func::Acos => func::acos_deg(x)?,
            Func::Sqrt => func::sqrt(x)?,
            Func::Abs => x.abs(),
            Func::Round => self.round(x)?,
            Func::Fix => func::fix(x),
            Func::Fup => func::fup(x),
            Func::Exp => func::exp(x)?,
            Func::Atan | Func::Max | Func::Min => return Err(format(f.name())),
        })
    }

    /// ROUND as 2.24.2 (7) says: to a whole number in a macro statement, to the
    /// least input increment in an NC word (through the same 9-digit decimal the
    /// word itself goes through, so `X[ROUND[#1]]` and `X#1` agree).
    fn round(&self, x: f64) -> Result<f64, AlarmKind> {
        match self.rounding {
            Rounding::Macro => Ok(func::round_macro(x)),
            Rounding::Nc { step_e9 } => {
                let n = Number::from_f64(x).ok_or(AlarmKind::MacroOverflow)?;
                let e9 = n.scaled(9).ok_or(AlarmKind::MacroOverflow)?;
                Ok(round_to(e9, step_e9) as f64 / 1e9)
            }
            Rounding::Unknown => Err(format("ROUND in a word needs the number format (use read_statement)")),
        }
    }

    /// Wraps a computed result: nothing is computed while not live; a non-finite
    /// result is alarm 0111.
    fn result(&self, f: impl FnOnce() -> Result<f64, AlarmKind>) -> Result<Val, AlarmKind> {
        if !self.live {
            return Ok(Val::Num(None));
        }
        finite(f()?)
    }

    /// `a op b`.
    fn binary(&self, op: Op, a: Val, b: Val) -> Result<Val, AlarmKind> {
        if matches!(op, Op::And | Op::Or | Op::Xor) {
            return self.logic(op, a, b);
        }
        let (x, y) = (number(a)?, number(b)?);
        self.result(|| match op {
            Op::Add => Ok(x + y),
            Op::Sub => Ok(x - y),
            Op::Mul => Ok(x * y),
            Op::Div if y == 0.0 => Err(AlarmKind::DivideByZero),
            Op::Div => Ok(x / y),
            _ => func::modulo(x, y),
        })
    }

    /// AND/OR/XOR: logical between two conditions, bit by bit between two whole
    /// numbers 0..2^32-1 (FANUC's 32-bit binary operation).
    fn logic(&self, op: Op, a: Val, b: Val) -> Result<Val, AlarmKind> {
        let pick = |x: bool, y: bool| match op {
            Op::And => x && y,
            Op::Or => x || y,
            _ => x != y,
        };
        match (a, b) {
            (Val::Bool(x), Val::Bool(y)) => Ok(Val::Bool(pick(x, y))),
            (Val::Num(x), Val::Num(y)) => {
                if !self.live {
                    return Ok(Val::Num(None));
                }
                let (x, y) = (bits(x.unwrap_or(0.0))?, bits(y.unwrap_or(0.0))?);
                let r = match op {
                    Op::And => x & y,
                    Op::Or => x | y,
                    _ => x ^ y,
                };
                Ok(Val::Num(Some(f64::from(r))))
            }
            _ => Err(format("AND/OR/XOR between a condition and a number")),
        }
    }
}

/// The number a value stands for in an operation: null counts as 0 (2.24.1).
pub(crate) fn number(v: Val) -> Result<f64, AlarmKind> {
    match v {
        Val::Num(x) => Ok(x.unwrap_or(0.0)),
        Val::Bool(_) => Err(format("a comparison where a number is needed")),
    }
}

/// The value itself, null kept (assignment, comparison, address words).
pub(crate) fn nullable(v: Val) -> Result<Value, AlarmKind> {
    match v {
        Val::Num(x) => Ok(x),
        Val::Bool(_) => Err(format("a comparison where a number is needed")),
    }
}

/// A computed number, alarm 0111 if it left the range.
fn finite(x: f64) -> Result<Val, AlarmKind> {
    if x.is_finite() { Ok(Val::Num(Some(x + 0.0))) } else { Err(AlarmKind::MacroOverflow) }
}

/// A whole number 0..2^32-1 for a bit operation.
#[inline(never)]
fn bits(x: f64) -> Result<u32, AlarmKind> {
    if libm::trunc(x) == x && (0.0..=f64::from(u32::MAX)).contains(&x) {
        Ok(x as u32)
    } else {
        Err(AlarmKind::ArgumentOutOfRange { function: "AND/OR/XOR" })
    }
}

/// A comparison with the null rules of 2.24.1 and note 6: null equals null and
/// differs from every number, 0 included. So with `#2` null, `#2 EQ #0`,
/// `#2 GE #0` and `#2 LE #0` hold and the others do not; with `#2 = 0` only
/// `#2 NE #0` holds.
pub(crate) fn compare(rel: Rel, a: Value, b: Value) -> bool {
    match (a, b) {
        (Some(x), Some(y)) => match rel {
            Rel::Eq => x == y,
            Rel::Ne => x != y,
            Rel::Gt => x > y,
            Rel::Ge => x >= y,
            Rel::Lt => x < y,
            Rel::Le => x <= y,
        },
        (None, None) => matches!(rel, Rel::Eq | Rel::Ge | Rel::Le),
        _ => rel == Rel::Ne,
    }
}

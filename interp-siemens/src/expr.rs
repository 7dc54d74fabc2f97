//! SINUMERIK expressions: the operators with the 840D's precedence (comparisons
//! bind loosest: `IF R1>5 AND R2<3` must be written `IF (R1>5) AND (R2<3)`), the
//! arithmetic functions, R parameters, DEF variables and the indexed variables
//! (`R[n]`, `_ZSD[n]`, `$TC_DPn[t,d]`). Values are typed (REAL, INT, BOOL, CHAR,
//! STRING): INT stays INT through `+ - *` and `DIV`, `/` gives REAL.
//!
//! Precedence, loosest first (the 840D's list): `== <> < > <= >=`, `<<` (strings),
//! `OR`, `XOR`, `AND`, `B_OR`, `B_XOR`, `B_AND`, `+ -`, `* / DIV MOD`, then `NOT`,
//! `B_NOT` and signs. Angles are degrees. Division by zero is alarm 0112, a
//! function outside its domain 0119, as in the FANUC language.

use super::lex::{Src, is, syntax};
use interp_core::alarm::{AlarmKind, SiemensAlarm as S};
use interp_core::geom::deg;
use interp_core::lang::siemens::vars::Value;

/// Most brackets and nested calls in one expression (the board's stack is small).
const MAX_DEPTH: u8 = 16;
/// Most indices of an indexed variable.
pub const MAX_INDICES: usize = 3;

/// Where an expression's variables come from.
pub trait Env {
    /// DEF variable `name` of the current program level.
    fn var(&self, name: &[u8]) -> Option<Value<'_>>;
    /// R parameter `n`.
    fn r(&self, n: i64) -> Result<f64, AlarmKind>;
    /// Indexed variable `name[idx…]` (not R): `_ZSD[i]`, `$TC_DPn[t,d]`.
    fn indexed(&self, name: &[u8], idx: &[i64]) -> Result<Value<'_>, AlarmKind>;
}

/// Evaluates the expression at `src` (up to the first thing that cannot continue
/// it: a `,`, `)`, keyword …).
pub fn eval<'t: 'x, 'x, E: Env>(src: &mut Src<'t>, env: &'x E) -> Result<Value<'x>, AlarmKind> {
    eval_in(src, env)
}

/// The evaluator reaches its variables through `dyn Env`: one copy of it in
/// flash for every kind of scope (the block reader's and the cycle's views were
/// two copies of ~13 KB each on the board).
fn eval_in<'t: 'x, 'x>(src: &mut Src<'t>, env: &'x dyn Env) -> Result<Value<'x>, AlarmKind> {
    Eval { src, env, depth: 0 }.expr()
}

/// Evaluates an expression that must give a number.
pub fn eval_num<E: Env>(src: &mut Src<'_>, env: &E) -> Result<f64, AlarmKind> {
    num(&eval(src, env)?)
}

/// A value as a number (12150 for a string).
pub fn num(v: &Value<'_>) -> Result<f64, AlarmKind> {
    let x = v.num().ok_or(AlarmKind::from(S::TypeMismatch))?;
    if x.is_finite() { Ok(x) } else { Err(AlarmKind::MacroOverflow) }
}

/// A value as a condition: a number is true when not zero.
pub fn truth(v: &Value<'_>) -> Result<bool, AlarmKind> {
    Ok(num(v)? != 0.0)
}

/// A whole number from a value (an index, a count): rounded REAL, INT.
pub fn whole(v: &Value<'_>) -> Result<i64, AlarmKind> {
    let x = libm::round(num(v)?);
    if x.abs() > 2_147_483_647.0 {
        return Err(S::ValueRange.into());
    }
    Ok(x as i64)
}

struct Eval<'s, 't, 'x> {
    src: &'s mut Src<'t>,
    env: &'x dyn Env,
    depth: u8,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Cmp {
    Eq,
    Ne,
    Lt,
    Gt,
    Le,
    Ge,
}

/// INT arithmetic when both sides are INT and the result fits, else REAL.
fn arith(a: &Value<'_>, b: &Value<'_>, op: u8) -> Result<Value<'static>, AlarmKind> {
    if let (Value::Int(x), Value::Int(y)) = (a, b) {
        let r = match op {
            b'+' => x.checked_add(*y),
            b'-' => x.checked_sub(*y),
            _ => x.checked_mul(*y),
        };
        if let Some(r) = r.filter(|r| (-2_147_483_648..=2_147_483_647).contains(r)) {
            return Ok(Value::Int(r));
        }
    }
    let (x, y) = (num(a)?, num(b)?);
    let r = match op {
        b'+' => x + y,
        b'-' => x - y,
        _ => x * y,
    };
    finite(r)
}

fn finite(r: f64) -> Result<Value<'static>, AlarmKind> {
    if r.is_finite() { Ok(Value::Real(r + 0.0)) } else { Err(AlarmKind::MacroOverflow) }
}

/// A binary operator.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Op {
    Cmp(Cmp),
    Or,
    Xor,
    And,
    BOr,
    BXor,
    BAnd,
    Add,
    Sub,
    Mul,
    Div,
    IntDiv,
    Mod,
}

/// `a op b`: comparisons give BOOL (strings and characters compare with `==`
/// and `<>` only), OR/XOR/AND BOOL, B_OR/B_XOR/B_AND INT, `/` REAL, DIV INT,
/// `+ - *` and MOD INT when both sides are INT (and the result fits).
fn apply(op: Op, a: &Value<'_>, b: &Value<'_>) -> Result<Value<'static>, AlarmKind> {
    Ok(match op {
        Op::Cmp(c) => Value::Bool(compare(c, a, b)?),
        Op::Or | Op::Xor | Op::And => {
            let (x, y) = (truth(a)?, truth(b)?);
            Value::Bool(match op {
                Op::Or => x || y,
                Op::Xor => x ^ y,
                _ => x && y,
            })
        }
        Op::BOr | Op::BXor | Op::BAnd => {
            let (x, y) = (whole(a)?, whole(b)?);
            Value::Int(match op {
                Op::BOr => x | y,
                Op::BXor => x ^ y,
                _ => x & y,
            })
        }
        Op::Add => return arith(a, b, b'+'),
        Op::Sub => return arith(a, b, b'-'),
        Op::Mul => return arith(a, b, b'*'),
        Op::Div | Op::IntDiv => {
            let (x, y) = (num(a)?, num(b)?);
            if y == 0.0 {
                return Err(AlarmKind::DivideByZero);
            }
            if op == Op::Div {
                return finite(x / y);
            }
            Value::Int(whole(&Value::Real(libm::trunc(x / y)))?)
        }
        Op::Mod => {
            let both_int = matches!((a, b), (Value::Int(_), Value::Int(_)));
            let r = deg::modulo(num(a)?, num(b)?)?;
            if both_int { Value::Int(r as i64) } else { Value::Real(r) }
        }
    })
}

/// `a c b` for a comparison.
fn compare(c: Cmp, a: &Value<'_>, b: &Value<'_>) -> Result<bool, AlarmKind> {
    let one = |v: &Value<'_>| match *v {
        Value::Char(c) => Some(c),
        Value::Str(&[c]) => Some(c),
        _ => None,
    };
    Ok(match (a, b) {
        (Value::Char(_), Value::Str(_)) | (Value::Str(_), Value::Char(_)) => match (one(a), one(b), c) {
            (Some(x), Some(y), Cmp::Eq) => x == y,
            (x, y, Cmp::Ne) => x.is_none() || y.is_none() || x != y,
            (_, _, Cmp::Eq) => false,
            _ => return Err(S::TypeMismatch.into()),
        },
        (Value::Str(x), Value::Str(y)) => match c {
            Cmp::Eq => x == y,
            Cmp::Ne => x != y,
            _ => return Err(S::TypeMismatch.into()),
        },
        _ => {
            let (x, y) = (num(a)?, num(b)?);
            match c {
                Cmp::Eq => x == y,
                Cmp::Ne => x != y,
                Cmp::Lt => x < y,
                Cmp::Gt => x > y,
                Cmp::Le => x <= y,
                Cmp::Ge => x >= y,
            }
        }
    })
}

impl<'t: 'x, 'x> Eval<'_, 't, 'x> {
    fn expr(&mut self) -> Result<Value<'x>, AlarmKind> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(syntax("expression nested too deep"));
        }
        let v = self.binary(0);
        self.depth -= 1;
        v
    }

    /// The operands and operators of precedence `level` and tighter, left to
    /// right: 0 comparisons, 1 OR, 2 XOR, 3 AND, 4 B_OR, 5 B_XOR, 6 B_AND,
    /// 7 `+ -`, 8 `* / DIV MOD` (one loop for every level).
    fn binary(&mut self, level: u8) -> Result<Value<'x>, AlarmKind> {
        let mut a = self.operand(level)?;
        while let Some(op) = self.op(level) {
            let b = self.operand(level)?;
            a = apply(op, &a, &b)?;
        }
        Ok(a)
    }

    /// An operand of `level`: the next tighter level (a comparison's is never a
    /// string concatenation `<<`).
    fn operand(&mut self, level: u8) -> Result<Value<'x>, AlarmKind> {
        match level {
            0 => {
                let a = self.binary(1)?;
                if self.src.peek() == Some(b'<') && self.src.at(1) == Some(b'<') {
                    return Err(AlarmKind::NotSupportedYet { what: "string concatenation <<" });
                }
                Ok(a)
            }
            8 => self.unary(),
            _ => self.binary(level + 1),
        }
    }

    /// The operator of `level` that comes next, consumed.
    fn op(&mut self, level: u8) -> Option<Op> {
        const WORDS: [&[u8]; 6] = [b"OR", b"XOR", b"AND", b"B_OR", b"B_XOR", b"B_AND"];
        const LOGIC: [Op; 6] = [Op::Or, Op::Xor, Op::And, Op::BOr, Op::BXor, Op::BAnd];
        match level {
            0 => self.cmp_op().map(Op::Cmp),
            1..=6 => {
                let k = usize::from(level - 1);
                self.src.keyword(WORDS[k]).then_some(LOGIC[k])
            }
            7 => {
                let op = match self.src.peek() {
                    Some(b'+') => Op::Add,
                    Some(b'-') => Op::Sub,
                    _ => return None,
                };
                self.src.i += 1;
                Some(op)
            }
            _ => {
                if self.src.eat(b'*') {
                    Some(Op::Mul)
                } else if self.src.peek() == Some(b'/') {
                    self.src.i += 1;
                    Some(Op::Div)
                } else if self.src.keyword(b"DIV") {
                    Some(Op::IntDiv)
                } else if self.src.keyword(b"MOD") {
                    Some(Op::Mod)
                } else {
                    None
                }
            }
        }
    }

    fn cmp_op(&mut self) -> Option<Cmp> {
        let (c0, c1) = (self.src.peek()?, self.src.at(1));
        let (op, n) = match (c0, c1) {
            (b'=', Some(b'=')) => (Cmp::Eq, 2),
            (b'<', Some(b'>')) => (Cmp::Ne, 2),
            (b'<', Some(b'=')) => (Cmp::Le, 2),
            (b'>', Some(b'=')) => (Cmp::Ge, 2),
            (b'<', Some(b'<')) => return None,
            (b'<', _) => (Cmp::Lt, 1),
            (b'>', _) => (Cmp::Gt, 1),
            _ => return None,
        };
        self.src.i += n;
        Some(op)
    }

    fn unary(&mut self) -> Result<Value<'x>, AlarmKind> {
        // A sign, NOT or B_NOT before the operand (0: none).
        let prefix = match self.src.peek() {
            Some(c @ (b'-' | b'+')) => {
                self.src.i += 1;
                c
            }
            _ if self.src.keyword(b"NOT") => b'!',
            _ if self.src.keyword(b"B_NOT") => b'~',
            _ => return self.primary(),
        };
        let v = self.nested(Self::unary)?;
        Ok(match prefix {
            b'-' => match v {
                Value::Int(n) => Value::Int(-n),
                v => finite(-num(&v)?)?,
            },
            b'+' => {
                num(&v)?;
                v
            }
            b'!' => Value::Bool(!truth(&v)?),
            _ => Value::Int(!whole(&v)?),
        })
    }

    /// `f` one level deeper (signs and NOT recurse).
    fn nested(&mut self, f: fn(&mut Self) -> Result<Value<'x>, AlarmKind>) -> Result<Value<'x>, AlarmKind> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(syntax("expression nested too deep"));
        }
        let v = f(self);
        self.depth -= 1;
        v
    }

    fn primary(&mut self) -> Result<Value<'x>, AlarmKind> {
        if self.src.at_number() {
            let n = self.src.number()?;
            return Ok(if n.has_point { Value::Real(n.to_f64()) } else { Value::Int(n.mantissa) });
        }
        match self.src.peek() {
            Some(b'(') => {
                self.src.i += 1;
                let v = self.expr()?;
                self.src.expect(b')', "')' missing")?;
                Ok(v)
            }
            Some(b'"') => Ok(Value::Str(self.src.string()?)),
            _ if self.src.at_name() => {
                let name = self.src.name();
                self.named(name)
            }
            Some(_) => Err(syntax("value expected")),
            None => Err(syntax("expression ends early")),
        }
    }

    /// A name in an expression: a constant, function, R parameter or variable.
    fn named(&mut self, name: &'t [u8]) -> Result<Value<'x>, AlarmKind> {
        if is(name, b"TRUE") {
            return Ok(Value::Bool(true));
        }
        if is(name, b"FALSE") {
            return Ok(Value::Bool(false));
        }
        if let Some(n) = r_number(name) {
            return Ok(Value::Real(self.env.r(n)?));
        }
        if self.src.peek() == Some(b'(') {
            return self.function(name);
        }
        if self.src.eat(b'[') {
            let mut idx = [0i64; MAX_INDICES];
            let mut k = 0;
            loop {
                let v = self.expr()?;
                *idx.get_mut(k).ok_or(AlarmKind::from(S::IndexOutOfRange))? = whole(&v)?;
                k += 1;
                if !self.src.eat(b',') {
                    break;
                }
            }
            self.src.expect(b']', "']' missing")?;
            if is(name, b"R") {
                return Ok(Value::Real(self.env.r(idx[0])?));
            }
            return self.env.indexed(name, &idx[..k]);
        }
        self.env.var(name).ok_or(S::NameNotDefined.into())
    }

    fn function(&mut self, name: &'t [u8]) -> Result<Value<'x>, AlarmKind> {
        use Func::*;
        let f = FUNCTIONS.iter().find(|(n, _)| is(name, n)).map(|&(_, f)| f);
        let want = match f {
            Some(Atan2 | MinVal | MaxVal) => 2,
            Some(Bound) => 3,
            _ => 1,
        };
        self.src.expect(b'(', "'(' expected")?;
        if f == Some(StrLen) {
            let v = self.expr()?;
            self.src.expect(b')', "')' missing")?;
            return match v {
                Value::Str(s) => Ok(Value::Int(s.len() as i64)),
                _ => Err(S::TypeMismatch.into()),
            };
        }
        let mut a = [0.0f64; 3];
        for (k, slot) in a.iter_mut().enumerate().take(want) {
            if k > 0 {
                self.src.expect(b',', "',' expected between the function's arguments")?;
            }
            *slot = eval_num_in(self)?;
        }
        self.src.expect(b')', "')' missing")?;
        let x = a[0];
        let Some(f) = f else { return Err(S::NameNotDefined.into()) };
        let r = match f {
            Sin => deg::sin_deg(x),
            Cos => deg::cos_deg(x),
            Tan => deg::tan_deg(x)?,
            Asin => deg::asin_deg(x)?,
            Acos => deg::acos_deg(x)?,
            Atan2 => atan2_deg(x, a[1])?,
            Sqrt => deg::sqrt(x)?,
            Abs => libm::fabs(x),
            Pot => x * x,
            Trunc => deg::fix(x),
            Round => libm::round(x) + 0.0,
            RoundUp => libm::ceil(x) + 0.0,
            Ln => {
                if x <= 0.0 {
                    return Err(AlarmKind::ArgumentOutOfRange { function: "LN" });
                }
                libm::log(x)
            }
            Exp => deg::exp(x)?,
            MinVal => x.min(a[1]),
            MaxVal => x.max(a[1]),
            Bound => {
                if x > a[1] {
                    return Err(AlarmKind::ArgumentOutOfRange { function: "BOUND" });
                }
                a[2].clamp(x, a[1])
            }
            StrLen => return Err(S::TypeMismatch.into()),
        };
        finite(r)
    }
}

/// The arithmetic functions of expressions.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Func {
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan2,
    Sqrt,
    Abs,
    Pot,
    Trunc,
    Round,
    RoundUp,
    Ln,
    Exp,
    MinVal,
    MaxVal,
    Bound,
    StrLen,
}

/// The functions by name: one lookup instead of a comparison per name in code.
const FUNCTIONS: [(&[u8], Func); 18] = [
    (b"SIN", Func::Sin),
    (b"COS", Func::Cos),
    (b"TAN", Func::Tan),
    (b"ASIN", Func::Asin),
    (b"ACOS", Func::Acos),
    (b"ATAN2", Func::Atan2),
    (b"SQRT", Func::Sqrt),
    (b"ABS", Func::Abs),
    (b"POT", Func::Pot),
    (b"TRUNC", Func::Trunc),
    (b"ROUND", Func::Round),
    (b"ROUNDUP", Func::RoundUp),
    (b"LN", Func::Ln),
    (b"EXP", Func::Exp),
    (b"MINVAL", Func::MinVal),
    (b"MAXVAL", Func::MaxVal),
    (b"BOUND", Func::Bound),
    (b"STRLEN", Func::StrLen),
];

fn eval_num_in<'t: 'x, 'x>(e: &mut Eval<'_, 't, 'x>) -> Result<f64, AlarmKind> {
    let v = e.expr()?;
    num(&v)
}

/// ATAN2(y, x): the angle of the vector (x, y) from the abscissa, −180..180°
/// (the 840D's, unlike FANUC's ATAN[j]/[k]); ATAN2(0, 0) is alarm 0119.
pub fn atan2_deg(y: f64, x: f64) -> Result<f64, AlarmKind> {
    if y == 0.0 && x == 0.0 {
        return Err(AlarmKind::ArgumentOutOfRange { function: "ATAN2" });
    }
    Ok(deg::degrees(libm::atan2(y, x)))
}

/// The number of an R parameter written `R<digits>`.
pub fn r_number(name: &[u8]) -> Option<i64> {
    let digits = name.strip_prefix(b"R").or_else(|| name.strip_prefix(b"r"))?;
    if digits.is_empty() || digits.len() > 4 || !digits.iter().all(u8::is_ascii_digit) {
        return None;
    }
    Some(digits.iter().fold(0, |n, d| n * 10 + i64::from(d - b'0')))
}

#[cfg(test)]
mod tests {
    use super::*;
    use interp_core::lang::siemens::vars::{VarTy, Vars};

    struct T(Vars);

    impl Env for T {
        fn var(&self, name: &[u8]) -> Option<Value<'_>> {
            self.0.get(name)
        }
        fn r(&self, n: i64) -> Result<f64, AlarmKind> {
            self.0.r(n)
        }
        fn indexed(&self, _: &[u8], _: &[i64]) -> Result<Value<'_>, AlarmKind> {
            Err(S::NameNotDefined.into())
        }
    }

    fn env() -> T {
        let mut v = Vars::new();
        v.define(b"MID", VarTy::Real).unwrap();
        v.set(b"MID", Value::Real(7.0)).unwrap();
        v.define(b"FFR", VarTy::Real).unwrap();
        v.set(b"FFR", Value::Real(200.0)).unwrap();
        v.define(b"ZAEHL", VarTy::Int).unwrap();
        v.set(b"ZAEHL", Value::Int(5)).unwrap();
        v.define(b"S", VarTy::Str { cap: 8 }).unwrap();
        v.set(b"S", Value::Str(b"ANFANG")).unwrap();
        v.set_r(1, 5.0).unwrap();
        T(v)
    }

    fn ev(t: &str) -> Result<Value<'static>, AlarmKind> {
        let e = env();
        let mut s = Src::new(t.as_bytes());
        let v = eval(&mut s, &e)?;
        if !s.done() {
            return Err(syntax("left over"));
        }
        Ok(match v {
            Value::Str(_) => Value::Str(b"<str>"),
            Value::Real(x) => Value::Real(x),
            Value::Int(x) => Value::Int(x),
            Value::Bool(x) => Value::Bool(x),
            Value::Char(x) => Value::Char(x),
        })
    }

    #[test]
    fn the_documents_expressions() {
        // CYCLE100 ("E", MID*0.5, FFR+100, 1): MID 3.5, feed 300 (lines 691-701).
        assert_eq!(ev("MID*0.5"), Ok(Value::Real(3.5)));
        assert_eq!(ev("FFR+100"), Ok(Value::Real(300.0)));
        assert_eq!(ev("ZAEHL<6"), Ok(Value::Bool(true)));
        assert_eq!(ev("ZAEHL+1"), Ok(Value::Int(6)));
        assert_eq!(ev("1.5*FFR"), Ok(Value::Real(300.0)));
        assert_eq!(ev("R1*2-1"), Ok(Value::Real(9.0)));
        assert_eq!(ev("R[R1-4]"), Ok(Value::Real(5.0)));
        assert_eq!(ev("S==\"ANFANG\""), Ok(Value::Bool(true)));
    }

    #[test]
    fn precedence_functions_and_types() {
        assert_eq!(ev("2+3*4"), Ok(Value::Int(14)));
        assert_eq!(ev("(2+3)*4"), Ok(Value::Int(20)));
        assert_eq!(ev("7/2"), Ok(Value::Real(3.5)));
        assert_eq!(ev("7 DIV 2"), Ok(Value::Int(3)));
        assert_eq!(ev("-7 MOD 3"), Ok(Value::Int(-1)));
        assert_eq!(ev("-2*-3"), Ok(Value::Int(6)));
        assert_eq!(ev("SIN(30)"), Ok(Value::Real(0.5)));
        assert_eq!(ev("ATAN2(1,-1)"), Ok(Value::Real(135.0)));
        assert_eq!(ev("ATAN2(-1,-1)"), Ok(Value::Real(-135.0)));
        assert_eq!(ev("SQRT(POT(3)+POT(4))"), Ok(Value::Real(5.0)));
        assert_eq!(ev("TRUNC(-2.7)+ROUND(2.5)+ABS(-1)"), Ok(Value::Real(2.0)));
        assert_eq!(ev("(1<2) AND (3>4)"), Ok(Value::Bool(false)));
        assert_eq!(ev("NOT (1==2) OR FALSE"), Ok(Value::Bool(true)));
        assert_eq!(ev("5 B_AND 3"), Ok(Value::Int(1)));
        // Comparisons bind loosest: 1 < (2 AND 0) < 1 → 1 < 0 → FALSE < 1 → TRUE.
        assert_eq!(ev("1<2 AND 0<1"), Ok(Value::Bool(true)));
        assert_eq!(ev("BOUND(0, 10, 12)"), Ok(Value::Real(10.0)));
    }

    #[test]
    fn errors_are_alarms() {
        assert_eq!(ev("1/0"), Err(AlarmKind::DivideByZero));
        assert_eq!(ev("SQRT(-1)"), Err(AlarmKind::ArgumentOutOfRange { function: "SQRT" }));
        assert_eq!(ev("NOPE+1"), Err(S::NameNotDefined.into()));
        assert_eq!(ev("S+1"), Err(S::TypeMismatch.into()));
        assert_eq!(ev("(1+2"), Err(syntax("')' missing")));
        assert_eq!(ev("R100"), Err(S::IndexOutOfRange.into()));
        assert_eq!(ev("SIN(1,2)"), Err(syntax("')' missing")));
        assert_eq!(ev(&"(".repeat(40)), Err(syntax("expression nested too deep")));
        assert_eq!(ev(&"-".repeat(40)), Err(syntax("expression nested too deep")));
        assert_eq!(ev("1EX300*1EX300"), Err(S::ValueRange.into()));
    }
}

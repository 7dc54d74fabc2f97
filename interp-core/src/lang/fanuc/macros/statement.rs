//! Macro statements (2.24.2): assignment, GOTO, IF…GOTO, IF…THEN, WHILE…DO, DO,
//! END. Read and evaluated in one pass against the variable table, so what comes
//! out holds plain values: the interpreter only has to store a value or move its
//! cursor.

use super::expr::{Eval, Val, format, nullable};
use super::vars::Value;
use crate::alarm::AlarmKind;
use crate::program::{Cursor, next_block, starts_program};

/// Highest sequence number a jump may name (2.24.2 note 1).
pub const MAX_SEQUENCE: u32 = 99_999;

/// A macro statement, already evaluated.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum MacroStatement {
    /// `#i=…`, or the THEN part of an IF whose condition held: `#var` becomes `value`
    /// (null when the right side is a bare null variable, 2.24.1).
    Assign {
        /// Variable number, 1–999.
        var: u16,
        /// The value.
        value: Value,
    },
    /// `GOTO n`, or `IF […] GOTO n` whose condition held: go to sequence number `seq`.
    Goto {
        /// Target sequence number, 1–99999.
        seq: u32,
    },
    /// An IF whose condition did not hold: nothing to do.
    Nop,
    /// `WHILE […] DO m` (`enter` = the condition held) or `DO m` alone (`enter` is
    /// always true: an endless loop, note 5).
    Loop {
        /// Loop number 1–3.
        label: u8,
        /// Run the range (true) or continue after its END (false).
        enter: bool,
    },
    /// `END m`: back to the WHILE/DO of loop `m`.
    End {
        /// Loop number 1–3.
        label: u8,
    },
    /// A macro call (G65, G66, G67, a G or M code that calls; note 7 counts it a
    /// macro statement): what it asks for and its arguments are in the
    /// [`CallRead`](crate::lang::fanuc::calls::CallRead) the reader was given.
    Call,
}

/// Words that begin a macro statement.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Keyword {
    If,
    Goto,
    Then,
    While,
    Do,
    End,
}

/// Statement keywords. Only the full spellings: the manual abbreviates functions,
/// not these, and `GO1` is much more likely a mistyped `G01` than a jump.
const KEYWORDS: &[(&[u8], Keyword)] = &[
    (b"IF", Keyword::If),
    (b"GOTO", Keyword::Goto),
    (b"THEN", Keyword::Then),
    (b"WHILE", Keyword::While),
    (b"DO", Keyword::Do),
    (b"END", Keyword::End),
];

/// Whether a macro statement starts at `pos` of `text`: a `#` (assignment) or a
/// statement keyword followed by something that is not a letter.
pub(crate) fn starts_statement(text: &[u8], pos: usize) -> bool {
    let rest = text.get(pos..).unwrap_or(&[]);
    match rest {
        [b'#', ..] => return true,
        // Every keyword starts with two letters; an NC word with a letter and a value.
        [a, b, ..] if a.is_ascii_alphabetic() && b.is_ascii_alphabetic() => {}
        _ => return false,
    }
    KEYWORDS.iter().any(|(w, _)| {
        rest.len() >= w.len()
            && rest[..w.len()].eq_ignore_ascii_case(w)
            && !rest.get(w.len()).is_some_and(u8::is_ascii_alphabetic)
    })
}

/// Reads the macro statement at the evaluator's position (where
/// [`starts_statement`] is true).
pub(crate) fn statement(e: &mut Eval) -> Result<MacroStatement, AlarmKind> {
    e.skip_blanks();
    if e.peek() == Some(b'#') {
        return assignment(e);
    }
    match e.take(KEYWORDS) {
        Some(Keyword::If) => if_statement(e),
        Some(Keyword::Goto) => Ok(MacroStatement::Goto { seq: jump_target(e)? }),
        Some(Keyword::While) => {
            let enter = condition(e)?;
            if e.take(KEYWORDS) != Some(Keyword::Do) {
                return Err(format("WHILE […] needs DO m"));
            }
            Ok(MacroStatement::Loop { label: loop_number(e)?, enter })
        }
        Some(Keyword::Do) => Ok(MacroStatement::Loop { label: loop_number(e)?, enter: true }),
        Some(Keyword::End) => Ok(MacroStatement::End { label: loop_number(e)? }),
        Some(Keyword::Then) => Err(format("THEN without IF")),
        None => Err(format("macro statement expected")),
    }
}

/// `#i = expression`.
fn assignment(e: &mut Eval) -> Result<MacroStatement, AlarmKind> {
    e.expect(b'#', "assignment '#i=…' expected")?;
    let var = e.variable_number()?;
    if var == 0 && e.live {
        return Err(AlarmKind::WriteProtectedVariable { number: 0 });
    }
    e.expect(b'=', "'=' expected after the variable")?;
    let value = nullable(e.expression()?)?;
    Ok(MacroStatement::Assign { var, value })
}

/// `IF [cond] GOTO n` or `IF [cond] THEN #i=…`; the part after the condition is
/// only checked for syntax when the condition does not hold.
fn if_statement(e: &mut Eval) -> Result<MacroStatement, AlarmKind> {
    let holds = condition(e)?;
    let keyword = e.take(KEYWORDS);
    let was_live = e.live;
    e.live = was_live && holds;
    let r = match keyword {
        Some(Keyword::Goto) => jump_target(e).map(|seq| MacroStatement::Goto { seq }),
        Some(Keyword::Then) => assignment(e),
        _ => Err(format("IF […] needs GOTO or THEN")),
    };
    e.live = was_live;
    if holds { r } else { r.map(|_| MacroStatement::Nop) }
}

/// `[a relop b]`: the condition of IF and WHILE (note 2: it needs an operator).
fn condition(e: &mut Eval) -> Result<bool, AlarmKind> {
    e.skip_blanks();
    if e.peek() != Some(b'[') {
        return Err(format("the condition must be in [ ]"));
    }
    match e.bracket()? {
        Val::Bool(b) => Ok(b),
        Val::Num(_) => Err(format("the condition needs EQ, NE, GT, GE, LT or LE")),
    }
}

/// The sequence number after GOTO: a constant, `#i` or `[expr]` (note 1). Alarm
/// 0128 unless it is a whole number 1–99999.
fn jump_target(e: &mut Eval) -> Result<u32, AlarmKind> {
    let v = e.unary()?;
    if !e.live {
        return Ok(0);
    }
    let n = nullable(v)?.unwrap_or(0.0);
    if libm::trunc(n) != n || !(1.0..=f64::from(MAX_SEQUENCE)).contains(&n) {
        return Err(AlarmKind::SequenceOutOfRange);
    }
    Ok(n as u32)
}

/// The loop number after DO or END: a constant 1, 2 or 3 (note 3, alarm 0126).
fn loop_number(e: &mut Eval) -> Result<u8, AlarmKind> {
    e.skip_blanks();
    let mut n: u32 = 0;
    let mut any = false;
    while let Some(d @ b'0'..=b'9') = e.peek() {
        n = n.saturating_mul(10).saturating_add(u32::from(d - b'0'));
        any = true;
        e.pos += 1;
    }
    if !any {
        return Err(format("DO and END need a loop number 1-3"));
    }
    match n {
        1..=3 => Ok(n as u8),
        _ => Err(AlarmKind::IllegalLoopNumber { label: n }),
    }
}

/// A DO or END found while skimming program text (not evaluated).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum LoopMark {
    /// `WHILE […] DO m` or `DO m`; `m` = 0 if it is not a valid number.
    Do(u8),
    /// `END m`.
    End(u8),
}

/// Whether the block `text` is a DO or END statement, without evaluating anything
/// (used to find the END of a loop). The block's `/` and N are skipped.
pub(crate) fn loop_mark(text: &[u8]) -> Option<LoopMark> {
    let mut e = Eval::new(text, crate::head::statement_start(text), None, super::expr::Rounding::Macro);
    e.live = false;
    if !starts_statement(text, e.pos) {
        return None;
    }
    let label = |e: &mut Eval| loop_number(e).unwrap_or(0);
    match e.take(KEYWORDS)? {
        Keyword::Do => Some(LoopMark::Do(label(&mut e))),
        Keyword::End => Some(LoopMark::End(label(&mut e))),
        Keyword::While => {
            skip_brackets(&mut e)?;
            (e.take(KEYWORDS)? == Keyword::Do).then(|| LoopMark::Do(label(&mut e)))
        }
        _ => None,
    }
}

/// Skips a balanced `[ … ]` group without evaluating it.
fn skip_brackets(e: &mut Eval) -> Option<()> {
    e.skip_blanks();
    if e.peek() != Some(b'[') {
        return None;
    }
    let mut depth = 0u32;
    while let Some(c) = e.peek() {
        e.pos += 1;
        match c {
            b'[' => depth += 1,
            b']' => {
                depth -= 1;
                if depth == 0 {
                    return Some(());
                }
            }
            _ => {}
        }
    }
    None
}

/// The cursor just after the `END label` that closes the loop whose range starts at
/// `from` (the block after its WHILE/DO), skipping inner DO–END pairs. Alarm 0124
/// if the END is missing (the program ends first) or the ranges overlap (note 4).
///
/// The work is bounded by the length of the loop's range; the interpreter does it
/// when it enters the loop, so it knows the range for jumps out of it.
pub fn find_loop_end(text: &[u8], from: Cursor, label: u8) -> Result<Cursor, AlarmKind> {
    let mut cur = from;
    let mut inner: heapless::Vec<u8, 8> = heapless::Vec::new();
    while let Some(block) = next_block(text, &mut cur) {
        if block.percent || starts_program(block.text) {
            break;
        }
        match loop_mark(block.text) {
            Some(LoopMark::Do(m)) if m == label || inner.contains(&m) => {
                return Err(AlarmKind::LoopsCrossed { label });
            }
            Some(LoopMark::Do(m)) => inner.push(m).map_err(|_| AlarmKind::LoopsCrossed { label })?,
            Some(LoopMark::End(m)) => match inner.last() {
                Some(&top) if top == m => {
                    inner.pop();
                }
                None if m == label => return Ok(cur),
                _ => return Err(AlarmKind::LoopsCrossed { label }),
            },
            None => {}
        }
    }
    Err(AlarmKind::MissingEnd { label })
}

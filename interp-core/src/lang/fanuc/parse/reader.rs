//! The block reader: bytes → a [`Statement`]. Accepts lowercase, blanks between and
//! inside words (between address and value), comments in parentheses, a leading
//! `/n`, a sequence number before a macro statement (2.24.2 note 10), and macro
//! values in words: `F#203`, `Z-#210`, `G#230`, `X[#1*2]`, `F[25.4/10]` (2.24.1).

use super::{Block, MacroBlock, Read, Statement, whole};
use crate::alarm::AlarmKind;
use crate::alarm::GNum;
use crate::lang::fanuc::calls::{CallBlock, CallCode, CallCodes, CallRead, Caller, Calls, MCall, MacroCall, SubCall};
use crate::lang::fanuc::macros::{
    Eval, MacroStatement, Rounding, Value, Variables, format, nullable, starts_statement, statement,
};
use crate::units::{InputMode, Number, NumberFormat, pow10};

/// Most digits before the decimal point.
const MAX_INT_DIGITS: u8 = 9;
/// Most digits after it (nanometres of a millimetre).
const MAX_FRAC_DIGITS: u8 = 9;
/// Largest whole number a macro value may give an integer address (8 digits).
const MAX_WHOLE_VALUE: f64 = 99_999_999.0;

/// Reads one block's text (without its end-of-block character), evaluating every
/// expression against `vars`. `fmt` is the number format in force: ROUND in a word
/// rounds to its least input increment (2.24.2 (7)).
///
/// This is the reader every consumer of program text uses — the interpreter (through
/// [`read_statement_into`]), and the canned cycles reading their profile blocks.
/// Only G65, G66 and G67 call here: codes that parameters 6050–6089 make calls are
/// recognised by [`read_program_block`].
pub fn read_statement(text: &[u8], line: u32, vars: &Variables, fmt: &NumberFormat) -> Result<Statement, AlarmKind> {
    let mut block = Block::default();
    let mut reader = Reader::new(text, Some(vars), Some(*fmt), &CallCodes::BUILT_IN);
    Ok(match reader.statement(line, &mut block, None)? {
        Read::Nc => Statement::Nc(block),
        Read::Macro(m) if m.statement == MacroStatement::Call => read_call(text, line, vars, fmt)?,
        Read::Macro(m) => Statement::Macro(m),
    })
}

/// A macro call block of [`read_statement`], read again with its arguments (only
/// a call pays for the 33 vacant locals it starts from).
#[cold]
#[inline(never)]
fn read_call(text: &[u8], line: u32, vars: &Variables, fmt: &NumberFormat) -> Result<Statement, AlarmKind> {
    let mut block = Block::default();
    let mut call = CallRead::EMPTY;
    Reader::new(text, Some(vars), Some(*fmt), &CallCodes::BUILT_IN).statement(line, &mut block, Some(&mut call))?;
    Ok(Statement::Call(call.block, call.args))
}

/// [`read_statement`] into `block`, reusing its storage (the interpreter's per-block
/// path: nothing large is copied). An NC statement's words end up in `block`; a
/// macro call's arguments are checked and dropped.
pub fn read_statement_into(
    text: &[u8],
    line: u32,
    vars: &Variables,
    fmt: &NumberFormat,
    block: &mut Block,
) -> Result<Read, AlarmKind> {
    Reader::new(text, Some(vars), Some(*fmt), &CallCodes::BUILT_IN).statement(line, block, None)
}

/// A block of a program as the interpreter reads it: [`read_statement_into`] with
/// the codes that call programs (`calls.codes`); a macro call block is read into
/// `calls.read` (its arguments `#1–#33`, vacant where not given).
pub fn read_program_block(
    text: &[u8],
    line: u32,
    vars: &Variables,
    fmt: &NumberFormat,
    block: &mut Block,
    calls: &mut Calls,
) -> Result<Read, AlarmKind> {
    let Calls { codes, read } = calls;
    Reader::new(text, Some(vars), Some(*fmt), codes).statement(line, block, Some(read))
}

/// [`read_statement_into`] with what is available: without `vars` a `#` raises
/// alarm 0114, without `fmt` a ROUND in a word does (the cycles' shape blocks).
pub fn read_with(
    text: &[u8],
    line: u32,
    vars: Option<&Variables>,
    fmt: Option<NumberFormat>,
    block: &mut Block,
) -> Result<Read, AlarmKind> {
    Reader::new(text, vars, fmt, &CallCodes::BUILT_IN).statement(line, block, None)
}

/// Reads an NC block that uses no variables (tools and tests). A `#`, a ROUND in a
/// word or a macro statement raise alarm 0114: use [`read_statement`] for those.
pub fn read_block(text: &[u8], line: u32) -> Result<Block, AlarmKind> {
    let mut block = Block::default();
    read_block_into(text, line, &mut block)?;
    Ok(block)
}

/// [`read_block`] into `block`, reusing its storage.
pub fn read_block_into(text: &[u8], line: u32, block: &mut Block) -> Result<(), AlarmKind> {
    match Reader::new(text, None, None, &CallCodes::BUILT_IN).statement(line, block, None)? {
        Read::Nc => Ok(()),
        Read::Macro(_) => Err(format("macro statement (use read_statement)")),
    }
}

struct Reader<'a, 'v, 'c> {
    text: &'a [u8],
    pos: usize,
    vars: Option<&'v Variables>,
    fmt: Option<NumberFormat>,
    /// The codes that call programs.
    codes: &'c CallCodes,
    /// A call code began the block: the call, and where its words begin.
    call: Option<(CallCode, usize)>,
}

impl<'a, 'v, 'c> Reader<'a, 'v, 'c> {
    fn new(text: &'a [u8], vars: Option<&'v Variables>, fmt: Option<NumberFormat>, codes: &'c CallCodes) -> Self {
        Reader { text, pos: 0, vars, fmt, codes, call: None }
    }

    /// The whole block: skip mark, sequence number, then a macro statement, a macro
    /// call or words.
    fn statement(&mut self, line: u32, block: &mut Block, call: Option<&mut CallRead>) -> Result<Read, AlarmKind> {
        block.clear(line);
        self.skip_blanks_and_comments()?;
        if self.peek() == Some(b'/') {
            self.pos += 1;
            block.skip_level = Some(match self.peek() {
                Some(d @ b'1'..=b'9') => {
                    self.pos += 1;
                    d - b'0'
                }
                _ => 1,
            });
        }
        self.skip_blanks_and_comments()?;
        if matches!(self.peek(), Some(b'N' | b'n')) {
            if let Some((n, end)) = plain_number(self.text, self.pos + 1) {
                self.pos = end;
                self.store(b'N', n, block)?;
            } else {
                self.pos += 1;
                self.word(b'N', block)?;
            }
            self.skip_blanks_and_comments()?;
        }
        if starts_statement(self.text, self.pos) {
            let statement = self.macro_statement()?;
            let (skip_level, seq) = (block.skip_level, block.seq);
            block.clear(line);
            return Ok(Read::Macro(MacroBlock { line, skip_level, seq, statement }));
        }
        match self.words(block) {
            Ok(()) => Ok(Read::Nc),
            // A call code began the block: the rest is the call's.
            Err(_) if let Some((code, at)) = self.call => {
                self.pos = at;
                let (skip_level, seq) = (block.skip_level, block.seq);
                self.macro_call(code, line, block, call)?;
                Ok(Read::Macro(MacroBlock { line, skip_level, seq, statement: MacroStatement::Call }))
            }
            Err(k) => Err(k),
        }
    }

    /// A macro statement, and nothing but comments after it (note 7).
    fn macro_statement(&mut self) -> Result<crate::lang::fanuc::macros::MacroStatement, AlarmKind> {
        let Some(vars) = self.vars else {
            return Err(format("macro statement (use read_statement)"));
        };
        let mut e = Eval::new(self.text, self.pos, Some(vars), Rounding::Macro);
        let s = statement(&mut e)?;
        self.pos = e.pos;
        self.skip_blanks_and_comments()?;
        match self.peek() {
            None => Ok(s),
            Some(c) if c.is_ascii_alphabetic() || c == b'/' => Err(AlarmKind::MacroAndNcInOneBlock),
            Some(_) => Err(format("unexpected text after the statement")),
        }
    }

    /// The words of an NC block.
    fn words(&mut self, block: &mut Block) -> Result<(), AlarmKind> {
        loop {
            self.plain_words(block)?;
            self.skip_blanks_and_comments()?;
            let Some(c) = self.peek() else { return Ok(()) };
            // Keywords start with two letters (checked here first: it is cheap).
            let two_letters =
                c.is_ascii_alphabetic() && self.text.get(self.pos + 1).is_some_and(u8::is_ascii_alphabetic);
            if c == b'#' || two_letters && starts_statement(self.text, self.pos) {
                // A macro statement after NC words (2.24.2 note 7).
                return Err(AlarmKind::MacroAndNcInOneBlock);
            }
            self.pos += 1;
            match c.to_ascii_uppercase() {
                letter @ b'A'..=b'Z' => self.word(letter, block)?,
                b',' => self.comma_word(block)?,
                b'/' => return Err(AlarmKind::MisplacedBlockSkip),
                c @ (b'0'..=b'9' | b'+' | b'-' | b'.' | b'[' | b'=' | b']') => {
                    return Err(AlarmKind::AddressNotFound { found: c });
                }
                other => return Err(AlarmKind::IllegalCharacter { found: other }),
            }
        }
    }

    /// The common words, one after the other: a letter right before its plain
    /// number (`X40.8`, `Z-0.1`), blanks between them. Reads with the position in
    /// a register and each number in one pass; stops (without an alarm) at the
    /// first thing that is not such a word — a comment, a keyword, a macro value,
    /// a blank inside a word, a number [`plain_number`] leaves to
    /// [`Reader::number`] — which the caller's general path reads.
    #[inline(always)]
    fn plain_words(&mut self, block: &mut Block) -> Result<(), AlarmKind> {
        let text = self.text;
        let mut i = self.pos;
        loop {
            while text.get(i).is_some_and(|&c| is_blank(c)) {
                i += 1;
            }
            let Some(&c) = text.get(i) else { break };
            let letter = c & !0x20;
            if letter.wrapping_sub(b'A') >= 26 {
                break;
            }
            let Some((n, end)) = plain_number(text, i + 1) else { break };
            i = end;
            self.pos = i;
            self.store(letter, n, block)?;
        }
        self.pos = i;
        Ok(())
    }

    fn peek(&self) -> Option<u8> {
        self.text.get(self.pos).copied()
    }

    fn skip_blanks(&mut self) {
        while self.text.get(self.pos).is_some_and(|&c| is_blank(c)) {
            self.pos += 1;
        }
    }

    fn skip_blanks_and_comments(&mut self) -> Result<(), AlarmKind> {
        loop {
            self.skip_blanks();
            if self.peek() != Some(b'(') {
                return Ok(());
            }
            match self.text[self.pos..].iter().position(|&c| c == b')') {
                Some(n) => self.pos += n + 1,
                None => return Err(AlarmKind::CommentNotClosed),
            }
        }
    }

    /// Reads the value of `letter` and stores it in the block. A word whose value
    /// is a null variable is ignored with its address (2.24.1).
    fn word(&mut self, letter: u8, block: &mut Block) -> Result<(), AlarmKind> {
        let Some(n) = self.value(letter)? else { return Ok(()) };
        self.store(letter, n, block)
    }

    /// Stores the value `n` of address `letter` in the block.
    #[inline(always)]
    fn store(&mut self, letter: u8, n: Number, block: &mut Block) -> Result<(), AlarmKind> {
        match letter {
            b'G' => {
                let tenths = g_tenths(&n)?;
                if self.codes.g_may_call(tenths)
                    && let Some(code) = self.codes.g_call(tenths)
                {
                    return self.call_code(code, block);
                }
                block.g.push(tenths).map_err(|_| AlarmKind::ValueOutOfRange { letter })
            }
            b'M' => {
                let m = whole(letter, &n, 999)? as u16;
                if self.codes.m_may_call()
                    && let Some(call) = self.codes.m_call(m)
                {
                    return self.m_call(call, m, block);
                }
                block.m.push(m).map_err(|_| AlarmKind::TooManyMCodes)
            }
            b'N' => set_once(&mut block.seq, letter, whole(letter, &n, 99_999)?),
            b'O' => set_once(&mut block.program, letter, whole(letter, &n, 9_999)?),
            _ => {
                if letter == b'T' {
                    let t = whole(letter, &n, 99_999_999)?;
                    if self.codes.t_calls() {
                        return block.set_sub_call(SubCall { program: 9_000, m: 0, t: Some(t) });
                    }
                }
                if block.set(letter, n) { Ok(()) } else { Err(AlarmKind::DuplicateAddress { letter }) }
            }
        }
    }

    /// A call code (G65–G67, a G or M code that calls a macro) read as a word: it
    /// must begin the block (2.24.2 note 7: a macro call is a macro statement); the
    /// words after it are the call's, read by [`Reader::macro_call`].
    #[cold]
    #[inline(never)]
    fn call_code(&mut self, code: CallCode, block: &Block) -> Result<(), AlarmKind> {
        if !block.is_empty() {
            return Err(AlarmKind::MacroAndNcInOneBlock);
        }
        self.call = Some((code, self.pos));
        // Out of the words loop (the alarm is not raised: `statement` reads the rest
        // of the block as the call's).
        Err(AlarmKind::MacroAndNcInOneBlock)
    }

    /// An M code that calls: a macro (a call block, as G65), or a subprogram after
    /// the block's other codes (as M98).
    #[cold]
    #[inline(never)]
    fn m_call(&mut self, call: MCall, m: u16, block: &mut Block) -> Result<(), AlarmKind> {
        match call {
            MCall::Macro(program) => self.call_code(CallCode::M { program }, block),
            MCall::Subprogram(program) => block.set_sub_call(SubCall { program, m, t: None }),
        }
    }

    /// The words of a call block after its code (at `self.pos`): P (G65/G66) and L,
    /// and the arguments (FANUC 0i argument specification I and II) into `args`.
    /// Out of line: the registers of the per-block path stay free of it.
    #[inline(never)]
    fn macro_call(
        &mut self,
        code: CallCode,
        line: u32,
        block: &mut Block,
        mut read: Option<&mut CallRead>,
    ) -> Result<(), AlarmKind> {
        if let Some(r) = read.as_deref_mut() {
            r.args.clear();
        }
        let takes_p = matches!(code, CallCode::G65 | CallCode::G66);
        let mut program = match code {
            CallCode::G { program } | CallCode::M { program } => Some(program),
            _ => None,
        };
        let (mut p_given, mut repeats) = (false, None);
        let mut spec = Arguments::default();
        loop {
            self.skip_blanks_and_comments()?;
            let Some(c) = self.peek() else { break };
            let two_letters =
                c.is_ascii_alphabetic() && self.text.get(self.pos + 1).is_some_and(u8::is_ascii_alphabetic);
            if c == b'#' || two_letters && starts_statement(self.text, self.pos) {
                return Err(AlarmKind::MacroAndNcInOneBlock);
            }
            self.pos += 1;
            let letter = c.to_ascii_uppercase();
            match letter {
                b'P' if takes_p => {
                    if core::mem::replace(&mut p_given, true) {
                        return Err(AlarmKind::DuplicateAddress { letter });
                    }
                    program = self.count(letter)?;
                }
                b'L' if code != CallCode::G67 => {
                    if repeats.is_some() {
                        return Err(AlarmKind::DuplicateAddress { letter });
                    }
                    repeats = Some(self.count(letter)?.unwrap_or(1));
                }
                b'A'..=b'Z' if code != CallCode::G67 && SPEC_I[usize::from(letter - b'A')] != 0 => {
                    let var = spec.variable(letter)?;
                    let v = self.argument(letter)?;
                    if let (Some(r), Some(v)) = (read.as_deref_mut(), v) {
                        r.args.set(var, Some(v));
                    }
                }
                b'A'..=b'Z' | b',' => return Err(AlarmKind::IllegalArgumentAddress { letter }),
                b'/' => return Err(AlarmKind::MisplacedBlockSkip),
                c @ (b'0'..=b'9' | b'+' | b'-' | b'.' | b'[' | b'=' | b']') => {
                    return Err(AlarmKind::AddressNotFound { found: c });
                }
                other => return Err(AlarmKind::IllegalCharacter { found: other }),
            }
        }
        let repeats = repeats.unwrap_or(1) as u16;
        let by = match code {
            CallCode::G { .. } => Caller::GCode,
            CallCode::M { .. } => Caller::MCodeMacro,
            _ => Caller::Program,
        };
        let call = match code {
            CallCode::G67 => MacroCall::Cancel,
            CallCode::G66 => MacroCall::Modal { program: program.ok_or(AlarmKind::SubprogramNumberMissing)?, repeats },
            _ => MacroCall::Simple { program: program.ok_or(AlarmKind::SubprogramNumberMissing)?, repeats, by },
        };
        let (skip_level, seq) = (block.skip_level, block.seq);
        block.clear(line);
        if let Some(r) = read {
            r.block = CallBlock { line, skip_level, seq, call };
        }
        Ok(())
    }

    /// A P or L of a call: a whole number 1–9999 (`None` for a null variable).
    fn count(&mut self, letter: u8) -> Result<Option<u32>, AlarmKind> {
        let Some(n) = self.value(letter)? else { return Ok(None) };
        match whole(letter, &n, 9_999)? {
            0 => Err(AlarmKind::ValueOutOfRange { letter }),
            v => Ok(Some(v)),
        }
    }

    /// An argument's value: a macro value as computed, or a number read by
    /// [`argument_value`]; `None` (vacant) for a null variable.
    fn argument(&mut self, letter: u8) -> Result<Value, AlarmKind> {
        if let Some(v) = self.macro_value(letter)? {
            return Ok(v);
        }
        let n = self.number(letter)?;
        Ok(Some(argument_value(&n, letter, self.fmt)))
    }

    /// `,C` or `,R`.
    fn comma_word(&mut self, block: &mut Block) -> Result<(), AlarmKind> {
        self.skip_blanks();
        let letter =
            self.peek().map(|c| c.to_ascii_uppercase()).ok_or(AlarmKind::NoDataAfterAddress { letter: b',' })?;
        self.pos += 1;
        let Some(n) = self.value(letter)? else { return Ok(()) };
        let slot = match letter {
            b'C' => &mut block.chamfer,
            b'R' => &mut block.corner,
            _ => return Err(AlarmKind::ImproperAddress { letter }),
        };
        // 2.23 note 9: with several C/R in one block the last one is effective.
        *slot = Some(n);
        block.corner_last = letter == b'R';
        Ok(())
    }

    /// The value after an address: a number as written, or a macro value
    /// (`#i`, `-#i`, `[expr]`, `-[expr]`); `None` for a null variable.
    fn value(&mut self, letter: u8) -> Result<Option<Number>, AlarmKind> {
        match self.macro_value(letter)? {
            None => self.number(letter).map(Some),
            Some(None) => Ok(None),
            Some(Some(x)) => macro_number(letter, x).map(Some),
        }
    }

    /// A macro value after an address (`#i`, `-#i`, `[expr]`, `-[expr]`), evaluated;
    /// `None` (nothing read) if a plain number follows.
    fn macro_value(&mut self, letter: u8) -> Result<Option<Value>, AlarmKind> {
        self.skip_blanks();
        let mut at = self.pos;
        let negative = match self.peek() {
            Some(s @ (b'+' | b'-')) => {
                at += 1;
                while self.text.get(at).is_some_and(|&c| is_blank(c)) {
                    at += 1;
                }
                s == b'-'
            }
            _ => false,
        };
        if !matches!(self.text.get(at), Some(b'#' | b'[')) {
            return Ok(None);
        }
        if matches!(letter, b'N' | b'O') {
            return Err(format("N and O take no variables"));
        }
        let mut e = Eval::new(self.text, at, self.vars, self.rounding(letter));
        let v = nullable(e.primary()?)?;
        self.pos = e.pos;
        Ok(Some(v.map(|x| if negative { -x } else { x })))
    }

    /// How ROUND rounds in a word of `letter`: to the least input increment of the
    /// address (angles for C/H, lengths for every other address).
    fn rounding(&self, letter: u8) -> Rounding {
        let Some(f) = self.fmt else { return Rounding::Unknown };
        let step_e9 = if matches!(letter, b'C' | b'H') {
            f.increments.angle_udeg() * 1_000
        } else {
            f.increments.linear_nm(f.units) * 1_000_000_000 / f.units.nm_per_unit()
        };
        Rounding::Nc { step_e9 }
    }

    /// A signed decimal number after an address letter: at most 9 digits before the
    /// point (leading zeros not counted) and 9 after it.
    /// The caller has skipped the blanks before it.
    #[inline(always)]
    fn number(&mut self, letter: u8) -> Result<Number, AlarmKind> {
        let text = self.text;
        let mut i = self.pos;
        let negative = match text.get(i) {
            Some(b'-') => {
                i += 1;
                true
            }
            Some(b'+') => {
                i += 1;
                false
            }
            _ => false,
        };
        let first = i;
        while text.get(i) == Some(&b'0') {
            i += 1;
        }
        // Each part has at most 9 digits: it fits a u32 (more wrap, and are refused).
        let start = i;
        let int = digits(text, &mut i);
        if i - start > usize::from(MAX_INT_DIGITS) {
            return Err(AlarmKind::TooManyDigits { letter });
        }
        let has_point = text.get(i) == Some(&b'.');
        let mut mantissa = u64::from(int);
        let mut frac_digits = 0;
        if has_point {
            i += 1;
            let start = i;
            let frac = digits(text, &mut i);
            frac_digits = i - start;
            if frac_digits > usize::from(MAX_FRAC_DIGITS) {
                return Err(AlarmKind::TooManyDigits { letter });
            }
            if text.get(i) == Some(&b'.') {
                return Err(AlarmKind::IllegalDecimalPoint { letter });
            }
            mantissa = mantissa * POW10_U32[frac_digits] as u64 + u64::from(frac);
        }
        if i == first {
            return Err(AlarmKind::NoDataAfterAddress { letter });
        }
        self.pos = i;
        // At most 18 digits: below 10^18, which fits an i64.
        let mantissa = mantissa as i64;
        Ok(Number { mantissa: if negative { -mantissa } else { mantissa }, frac_digits: frac_digits as u8, has_point })
    }
}

/// Reads a SINUMERIK line of plain words only into `block` (issue 19's short
/// way, [`crate::lang::fanuc::check::sinumerik_plain`]): `[N…] word…`, each word
/// a letter right before its plain number ([`plain_number`]), blanks between
/// them, an optional `;` comment to the end. N only first and whole; G and M
/// whole numbers up to 999 without a point (G in tenths, as [`Block::g`] keeps
/// them). False for anything else — a name (DIAMON, `CR=`, a call, a label), `=`,
/// brackets, an expression, a string, a skip mark, a word given twice, more G or
/// M codes than the block holds —: the front end's general reader reads that
/// line, and raises its alarm. Which letters a line may use is the checker's.
#[cfg(feature = "siemens")]
pub fn read_plain_line(text: &[u8], line: u32, block: &mut Block) -> bool {
    block.clear(line);
    let mut i = 0;
    let mut first = true;
    loop {
        while text.get(i).is_some_and(|&c| is_blank(c)) {
            i += 1;
        }
        let Some(&c) = text.get(i) else { return true };
        if c == b';' {
            return true;
        }
        let letter = c & !0x20;
        if letter.wrapping_sub(b'A') >= 26 {
            return false;
        }
        let Some((n, end)) = plain_number(text, i + 1) else { return false };
        // G, M and N: as written, whole (the general reader refuses a point in them).
        let whole = (!n.has_point && (0..=999).contains(&n.mantissa)).then_some(n.mantissa as u16);
        let stored = match letter {
            // `N10` (`N-10`, `N+10`, `N10.` are the general reader's).
            b'N' => {
                let digit = text.get(i + 1).is_some_and(u8::is_ascii_digit);
                if !first || !digit || n.has_point {
                    return false;
                }
                block.seq = Some(n.mantissa as u32);
                true
            }
            b'G' => whole.is_some_and(|g| block.g.push(g * 10).is_ok()),
            b'M' => whole.is_some_and(|m| block.m.push(m).is_ok()),
            _ => block.set(letter, n),
        };
        if !stored {
            return false;
        }
        first = false;
        i = end;
    }
}

/// The plain number at `text[i]` (an optional sign, then digits with a point or
/// without; at most 9 digits before the point, leading zeros included, and 9
/// after it) and the index after it. `None` for anything else — no digits, a
/// second point, more digits, a macro value —, which [`Reader::number`] reads
/// (or refuses with its alarm): the same value where both read one.
#[inline(always)]
fn plain_number(text: &[u8], mut i: usize) -> Option<(Number, usize)> {
    let negative = match text.get(i) {
        Some(b'-') => {
            i += 1;
            true
        }
        Some(b'+') => {
            i += 1;
            false
        }
        _ => false,
    };
    let first = i;
    let int = digits(text, &mut i);
    let int_digits = i - first;
    let has_point = text.get(i) == Some(&b'.');
    let mut mantissa = u64::from(int);
    let mut frac_digits = 0;
    if has_point {
        i += 1;
        let start = i;
        let frac = digits(text, &mut i);
        frac_digits = i - start;
        if frac_digits > usize::from(MAX_FRAC_DIGITS) || text.get(i) == Some(&b'.') {
            return None;
        }
        mantissa = mantissa * POW10_U32[frac_digits] as u64 + u64::from(frac);
    } else if int_digits == 0 {
        return None;
    }
    if int_digits > usize::from(MAX_INT_DIGITS) {
        return None;
    }
    let mantissa = mantissa as i64;
    let mantissa = if negative { -mantissa } else { mantissa };
    Some((Number { mantissa, frac_digits: frac_digits as u8, has_point }, i))
}

/// `10^n` for the fraction digits of a word (0–9).
const POW10_U32: [u32; 10] = [1, 10, 100, 1_000, 10_000, 100_000, 1_000_000, 10_000_000, 100_000_000, 1_000_000_000];

/// A blank between and inside words: space, tab, CR (one compare for most bytes).
#[inline(always)]
fn is_blank(c: u8) -> bool {
    c == b' ' || c < b' ' && (1u32 << c) & (1 << b'\t' | 1 << b'\r') != 0
}

/// Reads the decimal digits from `text[*i]` on, returns their value (wrapping past
/// 9 digits: the caller refuses that many anyway).
#[inline(always)]
fn digits(text: &[u8], i: &mut usize) -> u32 {
    let mut v = 0u32;
    while let Some(&c) = text.get(*i) {
        let d = u32::from(c).wrapping_sub(u32::from(b'0'));
        if d > 9 {
            break;
        }
        v = v.wrapping_mul(10).wrapping_add(d);
        *i += 1;
    }
    v
}

/// A macro value as the word of `letter`. Addresses that take whole numbers
/// (M S T L P Q) get the value rounded to a whole number, G to one decimal; every
/// other address gets a real number (decimal point set, 9 decimals), which checking
/// rounds to the least input increment (2.24.1: #1=1.23456, X#1 → 1.235).
fn macro_number(letter: u8, v: f64) -> Result<Number, AlarmKind> {
    let too_big = AlarmKind::TooManyDigits { letter };
    match letter {
        b'G' => {
            let tenths = libm::round(v * 10.0);
            if tenths.abs() > MAX_WHOLE_VALUE {
                return Err(too_big);
            }
            Ok(Number { mantissa: tenths as i64, frac_digits: 1, has_point: true })
        }
        b'M' | b'S' | b'T' | b'L' | b'P' | b'Q' => {
            let w = libm::round(v);
            if w.abs() > MAX_WHOLE_VALUE {
                return Err(too_big);
            }
            Ok(Number::int(w as i64))
        }
        _ => Number::from_f64(v).ok_or(too_big),
    }
}

/// Argument specification I (FANUC 0i): the variable each address sets, 0 for the
/// addresses that are no arguments (G, L, N, O, P). I, J and K are the first
/// triple of specification II as well.
const SPEC_I: [u16; 26] = [1, 2, 3, 7, 8, 9, 0, 11, 4, 5, 6, 0, 13, 0, 0, 0, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26];

/// Most I/J/K triples of argument specification II.
const MAX_IJK_GROUPS: u16 = 10;

/// Which arguments a call block has given: type I letters once each; I, J, K in
/// triples (argument specification II: A B C, then up to ten I J K as #4–#33).
#[derive(Default)]
struct Arguments {
    /// Type I letters given, bit `letter - 'A'`.
    given: u32,
    /// The triple the last I/J/K went into.
    group: u16,
    /// The last of I (1), J (2), K (3) given; 0 before the first.
    last_ijk: u16,
}

impl Arguments {
    /// The variable address `letter` sets. An I, J or K starts a new triple unless
    /// it comes after the last one's letter in I J K order; a letter of
    /// specification I only once (alarm 4004); an eleventh triple is alarm 0129. Of
    /// two arguments for one variable the later one counts (`I4. D5.`: #7 = 5).
    fn variable(&mut self, letter: u8) -> Result<u16, AlarmKind> {
        let order = match letter {
            b'I' => 1,
            b'J' => 2,
            b'K' => 3,
            _ => {
                let bit = 1 << (letter - b'A');
                if self.given & bit != 0 {
                    return Err(AlarmKind::DuplicateAddress { letter });
                }
                self.given |= bit;
                return Ok(SPEC_I[usize::from(letter - b'A')]);
            }
        };
        if self.last_ijk != 0 && order <= self.last_ijk {
            self.group += 1;
        }
        if self.group >= MAX_IJK_GROUPS {
            return Err(AlarmKind::IllegalArgumentAddress { letter });
        }
        self.last_ijk = order;
        Ok(4 + 3 * self.group + order - 1)
    }
}

/// An argument written as a number. With a decimal point it is what is written;
/// without one a whole number (2.24.1: `#1=123` is 123.000) under calculator-type
/// input, and under least-increment input (parameter 3401 = 0) a count of the
/// address's least input increments, as FANUC 0i reads arguments: X Y Z U V W I J
/// K R in the linear increment (`X60` = 0.060 mm in IS-B), A B C in the angle
/// increment, the other addresses as written.
fn argument_value(n: &Number, letter: u8, fmt: Option<NumberFormat>) -> f64 {
    let Some(f) = fmt.filter(|f| !n.has_point && f.input == InputMode::LeastIncrement) else {
        return n.to_f64();
    };
    let per_unit = match letter {
        b'X' | b'Y' | b'Z' | b'U' | b'V' | b'W' | b'I' | b'J' | b'K' | b'R' => {
            f.units.nm_per_unit() / f.increments.linear_nm(f.units)
        }
        b'A' | b'B' | b'C' => 1_000_000 / f.increments.angle_udeg(),
        _ => 1,
    };
    let mut frac_digits = 0;
    let mut r = per_unit;
    while r >= 10 {
        r /= 10;
        frac_digits += 1;
    }
    Number { mantissa: n.mantissa, frac_digits, has_point: true }.to_f64()
}

fn set_once(slot: &mut Option<u32>, letter: u8, v: u32) -> Result<(), AlarmKind> {
    if slot.replace(v).is_some() { Err(AlarmKind::DuplicateAddress { letter }) } else { Ok(()) }
}

/// A G number in tenths: G1 → 10, G02.1 → 21, G12.1 → 121.
fn g_tenths(n: &Number) -> Result<u16, AlarmKind> {
    // The usual G01, G96, G02.1: no multiplication to check.
    match (n.frac_digits, n.mantissa) {
        (0, m @ 0..100) => return Ok(m as u16 * 10),
        (1, m @ 0..1000) => return Ok(m as u16),
        _ => {}
    }
    if n.is_negative() {
        return Err(AlarmKind::IllegalMinusSign { letter: b'G' });
    }
    let tenths = n.scaled(1).unwrap_or(i64::MAX);
    let shown = GNum(u16::try_from(tenths).unwrap_or(u16::MAX));
    // Fraction digits past the first must be zeros (G2.10 is G2.1; G2.15 is nothing);
    // three-digit codes (G290, G291) are looked up, the tables hold no longer ones.
    let exact = n.frac_digits <= 1 || n.scaled(n.frac_digits) == Some(tenths * pow10(n.frac_digits - 1).unwrap_or(0));
    if !exact || tenths >= 10_000 {
        return Err(AlarmKind::ImproperGCode { code: shown });
    }
    Ok(tenths as u16)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn n(m: i64, f: u8, p: bool) -> Number {
        Number { mantissa: m, frac_digits: f, has_point: p }
    }

    #[test]
    fn reads_words_with_and_without_points() {
        let b = read_block(b"N10 G01 X60 Z7. F500 ; ignored", 3);
        assert!(b.is_err(), "';' is split by the program layer, not the reader");
        let b = read_block(b"n10 g01 x60 z-7.25 f0.15 (cut) m03 s800 t0101", 3).unwrap();
        assert_eq!(b.line, 3);
        assert_eq!(b.seq, Some(10));
        assert_eq!(b.g.as_slice(), &[10]);
        assert_eq!(b.m.as_slice(), &[3]);
        assert_eq!(b.get(b'X'), Some(n(60, 0, false)));
        assert_eq!(b.get(b'Z'), Some(n(-725, 2, true)));
        assert_eq!(b.get(b'F'), Some(n(15, 2, true)));
        assert_eq!(b.get(b'T'), Some(n(101, 0, false)));
    }

    #[test]
    fn g_codes_with_fractions() {
        let b = read_block(b"G02.1 G12.1 G2", 1).unwrap();
        assert_eq!(b.g.as_slice(), &[21, 121, 20]);
        assert!(matches!(read_block(b"G2.15", 1), Err(AlarmKind::ImproperGCode { .. })));
        assert_eq!(read_block(b"G-1", 1), Err(AlarmKind::IllegalMinusSign { letter: b'G' }));
    }

    #[test]
    fn block_skip_comments_and_comma_words() {
        let b = read_block(b"/2 G01 X10 ,C1.5 ,r2", 1).unwrap();
        assert_eq!(b.skip_level, Some(2));
        assert_eq!(b.chamfer, Some(n(15, 1, true)));
        assert_eq!(b.corner, Some(n(2, 0, false)));
        assert!(read_block(b"  (only a comment)  ", 1).unwrap().is_empty());
    }

    #[test]
    fn malformed_blocks_raise_alarms() {
        use AlarmKind::*;
        assert_eq!(read_block(b"X", 1), Err(NoDataAfterAddress { letter: b'X' }));
        assert_eq!(read_block(b"X1 X2", 1), Err(DuplicateAddress { letter: b'X' }));
        assert_eq!(read_block(b"N1.5", 1), Err(IllegalDecimalPoint { letter: b'N' }));
        assert_eq!(read_block(b"M-3", 1), Err(IllegalMinusSign { letter: b'M' }));
        assert_eq!(read_block(b"X1.2.3", 1), Err(IllegalDecimalPoint { letter: b'X' }));
        assert_eq!(read_block(b"X1234567890", 1), Err(TooManyDigits { letter: b'X' }));
        assert_eq!(read_block(b"X1.0000000001", 1), Err(TooManyDigits { letter: b'X' }));
        assert_eq!(read_block(b"G01 (open", 1), Err(CommentNotClosed));
        assert_eq!(read_block(b"G01 X1 / Z2", 1), Err(MisplacedBlockSkip));
        assert_eq!(read_block(b"12", 1), Err(AddressNotFound { found: b'1' }));
        assert_eq!(read_block(b"G01 ?", 1), Err(IllegalCharacter { found: b'?' }));
        assert_eq!(read_block(b"M3 M8 M9 M5", 1), Err(TooManyMCodes));
        assert_eq!(read_block(b",Q1", 1), Err(ImproperAddress { letter: b'Q' }));
    }

    #[test]
    fn blanks_inside_words_and_leading_zeros() {
        let b = read_block(b"X 0000060.5", 1).unwrap();
        assert_eq!(b.get(b'X'), Some(n(605, 1, true)));
        let b = read_block(b"X.", 1).unwrap();
        assert_eq!(b.get(b'X'), Some(n(0, 0, true)));
    }
}

//! Reading: one block of program text into a [`Statement`]: either a [`Block`] of
//! NC words (macro values already substituted) or an evaluated macro statement.
//! What the words mean and whether they belong together is checked later.

mod reader;

#[cfg(feature = "siemens")]
pub use reader::read_plain_line;
pub use reader::{read_block, read_block_into, read_program_block, read_statement, read_statement_into, read_with};

use crate::alarm::AlarmKind;
use crate::lang::fanuc::calls::{CallBlock, SubCall};
use crate::lang::fanuc::macros::{Locals, MacroStatement};
use crate::units::Number;

/// What one block of program text is (2.24.2 notes 7 and 8).
///
/// The NC variant is large (a [`Block`] holds every address); without an allocator
/// there is nothing to box it into, and a statement lives only while its block runs.
#[derive(Clone, Debug, PartialEq)]
#[allow(clippy::large_enum_variant)]
pub enum Statement {
    /// An NC statement: words with plain values.
    Nc(Block),
    /// A macro statement, evaluated.
    Macro(MacroBlock),
    /// A macro call (G65, G66, G67, a G or M code that calls) with its arguments.
    Call(CallBlock, Locals),
}

impl Statement {
    /// The source line.
    pub fn line(&self) -> u32 {
        match self {
            Statement::Nc(b) => b.line,
            Statement::Macro(m) => m.line,
            Statement::Call(c, _) => c.line,
        }
    }
}

/// What [`read_statement_into`] found in a block's text.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Read {
    /// An NC statement: its words are in the block.
    Nc,
    /// A macro statement, evaluated (the block is left empty). A macro call is
    /// [`MacroStatement::Call`].
    Macro(MacroBlock),
}

/// A macro statement with what may stand before it: a skip mark and a sequence
/// number (note 10).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MacroBlock {
    /// 1-based source line.
    pub line: u32,
    /// Optional block skip level.
    pub skip_level: Option<u8>,
    /// Sequence number `N`.
    pub seq: Option<u32>,
    /// The statement.
    pub statement: MacroStatement,
}

/// The optional block skip level a block's text starts with (`/` = 1, `/2`…`/9`),
/// read without evaluating anything, so a skipped block is never evaluated.
pub fn skip_level(text: &[u8]) -> Option<u8> {
    let i = text.iter().position(|c| !matches!(c, b' ' | b'\t' | b'\r'))?;
    if text[i] != b'/' {
        return None;
    }
    Some(match text.get(i + 1) {
        Some(d @ b'1'..=b'9') => d - b'0',
        _ => 1,
    })
}

/// Most G codes one block may hold.
pub const MAX_G: usize = 8;
/// Most M codes one block may hold (alarm 4010 beyond).
pub use crate::command::MAX_M;

/// The words of one block, as written.
///
/// Kept in place and reused block after block: the address words sit in a fixed
/// array with a bit per letter saying which are present, so clearing a block is a
/// few stores and nothing large is copied per block.
#[derive(Clone, Debug, PartialEq)]
pub struct Block {
    /// 1-based source line.
    pub line: u32,
    /// Optional block skip level: `/` or `/1` = 1, `/2`…`/9`.
    pub skip_level: Option<u8>,
    /// Sequence number `N`.
    pub seq: Option<u32>,
    /// Program number `O`.
    pub program: Option<u32>,
    /// G codes in tenths (G01 = 10, G02.1 = 21), in order of appearance.
    pub g: heapless::Vec<u16, MAX_G>,
    /// M codes, in order of appearance.
    pub m: heapless::Vec<u16, MAX_M>,
    /// Bit `letter - 'A'` set when that address is given.
    present: u32,
    /// Values of the other addresses A–Z, meaningful where `present` says so.
    values: [Number; 26],
    /// `,C` chamfer.
    pub chamfer: Option<Number>,
    /// `,R` corner radius.
    pub corner: Option<Number>,
    /// Of `,C` and `,R`, `,R` was written last (2.23 note 9: the last one counts).
    pub corner_last: bool,
    /// A subprogram call by an M code (parameters 6071–6079) or a T code (6001#5),
    /// meaningful where [`SUB_CALL`] is set in `present`. The block holds an M98 in
    /// its place (checked and run as one, after the block's other codes); the code
    /// itself is not among the M codes or the T word.
    sub: SubCall,
}

/// The bit of `present` that says the block holds a subprogram call by an M or T
/// code (the letters take bits 0–25): clearing the block clears it with them, and a
/// block without one pays for nothing.
pub(crate) const SUB_CALL: u32 = 1 << 31;

/// The M code a subprogram call by an M or T code stands in the block as.
const M98: u16 = 98;

/// A T code that calls O9000 in a block with an M code that stops, ends, calls or
/// jumps.
pub(crate) const T_WITH_FLOW: AlarmKind = AlarmKind::WordNotAllowed {
    letter: b'T',
    context: "M codes that stop, end, call or jump while T codes call O9000 (parameter 6001)",
};

impl Default for Block {
    fn default() -> Self {
        Block {
            line: 0,
            skip_level: None,
            seq: None,
            program: None,
            g: heapless::Vec::new(),
            m: heapless::Vec::new(),
            present: 0,
            values: [Number::int(0); 26],
            chamfer: None,
            corner: None,
            corner_last: false,
            sub: SubCall { program: 0, m: 0, t: None },
        }
    }
}

impl Block {
    /// Empties the block for reuse with the text of `line`.
    pub fn clear(&mut self, line: u32) {
        self.line = line;
        self.skip_level = None;
        self.seq = None;
        self.program = None;
        self.g.clear();
        self.m.clear();
        self.present = 0;
        self.chamfer = None;
        self.corner = None;
        self.corner_last = false;
    }

    /// The value of address `letter` (uppercase ASCII), if given.
    pub fn get(&self, letter: u8) -> Option<Number> {
        let i = letter.wrapping_sub(b'A');
        (i < 26 && self.present & (1 << i) != 0).then(|| self.values[usize::from(i)])
    }

    /// The addresses given, bit `letter - 'A'` each (beyond N, O, G, M), and
    /// [`SUB_CALL`].
    #[inline]
    pub(crate) fn present(&self) -> u32 {
        self.present
    }

    /// The subprogram call by an M or T code the block holds, if any.
    #[inline]
    pub fn sub_call(&self) -> Option<SubCall> {
        (self.present & SUB_CALL != 0).then_some(self.sub)
    }

    /// Puts a subprogram call by an M or T code into the block, as an M98 (one per
    /// block, and none with another M code that stops, ends, calls or jumps).
    #[cold]
    #[inline(never)]
    pub(crate) fn set_sub_call(&mut self, call: SubCall) -> Result<(), AlarmKind> {
        if let Some(first) = self.sub_call() {
            return Err(match (first.t, call.t) {
                (Some(_), Some(_)) => AlarmKind::DuplicateAddress { letter: b'T' },
                (None, None) => AlarmKind::ConflictingMCodes { first: first.m, second: call.m },
                _ => T_WITH_FLOW,
            });
        }
        let flow = |m: &&u16| matches!(**m, 0 | 1 | 2 | 30 | 91 | 92 | 98 | 99);
        if let Some(&first) = self.m.iter().find(flow) {
            return Err(if call.t.is_some() {
                T_WITH_FLOW
            } else {
                AlarmKind::ConflictingMCodes { first, second: call.m }
            });
        }
        self.m.push(M98).map_err(|_| AlarmKind::TooManyMCodes)?;
        self.sub = call;
        self.present |= SUB_CALL;
        Ok(())
    }

    /// The value stored for address `letter` (uppercase ASCII), meaningful only
    /// where [`Block::present`] says it is given.
    #[inline]
    pub(crate) fn value(&self, letter: u8) -> Number {
        self.values.get(usize::from(letter.wrapping_sub(b'A'))).copied().unwrap_or(Number::int(0))
    }

    /// Whether address `letter` is given.
    pub fn has(&self, letter: u8) -> bool {
        self.get(letter).is_some()
    }

    /// The addresses given (beyond N, O, G, M), in alphabetical order.
    pub fn letters(&self) -> impl Iterator<Item = u8> + '_ {
        let mut bits = self.present & !SUB_CALL;
        core::iter::from_fn(move || {
            if bits == 0 {
                return None;
            }
            let i = bits.trailing_zeros();
            bits &= bits - 1;
            // `present` has bits 0–25 only: i < 26.
            Some(b'A' + i as u8)
        })
    }

    /// Sets address `letter` (uppercase ASCII); false if it was already set.
    pub(crate) fn set(&mut self, letter: u8, n: Number) -> bool {
        let i = letter - b'A';
        if self.present & (1 << i) != 0 {
            return false;
        }
        self.present |= 1 << i;
        self.values[usize::from(i)] = n;
        true
    }

    /// True if the block commands nothing (blank, comment only, or only N/O).
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.g.is_empty() && self.m.is_empty() && self.present == 0 && self.chamfer.is_none() && self.corner.is_none()
    }
}

/// A whole number written without sign or decimal point, at most `max` (N, O, M,
/// S, T, G04 P …); the alarm names the address.
pub(crate) fn whole(letter: u8, n: &Number, max: u32) -> Result<u32, AlarmKind> {
    if n.has_point {
        return Err(AlarmKind::IllegalDecimalPoint { letter });
    }
    if n.is_negative() {
        return Err(AlarmKind::IllegalMinusSign { letter });
    }
    u32::try_from(n.mantissa).ok().filter(|v| *v <= max).ok_or(AlarmKind::ValueOutOfRange { letter })
}

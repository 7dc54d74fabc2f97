//! Reading: one block of program text into a [`Statement`]: either a [`Block`] of
//! NC words (macro values already substituted) or an evaluated macro statement.
//! What the words mean and whether they belong together is checked later.

mod reader;

pub use reader::{read_block, read_block_into, read_statement, read_statement_into, read_with};

use crate::lang::fanuc::macros::MacroStatement;
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
}

impl Statement {
    /// The source line.
    pub fn line(&self) -> u32 {
        match self {
            Statement::Nc(b) => b.line,
            Statement::Macro(m) => m.line,
        }
    }
}

/// What [`read_statement_into`] found in a block's text.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Read {
    /// An NC statement: its words are in the block.
    Nc,
    /// A macro statement, evaluated (the block is left empty).
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
}

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

    /// The addresses given, bit `letter - 'A'` each (beyond N, O, G, M).
    #[inline]
    pub(crate) fn present(&self) -> u32 {
        self.present
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
        let mut bits = self.present;
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
    pub fn is_empty(&self) -> bool {
        self.g.is_empty() && self.m.is_empty() && self.present == 0 && self.chamfer.is_none() && self.corner.is_none()
    }
}

/// A whole number written without sign or decimal point, at most `max` (N, O, M,
/// S, T, G04 P …); the alarm names the address.
pub(crate) fn whole(letter: u8, n: &Number, max: u32) -> Result<u32, crate::alarm::AlarmKind> {
    use crate::alarm::AlarmKind;
    if n.has_point {
        return Err(AlarmKind::IllegalDecimalPoint { letter });
    }
    if n.is_negative() {
        return Err(AlarmKind::IllegalMinusSign { letter });
    }
    u32::try_from(n.mantissa).ok().filter(|v| *v <= max).ok_or(AlarmKind::ValueOutOfRange { letter })
}

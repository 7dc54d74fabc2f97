//! The block reader: bytes → words. Accepts lowercase, blanks between and inside
//! words (between address and value), comments in parentheses, a leading `/n`.

use super::Block;
use crate::alarm::AlarmKind;
use crate::alarm::GNum;
use crate::units::{Number, pow10};

/// Most digits before the decimal point.
const MAX_INT_DIGITS: u8 = 9;
/// Most digits after it (nanometres of a millimetre).
const MAX_FRAC_DIGITS: u8 = 9;

/// Reads one block's text (without its end-of-block character).
pub fn read_block(text: &[u8], line: u32) -> Result<Block, AlarmKind> {
    let mut block = Block::default();
    read_block_into(text, line, &mut block)?;
    Ok(block)
}

/// Reads one block's text into `block`, reusing its storage (the interpreter's
/// per-block path: nothing large is copied).
pub fn read_block_into(text: &[u8], line: u32, block: &mut Block) -> Result<(), AlarmKind> {
    block.clear(line);
    let mut r = Reader { text, pos: 0 };
    r.skip_blanks_and_comments()?;
    if r.peek() == Some(b'/') {
        r.pos += 1;
        block.skip_level = Some(match r.peek() {
            Some(d @ b'1'..=b'9') => {
                r.pos += 1;
                d - b'0'
            }
            _ => 1,
        });
    }
    loop {
        r.skip_blanks_and_comments()?;
        let Some(c) = r.next() else { return Ok(()) };
        match c.to_ascii_uppercase() {
            letter @ b'A'..=b'Z' => r.word(letter, block)?,
            b',' => r.comma_word(block)?,
            b'/' => return Err(AlarmKind::MisplacedBlockSkip),
            b'#' | b'[' | b'=' => {
                return Err(AlarmKind::NotSupportedYet { what: "macro variables and expressions" });
            }
            c @ (b'0'..=b'9' | b'+' | b'-' | b'.') => return Err(AlarmKind::AddressNotFound { found: c }),
            other => return Err(AlarmKind::IllegalCharacter { found: other }),
        }
    }
}

struct Reader<'a> {
    text: &'a [u8],
    pos: usize,
}

impl Reader<'_> {
    fn peek(&self) -> Option<u8> {
        self.text.get(self.pos).copied()
    }

    fn next(&mut self) -> Option<u8> {
        let c = self.peek()?;
        self.pos += 1;
        Some(c)
    }

    fn skip_blanks(&mut self) {
        while matches!(self.peek(), Some(b' ' | b'\t' | b'\r')) {
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

    /// Reads the value of `letter` and stores it in the block.
    fn word(&mut self, letter: u8, block: &mut Block) -> Result<(), AlarmKind> {
        let n = self.number(letter)?;
        match letter {
            b'G' => {
                let tenths = g_tenths(&n)?;
                block.g.push(tenths).map_err(|_| AlarmKind::ValueOutOfRange { letter })
            }
            b'M' => {
                let m = whole(letter, &n, 999)?;
                block.m.push(m as u16).map_err(|_| AlarmKind::TooManyMCodes)
            }
            b'N' => set_once(&mut block.seq, letter, whole(letter, &n, 99_999)?),
            b'O' => set_once(&mut block.program, letter, whole(letter, &n, 9_999)?),
            _ => {
                if letter == b'T' {
                    whole(letter, &n, 99_999_999)?;
                }
                if block.set(letter, n) { Ok(()) } else { Err(AlarmKind::DuplicateAddress { letter }) }
            }
        }
    }

    /// `,C` or `,R`.
    fn comma_word(&mut self, block: &mut Block) -> Result<(), AlarmKind> {
        self.skip_blanks();
        let letter =
            self.next().map(|c| c.to_ascii_uppercase()).ok_or(AlarmKind::NoDataAfterAddress { letter: b',' })?;
        let n = self.number(letter)?;
        let slot = match letter {
            b'C' => &mut block.chamfer,
            b'R' => &mut block.corner,
            _ => return Err(AlarmKind::ImproperAddress { letter }),
        };
        // 2.23 note 9: with several C/R in one block the last one is effective.
        *slot = Some(n);
        Ok(())
    }

    /// A signed decimal number after an address letter.
    fn number(&mut self, letter: u8) -> Result<Number, AlarmKind> {
        self.skip_blanks();
        if matches!(self.peek(), Some(b'#' | b'[')) {
            return Err(AlarmKind::NotSupportedYet { what: "macro variables and expressions" });
        }
        let negative = match self.peek() {
            Some(b'-') => {
                self.pos += 1;
                true
            }
            Some(b'+') => {
                self.pos += 1;
                false
            }
            _ => false,
        };
        let (mut mantissa, mut int_digits, mut frac_digits, mut has_point, mut any) = (0i64, 0u8, 0u8, false, false);
        while let Some(c) = self.peek() {
            match c {
                b'0'..=b'9' => {
                    any = true;
                    let significant = mantissa != 0 || c != b'0' || has_point;
                    if has_point {
                        frac_digits += 1;
                        if frac_digits > MAX_FRAC_DIGITS {
                            return Err(AlarmKind::TooManyDigits { letter });
                        }
                    } else if significant {
                        int_digits += 1;
                        if int_digits > MAX_INT_DIGITS {
                            return Err(AlarmKind::TooManyDigits { letter });
                        }
                    }
                    mantissa = mantissa * 10 + i64::from(c - b'0');
                }
                b'.' if !has_point => {
                    has_point = true;
                    any = true;
                }
                b'.' => return Err(AlarmKind::IllegalDecimalPoint { letter }),
                _ => break,
            }
            self.pos += 1;
        }
        if !any {
            return Err(AlarmKind::NoDataAfterAddress { letter });
        }
        if negative {
            mantissa = -mantissa;
        }
        Ok(Number { mantissa, frac_digits, has_point })
    }
}

fn set_once(slot: &mut Option<u32>, letter: u8, v: u32) -> Result<(), AlarmKind> {
    if slot.replace(v).is_some() { Err(AlarmKind::DuplicateAddress { letter }) } else { Ok(()) }
}

/// A non-negative whole number without decimal point, at most `max`.
fn whole(letter: u8, n: &Number, max: u32) -> Result<u32, AlarmKind> {
    if n.has_point {
        return Err(AlarmKind::IllegalDecimalPoint { letter });
    }
    if n.is_negative() {
        return Err(AlarmKind::IllegalMinusSign { letter });
    }
    u32::try_from(n.mantissa).ok().filter(|v| *v <= max).ok_or(AlarmKind::ValueOutOfRange { letter })
}

/// A G number in tenths: G1 → 10, G02.1 → 21, G12.1 → 121.
fn g_tenths(n: &Number) -> Result<u16, AlarmKind> {
    if n.is_negative() {
        return Err(AlarmKind::IllegalMinusSign { letter: b'G' });
    }
    let tenths = n.scaled(1).unwrap_or(i64::MAX);
    let shown = GNum(u16::try_from(tenths).unwrap_or(u16::MAX));
    // Fraction digits past the first must be zeros (G2.10 is G2.1; G2.15 is nothing).
    let exact = n.frac_digits <= 1 || n.scaled(n.frac_digits) == Some(tenths * pow10(n.frac_digits - 1).unwrap_or(0));
    if !exact || tenths >= 1000 {
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

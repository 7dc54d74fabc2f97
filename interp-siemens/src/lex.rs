//! Reading the characters of a SINUMERIK line: blanks, names, numbers, strings
//! and operators. A name begins with a letter, `_` or `$` (system variables) and
//! goes on with letters, digits and `_`; the bytes of UTF-8 characters count as
//! letters (the document's label `孔圆弧1:`). Keywords and names are compared
//! without regard to case.

use interp_core::alarm::{AlarmKind, SiemensAlarm as S};
use interp_core::program::lines::name_byte;
use interp_core::units::{Number, times_pow10};

/// Most digits a number may have before and after its point.
const MAX_DIGITS: u8 = 18;

/// The text of a statement (a line without its comment) and the place being read.
#[derive(Clone, Copy, Debug)]
pub struct Src<'a> {
    /// The text.
    pub t: &'a [u8],
    /// The next byte to read.
    pub i: usize,
}

/// A syntax error (alarm 12080) saying `what`.
pub fn syntax(what: &'static str) -> AlarmKind {
    S::SyntaxError { what }.into()
}

/// Whether `t[i]` opens or closes a string: a `"`, but not one written `'"'` (a
/// double quote inside a string, seed 001 lines 9990-10000).
pub fn quote_at(t: &[u8], i: usize) -> bool {
    t.get(i) == Some(&b'"') && !(i > 0 && t.get(i - 1) == Some(&b'\'') && t.get(i + 1) == Some(&b'\''))
}

/// The line without its `;` comment (a `;` inside a string is text).
pub fn strip_comment(t: &[u8]) -> &[u8] {
    let mut quoted = false;
    for (i, &c) in t.iter().enumerate() {
        match c {
            b'"' if quote_at(t, i) => quoted = !quoted,
            b';' if !quoted => return &t[..i],
            _ => {}
        }
    }
    t
}

impl<'a> Src<'a> {
    /// Reading `t` from its start.
    pub const fn new(t: &'a [u8]) -> Self {
        Src { t, i: 0 }
    }

    /// Skips blanks (and CR/tabs).
    #[inline]
    pub fn blanks(&mut self) {
        while matches!(self.t.get(self.i), Some(b' ' | b'\t' | b'\r')) {
            self.i += 1;
        }
    }

    /// The next byte after blanks, not consumed.
    #[inline]
    pub fn peek(&mut self) -> Option<u8> {
        self.blanks();
        self.t.get(self.i).copied()
    }

    /// The byte `k` places after the next one (no blanks skipped).
    #[inline]
    pub fn at(&self, k: usize) -> Option<u8> {
        self.t.get(self.i + k).copied()
    }

    /// Whether everything has been read (blanks aside).
    pub fn done(&mut self) -> bool {
        self.peek().is_none()
    }

    /// Consumes `c` if it comes next (after blanks).
    #[inline]
    pub fn eat(&mut self, c: u8) -> bool {
        if self.peek() == Some(c) {
            self.i += 1;
            true
        } else {
            false
        }
    }

    /// Consumes `c` or raises 12080 with `what`.
    pub fn expect(&mut self, c: u8, what: &'static str) -> Result<(), AlarmKind> {
        if self.eat(c) { Ok(()) } else { Err(syntax(what)) }
    }

    /// Whether a name starts at the next byte (after blanks).
    pub fn at_name(&mut self) -> bool {
        matches!(self.peek(), Some(c) if c.is_ascii_alphabetic() || c == b'_' || c == b'$' || c >= 0x80)
    }

    /// Reads a name (nothing if none starts here).
    pub fn name(&mut self) -> &'a [u8] {
        self.blanks();
        let s = self.i;
        if matches!(self.t.get(s), Some(&c) if c.is_ascii_alphabetic() || c == b'_' || c == b'$' || c >= 0x80) {
            self.i += 1;
            while self.t.get(self.i).is_some_and(|&c| name_byte(c)) {
                self.i += 1;
            }
        }
        &self.t[s..self.i]
    }

    /// The name that starts here, without consuming it.
    pub fn peek_name(&mut self) -> &'a [u8] {
        let save = self.i;
        let n = self.name();
        self.i = save;
        n
    }

    /// Consumes keyword `kw` if the next name is it (whole name, any case).
    pub fn keyword(&mut self, kw: &[u8]) -> bool {
        let save = self.i;
        if self.name().eq_ignore_ascii_case(kw) {
            true
        } else {
            self.i = save;
            false
        }
    }

    /// Whether digits (or a point and digits) start here: a number.
    pub fn at_number(&mut self) -> bool {
        match self.peek() {
            Some(c) if c.is_ascii_digit() => true,
            Some(b'.') => self.at(1).is_some_and(|c| c.is_ascii_digit()),
            _ => false,
        }
    }

    /// Reads an unsigned decimal number `123`, `1.5`, `.5`, `10.` exactly, with
    /// an optional exponent `EX3` (×10³).
    pub fn number(&mut self) -> Result<Number, AlarmKind> {
        self.blanks();
        let (mut mantissa, mut frac, mut digits, mut point) = (0i64, 0u8, 0u8, false);
        loop {
            match self.t.get(self.i) {
                Some(&d) if d.is_ascii_digit() => {
                    if digits == 0 && d == b'0' && !point {
                        // Leading zeros count for nothing.
                    } else {
                        digits += 1;
                        if digits > MAX_DIGITS {
                            return Err(S::ValueRange.into());
                        }
                        mantissa = mantissa * 10 + i64::from(d - b'0');
                        if point {
                            frac += 1;
                        }
                    }
                }
                Some(b'.') if !point => point = true,
                _ => break,
            }
            self.i += 1;
        }
        let mut n = Number { mantissa, frac_digits: frac, has_point: point };
        // `EX`: a power of ten (1.5EX3 = 1500).
        if matches!(self.t.get(self.i..self.i + 2), Some(e) if e.eq_ignore_ascii_case(b"EX"))
            && self.t.get(self.i + 2).is_some_and(|c| c.is_ascii_digit() || *c == b'-' || *c == b'+')
        {
            self.i += 2;
            let neg = self.t.get(self.i) == Some(&b'-');
            if matches!(self.t.get(self.i), Some(b'-' | b'+')) {
                self.i += 1;
            }
            let mut e: i32 = 0;
            while let Some(&d) = self.t.get(self.i).filter(|c| c.is_ascii_digit()) {
                e = (e * 10 + i32::from(d - b'0')).min(99);
                self.i += 1;
            }
            // One rounding: the mantissa times 10^(exponent − fraction digits).
            let v = times_pow10(n.mantissa as f64, if neg { -e } else { e } - i32::from(n.frac_digits));
            n = Number::from_f64(v).ok_or(AlarmKind::from(S::ValueRange))?;
        }
        Ok(n)
    }

    /// Reads a string `"…"` (the opening quote next); the contents without quotes.
    pub fn string(&mut self) -> Result<&'a [u8], AlarmKind> {
        self.expect(b'"', "string expected")?;
        let s = self.i;
        let n = (s..self.t.len())
            .position(|i| quote_at(self.t, i))
            .ok_or_else(|| syntax("string without its closing \""))?;
        self.i = s + n + 1;
        Ok(&self.t[s..s + n])
    }

    /// The rest of the text from here.
    pub fn rest(&self) -> &'a [u8] {
        self.t.get(self.i..).unwrap_or(&[])
    }
}

/// Whether `name` is `kw`, ignoring case.
#[inline]
pub fn is(name: &[u8], kw: &[u8]) -> bool {
    name.eq_ignore_ascii_case(kw)
}

/// Which of `words` `name` is (ignoring case), by index: keywords as data, one
/// comparison loop instead of one comparison in code per keyword.
#[inline(never)]
pub fn which(name: &[u8], words: &[&[u8]]) -> Option<usize> {
    words.iter().position(|w| is(name, w))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_names_and_strings() {
        let mut s = Src::new(b" 40.824 .5 007 10. 1.5EX3 ANFANG:ENDE \"a;b\" _ZSD[0] $TC_DP1");
        assert_eq!(s.number().unwrap(), Number { mantissa: 40_824, frac_digits: 3, has_point: true });
        assert_eq!(s.number().unwrap(), Number { mantissa: 5, frac_digits: 1, has_point: true });
        assert_eq!(s.number().unwrap(), Number { mantissa: 7, frac_digits: 0, has_point: false });
        assert_eq!(s.number().unwrap(), Number { mantissa: 10, frac_digits: 0, has_point: true });
        assert_eq!(s.number().unwrap().to_f64(), 1500.0);
        assert_eq!(s.name(), b"ANFANG");
        assert!(s.eat(b':'));
        assert!(s.keyword(b"ende"));
        assert_eq!(s.string().unwrap(), b"a;b");
        assert_eq!(s.name(), b"_ZSD");
        assert!(s.eat(b'['));
        assert_eq!(s.number().unwrap().mantissa, 0);
        assert!(s.eat(b']'));
        assert_eq!(s.name(), b"$TC_DP1");
        assert!(s.done());
        let mut z = Src::new(b"0.05 .005");
        assert_eq!(z.number().unwrap(), Number { mantissa: 5, frac_digits: 2, has_point: true });
        assert_eq!(z.number().unwrap(), Number { mantissa: 5, frac_digits: 3, has_point: true });
        assert_eq!(strip_comment(b"X1 ; c \"q\""), b"X1 ");
        assert_eq!(strip_comment(b"A=\"x;y\" ; c"), b"A=\"x;y\" ");
        assert_eq!(Src::new(b"\"open").string(), Err(syntax("string without its closing \"")));
        let mut u = Src::new("孔圆弧1: X".as_bytes());
        assert_eq!(u.name(), "孔圆弧1".as_bytes());
    }
}

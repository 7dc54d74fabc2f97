//! Program text: where blocks come from, and how a cursor walks through them.
//!
//! Programs live in memory as text (on the board, memory-mapped flash or the DNC
//! buffer; on the host, files). A [`ProgramStore`] hands out program texts; a
//! [`Cursor`] is a position in one of them; [`next_block`] cuts out the next block.

/// Identifies a program in a store: its O number (0 = the main program as loaded).
pub type ProgramId = u32;

/// Where the interpreter gets program text from.
pub trait ProgramStore {
    /// The text of program `id`, if stored.
    fn text(&self, id: ProgramId) -> Option<&[u8]>;
}

/// A store holding a single main program (id 0).
#[derive(Clone, Copy, Debug)]
pub struct SingleProgram<'a>(pub &'a [u8]);

impl ProgramStore for SingleProgram<'_> {
    fn text(&self, id: ProgramId) -> Option<&[u8]> {
        (id == 0).then_some(self.0)
    }
}

/// A position in a program text.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Cursor {
    /// Program being read.
    pub program: ProgramId,
    /// Byte offset of the next block.
    pub offset: usize,
    /// 1-based line number at `offset`.
    pub line: u32,
}

impl Cursor {
    /// The start of program `program`.
    pub const fn start(program: ProgramId) -> Self {
        Cursor { program, offset: 0, line: 1 }
    }
}

/// One block's text as it stands in the program.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RawBlock<'a> {
    /// The block without its end-of-block character.
    pub text: &'a [u8],
    /// 1-based source line.
    pub line: u32,
    /// The block is a `%` record mark.
    pub percent: bool,
}

/// Cuts the next block out of `text` at `cur` and advances the cursor past it.
///
/// A block ends at LF or `;` (a `;` inside a comment is comment text). `None` at the
/// end of the text. Blank blocks are returned too (they carry line numbers).
pub fn next_block<'a>(text: &'a [u8], cur: &mut Cursor) -> Option<RawBlock<'a>> {
    let start = cur.offset;
    if start >= text.len() {
        return None;
    }
    let line = cur.line;
    let mut in_comment = false;
    let mut end = start;
    while end < text.len() {
        match text[end] {
            b'\n' => break,
            b'(' => in_comment = true,
            b')' => in_comment = false,
            b';' if !in_comment => break,
            _ => {}
        }
        end += 1;
    }
    if end < text.len() && text[end] == b'\n' {
        cur.line += 1;
    }
    cur.offset = end + 1;
    let body = &text[start..end];
    let percent = body.iter().find(|b| !b.is_ascii_whitespace()) == Some(&b'%');
    Some(RawBlock { text: body, line, percent })
}

/// The cursor of the first block of `text` whose sequence number is `n`, searching
/// from the start. A sequence number counts only as the first word of a block
/// (after an optional `/` skip mark and blanks), as FANUC searches it.
pub fn find_sequence(text: &[u8], program: ProgramId, n: u32) -> Option<Cursor> {
    let mut cur = Cursor::start(program);
    loop {
        let at = cur;
        let block = next_block(text, &mut cur)?;
        if leading_sequence(block.text) == Some(n) {
            return Some(at);
        }
    }
}

/// The N number a block starts with, if any.
fn leading_sequence(text: &[u8]) -> Option<u32> {
    let mut i = 0;
    let skip = |i: &mut usize| {
        while *i < text.len() && matches!(text[*i], b' ' | b'\t' | b'\r') {
            *i += 1;
        }
    };
    skip(&mut i);
    if text.get(i) == Some(&b'/') {
        i += 1;
        if text.get(i).is_some_and(u8::is_ascii_digit) {
            i += 1;
        }
        skip(&mut i);
    }
    if !matches!(text.get(i), Some(b'N' | b'n')) {
        return None;
    }
    i += 1;
    skip(&mut i);
    let digits = text[i..].iter().take_while(|c| c.is_ascii_digit()).take(6);
    let mut v: u32 = 0;
    let mut any = false;
    for d in digits {
        v = v * 10 + u32::from(d - b'0');
        any = true;
    }
    any.then_some(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_end_at_lf_and_semicolon_with_lines_counted() {
        let t = b"%\nO0001;\nG00 X1 (a;b) Z2;G01 X3\r\n\nM30\n%";
        let mut c = Cursor::start(0);
        let mut got = heapless::Vec::<(&[u8], u32, bool), 16>::new();
        while let Some(b) = next_block(t, &mut c) {
            got.push((b.text, b.line, b.percent)).unwrap();
        }
        assert_eq!(got[0], (&b"%"[..], 1, true));
        assert_eq!(got[1], (&b"O0001"[..], 2, false));
        assert_eq!(got[2], (&b""[..], 2, false));
        assert_eq!(got[3], (&b"G00 X1 (a;b) Z2"[..], 3, false));
        assert_eq!(got[4], (&b"G01 X3\r"[..], 3, false));
        assert_eq!(got[5], (&b""[..], 4, false));
        assert_eq!(got[6], (&b"M30"[..], 5, false));
        assert_eq!(got[7], (&b"%"[..], 6, true));
        assert_eq!(got.len(), 8);
    }

    #[test]
    fn sequence_numbers_are_found_at_the_start_of_blocks_only() {
        let t = b"O1\nN10 G00 X1\nG01 N20 X2\n/ N30 X3\nN0040 X4;N50 X5\nN10 X6\n";
        assert_eq!(find_sequence(t, 0, 10), Some(Cursor { program: 0, offset: 3, line: 2 }));
        assert_eq!(find_sequence(t, 0, 20), None);
        assert_eq!(find_sequence(t, 0, 30).map(|c| c.line), Some(4));
        assert_eq!(find_sequence(t, 0, 40).map(|c| c.line), Some(5));
        let c = find_sequence(t, 0, 50).unwrap();
        assert_eq!((c.line, &t[c.offset..c.offset + 3]), (5, &b"N50"[..]));
    }
}

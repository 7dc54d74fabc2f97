//! Program text: where blocks come from, and how a cursor walks through them.
//!
//! Programs live in memory as text (on the board, memory-mapped flash or the DNC
//! buffer; on the host, files). A [`ProgramStore`] hands out program texts and
//! finds sequence numbers in them; [`ProgramIndex`] knows where programs and their
//! sequence numbers are, over text in RAM ([`ProgramMemory`]) or left in place
//! ([`ProgramArea`]: flash, host buffers); a [`Cursor`] is a position in a
//! program; [`next_block`] cuts out the next block.

pub mod lines;
mod memory;

pub use memory::{LoadError, NAMED_BASE, ProgramArea, ProgramIndex, ProgramMemory};

pub(crate) use crate::head::leading_sequence;

/// Identifies a program in a store: its O number (0 = a main program without one).
pub type ProgramId = u32;

/// Where the interpreter gets program text from.
///
/// Cursors of program `id` index into `text(id)`. The text may begin before the
/// program (several programs loaded from one file share the file's text, so line
/// numbers stay those of the file): [`ProgramStore::start`] says where the program
/// begins, and the text ends where the program ends.
pub trait ProgramStore {
    /// The text of program `id`, if stored.
    fn text(&self, id: ProgramId) -> Option<&[u8]>;

    /// Where program `id` begins, if stored.
    fn start(&self, id: ProgramId) -> Option<Cursor> {
        self.text(id).map(|_| Cursor::start(id))
    }

    /// The first block with sequence number `n` in program `from.program`, searching
    /// forward from `from` to the end of the program and then from its start (as
    /// FANUC searches a GOTO target). Pass the program's start to get the first `N n`
    /// of the program (M99 P, 3.1.7 note 3).
    ///
    /// The default scans the text; [`ProgramMemory`] looks it up in an index.
    fn find_sequence(&self, n: u32, from: Cursor) -> Option<Cursor> {
        let text = self.text(from.program)?;
        let start = self.start(from.program)?;
        scan_sequence(text, from, None, n).or_else(|| scan_sequence(text, start, Some(from.offset), n))
    }

    /// Where the SINUMERIK program (or PROC) called `name` begins, if stored: the
    /// start of a named program in memory, or a `PROC name` line in the text of a
    /// store that keeps whole files (the stream window). The default has none.
    fn find_named(&self, name: &[u8]) -> Option<Cursor> {
        let _ = name;
        None
    }

    /// Whether more text of program `id` may still arrive (a stream being sent):
    /// then a jump target or END not found yet may come, and the interpreter waits
    /// for it instead of letting its look-ahead go. The default: every text is
    /// complete.
    fn still_arriving(&self, id: ProgramId) -> bool {
        let _ = id;
        false
    }
}

impl<P: ProgramStore + ?Sized> ProgramStore for &P {
    fn text(&self, id: ProgramId) -> Option<&[u8]> {
        (**self).text(id)
    }

    fn start(&self, id: ProgramId) -> Option<Cursor> {
        (**self).start(id)
    }

    fn find_sequence(&self, n: u32, from: Cursor) -> Option<Cursor> {
        (**self).find_sequence(n, from)
    }

    fn still_arriving(&self, id: ProgramId) -> bool {
        (**self).still_arriving(id)
    }

    fn find_named(&self, name: &[u8]) -> Option<Cursor> {
        (**self).find_named(name)
    }
}

/// A store holding a single main program (id 0).
#[derive(Clone, Copy, Debug)]
pub struct SingleProgram<'a>(pub &'a [u8]);

impl ProgramStore for SingleProgram<'_> {
    fn text(&self, id: ProgramId) -> Option<&[u8]> {
        (id == 0).then_some(self.0)
    }

    /// A `PROC name` line in the text.
    fn find_named(&self, name: &[u8]) -> Option<Cursor> {
        lines::find_proc(self.0, Cursor::start(0), name)
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

/// The bytes [`next_block`] stops at: end of block, `;`, and the comment brackets.
const MARKS: [bool; 256] = {
    let mut t = [false; 256];
    t[b'\n' as usize] = true;
    t[b';' as usize] = true;
    t[b'(' as usize] = true;
    t[b')' as usize] = true;
    t
};

/// The high bit of each byte of `w` that is one [`next_block`] stops at (LF, `;`,
/// `(`, `)`): zero if none is. Above the first such byte a flag may be false (a
/// borrow), so only "any" and the lowest flag are exact.
#[inline(always)]
fn marks(w: u32) -> u32 {
    const ONES: u32 = 0x0101_0101;
    const HIGHS: u32 = 0x8080_8080;
    let zero = |x: u32| x.wrapping_sub(ONES) & !x & HIGHS;
    // `(` and `)` differ only in bit 0.
    zero(w ^ 0x0A0A_0A0A) | zero(w ^ 0x3B3B_3B3B) | zero((w | ONES) ^ 0x2929_2929)
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
    // Four bytes at a time up to the first that matters (most blocks hold none
    // but their end), then one table look-up per byte.
    for chunk in text[start..].chunks_exact(4) {
        let m = marks(u32::from_le_bytes([chunk[0], chunk[1], chunk[2], chunk[3]]));
        if m != 0 {
            // Straight to the first byte that matters (little-endian: lowest byte first).
            end += (m.trailing_zeros() / 8) as usize;
            break;
        }
        end += 4;
    }
    while let Some(&c) = text.get(end) {
        if MARKS[usize::from(c)] {
            match c {
                b'\n' => break,
                b'(' => in_comment = true,
                b')' => in_comment = false,
                _ if !in_comment => break,
                _ => {}
            }
        }
        end += 1;
    }
    if text.get(end) == Some(&b'\n') {
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
    scan_sequence(text, Cursor::start(program), None, n)
}

/// The first block of the program beginning at `start` in `text` whose sequence
/// number is `n` (a linear scan).
pub fn find_sequence_from(text: &[u8], start: Cursor, n: u32) -> Option<Cursor> {
    scan_sequence(text, start, None, n)
}

/// The first block from `cur` (up to byte `until`) whose sequence number is `n`.
fn scan_sequence(text: &[u8], mut cur: Cursor, until: Option<usize>, n: u32) -> Option<Cursor> {
    loop {
        let at = cur;
        if until.is_some_and(|u| at.offset >= u) {
            return None;
        }
        let block = next_block(text, &mut cur)?;
        if leading_sequence(block.text) == Some(n) {
            return Some(at);
        }
    }
}

/// Whether a block is an `O` program number block.
pub fn starts_program(text: &[u8]) -> bool {
    let i = text.iter().position(|c| !matches!(c, b' ' | b'\t' | b'\r')).unwrap_or(text.len());
    matches!(text.get(i), Some(b'O' | b'o'))
        && text.get(i + 1..).is_some_and(|r| r.iter().find(|c| **c != b' ').is_some_and(u8::is_ascii_digit))
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

    /// The four-bytes-at-a-time scan cuts blocks exactly as a byte-by-byte one,
    /// whatever the alignment of the marks and comments.
    #[test]
    fn blocks_are_cut_as_byte_by_byte() {
        fn reference<'a>(text: &'a [u8], cur: &mut Cursor) -> Option<(&'a [u8], u32)> {
            let start = cur.offset;
            if start >= text.len() {
                return None;
            }
            let (mut end, mut in_comment) = (start, false);
            while let Some(&c) = text.get(end) {
                match c {
                    b'\n' => break,
                    b'(' => in_comment = true,
                    b')' => in_comment = false,
                    b';' if !in_comment => break,
                    _ => {}
                }
                end += 1;
            }
            let line = cur.line;
            if text.get(end) == Some(&b'\n') {
                cur.line += 1;
            }
            cur.offset = end + 1;
            Some((&text[start..end], line))
        }
        let alphabet = b"G1 X.;\n()%\r(;)";
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        let mut text = [0u8; 40];
        let mut cut = 0;
        for _ in 0..20_000 {
            let len = (next() % 41) as usize;
            for b in text.iter_mut().take(len) {
                *b = alphabet[(next() % alphabet.len() as u64) as usize];
            }
            let t = &text[..len];
            let (mut a, mut b) = (Cursor::start(0), Cursor::start(0));
            loop {
                let got = next_block(t, &mut a).map(|r| (r.text, r.line));
                assert_eq!(got, reference(t, &mut b), "{t:?}");
                assert_eq!(a, b);
                if got.is_none() {
                    break;
                }
                cut += 1;
            }
        }
        assert!(cut > 50_000, "{cut} blocks cut");
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

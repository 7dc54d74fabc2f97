//! SINUMERIK program text: a block is one line (LF ends it, a CR before it is
//! dropped; `;` starts a comment, which the reader strips), programs are named —
//! by a `%_N_NAME_MPF` / `%_N_NAME_SPF` header, by their `PROC NAME` statement or
//! after the file they come from — and one file may hold several (a main program
//! followed by the PROCs it calls, as the document prints CYCLE95's example).

use super::{Cursor, RawBlock};

/// Cuts the line at `cur` out of `text` and advances the cursor past its LF.
/// `None` at the end of the text. The line is returned without LF and CR.
#[inline]
pub fn next_line<'a>(text: &'a [u8], cur: &mut Cursor) -> Option<RawBlock<'a>> {
    let start = cur.offset;
    let rest = text.get(start..).filter(|r| !r.is_empty())?;
    let line = cur.line;
    let (body, step) = match rest.iter().position(|&b| b == b'\n') {
        Some(n) => {
            cur.line += 1;
            (&rest[..n], n + 1)
        }
        None => (rest, rest.len()),
    };
    cur.offset = start + step;
    let body = body.strip_suffix(b"\r").unwrap_or(body);
    let percent = body.first() == Some(&b'%');
    Some(RawBlock { text: body, line, percent })
}

/// Skips blanks.
fn blanks(t: &[u8], mut i: usize) -> usize {
    while matches!(t.get(i), Some(b' ' | b'\t')) {
        i += 1;
    }
    i
}

/// Whether `c` may stand in a name (ASCII letters, digits, `_`, and the bytes of
/// UTF-8 characters: the document names a label `孔圆弧1`).
#[inline]
pub fn name_byte(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_' || c >= 0x80
}

/// Where the statement of a line begins: after blanks, a `/n` skip mark, an `N`
/// number (or a `:n` main block number) and blanks.
pub fn after_block_number(t: &[u8]) -> usize {
    let mut i = blanks(t, 0);
    if t.get(i) == Some(&b'/') {
        i += 1;
        if t.get(i).is_some_and(u8::is_ascii_digit) {
            i += 1;
        }
        i = blanks(t, i);
    }
    if matches!(t.get(i), Some(b'N' | b'n' | b':')) && t.get(i + 1).is_some_and(u8::is_ascii_digit) {
        i += 1;
        while t.get(i).is_some_and(u8::is_ascii_digit) {
            i += 1;
        }
        i = blanks(t, i);
    }
    i
}

/// The `N` number a line starts with (after blanks and a skip mark).
pub fn line_number(t: &[u8]) -> Option<u32> {
    let mut i = blanks(t, 0);
    if t.get(i) == Some(&b'/') {
        i = blanks(t, i + 1 + usize::from(t.get(i + 1).is_some_and(u8::is_ascii_digit)));
    }
    if !matches!(t.get(i), Some(b'N' | b'n')) {
        return None;
    }
    let digits = t.get(i + 1..)?.iter().take_while(|c| c.is_ascii_digit());
    let mut n: u32 = 0;
    let mut any = false;
    for d in digits {
        n = n.saturating_mul(10).saturating_add(u32::from(d - b'0'));
        any = true;
    }
    any.then_some(n)
}

/// The name of a `%_N_NAME_MPF` / `%_N_NAME_SPF` header line.
pub fn header_name(t: &[u8]) -> Option<&[u8]> {
    let rest = t.strip_prefix(b"%_N_")?;
    let end = rest.iter().position(|&c| !name_byte(c)).unwrap_or(rest.len());
    let name = &rest[..end];
    let (stem, ext) = name.split_at(name.len().checked_sub(4).filter(|&k| k > 0)?);
    (ext.eq_ignore_ascii_case(b"_MPF") || ext.eq_ignore_ascii_case(b"_SPF")).then_some(stem)
}

/// The name a `PROC NAME …` line defines (the statement after the block number).
pub fn proc_name(t: &[u8]) -> Option<&[u8]> {
    let i = after_block_number(t);
    let kw = t.get(i..i + 4)?;
    if !kw.eq_ignore_ascii_case(b"PROC") || t.get(i + 4).is_some_and(|&c| name_byte(c)) {
        return None;
    }
    let s = blanks(t, i + 4);
    let n = t[s..].iter().take_while(|&&c| name_byte(c)).count();
    (n > 0 && !t[s].is_ascii_digit()).then(|| &t[s..s + n])
}

/// Whether a line holds a statement (anything but blanks, a comment, a header or
/// `; $PATH=` line).
pub fn has_statement(t: &[u8]) -> bool {
    let i = blanks(t, 0);
    !matches!(t.get(i), None | Some(b';' | b'%'))
}

/// The first `PROC name` line of `text` from `from` on (a PROC in the same text as
/// its caller: a streamed file, a single-text store).
pub fn find_proc(text: &[u8], from: Cursor, name: &[u8]) -> Option<Cursor> {
    let mut cur = from;
    loop {
        let at = cur;
        let line = next_line(text, &mut cur)?;
        if proc_name(line.text).is_some_and(|n| n.eq_ignore_ascii_case(name)) {
            return Some(at);
        }
    }
}

/// One program of a SINUMERIK file: its name (empty if the file's first program
/// has none of its own) and where it begins and ends.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NamedProgram<'a> {
    /// From its header or PROC line.
    pub name: &'a [u8],
    /// Its first line (its header, or its first line after the previous program).
    pub start: Cursor,
    /// Offset of its end (the start of the next program, or the end of the text).
    pub end: usize,
}

/// Splits a SINUMERIK file into its programs: a `%_N_…` header always begins a
/// program; a `PROC` line begins one unless the program so far has no statement
/// (then it names that program: header and comments before `PROC` belong to it).
/// Calls `each` for every program in order.
pub fn split_programs<'a, E>(text: &'a [u8], mut each: impl FnMut(NamedProgram<'a>) -> Result<(), E>) -> Result<(), E> {
    let mut cur = Cursor::start(0);
    let mut open = NamedProgram { name: &[], start: cur, end: 0 };
    let mut statements = false;
    let mut any_line = false;
    loop {
        let at = cur;
        let Some(line) = next_line(text, &mut cur) else { break };
        let header = header_name(line.text);
        let proc = proc_name(line.text);
        let begins = header.is_some() || (proc.is_some() && statements);
        if begins && any_line {
            open.end = at.offset;
            each(open)?;
            open = NamedProgram { name: &[], start: at, end: 0 };
            statements = false;
        }
        any_line = true;
        if let Some(n) = header {
            open.name = n;
        } else if let Some(n) = proc {
            open.name = n;
            statements = true;
        } else if has_statement(line.text) {
            statements = true;
        }
    }
    open.end = text.len();
    each(open)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_end_at_lf_and_keep_their_numbers() {
        let t = b"N10 G1 X1 ; a;b\r\n\nM30";
        let mut c = Cursor::start(0);
        let a = next_line(t, &mut c).unwrap();
        assert_eq!((a.text, a.line), (&b"N10 G1 X1 ; a;b"[..], 1));
        assert_eq!(next_line(t, &mut c).unwrap().text, b"");
        let m = next_line(t, &mut c).unwrap();
        assert_eq!((m.text, m.line), (&b"M30"[..], 3));
        assert_eq!(next_line(t, &mut c), None);
    }

    #[test]
    fn names_come_from_headers_and_procs() {
        assert_eq!(header_name(b"%_N_KONTUR_1_SPF"), Some(&b"KONTUR_1"[..]));
        assert_eq!(header_name(b"%_N_TSTCYC71_MPF ; comment"), Some(&b"TSTCYC71"[..]));
        assert_eq!(header_name(b"%_N_COMMON_COM"), None);
        assert_eq!(header_name(b"%"), None);
        assert_eq!(proc_name(b"PROC KONTUR_1 ; start"), Some(&b"KONTUR_1"[..]));
        assert_eq!(proc_name(b"N5 PROC ZYKL1 (REAL PAR1)"), Some(&b"ZYKL1"[..]));
        assert_eq!(proc_name(b"PROC CYC_832T(INT _ASVS,VAR INT _FACTOR) SAVE"), Some(&b"CYC_832T"[..]));
        assert_eq!(proc_name(b"PROCEED X1"), None);
        assert_eq!(line_number(b" N120 Z112"), Some(120));
        assert_eq!(line_number(b"MA1: G91 Z20"), None);
        assert_eq!(after_block_number(b"N50 MA1: G91"), 4);
    }

    #[test]
    fn a_file_splits_into_its_programs() {
        // CYCLE95's first example as printed: the main program, then PROC KONTUR_1.
        let t = b"DEF STRING[8] UPNAME\nN10 G0 X81\nN50 M30\nPROC KONTUR_1\nN100 G1 Z120 X37\nN220 M17\n\
%_N_ZYKL1_SPF\n; $PATH=/_N_CUS_DIR\nPROC ZYKL1 (REAL PAR1)\nM17\n";
        let mut got = heapless::Vec::<NamedProgram<'_>, 4>::new();
        split_programs(t, |p| got.push(p).map_err(|_| ())).unwrap();
        assert_eq!(got.len(), 3);
        assert_eq!((got[0].name, got[0].start.line), (&b""[..], 1));
        assert_eq!((got[1].name, got[1].start.line), (&b"KONTUR_1"[..], 4));
        assert_eq!(&t[got[1].start.offset..got[1].end], b"PROC KONTUR_1\nN100 G1 Z120 X37\nN220 M17\n");
        assert_eq!((got[2].name, got[2].start.line, got[2].end), (&b"ZYKL1"[..], 7, t.len()));
    }
}

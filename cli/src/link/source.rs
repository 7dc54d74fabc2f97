//! A program file as the lines that go over the link.
//!
//! The text goes as it is, line by line, with CR dropped, except the tape marks:
//! in grbl mode the leading `%` line is sent as an empty comment `()` (a `%` line would
//! switch the board to tape mode; the empty line keeps the board's line numbers
//! equal to the file's), in tape mode the program's own `%` lines are left out (the
//! sender adds its own). A `%` line after the first block ends the program: what
//! follows it is not sent. Before anything is sent every line is checked: only
//! printable ASCII and TAB (a `?`, `!` or `~` would act as a real-time command,
//! other bytes are refused by the board), at most 127 characters.

use std::path::Path;

/// One line to send and where it came from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SourceLine {
    /// 1-based line of the file.
    pub file_line: usize,
    /// The text, without line end.
    pub text: String,
}

/// The program's lines between its tape marks.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Source {
    /// The file's name as given, for messages.
    pub name: String,
    /// File line of the leading `%` (0: none); blank lines may come before it.
    pub leading_percent: usize,
    /// The lines to send, tape marks left out.
    pub lines: Vec<SourceLine>,
}

/// A line that cannot be sent, with the reason.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BadLine {
    /// 1-based line of the file.
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

/// The longest line the board takes, LF not counted.
pub const MAX_LINE: usize = 127;

impl Source {
    /// Reads `path`.
    pub fn read(path: &Path) -> Result<Source, crate::Error> {
        let bytes = std::fs::read(path).map_err(|source| crate::Error::Read { path: path.to_owned(), source })?;
        let name = path.display().to_string();
        Source::parse(&name, &bytes).map_err(|b| crate::Error::Unsendable {
            path: path.to_owned(),
            line: b.line,
            message: b.message,
        })
    }

    /// Splits `bytes` into lines and checks them.
    pub fn parse(name: &str, bytes: &[u8]) -> Result<Source, BadLine> {
        let mut src = Source { name: name.to_owned(), leading_percent: 0, lines: Vec::new() };
        let mut pieces: Vec<&[u8]> = bytes.split(|&b| b == b'\n').collect();
        if pieces.last().is_some_and(|l| l.is_empty()) {
            pieces.pop();
        }
        for (i, raw) in pieces.into_iter().enumerate() {
            let text = clean(raw).map_err(|message| BadLine { line: i + 1, message })?;
            if text.trim() == "%" {
                if src.lines.iter().all(|l| l.text.trim().is_empty()) && src.leading_percent == 0 {
                    src.leading_percent = i + 1;
                    src.lines.clear();
                    continue;
                }
                break;
            }
            src.lines.push(SourceLine { file_line: i + 1, text });
        }
        Ok(src)
    }

    /// The lines for grbl streaming: the leading `%` as an empty line, so stream
    /// line k is file line k — except that the first line goes as an empty comment
    /// `()` when it is blank: the board neither starts nor numbers a job with blank
    /// lines (a sender's wake-up `\r\n\r\n`), so a blank first line would shift
    /// the line numbers.
    pub fn stream_lines(&self) -> Vec<SourceLine> {
        let blanks = (1..=self.leading_percent).map(|n| SourceLine { file_line: n, text: String::new() });
        let mut lines: Vec<SourceLine> = blanks.chain(self.lines.iter().cloned()).collect();
        if let Some(first) = lines.first_mut().filter(|l| l.text.trim().is_empty()) {
            first.text = "()".into();
        }
        lines
    }

    /// The program number of the first block when it is `O<digits>`.
    pub fn o_number(&self) -> Option<u32> {
        self.first_block().and_then(|l| split_o(&l.text)).map(|(n, _)| n)
    }

    /// The first line that is not blank.
    fn first_block(&self) -> Option<&SourceLine> {
        self.lines.iter().find(|l| !l.text.trim().is_empty())
    }

    /// The lines for drip-feeding in tape mode: a leading `O` number is left out
    /// of its block (an `O` first makes the board store the program instead of
    /// running it); the line stays, so line numbers do not move.
    pub fn drip_lines(&self) -> Vec<SourceLine> {
        let first = self.first_block().map(|l| l.file_line);
        self.lines
            .iter()
            .map(|l| match split_o(&l.text) {
                Some((_, rest)) if Some(l.file_line) == first => {
                    SourceLine { file_line: l.file_line, text: rest.into() }
                }
                _ => l.clone(),
            })
            .collect()
    }

    /// The lines for punching into memory as program `number`: the first block's
    /// `O` word replaced by `O<number>` (4 digits), or an `O<number>` line put first
    /// when the program has none.
    pub fn upload_lines(&self, number: u32) -> Vec<SourceLine> {
        let o = format!("O{number:04}");
        let first = self.first_block().map(|l| l.file_line);
        let mut lines: Vec<SourceLine> = self
            .lines
            .iter()
            .map(|l| match split_o(&l.text) {
                Some((_, rest)) if Some(l.file_line) == first => {
                    SourceLine { file_line: l.file_line, text: format!("{o}{rest}") }
                }
                _ => l.clone(),
            })
            .collect();
        if self.o_number().is_none() {
            lines.insert(0, SourceLine { file_line: 0, text: o });
        }
        lines
    }
}

/// `O<digits>` at the start of `text` (blanks before it allowed): the number and the rest.
fn split_o(text: &str) -> Option<(u32, &str)> {
    let t = text.trim_start();
    let rest = t.strip_prefix('O').or_else(|| t.strip_prefix('o'))?;
    let digits = rest.bytes().take_while(u8::is_ascii_digit).count();
    let (num, after) = rest.split_at(digits);
    Some((num.parse().ok()?, after))
}

/// A raw line with CR dropped, or why it cannot be sent.
fn clean(raw: &[u8]) -> Result<String, String> {
    let text: Vec<u8> = raw.iter().copied().filter(|&b| b != b'\r').collect();
    if let Some((col, &b)) = text.iter().enumerate().find(|(_, b)| !sendable(**b)) {
        let what = match b {
            b'?' | b'!' | b'~' => format!("`{}` acts as a real-time command on the link", b as char),
            _ => format!("byte 0x{b:02X} is not printable ASCII"),
        };
        return Err(format!("column {}: {what}; remove it before sending", col + 1));
    }
    if text.len() > MAX_LINE {
        return Err(format!("{} characters; the board takes at most {MAX_LINE} per line", text.len()));
    }
    Ok(String::from_utf8_lossy(&text).into_owned())
}

/// Whether `b` may go inside a line.
fn sendable(b: u8) -> bool {
    (b == b'\t' || (0x20..0x7F).contains(&b)) && !matches!(b, b'?' | b'!' | b'~')
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texts(lines: &[SourceLine]) -> Vec<(usize, &str)> {
        lines.iter().map(|l| (l.file_line, l.text.as_str())).collect()
    }

    #[test]
    fn tape_marks_are_replaced_or_left_out_and_the_rest_goes_as_it_is() {
        let s = Source::parse("p.nc", b"%\r\nO0012 (SHAFT)\r\n\r\nG00 X20\nM30\n%\ntrailing text\n").unwrap();
        assert_eq!(s.leading_percent, 1);
        assert_eq!(s.o_number(), Some(12));
        assert_eq!(
            texts(&s.stream_lines()),
            vec![(1, "()"), (2, "O0012 (SHAFT)"), (3, ""), (4, "G00 X20"), (5, "M30")]
        );
        assert_eq!(texts(&s.drip_lines()), vec![(2, " (SHAFT)"), (3, ""), (4, "G00 X20"), (5, "M30")]);
        assert_eq!(texts(&s.upload_lines(7)), vec![(2, "O0007 (SHAFT)"), (3, ""), (4, "G00 X20"), (5, "M30")]);
    }

    #[test]
    fn a_program_without_marks_or_o_number() {
        let s = Source::parse("p.nc", b"G00 X20\nM30").unwrap();
        assert_eq!(s.leading_percent, 0);
        assert_eq!(s.o_number(), None);
        assert_eq!(texts(&s.stream_lines()), vec![(1, "G00 X20"), (2, "M30")]);
        assert_eq!(texts(&s.upload_lines(5)), vec![(0, "O0005"), (1, "G00 X20"), (2, "M30")]);
    }

    #[test]
    fn real_time_characters_non_ascii_and_long_lines_are_refused_with_their_line() {
        let e = Source::parse("p.nc", b"G00 X20\n(WHY?)\n").unwrap_err();
        assert_eq!(e.line, 2);
        assert_eq!(e.message, "column 5: `?` acts as a real-time command on the link; remove it before sending");
        let e = Source::parse("p.nc", "G00 X20 (粗车)\n".as_bytes()).unwrap_err();
        assert_eq!((e.line, e.message.starts_with("column 10: byte 0xE7")), (1, true));
        let long = format!("G01 X1\n{}\n", "X".repeat(128));
        assert_eq!(Source::parse("p.nc", long.as_bytes()).unwrap_err().line, 2);
        assert!(Source::parse("p.nc", "X".repeat(127).as_bytes()).is_ok());
    }
}

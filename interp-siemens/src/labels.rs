//! Finding where a jump, a REPEAT or a contour goes: labels (`NAME:` at the
//! start of a line, after its block number) and block numbers (`N100`), searched
//! within one program level — from its start (its PROC line, or the program's
//! first line) to its end (the next PROC line of the same text, or the end of
//! the text). GOTOF searches forward from the line after the jump, GOTOB backward
//! from the jump's line, GOTO/GOTOC forward first, then backward.

use crate::read::Dir;
use interp_core::program::Cursor;
use interp_core::program::lines::{after_block_number, line_number, name_byte, next_line, proc_name};

/// The label a line carries, if any.
pub fn label_of(t: &[u8]) -> Option<&[u8]> {
    let t = crate::lex::strip_comment(t);
    let i = after_block_number(t);
    let n = t[i..].iter().take_while(|&&c| name_byte(c)).count();
    (n > 0 && t.get(i + n) == Some(&b':') && !t[i].is_ascii_digit()).then(|| &t[i..i + n])
}

/// Whether line `t` is the target `target`: a label of that name, or the block
/// number `N…` written as the target.
fn is_target(t: &[u8], target: &[u8]) -> bool {
    if let Some(l) = label_of(t)
        && l.eq_ignore_ascii_case(target)
    {
        return true;
    }
    let digits = target.strip_prefix(b"N").or_else(|| target.strip_prefix(b"n")).unwrap_or(target);
    if digits.is_empty() || !digits.iter().all(u8::is_ascii_digit) || digits.len() > 9 {
        return false;
    }
    let n = digits.iter().fold(0u32, |a, d| a * 10 + u32::from(d - b'0'));
    line_number(t) == Some(n)
}

/// One program level of a text: where it starts (its PROC line or first line).
#[derive(Clone, Copy, Debug)]
pub struct Level<'a> {
    /// The text (of the file the program is in).
    pub text: &'a [u8],
    /// The level's first line.
    pub start: Cursor,
}

impl<'a> Level<'a> {
    /// The first target line from `from` up to the level's end.
    pub fn forward(&self, from: Cursor, target: &[u8]) -> Option<Cursor> {
        let mut cur = from;
        loop {
            let at = cur;
            let line = next_line(self.text, &mut cur)?;
            if at.offset > self.start.offset && proc_name(line.text).is_some() {
                return None;
            }
            if is_target(line.text, target) {
                return Some(at);
            }
        }
    }

    /// The last target line from the level's start up to (not including) `before`.
    pub fn backward(&self, before: Cursor, target: &[u8]) -> Option<Cursor> {
        let mut cur = self.start;
        let mut found = None;
        while cur.offset < before.offset {
            let at = cur;
            let Some(line) = next_line(self.text, &mut cur) else { break };
            if is_target(line.text, target) {
                found = Some(at);
            }
        }
        found
    }

    /// Where a jump from the line at `line` (the cursor after it: `after`) goes.
    pub fn jump(&self, dir: Dir, line: Cursor, after: Cursor, target: &[u8]) -> Option<Cursor> {
        match dir {
            Dir::Forward => self.forward(after, target),
            Dir::Backward => self.backward(line, target),
            Dir::Both | Dir::BothQuiet => self.forward(after, target).or_else(|| self.backward(line, target)),
        }
    }

    /// A label anywhere in the level (a contour range, a REPEAT section):
    /// backward from `at` first, then forward (the 840D's order for REPEAT).
    pub fn anywhere(&self, at: Cursor, target: &[u8]) -> Option<Cursor> {
        self.backward(at, target).or_else(|| self.forward(at, target))
    }
}

/// The cursor after the line at `at`.
pub fn after_line(text: &[u8], at: Cursor) -> Cursor {
    let mut c = at;
    let _ = next_line(text, &mut c);
    c
}

/// The first line from `from` whose label is ENDLABEL, before `until`.
pub fn end_label(text: &[u8], from: Cursor, until: usize) -> Option<Cursor> {
    let mut cur = from;
    while cur.offset < until {
        let at = cur;
        let line = next_line(text, &mut cur)?;
        if label_of(line.text).is_some_and(|l| l.eq_ignore_ascii_case(b"ENDLABEL")) {
            return Some(at);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    const T: &[u8] = b"N10 G0 X1\nMA1: G91 Z20\nN30 X2\nIF R1<6 GOTOB MA1\nGOTOF ENDE ; skip\nANFANG:\nN180 G1 X10\nENDE:\nN230 M02\nPROC OTHER\nENDE: M17\n";

    #[test]
    fn labels_and_block_numbers_are_found_within_the_level() {
        let lvl = Level { text: T, start: Cursor::start(0) };
        assert_eq!(label_of(b"N50 MA1: G91 Z20"), Some(&b"MA1"[..]));
        assert_eq!(label_of(b"_ENDE:M2"), Some(&b"_ENDE"[..]));
        assert_eq!(label_of(b"G1 X1 ; A: b"), None);
        assert_eq!(label_of(b"N10 X1"), None);
        let ifline = lvl.forward(Cursor::start(0), b"X").map(|c| c.line);
        assert_eq!(ifline, None);
        let at = Cursor { program: 0, offset: 30, line: 4 };
        assert_eq!(&T[at.offset..at.offset + 2], b"IF");
        let after = after_line(T, at);
        assert_eq!(lvl.jump(Dir::Backward, at, after, b"MA1").map(|c| c.line), Some(2));
        assert_eq!(lvl.jump(Dir::Forward, at, after, b"MA1"), None);
        assert_eq!(lvl.jump(Dir::Forward, at, after, b"ende").map(|c| c.line), Some(8), "not the PROC's");
        assert_eq!(lvl.jump(Dir::Both, at, after, b"MA1").map(|c| c.line), Some(2));
        assert_eq!(lvl.jump(Dir::Forward, at, after, b"N180").map(|c| c.line), Some(7));
        assert_eq!(lvl.anywhere(at, b"ANFANG").map(|c| c.line), Some(6));
        let proc = Level { text: T, start: Cursor { program: 0, offset: 101, line: 10 } };
        assert_eq!(&T[101..105], b"PROC");
        assert_eq!(proc.forward(proc.start, b"ENDE").map(|c| c.line), Some(11));
    }
}

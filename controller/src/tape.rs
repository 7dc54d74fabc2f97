//! FANUC tape mode (legacy DNC): after a `%` line while idle, XON/XOFF flow
//! control and no `ok` per line. The first block decides: an `O` number punches
//! the program into memory (setting `$300=0` or `1`), anything else is drip-fed
//! (run as it arrives; `$300=2` always drip-feeds). The closing `%` ends tape mode.
//!
//! [`Tape`] is the decision; the controller stores or runs what it says.

/// What the tape is doing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Tape {
    /// No block yet.
    Undecided,
    /// Collecting a program for memory (in the stream window); `failed` once it
    /// did not fit.
    Punch { failed: bool },
    /// Running the blocks as they come.
    Drip,
}

/// What a tape block asks of the controller.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Block<'a> {
    /// Nothing (the leader `%`, a blank line before the first block, a block of a
    /// program that could not be stored, a drip-fed block in alarm).
    Skip,
    /// The closing `%`: tape mode ends; the tape was doing this.
    End(Tape),
    /// A byte that cannot be G-code text: the block is dropped.
    BadByte(u8),
    /// Store this block of the punched program.
    Punch(&'a [u8]),
    /// Run this block; `first`: the tape's first block (its leading `%` then counts
    /// as line 1 of the job).
    Drip { text: &'a [u8], first: bool },
}

/// Whether a block starts with an O number.
fn starts_program(text: &[u8]) -> bool {
    matches!(text.first(), Some(b'O' | b'o')) && text.get(1).is_some_and(u8::is_ascii_digit)
}

impl Tape {
    /// Block `text` (trimmed) under setting `$300` = `mode`: what to do with it, the
    /// tape's state after it, and a note for the sender (`[MSG:…]`).
    pub fn block(self, text: &[u8], mode: u8, alarm: bool) -> (Block<'_>, Tape, Option<&'static str>) {
        if text == b"%" {
            // Before the first block a `%` is the tape's leader (after `$TAPE`);
            // after it, the end of the tape.
            let b = if self == Tape::Undecided { Block::Skip } else { Block::End(self) };
            return (b, self, None);
        }
        if let Some(b) = text.iter().copied().find(|&b| (b < 0x20 && b != b'\t') || b >= 0x7f) {
            return (Block::BadByte(b), self, None);
        }
        let mut note = None;
        let next = match self {
            Tape::Undecided if text.is_empty() => return (Block::Skip, self, None),
            Tape::Undecided => match (mode, starts_program(text)) {
                (0 | 1, true) => Tape::Punch { failed: false },
                (1, false) => {
                    note = Some("Tape: storing needs an O number first ($300=1)");
                    Tape::Punch { failed: true }
                }
                _ => Tape::Drip,
            },
            t => t,
        };
        let block = match next {
            Tape::Punch { failed: false } => Block::Punch(text),
            Tape::Drip if !alarm => Block::Drip { text, first: self == Tape::Undecided },
            _ => Block::Skip,
        };
        (block, next, note)
    }
}

/// The O number of the first block.
pub(crate) fn program_number(text: &[u8]) -> Option<u32> {
    let t = crate::lines::trim(text);
    if !starts_program(t) {
        return None;
    }
    let digits = t.get(1..)?.iter().take_while(|b| b.is_ascii_digit()).count();
    core::str::from_utf8(t.get(1..1 + digits)?).ok()?.parse().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_block_decides() {
        let (b, t, _) = Tape::Undecided.block(b"O0012", 0, false);
        assert_eq!((b, t), (Block::Punch(b"O0012"), Tape::Punch { failed: false }));
        let (b, t, _) = Tape::Undecided.block(b"G00 X1", 0, false);
        assert_eq!((b, t), (Block::Drip { text: b"G00 X1", first: true }, Tape::Drip));
        let (b, t, note) = Tape::Undecided.block(b"G00 X1", 1, false);
        assert_eq!((b, t), (Block::Skip, Tape::Punch { failed: true }));
        assert!(note.is_some());
        assert_eq!(Tape::Undecided.block(b"%", 0, false).0, Block::Skip);
        assert_eq!(Tape::Drip.block(b"%", 0, false).0, Block::End(Tape::Drip));
        assert_eq!(program_number(b" O12 (X)"), Some(12));
    }
}

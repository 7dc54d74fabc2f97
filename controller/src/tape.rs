//! FANUC tape mode (legacy DNC): after a `%` line while idle, XON/XOFF flow
//! control and no `ok` per line. The first block decides: an `O` number punches
//! the program into memory (setting `$300=0` or `1`), anything else is drip-fed
//! (run as it arrives; `$300=2` always drip-feeds). The closing `%` ends tape mode.

use crate::controller::{Controller, XON};
use crate::lines::{Handled, trim};
use crate::port::MotionPort;

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

/// Whether a block starts with an O number.
fn starts_program(text: &[u8]) -> bool {
    matches!(text.first(), Some(b'O' | b'o')) && text.get(1).is_some_and(u8::is_ascii_digit)
}

impl<const W: usize, const T: usize, const P: usize, const S: usize> Controller<W, T, P, S> {
    /// `%` while idle: tape mode.
    pub(crate) fn start_tape(&mut self) {
        self.tape = Some(Tape::Undecided);
        self.window.clear();
        self.rewind_stream();
        self.msg(format_args!("Tape mode: XON/XOFF, no ok per block, % ends it"));
        self.ok();
        self.out.control(XON);
    }

    /// One block in tape mode.
    pub(crate) fn tape_line<M: MotionPort + ?Sized>(&mut self, raw: &[u8], port: &mut M) -> Handled {
        let _ = port;
        let text = trim(raw);
        let Some(tape) = self.tape else { return Handled::Done };
        if text == b"%" {
            // Before the first block a `%` is the tape's leader (after `$TAPE`);
            // after it, the end of the tape.
            if tape != Tape::Undecided {
                self.end_tape(tape);
            }
            return Handled::Done;
        }
        if let Some(b) = text.iter().copied().find(|&b| (b < 0x20 && b != b'\t') || b >= 0x7f) {
            self.msg(format_args!("Tape: byte 0x{b:02X} is not G-code text: block dropped"));
            return Handled::Done;
        }
        let starting = tape == Tape::Undecided;
        let tape = match tape {
            Tape::Undecided if text.is_empty() => return Handled::Done,
            Tape::Undecided => match (self.settings.tape_mode, starts_program(text)) {
                (0 | 1, true) => Tape::Punch { failed: false },
                (1, false) => {
                    self.msg(format_args!("Tape: storing needs an O number first ($300=1)"));
                    Tape::Punch { failed: true }
                }
                _ => Tape::Drip,
            },
            t => t,
        };
        self.tape = Some(tape);
        match tape {
            Tape::Punch { failed: false } => {
                if !self.window.push_line(text) {
                    self.msg(format_args!("Tape: program longer than the window ({W} bytes): not stored"));
                    self.tape = Some(Tape::Punch { failed: true });
                }
                Handled::Done
            }
            Tape::Drip if self.alarm.is_none() => {
                // The leading `%` is line 1 of the tape: the program's lines keep the
                // numbers they have in the sender's file.
                if starting && !self.stream_text(b"") {
                    return Handled::Wait;
                }
                if self.stream_text(text) { Handled::Done } else { Handled::Wait }
            }
            _ => Handled::Done,
        }
    }

    /// The closing `%`.
    fn end_tape(&mut self, tape: Tape) {
        self.tape = None;
        self.record_closed = true;
        if self.xoff {
            self.xoff = false;
            self.out.control(XON);
        }
        if tape != (Tape::Punch { failed: false }) {
            return;
        }
        let mut number = None;
        if let Some(n) = program_number(self.window.text()) {
            self.memory.remove(n);
            number = Some(n);
        }
        match self.memory.load(self.window.text(), None) {
            Ok(n) => {
                self.dirty.programs = true;
                self.msg(format_args!("Stored O{n:04}"));
            }
            Err(e) => self.msg(format_args!("Tape: not stored: {e}")),
        }
        let _ = number;
        self.window.clear();
        self.rewind_stream();
    }
}

/// The O number of the first block.
fn program_number(text: &[u8]) -> Option<u32> {
    let t = trim(text);
    if !starts_program(t) {
        return None;
    }
    let digits = t.get(1..)?.iter().take_while(|b| b.is_ascii_digit()).count();
    core::str::from_utf8(t.get(1..1 + digits)?).ok()?.parse().ok()
}

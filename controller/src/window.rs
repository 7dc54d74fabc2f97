//! The stream window: the received program text the interpreter reads as program
//! 0, in a fixed buffer. Lines are appended whole (with their LF); text the
//! interpreter can no longer reach (behind every live cursor) is dropped from the
//! front when room is needed, and the interpreter's cursors are moved back by the
//! same amount ([`Interpreter::rebase`](interp_core::Interpreter::rebase)).
//!
//! [`Store`] joins the window and program memory into one
//! [`ProgramStore`]: program 0 is the window, every other number is a program in
//! memory (M98 calls, `$PR`).

use interp_core::program::{Cursor, ProgramId, ProgramMemory, ProgramStore, find_sequence_from};

/// Received text, `W` bytes at most.
#[derive(Debug)]
pub struct Window<const W: usize> {
    text: heapless::Vec<u8, W>,
    /// Source line of the window's first byte.
    first_line: u32,
    /// Bytes ever appended since the last clear (grows when text arrives, even
    /// when old text is dropped).
    received: u64,
}

impl<const W: usize> Default for Window<W> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const W: usize> Window<W> {
    /// Empty, starting at line 1.
    pub const fn new() -> Self {
        Window { text: heapless::Vec::new(), first_line: 1, received: 0 }
    }

    /// The text.
    pub fn text(&self) -> &[u8] {
        &self.text
    }

    /// Bytes held.
    pub fn len(&self) -> usize {
        self.text.len()
    }

    /// Nothing held.
    pub fn is_empty(&self) -> bool {
        self.text.is_empty()
    }

    /// Bytes free.
    pub fn free(&self) -> usize {
        W - self.text.len()
    }

    /// Total bytes appended since the last clear.
    pub fn received(&self) -> u64 {
        self.received
    }

    /// Source line of the first byte held.
    pub fn first_line(&self) -> u32 {
        self.first_line
    }

    /// Appends `line` and an LF; false (nothing appended) if it does not fit.
    pub fn push_line(&mut self, line: &[u8]) -> bool {
        if line.len() + 1 > self.free() {
            return false;
        }
        let _ = self.text.extend_from_slice(line);
        let _ = self.text.push(b'\n');
        self.received += line.len() as u64 + 1;
        true
    }

    /// Empties the window; line numbers start at 1 again.
    pub fn clear(&mut self) {
        self.text.clear();
        self.first_line = 1;
        self.received = 0;
    }

    /// Where to cut to free at least `need` bytes without dropping anything at or
    /// after `keep`: the first line boundary at or after `need`, or `keep` itself.
    /// `None` if `keep < need` (the text the run still needs fills the window).
    pub fn cut_point(&self, need: usize, keep: usize) -> Option<usize> {
        let keep = keep.min(self.text.len());
        if keep < need {
            return None;
        }
        let from = need.saturating_sub(1);
        let boundary = self.text.get(from..keep).and_then(|t| t.iter().position(|&b| b == b'\n')).map(|i| from + i + 1);
        Some(boundary.unwrap_or(keep).max(need))
    }

    /// Drops the first `n` bytes (the caller rebases the interpreter by `n`).
    pub fn drop_front(&mut self, n: usize) {
        let n = n.min(self.text.len());
        let lines = self.text.get(..n).map_or(0, |t| t.iter().filter(|&&b| b == b'\n').count());
        self.first_line = self.first_line.saturating_add(u32::try_from(lines).unwrap_or(u32::MAX));
        self.text.copy_within(n.., 0);
        self.text.truncate(self.text.len() - n);
    }
}

/// Program 0 = the stream window, other numbers = program memory.
#[derive(Clone, Copy, Debug)]
pub struct Store<'a, const W: usize, const T: usize, const P: usize, const S: usize> {
    /// The stream window.
    pub window: &'a Window<W>,
    /// Stored programs.
    pub memory: &'a ProgramMemory<T, P, S>,
}

impl<const W: usize, const T: usize, const P: usize, const S: usize> ProgramStore for Store<'_, W, T, P, S> {
    fn text(&self, id: ProgramId) -> Option<&[u8]> {
        if id == 0 { Some(self.window.text()) } else { self.memory.text(id) }
    }

    fn start(&self, id: ProgramId) -> Option<Cursor> {
        if id == 0 {
            Some(Cursor { program: 0, offset: 0, line: self.window.first_line() })
        } else {
            self.memory.start(id)
        }
    }

    fn find_sequence(&self, n: u32, from: Cursor) -> Option<Cursor> {
        if from.program != 0 {
            return self.memory.find_sequence(n, from);
        }
        let text = self.window.text();
        let start = Cursor { program: 0, offset: 0, line: self.window.first_line() };
        find_sequence_from(text, from, n).or_else(|| find_sequence_from(text, start, n))
    }

    /// The stream may bring what a look-ahead looks for (the controller decides
    /// how long to wait: `lookahead_wait_ms`); stored programs are complete.
    fn still_arriving(&self, id: ProgramId) -> bool {
        id == 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cutting_keeps_line_numbers_and_what_the_run_needs() {
        let mut w = Window::<32>::new();
        assert!(w.push_line(b"N1 G00 X1"));
        assert!(w.push_line(b"N2 X2"));
        assert!(w.push_line(b"N3 X3"));
        assert!(!w.push_line(b"N4 a line too long to fit in"));
        assert_eq!(w.cut_point(3, 10), Some(10));
        assert_eq!(w.cut_point(3, 16), Some(10));
        assert_eq!(w.cut_point(12, 10), None);
        w.drop_front(10);
        assert_eq!((w.text(), w.first_line()), (&b"N2 X2\nN3 X3\n"[..], 2));
        let mem = ProgramMemory::<16, 1, 1>::new();
        let s = Store { window: &w, memory: &mem };
        assert_eq!(s.find_sequence(3, s.start(0).unwrap()), Some(Cursor { program: 0, offset: 6, line: 3 }));
    }
}

//! FANUC tape mode (docs/PROTOCOL.md, FANUC tape mode) as a state machine without a
//! port: the whole tape (`%`, the blocks, `%`) goes out in small chunks, no `ok` per
//! line; DC3 (XOFF) from the board stops the output, DC1 (XON) resumes it.

/// DC1, XON: the board can take more.
pub const XON: u8 = 0x11;
/// DC3, XOFF: the board's buffer is ¾ full.
pub const XOFF: u8 = 0x13;

/// The tape being punched: its bytes, how far it went out, whether the board held it.
#[derive(Clone, Debug)]
pub struct Tape {
    data: Vec<u8>,
    pos: usize,
    held: bool,
    chunk: usize,
    lines: usize,
    /// Line ends written so far (the opening `%` line's included).
    ends: usize,
}

impl Tape {
    /// The tape `%` LF, `lines` each with LF, `%` LF, written at most `chunk` bytes at a time.
    pub fn new(lines: &[String], chunk: usize) -> Tape {
        let mut data = b"%\n".to_vec();
        for l in lines {
            data.extend_from_slice(l.as_bytes());
            data.push(b'\n');
        }
        data.extend_from_slice(b"%\n");
        Tape { data, pos: 0, held: false, chunk: chunk.max(1), lines: lines.len(), ends: 0 }
    }

    /// The bytes to write next: nothing while held or when all went out.
    pub fn next_chunk(&self) -> Option<&[u8]> {
        if self.held {
            return None;
        }
        let end = (self.pos + self.chunk).min(self.data.len());
        self.data.get(self.pos..end).filter(|c| !c.is_empty())
    }

    /// `n` bytes of the chunk were written.
    pub fn wrote(&mut self, n: usize) {
        let end = (self.pos + n).min(self.data.len());
        self.ends += self.data.get(self.pos..end).map_or(0, |w| w.iter().filter(|&&b| b == b'\n').count());
        self.pos = end;
    }

    /// A flow-control byte from the board: XOFF holds, XON releases.
    pub fn flow(&mut self, byte: u8) {
        match byte {
            XOFF => self.held = true,
            XON => self.held = false,
            _ => {}
        }
    }

    /// Whether the opening `%` line went out (before it, nothing grbl-like may be sent:
    /// a board that heard `?` since its reset takes `%` for a record mark, not tape mode).
    pub fn opened(&self) -> bool {
        self.ends >= 1
    }

    /// Whether the board holds the tape (XOFF seen, no XON since).
    pub fn held(&self) -> bool {
        self.held
    }

    /// The whole tape went out.
    pub fn done(&self) -> bool {
        self.pos >= self.data.len()
    }

    /// Program lines that went out completely (the `%` lines not counted).
    pub fn lines_sent(&self) -> usize {
        self.ends.saturating_sub(1).min(self.lines)
    }

    /// Number of program lines.
    pub fn total(&self) -> usize {
        self.lines
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tape() -> Tape {
        Tape::new(&["O0012".into(), "G00 X20".into(), "M30".into()], 4)
    }

    fn send_all(t: &mut Tape) -> Vec<u8> {
        let mut out = Vec::new();
        while let Some(c) = t.next_chunk() {
            out.extend_from_slice(c);
            let n = c.len();
            t.wrote(n);
        }
        out
    }

    #[test]
    fn the_tape_is_percent_blocks_percent() {
        let mut t = tape();
        assert_eq!(send_all(&mut t), b"%\nO0012\nG00 X20\nM30\n%\n");
        assert!(t.done());
        assert_eq!(t.lines_sent(), 3);
    }

    #[test]
    fn xoff_stops_the_output_until_xon() {
        let mut t = tape();
        let first = t.next_chunk().unwrap().to_vec();
        assert_eq!(first, b"%\nO0");
        t.wrote(first.len());
        t.flow(XOFF);
        assert!(t.held());
        assert_eq!(t.next_chunk(), None);
        t.flow(b'x');
        assert_eq!(t.next_chunk(), None, "other bytes do not release it");
        t.flow(XON);
        assert_eq!(t.next_chunk().unwrap(), b"012\n");
        assert_eq!(t.lines_sent(), 0);
        assert!(t.opened());
        t.wrote(4);
        assert_eq!(t.lines_sent(), 1);
    }

    #[test]
    fn a_partial_write_resumes_where_it_stopped() {
        let mut t = tape();
        t.wrote(1);
        assert!(!t.opened());
        t.wrote(2);
        assert_eq!(t.next_chunk().unwrap(), b"0012");
    }
}

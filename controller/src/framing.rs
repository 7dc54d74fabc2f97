//! Link checksums (docs/PROTOCOL.md, Checksums): `N<k> <line>*<crc>` framing of
//! received lines and the link's line numbering.

use crate::crc::crc16;

/// A line's link check.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Frame {
    /// No `N<k> …*<crc>` framing.
    Plain,
    /// Framed and correct: link line `k`, the body starts at byte `body` and ends
    /// before the `*` at `star`.
    Good { k: u32, body: usize, star: usize },
    /// Framed, CRC wrong or unreadable.
    Bad,
}

/// Reads the `N<k> …*<crc>` framing of a line. A line that merely looks framed
/// (`N10 #1=#2*1000` is a macro product) counts as framed with a wrong CRC only
/// once checksums are in use (`active`) or when it claims to be link line 1.
fn frame(line: &[u8], active: bool) -> Frame {
    let Some(star) = line.iter().rposition(|&b| b == b'*') else { return Frame::Plain };
    let hex = line.get(star + 1..).unwrap_or(&[]);
    let looks = matches!(line.first(), Some(b'N')) && hex.len() == 4 && hex.iter().all(u8::is_ascii_hexdigit);
    if !looks {
        return if active && hex.len() <= 4 && hex.iter().all(u8::is_ascii_hexdigit) {
            Frame::Bad
        } else {
            Frame::Plain
        };
    }
    let head = line.get(..star).unwrap_or(&[]);
    let digits = head.iter().skip(1).take_while(|b| b.is_ascii_digit()).count();
    let k: Option<u32> = core::str::from_utf8(head.get(1..1 + digits).unwrap_or(&[])).ok().and_then(|d| d.parse().ok());
    let crc = core::str::from_utf8(hex).ok().and_then(|h| u16::from_str_radix(h, 16).ok());
    match (k, crc) {
        (Some(k), Some(crc)) if crc16(head) == crc => {
            let mut body = 1 + digits;
            while head.get(body) == Some(&b' ') {
                body += 1;
            }
            Frame::Good { k, body, star }
        }
        (k, _) if active || k == Some(1) => Frame::Bad,
        _ => Frame::Plain,
    }
}

/// What a received line is to the link.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Checked<'a> {
    /// Text to handle; `Some(k)` when it came framed as link line `k` (then
    /// [`LinkSeq::accepted`] once it is handled).
    Text(&'a [u8], Option<u32>),
    /// A duplicate of link line `k`, already taken: answered `ok`, dropped.
    Duplicate(u32),
    /// Damaged, out of sequence, or unframed while checksums are in use: ask for
    /// link line [`LinkSeq::expected`] again.
    Resend,
}

/// Link line numbering of `N<k> …*<crc>` lines.
#[derive(Clone, Copy, Debug)]
pub(crate) struct LinkSeq {
    /// A checksummed line was accepted: every program line must carry one.
    pub active: bool,
    /// The number the next line must have.
    pub expected: u32,
}

impl LinkSeq {
    /// Checksums off, numbering from 1.
    pub const fn new() -> Self {
        LinkSeq { active: false, expected: 1 }
    }

    /// Checks `raw` (trimmed). `in_job`: a streamed job is open (there a line 1 is
    /// a stale resend, not a new numbering).
    pub fn check<'a>(&mut self, raw: &'a [u8], in_job: bool) -> Checked<'a> {
        let (text, k) = match frame(raw, self.active) {
            Frame::Good { k, body, star } => (raw.get(body..star).unwrap_or(&[]), k),
            Frame::Bad => return Checked::Resend,
            // An empty line too: no checksum sender sends one unframed, line noise
            // makes them (a flipped ENQ is a CR, a dropped `!` leaves the LF of
            // `!` LF, a partial line of a CR goes stale), and inside a job it would
            // count as a line of the stream and shift every line number after it.
            // A `$` command is taken unframed (a checksum sender sends `$LN=1`,
            // `$PR=` unframed between jobs), but not inside a streamed job: there the
            // sender sends only framed lines, and a `$` line is a framed line whose
            // `N` noise turned into `$` and whose `*hhhh` tail it cut off (answered
            // as a command, its `ok` would be taken for the answer to a line).
            Frame::Plain if self.active && (in_job || raw.first() != Some(&b'$')) => return Checked::Resend,
            Frame::Plain => return Checked::Text(raw, None),
        };
        // Line 1 restarts the numbering for a new job, but never inside a streamed
        // job: there it is a stale resend (answers to noise that arrive after the
        // sender went on), and restarting would run the job's first lines twice.
        // `$LN=1` restarts the numbering explicitly.
        if k == 1 && !in_job {
            self.expected = 1;
        }
        if k < self.expected {
            return Checked::Duplicate(k);
        }
        if k > self.expected {
            return Checked::Resend;
        }
        Checked::Text(text, Some(k))
    }

    /// Link line `k` was handled (answered): checksums are in use from now on and
    /// the next line is `k + 1`.
    pub fn accepted(&mut self) {
        self.active = true;
        self.expected = self.expected.saturating_add(1);
    }
}

/// The framed form of `line` as link line `k` (for senders and tests).
pub fn frame_line(k: u32, line: &str) -> heapless::String<160> {
    let mut s: heapless::String<160> = heapless::String::new();
    let _ = core::fmt::write(&mut s, format_args!("N{k} {line}"));
    let crc = crc16(s.as_bytes());
    let _ = core::fmt::write(&mut s, format_args!("*{crc:04X}"));
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn framing_is_read_and_checked() {
        let f = frame_line(12, "G01 X1");
        assert_eq!(frame(f.as_bytes(), false), Frame::Good { k: 12, body: 4, star: 10 });
        let mut bad: heapless::Vec<u8, 160> = heapless::Vec::from_slice(f.as_bytes()).unwrap();
        bad[5] ^= 1;
        assert_eq!(frame(&bad, true), Frame::Bad);
        assert_eq!(frame(&bad, false), Frame::Plain);
        assert_eq!(frame(b"N10 #1=#2*1000", false), Frame::Plain);
        assert_eq!(frame(b"G01 X1", true), Frame::Plain);
    }
}

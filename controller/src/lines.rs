//! Received lines: link checksums, refusing what cannot be G-code, `$` commands,
//! and program text into the stream window (`ok` = the line is in the window).

use crate::controller::{Controller, Job, RX};
use crate::crc::crc16;
use crate::port::MotionPort;

/// What became of a line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Handled {
    /// Answered; it leaves the receive buffer.
    Done,
    /// Cannot be taken yet (the window is full): it stays in the receive buffer.
    Wait,
}

/// A line's link check.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Link {
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
fn link_frame(line: &[u8], active: bool) -> Link {
    let Some(star) = line.iter().rposition(|&b| b == b'*') else { return Link::Plain };
    let hex = line.get(star + 1..).unwrap_or(&[]);
    let looks = matches!(line.first(), Some(b'N')) && hex.len() == 4 && hex.iter().all(u8::is_ascii_hexdigit);
    if !looks {
        return if active && hex.len() <= 4 && hex.iter().all(u8::is_ascii_hexdigit) { Link::Bad } else { Link::Plain };
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
            Link::Good { k, body, star }
        }
        (k, _) if active || k == Some(1) => Link::Bad,
        _ => Link::Plain,
    }
}

/// The first byte of `line` that cannot be program text (control characters other
/// than TAB and CR, DEL, bytes ≥ 0x80).
fn bad_byte(line: &[u8]) -> Option<u8> {
    line.iter().copied().find(|&b| (b < 0x20 && b != b'\t' && b != b'\r') || b >= 0x7f)
}

impl<const W: usize, const T: usize, const P: usize, const S: usize> Controller<W, T, P, S> {
    /// Handles complete lines in the receive buffer (a few per poll). Never inlined:
    /// see `soft_reset`.
    #[inline(never)]
    pub(crate) fn handle_lines<M: MotionPort + ?Sized>(&mut self, port: &mut M) {
        for _ in 0..crate::controller::LINES_PER_POLL {
            let Some(end) = self.rx.iter().position(|&b| b == b'\n') else { return };
            let mut line: heapless::Vec<u8, RX> = heapless::Vec::new();
            let _ = line.extend_from_slice(self.rx.get(..end).unwrap_or(&[]));
            let handled = if self.tape.is_some() { self.tape_line(&line, port) } else { self.line(&line, port) };
            if handled == Handled::Wait {
                return;
            }
            self.rx.copy_within(end + 1.., 0);
            self.rx.truncate(self.rx.len() - end - 1);
            self.rx_consumed(end + 1);
        }
    }

    /// One grbl-mode line (without its LF).
    fn line<M: MotionPort + ?Sized>(&mut self, raw: &[u8], port: &mut M) -> Handled {
        let raw = trim(raw);
        let (text, k) = match link_frame(raw, self.link.active) {
            Link::Good { k, body, star } => (raw.get(body..star).unwrap_or(&[]), Some(k)),
            Link::Bad => return self.resend(),
            Link::Plain if self.link.active && raw.first() != Some(&b'$') && !raw.is_empty() => {
                return self.resend();
            }
            Link::Plain => (raw, None),
        };
        if let Some(k) = k {
            // Line 1 restarts the numbering for a new job, but never inside a
            // streamed job: there it is a stale resend (answers to noise that
            // arrive after the sender went on), and restarting would run the job's
            // first lines twice. `$LN=1` restarts the numbering explicitly.
            if k == 1 && self.job != Job::Stream {
                self.link.expected = 1;
            }
            if k < self.link.expected {
                // A duplicate of a line already taken: answered, dropped.
                self.ok();
                return Handled::Done;
            }
            if k > self.link.expected {
                return self.resend();
            }
        }
        let text = trim(text);
        let handled = self.line_text(text, port);
        if handled == Handled::Done && k.is_some() {
            self.link.active = true;
            self.link.expected = self.link.expected.saturating_add(1);
        }
        handled
    }

    fn resend(&mut self) -> Handled {
        self.counters.resends = self.counters.resends.saturating_add(1);
        let n = self.link.expected;
        self.refuse(88, resend_text(n).as_str());
        Handled::Done
    }

    /// A line's text after the link framing.
    fn line_text<M: MotionPort + ?Sized>(&mut self, text: &[u8], port: &mut M) -> Handled {
        if let Some(b) = bad_byte(text) {
            self.refuse(1, bad_text(b).as_str());
            return Handled::Done;
        }
        match text.first() {
            // An empty line counts as a line of the stream (so its line numbers stay
            // those of the sender's file); in alarm it is just answered.
            None if self.alarm.is_some() => {
                self.ok();
                Handled::Done
            }
            None => self.program_line(text),
            Some(b'$') => {
                self.grbl_seen = true;
                self.dollar(text.get(1..).unwrap_or(&[]), port)
            }
            Some(b'%') if text == b"%" && self.tape_starts() => {
                self.start_tape();
                Handled::Done
            }
            Some(_) => self.program_line(text),
        }
    }

    /// Whether a `%` line starts tape mode now (setting `$301`): only while Idle,
    /// and by default only from a sender that has not spoken grbl since the last
    /// reset — grbl senders poll `?` and send `$` commands when they connect, tape
    /// DNC software never does; a grbl sender's `%` is a record mark.
    fn tape_starts(&self) -> bool {
        let idle = self.job == Job::None && self.alarm.is_none() && !self.check;
        idle && match self.settings.tape_detect {
            0 => !self.grbl_seen,
            1 => true,
            _ => false,
        }
    }

    /// Program text into the window.
    pub(crate) fn program_line(&mut self, text: &[u8]) -> Handled {
        if self.alarm.is_some() {
            self.refuse(9, "Alarm: $X or reset first");
            return Handled::Done;
        }
        if self.sleep || self.jog || self.homing.is_some() || matches!(self.job, Job::Memory(_)) {
            self.refuse(8, "Busy: not while sleeping, jogging, homing or running from memory");
            return Handled::Done;
        }
        let mut dwell: heapless::Vec<u8, 24> = heapless::Vec::new();
        let text = match grbl_sync_dwell(text) {
            Some(seconds) if self.settings.grbl_dwell && dwell.extend_from_slice(b"G04 X").is_ok() => {
                let _ = dwell.extend_from_slice(seconds);
                &dwell[..]
            }
            _ => text,
        };
        if !self.stream_text(text) {
            return Handled::Wait;
        }
        self.ok();
        Handled::Done
    }

    /// Appends program text to the window, starting a stream job if none runs;
    /// false if it does not fit even after dropping text the run is done with.
    pub(crate) fn stream_text(&mut self, text: &[u8]) -> bool {
        if self.job == Job::None {
            self.window.clear();
            self.interp.rewind();
            self.rewind_stream();
            self.job = Job::Stream;
            self.job_worked = false;
            self.record_closed = false;
        }
        if self.window.push_line(text) {
            self.window_stuck = false;
            return true;
        }
        let need = text.len() + 1 - self.window.free().min(text.len() + 1);
        let keep = self.interp.earliest_offset(0).unwrap_or(self.window.len());
        // Drop at least an eighth of the window at a time (fewer moves), keeping
        // as much recent text as possible for backward jumps.
        let want = need.max(W / 8).min(keep).max(need);
        match self.window.cut_point(want, keep) {
            Some(cut) => {
                self.window.drop_front(cut);
                self.interp.rebase(0, cut);
                self.counters.window_dropped = self.counters.window_dropped.saturating_add(cut as u64);
                let pushed = self.window.push_line(text);
                self.window_stuck = !pushed;
                pushed
            }
            None => {
                self.window_stuck = true;
                false
            }
        }
    }
}

/// A line without surrounding blanks and CR.
pub(crate) fn trim(mut s: &[u8]) -> &[u8] {
    while let [b' ' | b'\t' | b'\r', rest @ ..] = s {
        s = rest;
    }
    while let [rest @ .., b' ' | b'\t' | b'\r'] = s {
        s = rest;
    }
    s
}

fn resend_text(n: u32) -> heapless::String<32> {
    let mut s = heapless::String::new();
    let _ = core::fmt::write(&mut s, format_args!("Resend:{n}"));
    s
}

fn bad_text(b: u8) -> heapless::String<48> {
    let mut s = heapless::String::new();
    let _ = core::fmt::write(&mut s, format_args!("Byte 0x{b:02X} is not G-code text: line refused"));
    s
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
        assert_eq!(link_frame(f.as_bytes(), false), Link::Good { k: 12, body: 4, star: 10 });
        let mut bad: heapless::Vec<u8, 160> = heapless::Vec::from_slice(f.as_bytes()).unwrap();
        bad[5] ^= 1;
        assert_eq!(link_frame(&bad, true), Link::Bad);
        assert_eq!(link_frame(&bad, false), Link::Plain);
        assert_eq!(link_frame(b"N10 #1=#2*1000", false), Link::Plain);
        assert_eq!(link_frame(b"G01 X1", true), Link::Plain);
        assert_eq!(trim(b"  G1 \r"), b"G1");
    }
}

/// A grbl sender's sync dwell: a line that is only `G4 P<seconds>` with a decimal
/// point (CNCjs ends every job with `G4 P0.5`). In the board's language G04 P is in
/// milliseconds without a decimal point (a decimal point is alarm 0007), so such a
/// line can only mean grbl's dwell in seconds; with `$303=1` (the default) it runs as
/// `G04 X<seconds>`. Returns the seconds' text.
fn grbl_sync_dwell(text: &[u8]) -> Option<&[u8]> {
    let t: &[u8] = trim(text);
    let rest = t.strip_prefix(b"G4").or_else(|| t.strip_prefix(b"G04"))?;
    let rest = trim(rest);
    let value = trim(rest.strip_prefix(b"P")?);
    let digits_and_point = value.iter().all(|b| b.is_ascii_digit() || *b == b'.');
    let one_point = value.iter().filter(|&&b| b == b'.').count() == 1;
    (digits_and_point && one_point && value.len() <= 12).then_some(value)
}

#[cfg(test)]
mod dwell_tests {
    use super::grbl_sync_dwell;

    #[test]
    fn only_a_lone_g4_p_with_a_decimal_point_is_a_grbl_dwell() {
        assert_eq!(grbl_sync_dwell(b"G4 P0.5"), Some(&b"0.5"[..]));
        assert_eq!(grbl_sync_dwell(b"G04P1."), Some(&b"1."[..]));
        assert_eq!(grbl_sync_dwell(b"G4 P500"), None, "FANUC milliseconds stay as they are");
        assert_eq!(grbl_sync_dwell(b"G4 P0.5 X1"), None);
        assert_eq!(grbl_sync_dwell(b"G01 X1"), None);
    }
}

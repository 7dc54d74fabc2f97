//! The receive side of the link: bytes in, real-time commands latched, line data
//! into the 128-byte receive buffer, XON/XOFF for tape mode. It knows nothing of
//! what a line means: the controller takes complete lines out with
//! [`Receiver::line`] / [`Receiver::consume`] and acts on [`Latched`] commands at
//! its next poll.

use crate::controller::{RX, STALE_LINE_NS, XOFF, XON};

/// Real-time commands latched by [`Receiver::receive`] for the next poll.
#[derive(Clone, Debug, Default)]
pub(crate) struct Latched {
    pub status: bool,
    /// ENQ (0x05): the short link report `[LK:…]` asked.
    pub link: bool,
    pub hold: bool,
    pub resume: bool,
    pub reset: bool,
    pub door: bool,
    pub jog_cancel: bool,
    /// Override bytes 0x90–0x9D in the order they came (more than 16 in one poll
    /// are dropped).
    pub overrides: heapless::Vec<u8, 16>,
    pub spindle_stop: bool,
    pub flood: bool,
    pub mist: bool,
}

/// What [`Receiver::receive`] did with the tail behind a full receive buffer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Picked {
    /// Its real-time bytes were acted on; this many bytes are kept, at its end.
    Kept(usize),
    /// A 0x18 at this index: the tail up to it is consumed (the reset drops it).
    Reset(usize),
}

/// Whether a real-time byte met between lines acts (see [`Receiver::acts`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Acts {
    /// At once, alone.
    Alone,
    /// At once, with the LF behind it.
    WithLf,
    /// Not: it is line data.
    No,
    /// The byte behind it decides, and it has not come yet.
    Undecided,
}

/// Whether `b` is one of the real-time command bytes.
fn is_realtime(b: u8) -> bool {
    matches!(b, b'?' | ENQ | b'!' | b'~' | 0x18 | 0x84 | 0x85 | 0x90..=0x9D | 0x9E | 0xA0 | 0xA1)
}

/// ENQ (Ctrl-E): asks for the short link report `[LK:<last link line>,<free rx
/// bytes>]` (docs/PROTOCOL.md, Checksums).
pub(crate) const ENQ: u8 = 0x05;

/// The queries: real-time bytes that act anywhere, alone, even under checksums (they
/// only ask for an answer, so a byte line noise turns into one costs nothing but
/// the damaged line, which its CRC catches).
fn is_query(b: u8) -> bool {
    b == b'?' || b == ENQ
}

/// The receive buffer and what goes with it.
#[derive(Debug)]
pub(crate) struct Receiver {
    buf: heapless::Vec<u8, RX>,
    /// Dropping a line longer than the buffer up to its LF.
    discarding: bool,
    /// Commands for the next poll.
    pub latched: Latched,
    /// Tape mode: `Some(strip bit 7)`.
    tape: Option<bool>,
    /// DC3 sent, DC1 not yet.
    xoff: bool,
    /// The flow-control byte to send next.
    flow: Option<u8>,
    /// Lines dropped as longer than the buffer, not yet answered `error:11`.
    overlong: u8,
    /// grbl traffic (`?`, a real-time byte, a `$` line) since power-on or reset.
    pub grbl_seen: bool,
    /// A real-time byte arrived behind this many received bytes not yet handled:
    /// it counts as grbl traffic only once they are (a `?` right behind a tape's
    /// opening `%` must not make that `%` a record mark).
    grbl_after: Option<usize>,
    /// When the last line byte (not a real-time byte) arrived.
    pub last_line_byte: u64,
    /// When the last byte of any kind (a line, `?`, a real-time byte) arrived.
    pub last_byte: u64,
}

impl Receiver {
    pub const fn new() -> Self {
        Receiver {
            buf: heapless::Vec::new(),
            discarding: false,
            latched: Latched {
                status: false,
                link: false,
                hold: false,
                resume: false,
                reset: false,
                door: false,
                jog_cancel: false,
                overrides: heapless::Vec::new(),
                spindle_stop: false,
                flood: false,
                mist: false,
            },
            tape: None,
            xoff: false,
            flow: None,
            overlong: 0,
            grbl_seen: false,
            grbl_after: None,
            last_line_byte: 0,
            last_byte: 0,
        }
    }

    /// Bytes in the receive buffer.
    pub fn len(&self) -> usize {
        self.buf.len()
    }

    /// Takes bytes from the link (see `Controller::receive`); `framed`: link
    /// checksums are in use (real-time bytes then act only between lines).
    /// Returns how many bytes were consumed.
    pub fn receive(&mut self, bytes: &mut [u8], now: u64, framed: bool) -> usize {
        let mut start = 0;
        loop {
            let Some(rest) = bytes.get_mut(start..) else { return bytes.len() };
            let taken = self.take(rest, now, framed);
            let Some(tail) = rest.get_mut(taken..).filter(|t| !t.is_empty()) else { return bytes.len() };
            match self.pick_realtime(tail, now, framed) {
                Picked::Kept(kept) => return bytes.len() - kept,
                Picked::Reset(at) => start += taken + at + 1,
            }
        }
    }

    /// Takes bytes in order while the receive buffer has room; how many were
    /// consumed.
    fn take(&mut self, bytes: &[u8], now: u64, framed: bool) -> usize {
        let mut command_lf = false;
        for (i, &raw) in bytes.iter().enumerate() {
            self.last_byte = now;
            let b = self.stripped(raw);
            if core::mem::take(&mut command_lf) || b == XON || b == XOFF {
                continue;
            }
            if (self.at_line_boundary(framed) || is_query(b)) && is_realtime(b) {
                match self.acts(b, bytes.get(i + 1).map(|&n| self.stripped(n)), framed) {
                    Acts::Alone => {
                        self.realtime(b, self.buf.len());
                        continue;
                    }
                    Acts::WithLf => {
                        self.realtime(b, self.buf.len());
                        command_lf = true;
                        continue;
                    }
                    // Decided by the next byte: kept for the next offer.
                    Acts::Undecided => return i,
                    Acts::No => {}
                }
            }
            // Line data (not status polls) is what keeps the link from being quiet.
            self.last_line_byte = now;
            if self.discarding {
                if b == b'\n' {
                    self.discarding = false;
                    self.overlong = self.overlong.saturating_add(1);
                }
                continue;
            }
            if self.buf.is_full() {
                if self.buf.contains(&b'\n') {
                    return i;
                }
                // A line longer than the buffer: drop it up to its LF.
                self.consumed(self.buf.len());
                self.buf.clear();
                self.discarding = b != b'\n';
                if b == b'\n' {
                    self.overlong = self.overlong.saturating_add(1);
                }
                continue;
            }
            let _ = self.buf.push(b);
            if self.tape.is_some() && !self.xoff && self.buf.len() >= RX * 3 / 4 {
                self.flow = Some(XOFF);
                self.xoff = true;
            }
        }
        bytes.len()
    }

    /// The unconsumed `tail` behind a full receive buffer: its real-time bytes
    /// (and XON/XOFF) are latched and removed, the rest is moved to the end of
    /// `tail`. A tail byte is between lines when the line data before it in the
    /// stream (the buffer's last byte, then the tail's kept bytes) ends with a LF
    /// (see [`Receiver::at_line_boundary`]). Stops at a 0x18: its index.
    fn pick_realtime(&mut self, tail: &mut [u8], now: u64, framed: bool) -> Picked {
        let mut between = !self.discarding && self.buf.last().is_none_or(|&b| b == b'\n');
        let mut kept = 0;
        let mut command_lf = false;
        for i in 0..tail.len() {
            let Some(&raw) = tail.get(i) else { break };
            self.last_byte = now;
            let b = self.stripped(raw);
            if b == XON || b == XOFF {
                continue;
            }
            if core::mem::take(&mut command_lf) {
                continue;
            }
            let next = tail.get(i + 1).map(|&n| self.stripped(n));
            let acts = if (!framed || between || is_query(b)) && is_realtime(b) {
                self.acts(b, next, framed)
            } else {
                Acts::No
            };
            if matches!(acts, Acts::Alone | Acts::WithLf) {
                self.realtime(b, self.buf.len() + kept);
                if b == 0x18 {
                    return Picked::Reset(i + usize::from(acts == Acts::WithLf));
                }
                command_lf = acts == Acts::WithLf;
                continue;
            }
            self.last_line_byte = now;
            if let Some(slot) = tail.get_mut(kept) {
                *slot = raw;
            }
            kept += 1;
            between = b == b'\n';
        }
        tail.copy_within(..kept, tail.len() - kept);
        Picked::Kept(kept)
    }

    /// `raw` as the controller reads it: bit 7 stripped for a tape reader that
    /// sends parity.
    fn stripped(&self, raw: u8) -> u8 {
        if self.tape == Some(true) { raw & 0x7f } else { raw }
    }

    /// Whether a real-time byte would be acted on now. Always, except while link
    /// checksums are in use: then the queries `?` and ENQ anywhere (a byte line noise turns into `?` goes
    /// missing from its line, whose CRC then fails, as for a dropped byte; and a
    /// sender's status polls never become data of a line whose LF was lost, which
    /// would keep that line from going stale), every other one only between lines
    /// (the first byte after a LF),
    /// so that line noise turning a byte of a line into `!`, `~` or 0x18 (a flipped
    /// bit makes `1` a `!`, `X` a 0x18) corrupts that line — caught by its CRC and
    /// resent — instead of holding or resetting the machine. A sender writes
    /// real-time bytes between its lines, so they still act at once.
    fn at_line_boundary(&self, framed: bool) -> bool {
        !framed || (!self.discarding && self.buf.last().is_none_or(|&b| b == b'\n'))
    }

    /// Whether real-time byte `b`, met between lines, acts (`next`: the byte after
    /// it, if it came yet). Without link checksums it acts alone, as in grbl. With
    /// them (`framed`), `?` and ENQ act alone and every other real-time byte only when a
    /// LF follows it (`!` LF, 0x18 LF …; the LF is part of the command): line noise
    /// that drops the `N` of a framed line makes the line's second byte the first
    /// after a LF, and one flipped bit of it (`8` → 0x18, `1` → `!`) must not reset
    /// or hold the machine — it then acts only if the noise also turns the third
    /// byte into a LF.
    fn acts(&self, b: u8, next: Option<u8>, framed: bool) -> Acts {
        match (framed && !is_query(b), next) {
            (false, _) => Acts::Alone,
            (true, Some(b'\n')) => Acts::WithLf,
            (true, Some(_)) => Acts::No,
            (true, None) => Acts::Undecided,
        }
    }

    /// A real-time byte: latched, true; any other byte: false. `behind`: received
    /// bytes not yet handled that came before it.
    fn realtime(&mut self, b: u8, behind: usize) -> bool {
        let rt = &mut self.latched;
        match b {
            b'?' => rt.status = true,
            ENQ => rt.link = true,
            b'!' => rt.hold = true,
            b'~' => rt.resume = true,
            0x18 => {
                rt.reset = true;
                // What was received before the reset is dropped with it (override
                // bytes too: the reset sets the overrides back to 100 %).
                rt.overrides.clear();
                self.buf.clear();
                self.discarding = false;
                self.tape = None;
                self.xoff = false;
            }
            0x84 => rt.door = true,
            0x85 => rt.jog_cancel = true,
            0x90..=0x9D => {
                let _ = rt.overrides.push(b);
            }
            0x9E => rt.spindle_stop = true,
            0xA0 => rt.flood = true,
            0xA1 => rt.mist = true,
            _ => return false,
        }
        if b == 0x18 {
            self.grbl_seen = false;
            self.grbl_after = None;
        } else if behind == 0 {
            self.grbl_seen = true;
        } else {
            self.grbl_after.get_or_insert(behind);
        }
        true
    }

    /// `n` received bytes were handled (or dropped): a real-time byte behind them
    /// now counts as grbl traffic.
    fn consumed(&mut self, n: usize) {
        match self.grbl_after {
            Some(k) if k > n => self.grbl_after = Some(k - n),
            Some(_) => {
                self.grbl_seen = true;
                self.grbl_after = None;
            }
            None => {}
        }
    }

    /// With link checksums (`framed`), a line whose end has not come for
    /// [`STALE_LINE_NS`] lost its LF to line noise: it is ended here (its CRC fails,
    /// the sender is asked to resend), so real-time bytes, which count as line data
    /// inside a line, act again.
    pub fn end_stale_line(&mut self, now: u64, framed: bool) {
        let partial = !self.discarding && self.buf.last().is_some_and(|&b| b != b'\n');
        let stale = framed && partial && now.saturating_sub(self.last_line_byte) >= STALE_LINE_NS;
        if stale && self.buf.push(b'\n').is_err() {
            self.consumed(self.buf.len());
            self.buf.clear();
            self.overlong = self.overlong.saturating_add(1);
        }
    }

    /// The first complete line in the buffer (without its LF).
    pub fn line(&self) -> Option<&[u8]> {
        let end = self.buf.iter().position(|&b| b == b'\n')?;
        self.buf.get(..end)
    }

    /// The first line (see [`Receiver::line`]) was handled: it leaves the buffer.
    pub fn consume_line(&mut self) {
        let Some(end) = self.buf.iter().position(|&b| b == b'\n') else { return };
        self.buf.copy_within(end + 1.., 0);
        self.buf.truncate(self.buf.len() - end - 1);
        self.consumed(end + 1);
    }

    /// Lines dropped as longer than the buffer since the last call (each to be
    /// answered `error:11`).
    pub fn take_overlong(&mut self) -> u8 {
        core::mem::take(&mut self.overlong)
    }

    /// Tape mode from now on (`Some(strip bit 7)`) or no more (`None`, which also
    /// releases a sender held with DC3).
    pub fn set_tape(&mut self, tape: Option<bool>) {
        self.tape = tape;
        if tape.is_none() && self.xoff {
            self.xoff = false;
            self.flow = Some(XON);
        }
    }

    /// In tape mode, DC1 once the buffer has room again — or when what is left is
    /// only the start of a line (longer than a quarter of the buffer): it needs more
    /// bytes to end, so holding the sender would never release.
    pub fn release(&mut self) {
        let partial_only = !self.buf.contains(&b'\n');
        if self.tape.is_some() && self.xoff && (self.buf.len() <= RX / 4 || partial_only) {
            self.flow = Some(XON);
            self.xoff = false;
        }
    }

    /// The flow-control byte to send now, if any.
    pub fn take_flow(&mut self) -> Option<u8> {
        self.flow.take()
    }
}

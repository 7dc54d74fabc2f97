//! The output queue the shell drains: whole lines, never blocking. When it runs
//! short, status reports and messages are dropped first: `RESERVE` bytes are kept
//! for replies (`ok`, `error:N`, `ALARM:N`, the welcome line).

use core::fmt::{self, Write};

/// What a line is, for what to drop when the queue is short.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Class {
    /// `ok`, `error:N`, `ALARM:N`, welcome: dropped only if nothing fits.
    Reply,
    /// `[MSG:…]`, status reports, listings: need `RESERVE` bytes left over.
    Info,
}

/// Bytes kept free for replies.
pub const RESERVE: usize = 256;

/// The longest line formatted at once.
pub const LINE: usize = 200;

/// A byte queue of `N` bytes.
#[derive(Debug)]
pub struct OutQueue<const N: usize> {
    buf: heapless::Deque<u8, N>,
    /// The flow-control byte (DC1/DC3) to send before anything queued: only the
    /// latest flow state counts.
    flow: Option<u8>,
    /// Replies dropped because the queue was full (should stay 0).
    pub lost_replies: u32,
    /// Info lines dropped.
    pub lost_info: u32,
    /// Every line gets `*<CRC-16>` of its text (link checksums in use).
    pub crc: bool,
}

impl<const N: usize> Default for OutQueue<N> {
    fn default() -> Self {
        OutQueue { buf: heapless::Deque::new(), flow: None, lost_replies: 0, lost_info: 0, crc: false }
    }
}

impl<const N: usize> OutQueue<N> {
    /// Queues `text` and CR LF, whole or not at all; with [`OutQueue::crc`]
    /// `text*<crc>` CR LF, the CRC-16/CCITT-FALSE of `text` in 4 upper-case hex
    /// digits (docs/PROTOCOL.md, Checksums).
    pub fn line(&mut self, class: Class, text: &str) {
        let mut tail: heapless::String<5> = heapless::String::new();
        if self.crc {
            let _ = write!(tail, "*{:04X}", crate::crc::crc16(text.as_bytes()));
        }
        let need = text.len() + tail.len() + 2;
        let free = N - self.buf.len();
        let room = match class {
            Class::Reply => free >= need,
            Class::Info => free >= need + RESERVE,
        };
        if !room {
            match class {
                Class::Reply => self.lost_replies = self.lost_replies.saturating_add(1),
                Class::Info => self.lost_info = self.lost_info.saturating_add(1),
            }
            return;
        }
        for &b in text.as_bytes().iter().chain(tail.as_bytes()).chain(b"\r\n") {
            let _ = self.buf.push_back(b);
        }
    }

    /// Formats and queues a line.
    pub fn fmt(&mut self, class: Class, args: fmt::Arguments<'_>) {
        let mut s: heapless::String<LINE> = heapless::String::new();
        if s.write_fmt(args).is_err() {
            // Too long: cut at the capacity (still a useful line).
            let _ = s.push_str("…");
        }
        self.line(class, &s);
    }

    /// Sends a flow-control byte ahead of everything queued. Only the latest flow
    /// state counts: it replaces a DC1/DC3 still waiting (an older XOFF must never
    /// reach the sender after a newer XON and hold it).
    pub fn control(&mut self, b: u8) {
        self.flow = Some(b);
    }

    /// Moves queued bytes into `out`; how many.
    pub fn drain(&mut self, out: &mut [u8]) -> usize {
        let mut n = 0;
        for slot in out.iter_mut() {
            let Some(b) = self.flow.take().or_else(|| self.buf.pop_front()) else { break };
            *slot = b;
            n += 1;
        }
        n
    }

    /// Bytes waiting.
    pub fn len(&self) -> usize {
        self.buf.len() + usize::from(self.flow.is_some())
    }

    /// Nothing waiting.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Drops everything.
    pub fn clear(&mut self) {
        self.buf.clear();
        self.flow = None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::format;

    #[test]
    fn replies_are_kept_when_reports_fill_the_queue() {
        let mut q = OutQueue::<300>::default();
        for _ in 0..10 {
            q.line(Class::Info, "<Idle|MPos:0.000,0.000,0.000|FS:0,0>");
        }
        assert!(q.lost_info > 0);
        let before = q.len();
        for _ in 0..40 {
            q.line(Class::Reply, "ok");
        }
        assert_eq!(q.lost_replies, 0);
        assert_eq!(q.len(), before + 40 * 4);
        q.control(0x13);
        let mut out = [0u8; 1];
        assert_eq!((q.drain(&mut out), out[0]), (1, 0x13));
    }

    #[test]
    fn with_crc_every_line_carries_the_crc_of_its_text() {
        let mut q = OutQueue::<64> { crc: true, ..Default::default() };
        q.line(Class::Reply, "ok");
        let mut out = [0u8; 16];
        let n = q.drain(&mut out);
        let want = format!("ok*{:04X}\r\n", crate::crc::crc16(b"ok"));
        assert_eq!(core::str::from_utf8(&out[..n]).unwrap(), want);
    }

    #[test]
    fn the_latest_flow_byte_goes_first_and_alone() {
        let mut q = OutQueue::<64>::default();
        q.line(Class::Reply, "ok");
        q.control(0x13);
        q.control(0x11);
        assert_eq!(q.len(), 5);
        let mut out = [0u8; 8];
        assert_eq!(q.drain(&mut out), 5);
        assert_eq!(&out[..5], b"\x11ok\r\n");
    }
}

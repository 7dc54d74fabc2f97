//! The bytes a link received that the controller could not take yet (its receive
//! buffer was full): a sender that ignores character counting sends beyond it.
//! They are offered again after every poll and with every new byte; the controller
//! picks the real-time bytes (`?`, `!`, `~`, 0x18, …) out of them at once
//! (docs/PROTOCOL.md), so a feed hold or status poll never waits behind them.

use crate::Endpoint;

/// Up to `N` bytes held for the controller, in arrival order.
#[derive(Debug)]
pub struct Held<const N: usize> {
    buf: [u8; N],
    len: usize,
}

impl<const N: usize> Default for Held<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize> Held<N> {
    /// Nothing held.
    pub const fn new() -> Self {
        Held { buf: [0; N], len: 0 }
    }

    /// Bytes held.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Nothing held.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Room for more bytes, in bytes.
    pub fn room_len(&self) -> usize {
        N - self.len
    }

    /// Where the next bytes go: fill some, then call [`Held::filled`].
    pub fn room(&mut self) -> &mut [u8] {
        self.buf.get_mut(self.len..).unwrap_or(&mut [])
    }

    /// `n` bytes were written at the start of [`Held::room`].
    pub fn filled(&mut self, n: usize) {
        self.len = (self.len + n).min(N);
    }

    /// Appends what fits of `bytes`; how many.
    pub fn push(&mut self, bytes: &[u8]) -> usize {
        let n = bytes.len().min(self.room_len());
        self.room()[..n].copy_from_slice(&bytes[..n]);
        self.filled(n);
        n
    }

    /// Offers everything held to `to`: what it takes leaves; the real-time bytes it
    /// acted on leave too, wherever they were; the rest stays, in order.
    pub fn offer<E: Endpoint + ?Sized>(&mut self, to: &mut E, now: u64) {
        if self.len == 0 {
            return;
        }
        let held = &mut self.buf[..self.len];
        let taken = to.receive(held, now).min(self.len);
        self.buf.copy_within(taken..self.len, 0);
        self.len -= taken;
    }

    /// Drops everything held (the link is not the controller's now).
    pub fn clear(&mut self) {
        self.len = 0;
    }
}

#[cfg(test)]
mod tests {
    use std::vec::Vec;

    use super::*;

    /// Takes up to `room` bytes in order; `?` anywhere counts as a status poll and is
    /// removed, as the controller does.
    struct Fake {
        room: usize,
        got: Vec<u8>,
        polls: usize,
    }

    impl Endpoint for Fake {
        fn receive(&mut self, bytes: &mut [u8], _now: u64) -> usize {
            let take = bytes.len().min(self.room);
            self.got.extend_from_slice(&bytes[..take]);
            self.room -= take;
            let tail: Vec<u8> = bytes[take..].to_vec();
            let kept: Vec<u8> = tail.iter().copied().filter(|&b| b != b'?').collect();
            self.polls += tail.len() - kept.len();
            let n = bytes.len();
            bytes[n - kept.len()..].copy_from_slice(&kept);
            n - kept.len()
        }

        fn transmit(&mut self, _out: &mut [u8]) -> usize {
            0
        }
    }

    #[test]
    fn what_the_controller_leaves_stays_in_order_and_its_real_time_bytes_leave() {
        let mut h = Held::<16>::new();
        assert_eq!(h.push(b"abc?def?gh"), 10);
        let mut f = Fake { room: 2, got: Vec::new(), polls: 0 };
        h.offer(&mut f, 0);
        assert_eq!(f.got, b"ab");
        assert_eq!(f.polls, 2);
        assert_eq!(h.len(), 6);
        f.room = 100;
        h.offer(&mut f, 0);
        assert_eq!(f.got, b"abcdefgh");
        assert!(h.is_empty());
    }

    #[test]
    fn it_never_holds_more_than_its_size() {
        let mut h = Held::<8>::new();
        assert_eq!(h.push(b"0123456789"), 8);
        assert_eq!(h.room_len(), 0);
        assert!(h.room().is_empty());
        h.filled(3);
        assert_eq!(h.len(), 8);
        h.clear();
        assert_eq!(h.room_len(), 8);
    }
}

//! A single-producer single-consumer ring of step edges for one axis, lock-free: the
//! motion interrupt (producer) queues the period's edges, the step interrupt
//! (consumer, higher priority) plays them. The two sides are separate handles taken
//! once from a `'static` ring, so each interrupt owns its end and neither ever waits.

use core::cell::UnsafeCell;
use core::mem::MaybeUninit;
use core::sync::atomic::{AtomicBool, AtomicU32, Ordering};

/// What an edge does to the axis's pins.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Edge {
    /// Raise STEP (the fall follows after the pulse width, timed by the player).
    #[default]
    Step,
    /// Set DIR high (true = positive) or low.
    Dir(bool),
}

/// An edge and its time on the step timer, ticks (wrapping 32-bit counter).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Timed {
    /// Step timer count at which the edge is due.
    pub at: u32,
    /// What happens.
    pub edge: Edge,
}

/// Edge ring with `N` slots (`N` a power of two; one slot stays empty).
pub struct EdgeRing<const N: usize> {
    /// Slots (uninitialised until written: a `static` ring costs no flash for an
    /// initial image and lands in `.bss`).
    buf: UnsafeCell<[MaybeUninit<Timed>; N]>,
    /// Next slot the consumer reads (written by the consumer only).
    head: AtomicU32,
    /// Next slot the producer writes (written by the producer only).
    tail: AtomicU32,
    split: AtomicBool,
}

// SAFETY: the buffer is shared between exactly one Producer and one Consumer (split
// hands each out once). A slot is written by the producer only while it is outside
// head..tail and read by the consumer only while inside; the Release store of the
// index that moves a slot across that boundary orders the slot's contents.
unsafe impl<const N: usize> Sync for EdgeRing<N> {}

impl<const N: usize> EdgeRing<N> {
    const MASK: u32 = {
        assert!(N.is_power_of_two() && N >= 2 && N <= 1 << 16, "ring size must be a power of two");
        (N - 1) as u32
    };

    /// An empty ring.
    pub const fn new() -> Self {
        EdgeRing {
            buf: UnsafeCell::new([const { MaybeUninit::uninit() }; N]),
            head: AtomicU32::new(0),
            tail: AtomicU32::new(0),
            split: AtomicBool::new(false),
        }
    }

    /// The producer and consumer ends; `None` after the first call.
    pub fn split(&'static self) -> Option<(Producer<N>, Consumer<N>)> {
        if self.split.swap(true, Ordering::AcqRel) {
            return None;
        }
        Some((Producer { ring: self }, Consumer { ring: self }))
    }

    fn slot(&self, index: u32) -> *mut Timed {
        let base = self.buf.get().cast::<Timed>();
        // `index & MASK < N`: always inside the array.
        base.wrapping_add((index & Self::MASK) as usize)
    }
}

impl<const N: usize> Default for EdgeRing<N> {
    fn default() -> Self {
        Self::new()
    }
}

/// The queuing end of an [`EdgeRing`] (the motion interrupt's).
pub struct Producer<const N: usize> {
    ring: &'static EdgeRing<N>,
}

impl<const N: usize> Producer<N> {
    /// Queues `e`; gives it back when the ring is full.
    pub fn push(&mut self, e: Timed) -> Result<(), Timed> {
        let tail = self.ring.tail.load(Ordering::Relaxed);
        let head = self.ring.head.load(Ordering::Acquire);
        if tail.wrapping_sub(head) >= EdgeRing::<N>::MASK {
            return Err(e);
        }
        // SAFETY: the slot at `tail` is outside head..tail, so the consumer does not
        // read it, and only this (unique) producer writes.
        unsafe { self.ring.slot(tail).write(e) };
        self.ring.tail.store(tail.wrapping_add(1), Ordering::Release);
        Ok(())
    }

    /// Edges queued and not yet played.
    pub fn len(&self) -> u32 {
        self.ring.tail.load(Ordering::Relaxed).wrapping_sub(self.ring.head.load(Ordering::Acquire))
    }

    /// Nothing queued.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// The playing end of an [`EdgeRing`] (the step interrupt's).
pub struct Consumer<const N: usize> {
    ring: &'static EdgeRing<N>,
}

impl<const N: usize> Consumer<N> {
    /// The oldest queued edge.
    pub fn peek(&self) -> Option<Timed> {
        let head = self.ring.head.load(Ordering::Relaxed);
        let tail = self.ring.tail.load(Ordering::Acquire);
        if head == tail {
            return None;
        }
        // SAFETY: the slot at `head` is inside head..tail: the producer wrote it
        // (initialised) before its Release store of `tail` and does not touch it
        // until we move on.
        Some(unsafe { self.ring.slot(head).read() })
    }

    /// Drops the oldest queued edge (after [`Consumer::peek`] returned it).
    pub fn advance(&mut self) {
        let head = self.ring.head.load(Ordering::Relaxed);
        if head != self.ring.tail.load(Ordering::Acquire) {
            self.ring.head.store(head.wrapping_add(1), Ordering::Release);
        }
    }

    /// Drops every queued edge (emergency stop).
    pub fn clear(&mut self) {
        let tail = self.ring.tail.load(Ordering::Acquire);
        self.ring.head.store(tail, Ordering::Release);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fifo_until_full_then_gives_the_edge_back() {
        static RING: EdgeRing<4> = EdgeRing::new();
        let (mut tx, mut rx) = RING.split().unwrap();
        assert!(RING.split().is_none());
        for at in 1..=3 {
            tx.push(Timed { at, edge: Edge::Step }).unwrap();
        }
        assert_eq!(tx.push(Timed { at: 4, edge: Edge::Step }), Err(Timed { at: 4, edge: Edge::Step }));
        assert_eq!(tx.len(), 3);
        assert_eq!(rx.peek().map(|t| t.at), Some(1));
        rx.advance();
        tx.push(Timed { at: 9, edge: Edge::Dir(true) }).unwrap();
        let mut seen = [0; 3];
        for s in &mut seen {
            *s = rx.peek().unwrap().at;
            rx.advance();
        }
        assert_eq!(seen, [2, 3, 9]);
        assert_eq!(rx.peek(), None);
        rx.advance();
        assert!(tx.is_empty());
    }

    #[test]
    fn clear_drops_everything_queued() {
        static RING: EdgeRing<8> = EdgeRing::new();
        let (mut tx, mut rx) = RING.split().unwrap();
        for at in 0..5 {
            tx.push(Timed { at, edge: Edge::Step }).unwrap();
        }
        rx.clear();
        assert_eq!(rx.peek(), None);
        assert_eq!(tx.len(), 0);
    }
}

//! The step interrupt's logic: plays each axis's queued edges at their timer ticks
//! as GPIO set/reset words (one BSRR write sets or clears every pin that changes),
//! ends each step pulse after the driver's pulse width, and keeps the driver's
//! timing even when an edge comes late. While the e-stop input is active it raises
//! no STEP pin at all. Nothing here divides, allocates or touches the motion core.

use motion_core::stepgen::DriverTiming;

use crate::ring::{Consumer, Edge, Timed};
use crate::timebase::TimeBase;

/// Driver timing in step-timer ticks (from the machine's `pulse_ns`,
/// `dir_setup_ns` and step rate).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PlayTiming {
    /// STEP high time; also DIR hold after a step's fall.
    pub pulse: u32,
    /// DIR stable before a STEP rise.
    pub dir_setup: u32,
    /// Shortest time between two STEP rises.
    pub min_period: u32,
}

impl PlayTiming {
    /// The timing of a driver in ticks of `tb`, each rounded up (never shorter).
    pub fn new(t: DriverTiming, tb: &TimeBase) -> Self {
        let up = |ns: u32| tb.ticks(ns) + u32::from(tb.ns(tb.ticks(ns)) < u64::from(ns));
        PlayTiming { pulse: up(t.pulse_ns), dir_setup: up(t.dir_setup_ns), min_period: up(t.min_period_ns) }
    }

    /// The longest hold any edge can impose (older `ready` values are in the past).
    fn hold(&self) -> u32 {
        self.pulse.max(self.dir_setup).max(self.min_period)
    }
}

/// Pin numbers (0–15) of one axis's STEP and DIR lines on the step port.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AxisPins {
    /// STEP pin number.
    pub step: u8,
    /// DIR pin number.
    pub dir: u8,
}

/// What one run of the step interrupt does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Out {
    /// Word for the port's BSRR (low half sets pins, high half clears; 0 = nothing).
    pub bsrr: u32,
    /// Timer tick of the next edge (may already be due), `None` when nothing is queued.
    pub next: Option<u32>,
}

/// Whether tick `at` has come at `now` (wrapping counter; edges are within 2^31 ticks).
#[inline]
fn due(at: u32, now: u32) -> bool {
    now.wrapping_sub(at) as i32 >= 0
}

/// One axis's player.
struct PlayAxis<const N: usize> {
    rx: Consumer<N>,
    step_set: u32,
    step_clear: u32,
    dir_set: u32,
    dir_clear: u32,
    timing: PlayTiming,
    /// [`PlayTiming::hold`], kept.
    hold: u32,
    /// End of the running STEP pulse.
    fall_at: Option<u32>,
    /// No edge before this tick (driver timing after the last edge).
    ready: u32,
}

impl<const N: usize> PlayAxis<N> {
    /// When `e` may be played: its own time, or later if the driver needs it.
    fn when(&self, e: &Timed, now: u32) -> u32 {
        let ahead = self.ready.wrapping_sub(now);
        let ready_future = ahead != 0 && ahead <= self.hold;
        if ready_future && !due(self.ready, e.at) { self.ready } else { e.at }
    }

    /// Plays what is due at `now` (at most one edge, so DIR set-up and pulse width
    /// hold between edges of one axis); returns the BSRR bits and this axis's next time.
    #[inline]
    fn run(&mut self, now: u32, estop: bool) -> (u32, Option<u32>) {
        if let Some(f) = self.fall_at {
            if !due(f, now) {
                return (0, Some(f));
            }
            self.fall_at = None;
            // DIR hold and STEP low time after the fall, unless the step period is later.
            let hold = now.wrapping_add(self.timing.pulse);
            if due(self.ready, hold) {
                self.ready = hold;
            }
            return (self.step_clear, self.rx.peek().map(|e| self.when(&e, now)));
        }
        let Some(e) = self.rx.peek() else { return (0, None) };
        let at = self.when(&e, now);
        if !due(at, now) {
            return (0, Some(at));
        }
        self.rx.advance();
        let bits = match e.edge {
            Edge::Step if estop => 0,
            Edge::Step => {
                let fall = now.wrapping_add(self.timing.pulse);
                self.fall_at = Some(fall);
                self.ready = now.wrapping_add(self.timing.min_period);
                return (self.step_set, Some(fall));
            }
            Edge::Dir(positive) => {
                self.ready = now.wrapping_add(self.timing.dir_setup);
                if positive { self.dir_set } else { self.dir_clear }
            }
        };
        (bits, self.rx.peek().map(|e| self.when(&e, now)))
    }
}

/// The step player of `A` axes with rings of `N` edges.
pub struct Player<const N: usize, const A: usize> {
    axes: [PlayAxis<N>; A],
}

impl<const N: usize, const A: usize> Player<N, A> {
    /// A player for the axes' ring ends, pins and timings (all STEP and DIR pins on
    /// one GPIO port).
    pub fn new(axes: [(Consumer<N>, AxisPins, PlayTiming); A]) -> Self {
        Player {
            axes: axes.map(|(rx, pins, timing)| PlayAxis {
                rx,
                step_set: 1 << (pins.step & 15),
                step_clear: 1 << ((pins.step & 15) + 16),
                dir_set: 1 << (pins.dir & 15),
                dir_clear: 1 << ((pins.dir & 15) + 16),
                timing,
                hold: timing.hold(),
                fall_at: None,
                ready: 0,
            }),
        }
    }

    /// Plays every axis's edge that is due at timer tick `now`; `estop` suppresses
    /// STEP rises (the queued steps are dropped, pulses in progress end normally).
    pub fn run(&mut self, now: u32, estop: bool) -> Out {
        let mut bsrr = 0;
        let mut next: Option<u32> = None;
        for ax in &mut self.axes {
            let (bits, t) = ax.run(now, estop);
            bsrr |= bits;
            if let Some(t) = t {
                next = Some(match next {
                    Some(n) if (n.wrapping_sub(now) as i32) <= (t.wrapping_sub(now) as i32) => n,
                    _ => t,
                });
            }
        }
        Out { bsrr, next }
    }

    /// Drops every queued edge (after an emergency stop, before motion restarts).
    pub fn clear(&mut self) {
        for ax in &mut self.axes {
            ax.rx.clear();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ring::EdgeRing;
    use std::vec::Vec;

    const T: PlayTiming = PlayTiming { pulse: 210, dir_setup: 420, min_period: 840 };

    /// Runs the player like the interrupt does, from `from` to `to`, waking at every
    /// `next`; returns (tick, BSRR word) of every write.
    fn play<const N: usize, const A: usize>(p: &mut Player<N, A>, from: u32, to: u32, estop: bool) -> Vec<(u32, u32)> {
        let mut out = Vec::new();
        let mut now = from;
        while now <= to {
            let o = p.run(now, estop);
            if o.bsrr != 0 {
                out.push((now, o.bsrr));
            }
            match o.next {
                Some(n) if n.wrapping_sub(now) as i32 > 0 => now = n,
                Some(_) => now += 1,
                None => break,
            }
        }
        out
    }

    #[test]
    fn steps_and_directions_at_their_ticks_with_pulse_ends() {
        static RING: EdgeRing<16> = EdgeRing::new();
        let (mut tx, rx) = RING.split().unwrap();
        let mut p = Player::new([(rx, AxisPins { step: 6, dir: 10 }, T)]);
        tx.push(Timed { at: 1_000, edge: Edge::Dir(true) }).unwrap();
        tx.push(Timed { at: 1_420, edge: Edge::Step }).unwrap();
        tx.push(Timed { at: 3_000, edge: Edge::Step }).unwrap();
        let w = play(&mut p, 0, 10_000, false);
        assert_eq!(w, [(1_000, 1 << 10), (1_420, 1 << 6), (1_630, 1 << 22), (3_000, 1 << 6), (3_210, 1 << 22)]);
    }

    #[test]
    fn late_edges_keep_the_driver_timing() {
        static RING: EdgeRing<16> = EdgeRing::new();
        let (mut tx, rx) = RING.split().unwrap();
        let mut p = Player::new([(rx, AxisPins { step: 7, dir: 11 }, T)]);
        // All due at once (the interrupt was held up): DIR, then the set-up time,
        // then steps a full step period apart.
        tx.push(Timed { at: 100, edge: Edge::Dir(false) }).unwrap();
        tx.push(Timed { at: 110, edge: Edge::Step }).unwrap();
        tx.push(Timed { at: 120, edge: Edge::Step }).unwrap();
        let w = play(&mut p, 500, 10_000, false);
        assert_eq!(w, [(500, 1 << 27), (920, 1 << 7), (1_130, 1 << 23), (1_760, 1 << 7), (1_970, 1 << 23)]);
    }

    #[test]
    fn two_axes_share_one_write_and_estop_raises_no_step() {
        static RX: EdgeRing<16> = EdgeRing::new();
        static RZ: EdgeRing<16> = EdgeRing::new();
        let (mut tx, rx) = RX.split().unwrap();
        let (mut tz, rz) = RZ.split().unwrap();
        let mut p = Player::new([(rx, AxisPins { step: 6, dir: 10 }, T), (rz, AxisPins { step: 7, dir: 11 }, T)]);
        tx.push(Timed { at: 50, edge: Edge::Step }).unwrap();
        tz.push(Timed { at: 50, edge: Edge::Step }).unwrap();
        assert_eq!(play(&mut p, 0, 1_000, false), [(50, (1 << 6) | (1 << 7)), (260, (1 << 22) | (1 << 23))]);
        tx.push(Timed { at: 2_000, edge: Edge::Step }).unwrap();
        tz.push(Timed { at: 2_000, edge: Edge::Dir(true) }).unwrap();
        assert_eq!(play(&mut p, 1_500, 5_000, true), [(2_000, 1 << 11)]);
    }

    #[test]
    fn the_timer_wraps() {
        static RING: EdgeRing<16> = EdgeRing::new();
        let (mut tx, rx) = RING.split().unwrap();
        let mut p = Player::new([(rx, AxisPins { step: 8, dir: 12 }, T)]);
        tx.push(Timed { at: 100, edge: Edge::Step }).unwrap();
        let o = p.run(u32::MAX - 50, false);
        assert_eq!(o, Out { bsrr: 0, next: Some(100) });
        let o = p.run(100, false);
        assert_eq!(o, Out { bsrr: 1 << 8, next: Some(310) });
    }
}

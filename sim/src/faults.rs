//! Machine faults injected into the simulated machine, for the tests that check
//! that each one ends in a controlled stop with the right alarm: the spindle
//! encoder's signals lost for a while, the spindle slowed or stalled by a load
//! (or running away), the link going down, an axis losing steps (so the machine
//! is not where the controller believes and runs into a limit switch). E-stop,
//! feed hold and door are the operator's [`Switches`](crate::board::Switches).
//!
//! The faults act where the real ones would: on what the motion core reads (the
//! encoder count and index), on the spindle drive, on the wire, on the axes.

use interp_core::axis::Axis;
use motion_core::motion::Feedback;

use crate::Sim;

/// A span of simulated time, ns: `from` included, `until` not.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Span {
    /// Start, ns.
    pub from: u64,
    /// End, ns (`u64::MAX`: for good).
    pub until: u64,
}

impl Span {
    /// From `from` on, for good.
    pub fn from(from: u64) -> Self {
        Span { from, until: u64::MAX }
    }

    /// Whether `t` is inside.
    pub fn contains(&self, t: u64) -> bool {
        (self.from..self.until).contains(&t)
    }
}

/// The faults in force on a simulated machine ([`Sim::faults`]). None by default.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Faults {
    /// The encoder's signals are lost (cable, supply): the count and the index
    /// the motion core reads stand still while the spindle goes on turning.
    pub encoder_lost: Option<Span>,
    /// From this time (ns) the spindle turns at `factor` × its command: 0 stalled,
    /// 0.5 slowed by a load the drive cannot hold, 1.5 running away. It gets there
    /// at the drive's acceleration.
    pub spindle_load: Option<(u64, f64)>,
    /// From this time (ns) the link is down: nothing sent either way arrives.
    pub link_down: Option<u64>,
    /// What the encoder showed when its signals were lost.
    frozen: Option<Feedback>,
}

impl Faults {
    /// Whether the encoder's signals are lost at `t`.
    pub fn encoder_lost_at(&self, t: u64) -> bool {
        self.encoder_lost.is_some_and(|s| s.contains(t))
    }

    /// The encoder reading the motion core gets at `t`, the machine's being `real`.
    pub fn feedback(&mut self, t: u64, real: Feedback) -> Feedback {
        if self.encoder_lost_at(t) {
            *self.frozen.get_or_insert(real)
        } else {
            self.frozen = None;
            real
        }
    }

    /// The speed the spindle drive reaches at `t` for the commanded `rpm`.
    pub fn spindle_rpm(&self, t: u64, rpm: u32) -> u32 {
        match self.spindle_load {
            Some((from, factor)) if t >= from => (f64::from(rpm) * factor.max(0.0)).round() as u32,
            _ => rpm,
        }
    }

    /// Whether the link is down at `t`.
    pub fn link_down_at(&self, t: u64) -> bool {
        self.link_down.is_some_and(|from| t >= from)
    }
}

impl Sim {
    /// The axis loses (or gains) `nm` of travel at once, as a stepper that misses
    /// steps or a slipping coupling: the machine stands `nm` further than the
    /// motion core believes (it only counts the steps it issued).
    pub fn slip(&mut self, axis: Axis, nm: i64) {
        let i = axis.index();
        let steps = self.core.params().scale[i].steps(nm);
        if let Some(a) = self.axes.get_mut(i) {
            a.steps += steps;
        }
    }

    /// Step pulses the drivers have received, all axes.
    pub fn pulses(&self) -> u64 {
        self.axes.iter().map(|a| a.pulses).sum()
    }

    /// Driver timing violations (step rate, pulse, direction set-up), all axes.
    pub fn violations(&self) -> u32 {
        self.axes.iter().map(|a| a.violations).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lost_encoder_freezes_the_reading_until_it_returns() {
        let mut f = Faults { encoder_lost: Some(Span { from: 10, until: 20 }), ..Faults::default() };
        let r = |count| Feedback { count, index: Some(5) };
        assert_eq!(f.feedback(5, r(100)).count, 100);
        assert_eq!(f.feedback(10, r(110)).count, 110);
        assert_eq!(f.feedback(15, r(150)).count, 110);
        assert_eq!(f.feedback(19, r(190)), r(110));
        assert_eq!(f.feedback(20, r(200)).count, 200);
    }

    #[test]
    fn load_scales_the_spindle_from_its_time() {
        let f = Faults { spindle_load: Some((1_000, 0.5)), ..Faults::default() };
        assert_eq!((f.spindle_rpm(999, 600), f.spindle_rpm(1_000, 600)), (600, 300));
        let stall = Faults { spindle_load: Some((0, 0.0)), ..Faults::default() };
        assert_eq!(stall.spindle_rpm(5, 600), 0);
        assert!(Faults { link_down: Some(7), ..Faults::default() }.link_down_at(7));
        assert!(!Faults::default().link_down_at(u64::MAX));
    }
}

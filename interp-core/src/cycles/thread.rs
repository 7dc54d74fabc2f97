//! Threading: G32/G34 single thread blocks (2.17.1–2), the G92 thread cycle with
//! its pull-out and multiple starts (2.17.3) and the G76 multiple threading cycle
//! (2.17.4).
//!
//! Every thread move is an `Action::Thread` with the lead along the long axis, the
//! start angle after the spindle index and whether it waits for the index. A
//! pull-out (chamfer) at the end of a G92/G76 pass is a second thread move with
//! `ThreadSync::Continue` and the same lead: the long axis keeps its lead while the
//! short axis pulls out.

use super::StepQueue;
use super::emit::{Pt, Step};
use crate::alarm::AlarmKind;
use crate::axis::Axis;
use crate::canon::ThreadSync;

/// Micro-degrees in a turn.
const TURN_UDEG: i64 = 360_000_000;

/// The long axis of a thread from `a` to `b`: Z unless X moves more (2.17.3).
pub fn long_axis(a: Pt, b: Pt) -> Axis {
    if (b.z - a.z).abs() > (b.x - a.x).abs() { Axis::Z } else { Axis::X }
}

/// Pull-out of a thread from `b` to `c`: parameter 5130 (tenths of the lead `pitch`)
/// along the long axis, the short axis at the angle of 5131 from the long axis
/// (0 = 45°), never further than back to `retract_to` on the short axis (note 6).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pullout {
    /// Tenths of the pitch (5130 / G76 r).
    pub tenths: i64,
    /// Angle in degrees (5131), 0 = 45°.
    pub angle_deg: i64,
}

impl Pullout {
    /// The point where the pull-out starts and its end, or `None` without pull-out.
    /// Alarm 4034 if it is longer than the thread (2.17.3 note 5, 2.17.4 note 8).
    pub fn points(&self, b: Pt, c: Pt, pitch: i64, retract_to: i64) -> Result<Option<(Pt, Pt)>, AlarmKind> {
        let long = long_axis(b, c);
        let short = if long == Axis::Z { Axis::X } else { Axis::Z };
        let len = self.tenths.checked_mul(pitch).ok_or(AlarmKind::Overflow)? / 10;
        if len == 0 {
            return Ok(None);
        }
        let run = (c.get(long) - b.get(long)).abs();
        if len > run {
            return Err(AlarmKind::ThreadPulloutTooLong);
        }
        let t = (run - len) as f64 / run as f64;
        let p = Pt::new(lerp(b.x, c.x, t), lerp(b.z, c.z, t))
            .with(long, c.get(long) - (c.get(long) - b.get(long)).signum() * len);
        let deg = if self.angle_deg == 0 { 45.0 } else { self.angle_deg as f64 };
        let pull = libm::round(len as f64 * libm::tan(deg.to_radians())) as i64;
        let room = (retract_to - c.get(short)).abs();
        let pull = pull.min(room);
        let e = c.with(short, c.get(short) + (retract_to - c.get(short)).signum() * pull);
        Ok(Some((p, e)))
    }
}

#[inline(never)]
fn lerp(a: i64, b: i64, t: f64) -> i64 {
    a + libm::round((b - a) as f64 * t) as i64
}

/// The thread pass from `b` to `c` with its pull-out, as steps.
#[allow(clippy::too_many_arguments)]
fn pass(
    out: &mut StepQueue,
    b: Pt,
    c: Pt,
    lead: i64,
    pitch: i64,
    start_udeg: u32,
    pull: Pullout,
    retract_to: i64,
) -> Result<(), AlarmKind> {
    match pull.points(b, c, pitch, retract_to)? {
        Some((p, e)) => {
            push(out, Step::Thread { to: p, lead, delta: 0, start_udeg, sync: ThreadSync::Index })?;
            push(out, Step::Thread { to: e, lead, delta: 0, start_udeg, sync: ThreadSync::Continue })
        }
        None => push(out, Step::Thread { to: c, lead, delta: 0, start_udeg, sync: ThreadSync::Index }),
    }
}

/// G92: for each start, X to the thread start B, thread to C with pull-out,
/// rapid back to the start's X (③) and Z (④).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ThreadCycleGen {
    start: Pt,
    end: Pt,
    taper: i64,
    pitch: i64,
    starts: u8,
    pull: Pullout,
    next: u8,
}

impl ThreadCycleGen {
    /// G92 from `start` to `end` with taper R, pitch F and `starts` starts (lead = F·H).
    pub fn new(start: Pt, end: Pt, taper: i64, pitch: i64, starts: u8, pull: Pullout) -> Result<Self, AlarmKind> {
        let g = ThreadCycleGen { start, end, taper, pitch, starts, pull, next: 0 };
        // Validate the pull-out once (it is the same for every start).
        g.pull.points(g.b(), end, pitch, start.x)?;
        Ok(g)
    }

    fn b(&self) -> Pt {
        Pt::new(self.end.x + self.taper, self.start.z)
    }

    /// The lead: pitch × starts.
    pub fn lead(&self) -> i64 {
        self.pitch * i64::from(self.starts)
    }

    /// One start's pass; `false` when all are done.
    pub fn fill(&mut self, out: &mut StepQueue) -> Result<bool, AlarmKind> {
        if self.next >= self.starts {
            return Ok(false);
        }
        let angle = (i64::from(self.next) * TURN_UDEG / i64::from(self.starts)) as u32;
        let b = self.b();
        push(out, Step::Rapid(b))?;
        pass(out, b, self.end, self.lead(), self.pitch, angle, self.pull, self.start.x)?;
        let end_z = match self.pull.points(b, self.end, self.pitch, self.start.x)? {
            Some((_, e)) => e.z,
            None => self.end.z,
        };
        push(out, Step::Rapid(Pt::new(self.start.x, end_z)))?;
        push(out, Step::Rapid(self.start))?;
        self.next += 1;
        Ok(true)
    }
}

/// What G76 needs (all radius values, nm).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MultiThreadSpec {
    /// Start A.
    pub start: Pt,
    /// Thread end D.
    pub end: Pt,
    /// Taper i.
    pub taper: i64,
    /// Thread height k.
    pub height: i64,
    /// First depth Δd.
    pub first: i64,
    /// Minimum depth Δdmin.
    pub min_depth: i64,
    /// Finishing allowance d.
    pub allowance: i64,
    /// Finishing passes m.
    pub finish: u32,
    /// Tool angle a, degrees.
    pub angle_deg: u32,
    /// Lead.
    pub lead: i64,
    /// Pull-out.
    pub pull: Pullout,
}

/// Where G76 is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MultiThreadGen {
    spec: MultiThreadSpec,
    /// Rough passes done.
    n: u32,
    /// Depth of the last rough pass.
    depth: i64,
    /// Rough passes are over.
    rough_done: bool,
    /// Finishing passes done.
    finished: u32,
}

impl MultiThreadGen {
    /// Validates G76's values (notes 6–8, the missing P(k)/Q(Δd) alarm).
    pub fn new(spec: MultiThreadSpec) -> Result<Self, AlarmKind> {
        if spec.height <= 0 || spec.first <= 0 {
            return Err(AlarmKind::CycleValueIllegal { what: "G76 needs thread height P(k) and first depth Q(d) > 0" });
        }
        if spec.min_depth > spec.height || spec.allowance > spec.height {
            return Err(AlarmKind::CycleValueIllegal {
                what: "G76 minimum depth or finishing allowance above the height",
            });
        }
        if spec.end.x == spec.start.x {
            return Err(AlarmKind::CycleValueIllegal { what: "G76 end point X equals the start point X" });
        }
        if spec.finish == 0 {
            return Err(AlarmKind::CycleValueIllegal { what: "G76 finishing count m must be 01-99" });
        }
        let g = MultiThreadGen { spec, n: 0, depth: 0, rough_done: false, finished: 0 };
        let (b, c) = g.line(0);
        spec.pull.points(b, c, spec.lead, spec.start.x)?;
        let (b, c) = g.line(spec.height);
        spec.pull.points(b, c, spec.lead, spec.start.x)?;
        Ok(g)
    }

    /// Depth of rough pass `n` (1-based) after `prev`: the larger of √n·Δd and
    /// prev + Δdmin, and at most k − d (then it is the last rough pass).
    pub fn rough_depth(spec: &MultiThreadSpec, n: u32, prev: i64) -> (i64, bool) {
        let limit = spec.height - spec.allowance;
        let root = libm::round(libm::sqrt(f64::from(n)) * spec.first as f64) as i64;
        let d = if n == 1 { spec.first } else { root.max(prev + spec.min_depth) };
        if d >= limit { (limit, true) } else { (d, false) }
    }

    /// Start B_n and end of the pass at `depth`: from B shifted along the flank
    /// (tan(a/2) = |ΔZ|/|ΔX|, towards D) parallel to C→D up to D's Z.
    fn line(&self, depth: i64) -> (Pt, Pt) {
        let s = &self.spec;
        let inward = (s.end.x - s.start.x).signum();
        let c = Pt::new(s.end.x + s.taper, s.start.z);
        let b = Pt::new(c.x - inward * s.height, c.z);
        let half = (f64::from(s.angle_deg) / 2.0).to_radians();
        let dz = libm::round(depth as f64 * libm::tan(half)) as i64;
        let zdir = (s.end.z - s.start.z).signum();
        let bn = Pt::new(b.x + inward * depth, b.z + zdir * dz);
        let slope = (s.end.x - c.x) as f64 / (s.end.z - c.z) as f64;
        let xe = bn.x + libm::round(slope * (s.end.z - bn.z) as f64) as i64;
        (bn, Pt::new(xe, s.end.z))
    }

    /// One pass; `false` when the cycle is done.
    pub fn fill(&mut self, out: &mut StepQueue) -> Result<bool, AlarmKind> {
        let depth = if !self.rough_done {
            self.n += 1;
            let (d, last) = Self::rough_depth(&self.spec, self.n, self.depth);
            self.depth = d;
            self.rough_done = last;
            d
        } else if self.finished < self.spec.finish {
            self.finished += 1;
            self.spec.height
        } else {
            return Ok(false);
        };
        let s = self.spec;
        let (bn, e) = self.line(depth);
        push(out, Step::Rapid(bn))?;
        pass(out, bn, e, s.lead, s.lead, 0, s.pull, s.start.x)?;
        let end_z = match s.pull.points(bn, e, s.lead, s.start.x)? {
            Some((_, pe)) => pe.z,
            None => e.z,
        };
        push(out, Step::Rapid(Pt::new(s.start.x, end_z)))?;
        push(out, Step::Rapid(s.start))?;
        Ok(true)
    }
}

/// G32/G34: one thread move from `from` to `to`.
pub fn single(to: Pt, lead: i64, delta: i64, start_udeg: u32, chained: bool) -> Step {
    let sync = if chained { ThreadSync::Continue } else { ThreadSync::Index };
    Step::Thread { to, lead, delta, start_udeg, sync }
}

/// G34: alarm 0014 if the lead would reach zero or go negative, or exceed the
/// maximum, before the end of `length` (nm along the long axis).
pub fn check_variable_lead(lead: i64, delta: i64, length: i64, max: i64) -> Result<(), AlarmKind> {
    // After length L the lead is sqrt(F² + 2·K·L) (lead grows by K per revolution).
    let (f, k, l) = (lead as f64, delta as f64, length.abs() as f64);
    let sq = f * f + 2.0 * k * l;
    if sq <= 0.0 || libm::sqrt(sq) > max as f64 {
        return Err(AlarmKind::IllegalLead);
    }
    Ok(())
}

fn push(out: &mut StepQueue, s: Step) -> Result<(), AlarmKind> {
    out.push_back(s).map_err(|_| AlarmKind::Overflow)
}

#[cfg(test)]
mod tests {
    use super::*;

    const MM: i64 = 1_000_000;

    #[test]
    fn pullout_45_degrees_and_clamped_short_axis() {
        let p = Pullout { tenths: 10, angle_deg: 0 };
        let b = Pt::new(29_350_000, 5 * MM);
        let c = Pt::new(29_350_000, -28 * MM);
        let (s, e) = p.points(b, c, 3 * MM, 32_500_000).unwrap().unwrap();
        assert_eq!(s, Pt::new(29_350_000, -25 * MM));
        assert_eq!(e, Pt::new(32_350_000, -28 * MM));
        // Only 1 mm to retract: the short axis pulls out 1 mm (note 6).
        let (_, e) = p.points(b, c, 3 * MM, 30_350_000).unwrap().unwrap();
        assert_eq!(e, Pt::new(30_350_000, -28 * MM));
        // Longer than the thread: alarm (note 5).
        let p = Pullout { tenths: 200, angle_deg: 0 };
        assert_eq!(p.points(b, c, 3 * MM, 32_500_000), Err(AlarmKind::ThreadPulloutTooLong));
    }

    #[test]
    fn variable_lead_limits() {
        assert!(check_variable_lead(4 * MM, 200_000, 78 * MM, 500 * MM).is_ok());
        assert_eq!(check_variable_lead(4 * MM, -200_000, 78 * MM, 500 * MM), Err(AlarmKind::IllegalLead));
    }
}

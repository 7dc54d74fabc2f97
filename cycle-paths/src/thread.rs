//! Threading: G32/G34 single thread blocks (2.17.1–2), the G92 thread cycle with
//! its pull-out and multiple starts (2.17.3) and the G76 multiple threading cycle
//! (2.17.4).
//!
//! Every thread move is an `Action::Thread` with the lead along the long axis, the
//! start angle after the spindle index and whether it waits for the index. A
//! pull-out (chamfer) at the end of a G92/G76 pass is a second thread move with
//! `ThreadSync::Continue` and the same lead: the long axis keeps its lead while the
//! short axis pulls out.

use super::{StepQueue, sign};
use crate::alarm::AlarmKind;
use crate::axis::Axis;
use crate::canon::ThreadSync;
use crate::spec::job::CHAIN_POINTS;
use crate::step::push;
use crate::step::{Pt, Step};

/// Micro-degrees in a turn.
const TURN_UDEG: i64 = 360_000_000;

/// The long axis of a thread from `a` to `b`: Z unless X moves more (2.17.3).
pub fn long_axis(a: Pt, b: Pt) -> Axis {
    if (b.z - a.z).abs() > (b.x - a.x).abs() { Axis::Z } else { Axis::X }
}

pub use crate::spec::job::Pullout;

/// Pull-out of a thread from `b` to `c`: parameter 5130 (tenths of the lead `pitch`)
/// along the long axis, the short axis at the angle of 5131 from the long axis
/// (0 = 45°), never further than back to `retract_to` on the short axis (note 6).
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
            .with(long, c.get(long) - sign(c.get(long) - b.get(long)) * len);
        let deg = if self.angle_deg == 0 { 45.0 } else { self.angle_deg as f64 };
        let pull = crate::geom::round_i64(len as f64 * libm::tan(deg.to_radians()));
        let room = (retract_to - c.get(short)).abs();
        let pull = pull.min(room);
        let e = c.with(short, c.get(short) + sign(retract_to - c.get(short)) * pull);
        Ok(Some((p, e)))
    }
}

#[inline(never)]
fn lerp(a: i64, b: i64, t: f64) -> i64 {
    a + crate::geom::round_i64((b - a) as f64 * t)
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
            push(out, Step::Thread { to: e, lead, delta: 0, start_udeg, sync: ThreadSync::Continue })?;
        }
        None => push(out, Step::Thread { to: c, lead, delta: 0, start_udeg, sync: ThreadSync::Index })?,
    }
    Ok(())
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

pub use crate::spec::job::{Depths, Flank, MultiThreadSpec};

/// Where the infeed engine is (G76; CYCLE97, CYCLE98).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MultiThreadGen {
    spec: MultiThreadSpec,
    /// Thread start being cut (0-based).
    start_no: u32,
    /// Rough passes done.
    n: u32,
    /// Depth of the last rough pass.
    depth: i64,
    /// Rough passes are over.
    rough_done: bool,
    /// Passes at the full height done.
    finished: u32,
}

impl MultiThreadGen {
    /// Validates the values (G76 notes 6–8, the missing P(k)/Q(Δd) alarm; the
    /// front end checks its own cycle's values before).
    pub fn new(spec: MultiThreadSpec) -> Result<Self, AlarmKind> {
        if let Depths::Root { first, min_depth } = spec.depths {
            if spec.height <= 0 || first <= 0 {
                return Err(AlarmKind::CycleValueIllegal {
                    what: "G76 needs thread height P(k) and first depth Q(d) > 0",
                });
            }
            if min_depth > spec.height || spec.allowance > spec.height {
                return Err(AlarmKind::CycleValueIllegal {
                    what: "G76 minimum depth or finishing allowance above the height",
                });
            }
            if spec.finish == 0 {
                return Err(AlarmKind::CycleValueIllegal { what: "G76 finishing count m must be 01-99" });
            }
        }
        if spec.count < 2 || spec.count > spec.points.len() || spec.starts == 0 {
            return Err(AlarmKind::CycleValueIllegal { what: "thread without a length" });
        }
        let g = MultiThreadGen { spec, start_no: 0, n: 0, depth: 0, rough_done: false, finished: 0 };
        let lead = spec.leads[spec.count - 2];
        for d in [0, spec.height] {
            let (pts, n) = g.line(d, 0);
            spec.pull.points(pts[n - 2], pts[n - 1], lead, spec.retract)?;
        }
        Ok(g)
    }

    /// Depth of rough pass `n` (1-based) after `prev` and whether it is the last:
    /// G76 the larger of √n·Δd and prev + Δdmin; CYCLE97 constant infeed or
    /// constant cross-section. Never beyond k − d (then it is the last).
    pub fn rough_depth(spec: &MultiThreadSpec, n: u32, prev: i64) -> (i64, bool) {
        let limit = spec.height - spec.allowance;
        let d = match spec.depths {
            Depths::Root { first, min_depth } => {
                let root = crate::geom::round_i64(libm::sqrt(f64::from(n)) * first as f64);
                if n == 1 { first } else { root.max(prev + min_depth) }
            }
            // CYCLE97's spacings: only its front end makes them (without SINUMERIK
            // their code is left out; the same for the other `crate::SIEMENS` below).
            Depths::Split { .. } if !crate::SIEMENS => limit,
            Depths::Split { passes, constant_section } => {
                let passes = passes.max(1);
                let share = f64::from(n) / f64::from(passes);
                let share = if constant_section { libm::sqrt(share) } else { share };
                if n >= passes { limit } else { crate::geom::round_i64(limit as f64 * share) }
            }
        };
        if d >= limit { (limit, true) } else { (d, false) }
    }

    /// The long and the infeed axis.
    fn axes(&self) -> (Axis, Axis) {
        if crate::SIEMENS && self.spec.face { (Axis::X, Axis::Z) } else { (Axis::Z, Axis::X) }
    }

    /// The points of pass number `k` (0-based) at `depth`: the nominal line moved
    /// inward by the depth and along the long axis as the flank rule says.
    fn line(&self, depth: i64, k: u32) -> ([Pt; CHAIN_POINTS], usize) {
        let s = &self.spec;
        let (long, feed) = self.axes();
        let mut pts = s.points;
        // G76 has two points (A's and D's); a chain of more is CYCLE98's.
        let n = if crate::SIEMENS { s.count } else { 2 };
        for p in pts[..n].iter_mut() {
            *p = p.with(feed, p.get(feed) + s.inward * depth);
        }
        let dir = sign(s.points[n - 1].get(long) - s.points[0].get(long));
        match s.flank {
            Flank::FromStart { angle_udeg } => {
                // G76: the start moves towards the end, the pass ends at the end's long
                // coordinate on the line parallel to the thread.
                let (a, e) = (pts[0], pts[n - 1]);
                let shift = crate::geom::round_i64(depth as f64 * tan_udeg(angle_udeg));
                let bn = a.with(long, a.get(long) + dir * shift);
                let slope = (e.get(feed) - a.get(feed)) as f64 / (e.get(long) - a.get(long)) as f64;
                let fe = bn.get(feed) + crate::geom::round_i64(slope * (e.get(long) - bn.get(long)) as f64);
                pts[0] = bn;
                pts[n - 1] = e.with(feed, fe);
            }
            Flank::ToFinal { .. } if !crate::SIEMENS => {}
            Flank::ToFinal { angle_udeg, alternate } => {
                let side = if alternate && k % 2 == 1 { -1 } else { 1 };
                let shift = crate::geom::round_i64((s.height - depth) as f64 * tan_udeg(angle_udeg));
                for p in pts[..n].iter_mut() {
                    *p = p.with(long, p.get(long) + side * dir * shift);
                }
            }
        }
        (pts, n)
    }

    /// One pass; `false` when the cycle is done.
    pub fn fill(&mut self, out: &mut StepQueue) -> Result<bool, AlarmKind> {
        let s = self.spec;
        let depth = if !self.rough_done {
            self.n += 1;
            let (d, last) = Self::rough_depth(&s, self.n, self.depth);
            self.depth = d;
            self.rough_done = last;
            d
        } else if self.finished < s.finish {
            self.finished += 1;
            s.height
        } else if crate::SIEMENS && self.start_no + 1 < s.starts {
            // The next start: the whole sequence again (CYCLE97 NUMT).
            self.start_no += 1;
            (self.n, self.depth, self.rough_done, self.finished) = (0, 0, false, 0);
            return Ok(true);
        } else {
            return Ok(false);
        };
        if self.start_no == 0 && self.n + self.finished == 1 {
            // To the start point first (nothing for G76, which starts there).
            push(out, Step::Rapid(s.start))?;
        }
        let k = self.n + self.finished - 1;
        let turn = if crate::SIEMENS { i64::from(self.start_no) * TURN_UDEG / i64::from(s.starts) } else { 0 };
        let angle = ((i64::from(s.start_udeg) + turn) % TURN_UDEG) as u32;
        let (pts, n) = self.line(depth, k);
        let (long, feed) = self.axes();
        push(out, Step::Rapid(pts[0]))?;
        let last = n - 2;
        for i in 0..last {
            let sync = if i == 0 { ThreadSync::Index } else { ThreadSync::Continue };
            push(out, Step::Thread { to: pts[i + 1], lead: s.leads[i], delta: 0, start_udeg: angle, sync })?;
        }
        let lead = s.leads[last];
        let end = if last == 0 {
            pass(out, pts[0], pts[1], lead, lead, angle, s.pull, s.retract)?;
            match s.pull.points(pts[0], pts[1], lead, s.retract)? {
                Some((_, pe)) => pe,
                None => pts[1],
            }
        } else {
            let to = pts[last + 1];
            push(out, Step::Thread { to, lead, delta: 0, start_udeg: angle, sync: ThreadSync::Continue })?;
            to
        };
        push(out, Step::Rapid(end.with(feed, s.retract)))?;
        push(out, Step::Rapid(s.start.with(feed, s.retract).with(long, s.start.get(long))))?;
        Ok(true)
    }
}

/// tan of an angle in µdeg.
fn tan_udeg(udeg: i64) -> f64 {
    libm::tan((udeg as f64 / 1e6).to_radians())
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

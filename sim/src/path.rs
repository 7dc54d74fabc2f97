//! The programmed path, for measuring how far the simulated axes stray from it:
//! every motion action the motion core accepted, as a line, an arc (a spiral when
//! the end radius differs by the arc tolerance) or, for an independent rapid, the
//! box its dog-leg stays in.

use interp_core::axis::{AXIS_COUNT, Pos};
use interp_core::canon::Action;

type P = [f64; AXIS_COUNT];

fn pos(p: &Pos) -> P {
    p.0.map(|v| v as f64)
}

fn dist2(a: &P, b: &P) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

/// One programmed element.
#[derive(Clone, Debug, PartialEq)]
enum Element {
    Line { a: P, b: P },
    Arc { ia: usize, ib: usize, c: (f64, f64), r0: f64, r1: f64, th0: f64, sweep: f64, a: P, b: P },
    Box { lo: P, hi: P },
}

impl Element {
    /// The nearest point of the element to `p`.
    fn nearest(&self, p: &P) -> P {
        match self {
            Element::Line { a, b } => {
                let d: P = core::array::from_fn(|i| b[i] - a[i]);
                let len2: f64 = d.iter().map(|x| x * x).sum();
                let t = if len2 > 0.0 {
                    (d.iter().zip(p.iter().zip(a)).map(|(d, (p, a))| d * (p - a)).sum::<f64>() / len2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                core::array::from_fn(|i| a[i] + t * d[i])
            }
            Element::Arc { ia, ib, c, r0, r1, th0, sweep, a, b } => {
                let phi = (p[*ib] - c.1).atan2(p[*ia] - c.0);
                let tau = core::f64::consts::TAU;
                let along = if *sweep >= 0.0 { phi - th0 } else { th0 - phi }.rem_euclid(tau);
                if along > sweep.abs() {
                    return if dist2(p, a) < dist2(p, b) { *a } else { *b };
                }
                let f = along / sweep.abs();
                let r = r0 + (r1 - r0) * f;
                // A helix: the axes outside the plane move linearly with the arc.
                let mut q: P = core::array::from_fn(|i| a[i] + (b[i] - a[i]) * f);
                q[*ia] = c.0 + r * phi.cos();
                q[*ib] = c.1 + r * phi.sin();
                q
            }
            Element::Box { lo, hi } => core::array::from_fn(|i| p[i].clamp(lo[i], hi[i])),
        }
    }
}

/// The programmed path and where along it the machine is.
#[derive(Clone, Debug, Default)]
pub struct PathRef {
    elements: Vec<Element>,
    cursor: usize,
}

impl PathRef {
    /// Adds the element of a motion action starting at `from` (machine, nm).
    pub fn add(&mut self, from: &Pos, action: &Action) {
        // Like the planner: an action that does not move is no block.
        let full = matches!(action, Action::Arc(a) if a.full_circle);
        if action.endpoint().is_some_and(|e| e.machine == *from) && !full {
            return;
        }
        let a = pos(from);
        let element = match action {
            Action::Rapid(m) if m.independent => {
                let b = pos(&m.to.machine);
                Element::Box {
                    lo: core::array::from_fn(|i| a[i].min(b[i])),
                    hi: core::array::from_fn(|i| a[i].max(b[i])),
                }
            }
            Action::Rapid(m) | Action::Linear(m) => Element::Line { a, b: pos(&m.to.machine) },
            Action::Thread(t) => Element::Line { a, b: pos(&t.to.machine) },
            Action::Tap(t) => Element::Line { a, b: pos(&t.to.machine) },
            Action::Arc(arc) => {
                let (pa, pb) = arc.plane.axes();
                let (ia, ib) = (pa.index(), pb.index());
                let b = pos(&arc.to.machine);
                let c = (arc.center.machine.0[ia] as f64, arc.center.machine.0[ib] as f64);
                let th0 = (a[ib] - c.1).atan2(a[ia] - c.0);
                let th1 = (b[ib] - c.1).atan2(b[ia] - c.0);
                let tau = core::f64::consts::TAU;
                let mut sweep = th1 - th0;
                if arc.cw {
                    sweep = -(th0 - th1).rem_euclid(tau);
                    if sweep == 0.0 || arc.full_circle {
                        sweep = -tau;
                    }
                } else {
                    sweep = sweep.rem_euclid(tau);
                    if sweep == 0.0 || arc.full_circle {
                        sweep = tau;
                    }
                }
                let r0 = (a[ia] - c.0).hypot(a[ib] - c.1);
                let r1 = (b[ia] - c.0).hypot(b[ib] - c.1);
                Element::Arc { ia, ib, c, r0, r1, th0, sweep, a, b }
            }
            _ => return,
        };
        self.elements.push(element);
    }

    /// Elements recorded and the one the machine was last matched to.
    pub fn progress(&self) -> (usize, usize) {
        (self.elements.len(), self.cursor)
    }

    /// The error vector (nm per axis) from the path to `p` (machine, nm). The
    /// machine is on one of the elements from the last match up to `started` (the
    /// blocks the motion core has taken so far, plus one being taken); a later
    /// element must be nearer by half a nanometre to take over, so a path that comes
    /// back over itself is not skipped ahead on a tie.
    pub fn error(&mut self, p: &Pos, started: usize) -> P {
        let p = pos(p);
        if self.elements.is_empty() {
            return [0.0; AXIS_COUNT];
        }
        let lo = self.cursor.saturating_sub(1);
        let hi = (started + 1).clamp(lo + 1, self.elements.len());
        let mut best = (f64::MAX, self.cursor, [0.0; AXIS_COUNT]);
        for (k, e) in self.elements[lo..hi].iter().enumerate() {
            let q = e.nearest(&p);
            let d = dist2(&p, &q).sqrt();
            if d < best.0 - 0.5 {
                best = (d, lo + k, q);
            }
        }
        self.cursor = best.1;
        core::array::from_fn(|i| p[i] - best.2[i])
    }
}

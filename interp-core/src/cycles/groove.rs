//! G74 face (Z) and G75 outer (X) peck grooving, steps ① to ⑦ of 2.16.5–6.
//!
//! Written for G75 (peck along X, step along Z); G74 is the same with the axes
//! swapped. Columns A_n step by Δk from the start towards the end point's Z, the
//! last one at the end point's Z. In each column: feed Δi, rapid back e, feed
//! Δi + e, … until the next feed would reach B_n, then feed to B_n (①–③); relief Δd
//! along the step axis away from the end point (④; towards − when the end point is
//! level with the start); rapid back to the start's X (⑤); rapid to the next column
//! (⑥); after the last column rapid back to the start along the step axis (⑦).

use super::StepQueue;
use super::emit::{Pt, Step};
use crate::alarm::AlarmKind;
use crate::axis::Axis;

/// Where G74/G75 is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GrooveGen {
    /// Peck axis (X for G75, Z for G74).
    peck: Axis,
    /// Step axis.
    step: Axis,
    start: Pt,
    end: Pt,
    /// Peck depth per feed (Δi of G75, Δk of G74).
    peck_depth: i64,
    /// Column step (Δk of G75, Δi of G74).
    column: i64,
    relief: i64,
    retract: i64,
    /// Current column's position on the step axis.
    at: i64,
    /// Depth reached in the current column (peck axis); `None` before its first feed.
    depth: Option<i64>,
    done: bool,
}

impl GrooveGen {
    /// G75 (`face` false) or G74 from `start` to `end`. P/Q as written: `p` is Δi
    /// (X, radius), `q` is Δk (Z).
    pub fn new(face: bool, start: Pt, end: Pt, p: i64, q: i64, relief: i64, retract: i64) -> Result<Self, AlarmKind> {
        let (peck, step, peck_depth, column) = if face { (Axis::Z, Axis::X, q, p) } else { (Axis::X, Axis::Z, p, q) };
        if column == 0 && end.get(step) != start.get(step) {
            return Err(AlarmKind::CycleValueIllegal { what: "G74/G75 step P/Q is zero with a width to cut" });
        }
        Ok(GrooveGen {
            peck,
            step,
            start,
            end,
            peck_depth,
            column,
            relief,
            retract,
            at: start.get(step),
            depth: None,
            done: false,
        })
    }

    /// The next group of steps; `false` when finished.
    pub fn fill(&mut self, out: &mut StepQueue) -> Result<bool, AlarmKind> {
        if self.done {
            return Ok(false);
        }
        let (a0, b0) = (self.start.get(self.peck), self.end.get(self.peck));
        let dir = (b0 - a0).signum();
        let pt = |p: i64, s: i64, g: &Self| Pt::default().with(g.peck, p).with(g.step, s);
        let reached = self.depth.unwrap_or(a0);
        if reached != b0 {
            // ①–③: feed to the next depth (or the bottom), then back e unless at the bottom.
            let next = if self.peck_depth == 0 { b0 } else { reached + dir * self.peck_depth };
            let next = if (b0 - next) * dir <= 0 { b0 } else { next };
            push(out, Step::Feed(pt(next, self.at, self)))?;
            self.depth = Some(next);
            if next != b0 {
                push(out, Step::Rapid(pt(next - dir * self.retract, self.at, self)))?;
            }
            return Ok(true);
        }
        // ④ relief, ⑤ back to the start's peck coordinate.
        let (s0, s1) = (self.start.get(self.step), self.end.get(self.step));
        let sdir = (s1 - s0).signum();
        let relief_dir = if sdir == 0 { -1 } else { -sdir };
        let relieved = self.at + relief_dir * self.relief;
        push(out, Step::Rapid(pt(b0, relieved, self)))?;
        push(out, Step::Rapid(pt(a0, relieved, self)))?;
        if self.at == s1 {
            // ⑦ back to the start.
            push(out, Step::Rapid(self.start))?;
            self.done = true;
            return Ok(true);
        }
        // ⑥ next column (Δd + Δk from the relieved point), the last at the end's value.
        let next = self.at + sdir * self.column;
        self.at = if (s1 - next) * sdir <= 0 { s1 } else { next };
        push(out, Step::Rapid(pt(a0, self.at, self)))?;
        self.depth = None;
        Ok(true)
    }
}

fn push(out: &mut StepQueue, s: Step) -> Result<(), AlarmKind> {
    out.push_back(s).map_err(|_| AlarmKind::Overflow)
}

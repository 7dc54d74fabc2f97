//! G73 pattern repeating (2.16.3): d passes along the shape A→B→C, each a
//! translated copy. Pass n (1-based) is offset from the shape by
//! (Δi·(d−n)/(d−1) + Δu/2, Δk·(d−n)/(d−1) + Δw): the first pass by (Δi + Δu/2,
//! Δk + Δw), the last by (Δu/2, Δw), each the previous one moved by
//! (Δi/(d−1), Δk/(d−1)) — the definitions table in radius values. With d = 1 the
//! single pass is the last one.
//!
//! A pass: rapid to A_n, the ns move A_n→B_n in its own G00/G01, the rest of the
//! shape at the cycle's feed, then X back to the start's X and Z to its Z.

use super::StepQueue;
use super::profile::Profile;
use crate::alarm::AlarmKind;
use crate::step::contour_step;
use crate::step::push;
use crate::step::{Pt, Step};

/// Where G73 is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PatternGen {
    start: Pt,
    /// Δi (radius) and Δk.
    relief: Pt,
    /// Δu/2 and Δw.
    allowance: Pt,
    count: u32,
    /// Pass being cut (1-based); `count + 1` when done.
    pass: u32,
    /// Next segment of the pass (0 = rapid to A_n and the ns move).
    seg: usize,
}

impl PatternGen {
    /// G73 from `start` with relief Δi/Δk, `count` passes and the allowances.
    pub fn new(start: Pt, relief: Pt, count: u32, allowance: Pt) -> Result<Self, AlarmKind> {
        if count == 0 || count > 9_999 {
            return Err(AlarmKind::CycleValueIllegal { what: "G73 number of passes must be 1-9999" });
        }
        Ok(PatternGen { start, relief, allowance, count, pass: 1, seg: 0 })
    }

    /// The offset of pass `n` from the shape.
    pub fn offset(&self, n: u32) -> Pt {
        let left = i64::from(self.count.saturating_sub(n));
        let div = i64::from(self.count.max(2) - 1);
        let part = |v: i64| if self.count == 1 { 0 } else { share(v, left, div) };
        Pt::new(part(self.relief.x) + self.allowance.x, part(self.relief.z) + self.allowance.z)
    }

    /// The next group of steps; `false` when finished.
    pub fn fill(&mut self, profile: &Profile, out: &mut StepQueue) -> Result<bool, AlarmKind> {
        self.fill_segs(&profile.segs, profile.ns_rapid, out)
    }

    /// [`PatternGen::fill`] over a shape `segs` whose first segment is the move from
    /// the start point onto it (G00 if `ns_rapid`).
    pub fn fill_segs(
        &mut self,
        segs: &[super::profile::Seg],
        ns_rapid: bool,
        out: &mut StepQueue,
    ) -> Result<bool, AlarmKind> {
        if self.pass > self.count {
            return Ok(false);
        }
        let d = self.offset(self.pass);
        if self.seg == 0 {
            let a_n = Pt::new(self.start.x + d.x, self.start.z + d.z);
            push(out, Step::Rapid(a_n))?;
            let ns = segs[0].shifted(d);
            push(out, if ns_rapid { Step::Rapid(ns.b) } else { Step::Feed(ns.b) })?;
            self.seg = 1;
        } else if let Some(s) = segs.get(self.seg) {
            push(out, contour_step(&s.shifted(d)))?;
            self.seg += 1;
        } else {
            let here = segs.last().map(|s| s.shifted(d).b).unwrap_or(self.start);
            push(out, Step::Rapid(Pt::new(self.start.x, here.z)))?;
            push(out, Step::Rapid(self.start))?;
            self.pass += 1;
            self.seg = 0;
        }
        Ok(true)
    }
}

/// `v · left / div` rounded, for one axis of a pass's offset (out of line: X and Z
/// share it). |v| < 1e15 nm (nine digits of mm) and left < 10⁴: the product fits.
#[inline(never)]
fn share(v: i64, left: i64, div: i64) -> i64 {
    crate::units::div_round(v.saturating_mul(left), div)
}

//! One pass along a contour with the nose compensated ([`super::offset`]): rapids
//! to where it begins, a feed onto its first point, its elements at the pass's feed,
//! rapids away. The finishing pass of CYCLE95, the undercuts of CYCLE94/CYCLE96 and
//! the finishing of CYCLE93's groove sides are such passes over contours kept in
//! the expansion's profile.

use super::StepQueue;
use super::offset::{Offsets, nth};
use crate::alarm::AlarmKind;
use crate::geom::{Pt, Seg, SegKind};
use crate::step::Step;
use crate::step::push;

/// Where a pass is.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Phase {
    In,
    Walk(u16),
    Out,
    Done,
}

/// Most rapids before or after the path.
pub const LEADS: usize = 3;

/// A pass along `raw[from..to]` of the profile.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PassGen {
    offsets: Offsets,
    from: u16,
    to: u16,
    /// Added to every point of the path: the positions of another cutting edge of
    /// the tool expressed for the edge whose offset is in force.
    shift: Pt,
    /// Rapids before the path ([`Pt`]s; unused ones are `None`).
    before: [Option<Pt>; LEADS],
    /// Feed along the path (in the cycle's feed mode); 0 = the cycle's feed.
    feed: i64,
    /// Rapids after it.
    after: [Option<Pt>; LEADS],
    /// Feed on the path's arcs (CYCLE950 `_FF4`); 0 = `feed`.
    arc_feed: i64,
    phase: Phase,
}

impl PassGen {
    /// A pass along `raw[from..to]` moved by `offsets` (and `shift`), entered with
    /// the rapids `before`, left with the rapids `after`, at `feed`.
    pub fn new(
        offsets: Offsets,
        (from, to): (u16, u16),
        shift: Pt,
        before: [Option<Pt>; LEADS],
        feed: i64,
        after: [Option<Pt>; LEADS],
    ) -> Self {
        PassGen { offsets, from, to, shift, before, feed, after, arc_feed: 0, phase: Phase::In }
    }

    /// The pass with its arcs at `feed` (0: the path's feed).
    pub fn arcs_at(mut self, feed: i64) -> Self {
        self.arc_feed = feed;
        self
    }

    /// Element `k` of the pass's path (shifted), if it has one.
    pub fn element(&self, raw: &[Seg], k: u16) -> Result<Option<Seg>, AlarmKind> {
        let part = raw.get(usize::from(self.from)..usize::from(self.to)).unwrap_or(&[]);
        Ok(nth(part, &self.offsets, k)?.map(|s| shifted(&s, self.shift)))
    }

    /// The next steps; false when the pass is done.
    pub fn fill(&mut self, raw: &[Seg], out: &mut StepQueue) -> Result<bool, AlarmKind> {
        match self.phase {
            Phase::In => {
                for p in self.before.iter().flatten() {
                    push(out, Step::Rapid(*p))?;
                }
                if self.feed > 0 {
                    push(out, Step::Feedrate(self.feed))?;
                }
                if let Some(first) = self.element(raw, 0)? {
                    push(out, Step::Feed(first.a))?;
                }
                self.phase = Phase::Walk(0);
            }
            Phase::Walk(k) => {
                let mut k = k;
                while out.len() + 3 <= out.capacity() {
                    match self.element(raw, k)? {
                        Some(s) => {
                            let arc = matches!(s.kind, SegKind::Arc { .. }) && self.arc_feed > 0;
                            if arc {
                                push(out, Step::Feedrate(self.arc_feed))?;
                            }
                            push(out, along(&s))?;
                            if arc && self.feed > 0 {
                                push(out, Step::Feedrate(self.feed))?;
                            }
                        }
                        None => {
                            self.phase = Phase::Out;
                            return Ok(true);
                        }
                    }
                    k += 1;
                }
                self.phase = Phase::Walk(k);
            }
            Phase::Out => {
                for p in self.after.iter().flatten() {
                    push(out, Step::Rapid(*p))?;
                }
                self.phase = Phase::Done;
            }
            Phase::Done => return Ok(false),
        }
        Ok(true)
    }
}

/// `s` moved by `d`.
fn shifted(s: &Seg, d: Pt) -> Seg {
    if d == Pt::default() {
        return *s;
    }
    s.shifted(d)
}

/// The move along a segment (a contour's rapids too at the pass's feed). Out of
/// line: five callers in the passes and the roughing's sections.
#[inline(never)]
pub fn along(s: &Seg) -> Step {
    match s.kind {
        // A piece of an arc rounded to nothing is no move (not a full circle).
        SegKind::Arc { center, cw } if s.a != s.b => Step::Arc { to: s.b, center, cw },
        _ => Step::Feed(s.b),
    }
}

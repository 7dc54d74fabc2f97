//! G71 (stock removal in turning) and G72 (in facing), types I and II (2.16.1–2).
//!
//! One algorithm serves both codes and all four allowance quadrants: it works in a
//! normalised frame where `u` is the infeed ("level") axis measured outward from
//! the part and `w` the cutting axis measured along the cut. G71 has level axis X
//! and cuts along Z; G72 has level axis Z and cuts along X.
//!
//! The rough contour is the shape B→C shifted by the allowances (Δu/2, Δw; type II
//! ignores Δw, note 2). Levels are `u_k = u_A − k·Δd` while above the lowest contour
//! point. At a level, the material still to cut is every `w` from the start's `w_A`
//! to C' where the contour lies below the level (before B' there is no part). Each
//! maximal run is one cut. Cuts are taken depth-first: the cuts of a level are
//! nested in the cut above them, and a pocket is finished to its bottom before the
//! next pocket (type II, note 3). Type I shapes give one cut per level.
//!
//! Moves of one cut: up to the safe height (the level above + e, all air), along to
//! the cut's start, infeed (the ns block's G00/G01 at the start side; G01 into a
//! pocket, note 3), cut along `w`, 45° retract by e. Then the contour pass B'→C' at
//! the cycle's feed, and back to the start point (X first for G71, Z first for G72;
//! type II first retracts to the start + allowance + Δd, note 7).

use super::emit::{Pt, Step};
use super::profile::{Profile, Seg, SegKind};
use crate::alarm::AlarmKind;
use crate::axis::Axis;

/// Most cuts one level may have (10 pockets and the start side).
const MAX_RUNS: usize = 12;

/// The normalised frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Frame {
    /// Infeed axis (X for G71, Z for G72).
    pub level: Axis,
    /// Cutting axis.
    pub cut: Axis,
    /// +1 if outward is the positive direction of the level axis.
    pub out: i64,
    /// +1 if cutting runs towards positive on the cutting axis.
    pub dir: i64,
}

impl Frame {
    /// (u, w) of a work point.
    pub fn norm(&self, p: Pt) -> (i64, i64) {
        (self.out * p.get(self.level), self.dir * p.get(self.cut))
    }

    /// The work point of (u, w).
    #[inline(never)]
    pub fn work(&self, u: i64, w: i64) -> Pt {
        Pt::default().with(self.level, self.out * u).with(self.cut, self.dir * w)
    }
}

/// A run of material to cut at one level, normalised.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Run {
    w0: f64,
    w1: f64,
}

/// The G71/G72 expansion: where it is in the depth-first walk.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughGen {
    frame: Frame,
    /// Start point, normalised.
    a: (i64, i64),
    depth: i64,
    retract: i64,
    /// Lowest level (exclusive): the innermost contour point.
    bottom: i64,
    /// Height to retract to before returning (type II note 7).
    return_u: i64,
    type2: bool,
    /// G00 infeed (the ns block's mode).
    rapid_infeed: bool,
    phase: Phase,
    level: i64,
    run: Run,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Phase {
    Start,
    Rough,
    Contour(usize),
    Return,
    Done,
}

/// What G71/G72 is asked to do.
pub struct RoughSpec {
    /// G72 (facing) instead of G71.
    pub facing: bool,
    /// Start point A.
    pub start: Pt,
    /// Δd and e.
    pub depth: i64,
    /// e.
    pub retract: i64,
    /// Δu as a radius and Δw.
    pub allowance: Pt,
}

impl RoughGen {
    /// Validates the shape (notes of 2.16.1, 2.16.7) and shifts it by the
    /// allowances in place. `profile` must start at `spec.start`.
    pub fn new(spec: &RoughSpec, profile: &mut Profile) -> Result<RoughGen, AlarmKind> {
        if spec.depth <= 0 {
            return Err(AlarmKind::CycleValueIllegal { what: "depth of cut must be positive" });
        }
        let (level, cut) = if spec.facing { (Axis::Z, Axis::X) } else { (Axis::X, Axis::Z) };
        let type2 = profile.ns_x && profile.ns_z;
        let ns_cut_axis = if cut == Axis::Z { profile.ns_z } else { profile.ns_x };
        let ns_level_axis = if level == Axis::X { profile.ns_x } else { profile.ns_z };
        if !type2 && (ns_cut_axis || !ns_level_axis) {
            return Err(AlarmKind::ProfileFirstBlock);
        }
        let mut shift = spec.allowance;
        if type2 {
            // Note 2: a pocket shape takes the X allowance only (G72: the Z one).
            shift = shift.with(cut, 0);
        }
        for s in profile.segs.iter_mut() {
            *s = s.shifted(shift);
        }
        let first = *profile.segs.first().ok_or(AlarmKind::ProfileFirstBlock)?;
        let last = *profile.segs.last().ok_or(AlarmKind::ProfileFirstBlock)?;
        let b = first.b;
        let c = last.b;
        let a = spec.start;
        let out = sign(a.get(level) - b.get(level));
        let dir = sign(c.get(cut) - b.get(cut));
        if out == 0 {
            return Err(AlarmKind::ProfileFirstBlock);
        }
        if dir == 0 {
            return Err(AlarmKind::ProfileNotMonotone);
        }
        let frame = Frame { level, cut, out, dir };
        if frame.norm(c).1 <= frame.norm(a).1 {
            // The allowance pushed C' back past the start point: there is nothing to
            // rough, and a "cut" would run backwards, away from the part.
            return Err(AlarmKind::CycleValueIllegal {
                what: "the shape shifted by the allowances ends before the start point",
            });
        }
        let shape = &profile.segs[1..];
        check_monotone(&frame, if type2 { &profile.segs[..] } else { shape }, type2)?;
        let bottom = shape.iter().map(|s| lowest(&frame, s)).min().unwrap_or(frame.norm(b).0).min(frame.norm(b).0);
        let a_n = frame.norm(a);
        let return_u = if type2 { a_n.0 + spec.allowance.get(level).abs() + spec.depth } else { a_n.0 };
        let generator = RoughGen {
            frame,
            a: a_n,
            depth: spec.depth,
            retract: spec.retract,
            bottom,
            return_u,
            type2,
            rapid_infeed: profile.ns_rapid,
            phase: Phase::Start,
            level: 0,
            run: Run { w0: 0.0, w1: 0.0 },
        };
        generator.count_pockets(shape)?;
        Ok(generator)
    }

    /// The next group of steps (at most 6); `false` when the cycle is finished.
    pub fn fill(&mut self, profile: &Profile, here: Pt, out: &mut super::StepQueue) -> Result<bool, AlarmKind> {
        let full = &profile.segs[..];
        let shape = &profile.segs[1..];
        match self.phase {
            Phase::Start => {
                self.phase = Phase::Rough;
                match self.first_run(full)? {
                    Some((lv, run)) => self.cut(lv, run, here, 0, out)?,
                    None => self.phase = Phase::Contour(0),
                }
            }
            Phase::Rough => match self.next_run(full)? {
                Some((lv, run, safe)) => self.cut(lv, run, here, safe, out)?,
                None => {
                    self.approach_contour(profile, here, out)?;
                    self.phase = Phase::Contour(0);
                }
            },
            Phase::Contour(i) => match shape.get(i) {
                Some(s) => {
                    push(out, contour_step(s))?;
                    self.phase = Phase::Contour(i + 1);
                }
                None => self.phase = Phase::Return,
            },
            Phase::Return => {
                let (u, _) = self.frame.norm(here);
                let f = &self.frame;
                let up = u.max(self.return_u);
                push(out, Step::Rapid(f.work(up, f.norm(here).1)))?;
                push(out, Step::Rapid(f.work(up, self.a.1)))?;
                push(out, Step::Rapid(f.work(self.a.0, self.a.1)))?;
                self.phase = Phase::Done;
            }
            Phase::Done => return Ok(false),
        }
        Ok(self.phase != Phase::Done)
    }

    /// Level `k`'s u.
    fn level_u(&self, k: i64) -> i64 {
        self.a.0 - k * self.depth
    }

    /// The first cut: the first run of the first level above the bottom.
    fn first_run(&mut self, shape: &[Seg]) -> Result<Option<(i64, Run)>, AlarmKind> {
        let mut k = 1;
        while self.level_u(k) > self.bottom {
            if let Some(r) = self.runs(shape, self.level_u(k))?.first() {
                self.level = k;
                self.run = *r;
                return Ok(Some((k, *r)));
            }
            k += 1;
        }
        Ok(None)
    }

    /// The next cut in depth-first order, with the level whose height + e is safe to
    /// travel at on the way there.
    fn next_run(&mut self, shape: &[Seg]) -> Result<Option<(i64, Run, i64)>, AlarmKind> {
        let k = self.level;
        // A child: the first run of the level below inside this one.
        if self.level_u(k + 1) > self.bottom {
            let cur = self.run;
            if let Some(r) = self.runs(shape, self.level_u(k + 1))?.iter().find(|r| inside(r, &cur)) {
                self.level = k + 1;
                self.run = *r;
                return Ok(Some((k + 1, *r, k)));
            }
        }
        // Else the next sibling, or the next sibling of an ancestor.
        let mut lv = k;
        let mut cur = self.run;
        while lv >= 1 {
            let parent = if lv == 1 {
                None
            } else {
                self.runs(shape, self.level_u(lv - 1))?.into_iter().find(|p| inside(&cur, p))
            };
            let runs = self.runs(shape, self.level_u(lv))?;
            let sibling = runs.iter().find(|r| r.w0 > cur.w1 && parent.is_none_or(|p| inside(r, &p)));
            if let Some(r) = sibling {
                self.level = lv;
                self.run = *r;
                return Ok(Some((lv, *r, lv - 1)));
            }
            match parent {
                Some(p) => cur = p,
                None => break,
            }
            lv -= 1;
        }
        Ok(None)
    }

    /// Steps of one cut at level `k`: up to the safe height, along, infeed, cut, retract.
    fn cut(&self, k: i64, run: Run, here: Pt, safe: i64, out: &mut super::StepQueue) -> Result<(), AlarmKind> {
        let f = self.frame;
        let u = self.level_u(k);
        let h = if safe == 0 { self.a.0 } else { self.level_u(safe) + self.retract };
        let (hu, hw) = f.norm(here);
        // Rounded to whole nm away from the shape, so a cut never ends inside it.
        let w0 = libm::ceil(run.w0 - 1e-6) as i64;
        let w1 = libm::floor(run.w1 + 1e-6) as i64;
        if hu < h {
            push(out, Step::Rapid(f.work(h, hw)))?;
        }
        let top = hu.max(h);
        push(out, Step::Rapid(f.work(top, w0)))?;
        if w0 == self.a.1 {
            let p = f.work(u, w0);
            push(out, if self.rapid_infeed { Step::Rapid(p) } else { Step::Feed(p) })?;
        } else {
            push(out, Step::Feed(f.work(u, w0)))?;
        }
        push(out, Step::Feed(f.work(u, w1)))?;
        let back = self.retract.min(w1 - w0);
        push(out, Step::Feed(f.work(u + self.retract, w1 - back)))
    }

    /// Up to the start level, along to B', down to B' with the ns block's mode.
    fn approach_contour(&self, profile: &Profile, here: Pt, out: &mut super::StepQueue) -> Result<(), AlarmKind> {
        let f = self.frame;
        let b = profile.segs[0].b;
        let (bu, bw) = f.norm(b);
        let (hu, hw) = f.norm(here);
        // Type I: the way back along the last cut is air. Type II: bumps between
        // pockets, so over the start level.
        let top = if self.type2 { hu.max(self.a.0) } else { hu };
        push(out, Step::Rapid(f.work(top, hw)))?;
        push(out, Step::Rapid(f.work(top, bw)))?;
        let p = f.work(bu, bw);
        push(out, if self.rapid_infeed { Step::Rapid(p) } else { Step::Feed(p) })
    }

    /// The runs of material at level `u`, in cutting order.
    fn runs(&self, full: &[Seg], u: i64) -> Result<heapless::Vec<Run, MAX_RUNS>, AlarmKind> {
        let f = &self.frame;
        let uf = u as f64;
        let mut out: heapless::Vec<Run, MAX_RUNS> = heapless::Vec::new();
        let wa = self.a.1 as f64;
        let mut add = |w0: f64, w1: f64| -> Result<(), AlarmKind> {
            let (w0, w1) = (w0.max(wa), w1);
            if w1 <= w0 {
                return Ok(());
            }
            if let Some(l) = out.last_mut()
                && (w0 - l.w1).abs() < 0.5
            {
                l.w1 = w1;
                return Ok(());
            }
            out.push(Run { w0, w1 }).map_err(|_| AlarmKind::TooManyPockets)
        };
        // Type I: before B' there is no part. Type II: the ns move A'→B' bounds the
        // cuts too ("the first cut need not be vertical", figure 2.35).
        let shape = if self.type2 { full } else { &full[1..] };
        if !self.type2
            && let Some(s0) = shape.first()
        {
            let wb = f.norm(s0.a).1 as f64;
            if wb > wa {
                add(wa, wb)?;
            }
        }
        for s in shape {
            let wn = |t: f64| {
                let p = s.point_at(t);
                f.dir as f64 * if f.cut == Axis::X { p.0 } else { p.1 }
            };
            below(f, s, uf, |t0, t1| add(wn(t0), wn(t1)))?;
        }
        Ok(out)
    }

    /// Alarm 4036 for more than 10 pockets: descents after a rise.
    fn count_pockets(&self, shape: &[Seg]) -> Result<(), AlarmKind> {
        let mut rising = false;
        let mut pockets = 0;
        for s in shape {
            let du = self.frame.norm(s.b).0 - self.frame.norm(s.a).0;
            if du > 0 {
                rising = true;
            } else if du < 0 && rising {
                pockets += 1;
                rising = false;
            }
        }
        if pockets > 10 { Err(AlarmKind::TooManyPockets) } else { Ok(()) }
    }
}

/// Calls `add(t0, t1)` for each piece of `s` (parameters along it) that lies below
/// level `u` of frame `f`, in order: the material a cut at that level reaches.
#[inline]
pub fn below(
    f: &Frame,
    s: &Seg,
    u: f64,
    mut add: impl FnMut(f64, f64) -> Result<(), AlarmKind>,
) -> Result<(), AlarmKind> {
    below_dyn(f, s, u, &mut add)
}

/// [`below`] with the visitor behind a reference (one copy in flash).
#[inline(never)]
fn below_dyn(
    f: &Frame,
    s: &Seg,
    u: f64,
    add: &mut dyn FnMut(f64, f64) -> Result<(), AlarmKind>,
) -> Result<(), AlarmKind> {
    let mut ts: heapless::Vec<f64, 4> = heapless::Vec::new();
    let _ = ts.push(0.0);
    for t in s.crossings(f.level, f.out as f64 * u) {
        let _ = ts.push(t);
    }
    let _ = ts.push(1.0);
    for pair in ts.windows(2) {
        let (t0, t1) = (pair[0], pair[1]);
        let mid = s.point_at((t0 + t1) / 2.0);
        let umid = f.out as f64 * if f.level == Axis::X { mid.0 } else { mid.1 };
        if umid < u {
            add(t0, t1)?;
        }
    }
    Ok(())
}

/// Both types need the shape monotone along the cut (alarm 0064, note 4); type I
/// also along the infeed axis, outward from B (alarm 0329).
fn check_monotone(f: &Frame, shape: &[Seg], type2: bool) -> Result<(), AlarmKind> {
    for s in shape {
        let (au, aw) = f.norm(s.a);
        let (bu, bw) = f.norm(s.b);
        if bw < aw || !within(s.extent(f.cut), s.a.get(f.cut), s.b.get(f.cut)) {
            return Err(AlarmKind::ProfileNotMonotone);
        }
        if !type2 && (bu < au || !within(s.extent(f.level), s.a.get(f.level), s.b.get(f.level))) {
            return Err(AlarmKind::ProfileNotMonotoneInfeed);
        }
    }
    Ok(())
}

/// Whether an extent stays between a segment's end values (1 nm slack).
fn within(ext: (i64, i64), a: i64, b: i64) -> bool {
    ext.0 >= a.min(b) - 1 && ext.1 <= a.max(b) + 1
}

/// The lowest u of a segment.
fn lowest(f: &Frame, s: &Seg) -> i64 {
    let (lo, hi) = s.extent(f.level);
    if f.out > 0 { lo } else { -hi }
}

#[inline(never)]
fn inside(r: &Run, p: &Run) -> bool {
    r.w0 >= p.w0 - 0.5 && r.w1 <= p.w1 + 0.5
}

fn sign(v: i64) -> i64 {
    v.signum()
}

/// The contour pass move of a shape segment (the shape's G00 stays a rapid).
pub fn contour_step(s: &Seg) -> Step {
    match s.kind {
        SegKind::Rapid => Step::Rapid(s.b),
        SegKind::Line => Step::Feed(s.b),
        SegKind::Arc { center, cw } => Step::Arc { to: s.b, center, cw },
    }
}

fn push(out: &mut super::StepQueue, s: Step) -> Result<(), AlarmKind> {
    out.push_back(s).map_err(|_| AlarmKind::Overflow)
}

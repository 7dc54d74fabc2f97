//! The roughing engine: G71 (stock removal in turning) and G72 (in facing), types
//! I and II (seed 000 2.16.1–2), and SINUMERIK's CYCLE95 / CYCLE950 (seed 001 4.5,
//! 4.10), which describe their parameters in `interp_siemens::cycles` and
//! run here with the options they need ([`Sections`]).
//!
//! One algorithm: it works in a normalised frame where `u` is the infeed ("level")
//! axis measured outward from the part and `w` the cutting axis measured along the
//! cut. G71 has level axis X and cuts along Z; G72 has level axis Z and cuts along X.
//! Both languages share the frame, the material below a level ([`below`]), the
//! level spacing ([`Spacing`]), the cut along a level with its chip breaking, the
//! way the tool leaves a cut ([`RoughGen::leave`]) and the return to the start.
//!
//! G71/G72: the rough contour is the shape B→C shifted by the allowances (Δu/2, Δw;
//! type II ignores Δw, note 2). Levels are `u_k = u_A − k·Δd` while above the lowest
//! contour point. At a level, the material still to cut is every `w` from the
//! start's `w_A` to C' where the contour lies below the level (before B' there is no
//! part). Each maximal run is one cut. Cuts are taken depth-first: the cuts of a
//! level are nested in the cut above them, and a pocket is finished to its bottom
//! before the next pocket (type II, note 3). Type I shapes give one cut per level.
//!
//! Moves of one cut: up to the safe height (the level above + e, all air), along to
//! the cut's start, infeed (the ns block's G00/G01 at the start side; G01 into a
//! pocket, note 3), cut along `w`, 45° retract by e. Then the contour pass B'→C' at
//! the cycle's feed, and back to the start point (X first for G71, Z first for G72;
//! type II first retracts to the start + allowance + Δd, note 7).
//!
//! CYCLE95 / CYCLE950 (the options of [`Sections`], seed 001 lines 10596–10954,
//! 11511–12156): the contour (read once, kept in the expansion's profile) is cut in
//! the machining direction: from its end nearer the axis (outside; nearer the tool
//! inside) to the other; a contour programmed the other way round is turned. When
//! its highest point is not an end, an axis-parallel line from the end up to it
//! closes it (lines 10841–10843). The roughing works on the contour moved by the
//! allowances and the nose ([`super::offset`], so the cuts and the contour following
//! are compensated), the finishing on the contour moved by the nose only.
//!
//! Their roughing (lines 10661–10690): the *main section* is the stock above the
//! contour as seen from its start; every *undercut* (a descent of the contour in the
//! machining direction, down to where it stops going down) is a section of its own,
//! below the level where it starts — G71 type II's pockets, each with its own
//! levels. Each section is cut in n = ⌈depth / MID⌉ passes of equal infeed depth / n,
//! between MID and MID/2 (lines 10727–10737: 39 mm with MID 5 → 8 passes of 4.875;
//! CYCLE950: full MID steps, then two halves). A pass of the main section: G0
//! infeed at the start point's Z, G1 FF1 axis-parallel to the contour (DAM/DT chip
//! breaking), along the contour (FF1) up to the previous pass's cut point (VARI
//! hundreds 2) or one further (hundreds 0, overlapping), over any undercut on the way
//! on a straight line at its mouth; the tool leaves at _VRT (at _ANGB), G0 back. A
//! pass of an undercut: G0 axis by axis to above the undercut's start, G1 FF2 along
//! its descending contour down to the level, G1 FF1 across, along the contour and
//! out as above. After the last section, back to the start point axis by axis.
//!
//! Their finishing (lines 10692–10697, 10888–10890): G0 to the start point, G0 to
//! allowance + nose radius + 1 mm before the contour's start, G1 onto it, the
//! contour at FF3 with the nose compensated, G0 back axis by axis, the infeed axis
//! first. The start point (lines 10878–10886): allowance + _VRT off the contour's
//! highest point on the infeed axis, allowance + _VRT before its start on the other.

use super::profile::{Profile, Seg, SegKind};
use super::sign;
use crate::alarm::AlarmKind;
use crate::axis::Axis;
use crate::step::push;
use crate::step::{Pt, Step, contour_step};
#[cfg(feature = "siemens")]
use {super::pattern::PatternGen, sections::Part};

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
    /// (u, w) of a work point (out of line: ~30 call sites).
    #[inline(never)]
    pub fn norm(&self, p: Pt) -> (i64, i64) {
        (self.out * p.get(self.level), self.dir * p.get(self.cut))
    }

    /// The work point of (u, w).
    #[inline(never)]
    pub fn work(&self, u: i64, w: i64) -> Pt {
        Pt::default().with(self.level, self.out * u).with(self.cut, self.dir * w)
    }
}

/// How the levels of a section are spaced between its top and its bottom.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(not(feature = "siemens"), allow(dead_code))]
pub enum Spacing {
    /// Δd apart from the top while above the bottom (G71/G72).
    Step,
    /// ⌈depth / MID⌉ equal ones, the last on the bottom (CYCLE95, line 10731).
    Equal,
    /// Full MID steps while at least two are left, then two halves (CYCLE950,
    /// lines 11702–11706).
    Halves,
}

impl Spacing {
    /// How many levels a section `depth` deep has with infeed `mid` (G71/G72: the
    /// levels strictly above the bottom).
    #[cfg_attr(not(feature = "siemens"), allow(dead_code))]
    #[inline(never)]
    fn count(self, depth: i64, mid: i64) -> u32 {
        if depth <= 0 || mid <= 0 {
            return 0;
        }
        let n = match self {
            Spacing::Step => (depth - 1) / mid,
            Spacing::Equal => (depth + mid - 1) / mid,
            Spacing::Halves if depth >= 2 * mid => (depth - 2 * mid) / mid + 3,
            Spacing::Halves => 2,
        };
        u32::try_from(n).unwrap_or(u32::MAX)
    }

    /// Level `k` (1-based) of `n` of a section from `top` down to `bottom`.
    fn at(self, top: i64, bottom: i64, k: u32, n: u32, mid: i64) -> i64 {
        let depth = top - bottom;
        match self {
            Spacing::Step => top - i64::from(k) * mid,
            Spacing::Equal => top - crate::geom::round_i64(depth as f64 * f64::from(k) / f64::from(n)),
            Spacing::Halves if n < 2 => top - crate::geom::round_i64(depth as f64 * f64::from(k) / f64::from(n)),
            Spacing::Halves => {
                let full = i64::from(n - 2);
                if i64::from(k) <= full {
                    return top - i64::from(k) * mid;
                }
                let rest = depth - full * mid;
                if k == n { bottom } else { top - full * mid - rest / 2 }
            }
        }
    }
}

/// A run of material to cut at one level, normalised.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Run {
    w0: f64,
    w1: f64,
}

/// A roughing cycle as an expansion: where it is in its walk over the levels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughGen {
    frame: Frame,
    /// Start point, normalised (G71/G72: A; CYCLE95: the start point it works out).
    a: (i64, i64),
    /// Infeed of a level: Δd, MID.
    depth: i64,
    /// e (G71/G72), _VRT (CYCLE95/950): the safety distance off the material.
    retract: i64,
    /// How far the tool leaves a cut, up the level axis and back along the cut:
    /// e and e (G71/G72, 45°), _VRT at the angle _ANGB (CYCLE950; CYCLE95 45°).
    leave: (i64, i64),
    /// Lowest level (exclusive): the innermost contour point.
    bottom: i64,
    /// Height to retract to before returning (type II note 7).
    return_u: i64,
    type2: bool,
    /// G00 infeed (the ns block's mode).
    rapid_infeed: bool,
    phase: Phase,
    /// The options of CYCLE95/950: `None` for G71/G72.
    #[cfg(feature = "siemens")]
    sections: Option<Sections>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Phase {
    Start,
    /// G71/G72: the depth-first walk over the runs of the levels, at the cut of
    /// `run` on level `level`.
    Rough {
        level: i64,
        run: Run,
    },
    /// CYCLE95/950: pass `k` of section `s`.
    #[cfg(feature = "siemens")]
    Level {
        s: u16,
        k: u32,
        part: Part,
    },
    /// Contour-parallel roughing (CYCLE950): G73's passes.
    #[cfg(feature = "siemens")]
    Pattern(PatternGen),
    /// G71/G72's contour pass.
    Contour(usize),
    Return,
    /// CYCLE95/950's compensated finishing pass.
    #[cfg(feature = "siemens")]
    Finish,
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
            leave: (spec.retract, spec.retract),
            bottom,
            return_u,
            type2,
            rapid_infeed: profile.ns_rapid,
            phase: Phase::Start,
            #[cfg(feature = "siemens")]
            sections: None,
        };
        generator.count_pockets(shape)?;
        Ok(generator)
    }

    /// The next group of steps (at most 6); `false` when the cycle is finished.
    pub fn fill(&mut self, profile: &Profile, here: Pt, out: &mut super::StepQueue) -> Result<bool, AlarmKind> {
        let full = &profile.segs[..];
        let shape = &profile.segs[1..];
        match self.phase {
            #[cfg(feature = "siemens")]
            Phase::Start if self.sections.is_some() => self.begin_sections(out)?,
            Phase::Start => match self.first_run(full)? {
                Some((level, run)) => {
                    self.phase = Phase::Rough { level, run };
                    self.cut(level, run, here, 0, out)?;
                }
                None => self.phase = Phase::Contour(0),
            },
            Phase::Rough { level, run } => match self.next_run(full, level, run)? {
                Some((level, run, safe)) => {
                    self.phase = Phase::Rough { level, run };
                    self.cut(level, run, here, safe, out)?;
                }
                None => {
                    self.approach_contour(profile, here, out)?;
                    self.phase = Phase::Contour(0);
                }
            },
            #[cfg(feature = "siemens")]
            Phase::Level { s, k, part } => self.phase = self.level(full, here, s, k, part, out)?,
            #[cfg(feature = "siemens")]
            Phase::Pattern(mut p) => {
                self.phase = if p.fill_segs(full, true, out)? { Phase::Pattern(p) } else { self.after_roughing() };
            }
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
                self.phase = self.after_roughing();
            }
            #[cfg(feature = "siemens")]
            Phase::Finish => {
                let more = match self.sections.as_mut() {
                    Some(o) => o.finish.fill(full, out)?,
                    None => false,
                };
                if !more {
                    self.phase = Phase::Done;
                }
            }
            Phase::Done => return Ok(false),
        }
        Ok(self.phase != Phase::Done)
    }

    /// What follows the return to the start point: CYCLE95's finishing pass when
    /// it has one, else the end.
    fn after_roughing(&self) -> Phase {
        #[cfg(feature = "siemens")]
        if self.sections.is_some_and(|o| o.finishes) {
            return Phase::Finish;
        }
        Phase::Done
    }

    /// Level `k`'s u.
    fn level_u(&self, k: i64) -> i64 {
        Spacing::Step.at(self.a.0, self.bottom, u32::try_from(k).unwrap_or(u32::MAX), 0, self.depth)
    }

    /// The step leaving a cut at (u, w): up the level axis and back along the cut
    /// by [`RoughGen::leave`], never back more than `room`.
    fn leave(&self, u: i64, w: i64, room: i64) -> Step {
        Step::Feed(self.frame.work(u + self.leave.0, w - self.leave.1.min(room)))
    }

    /// Where a cut along a level from `w` towards `w_end` stops next: at `w_end`,
    /// or `interrupt` further for chip breaking (DAM; 0 = never).
    fn cut_piece(w: i64, w_end: i64, interrupt: i64) -> i64 {
        if interrupt > 0 && w_end - w > interrupt { w + interrupt } else { w_end }
    }

    /// The first cut: the first run of the first level above the bottom.
    fn first_run(&self, shape: &[Seg]) -> Result<Option<(i64, Run)>, AlarmKind> {
        let mut k = 1;
        while self.level_u(k) > self.bottom {
            if let Some(r) = self.runs(shape, self.level_u(k))?.first() {
                return Ok(Some((k, *r)));
            }
            k += 1;
        }
        Ok(None)
    }

    /// The next cut in depth-first order after the cut of `run` on level `k`, with
    /// the level whose height + e is safe to travel at on the way there.
    fn next_run(&self, shape: &[Seg], k: i64, run: Run) -> Result<Option<(i64, Run, i64)>, AlarmKind> {
        // A child: the first run of the level below inside this one.
        if self.level_u(k + 1) > self.bottom {
            let cur = run;
            if let Some(r) = self.runs(shape, self.level_u(k + 1))?.iter().find(|r| inside(r, &cur)) {
                return Ok(Some((k + 1, *r, k)));
            }
        }
        // Else the next sibling, or the next sibling of an ancestor.
        let mut lv = k;
        let mut cur = run;
        while lv >= 1 {
            let parent = if lv == 1 {
                None
            } else {
                self.runs(shape, self.level_u(lv - 1))?.into_iter().find(|p| inside(&cur, p))
            };
            let runs = self.runs(shape, self.level_u(lv))?;
            let sibling = runs.iter().find(|r| r.w0 > cur.w1 && parent.is_none_or(|p| inside(r, &p)));
            if let Some(r) = sibling {
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
        // G71/G72 cut without chip breaking: one piece.
        push(out, Step::Feed(f.work(u, Self::cut_piece(w0, w1, 0))))?;
        Ok(push(out, self.leave(u, w1, w1 - w0))?)
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
        Ok(push(out, if self.rapid_infeed { Step::Rapid(p) } else { Step::Feed(p) })?)
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

/// Whether an extent stays between a segment's end values (1 nm slack; out of
/// line: three callers).
#[inline(never)]
fn within(ext: (i64, i64), a: i64, b: i64) -> bool {
    ext.0 >= a.min(b) - 1 && ext.1 <= a.max(b) + 1
}

/// The lowest u of a segment (out of line: three callers).
#[inline(never)]
fn lowest(f: &Frame, s: &Seg) -> i64 {
    let (lo, hi) = s.extent(f.level);
    if f.out > 0 { lo } else { -hi }
}

#[inline(never)]
fn inside(r: &Run, p: &Run) -> bool {
    r.w0 >= p.w0 - 0.5 && r.w1 <= p.w1 + 0.5
}

/// CYCLE95 / CYCLE950's options of the engine (the SINUMERIK side fills them).
#[cfg(feature = "siemens")]
pub use sections::{Nose, Sections};

/// The options of the roughing engine that CYCLE95 and CYCLE950 use beyond G71/G72's
/// (see the module's doc): levels of equal depth per section, undercut sections
/// entered along their descent at FF2, following the contour back to the previous
/// cut, the tool leaving at _VRT at an angle, DAM/DT chip breaking, G73-style
/// contour-parallel passes and the compensated finishing pass.
#[cfg(feature = "siemens")]
mod sections {
    use super::*;
    use crate::StepQueue;
    use crate::alarm::CycleAlarm;
    use crate::geom::path::V2;
    use crate::offset::{Offsets, nth, walk};
    use crate::pass::{PassGen, along};
    use crate::spec::job::{Blank, Pull, StockSpec};

    /// A roughing level's material within 1 µm of the contour counts: the last pass of
    /// a section cuts along a floor that lies exactly at its level.
    const FLOOR_NM: f64 = 1_000.0;

    /// The nose of the tool in force.
    #[derive(Clone, Copy, Debug)]
    pub struct Nose {
        /// Radius, nm.
        pub radius: i64,
        /// Imaginary tip (cutting edge position) 0–9.
        pub tip: u8,
        /// Clearance angle (P24), µdeg; 0 = no check.
        pub clearance_udeg: u32,
    }

    /// What CYCLE95/950 ask of the engine beyond its frame, start, depth and _VRT
    /// (from their [`StockSpec`]; what only the set-up needs is not kept).
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct Sections {
        /// The contour moved by the allowances and the nose: the roughing's shape.
        rough: Offsets,
        /// The finishing pass.
        pub(super) finish: PassGen,
        /// FF1, FF2, FF3 (the feed in force at the call where one is 0).
        feeds: [i64; 3],
        /// DAM: a cut is interrupted after this path length (0: never) …
        interrupt: i64,
        /// … for DT, ms.
        dwell_ms: u32,
        /// The blank (contour-parallel roughing: its allowance round the contour).
        blank: Blank,
        /// The finishing allowances along the infeed and the cutting axis, each with
        /// the contour-parallel one (contour-parallel roughing stops there).
        allowance: (i64, i64),
        pull: Pull,
        spacing: Spacing,
        /// Rough the undercut sections too.
        undercuts: bool,
        /// Contour-parallel roughing (G73's passes).
        parallel: bool,
        /// Rough at all / finish.
        roughs: bool,
        pub(super) finishes: bool,
        facing: bool,
    }

    /// A point on the shape: element `elem`, parameter `t` along it.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub(super) struct Mark {
        elem: u16,
        t: f64,
    }

    /// What a pass of a section does next.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub(super) enum Part {
        /// Compute the level's run and go to where the cut starts.
        Begin,
        /// Down the undercut's contour (FF2) from `at` to the level at `to`; the cut
        /// then ends at `end`.
        Follow { at: Mark, to: Mark, end: Mark },
        /// Across at the level (FF1) from `w` to the contour at `end`.
        Cut { w: i64, end: Mark },
        /// Along the contour from `at` up to `target` (FF1).
        Pull { at: Mark, target: i64 },
        /// Retract and return.
        Out,
    }

    /// One section: the main one or an undercut, its levels and where it starts.
    #[derive(Clone, Copy, Debug)]
    struct Section {
        /// First and last element of the undercut's descent (main: none).
        descent: Option<(u16, u16)>,
        top: i64,
        bottom: i64,
    }

    impl RoughGen {
        /// Sets up CYCLE95/950 on the contour `raw` (from its first point, as
        /// programmed), turning it into the machining direction in place when it
        /// roughs, closing it up to its highest point. `here` is where the tool is.
        #[inline(never)]
        pub fn sections(
            spec: &StockSpec,
            raw: &mut heapless::Vec<Seg, { crate::profile::PROFILE_MAX }>,
            here: Pt,
            nose: Nose,
            base_feed: i64,
        ) -> Result<RoughGen, AlarmKind> {
            if spec.rough && spec.depth <= 0 {
                return Err(AlarmKind::CycleValueIllegal { what: "MID (infeed depth) must be above 0 for roughing" });
            }
            let (level, cut) = if spec.facing { (Axis::Z, Axis::X) } else { (Axis::X, Axis::Z) };
            let out = if spec.internal { -1 } else { 1 };
            let u = |p: Pt| out * p.get(level);
            let (first, last) = match (raw.first(), raw.last()) {
                (Some(f), Some(l)) => (f.a, l.b),
                _ => return Err(AlarmKind::SiemensCycle(CycleAlarm::ContourPreparation { cause: 10933 })),
            };
            // Lines 10878, 10926: a start point inside the contour's rectangle.
            let (lo, hi) = bounds(raw);
            let inside = |a: Axis| here.get(a) > lo.get(a) && here.get(a) < hi.get(a);
            if inside(Axis::X) && inside(Axis::Z) {
                return Err(AlarmKind::SiemensCycle(CycleAlarm::StartPointWrong));
            }
            // The machining direction: from the lower end up to the higher one.
            let turned = u(first) > u(last);
            if turned && spec.rough {
                reverse(raw);
            }
            let (a, b) = match (raw.first(), raw.last()) {
                (Some(f), Some(l)) => (f.a, l.b),
                _ => return Err(AlarmKind::SiemensCycle(CycleAlarm::ContourPreparation { cause: 10933 })),
            };
            let (a, b) = if turned && !spec.rough { (b, a) } else { (a, b) };
            let dir = sign(b.get(cut) - a.get(cut));
            if dir == 0 {
                return Err(AlarmKind::SiemensCycle(CycleAlarm::ContourWrong));
            }
            if spec.direction != 0 && spec.direction != dir {
                // CYCLE950 asked for the other direction: the contour cannot be cut so.
                return Err(AlarmKind::SiemensCycle(CycleAlarm::ContourDirection));
            }
            let frame = Frame { level, cut, out, dir };
            check_contour(&frame, raw, turned && !spec.rough, nose.clearance_udeg)?;
            // Line 10841: up to the highest point along the infeed axis at the end.
            let mut top = raw.iter().map(|s| high(&frame, s)).max().unwrap_or(0);
            if !spec.parallel {
                // A blank above the contour's highest point (CYCLE950 _APX/_APZ).
                match spec.blank {
                    Blank::At(p) => top = top.max(u(p)),
                    Blank::Allowance(a) => top += a.get(level).abs(),
                    Blank::Contour => {}
                }
            }
            if spec.rough && !spec.parallel && u(b) < top {
                let end = b.with(level, out * top);
                raw.push(Seg { kind: SegKind::Line, a: b, b: end })
                    .map_err(|_| AlarmKind::SiemensCycle(CycleAlarm::ContourPreparation { cause: 10934 }))?;
            }
            let tool_left = tool_left(&frame);
            let tip = crate::geom::path::tip_vector(nose.tip, nose.radius);
            let r = nose.radius as f64;
            let unit = |a: Axis, s: i64| if a == Axis::Z { V2::new(s as f64, 0.0) } else { V2::new(0.0, s as f64) };
            let along = unit(cut, dir);
            // The axis allowances: outward on the infeed axis, back towards the start on
            // the cutting axis (an undercut's descent forward).
            let (au, aw) = if spec.facing { (spec.allow_z, spec.allow_x) } else { (spec.allow_x, spec.allow_z) };
            let outward = unit(level, out).scale(au as f64);
            let rough = Offsets {
                side: if tool_left { 1.0 } else { -1.0 },
                equi: r + spec.allow as f64,
                front: outward.minus(along.scale(aw as f64)),
                back: outward.plus(along.scale(aw as f64)),
                along,
                tip,
            };
            let back = turned && !spec.rough;
            let zero = V2::new(0.0, 0.0);
            let finish = Offsets {
                side: if tool_left != back { 1.0 } else { -1.0 },
                equi: r,
                front: zero,
                back: zero,
                along: if back { along.scale(-1.0) } else { along },
                tip,
            };
            // At 45° _VRT in both axes; at another angle never more (line 11632).
            let angle = (spec.retract_angle_udeg as f64 / 1e6).to_radians();
            let (tu, tw) = (libm::tan(angle).min(1.0), (1.0 / libm::tan(angle)).min(1.0));
            let r_vrt = spec.retract as f64;
            let mut g = RoughGen {
                frame,
                a: (0, 0),
                depth: spec.depth,
                retract: spec.retract,
                leave: (crate::geom::round_i64(r_vrt * tu), crate::geom::round_i64(r_vrt * tw)),
                bottom: 0,
                return_u: 0,
                type2: false,
                rapid_infeed: true,
                phase: Phase::Start,
                sections: Some(Sections {
                    rough,
                    finish: PassGen::new(finish, (0, 0), Pt::default(), [None; 3], 0, [None; 3]),
                    feeds: spec.feeds.map(|f| if f > 0 { f } else { base_feed }),
                    interrupt: spec.interrupt,
                    dwell_ms: spec.dwell_ms,
                    blank: spec.blank,
                    allowance: (au + spec.allow, aw + spec.allow),
                    pull: spec.pull,
                    spacing: if spec.equal { Spacing::Equal } else { Spacing::Halves },
                    undercuts: spec.undercuts,
                    parallel: spec.parallel,
                    roughs: spec.rough,
                    finishes: spec.finish,
                    facing: spec.facing,
                }),
            };
            // The start point, from the rough shape (the finishing shape when it is
            // walked backwards: its start is the far end).
            let (mut umax, mut wfirst) = (i64::MIN, None);
            let o = if back { finish } else { rough };
            walk(raw, &o, |s| {
                umax = umax.max(high(&frame, &s));
                wfirst.get_or_insert(frame.norm(s.a).1);
                Ok(true)
            })?;
            // Allowance + _VRT before the contour's start (line 10882), and never in
            // front of the compensated path's start.
            let allow_cut = if spec.facing { spec.allow_x } else { spec.allow_z };
            let w_raw = frame.norm(a).1 - allow_cut - spec.allow;
            let w0 = if back { w_raw } else { w_raw.min(wfirst.unwrap_or(w_raw)) };
            // Contour-parallel roughing starts outside the blank round the contour.
            let (bu, bw) = match (spec.parallel, spec.blank) {
                (true, Blank::Allowance(a)) => {
                    let (au, aw) = if spec.facing { (a.z, a.x) } else { (a.x, a.z) };
                    (au.abs(), aw.abs())
                }
                _ => (0, 0),
            };
            let top_u = if spec.parallel { umax } else { umax.max(top) };
            g.a = (top_u + bu + spec.retract, w0 - bw - spec.retract.max(spec.approach));
            g.return_u = g.a.0;
            // Finishing (lines 10692-10697): G0 to the start point, G0 to allowance +
            // nose radius + 1 mm before the contour's start, G1 onto it, the contour at
            // FF3, back axis by axis with the infeed axis first.
            let (mut first, mut last) = (None, None);
            walk(raw, &finish, |s| {
                first.get_or_insert(s.a);
                last = Some(s.b);
                Ok(true)
            })?;
            let (Some(first), Some(last)) = (first, last) else {
                return Err(AlarmKind::SiemensCycle(CycleAlarm::ContourPreparation { cause: 10933 }));
            };
            let (u0, w0) = frame.norm(first);
            let (au, aw) = if spec.facing { (spec.allow_z, spec.allow_x) } else { (spec.allow_x, spec.allow_z) };
            let du = au + spec.allow + nose.radius + crate::units::NM_PER_MM;
            let dw = aw + spec.allow + nose.radius + crate::units::NM_PER_MM;
            let sign = if back { -1 } else { 1 };
            let s = g.s_point();
            let before = [Some(s), Some(frame.work(u0 + du, w0 - sign * dw)), None];
            let after = [Some(frame.work(g.a.0, frame.norm(last).1)), Some(s), None];
            let n = u16::try_from(raw.len())
                .map_err(|_| AlarmKind::SiemensCycle(CycleAlarm::ContourPreparation { cause: 10934 }))?;
            let mut path = (0, n);
            if spec.parallel && spec.rough {
                // G73's shape: the move from the start point onto the contour first.
                let s = g.s_point();
                raw.insert(0, Seg { kind: SegKind::Rapid, a: s, b: first_raw(raw) })
                    .map_err(|_| AlarmKind::SiemensCycle(CycleAlarm::ContourPreparation { cause: 10934 }))?;
                path = (1, n + 1);
            }
            if let Some(o) = g.sections.as_mut() {
                o.finish = PassGen::new(finish, path, Pt::default(), before, o.feeds[2], after).arcs_at(spec.arc_feed);
            }
            Ok(g)
        }

        /// The options (CYCLE95/950 only).
        fn opts(&self) -> Result<&Sections, AlarmKind> {
            self.sections.as_ref().ok_or(AlarmKind::SiemensCycle(CycleAlarm::ContourPreparation { cause: 10931 }))
        }

        /// To the start point, then the roughing (axis-parallel or contour-parallel)
        /// or straight the finishing.
        pub(super) fn begin_sections(&mut self, out: &mut StepQueue) -> Result<(), AlarmKind> {
            push(out, Step::Rapid(self.s_point()))?;
            let o = self.opts()?;
            self.phase = if !o.roughs {
                Phase::Finish
            } else if o.parallel {
                push(out, Step::Feedrate(o.feeds[0]))?;
                Phase::Pattern(self.pattern()?)
            } else {
                Phase::Level { s: 0, k: 1, part: Part::Begin }
            };
            Ok(())
        }

        /// Contour-parallel roughing: G73's passes from the blank's allowance down to
        /// the finishing allowances, MID apart (perpendicular to the contour: the larger
        /// of the two allowances decides the count).
        fn pattern(&self) -> Result<PatternGen, AlarmKind> {
            let f = self.frame;
            let o = self.opts()?;
            let blank = match o.blank {
                Blank::Allowance(a) => a,
                _ => Pt::default(),
            };
            let (au, aw) = if o.facing { (blank.z, blank.x) } else { (blank.x, blank.z) };
            let count = Spacing::Equal.count(au.abs().max(aw.abs()), self.depth).max(1);
            // G73's first pass is at the relief: one step inside the blank's surface.
            let inside = |v: i64| v.abs() * i64::from(count - 1) / i64::from(count);
            let (au, aw) = (inside(au), inside(aw));
            // Outward on the infeed axis, back towards the start on the cutting axis.
            let relief = f.work(au, -aw);
            let allowance = f.work(o.allowance.0, -o.allowance.1);
            PatternGen::new(self.s_point(), relief, count, allowance)
        }

        /// The start point (work).
        fn s_point(&self) -> Pt {
            self.frame.work(self.a.0, self.a.1)
        }

        /// One part of a roughing pass; the phase that follows.
        pub(super) fn level(
            &self,
            raw: &[Seg],
            here: Pt,
            s: u16,
            k: u32,
            part: Part,
            out: &mut StepQueue,
        ) -> Result<Phase, AlarmKind> {
            let f = self.frame;
            let spec = self.opts()?;
            let sec = if s > 0 && !spec.undercuts { None } else { self.section(raw, s)? };
            let Some(sec) = sec else {
                return Ok(Phase::Return);
            };
            let spacing = spec.spacing;
            let n = spacing.count(sec.top - sec.bottom, self.depth);
            if k > n {
                return Ok(Phase::Level { s: s + 1, k: 1, part: Part::Begin });
            }
            let level_u = |k: u32| spacing.at(sec.top, sec.bottom, k, n, self.depth);
            let u_k = level_u(k);
            let set = |part| Ok(Phase::Level { s, k, part });
            match part {
                Part::Begin => {
                    let floor = if k == n { FLOOR_NM } else { 0.0 };
                    let Some((from, to)) = self.run(raw, &sec, u_k as f64 + floor)? else {
                        // Nothing at this level.
                        return Ok(Phase::Level { s, k: k + 1, part: Part::Begin });
                    };
                    match sec.descent {
                        None => {
                            push(out, Step::Rapid(f.work(u_k, self.a.1)))?;
                            push(out, Step::Feedrate(spec.feeds[0]))?;
                            set(Part::Cut { w: self.a.1, end: to })
                        }
                        Some((d0, _)) => {
                            let top = self.point(raw, Mark { elem: d0, t: 0.0 })?;
                            let (tu, tw) = f.norm(top);
                            let above = (sec.top + self.retract, tw - self.retract);
                            let (hu, hw) = f.norm(here);
                            if (hu, hw) != above {
                                // Axis by axis over the part to above the undercut.
                                push(out, Step::Rapid(f.work(self.a.0.max(hu), hw)))?;
                                push(out, Step::Rapid(f.work(self.a.0.max(hu), above.1)))?;
                                push(out, Step::Rapid(f.work(above.0, above.1)))?;
                            }
                            push(out, Step::Feedrate(spec.feeds[1]))?;
                            push(out, Step::Feed(f.work(tu, tw)))?;
                            set(Part::Follow { at: Mark { elem: d0, t: 0.0 }, to: from, end: to })
                        }
                    }
                }
                Part::Follow { at, to, end } => {
                    let mut at = at;
                    for _ in 0..4 {
                        let seg = self.rough_seg(raw, at.elem)?;
                        if at.elem == to.elem {
                            let piece = part_of(&seg, at.t, to.t);
                            push(out, along(&piece))?;
                            push(out, Step::Feedrate(spec.feeds[0]))?;
                            return set(Part::Cut { w: f.norm(piece.b).1, end });
                        }
                        push(out, along(&part_of(&seg, at.t, 1.0)))?;
                        at = Mark { elem: at.elem + 1, t: 0.0 };
                    }
                    set(Part::Follow { at, to, end })
                }
                Part::Cut { w, end } => {
                    let seg = self.rough_seg(raw, end.elem)?;
                    let w_end = f.norm(point_at(&seg, end.t)).1;
                    let mut w = w;
                    for _ in 0..3 {
                        let next = Self::cut_piece(w, w_end, spec.interrupt);
                        push(out, Step::Feed(f.work(u_k, next)))?;
                        if next == w_end {
                            push(out, Step::Feed(point_at(&seg, end.t)))?;
                            let back = match spec.pull {
                                Pull::None => 0,
                                Pull::Previous => 1,
                                Pull::Overlap => 2,
                            };
                            let target = if k > back { level_u(k - back) } else { sec.top };
                            return set(if back == 0 { Part::Out } else { Part::Pull { at: end, target } });
                        }
                        push(out, Step::Dwell(spec.dwell_ms))?;
                        w = next;
                    }
                    set(Part::Cut { w, end })
                }
                Part::Pull { at, target } => match self.pull(raw, at, target, out)? {
                    Some(m) => set(Part::Pull { at: m, target }),
                    None => set(Part::Out),
                },
                Part::Out => {
                    let (hu, hw) = f.norm(here);
                    let r = self.retract;
                    let leave = self.leave(hu, hw, i64::MAX);
                    push(out, leave)?;
                    let (ru, rw) = (hu + self.leave.0, hw - self.leave.1);
                    match sec.descent {
                        None => push(out, Step::Rapid(f.work(ru, self.a.1)))?,
                        Some((d0, _)) => {
                            let top = self.point(raw, Mark { elem: d0, t: 0.0 })?;
                            let up = sec.top + r;
                            push(out, Step::Rapid(f.work(ru.max(up), rw)))?;
                            push(out, Step::Rapid(f.work(ru.max(up), f.norm(top).1 - r)))?;
                        }
                    }
                    Ok(Phase::Level { s, k: k + 1, part: Part::Begin })
                }
            }
        }
        /// Along the contour from `at` (at most four steps) towards the level
        /// `target`, over undercuts on a straight line at their mouth; `None` when
        /// the level is reached (or the contour ends).
        fn pull(&self, raw: &[Seg], at: Mark, target: i64, out: &mut StepQueue) -> Result<Option<Mark>, AlarmKind> {
            let f = self.frame;
            let mut at = at;
            for _ in 0..4 {
                let Some(seg) = self.shape_seg(raw, at.elem)? else { return Ok(None) };
                let here = point_at(&seg, at.t);
                let (hu, _) = f.norm(here);
                if hu >= target {
                    return Ok(None);
                }
                let rest = part_of(&seg, at.t, 1.0);
                let (eu, _) = f.norm(rest.b);
                // The level on this element?
                let mut hit = None;
                below(&f, &rest, target as f64, |_, t1| {
                    if t1 < 1.0 && hit.is_none() {
                        hit = Some(t1);
                    }
                    Ok(())
                })?;
                if let Some(t) = hit {
                    push(out, along(&part_of(&rest, 0.0, t)))?;
                    return Ok(None);
                }
                if eu < hu - 1 {
                    // An undercut: straight on at this height to where the contour is back up.
                    let Some(m) = self.next_rise(raw, at, hu as f64)? else { return Ok(None) };
                    push(out, Step::Feed(self.point(raw, m)?))?;
                    at = m;
                    continue;
                }
                push(out, along(&rest))?;
                at = Mark { elem: at.elem + 1, t: 0.0 };
            }
            Ok(Some(at))
        }

        /// The first place after `from` where the rough shape comes back up to level
        /// `h` after going below it.
        fn next_rise(&self, raw: &[Seg], from: Mark, h: f64) -> Result<Option<Mark>, AlarmKind> {
            let f = self.frame;
            let mut k = 0u16;
            let mut found = None;
            let mut below_open = false;
            walk(raw, &self.opts()?.rough, |s| {
                let i = k;
                k += 1;
                if i < from.elem {
                    return Ok(true);
                }
                let t_from = if i == from.elem { from.t } else { 0.0 };
                let mut pieces: heapless::Vec<(f64, f64), 3> = heapless::Vec::new();
                below(&f, &s, h, |t0, t1| {
                    if t1 > t_from + 1e-9 {
                        let _ = pieces.push((t0.max(t_from), t1));
                    }
                    Ok(())
                })?;
                if pieces.is_empty() {
                    if below_open {
                        found = Some(Mark { elem: i, t: 0.0 });
                        return Ok(false);
                    }
                    return Ok(true);
                }
                for (t0, t1) in pieces {
                    if below_open && t0 > 1e-9 {
                        found = Some(Mark { elem: i, t: 0.0 });
                        return Ok(false);
                    }
                    below_open = true;
                    if t1 < 1.0 - 1e-9 {
                        found = Some(Mark { elem: i, t: t1 });
                        return Ok(false);
                    }
                }
                Ok(true)
            })?;
            Ok(found)
        }

        /// Section `s`: 0 the main one, then the undercuts in machining order.
        fn section(&self, raw: &[Seg], s: u16) -> Result<Option<Section>, AlarmKind> {
            let f = self.frame;
            let (mut top, mut entry, mut k) = (i64::MIN, None, 0u16);
            let mut found: Option<Section> = None;
            let mut count = 0u16;
            let mut open: Option<Section> = None;
            walk(raw, &self.opts()?.rough, |seg| {
                let i = k;
                k += 1;
                top = top.max(high(&f, &seg));
                entry.get_or_insert(f.norm(seg.a).0);
                let (ua, ub) = (f.norm(seg.a).0, f.norm(seg.b).0);
                let low = lowest(&f, &seg);
                if ub < ua - 1_000 {
                    match open.as_mut() {
                        Some(d) => {
                            d.descent = d.descent.map(|(a, _)| (a, i));
                            d.bottom = d.bottom.min(low);
                        }
                        None => open = Some(Section { descent: Some((i, i)), top: ua, bottom: low }),
                    }
                } else if ub <= ua + 1_000 && open.is_some() {
                    // A flat: the descent may go on.
                } else if let Some(d) = open.take() {
                    count += 1;
                    if count == s {
                        found = Some(d);
                        return Ok(false);
                    }
                }
                Ok(true)
            })?;
            if s == 0 {
                return Ok(Some(Section { descent: None, top, bottom: entry.unwrap_or(top) }));
            }
            if found.is_none()
                && let Some(d) = open
                && count + 1 == s
            {
                found = Some(d);
            }
            Ok(found)
        }

        /// The run of section `sec` at level `u`: where its cut starts and ends on the
        /// rough shape (main section: it starts before the contour).
        fn run(&self, raw: &[Seg], sec: &Section, u: f64) -> Result<Option<(Mark, Mark)>, AlarmKind> {
            let f = self.frame;
            let mut k = 0u16;
            let mut cur: Option<(Mark, Mark)> = None;
            let mut done: Option<(Mark, Mark)> = None;
            walk(raw, &self.opts()?.rough, |s| {
                let i = k;
                k += 1;
                let mut stop = false;
                below(&f, &s, u, |t0, t1| {
                    if stop {
                        return Ok(());
                    }
                    let (t0, t1) = (snap(&f, &s, t0), snap(&f, &s, t1));
                    match cur.as_mut() {
                        Some((_, end)) if end.elem + 1 == i && end.t >= 1.0 - 1e-9 && t0 <= 1e-9 => {
                            *end = Mark { elem: i, t: t1 };
                        }
                        _ => {
                            if let Some(r) = cur.take()
                                && wanted(sec, r.0)
                            {
                                done = Some(r);
                                stop = true;
                                return Ok(());
                            }
                            cur = Some((Mark { elem: i, t: t0 }, Mark { elem: i, t: t1 }));
                        }
                    }
                    Ok(())
                })?;
                if stop {
                    return Ok(false);
                }
                // A run ended inside this element: decide now.
                if let Some(r) = cur
                    && r.1.elem == i
                    && r.1.t < 1.0 - 1e-9
                {
                    cur = None;
                    if wanted(sec, r.0) {
                        done = Some(r);
                        return Ok(false);
                    }
                }
                Ok(true)
            })?;
            if done.is_none()
                && let Some(r) = cur
                && wanted(sec, r.0)
            {
                done = Some(r);
            }
            Ok(done)
        }

        /// Element `k` of the rough shape (out of line: four callers).
        #[inline(never)]
        fn shape_seg(&self, raw: &[Seg], k: u16) -> Result<Option<Seg>, AlarmKind> {
            nth(raw, &self.opts()?.rough, k)
        }

        /// Element `k` of the rough shape, which must be there.
        #[inline(never)]
        fn rough_seg(&self, raw: &[Seg], k: u16) -> Result<Seg, AlarmKind> {
            self.shape_seg(raw, k)?.ok_or(AlarmKind::SiemensCycle(CycleAlarm::ContourPreparation { cause: 10931 }))
        }

        /// The point at mark `m` of the rough shape.
        fn point(&self, raw: &[Seg], m: Mark) -> Result<Pt, AlarmKind> {
            Ok(point_at(&self.rough_seg(raw, m.elem)?, m.t))
        }
    }

    /// The contour's first point.
    fn first_raw(raw: &[Seg]) -> Pt {
        raw.first().map_or(Pt::default(), |s| s.a)
    }

    /// Whether the run starting at `start` is section `sec`'s (out of line: three
    /// call sites in the run's walk).
    #[inline(never)]
    fn wanted(sec: &Section, start: Mark) -> bool {
        match sec.descent {
            None => start.elem == 0 && start.t <= 1e-9,
            Some((a, b)) => start.elem >= a && start.elem <= b && !(start.elem == 0 && start.t <= 1e-9),
        }
    }

    /// Whether the tool (on the outward side) is left of the machining direction in
    /// the (Z, X) plane.
    fn tool_left(f: &Frame) -> bool {
        let v = |a: Axis, s: i64| if a == Axis::Z { V2::new(s as f64, 0.0) } else { V2::new(0.0, s as f64) };
        v(f.cut, f.dir).left().dot(v(f.level, f.out)) > 0.0
    }

    /// Highest u of a segment (out of line: four callers).
    #[inline(never)]
    fn high(f: &Frame, s: &Seg) -> i64 {
        let (lo, hi) = s.extent(f.level);
        if f.out > 0 { hi } else { -lo }
    }

    /// The smallest and largest X and Z of the contour.
    fn bounds(raw: &[Seg]) -> (Pt, Pt) {
        let mut lo = Pt::new(i64::MAX, i64::MAX);
        let mut hi = Pt::new(i64::MIN, i64::MIN);
        for s in raw {
            for a in [Axis::X, Axis::Z] {
                let (l, h) = s.extent(a);
                lo = lo.with(a, lo.get(a).min(l));
                hi = hi.with(a, hi.get(a).max(h));
            }
        }
        (lo, hi)
    }

    /// The contour the other way round.
    fn reverse(raw: &mut [Seg]) {
        raw.reverse();
        for s in raw.iter_mut() {
            *s = reversed(s);
        }
    }

    /// A segment the other way round.
    fn reversed(s: &Seg) -> Seg {
        let kind = match s.kind {
            SegKind::Arc { center, cw } => SegKind::Arc { center, cw: !cw },
            k => k,
        };
        Seg { kind, a: s.b, b: s.a }
    }

    /// The contour must go on along the machining direction (an element turning back
    /// is an undercut the cycle cannot cut: 61605), and its undercuts must not be
    /// steeper than the tool's clearance angle allows (61604, P24 = 0: no check).
    fn check_contour(f: &Frame, raw: &[Seg], backwards: bool, clearance_udeg: u32) -> Result<(), AlarmKind> {
        let sign = if backwards { -1.0 } else { 1.0 };
        let limit = f64::from(clearance_udeg) / 1e6;
        for s in raw {
            let (wa, wb) = (f.norm(s.a).1, f.norm(s.b).1);
            // G71/G72's rule too (alarm 0064 there): monotone along the cut.
            if (wb - wa) as f64 * sign < -1.0 || !within(s.extent(f.cut), s.a.get(f.cut), s.b.get(f.cut)) {
                return Err(AlarmKind::SiemensCycle(CycleAlarm::ContourWrong));
            }
            if clearance_udeg == 0 {
                continue;
            }
            // The steepest descent along the element, in the machining direction.
            for i in 0..=8 {
                let t = f64::from(i) / 8.0;
                let (p, q) = (s.point_at((t - 0.01).max(0.0)), s.point_at((t + 0.01).min(1.0)));
                let n = |p: (f64, f64)| {
                    let (x, z) = p;
                    let u = f.out as f64 * if f.level == Axis::X { x } else { z };
                    let w = f.dir as f64 * if f.cut == Axis::X { x } else { z };
                    (u, w)
                };
                let ((u0, w0), (u1, w1)) = (n(p), n(q));
                let (du, dw) = ((u1 - u0) * sign, (w1 - w0) * sign);
                if du < -1e-9 && libm::atan2(-du, dw).to_degrees() > limit + 1e-6 {
                    return Err(AlarmKind::SiemensCycle(CycleAlarm::ToolViolatesContour));
                }
            }
        }
        Ok(())
    }

    /// `t`, or the end of `s` whose level it is within the floor's 1 µm of (and at
    /// most 50 µm from): a level found 1 µm above a floor ends where the floor does.
    fn snap(f: &Frame, s: &Seg, t: f64) -> f64 {
        let p = point_at(s, t);
        let near = |q: Pt| {
            let du = (f.norm(p).0 - f.norm(q).0).abs() as f64;
            let d = libm::hypot((p.x - q.x) as f64, (p.z - q.z) as f64);
            du <= FLOOR_NM * 1.5 && d < 50_000.0
        };
        if near(s.a) {
            0.0
        } else if near(s.b) {
            1.0
        } else {
            t
        }
    }

    /// The point at parameter `t` of a segment, rounded (out of line: inlined, its
    /// f64 evaluation of a line or an arc was copied a dozen times).
    #[inline(never)]
    fn point_at(s: &Seg, t: f64) -> Pt {
        if t <= 0.0 {
            return s.a;
        }
        if t >= 1.0 {
            return s.b;
        }
        let (x, z) = s.point_at(t);
        Pt::new(crate::geom::round_i64(x), crate::geom::round_i64(z))
    }

    /// The piece of `s` from parameter `t0` to `t1` (out of line: three callers).
    #[inline(never)]
    fn part_of(s: &Seg, t0: f64, t1: f64) -> Seg {
        Seg { kind: s.kind, a: point_at(s, t0), b: point_at(s, t1) }
    }
}

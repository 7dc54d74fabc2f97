//! Stock removal by sections (SINUMERIK CYCLE95, seed 001 4.5, lines 10596–10954),
//! on the roughing geometry of G71/G72 ([`super::rough`]: the normalised frame,
//! the material below a level) and the contour offsets of [`super::offset`].
//!
//! The contour (read once, kept in the expansion's profile) is cut in the machining
//! direction: from its end nearer the axis (outside; nearer the tool inside) to the
//! other; a contour programmed the other way round is turned. When its highest
//! point is not an end, an axis-parallel line from the end up to it closes it
//! (lines 10841–10843). The roughing works on the contour moved by the allowances
//! and the nose (so the cuts and the contour following are compensated), the
//! finishing on the contour moved by the nose only.
//!
//! Roughing (lines 10661–10690): the *main section* is the stock above the contour
//! as seen from its start; every *undercut* (a descent of the contour in the
//! machining direction, down to where it stops going down) is a section of its
//! own, below the level where it starts. Each section is cut in n = ⌈depth / MID⌉
//! passes of equal infeed depth / n, between MID and MID/2 (lines 10727–10737:
//! 39 mm with MID 5 → 8 passes of 4.875). A pass of the main section: G0 infeed at
//! the start point's Z, G1 FF1 axis-parallel to the contour, along the contour
//! (FF1) up to the previous pass's cut point (VARI hundreds 2) or one further
//! (hundreds 0, overlapping), over any undercut on the way on a straight line at
//! its mouth; retract _VRT in both axes, G0 back. A pass of an undercut: G0 axis by
//! axis to above the undercut's start, G1 FF2 along its descending contour down to
//! the level, G1 FF1 across, along the contour and out as above. After the last
//! section, back to the start point axis by axis.
//!
//! Finishing (lines 10692–10697, 10888–10890): G0 to the start point, G0 to
//! allowance + nose radius + 1 mm before the contour's start, G1 onto it, the
//! contour at FF3, G0 back axis by axis, the infeed axis first.
//!
//! The start point (lines 10878–10886): allowance + _VRT off the contour's highest
//! point on the infeed axis, allowance + _VRT before its start on the other.

use super::StepQueue;
use super::emit::Step;
use super::offset::{Offsets, walk};
use super::pass::{PassGen, along};
use super::pattern::PatternGen;
use super::rough::{Frame, below};
use crate::alarm::{AlarmKind, CycleAlarm};
use crate::axis::Axis;
use crate::command::job::{Blank, Pull, StockSpec};
use crate::geom::path::V2;
use crate::geom::{Pt, Seg, SegKind};

/// A roughing level's material within 1 µm of the contour counts: the last pass of
/// a section cuts along a floor that lies exactly at its level.
const FLOOR_NM: f64 = 1_000.0;

/// A point on the shape: element `elem`, parameter `t` along it.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Mark {
    elem: u16,
    t: f64,
}

/// What a pass of a section does next.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Part {
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

#[derive(Clone, Copy, Debug, PartialEq)]
enum Phase {
    Approach,
    Level {
        s: u16,
        k: u32,
        part: Part,
    },
    Return,
    /// Contour-parallel roughing (CYCLE950): G73's passes.
    Pattern(PatternGen),
    Finish,
    Done,
}

/// One section: the main one or an undercut, its levels and where it starts.
#[derive(Clone, Copy, Debug)]
struct Section {
    /// First and last element of the undercut's descent (main: none).
    descent: Option<(u16, u16)>,
    top: i64,
    bottom: i64,
}

/// CYCLE95 as an expansion.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StockGen {
    spec: StockSpec,
    frame: Frame,
    rough: Offsets,
    /// The finishing pass.
    finish: PassGen,
    /// The cycle's start point, normalised.
    start: (i64, i64),
    /// Feed in force at the call (an FF of 0).
    base_feed: i64,
    phase: Phase,
}

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

impl StockGen {
    /// Sets up CYCLE95 on the contour `raw` (from its first point, as programmed),
    /// turning it into the machining direction in place when it roughs, closing
    /// it up to its highest point. `here` is where the tool is.
    pub fn new(
        spec: &StockSpec,
        raw: &mut heapless::Vec<Seg, { super::profile::PROFILE_MAX }>,
        here: Pt,
        nose: Nose,
        base_feed: i64,
    ) -> Result<StockGen, AlarmKind> {
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
        let dir = (b.get(cut) - a.get(cut)).signum();
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
        let tip = crate::contour::comp::tip_vector(nose.tip, nose.radius);
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
        let mut g = StockGen {
            spec: *spec,
            frame,
            rough,
            finish: PassGen::new(finish, (0, 0), Pt::default(), [None; 3], 0, [None; 3]),
            start: (0, 0),
            base_feed,
            phase: Phase::Approach,
        };
        // The start point, from the rough shape (the finishing shape when it is
        // walked backwards: its start is the far end).
        let (mut umax, mut wfirst) = (i64::MIN, None);
        let o = if back { finish } else { g.rough };
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
        g.start = (top_u + bu + spec.retract, w0 - bw - spec.retract.max(spec.approach));
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
        let after = [Some(frame.work(g.start.0, frame.norm(last).1)), Some(s), None];
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
        g.finish = PassGen::new(finish, path, Pt::default(), before, g.feed(2), after).arcs_at(spec.arc_feed);
        Ok(g)
    }

    /// Contour-parallel roughing: G73's passes from the blank's allowance down to
    /// the finishing allowances, MID apart (perpendicular to the contour: the larger
    /// of the two allowances decides the count).
    fn pattern(&self) -> Result<PatternGen, AlarmKind> {
        let f = self.frame;
        let blank = match self.spec.blank {
            Blank::Allowance(a) => a,
            _ => Pt::default(),
        };
        let (au, aw) = if self.spec.facing { (blank.z, blank.x) } else { (blank.x, blank.z) };
        let count = levels(au.abs().max(aw.abs()), self.spec.depth, true).max(1);
        // G73's first pass is at the relief: one step inside the blank's surface.
        let inside = |v: i64| v.abs() * i64::from(count - 1) / i64::from(count);
        let (au, aw) = (inside(au), inside(aw));
        let (fu, fw) = if self.spec.facing {
            (self.spec.allow_z, self.spec.allow_x)
        } else {
            (self.spec.allow_x, self.spec.allow_z)
        };
        // Outward on the infeed axis, back towards the start on the cutting axis.
        let relief = f.work(au, -aw);
        let allowance = f.work(fu + self.spec.allow, -(fw + self.spec.allow));
        PatternGen::new(self.s_point(), relief, count, allowance)
    }

    /// The start point (work).
    fn s_point(&self) -> Pt {
        self.frame.work(self.start.0, self.start.1)
    }

    fn feed(&self, i: usize) -> i64 {
        if self.spec.feeds[i] > 0 { self.spec.feeds[i] } else { self.base_feed }
    }

    /// The next group of steps; `false` when finished.
    pub fn fill(&mut self, raw: &[Seg], here: Pt, out: &mut StepQueue) -> Result<bool, AlarmKind> {
        let f = self.frame;
        match self.phase {
            Phase::Approach => {
                push(out, Step::Rapid(self.s_point()))?;
                self.phase = if !self.spec.rough {
                    Phase::Finish
                } else if self.spec.parallel {
                    push(out, Step::Feedrate(self.feed(0)))?;
                    Phase::Pattern(self.pattern()?)
                } else {
                    Phase::Level { s: 0, k: 1, part: Part::Begin }
                };
            }
            Phase::Pattern(mut p) => {
                if p.fill_segs(raw, true, out)? {
                    self.phase = Phase::Pattern(p);
                } else {
                    self.phase = if self.spec.finish { Phase::Finish } else { Phase::Done };
                }
            }
            Phase::Level { s, k, part } => self.level(raw, here, s, k, part, out)?,
            Phase::Return => {
                let (_, w) = f.norm(here);
                push(out, Step::Rapid(f.work(self.start.0, w)))?;
                push(out, Step::Rapid(self.s_point()))?;
                self.phase = if self.spec.finish { Phase::Finish } else { Phase::Done };
            }
            Phase::Finish => {
                if !self.finish.fill(raw, out)? {
                    self.phase = Phase::Done;
                }
            }
            Phase::Done => return Ok(false),
        }
        Ok(true)
    }

    /// One part of a roughing pass.
    fn level(
        &mut self,
        raw: &[Seg],
        here: Pt,
        s: u16,
        k: u32,
        part: Part,
        out: &mut StepQueue,
    ) -> Result<(), AlarmKind> {
        let f = self.frame;
        let sec = if s > 0 && !self.spec.undercuts { None } else { self.section(raw, s)? };
        let Some(sec) = sec else {
            self.phase = Phase::Return;
            return Ok(());
        };
        let equal = self.spec.equal;
        let n = levels(sec.top - sec.bottom, self.spec.depth, equal);
        if k > n {
            self.phase = Phase::Level { s: s + 1, k: 1, part: Part::Begin };
            return Ok(());
        }
        let u_k = level_u(&sec, k, n, equal, self.spec.depth);
        let set = |me: &mut Self, part| me.phase = Phase::Level { s, k, part };
        match part {
            Part::Begin => {
                let floor = if k == n { FLOOR_NM } else { 0.0 };
                let Some((from, to)) = self.run(raw, &sec, u_k as f64 + floor)? else {
                    // Nothing at this level.
                    self.phase = Phase::Level { s, k: k + 1, part: Part::Begin };
                    return Ok(());
                };
                match sec.descent {
                    None => {
                        push(out, Step::Rapid(f.work(u_k, self.start.1)))?;
                        push(out, Step::Feedrate(self.feed(0)))?;
                        set(self, Part::Cut { w: self.start.1, end: to });
                    }
                    Some((d0, _)) => {
                        let top = self.point(raw, Mark { elem: d0, t: 0.0 })?;
                        let (tu, tw) = f.norm(top);
                        let above = (sec.top + self.spec.retract, tw - self.spec.retract);
                        let (hu, hw) = f.norm(here);
                        if (hu, hw) != above {
                            // Axis by axis over the part to above the undercut.
                            push(out, Step::Rapid(f.work(self.start.0.max(hu), hw)))?;
                            push(out, Step::Rapid(f.work(self.start.0.max(hu), above.1)))?;
                            push(out, Step::Rapid(f.work(above.0, above.1)))?;
                        }
                        push(out, Step::Feedrate(self.feed(1)))?;
                        push(out, Step::Feed(f.work(tu, tw)))?;
                        set(self, Part::Follow { at: Mark { elem: d0, t: 0.0 }, to: from, end: to });
                    }
                }
            }
            Part::Follow { at, to, end } => {
                let mut at = at;
                for _ in 0..4 {
                    let seg = self
                        .shape_seg(raw, &self.rough, at.elem)?
                        .ok_or(AlarmKind::SiemensCycle(CycleAlarm::ContourPreparation { cause: 10931 }))?;
                    if at.elem == to.elem {
                        let piece = part_of(&seg, at.t, to.t);
                        push(out, along(&piece))?;
                        push(out, Step::Feedrate(self.feed(0)))?;
                        set(self, Part::Cut { w: f.norm(piece.b).1, end });
                        return Ok(());
                    }
                    push(out, along(&part_of(&seg, at.t, 1.0)))?;
                    at = Mark { elem: at.elem + 1, t: 0.0 };
                }
                set(self, Part::Follow { at, to, end });
            }
            Part::Cut { w, end } => {
                let seg = self
                    .shape_seg(raw, &self.rough, end.elem)?
                    .ok_or(AlarmKind::SiemensCycle(CycleAlarm::ContourPreparation { cause: 10931 }))?;
                let w_end = f.norm(point_at(&seg, end.t)).1;
                let step = self.spec.interrupt;
                let mut w = w;
                for _ in 0..3 {
                    let next = if step > 0 && w_end - w > step { w + step } else { w_end };
                    push(out, Step::Feed(f.work(u_k, next)))?;
                    if next == w_end {
                        push(out, Step::Feed(point_at(&seg, end.t)))?;
                        let back = match self.spec.pull {
                            Pull::None => 0,
                            Pull::Previous => 1,
                            Pull::Overlap => 2,
                        };
                        let target =
                            if k > back { level_u(&sec, k - back, n, equal, self.spec.depth) } else { sec.top };
                        set(self, if back == 0 { Part::Out } else { Part::Pull { at: end, target } });
                        return Ok(());
                    }
                    push(out, Step::Dwell(self.spec.dwell_ms))?;
                    w = next;
                }
                set(self, Part::Cut { w, end });
            }
            Part::Pull { at, target } => {
                let next = self.pull(raw, at, target, out)?;
                match next {
                    Some(m) => set(self, Part::Pull { at: m, target }),
                    None => set(self, Part::Out),
                }
            }
            Part::Out => {
                let (hu, hw) = f.norm(here);
                let r = self.spec.retract;
                // At 45° _VRT in both axes; at another angle never more (line 11632).
                let a = (self.spec.retract_angle_udeg as f64 / 1e6).to_radians();
                let (tu, tw) = (libm::tan(a).min(1.0), (1.0 / libm::tan(a)).min(1.0));
                let (ru, rw) = (hu + libm::round(r as f64 * tu) as i64, hw - libm::round(r as f64 * tw) as i64);
                push(out, Step::Feed(f.work(ru, rw)))?;
                match sec.descent {
                    None => push(out, Step::Rapid(f.work(ru, self.start.1)))?,
                    Some((d0, _)) => {
                        let top = self.point(raw, Mark { elem: d0, t: 0.0 })?;
                        let up = sec.top + r;
                        push(out, Step::Rapid(f.work(ru.max(up), rw)))?;
                        push(out, Step::Rapid(f.work(ru.max(up), f.norm(top).1 - r)))?;
                    }
                }
                self.phase = Phase::Level { s, k: k + 1, part: Part::Begin };
            }
        }
        Ok(())
    }

    /// Along the contour from `at` (at most four steps) towards the level
    /// `target`, over undercuts on a straight line at their mouth; `None` when
    /// the level is reached (or the contour ends).
    fn pull(&self, raw: &[Seg], at: Mark, target: i64, out: &mut StepQueue) -> Result<Option<Mark>, AlarmKind> {
        let f = self.frame;
        let mut at = at;
        for _ in 0..4 {
            let Some(seg) = self.shape_seg(raw, &self.rough, at.elem)? else { return Ok(None) };
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
        walk(raw, &self.rough, |s| {
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
        walk(raw, &self.rough, |seg| {
            let i = k;
            k += 1;
            top = top.max(high(&f, &seg));
            entry.get_or_insert(f.norm(seg.a).0);
            let (ua, ub) = (f.norm(seg.a).0, f.norm(seg.b).0);
            let low = low(&f, &seg);
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
        walk(raw, &self.rough, |s| {
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

    /// Element `k` of the path `o` makes of `raw`.
    fn shape_seg(&self, raw: &[Seg], o: &Offsets, k: u16) -> Result<Option<Seg>, AlarmKind> {
        let mut i = 0u16;
        let mut found = None;
        walk(raw, o, |s| {
            if i == k {
                found = Some(s);
                return Ok(false);
            }
            i += 1;
            Ok(true)
        })?;
        Ok(found)
    }

    /// The point at mark `m` of the rough shape.
    fn point(&self, raw: &[Seg], m: Mark) -> Result<Pt, AlarmKind> {
        let s = self
            .shape_seg(raw, &self.rough, m.elem)?
            .ok_or(AlarmKind::SiemensCycle(CycleAlarm::ContourPreparation { cause: 10931 }))?;
        Ok(point_at(&s, m.t))
    }
}

/// The contour's first point.
fn first_raw(raw: &[Seg]) -> Pt {
    raw.first().map_or(Pt::default(), |s| s.a)
}

/// Whether the run starting at `start` is section `sec`'s.
fn wanted(sec: &Section, start: Mark) -> bool {
    match sec.descent {
        None => start.elem == 0 && start.t <= 1e-9,
        Some((a, b)) => start.elem >= a && start.elem <= b && !(start.elem == 0 && start.t <= 1e-9),
    }
}

/// Passes for a depth: ⌈depth / MID⌉ equal ones (line 10731), or full MID steps
/// while at least two are left, then two halves (lines 11702–11706).
fn levels(depth: i64, mid: i64, equal: bool) -> u32 {
    if depth <= 0 || mid <= 0 {
        return 0;
    }
    let n = if equal {
        (depth + mid - 1) / mid
    } else if depth >= 2 * mid {
        (depth - 2 * mid) / mid + 3
    } else {
        2
    };
    u32::try_from(n).unwrap_or(u32::MAX)
}

/// Level `k` of `n` of a section from its top to its bottom: equal steps (CYCLE95,
/// line 10731), or full steps of `mid` until less than two are left, then two
/// halves (CYCLE950, lines 11702–11706).
fn level_u(sec: &Section, k: u32, n: u32, equal: bool, mid: i64) -> i64 {
    let depth = sec.top - sec.bottom;
    if equal || n < 2 {
        return sec.top - libm::round(depth as f64 * f64::from(k) / f64::from(n)) as i64;
    }
    let full = i64::from(n - 2);
    if i64::from(k) <= full {
        return sec.top - i64::from(k) * mid;
    }
    let rest = depth - full * mid;
    if k == n { sec.bottom } else { sec.top - full * mid - rest / 2 }
}

/// Whether the tool (on the outward side) is left of the machining direction in
/// the (Z, X) plane.
fn tool_left(f: &Frame) -> bool {
    let v = |a: Axis, s: i64| if a == Axis::Z { V2::new(s as f64, 0.0) } else { V2::new(0.0, s as f64) };
    v(f.cut, f.dir).left().dot(v(f.level, f.out)) > 0.0
}

/// Highest u of a segment.
fn high(f: &Frame, s: &Seg) -> i64 {
    let (lo, hi) = s.extent(f.level);
    if f.out > 0 { hi } else { -lo }
}

/// Lowest u of a segment.
fn low(f: &Frame, s: &Seg) -> i64 {
    let (lo, hi) = s.extent(f.level);
    if f.out > 0 { lo } else { -hi }
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
        let (lo, hi) = s.extent(f.cut);
        let within = lo >= s.a.get(f.cut).min(s.b.get(f.cut)) - 1 && hi <= s.a.get(f.cut).max(s.b.get(f.cut)) + 1;
        if (wb - wa) as f64 * sign < -1.0 || !within {
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

/// The point at parameter `t` of a segment, rounded.
fn point_at(s: &Seg, t: f64) -> Pt {
    if t <= 0.0 {
        return s.a;
    }
    if t >= 1.0 {
        return s.b;
    }
    let (x, z) = s.point_at(t);
    Pt::new(libm::round(x) as i64, libm::round(z) as i64)
}

/// The piece of `s` from parameter `t0` to `t1`.
fn part_of(s: &Seg, t0: f64, t1: f64) -> Seg {
    Seg { kind: s.kind, a: point_at(s, t0), b: point_at(s, t1) }
}

fn push(out: &mut StepQueue, s: Step) -> Result<(), AlarmKind> {
    out.push_back(s).map_err(|_| AlarmKind::Overflow)
}

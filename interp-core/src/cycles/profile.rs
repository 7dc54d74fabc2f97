//! The finishing shape of G70–G73: the blocks ns–nf read, checked and executed
//! through the normal pipeline on a scratch copy of the state, their motion kept as
//! segments in work coordinates. Plus the segment geometry the roughing cycles need
//! (points along a segment, crossings with a level, extents).

use super::emit::Pt;
use super::{CycleStage, Execute};
use crate::alarm::AlarmKind;
use crate::axis::Axis;
use crate::canon::{Action, SpindleDir};
use crate::codes::{GCode, MFunction};
use crate::config::MachineConfig;
use crate::env::Environment;
use crate::lang::ProgramText;
use crate::lang::fanuc::check::check;
use crate::lang::fanuc::macros::MacroStatement;
use crate::lang::fanuc::parse::{Block, Read, read_with};
use crate::modal::State;
use crate::program::{Cursor, find_sequence_from, next_block};
use crate::stage::Flow;

/// Most segments a finishing shape may have (alarm 4035 beyond).
pub const PROFILE_MAX: usize = 48;

/// How a segment of the shape moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SegKind {
    /// G00.
    Rapid,
    /// G01.
    Line,
    /// G02/G03 around `center`.
    Arc {
        /// Centre.
        center: Pt,
        /// G02.
        cw: bool,
    },
}

/// One move of the shape, start to end.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Seg {
    /// Kind.
    pub kind: SegKind,
    /// Start.
    pub a: Pt,
    /// End.
    pub b: Pt,
}

/// The finishing shape A → B → … → C.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Profile {
    /// The segments in order; the first is the ns block's move from A.
    pub segs: heapless::Vec<Seg, PROFILE_MAX>,
    /// The ns block commanded X (or U).
    pub ns_x: bool,
    /// The ns block commanded Z (or W).
    pub ns_z: bool,
    /// The ns block is G00 (else G01).
    pub ns_rapid: bool,
    /// Where the program goes on after the cycle: the block after nf.
    pub resume: Cursor,
}

impl Seg {
    /// The segment moved by `d`.
    #[inline(never)]
    pub fn shifted(self, d: Pt) -> Seg {
        let mv = |p: Pt| Pt::new(p.x + d.x, p.z + d.z);
        let kind = match self.kind {
            SegKind::Arc { center, cw } => SegKind::Arc { center: mv(center), cw },
            k => k,
        };
        Seg { kind, a: mv(self.a), b: mv(self.b) }
    }

    /// Signed sweep of an arc in radians, counter-clockwise positive in the (Z, X) plane.
    fn sweep(&self, center: Pt, cw: bool) -> f64 {
        let tau = core::f64::consts::TAU;
        let d = wrap(angle(center, self.b) - angle(center, self.a));
        if cw {
            if d == 0.0 { -tau } else { d - tau }
        } else if d == 0.0 {
            tau
        } else {
            d
        }
    }

    /// The point at parameter `t` ∈ [0, 1] (by length for lines, by angle for arcs), f64 nm.
    pub fn point_at(&self, t: f64) -> (f64, f64) {
        match self.kind {
            SegKind::Arc { center, cw } => {
                let r = radius(center, self.a);
                let th = angle(center, self.a) + t * self.sweep(center, cw);
                (center.x as f64 + r * libm::sin(th), center.z as f64 + r * libm::cos(th))
            }
            _ => {
                let (ax, az) = (self.a.x as f64, self.a.z as f64);
                (ax + t * (self.b.x - self.a.x) as f64, az + t * (self.b.z - self.a.z) as f64)
            }
        }
    }

    /// Parameters t ∈ (0, 1) where the segment's `axis` coordinate equals `v`.
    pub fn crossings(&self, axis: Axis, v: f64) -> heapless::Vec<f64, 2> {
        let mut out = heapless::Vec::new();
        let coord = |p: Pt| if axis == Axis::X { p.x as f64 } else { p.z as f64 };
        match self.kind {
            SegKind::Arc { center, cw } => {
                let r = radius(center, self.a);
                let c = coord(center);
                let s = (v - c) / r;
                if !(-1.0..=1.0).contains(&s) {
                    return out;
                }
                // x = cx + r·sin θ, z = cz + r·cos θ.
                let (t1, t2) = if axis == Axis::X {
                    let a = libm::asin(s);
                    (a, core::f64::consts::PI - a)
                } else {
                    let a = libm::acos(s);
                    (a, -a)
                };
                let sweep = self.sweep(center, cw);
                let start = angle(center, self.a);
                for th in [t1, t2] {
                    let d = if sweep >= 0.0 { wrap(th - start) } else { wrap(start - th) };
                    let t = d / sweep.abs();
                    if t > 0.0 && t < 1.0 && !out.iter().any(|o: &f64| (o - t).abs() < 1e-12) {
                        let _ = out.push(t);
                    }
                }
                if out.len() == 2 && out[0] > out[1] {
                    out.swap(0, 1);
                }
            }
            _ => {
                let (a, b) = (coord(self.a), coord(self.b));
                if a != b {
                    let t = (v - a) / (b - a);
                    if t > 0.0 && t < 1.0 {
                        let _ = out.push(t);
                    }
                }
            }
        }
        out
    }

    /// Smallest and largest value of `axis` along the segment.
    #[inline(never)]
    pub fn extent(&self, axis: Axis) -> (i64, i64) {
        match self.kind {
            SegKind::Arc { center, cw } => {
                let e = crate::geom::arc_extents(
                    (self.a.z, self.a.x),
                    (self.b.z, self.b.x),
                    (center.z, center.x),
                    cw,
                    false,
                );
                if axis == Axis::X { e.b } else { e.a }
            }
            _ => {
                let (a, b) = (self.a.get(axis), self.b.get(axis));
                (a.min(b), a.max(b))
            }
        }
    }
}

fn angle(c: Pt, p: Pt) -> f64 {
    libm::atan2((p.x - c.x) as f64, (p.z - c.z) as f64)
}

fn radius(c: Pt, p: Pt) -> f64 {
    libm::hypot((p.x - c.x) as f64, (p.z - c.z) as f64)
}

fn wrap(x: f64) -> f64 {
    let tau = core::f64::consts::TAU;
    let r = libm::fmod(x, tau);
    if r < 0.0 { r + tau } else { r }
}

/// Where the blocks ns–nf are and how to run them.
pub struct ShapeSource<'a> {
    /// The current program (text, start, variables for the words).
    pub program: ProgramText<'a>,
    /// First block's sequence number.
    pub ns: u32,
    /// Last block's sequence number.
    pub nf: u32,
}

/// The cursor of block ns (alarm 0063 if missing).
pub fn start_of(src: &ShapeSource<'_>) -> Result<Cursor, AlarmKind> {
    let (text, from) = (src.program.text, src.program.start);
    let start = find_sequence_from(text, from, src.ns).ok_or(AlarmKind::SequenceNotFound { n: src.ns })?;
    find_sequence_from(text, from, src.nf).ok_or(AlarmKind::SequenceNotFound { n: src.nf })?;
    Ok(start)
}

/// What reading one shape block gave.
pub struct ShapeBlock {
    /// The block's words.
    pub block: Block,
    /// It is the nf block.
    pub last: bool,
}

/// Reads the next block of the shape at `cur` (skipping blank and skipped blocks),
/// with the checks of 2.16.7 notes 2–3 that need only the words. `first` is the
/// ns block. `None` past the text (alarm 0063 for nf then).
pub fn next_shape_block<E: Environment + ?Sized>(
    src: &ShapeSource<'_>,
    cur: &mut Cursor,
    env: &E,
) -> Result<Option<ShapeBlock>, AlarmKind> {
    loop {
        let Some(raw) = next_block(src.program.text, cur) else {
            return Err(AlarmKind::SequenceNotFound { n: src.nf });
        };
        if raw.percent {
            return Err(AlarmKind::SequenceNotFound { n: src.nf });
        }
        // Words may use variables (read as the cycle block saw them); a macro
        // statement or call (G65, G66, G67) cannot be part of a shape.
        let mut block = Block::default();
        match read_with(raw.text, raw.line, src.program.vars, src.program.fmt, &mut block)? {
            Read::Nc => {}
            Read::Macro(m) if m.statement == MacroStatement::Call => {
                return Err(AlarmKind::ProfileForbiddenCode { what: "a macro call (G65, G66, G67)" });
            }
            Read::Macro(_) => return Err(AlarmKind::ProfileForbiddenCode { what: "a macro statement" }),
        }
        let last = block.seq == Some(src.nf);
        // Note 4: block skip as the switch stands when the block is read.
        let skipped = block.skip_level.is_some_and(|l| env.block_skip(l));
        if (skipped || block.is_empty()) && !last {
            continue;
        }
        if block.m.iter().any(|&m| m == 98 || m == 99) {
            return Err(AlarmKind::ProfileForbiddenCode { what: "M98/M99" });
        }
        return Ok(Some(ShapeBlock { block, last }));
    }
}

/// Checks a shape block's command against 2.16.7 notes 2–3.
pub fn check_shape_command(cmd: &crate::command::Command, first: bool) -> Result<(), AlarmKind> {
    use GCode::*;
    if let Some(c) = cmd.g.one_shot
        && c != Dwell
    {
        return Err(AlarmKind::ProfileForbiddenCode { what: "a group 00 code other than G04" });
    }
    if let Some(m) = cmd.g.motion
        && !matches!(m, Rapid | Linear | ArcCw | ArcCcw)
    {
        return Err(AlarmKind::ProfileForbiddenCode { what: "a group 01 code other than G00-G03" });
    }
    if cmd.g.units.is_some() {
        return Err(AlarmKind::ProfileForbiddenCode { what: "G20/G21" });
    }
    if cmd.g.drilling.is_some_and(|d| d != DrillCancel) {
        return Err(AlarmKind::ProfileForbiddenCode { what: "a drilling cycle" });
    }
    if cmd
        .m
        .iter()
        .any(|&(_, f)| matches!(f, MFunction::Stop | MFunction::OptionalStop | MFunction::End | MFunction::EndRewind))
    {
        return Err(AlarmKind::ProfileForbiddenCode { what: "M00/M01/M02/M30" });
    }
    if first && !matches!(cmd.g.motion, Some(Rapid | Linear)) {
        return Err(AlarmKind::ProfileFirstBlock);
    }
    Ok(())
}

/// Runs one shape block on `st` through check and `execute` (exec) into `staged`.
pub fn run_shape_block<E: Environment + ?Sized>(
    sb: &ShapeBlock,
    first: bool,
    st: &mut State,
    cfg: &MachineConfig,
    env: &E,
    execute: Execute,
    staged: &mut CycleStage<'_>,
) -> Result<crate::command::Command, AlarmKind> {
    let units = |t: &u16| matches!(GCode::from_tenths(cfg.code_table(), *t), Some(GCode::Inch | GCode::Metric));
    if sb.block.g.iter().any(units) {
        return Err(AlarmKind::ProfileForbiddenCode { what: "G20/G21" });
    }
    let cmd = check(&sb.block, st, cfg)?;
    check_shape_command(&cmd, first)?;
    let mut next = *st;
    let flow = execute(&cmd, &mut next, cfg, &EnvRef(env), staged)?;
    if flow != Flow::Continue {
        return Err(AlarmKind::ProfileForbiddenCode { what: "M00/M01/M02/M30" });
    }
    *st = next;
    Ok(cmd)
}

/// Adapts `&E` (possibly unsized) to `&dyn Environment`.
struct EnvRef<'a, E: ?Sized>(&'a E);

impl<E: Environment + ?Sized> Environment for EnvRef<'_, E> {
    fn block_skip(&self, level: u8) -> bool {
        self.0.block_skip(level)
    }
    fn optional_stop(&self) -> bool {
        self.0.optional_stop()
    }
    fn referenced(&self, axis: Axis) -> bool {
        self.0.referenced(axis)
    }
    fn input(&self, n: u16) -> Option<bool> {
        self.0.input(n)
    }
}

/// Reads the shape ns–nf starting at the state `st` (the cycle's start point A)
/// into `profile` (in the expansion itself: a profile is ~3 KB). Roughing ignores
/// the shape's F, S and T, so the scratch state gets a feed and a turning spindle:
/// geometry must not fail on a feed that roughing never uses.
pub fn read_profile<E: Environment + ?Sized>(
    src: &ShapeSource<'_>,
    st: &State,
    cfg: &MachineConfig,
    env: &E,
    execute: Execute,
    profile: &mut Profile,
) -> Result<(), AlarmKind> {
    let mut scratch = *st;
    // Roughing follows the programmed shape: no nose compensation (2.16.7 note 5).
    scratch.contour.clear();
    scratch.contour.no_comp = true;
    scratch.feed.per_min = scratch.feed.per_min.max(1);
    scratch.feed.per_rev = scratch.feed.per_rev.max(1);
    if scratch.spindle.dir == SpindleDir::Stop {
        scratch.spindle.dir = SpindleDir::Cw;
    }
    scratch.spindle.rpm = scratch.spindle.rpm.max(1);
    let mut cur = start_of(src)?;
    profile.segs.clear();
    let mut first = true;
    loop {
        let Some(sb) = next_shape_block(src, &mut cur, env)? else { break };
        let mut outbox = crate::stage::Outbox::new();
        let mut staged = CycleStage::new(sb.block.line, &mut outbox);
        let here = scratch.work_pos(cfg);
        // A move held back for a corner (2.23) comes out with this block: it
        // starts where the last segment ended.
        let held = scratch.contour.is_holding();
        let cmd = run_shape_block(&sb, first, &mut scratch, cfg, env, execute, &mut staged)?;
        if first {
            profile.ns_x = cmd.axes[Axis::X.index()].is_some();
            profile.ns_z = cmd.axes[Axis::Z.index()].is_some();
            profile.ns_rapid = cmd.g.motion == Some(GCode::Rapid);
        }
        let mut a = match profile.segs.last() {
            Some(s) if held => s.b,
            _ => Pt::new(here[Axis::X], here[Axis::Z]),
        };
        if sb.last {
            crate::contour::flush(&mut scratch, &mut staged)?;
        }
        for c in staged.actions.iter() {
            let (kind, to) = match c.action {
                Action::Rapid(m) => (SegKind::Rapid, m.to.work),
                Action::Linear(m) => (SegKind::Line, m.to.work),
                Action::Arc(arc) => {
                    if arc.plane != crate::canon::Plane::Zx {
                        return Err(AlarmKind::CycleNotInZxPlane);
                    }
                    let center = Pt::new(arc.center.work[Axis::X], arc.center.work[Axis::Z]);
                    (SegKind::Arc { center, cw: arc.cw }, arc.to.work)
                }
                Action::Thread(_) | Action::Tap(_) => {
                    return Err(AlarmKind::ProfileForbiddenCode { what: "threading" });
                }
                _ => continue,
            };
            let b = Pt::new(to[Axis::X], to[Axis::Z]);
            profile.segs.push(Seg { kind, a, b }).map_err(|_| AlarmKind::ProfileTooLong)?;
            a = b;
        }
        if first && profile.segs.is_empty() {
            // The ns block must move (it defines B).
            return Err(AlarmKind::ProfileFirstBlock);
        }
        first = false;
        if sb.last {
            profile.resume = cur;
            return Ok(());
        }
    }
    Err(AlarmKind::SequenceNotFound { n: src.nf })
}

#[cfg(test)]
mod tests {
    use super::*;

    const MM: i64 = 1_000_000;

    #[test]
    fn arc_points_and_crossings() {
        // Quarter circle from (x0, z10) around (x0, z0) counter-clockwise in (Z, X):
        // angle 0 at +Z, 90° at +X: ends at (x10, z0).
        let s = Seg {
            kind: SegKind::Arc { center: Pt::new(0, 0), cw: false },
            a: Pt::new(0, 10 * MM),
            b: Pt::new(10 * MM, 0),
        };
        let (x, z) = s.point_at(0.5);
        assert!((x - 7.0710678e6).abs() < 1.0 && (z - 7.0710678e6).abs() < 1.0);
        let c = s.crossings(Axis::X, 5.0 * MM as f64);
        assert_eq!(c.len(), 1);
        let (x, _) = s.point_at(c[0]);
        assert!((x - 5.0e6).abs() < 1e-3);
        assert_eq!(s.extent(Axis::X), (0, 10 * MM));
        // Clockwise the long way round passes x = -10.
        let s2 = Seg { kind: SegKind::Arc { center: Pt::new(0, 0), cw: true }, ..s };
        assert_eq!(s2.extent(Axis::X), (-10 * MM, 10 * MM));
        assert_eq!(s2.crossings(Axis::X, 5.0 * MM as f64).len(), 1);
    }
}

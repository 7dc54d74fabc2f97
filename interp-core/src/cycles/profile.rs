//! The finishing shape of G70–G73: the blocks ns–nf read, checked and executed
//! through the normal pipeline on a scratch copy of the state, their motion kept as
//! segments in work coordinates. Plus the segment geometry the roughing cycles need
//! (points along a segment, crossings with a level, extents).

use super::emit::Pt;
use super::{CycleStage, Execute};
use crate::alarm::{AlarmKind, CycleAlarm};
use crate::axis::Axis;
use crate::canon::{Action, SpindleDir};
use crate::codes::{GCode, MFunction};
use crate::config::MachineConfig;
use crate::env::Environment;
pub use crate::geom::{Seg, SegKind};
use crate::lang::ProgramText;
use crate::lang::fanuc::check::check;
use crate::lang::fanuc::macros::MacroStatement;
use crate::lang::fanuc::parse::{Block, Read, read_with};
use crate::modal::State;
use crate::program::{Cursor, find_sequence_from, next_block};
use crate::stage::Flow;

pub use cycle_paths::profile::{PROFILE_MAX, Profile};

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
/// Out of line and not generic: G70's finishing pass and the profile reader
/// share one copy (generic over the environment, it had two).
#[inline(never)]
pub fn next_shape_block(
    src: &ShapeSource<'_>,
    cur: &mut Cursor,
    env: &dyn Environment,
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

/// Runs one shape block on `st` through check and `execute` (exec) into `staged`;
/// after an alarm `st` is left as the block's execution left it (every caller
/// drops it then). Out of line: G70's finishing pass and the profile reader
/// share one copy. (Generic over the environment on purpose: the profile
/// reader's copy calls `exec::execute` directly, which `firmware/stack-bound.py`
/// follows; one `&dyn Environment` copy, 500 B smaller, calls it only through
/// the pointer, and the tool's bound then misses the shape blocks' recursion.)
#[inline(never)]
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
    // Executed on `st` in place (no copy of the state on the stack under the
    // block's execution): after an alarm `st` is thrown away with the cycle
    // (the profile reader's scratch state, G70's expansion or its dry run).
    let flow = execute(&cmd, st, cfg, &EnvRef(env), staged)?;
    if flow != Flow::Continue {
        return Err(AlarmKind::ProfileForbiddenCode { what: "M00/M01/M02/M30" });
    }
    Ok(cmd)
}

/// Adapts `&E` (possibly unsized) to `&dyn Environment`.
pub(super) struct EnvRef<'a, E: ?Sized>(pub(super) &'a E);

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
/// into `profile` (in the expansion itself: a profile is ~3 KB), each block's
/// actions staged in `outbox` (the expansion's, left empty). Roughing ignores
/// the shape's F, S and T, so the scratch state gets a feed and a turning spindle:
/// geometry must not fail on a feed that roughing never uses.
pub fn read_profile<E: Environment + ?Sized>(
    src: &ShapeSource<'_>,
    st: &State,
    cfg: &MachineConfig,
    env: &E,
    execute: Execute,
    profile: &mut Profile,
    outbox: &mut crate::stage::Outbox,
) -> Result<Cursor, AlarmKind> {
    let mut scratch = scratch(st);
    let mut cur = start_of(src)?;
    profile.segs.clear();
    let mut first = true;
    loop {
        let Some(sb) = next_shape_block(src, &mut cur, &EnvRef(env))? else { break };
        outbox.clear();
        let mut staged = CycleStage::new(sb.block.line, outbox);
        let here = super::emit::work_pos(&scratch, cfg);
        // A move held back for a corner (2.23) comes out with this block: it
        // starts where the last segment ended.
        let held = scratch.contour.is_holding();
        let cmd = run_shape_block(&sb, first, &mut scratch, cfg, env, execute, &mut staged)?;
        if first {
            profile.ns_x = cmd.axes[Axis::X.index()].is_some();
            profile.ns_z = cmd.axes[Axis::Z.index()].is_some();
            profile.ns_rapid = cmd.g.motion == Some(GCode::Rapid);
        }
        let a = match profile.segs.last() {
            Some(s) if held => s.b,
            _ => Pt::new(here[Axis::X], here[Axis::Z]),
        };
        if sb.last {
            crate::contour::flush(&mut scratch, &mut staged)?;
        }
        keep_moves(&staged, a, crate::canon::Plane::Zx, profile)?;
        if first && profile.segs.is_empty() {
            // The ns block must move (it defines B).
            return Err(AlarmKind::ProfileFirstBlock);
        }
        first = false;
        if sb.last {
            outbox.clear();
            return Ok(cur);
        }
    }
    Err(AlarmKind::SequenceNotFound { n: src.nf })
}

/// A copy of `st` to run a shape's blocks on. Roughing follows the programmed
/// shape: no nose compensation (2.16.7 note 5); it ignores the shape's F, S and T,
/// so the copy has a feed and a turning spindle: geometry must not fail on a feed
/// the roughing never uses.
fn scratch(st: &State) -> State {
    let mut scratch = *st;
    scratch.contour.clear();
    scratch.contour.no_comp = true;
    scratch.feed.per_min = scratch.feed.per_min.max(1);
    scratch.feed.per_rev = scratch.feed.per_rev.max(1);
    if scratch.spindle.dir == SpindleDir::Stop {
        scratch.spindle.dir = SpindleDir::Cw;
    }
    scratch.spindle.rpm = scratch.spindle.rpm.max(1);
    scratch
}

/// `w` in `plane` as a shape point: the abscissa in `z`, the ordinate in `x`
/// (a lathe's G18: Z and X; a mill's G17: X and Y).
fn in_plane(w: &crate::axis::Pos, plane: crate::canon::Plane) -> Pt {
    let (a, o) = plane.axes();
    Pt::new(w[o], w[a])
}

/// Appends the moves staged in `staged` to `profile` as segments in `plane`, the
/// first from `a`; returns how many.
fn keep_moves(
    staged: &CycleStage<'_>,
    mut a: Pt,
    plane: crate::canon::Plane,
    profile: &mut Profile,
) -> Result<usize, AlarmKind> {
    let mut n = 0;
    for c in staged.actions.iter() {
        let (kind, to) = match c.action {
            Action::Rapid(m) => (SegKind::Rapid, m.to.work),
            Action::Linear(m) => (SegKind::Line, m.to.work),
            Action::Arc(arc) => {
                if arc.plane != plane {
                    return Err(AlarmKind::CycleNotInZxPlane);
                }
                let center = in_plane(&arc.center.work, plane);
                (SegKind::Arc { center, cw: arc.cw }, arc.to.work)
            }
            Action::Thread(_) | Action::Tap(_) => {
                return Err(AlarmKind::ProfileForbiddenCode { what: "threading" });
            }
            _ => continue,
        };
        let b = in_plane(&to, plane);
        profile.segs.push(Seg { kind, a, b }).map_err(|_| AlarmKind::ProfileTooLong)?;
        a = b;
        n += 1;
    }
    Ok(n)
}

/// Reads and checks one block of a contour in the language of its program;
/// `None` for a block without words. A SINUMERIK contour's words may use the
/// calling level's variables (`src.vars`); its blocks are NC blocks only
/// (a label, a comment, DIAMON/DIAMOF are fine; DEF, a jump or a call is 10930).
/// Not inlined: the reader's scratch (words, pending assignments, call arguments,
/// a FANUC block: ~1.8 KB) stays out of the frame that runs the contour's blocks.
#[inline(never)]
fn contour_command(
    src: &crate::lang::siemens::call::ContourSource<'_>,
    raw: &crate::program::RawBlock<'_>,
    st: &State,
    cfg: &MachineConfig,
) -> Result<Option<crate::command::Command>, AlarmKind> {
    let prep = |cause| AlarmKind::SiemensCycle(CycleAlarm::ContourPreparation { cause });
    match src.program.language {
        crate::config::Language::Fanuc => {
            let mut block = Block::default();
            if let Read::Macro(_) = read_with(raw.text, raw.line, src.program.vars, src.program.fmt, &mut block)? {
                return Err(prep(10931));
            }
            if block.is_empty() {
                return Ok(None);
            }
            check(&block, st, cfg).map(Some)
        }
        crate::config::Language::Siemens => src.front.contour_command(raw, src.vars, st, cfg),
    }
}

/// The next block of a contour's text: a line in SINUMERIK, up to LF or `;` in
/// FANUC; `None` at the end of the text or, in SINUMERIK, at the next PROC.
fn next_contour_block<'t>(
    language: crate::config::Language,
    text: &'t [u8],
    cur: &mut Cursor,
) -> Option<crate::program::RawBlock<'t>> {
    match language {
        crate::config::Language::Fanuc => next_block(text, cur),
        crate::config::Language::Siemens => {
            let at = *cur;
            let raw = crate::program::lines::next_line(text, cur)?;
            if crate::program::lines::proc_name(raw.text).is_some() {
                *cur = at;
                return None;
            }
            Some(raw)
        }
    }
}

/// Whether a contour block ends its subprogram (M17/RET, M02/M30, M99).
fn ends_subprogram(cmd: &crate::command::Command) -> bool {
    matches!(cmd.flow, Some(crate::command::FlowWord::Return { .. }))
        || cmd.m.iter().any(|&(_, f)| matches!(f, MFunction::End | MFunction::EndRewind))
}

/// The checks of a stock-removal contour block (CYCLE95, seed 001 lines
/// 10820–10858), as the NCK alarm under 61606: G0–G3 only (10930); no G41/G42,
/// plane selection or frame (10931); the first block moving in the plane must
/// have its G0–G3 (15800).
fn check_contour_command(cmd: &crate::command::Command, first: bool) -> Result<(), AlarmKind> {
    use GCode::*;
    let prep = |cause| Err(AlarmKind::SiemensCycle(CycleAlarm::ContourPreparation { cause }));
    if let Some(m) = cmd.g.motion
        && !matches!(m, Rapid | Linear | ArcCw | ArcCcw)
    {
        return prep(10930);
    }
    if cmd.g.one_shot.is_some_and(|c| c != Dwell) || cmd.g.drilling.is_some_and(|d| d != DrillCancel) {
        return prep(10930);
    }
    if cmd.g.nose_comp.is_some_and(|c| c != NoseCompOff) || cmd.g.plane.is_some() || cmd.g.units.is_some() {
        return prep(10931);
    }
    if first && cmd.has_axes() && cmd.g.motion.is_none() {
        return prep(15800);
    }
    Ok(())
}

/// The contour of a stock-removal cycle (CYCLE95 `NPP`) read from `src`: its blocks
/// run on a scratch copy of `st` through `execute`, their moves kept as segments
/// in `profile` starting at the contour's first programmed point, which is
/// returned (the first block's move only gets there). Alarms 61606 with the
/// NCK cause: fewer than three moving blocks (10933), more elements than the
/// profile holds (10934), an arc over 180° or a chamfer/rounding on the first
/// block (10931), G41/G42 in force at the call (15800). Not inlined into the cycle
/// call that starts the expansion: its frame (the scratch state and the outbox the
/// contour's blocks run through) is on the stack only while the contour is read.
/// `plane` is where the points are read (CYCLE95: G18's Z/X; CYCLE72: the
/// active plane), `min` the fewest moving blocks (the start point included).
#[inline(never)]
#[allow(clippy::too_many_arguments)]
pub fn read_contour<E: Environment + ?Sized>(
    src: &crate::lang::siemens::call::ContourSource<'_>,
    plane: crate::canon::Plane,
    min: usize,
    st: &State,
    cfg: &MachineConfig,
    env: &E,
    execute: Execute,
    profile: &mut Profile,
) -> Result<Pt, AlarmKind> {
    let prep = |cause| AlarmKind::SiemensCycle(CycleAlarm::ContourPreparation { cause });
    if matches!(st.modal.nose_comp, GCode::NoseCompLeft | GCode::NoseCompRight) {
        return Err(prep(15800));
    }
    let mut scratch = scratch(st);
    profile.segs.clear();
    let (text, mut cur) = (src.program.text, src.start);
    let mut first: Option<Pt> = None;
    let mut blocks = 0;
    loop {
        let at = cur;
        let Some(raw) = next_contour_block(src.program.language, text, &mut cur) else {
            if src.end.is_some() {
                return Err(prep(10933));
            }
            break;
        };
        let last = src.end.is_some_and(|e| at.offset >= e.offset);
        let Some(cmd) = contour_command(src, &raw, &scratch, cfg)? else {
            if last {
                break;
            }
            continue;
        };
        if ends_subprogram(&cmd) {
            break;
        }
        check_contour_command(&cmd, first.is_none())?;
        let mut outbox = crate::stage::Outbox::new();
        let mut staged = CycleStage::new(raw.line, &mut outbox);
        let here = super::emit::work_pos(&scratch, cfg);
        let held = scratch.contour.is_holding();
        // On the scratch copy itself: an alarm or a block that leaves the contour
        // ends the reading, so nothing needs the state from before the block.
        let flow = execute(&cmd, &mut scratch, cfg, &EnvRef(env), &mut staged)?;
        if flow != Flow::Continue {
            return Err(prep(10930));
        }
        if last {
            crate::contour::flush(&mut scratch, &mut staged)?;
        }
        match first {
            None => {
                if scratch.contour.is_holding() {
                    return Err(prep(10931));
                }
                let w = super::emit::work_pos(&scratch, cfg);
                if staged.actions.iter().any(|c| c.action.endpoint().is_some()) || cmd.has_axes() {
                    first = Some(in_plane(&w, plane));
                    blocks += 1;
                }
            }
            Some(p0) => {
                let a = match profile.segs.last() {
                    Some(s) if held => s.b,
                    Some(_) => in_plane(&here, plane),
                    None => p0,
                };
                if keep_moves(&staged, a, plane, profile)
                    .map_err(|e| if e == AlarmKind::ProfileTooLong { prep(10934) } else { e })?
                    > 0
                {
                    blocks += 1;
                }
            }
        }
        if last {
            break;
        }
    }
    let Some(p0) = first else { return Err(prep(10933)) };
    if blocks < min {
        return Err(prep(10933));
    }
    for s in &profile.segs {
        if let SegKind::Arc { center, cw } = s.kind {
            let e = crate::geom::path::Elem::Arc {
                start: crate::geom::path::V2::new(s.a.z as f64, s.a.x as f64),
                end: crate::geom::path::V2::new(s.b.z as f64, s.b.x as f64),
                center: crate::geom::path::V2::new(center.z as f64, center.x as f64),
                ccw: !cw,
            };
            if e.length() > core::f64::consts::PI * e.radius() + 1.0 {
                return Err(prep(10931));
            }
        }
    }
    Ok(p0)
}

//! The contour layer between execution and the canonical stream: a bounded
//! look-ahead that holds a move back until the next move is known, so that the
//! corner between them can be shaped. Two stages, each holding at most one move
//! and the non-motion actions behind it:
//!
//! 1. chamfer and corner R (`,C`/`,R`, 2.23; [`corner`]): the programmed path with
//!    the corner blocks inserted;
//! 2. tool-nose radius compensation (G40/G41/G42, 2.18; [`comp`]): that path offset
//!    by the nose radius, with the corner types of the manual.
//!
//! The G90/G94 single cycles are compensated as a whole when they are planned
//! ([`cycle`]); the look-ahead treats them as a temporary cancel.
//!
//! The held actions live in the [`State`] (fixed arrays, no allocation), so they
//! follow the interpreter's rule that a failed block is undone: a block that
//! raises an alarm leaves the held moves exactly as they were ([`State::save`]
//! copies them only while a move is held). All geometry is
//! done in machine coordinates (the path the tool really follows) with f64
//! ([`crate::geom::path`]), results rounded to whole nanometres.

pub mod comp;
mod corner;
pub mod cycle;

pub use comp::{Comp, Side};
// The look-ahead's data is part of the modal state, below `check`.
pub use crate::modal::lookahead::{Buffer, Contour, Corner, HOLD, Marks};

use crate::alarm::AlarmKind;
use crate::axis::{Axis, Pos};
use crate::canon::{Action, Canon, Endpoint, Plane};
use crate::codes::GCode;
use crate::command::Command;
use crate::geom::path::V2;
use crate::modal::State;
use crate::stage::{Flow, STAGE, Staged};

/// The corner a block asks for, checked against 2.23 notes 1, 7 and 8: thread
/// blocks refuse `,C`/`,R` (alarm 0050), group 00 codes other than G04 may not share
/// their block (0051), blocks other than G01/G02/G03 ignore it.
pub fn corner_request(cmd: &Command, st: &State) -> Result<Option<Corner>, AlarmKind> {
    use GCode::*;
    let Some(corner) = cmd.corner else { return Ok(None) };
    if let Some(c) = cmd.g.one_shot
        && c != Dwell
    {
        return Err(if c == MultiThreadCycle {
            AlarmKind::ChamferInThread
        } else {
            AlarmKind::ChamferNoMove { what: "a group 00 code other than G04 in the block" }
        });
    }
    if cmd.g.one_shot.is_some() {
        return Ok(None);
    }
    Ok(match st.modal.motion {
        Thread | VariableLeadThread | ThreadCycle => return Err(AlarmKind::ChamferInThread),
        Linear | ArcCw | ArcCcw => Some(corner),
        _ => None,
    })
}

/// The rules for the block after a chamfered one (2.23 notes 2, 4 and 7): a G01,
/// G02 or G03 move in the same plane, with at most one G04 block before it.
/// Returns whether the block is that G04.
fn check_follower(cmd: &Command, st: &State) -> Result<bool, AlarmKind> {
    use GCode::*;
    if cmd.g.plane.is_some() {
        return Err(AlarmKind::ChamferPlaneChange);
    }
    match cmd.g.one_shot {
        Some(Dwell) if !cmd.has_axes() && cmd.g.motion.is_none() => {
            if st.contour.idle_blocks > 0 {
                return Err(AlarmKind::ChamferNoMove { what: "more than one block between" });
            }
            Ok(true)
        }
        Some(_) => Err(AlarmKind::ChamferNoMove { what: "a group 00 code" }),
        None if matches!(st.modal.motion, Linear | ArcCw | ArcCcw) => Ok(false),
        None => Err(AlarmKind::ChamferNoMove { what: "a code other than G01/G02/G03" }),
    }
}

/// What the block does to the compensation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct CompPlan {
    /// G40 in this block while compensating: the block's first move cancels.
    cancel: bool,
    /// A temporary cancel before the block's moves (G28, G30, G50, G52, G53, G51.2).
    pause: bool,
    /// A mill's D changed the radius while compensating: the held move ends on its
    /// normal with the old radius and the block's moves start up with the new one.
    restart: bool,
}

/// G40/G41/G42 of the block checked against 2.18.4 and put in force: a direct
/// G41↔G42 switch (3576), a T code (3577) or a plane change (0037) while
/// compensating are alarms.
fn plan_comp(cmd: &Command, st: &mut State) -> Result<CompPlan, AlarmKind> {
    use GCode::*;
    let was = st.contour.comp.side;
    if st.contour.no_comp {
        return Ok(CompPlan { cancel: false, pause: false, restart: false });
    }
    let now = match st.modal.nose_comp {
        NoseCompLeft => Some(Side::Left),
        NoseCompRight => Some(Side::Right),
        _ => None,
    };
    if let (Some(a), Some(b)) = (was, now) {
        if a != b {
            return Err(AlarmKind::NoseCompReversed);
        }
        if cmd.tool.is_some() {
            return Err(AlarmKind::ToolChangeInNoseComp);
        }
        if cmd.g.plane.is_some_and(|p| p != st.contour.comp.plane) {
            return Err(AlarmKind::NoseCompPlaneChange);
        }
    }
    if was.is_none()
        && let Some(side) = now
    {
        let comp = Comp {
            side: Some(side),
            radius: st.tool.nose_radius,
            tip: st.tool.tip,
            plane: st.modal.plane,
            engaged: false,
            centre: (0, 0),
            starting: false,
            off_path: false,
        };
        st.contour.comp = comp;
    }
    let restart = was.is_some() && now.is_some() && st.contour.comp.radius != st.tool.nose_radius;
    // G51.2 turns C to its phase: a move outside the plane, run uncompensated.
    let pause = matches!(
        cmd.g.one_shot,
        Some(ReferenceReturn | ReferenceReturnN | SetCoordinates | LocalFrame | MachineCoordinates)
    ) || cmd.g.polygon == Some(true);
    Ok(CompPlan { cancel: was.is_some() && now.is_none(), pause: was.is_some() && now.is_some() && pause, restart })
}

/// Whether [`after_block`] has nothing to do for the block: no corner asked for,
/// nothing held, compensation neither in force nor being started. Then
/// [`corner_request`] and [`plan_comp`] would return nothing and change nothing
/// (most blocks of a program without G41/G42 and chamfers).
#[inline]
fn idle(cmd: &Command, st: &State) -> bool {
    let starts_comp = !st.contour.no_comp && matches!(st.modal.nose_comp, GCode::NoseCompLeft | GCode::NoseCompRight);
    cmd.corner.is_none() && st.contour.comp.side.is_none() && !starts_comp && !st.contour.is_holding()
}

/// Passes the actions the block just staged in `out` through both stages. `from`
/// is the machine position before the block, `flow` what the block does next (a
/// stop or the end of the program empties the look-ahead). Actions after a
/// cycle's place (`out.split`) come after everything held; the cycle itself is a
/// temporary cancel (G90/G94 offset their own moves, [`cycle`]) and the next move
/// starts the offset up again. Always inlined: a block without work for the stages
/// pays only the idle check (left to LLVM, it became a call from `exec::full` once
/// the cold code around it shrank: 53 instructions more per M3 S block).
#[inline(always)]
pub fn after_block(
    cmd: &Command,
    st: &mut State,
    cfg: &crate::config::MachineConfig,
    from: Pos,
    flow: Flow,
    out: &mut Staged<'_>,
) -> Result<(), AlarmKind> {
    if idle(cmd, st) {
        return Ok(());
    }
    through_stages(cmd, st, cfg, from, flow, out)
}

/// [`after_block`] for a block the stages have work for.
#[inline(never)]
fn through_stages(
    cmd: &Command,
    st: &mut State,
    cfg: &crate::config::MachineConfig,
    from: Pos,
    flow: Flow,
    out: &mut Staged<'_>,
) -> Result<(), AlarmKind> {
    let request = corner_request(cmd, st)?;
    let plan = plan_comp(cmd, st)?;
    let comp_on = st.contour.comp.side.is_some();
    if !st.contour.is_holding() && request.is_none() && !comp_on {
        return Ok(());
    }
    let dwell_between = match st.contour.corner {
        Some(_) => check_follower(cmd, st)?,
        None => false,
    };
    let mut acts: heapless::Vec<Canon, STAGE> = heapless::Vec::new();
    while let Some(c) = out.actions.pop_front() {
        acts.push(c).map_err(|_| AlarmKind::Overflow)?;
    }
    if plan.pause || plan.restart {
        // The held moves end before the block's own actions (the G28 move …).
        flush(st, out)?;
        st.contour.comp.radius = st.tool.nose_radius;
    }
    let split = out.split.unwrap_or(acts.len());
    let last_move = acts[..split].iter().rposition(|c| c.action.endpoint().is_some());
    let waited = st.contour.corner.is_some();
    let mut moved = false;
    let mut cancel = plan.cancel;
    let mut pos = from;
    for (i, c) in acts.iter().enumerate() {
        if i == split {
            flush(st, out)?;
            out.split = Some(out.actions.len());
        }
        let Some(end) = c.action.endpoint().map(|e| e.machine) else {
            shape_aside(st, *c, out)?;
            continue;
        };
        moved = true;
        let mut start = pos;
        if st.contour.shape.is_holding() {
            start = join(st, *c, pos, out)?;
        }
        if i >= split || plan.pause {
            put(out, *c)?;
        } else if cancel {
            cancel = false;
            let ct = &mut st.contour;
            // A lathe's moves all count as in the plane (its plunges are a mill's).
            if !crate::MILL || comp::in_plane_move(&c.action, start, ct.comp.plane) {
                comp::cancel_with(&mut ct.offset, &mut ct.comp, *c, start, out)?;
            } else {
                // G40 with a move along the normal only (a retract): the held move
                // ends on its normal and the retract is made there; the next move
                // leaves the offset path.
                comp::end_here(&mut ct.offset, &mut ct.comp, out)?;
                if !comp::plunge(&mut ct.offset, &ct.comp, *c, start, out)? {
                    return Err(AlarmKind::NoseCompGouge);
                }
            }
            st.contour.comp = Comp::default();
        } else {
            match request.filter(|_| Some(i) == last_move) {
                Some(corner) if shapeable(&c.action) => {
                    st.contour.shape.hold(*c, start);
                    st.contour.corner = Some(corner);
                    st.contour.idle_blocks = 0;
                }
                _ => to_offset(st, *c, start, out)?,
            }
        }
        pos = end;
    }
    if split == acts.len() && out.split.is_some() {
        flush(st, out)?;
        out.split = Some(out.actions.len());
    }
    if cancel {
        // G40 without a move: the held move ends on its normal.
        comp::end_here(&mut st.contour.offset, &mut st.contour.comp, out)?;
        st.contour.comp = Comp::default();
    }
    if matches!(flow, Flow::Stop | Flow::End) {
        flush(st, out)?;
        if flow == Flow::End {
            // M02/M30 cancel the compensation (3.1.4).
            st.contour.comp = Comp::default();
        }
    }
    finish_block(st, waited, moved, dwell_between)?;
    if st.polar.is_none() {
        // The shaped and offset points must respect the soft limits too.
        for c in out.actions.iter() {
            if let Some(e) = c.action.endpoint() {
                crate::moves::motion::check_limits(&e.machine, cfg)?;
            }
        }
    }
    Ok(())
}

/// A non-motion action: behind stage 1's held move, else behind stage 2's, else out.
fn shape_aside(st: &mut State, c: Canon, out: &mut Staged<'_>) -> Result<(), AlarmKind> {
    if st.contour.shape.is_holding() {
        st.contour.shape.push(c)
    } else if st.contour.offset.is_holding() {
        st.contour.offset.push(c)
    } else {
        put(out, c)
    }
}

/// Stage 2: a move of the programmed path (from `start`) into the compensation, or
/// straight out without it.
fn to_offset(st: &mut State, c: Canon, start: Pos, out: &mut Staged<'_>) -> Result<(), AlarmKind> {
    let ct = &mut st.contour;
    if ct.comp.side.is_none() {
        return put(out, c);
    }
    if c.action.endpoint().is_none() {
        return if ct.offset.is_holding() { ct.offset.push(c) } else { put(out, c) };
    }
    if crate::MILL
        && !comp::in_plane_move(&c.action, start, ct.comp.plane)
        && comp::plunge(&mut ct.offset, &ct.comp, c, start, out)?
    {
        return Ok(());
    }
    if ct.comp.engaged {
        comp::advance(&mut ct.offset, &mut ct.comp, c, start, out)
    } else {
        comp::start_up(&mut ct.offset, &mut ct.comp, c, start)
    }
}

/// After the block: a corner still waiting from before means the block had no
/// move; only one G04 block may stand there (2.23 note 2).
fn finish_block(st: &mut State, waited: bool, moved: bool, dwell_between: bool) -> Result<(), AlarmKind> {
    if waited && !moved {
        if !dwell_between {
            return Err(AlarmKind::ChamferNoMove { what: "a block without a G01/G02/G03 move" });
        }
        st.contour.idle_blocks += 1;
    }
    Ok(())
}

/// Whether a corner can be shaped at the end of this action (a feed move).
fn shapeable(a: &Action) -> bool {
    matches!(a, Action::Linear(_) | Action::Arc(_))
}

/// Emits everything held: stage 1 unchanged (nothing may be waiting for a corner,
/// alarm 0051), stage 2 ending on the normal of its move (a temporary cancel: the
/// next move starts the offset up again).
pub fn flush(st: &mut State, out: &mut Staged<'_>) -> Result<(), AlarmKind> {
    if st.contour.corner.is_some() {
        return Err(AlarmKind::ChamferNoMove { what: "a block without a G01/G02/G03 move" });
    }
    let start = st.contour.shape.start;
    let (held, after) = st.contour.shape.take();
    if let Some(c) = held {
        to_offset(st, c, start, out)?;
    }
    for c in after {
        to_offset(st, c.plain(), start, out)?;
    }
    comp::end_here(&mut st.contour.offset, &mut st.contour.comp, out)
}

/// The look-ahead when a block raised an alarm (the block undone, the held moves
/// as before it). The moves held back belong to earlier, good blocks, so the
/// machine runs them before it stops, the last one ending on its normal as
/// compensation does before a block it cannot look past (2.18.3; a `,C`/`,R`
/// waiting for this block is left out: its corner needs the faulty block). If a
/// held move is itself the fault (`faulty`: the line of a move whose offset runs
/// against it, 2.18.4 criterion 1), the machine stops before that move, as FANUC
/// stops before the block where the nose would cut in; what was held behind it is
/// dropped. Compensation stays in force (the next move starts up again).
pub fn stop_on_alarm(st: &mut State, faulty: Option<u32>, out: &mut Staged<'_>) {
    if !st.contour.is_holding() {
        return;
    }
    let line_of = |b: &Buffer| b.held.map(|c| c.line);
    let at_fault = |b: &Buffer| faulty.is_some() && line_of(b) == faulty;
    if at_fault(&st.contour.offset) {
        st.contour.offset = Buffer::default();
    } else {
        st.contour.corner = None;
        let before = st.contour;
        let mark = out.actions.len();
        let shape_ok = !at_fault(&st.contour.shape);
        if !shape_ok || flush(st, out).is_err() {
            st.contour = before;
            while out.actions.len() > mark {
                out.actions.pop_back();
            }
            // Only stage 2's move: stage 1's (or the corner to it) is the fault.
            if comp::end_here(&mut st.contour.offset, &mut st.contour.comp, out).is_err() {
                while out.actions.len() > mark {
                    out.actions.pop_back();
                }
            }
        }
    }
    st.contour.shape = Buffer::default();
    st.contour.offset = Buffer::default();
    st.contour.corner = None;
    st.contour.idle_blocks = 0;
    st.contour.comp.engaged = false;
}

/// Stage 1's held move meets `next` (starting at `from`): shapes the corner, passes
/// the held actions on to stage 2 and returns where `next` now starts.
fn join(st: &mut State, next: Canon, from: Pos, out: &mut Staged<'_>) -> Result<Pos, AlarmKind> {
    let start = st.contour.shape.start;
    let corner = st.contour.corner.take();
    let (held, rest) = st.contour.shape.take();
    let Some(first) = held else { return Ok(from) };
    let plane = st.modal.plane;
    let shaped = match corner {
        Some(corner) => corner::shape(corner, plane, start, first, next)?,
        None => corner::Shaped { trimmed: Some(first), insert: None, next_start: from },
    };
    let mut at = start;
    for c in [shaped.trimmed, shaped.insert].into_iter().flatten() {
        to_offset(st, c, at, out)?;
        at = c.action.endpoint().map_or(at, |e| e.machine);
    }
    for c in rest {
        to_offset(st, c.plain(), at, out)?;
    }
    Ok(shaped.next_start)
}

/// Queues an action as it is (with its own line).
fn put(out: &mut Staged<'_>, c: Canon) -> Result<(), AlarmKind> {
    out.actions.push_back(c).map_err(|_| AlarmKind::Overflow)
}

/// The plane coordinates of a machine position.
#[inline(never)]
pub(crate) fn in_plane(p: &Pos, plane: Plane) -> V2 {
    let (a, b) = plane.axes();
    V2::new(p[a] as f64, p[b] as f64)
}

/// `ep` with its plane coordinates (machine) replaced by `p`, the work coordinates
/// shifted alike.
#[inline(never)]
pub(crate) fn moved_to(ep: Endpoint, plane: Plane, p: V2) -> Endpoint {
    let (a, b) = plane.axes();
    let (pa, pb) = p.round();
    let mut out = ep;
    for (axis, v) in [(a, pa), (b, pb)] {
        // Saturating: a point thrown far off by degenerate geometry must not panic
        // (it then fails the soft limits downstream instead).
        let d = v.saturating_sub(ep.machine[axis]);
        out.machine[axis] = v;
        out.work[axis] = ep.work[axis].saturating_add(d);
    }
    out
}

/// Whether `a` and `b` differ in an axis outside `plane`.
pub(crate) fn leaves_plane(a: &Pos, b: &Pos, plane: Plane) -> bool {
    Axis::ALL.into_iter().any(|x| !plane.contains(x) && a[x] != b[x])
}

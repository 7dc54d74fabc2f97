//! The contour layer between execution and the canonical stream: a bounded
//! look-ahead that holds a block's last move back until the next move is known, so
//! that the corner between them can be shaped — a chamfer or corner R inserted
//! (`,C`/`,R`, 2.23).
//!
//! The held actions live in the [`State`] (fixed arrays, no allocation), so they
//! follow the interpreter's rule that a block runs on a copy of the state: a block
//! that raises an alarm leaves the held move exactly as it was. All geometry is done
//! in machine coordinates (the path the tool really follows) with f64
//! ([`crate::geom::path`]), results rounded to whole nanometres.

mod corner;

use crate::alarm::AlarmKind;
use crate::axis::{Axis, Pos};
use crate::canon::{Action, Canon, Endpoint, Plane};
use crate::check::Command;
use crate::codes::GCode;
use crate::exec::{STAGE, Staged, State};
use crate::geom::path::V2;

/// Most actions held back behind the move: what the blocks after it produced
/// before the next move (a G04 between a chamfered block and its follower, M codes …).
pub const HOLD: usize = 6;

/// What `,C` or `,R` asks for at the end of a block's move (2.23).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Corner {
    /// `,C`: a straight chamfer from the point this far (nm, straight line) before
    /// the imaginary corner to the point this far after it.
    Chamfer(i64),
    /// `,R`: a corner arc of this radius (nm) tangent to both moves.
    Round(i64),
}

/// A non-motion action waiting behind the held move, kept small (the state is
/// copied for every block).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
enum Aside {
    Dwell { ms: u32 },
    Spindle(crate::canon::SpindleCommand),
    Tool { tool: u16, offset: u16 },
    Aux { m: u16 },
    Stop { optional: bool },
    End { rewind: bool },
}

impl Aside {
    fn of(a: &Action) -> Option<Aside> {
        Some(match *a {
            Action::Dwell { ms } => Aside::Dwell { ms },
            Action::Spindle(s) => Aside::Spindle(s),
            Action::Tool { tool, offset } => Aside::Tool { tool, offset },
            Action::Aux { m } => Aside::Aux { m },
            Action::Stop { optional } => Aside::Stop { optional },
            Action::End { rewind } => Aside::End { rewind },
            _ => return None,
        })
    }

    fn action(self) -> Action {
        match self {
            Aside::Dwell { ms } => Action::Dwell { ms },
            Aside::Spindle(s) => Action::Spindle(s),
            Aside::Tool { tool, offset } => Action::Tool { tool, offset },
            Aside::Aux { m } => Action::Aux { m },
            Aside::Stop { optional } => Action::Stop { optional },
            Aside::End { rewind } => Action::End { rewind },
        }
    }
}

/// The look-ahead buffer: a held move, the actions after it, and what is to be done
/// at its end.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Contour {
    /// The held move.
    held: Option<Canon>,
    /// The actions after it (with their lines), in order.
    after: [Option<(u32, Aside)>; HOLD],
    /// Machine position where the held move starts.
    start: Pos,
    /// The corner requested at the held move's end.
    corner: Option<Corner>,
    /// Blocks without motion read since the held move (2.23 note 2 allows one G04).
    idle_blocks: u8,
}

// Every field compares exactly (integers only).
impl Eq for Contour {}

impl Default for Contour {
    fn default() -> Self {
        Contour { held: None, after: [None; HOLD], start: Pos::ZERO, corner: None, idle_blocks: 0 }
    }
}

impl Contour {
    /// Whether a move is held back.
    pub fn is_holding(&self) -> bool {
        self.held.is_some()
    }

    /// The corner the held move waits for, if any.
    pub fn pending_corner(&self) -> Option<Corner> {
        self.corner
    }

    /// Drops everything held (rewind, reset).
    pub fn clear(&mut self) {
        *self = Contour::default();
    }

    fn hold(&mut self, c: Canon, start: Pos, corner: Option<Corner>) {
        *self = Contour { held: Some(c), start, corner, ..Contour::default() };
    }

    /// Appends a non-motion action behind the held move.
    fn push(&mut self, c: Canon) -> Result<(), AlarmKind> {
        let aside = Aside::of(&c.action).ok_or(AlarmKind::ContourBufferFull)?;
        let slot = self.after.iter_mut().find(|s| s.is_none()).ok_or(AlarmKind::ContourBufferFull)?;
        *slot = Some((c.line, aside));
        Ok(())
    }

    /// Takes the held move and the actions after it.
    fn take(&mut self) -> (Option<Canon>, impl Iterator<Item = Canon>) {
        let (held, after) = (self.held, self.after);
        self.clear();
        (held, after.into_iter().flatten().map(|(line, a)| Canon { line, action: a.action() }))
    }
}

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

/// Passes the actions the block just staged in `out` through the look-ahead: the
/// held move meets the block's first move (its corner is shaped), the block's last
/// move is held if it asks for a corner. `from` is the machine position before the
/// block. Actions after a cycle's place (`out.split`) come after the held ones.
pub fn after_block(cmd: &Command, st: &mut State, from: Pos, out: &mut Staged<'_>) -> Result<(), AlarmKind> {
    let request = corner_request(cmd, st)?;
    if !st.contour.is_holding() && request.is_none() {
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
    let split = out.split.unwrap_or(acts.len());
    let last_move = acts[..split].iter().rposition(|c| c.action.endpoint().is_some());
    let plane = st.modal.plane;
    let waited = st.contour.corner.is_some();
    let mut moved = false;
    let mut pos = from;
    for (i, c) in acts.iter().enumerate() {
        if i == split {
            flush(st, out)?;
            out.split = Some(out.actions.len());
        }
        let Some(end) = c.action.endpoint().map(|e| e.machine) else {
            if st.contour.is_holding() {
                st.contour.push(*c)?
            } else {
                put(out, *c)?
            }
            continue;
        };
        moved = true;
        let mut start = pos;
        if st.contour.is_holding() {
            start = join(st, *c, pos, plane, out)?;
        }
        match request.filter(|_| Some(i) == last_move) {
            Some(corner) if shapeable(&c.action) => st.contour.hold(*c, start, Some(corner)),
            _ => put(out, *c)?,
        }
        pos = end;
    }
    if split == acts.len() && out.split.is_some() {
        flush(st, out)?;
        out.split = Some(out.actions.len());
    }
    finish_block(st, waited, moved, dwell_between)
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

/// Emits everything held unchanged (nothing may be waiting for a corner).
pub fn flush(st: &mut State, out: &mut Staged<'_>) -> Result<(), AlarmKind> {
    if st.contour.corner.is_some() {
        return Err(AlarmKind::ChamferNoMove { what: "a block without a G01/G02/G03 move" });
    }
    let (held, after) = st.contour.take();
    for c in held.into_iter().chain(after) {
        put(out, c)?;
    }
    Ok(())
}

/// The held move meets `next` (starting at `from`): shapes the corner, emits the
/// held actions and returns where `next` now starts.
fn join(st: &mut State, next: Canon, from: Pos, plane: Plane, out: &mut Staged<'_>) -> Result<Pos, AlarmKind> {
    let start = st.contour.start;
    let corner = st.contour.corner;
    let (held, rest) = st.contour.take();
    let Some(first) = held else { return Ok(from) };
    let Some(corner) = corner else {
        put(out, first)?;
        for c in rest {
            put(out, c)?;
        }
        return Ok(from);
    };
    let shaped = corner::shape(corner, plane, start, first, next)?;
    for c in [shaped.trimmed, shaped.insert].into_iter().flatten() {
        put(out, c)?;
    }
    for c in rest {
        put(out, c)?;
    }
    Ok(shaped.next_start)
}

/// Queues an action as it is (with its own line).
fn put(out: &mut Staged<'_>, c: Canon) -> Result<(), AlarmKind> {
    out.actions.push_back(c).map_err(|_| AlarmKind::Overflow)
}

/// The plane coordinates of a machine position.
pub(crate) fn in_plane(p: &Pos, plane: Plane) -> V2 {
    let (a, b) = plane.axes();
    V2::new(p[a] as f64, p[b] as f64)
}

/// `ep` with its plane coordinates (machine) replaced by `p`, the work coordinates
/// shifted alike.
pub(crate) fn moved_to(ep: Endpoint, plane: Plane, p: V2) -> Endpoint {
    let (a, b) = plane.axes();
    let (pa, pb) = p.round();
    let mut out = ep;
    for (axis, v) in [(a, pa), (b, pb)] {
        let d = v - ep.machine[axis];
        out.machine[axis] = v;
        out.work[axis] = ep.work[axis] + d;
    }
    out
}

/// Whether `a` and `b` differ in an axis outside `plane`.
pub(crate) fn leaves_plane(a: &Pos, b: &Pos, plane: Plane) -> bool {
    Axis::ALL.into_iter().any(|x| !plane.contains(x) && a[x] != b[x])
}

//! Execution: a checked [`Command`] applied to the [`State`], emitting canonical
//! actions in the order the control performs them. Runs on the state in place;
//! the caller undoes the block ([`State::save`], [`State::restore`]) unless the
//! whole block succeeded.

mod coords;
pub(crate) mod motion;
pub mod polar;
mod polygon;
mod spindle;
mod state;
pub mod stroke;

pub use spindle::spindle_speed;
pub use state::{
    CycleMemory, FeedMemory, Frames, HoleMemory, Modal, RigidTap, Saved, SingleMemory, SpindleState, State, ToolState,
};

use crate::alarm::AlarmKind;
use crate::axis::Pos;
use crate::canon::{Action, Canon, SpindleDir};
use crate::check::{Command, FlowWord};
use crate::codes::{GCode, MFunction};
use crate::config::{MTiming, MachineConfig, Param, ToolOffset};
use crate::cycles::{self, Expansion};
use crate::env::Environment;

/// Most actions one block produces.
pub const STAGE: usize = 16;

/// The queue a block's actions are staged in. The interpreter runs a block only
/// when its outbox is empty and empties it again if the block fails, so staged
/// actions reach the sink only when the whole block succeeded.
pub type Outbox = heapless::Deque<Canon, STAGE>;

/// Actions of the block being executed, staged in the (empty) outbox, and what a
/// cycle block hands to the interpreter.
#[derive(Debug)]
pub struct Staged<'a> {
    line: u32,
    /// The staged actions, in order.
    pub actions: &'a mut Outbox,
    /// The program the block is in: G70–G73 read their ns–nf blocks from it.
    pub program: crate::program::ProgramText<'a>,
    /// Where a cycle started by this block goes (the interpreter's expansion slot);
    /// `None` where no cycle may start (inside a cycle's own blocks).
    slot: Option<&'a mut Option<Expansion>>,
    /// Index in `actions` where the cycle's moves belong: actions staged after it
    /// (M05, M30 …) are delivered after the cycle.
    pub split: Option<usize>,
    /// Parameters the block sets (G71 U(Δd) → 5147 …), written only if it succeeds.
    pub params: heapless::Vec<(Param, i64), 8>,
    /// Where the program goes on after the block if not with the next block: after
    /// the nf block of G71–G73 (the shape's blocks are not executed).
    pub resume: Option<crate::program::Cursor>,
    /// Line of a held move that nose compensation found faulty (its offset runs
    /// against it, 3605) while the block ran: on the alarm the machine stops before
    /// that move instead of after it ([`crate::contour::stop_on_alarm`]).
    pub faulty_move: Option<u32>,
}

impl<'a> Staged<'a> {
    /// Stages the actions of the block on `line` in `outbox` (no cycle may start).
    pub fn new(line: u32, outbox: &'a mut Outbox) -> Self {
        Staged {
            line,
            actions: outbox,
            program: crate::program::ProgramText::NONE,
            slot: None,
            split: None,
            params: heapless::Vec::new(),
            resume: None,
            faulty_move: None,
        }
    }

    /// A stage for a block of `program` that may start a cycle into `slot`.
    pub fn in_program(
        line: u32,
        outbox: &'a mut Outbox,
        program: crate::program::ProgramText<'a>,
        slot: &'a mut Option<Expansion>,
    ) -> Self {
        Staged { program, slot: Some(slot), ..Staged::new(line, outbox) }
    }

    /// The interpreter's expansion slot, for the block's cycle to be built in place
    /// (an expansion is ~5 KB: built here it is never moved through the frames of
    /// its callers, which are on the stack under the shape's blocks). The cycle's
    /// moves come after the actions staged so far.
    pub fn cycle_slot(&mut self) -> Result<&mut Option<Expansion>, AlarmKind> {
        let slot = self.slot.as_deref_mut().ok_or(AlarmKind::ProfileForbiddenCode { what: "a cycle" })?;
        self.split = Some(self.actions.len());
        Ok(slot)
    }

    /// Stages one action.
    pub fn emit(&mut self, action: Action) -> Result<(), AlarmKind> {
        self.actions.push_back(Canon { line: self.line, action }).map_err(|_| AlarmKind::Overflow)
    }
}

/// What the interpreter does after a block.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Flow {
    /// Go on with the next block.
    Continue,
    /// M00, or M01 with the optional-stop switch on: wait for cycle start.
    Stop,
    /// M02/M30.
    End,
    /// M98: call subprogram `program` `repeats` times, after the block's other codes.
    Call {
        /// O number.
        program: u32,
        /// Repetitions.
        repeats: u16,
    },
    /// M99: return to the caller (at sequence `seq`), or restart a main program.
    Return {
        /// Sequence number in the caller.
        seq: Option<u32>,
    },
    /// M91/M92 whose input condition held: go to sequence `seq`.
    Jump {
        /// Sequence number in this program.
        seq: u32,
    },
}

/// Executes `cmd` on `st`, staging the actions in `out`.
pub fn execute(
    cmd: &Command,
    st: &mut State,
    cfg: &MachineConfig,
    env: &dyn Environment,
    out: &mut Staged<'_>,
) -> Result<Flow, AlarmKind> {
    polar::check_codes(cmd, st)?;
    polygon::check_block(cmd, st)?;
    let from = st.polar.map_or(st.pos, |p| p.virtual_pos());
    let chained = cycles::before_block(cmd, st)?;
    apply_modal(cmd, st);
    stroke::apply(cmd, st, cfg)?;
    spindle::before_motion(cmd, st, cfg, out)?;
    cycles::after_spindle(cmd, st, out)?;
    tool_change(cmd, st, cfg, out)?;
    aux(cmd, MTiming::Before, out)?;
    match cmd.g.one_shot {
        Some(GCode::Dwell) => out.emit(Action::Dwell { ms: cmd.dwell_ms.unwrap_or(0) })?,
        Some(GCode::SetCoordinates) => coords::set_coordinates(cmd, st, cfg)?,
        Some(GCode::LocalFrame) => coords::local_frame(cmd, st),
        Some(GCode::MachineCoordinates) => coords::machine_move(cmd, st, cfg, out)?,
        Some(GCode::ReferenceReturn | GCode::ReferenceReturnN) => coords::reference_return(cmd, st, cfg, env, out)?,
        _ if cmd.g.stroke.is_some() => {}
        _ if cmd.g.polygon.is_some() => polygon::switch(cmd, st, cfg, out)?,
        _ if polar::mode_change(cmd, st, cfg)? => {}
        _ if st.polar.is_some() => polar::execute(cmd, st, cfg, out)?,
        _ => {
            let mut ctx = cycles::Ctx { cfg, env, out };
            if !cycles::execute(cmd, st, &mut ctx, chained)? {
                motion::execute(cmd, st, cfg, ctx.out)?;
            }
        }
    }
    // 2.14 item 5: G61/G64 take effect from the next block.
    if let Some(e) = cmd.g.exact_stop_mode {
        st.modal.exact_stop_mode = e;
    }
    aux(cmd, MTiming::After, out)?;
    spindle::after_motion(cmd, st, out)?;
    if cmd.m.iter().any(|&(_, f)| matches!(f, MFunction::End | MFunction::EndRewind)) {
        // M02/M30 end polygon turning with the program.
        polygon::stop(st, out)?;
    }
    let flow = program_flow(cmd, cfg, env, out)?;
    if st.polar.is_none() {
        stroke::check_actions(st, from, out.actions.iter())?;
    }
    crate::contour::after_block(cmd, st, cfg, from, flow, out)?;
    if st.polar.is_some() {
        cycles::polar_block(st, cfg, out)?;
    }
    Ok(flow)
}

/// Modal codes that govern how the rest of the block is read.
fn apply_modal(cmd: &Command, st: &mut State) {
    let g = &cmd.g;
    let m = &mut st.modal;
    if let Some(u) = g.units {
        m.units = u;
    }
    if let Some(f) = g.feed_mode {
        m.feed_mode = f;
    }
    if let Some(f) = cmd.feed {
        st.feed.set(m.feed_mode, f);
    }
    if let Some(p) = g.plane {
        m.plane = p;
    }
    if let Some(i) = g.incremental {
        m.incremental = i;
    }
    if let Some(n) = g.nose_comp {
        m.nose_comp = n;
    }
    if let Some(w) = g.work_frame {
        m.work_frame = w;
    }
    if let Some(d) = g.drilling {
        m.drilling = d;
    }
    if let Some(r) = g.return_to_r {
        m.return_to_r = r;
    }
    if let Some(mo) = g.motion {
        m.motion = mo;
    }
}

/// T: index the turret and put the offset in force; the axes pick the offset up
/// with their next move.
fn tool_change(cmd: &Command, st: &mut State, cfg: &MachineConfig, out: &mut Staged<'_>) -> Result<(), AlarmKind> {
    let Some((tool, offset_number)) = cmd.tool else { return Ok(()) };
    let row = match offset_number {
        0 => ToolOffset::default(),
        n => *cfg.tools.get(n).ok_or(AlarmKind::IllegalOffsetNumber { number: n })?,
    };
    st.tool = ToolState {
        tool: if tool == 0 { st.tool.tool } else { tool },
        offset_number,
        offset: Pos::xz(row.total_x(), row.total_z()),
        nose_radius: row.radius,
        tip: row.tip,
    };
    out.emit(Action::Tool { tool, offset: offset_number })
}

/// Machine outputs switched by M codes at `timing`.
fn aux(cmd: &Command, timing: MTiming, out: &mut Staged<'_>) -> Result<(), AlarmKind> {
    for &(m, f) in &cmd.m {
        if f == MFunction::Aux(timing) {
            out.emit(Action::Aux { m })?;
        }
    }
    Ok(())
}

/// M00, M01, M02, M30, M98, M99, M91, M92 after the block's other codes (3.1.3–3.1.7:
/// "当前程序段的其它代码执行完成后").
fn program_flow(
    cmd: &Command,
    cfg: &MachineConfig,
    env: &dyn Environment,
    out: &mut Staged<'_>,
) -> Result<Flow, AlarmKind> {
    for &(_, f) in &cmd.m {
        match f {
            MFunction::Stop => {
                out.emit(Action::Stop { optional: false })?;
                return Ok(Flow::Stop);
            }
            MFunction::OptionalStop if env.optional_stop() => {
                out.emit(Action::Stop { optional: true })?;
                return Ok(Flow::Stop);
            }
            MFunction::End | MFunction::EndRewind => {
                out.emit(Action::End { rewind: f == MFunction::EndRewind })?;
                return Ok(Flow::End);
            }
            _ => {}
        }
    }
    Ok(match cmd.flow {
        None => Flow::Continue,
        Some(FlowWord::Call { program, repeats }) => Flow::Call { program, repeats },
        Some(FlowWord::Return { seq }) => Flow::Return { seq },
        Some(FlowWord::Jump { seq, high }) => {
            let input = cfg.jump_input;
            let level = env.input(input).ok_or(AlarmKind::InputNotAvailable { input })?;
            if level == high { Flow::Jump { seq } } else { Flow::Continue }
        }
    })
}

/// Direction a spindle M code commands, if it is one.
pub(crate) fn spindle_dir(f: MFunction) -> Option<SpindleDir> {
    match f {
        MFunction::SpindleCw => Some(SpindleDir::Cw),
        MFunction::SpindleCcw => Some(SpindleDir::Ccw),
        MFunction::SpindleStop => Some(SpindleDir::Stop),
        _ => None,
    }
}

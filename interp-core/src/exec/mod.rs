//! Execution: a checked [`Command`] applied to the [`State`], emitting canonical
//! actions in the order the control performs them. Runs on the state in place;
//! the caller undoes the block ([`State::save`], [`State::restore`]) unless the
//! whole block succeeded. The top of the execution layers: it dispatches to the
//! cycles, the contour look-ahead and the move helpers ([`crate::moves`]) below it.

mod coords;
mod mill;
mod polygon;

use crate::alarm::AlarmKind;
use crate::axis::Pos;
use crate::canon::Action;
use crate::codes::{GCode, MFunction};
use crate::command::{Command, FlowWord};
use crate::config::{MTiming, MachineConfig, ToolOffset};
use crate::cycles::{self, CycleStage};
use crate::env::Environment;
use crate::modal::{State, ToolState};
use crate::moves::{motion, polar, spindle, stroke};
use crate::stage::{Flow, Staged};

/// Executes `cmd` on `st`, staging the actions in `out`.
pub fn execute(
    cmd: &Command,
    st: &mut State,
    cfg: &MachineConfig,
    env: &dyn Environment,
    out: &mut CycleStage<'_>,
) -> Result<Flow, AlarmKind> {
    if is_plain(cmd, st) {
        return plain(cmd, st, cfg, env, out);
    }
    polar::check_codes(cmd, st)?;
    polygon::check_block(cmd, st)?;
    let from = st.polar.map_or(st.pos, |p| p.virtual_pos());
    let chained = cycles::before_block(cmd, st, cfg)?;
    apply_modal(cmd, st);
    if crate::MILL && cmd.g.mill {
        return mill_block(cmd, st, cfg, env, out, from, chained);
    }
    full(cmd, st, cfg, env, out, from, chained)
}

/// [`execute`] of a machining centre's block that needs its paths (see
/// [`crate::command::GSet::mill`]): tool length, D, the transformations, T/M06,
/// G10, G29 around the full way. Never inlined: the adapted copy of the block stays
/// out of [`execute`]'s frame.
#[inline(never)]
fn mill_block(
    cmd: &Command,
    st: &mut State,
    cfg: &MachineConfig,
    env: &dyn Environment,
    out: &mut CycleStage<'_>,
    from: Pos,
    chained: bool,
) -> Result<Flow, AlarmKind> {
    let mut adapted = cmd.clone();
    let prepared = mill::prepare(cmd, st, cfg, &mut adapted)?;
    let (motion, side) = (st.modal.motion, st.modal.nose_comp);
    if prepared.mirrored {
        // A mirror image turns G02 into G03 and G41 into G42 (FANUC); the modal
        // codes stay as programmed.
        st.modal.motion = match motion {
            GCode::ArcCw => GCode::ArcCcw,
            GCode::ArcCcw => GCode::ArcCw,
            m => m,
        };
        st.modal.nose_comp = match side {
            GCode::NoseCompLeft => GCode::NoseCompRight,
            GCode::NoseCompRight => GCode::NoseCompLeft,
            c => c,
        };
    }
    let done = full(&adapted, st, cfg, env, out, from, chained);
    st.modal.motion = motion;
    st.modal.nose_comp = side;
    let flow = done?;
    mill::after(st, cfg, &prepared);
    Ok(flow)
}

/// [`execute`] after the block's modal codes, for every block that does not take
/// the short way.
#[allow(clippy::too_many_arguments)]
fn full(
    cmd: &Command,
    st: &mut State,
    cfg: &MachineConfig,
    env: &dyn Environment,
    out: &mut CycleStage<'_>,
    from: Pos,
    chained: bool,
) -> Result<Flow, AlarmKind> {
    stroke::apply(cmd, st, cfg)?;
    spindle::before_motion(cmd, st, cfg, out)?;
    cycles::after_spindle(cmd, st, out)?;
    tool_change(cmd, st, cfg, out)?;
    aux(cmd, MTiming::Before, out)?;
    match cmd.g.one_shot {
        Some(GCode::Dwell) => out.emit(Action::Dwell { ms: cmd.dwell_ms.unwrap_or(0) })?,
        Some(GCode::SetCoordinates) => coords::set_coordinates(cmd, st, cfg)?,
        Some(GCode::LocalFrame) => coords::local_frame(cmd, st, cfg)?,
        Some(GCode::MachineCoordinates) => coords::machine_move(cmd, st, cfg, out)?,
        Some(GCode::ReferenceReturn | GCode::ReferenceReturnN) => coords::reference_return(cmd, st, cfg, env, out)?,
        Some(GCode::ReturnFromReference) if crate::MILL => coords::return_from_reference(cmd, st, cfg, env, out)?,
        Some(GCode::DataSetting) if crate::MILL => mill::data(cmd, st, cfg, out)?,
        Some(GCode::Language(_)) => {}
        _ if cmd.g.stroke.is_some() || cmd.g.frame.is_some() => {}
        _ if cmd.g.polygon.is_some() => polygon::switch(cmd, st, cfg, out)?,
        _ if polar::mode_change(cmd, st, cfg)? => {}
        _ if st.polar.is_some() => polar::execute(cmd, st, cfg, out)?,
        _ => cycle_or_motion(cmd, st, cfg, env, out, chained)?,
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

/// Whether [`execute`] may take the short way of [`plain`]: no M, T or flow
/// word, no group 00, stroke check, polygon or polar code in the block, neither
/// polar interpolation nor polygon turning in force — most blocks of a contour.
fn is_plain(cmd: &Command, st: &State) -> bool {
    let g = &cmd.g;
    cmd.m.is_empty()
        && cmd.tool.is_none()
        && cmd.flow.is_none()
        && !g.mill
        && g.one_shot.is_none()
        && g.stroke.is_none()
        && g.polygon.is_none()
        && g.polar.is_none()
        && st.polar.is_none()
        && st.modal.polygon.is_none()
}

/// [`execute`] of a block [`is_plain`] accepts, without the stages that have
/// nothing to do for it (polar and polygon checks, stroke-check switching, M
/// codes, tool change, group 00 codes, program flow): the same actions, state
/// and alarms, about a hundred Cortex-M4 instructions sooner.
fn plain(
    cmd: &Command,
    st: &mut State,
    cfg: &MachineConfig,
    env: &dyn Environment,
    out: &mut CycleStage<'_>,
) -> Result<Flow, AlarmKind> {
    let from = st.pos;
    let chained = cycles::before_block(cmd, st, cfg)?;
    apply_modal(cmd, st);
    spindle::before_motion(cmd, st, cfg, out)?;
    cycle_or_motion(cmd, st, cfg, env, out, chained)?;
    if let Some(e) = cmd.g.exact_stop_mode {
        st.modal.exact_stop_mode = e;
    }
    spindle::after_motion(cmd, st, out)?;
    stroke::check_actions(st, from, out.actions.iter())?;
    crate::contour::after_block(cmd, st, cfg, from, Flow::Continue, out)?;
    Ok(Flow::Continue)
}

/// [`execute`] for the cycles below, which run the blocks of a G70–G73 shape.
pub struct Blocks;

/// What alarm 4007 names on a build without the `siemens` feature.
pub(crate) const SINUMERIK: &str = "SINUMERIK mode";

impl cycles::Executor for Blocks {
    fn execute(
        cmd: &Command,
        st: &mut State,
        cfg: &MachineConfig,
        env: &dyn Environment,
        out: &mut CycleStage<'_>,
    ) -> Result<Flow, AlarmKind> {
        execute(cmd, st, cfg, env, out)
    }

    #[cfg(not(feature = "siemens"))]
    fn cycle_call(_: &Command, _: &mut State, _: &mut cycles::Ctx<'_, '_>) -> Result<(), AlarmKind> {
        Err(AlarmKind::NotInThisBuild { what: SINUMERIK })
    }

    #[cfg(feature = "siemens")]
    fn cycle_call(cmd: &Command, st: &mut State, ctx: &mut cycles::Ctx<'_, '_>) -> Result<(), AlarmKind> {
        use crate::lang::siemens::call::{Arg, MAX_ARGS};
        // The driver puts the bound call into the stage of every cycle-call block.
        let call = *ctx.out.call.ok_or(AlarmKind::NotSupportedYet { what: "a cycle call without its arguments" })?;
        let mut buf = [Arg::Empty; MAX_ARGS];
        let args = call.args.args(&mut buf);
        call.front.cycle_start(call.sig, args, cmd, st, &mut cycles::CallEngine::<Blocks>::new(ctx), call.contour)
    }
}

/// The block's cycle (a canned cycle it starts or continues, `chained` from
/// [`cycles::before_block`]) or else its motion: the part of a block both
/// [`execute`] and its short way [`plain`] run.
#[inline(always)]
fn cycle_or_motion(
    cmd: &Command,
    st: &mut State,
    cfg: &MachineConfig,
    env: &dyn Environment,
    out: &mut CycleStage<'_>,
    chained: bool,
) -> Result<(), AlarmKind> {
    let mut ctx = cycles::Ctx { cfg, env, out };
    if !cycles::execute::<Blocks>(cmd, st, &mut ctx, chained)? {
        motion_or_curve(cmd, st, cfg, ctx.out)?;
    }
    Ok(())
}

/// Executes the block's motion in the modal motion mode: G02.1/G03.1 and
/// G02.2/G03.2 (with axis words) as a curve expansion, the others as moves.
fn motion_or_curve(
    cmd: &Command,
    st: &mut State,
    cfg: &MachineConfig,
    out: &mut CycleStage<'_>,
) -> Result<(), AlarmKind> {
    let code = st.modal.motion;
    if matches!(code, GCode::EllipseCw | GCode::EllipseCcw | GCode::ParabolaCw | GCode::ParabolaCcw) {
        return if cmd.has_axes() { cycles::curve_block(cmd, st, cfg, out) } else { Ok(()) };
    }
    motion::execute(cmd, st, cfg, out)
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
        // G54.1 P1–P48 (6–53) stand on G54's slot; their offset is the mill's
        // business (exec::mill::prepare).
        (m.work_frame, m.extra_frame) = if w < 6 { (w, 0) } else { (0, w - 5) };
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
/// with their next move. A machining centre's T selects and M06 changes
/// ([`mill::tool`]).
fn tool_change(cmd: &Command, st: &mut State, cfg: &MachineConfig, out: &mut Staged<'_>) -> Result<(), AlarmKind> {
    if crate::is_mill(cfg) {
        return mill::tool(cmd, st, cfg, out);
    }
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
    st.sum_own_offsets();
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
    if let Some(GCode::Language(l)) = cmd.g.one_shot {
        // A board built without the `siemens` feature (the F446) refuses G290.
        if cfg!(not(feature = "siemens")) && l == crate::config::Language::Siemens {
            return Err(AlarmKind::NotInThisBuild { what: SINUMERIK });
        }
        return Ok(Flow::Language(l));
    }
    Ok(match cmd.flow {
        None => Flow::Continue,
        Some(FlowWord::Call { program, repeats, by }) => Flow::Call { program, repeats, by },
        Some(FlowWord::Return { seq }) => Flow::Return { seq },
        Some(FlowWord::Jump { seq, high }) => {
            let input = cfg.jump_input;
            let level = env.input(input).ok_or(AlarmKind::InputNotAvailable { input })?;
            if level == high { Flow::Jump { seq } } else { Flow::Continue }
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lang::siemens::call::{Arg, CallArgs, ContourSource, CycleCall, Signature};
    use crate::stage::Outbox;

    /// A front end whose cycles all refuse to start (the language's own are
    /// interp-siemens's, tested there).
    #[derive(Debug)]
    struct Refuses;

    impl crate::lang::Front for Refuses {
        fn step(
            &self,
            _: &mut crate::Interpreter,
            _: &dyn crate::program::ProgramStore,
            _: &dyn Environment,
            _: &mut dyn crate::canon::CanonSink,
        ) -> Result<crate::Progress, crate::Alarm> {
            unreachable!("not stepped")
        }

        fn ret(&self, _: &mut crate::Interpreter) {
            unreachable!("no blocks of its own")
        }

        fn cycle_start(
            &self,
            _: &'static Signature,
            _: &[Arg<'_>],
            _: &Command,
            _: &mut State,
            _: &mut dyn crate::lang::Engine,
            _: Option<ContourSource<'_>>,
        ) -> Result<(), AlarmKind> {
            Err(AlarmKind::NotSupportedYet { what: "this SINUMERIK cycle" })
        }

        fn contour_command(
            &self,
            _: &crate::program::RawBlock<'_>,
            _: &crate::lang::siemens::vars::Vars,
            _: &State,
            _: &MachineConfig,
        ) -> Result<Option<Command>, AlarmKind> {
            Ok(None)
        }
    }

    /// A cycle-call block reaches the language's cycle start through
    /// `cycles::execute` with its bound call; without one it is refused. Either way
    /// a refused block stages nothing and starts no cycle.
    #[test]
    fn a_cycle_call_block_reaches_the_cycle_start() {
        static NOT_A_CYCLE: Signature = crate::signature!("CYCLE100" (MID: R));
        let cfg = MachineConfig::default();
        let mut st = State::power_on(&cfg, Pos::ZERO);
        let mut cmd = Command::EMPTY;
        cmd.g.one_shot = Some(GCode::CycleCall);
        let mut args = CallArgs::new();
        args.push(Arg::Real(5.0)).unwrap();
        args.bind(NOT_A_CYCLE.types()).unwrap();
        let call = CycleCall {
            sig: &NOT_A_CYCLE,
            args: &args,
            contour: None,
            front: &Refuses,
            #[cfg(feature = "mill-island")]
            islands: &[],
        };
        for call in [None, Some(&call)] {
            let mut outbox = Outbox::new();
            let mut slot = None;
            let mut stage =
                CycleStage::in_program(1, &mut outbox, crate::lang::ProgramText::plain(b"CYCLE100(5)"), &mut slot);
            stage.call = call;
            assert!(execute(&cmd, &mut st, &cfg, &crate::env::Panel::default(), &mut stage).is_err());
            assert!(stage.actions.is_empty());
            assert!(slot.is_none());
        }
    }
}

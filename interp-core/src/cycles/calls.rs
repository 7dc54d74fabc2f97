//! The engine's side of a language's cycle calls: a SINUMERIK cycle
//! (`interp_siemens::cycles`, through [`crate::lang::Front::cycle_start`]) checks its parameters and maps them onto the
//! specification of one of the shared generators; [`CallEngine`] starts that
//! generator as the block's expansion, exactly as the FANUC cycle that shares it.

use super::emit::Emitter;
use super::groove::{GrooveSpec, GroovingGen};
use super::offset::Offsets;
use super::pass::PassGen;
use super::rough::{Nose, RoughGen};
use super::thread::MultiThreadGen;
use super::{Ctx, Executor, Gen, profile, start_cycle};
use crate::alarm::AlarmKind;
use crate::command::Command;
use crate::command::cycle::check_lead;
use crate::command::job::{MultiThreadSpec, StockSpec};
use crate::config::MachineConfig;
use crate::lang::Engine;
use crate::lang::siemens::call::ContourSource;
use crate::modal::State;

/// The engine for the cycle calls of a block: its stage and machine ([`Ctx`]) and
/// how blocks are executed (`X`, for cycles that read a contour's blocks).
pub struct CallEngine<'c, 'a, 'b, X> {
    ctx: &'c mut Ctx<'a, 'b>,
    _blocks: core::marker::PhantomData<X>,
}

impl<'c, 'a, 'b, X: Executor> CallEngine<'c, 'a, 'b, X> {
    /// The engine for the block staged in `ctx`.
    pub fn new(ctx: &'c mut Ctx<'a, 'b>) -> Self {
        CallEngine { ctx, _blocks: core::marker::PhantomData }
    }
}

impl<X: Executor> Engine for CallEngine<'_, '_, '_, X> {
    fn cfg(&self) -> &MachineConfig {
        self.ctx.cfg
    }

    fn stock(
        &mut self,
        spec: &StockSpec,
        contour: ContourSource<'_>,
        cmd: &Command,
        st: &mut State,
    ) -> Result<(), AlarmKind> {
        self.stock_removal(spec, contour, cmd, st)
    }

    fn contour_pass(
        &mut self,
        path: &[crate::geom::Seg],
        tool_left: bool,
        start: crate::geom::Pt,
        cmd: &Command,
        st: &mut State,
    ) -> Result<(), AlarmKind> {
        let em = Emitter::for_block(st, cmd.line);
        let feed = em.feed.value;
        let zero = crate::geom::path::V2::new(0.0, 0.0);
        let offsets = Offsets {
            side: if tool_left { 1.0 } else { -1.0 },
            equi: st.tool.nose_radius as f64,
            front: zero,
            back: zero,
            along: zero,
            tip: crate::geom::path::tip_vector(st.tool.tip, st.tool.nose_radius),
        };
        self.expansion(em, |exp, _, _| {
            for s in path {
                exp.profile.segs.push(*s).map_err(|_| AlarmKind::ProfileTooLong)?;
            }
            let n = u16::try_from(path.len()).map_err(|_| AlarmKind::ProfileTooLong)?;
            let ends = [Some(start), None, None];
            exp.generator = Gen::Pass(PassGen::new(offsets, (0, n), crate::geom::Pt::default(), ends, feed, ends));
            Ok(())
        })
    }

    fn grooving(
        &mut self,
        spec: &GrooveSpec,
        segs: &[crate::geom::Seg],
        cmd: &Command,
        st: &mut State,
    ) -> Result<(), AlarmKind> {
        let em = Emitter::for_block(st, cmd.line);
        self.expansion(em, |exp, _, _| {
            for s in segs {
                exp.profile.segs.push(*s).map_err(|_| AlarmKind::ProfileTooLong)?;
            }
            exp.generator = Gen::Grooving(GroovingGen::new(spec, &exp.profile.segs)?);
            Ok(())
        })
    }

    fn hole(
        &mut self,
        spec: &crate::command::hole::HoleSpec,
        spindle: Option<crate::canon::SpindleDir>,
        cmd: &Command,
        st: &mut State,
    ) -> Result<(), AlarmKind> {
        let mut generator = super::hole::HoleGen::new(*spec);
        if let Some(dir) = spindle {
            generator = generator.starting(dir);
        }
        let em = Emitter { lead: generator.lead(), ..Emitter::for_block(st, cmd.line) };
        start_cycle(em, Gen::Hole(generator), self.ctx.out).map(|_| ())
    }

    fn message(&mut self, code: u16) {
        if let Some(exp) = self.ctx.out.started() {
            exp.notice = Some(code);
        }
    }

    fn emit(&mut self, action: crate::canon::Action) -> Result<(), AlarmKind> {
        self.ctx.out.emit(action)
    }

    fn mill(&mut self, path: mill_paths::MillGen, cmd: &Command, st: &mut State) -> Result<(), AlarmKind> {
        let run = super::mill::MillRun::new(path, st);
        start_cycle(Emitter::for_block(st, cmd.line), Gen::Mill(run), self.ctx.out).map(|_| ())
    }

    #[cfg(feature = "mill-contour")]
    fn mill_contour(
        &mut self,
        path: mill_paths::MillGen,
        contour: ContourSource<'_>,
        cmd: &Command,
        st: &mut State,
    ) -> Result<(), AlarmKind> {
        let run = super::mill::MillRun::new(path, st);
        let plane = st.modal.plane;
        self.expansion(Emitter::for_block(st, cmd.line), |exp, cfg, env| {
            profile::read_contour(&contour, plane, 2, st, cfg, env, X::execute, &mut exp.profile)?;
            exp.generator = Gen::Mill(run);
            Ok(())
        })
    }

    #[cfg(feature = "mill-island")]
    fn mill_islands(
        &mut self,
        spec: &mill_paths::island::IslandSpec,
        edge: ContourSource<'_>,
        cmd: &Command,
        st: &mut State,
    ) -> Result<(), AlarmKind> {
        let call = self.ctx.out.call.copied();
        self.expansion(Emitter::for_block(st, cmd.line), |exp, cfg, env| {
            let islands = (0..).map_while(|i| call.and_then(|c| c.island(i)));
            let shape = super::mill::read_pocket(&edge, islands, st, cfg, env, X::execute, &mut exp.profile)?;
            let moves = mill_paths::island::plan(spec, &shape.edge, &shape.island_refs())?;
            exp.generator = Gen::Island(super::mill::IslandRun::new(moves, st));
            Ok(())
        })
    }

    fn thread(&mut self, spec: &MultiThreadSpec, cmd: &Command, st: &mut State) -> Result<(), AlarmKind> {
        for &lead in &spec.leads[..spec.count - 1] {
            check_lead(lead, st.modal.units)?;
        }
        let generator = MultiThreadGen::new(*spec)?;
        start_cycle(Emitter::for_block(st, cmd.line), Gen::MultiThread(generator), self.ctx.out).map(|_| ())
    }
}

impl<X: Executor> CallEngine<'_, '_, '_, X> {
    /// Runs `build` on a new expansion in the block's slot; on an alarm the slot
    /// is emptied again (the block moves nothing).
    fn expansion(
        &mut self,
        em: Emitter,
        build: impl FnOnce(&mut super::Expansion, &MachineConfig, &dyn crate::env::Environment) -> Result<(), AlarmKind>,
    ) -> Result<(), AlarmKind> {
        let (cfg, env) = (self.ctx.cfg, self.ctx.env);
        let exp = start_cycle(em, Gen::Plan(heapless::Vec::new()), self.ctx.out)?;
        let built = build(exp, cfg, env);
        if built.is_err() {
            self.ctx.out.cycle_slot()?.take();
        }
        built
    }
}

impl<X: Executor> CallEngine<'_, '_, '_, X> {
    /// CYCLE95: the contour read into the expansion, then the stock generator on it.
    pub(crate) fn stock_removal(
        &mut self,
        spec: &StockSpec,
        contour: ContourSource<'_>,
        cmd: &Command,
        st: &State,
    ) -> Result<(), AlarmKind> {
        let em = Emitter::for_block(st, cmd.line);
        let here = em.here(self.ctx.cfg);
        let feed = em.feed.value;
        let nose = Nose {
            radius: st.tool.nose_radius,
            tip: st.tool.tip,
            clearance_udeg: self.ctx.cfg.tools.get(st.tool.offset_number).map_or(0, |r| r.clearance_udeg),
        };
        self.expansion(em, |exp, cfg, env| {
            profile::read_contour(&contour, crate::canon::Plane::Zx, 3, st, cfg, env, X::execute, &mut exp.profile)?;
            exp.generator = Gen::Rough(RoughGen::sections(spec, &mut exp.profile.segs, here, nose, feed)?);
            Ok(())
        })
    }
}

//! The engine's side of a language's cycle calls: a SINUMERIK cycle
//! ([`crate::lang::siemens::cycles`]) checks its parameters and maps them onto the
//! specification of one of the shared generators; [`CallEngine`] starts that
//! generator as the block's expansion, exactly as the FANUC cycle that shares it.

use super::emit::Emitter;
use super::thread::MultiThreadGen;
use super::{Ctx, Executor, Gen, start_cycle};
use crate::alarm::AlarmKind;
use crate::command::Command;
use crate::command::cycle::check_lead;
use crate::command::job::MultiThreadSpec;
use crate::config::MachineConfig;
use crate::lang::siemens::cycles::Engine;
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

    fn thread(&mut self, spec: &MultiThreadSpec, cmd: &Command, st: &mut State) -> Result<(), AlarmKind> {
        for &lead in &spec.leads[..spec.count - 1] {
            check_lead(lead, st.modal.units)?;
        }
        let generator = MultiThreadGen::new(*spec)?;
        start_cycle(Emitter::new(*st, cmd.line), Gen::MultiThread(generator), self.ctx.out).map(|_| ())
    }
}

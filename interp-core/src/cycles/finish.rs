//! G70 finishing (2.16.4): the blocks ns–nf run as written — their F, S and T take
//! effect — one block per refill through the normal check/exec pipeline, then a
//! rapid back to the start point.

use super::emit::{Emitter, Out, Pt, Step};
use super::profile::{EnvRef, ShapeSource, next_shape_block, run_shape_block};
use super::{CycleStage, Execute, StepQueue};
use crate::alarm::AlarmKind;
use crate::config::MachineConfig;
use crate::env::Environment;
use crate::program::Cursor;

/// Where G70 is in its blocks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FinishGen {
    cur: Cursor,
    ns: u32,
    nf: u32,
    first: bool,
    start: Pt,
    done: bool,
    /// How the blocks are executed (`exec::execute`).
    execute: ExecuteFn,
}

/// [`Execute`] kept in the generator: the same when it is the same function.
#[derive(Clone, Copy, Debug)]
struct ExecuteFn(Execute);

impl PartialEq for ExecuteFn {
    fn eq(&self, other: &Self) -> bool {
        core::ptr::fn_addr_eq(self.0, other.0)
    }
}

impl Eq for ExecuteFn {}

impl FinishGen {
    /// G70 reading from block ns at `cur`, returning to `start`, running the
    /// blocks through `execute`.
    pub fn new(cur: Cursor, ns: u32, nf: u32, start: Pt, execute: Execute) -> Self {
        FinishGen { cur, ns, nf, first: true, start, done: false, execute: ExecuteFn(execute) }
    }

    /// Runs the next block into `out` (which has room for a whole block); after nf
    /// queues the return to the start. False when finished.
    pub fn step<E: Environment + ?Sized>(
        &mut self,
        em: &mut Emitter,
        cfg: &MachineConfig,
        program: crate::lang::ProgramText<'_>,
        env: &E,
        out: &mut dyn Out,
        queue: &mut StepQueue,
    ) -> Result<bool, AlarmKind> {
        if self.done {
            return Ok(false);
        }
        let src = ShapeSource { program, ns: self.ns, nf: self.nf };
        let Some(sb) = next_shape_block(&src, &mut self.cur, &EnvRef(env))? else {
            return Err(AlarmKind::SequenceNotFound { n: self.nf });
        };
        let mut outbox = crate::stage::Outbox::new();
        let mut staged = CycleStage::new(em.line, &mut outbox);
        run_shape_block(&sb, self.first, &mut em.st, cfg, env, self.execute.0, &mut staged)?;
        if sb.last {
            crate::contour::flush(&mut em.st, &mut staged)?;
        }
        self.first = false;
        while let Some(c) = outbox.pop_front() {
            out.put(c)?;
        }
        if sb.last {
            queue.push_back(Step::Rapid(self.start)).map_err(|_| AlarmKind::Overflow)?;
            self.done = true;
        }
        Ok(true)
    }
}

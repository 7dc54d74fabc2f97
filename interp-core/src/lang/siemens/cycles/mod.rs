//! The SINUMERIK standard cycles (seed 001 chapters 2 and 4): each cycle's
//! parameter list ([`SIGNATURES`]) and its start on the engine's generators
//! ([`start`]). The front end binds a call's arguments to the signature
//! ([`crate::lang::siemens::call::CallArgs::bind`]) before `start` sees them.
//!
//! This module sits in the execution row (it builds the engine's cycle
//! specifications): `tools/module-cycles.py` treats it as a layer of its own,
//! between `cycles` and `exec`. The language's reader never uses it; the driver
//! looks signatures up and `exec` calls [`start`].

use crate::alarm::AlarmKind;
use crate::command::Command;
use crate::lang::siemens::call::{Arg, ContourSource, Signature};
use crate::modal::State;

/// Every standard cycle implemented.
pub static SIGNATURES: &[Signature] = &[];

/// The cycle called `name` (case-insensitive), if implemented.
pub fn signature(name: &[u8]) -> Option<&'static Signature> {
    SIGNATURES.iter().find(|s| s.is(name))
}

/// Starts the cycle `sig` with `args` (already type-checked and padded with
/// `Empty`: one per parameter) on the state: builds the engine's spec and starts
/// the expansion in the stage's cycle slot, or stages plain moves; the cycle's own
/// alarms (61xxx) come from here. `contour` is where the cycle's contour is, when
/// its contour parameter names one.
pub fn start(
    sig: &Signature,
    args: &[Arg<'_>],
    cmd: &Command,
    st: &mut State,
    ctx: &mut crate::cycles::Ctx<'_, '_>,
    contour: Option<ContourSource<'_>>,
) -> Result<(), AlarmKind> {
    let _ = (sig, args, cmd, st, ctx, contour);
    Err(AlarmKind::NotSupportedYet { what: "this SINUMERIK cycle" })
}

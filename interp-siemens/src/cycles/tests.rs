//! The SINUMERIK turning cycles called directly (the front end's call plumbing
//! hands `start` the same argument lists), their expansions run to the end. The
//! expected geometry is computed here from the document's formulas.

use super::*;
use interp_core::axis::{Axis, Pos};
use interp_core::canon::{Action, Canon, FeedMode, SpindleDir, ThreadSync};
use interp_core::cycles::{CallEngine, Ctx, CycleStage, Expansion};
use interp_core::exec::Blocks;
use interp_core::lang::ProgramText;
use interp_core::stage::Outbox;
use interp_core::{MachineConfig, Panel};
use std::vec;
use std::vec::Vec;

mod drill;
#[cfg(feature = "mill-face")]
mod face;
mod groove;
mod stock;
mod threads;
mod undercut;

/// A lathe with room for the document's examples (X ±200 mm radius, Z ±600 mm).
pub(super) fn machine() -> MachineConfig {
    let mut cfg = MachineConfig::default();
    cfg.axes[0] = interp_core::config::AxisConfig::linear(-200, 200, 6_000);
    cfg.axes[2] = interp_core::config::AxisConfig::linear(-600, 600, 8_000);
    cfg
}

/// The state at work X (diameter) and Z, mm, spindle turning M3 at 1000 rev/min,
/// feed per revolution F0.2, DIAMON.
pub(super) fn at(cfg: &MachineConfig, x_dia: f64, z: f64) -> State {
    let pos = Pos::xz(mm(x_dia / 2.0), mm(z));
    let mut st = State::power_on(cfg, pos);
    st.spindle.dir = SpindleDir::Cw;
    st.spindle.rpm = 1000;
    st.modal.feed_mode = FeedMode::PerRev;
    st.feed.per_rev = mm(0.2);
    st
}

/// Millimetres as nm.
pub(super) fn mm(v: f64) -> i64 {
    libm::round(v * 1e6) as i64
}

/// REAL arguments (0 for a left-out one written as `None`).
pub(super) fn reals(v: &[Option<f64>]) -> Vec<Arg<'static>> {
    v.iter().map(|x| x.map_or(Arg::Empty, Arg::Real)).collect()
}

/// What a cycle call did: the actions staged with the block and the expansion's.
#[derive(Debug)]
pub(super) struct Called {
    pub actions: Vec<Canon>,
    /// The state the block leaves (position back where the cycle ends).
    pub state: State,
}

/// Calls cycle `name` with `args` on `st` (line 7) and runs its expansion (dry run
/// first, as the interpreter does, then the real run) to the end. An alarm leaves
/// no expansion and no staged action.
pub(super) fn call(name: &str, args: &[Arg<'_>], st: &State, cfg: &MachineConfig) -> Result<Called, AlarmKind> {
    call_with(name, args, st, cfg, None)
}

/// [`call`] with a contour.
pub(super) fn call_with(
    name: &str,
    args: &[Arg<'_>],
    st: &State,
    cfg: &MachineConfig,
    contour: Option<ContourSource<'_>>,
) -> Result<Called, AlarmKind> {
    let sig = signature(name.as_bytes()).expect("a cycle of SIGNATURES");
    assert!(args.len() <= sig.len(), "{name} takes {} parameters", sig.len());
    let panel = Panel::default();
    let mut outbox = Outbox::new();
    let mut slot: Option<Expansion> = None;
    let mut state = *st;
    let mut cmd = Command::EMPTY;
    cmd.line = 7;
    let program = contour.map_or(ProgramText::NONE, |c| c.program);
    let started = {
        let mut stage = CycleStage::in_program(7, &mut outbox, program, &mut slot);
        let mut ctx = Ctx { cfg, env: &panel, out: &mut stage };
        start(sig, args, &cmd, &mut state, &mut CallEngine::<Blocks>::new(&mut ctx), contour)
    };
    if let Err(e) = started {
        assert!(slot.is_none() && outbox.is_empty(), "{name}: an alarm left motion behind");
        return Err(e);
    }
    let mut actions: Vec<Canon> = outbox.iter().copied().collect();
    if let Some(exp) = slot {
        let mut dry = exp.clone();
        while !dry.dry_run(cfg, program, &panel)? {}
        dry.settle(&mut state, cfg);
        let mut exp = exp;
        loop {
            let mut q: heapless::Deque<Canon, 16> = heapless::Deque::new();
            let done = exp.run(cfg, program, &panel, &mut q)?;
            actions.extend(q.iter().copied());
            if done {
                break;
            }
        }
    }
    assert!(actions.iter().all(|c| c.line == 7));
    Ok(Called { actions, state })
}

/// A move as (kind, X diameter, Z) in mm rounded to µm: 'r' rapid, 'l' line,
/// 'a' arc, 't' thread; other actions left out.
pub(super) fn moves(c: &Called) -> Vec<(char, f64, f64)> {
    c.actions
        .iter()
        .filter_map(|a| {
            let (k, to) = match a.action {
                Action::Rapid(m) => ('r', m.to.work),
                Action::Linear(m) => ('l', m.to.work),
                Action::Arc(m) => ('a', m.to.work),
                Action::Thread(t) => ('t', t.to.work),
                _ => return None,
            };
            Some((k, um(2 * to[Axis::X]), um(to[Axis::Z])))
        })
        .collect()
}

/// nm as mm rounded to µm.
pub(super) fn um(nm: i64) -> f64 {
    libm::round(nm as f64 / 1e3) / 1e3
}

/// `v` rounded to µm.
pub(super) fn r3(v: f64) -> f64 {
    libm::round(v * 1e3) / 1e3
}

/// The thread moves: (X diameter, Z, lead mm, start angle °, waits for the index).
pub(super) fn threads(c: &Called) -> Vec<(f64, f64, f64, f64, bool)> {
    c.actions
        .iter()
        .filter_map(|a| match a.action {
            Action::Thread(t) => Some((
                um(2 * t.to.work[Axis::X]),
                um(t.to.work[Axis::Z]),
                um(t.lead),
                t.start_udeg as f64 / 1e6,
                t.sync == ThreadSync::Index,
            )),
            _ => None,
        })
        .collect()
}

#[test]
fn signatures_are_found_in_any_case() {
    assert_eq!(signature(b"cycle97").map(|s| s.name), Some("CYCLE97"));
    assert_eq!(signature(b"Cycle98").map(|s| s.len()), Some(22));
    assert!(signature(b"CYCLE100").is_none());
    // The manual's parameter lists (lines 11069, 11259).
    let names = |n: &[u8]| signature(n).map(|s| s.names().collect::<Vec<_>>());
    assert_eq!(
        names(b"CYCLE97").unwrap(),
        [
            "PIT", "MPIT", "SPL", "FPL", "DM1", "DM2", "APP", "ROP", "TDEP", "FAL", "IANG", "NSP", "NRC", "NID",
            "VARI", "NUMT", "_VRT"
        ]
    );
}

/// A cycle message raised after a milling cycle started travels with its
/// expansion (the interpreter shows it once the dry run has passed).
#[test]
fn a_message_travels_with_the_cycle_it_belongs_to() {
    use interp_core::lang::Engine;
    let cfg = MachineConfig::mill();
    let mut st = State::power_on(&cfg, Pos::default());
    let panel = Panel::default();
    let mut outbox = Outbox::new();
    let mut slot: Option<Expansion> = None;
    let mut cmd = Command::EMPTY;
    cmd.line = 3;
    {
        let mut stage = CycleStage::in_program(3, &mut outbox, ProgramText::NONE, &mut slot);
        let mut ctx = Ctx { cfg: &cfg, env: &panel, out: &mut stage };
        let mut engine = CallEngine::<Blocks>::new(&mut ctx);
        // No cycle yet: nothing to carry it.
        engine.message(62101);
        let plan = mill_paths::plan::Plan::new(&[mill_paths::Move::Dwell(10)]).unwrap();
        engine.mill(mill_paths::MillGen::Plan(plan), &cmd, &mut st).unwrap();
        engine.message(62101);
    }
    assert_eq!(slot.map(|e| e.notice), Some(Some(62101)));
}

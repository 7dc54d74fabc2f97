//! `lathe sim` on the simulated machine: the program runs interpreter → planner →
//! interpolator → step generation on the simulator of the `sim` crate (axes that count
//! steps, a spindle with an encoder), as the board will run it. This gives the
//! cycle time with acceleration, spindle starts and dwells, how far the stepped
//! axes strayed from the programmed path, and the step trace of `--trace`.

use std::fs::File;
use std::io::BufWriter;
use std::path::Path;

use interp_core::lang::fanuc::macros::Variables;
use interp_core::{Alarm, MachineConfig, Panel};
use sim::{Sim, SimOptions, SpindleModel};

use crate::error::Error;
use crate::program::Programs;

/// What the simulated machine did.
#[derive(Clone, Debug, PartialEq)]
pub struct Motion {
    /// From the first block to the end of the program (or to the alarm), s.
    pub cycle_s: f64,
    /// Largest distance of the stepped position from the programmed path, mm.
    pub deviation_mm: f64,
    /// The same in steps of the axis that strays most.
    pub deviation_steps: f64,
    /// Line where it happened.
    pub deviation_line: u32,
    /// Step events.
    pub steps: u64,
    /// A motion alarm (45xx), if one stopped the machine.
    pub alarm: Option<Alarm>,
}

/// Simulated time after which a run is given up (a day: no part program runs longer).
const MAX_SIM_S: f64 = 86_400.0;

/// Runs the main program of `programs` on the simulated machine `cfg` from
/// reference position 1 with the switches `panel` and the macro variables
/// `variables`, writing the step trace to `trace` if given.
pub fn simulate(
    programs: &Programs,
    cfg: &MachineConfig,
    panel: &Panel,
    variables: &Variables,
    trace: Option<&Path>,
) -> Result<Motion, Error> {
    let spindle = SpindleModel {
        // The drive is a little quicker than the acceleration the core plans taps with.
        accel_rpm_s: f64::from(cfg.spindle.accel_rpm_per_s) * 1.25,
        cpr: cfg.spindle.encoder_cpr,
        ..SpindleModel::default()
    };
    let opts = SimOptions { spindle, max_time_s: MAX_SIM_S, start: cfg.reference[0], ..SimOptions::default() };
    let Ok(mut sim) = Sim::new(cfg.clone(), opts) else {
        return Err(Error::Machine { path: "machine".into(), message: "motion settings unusable".into() });
    };
    sim.panel = *panel;
    let target = |p: &Path| p.display().to_string();
    if let Some(path) = trace {
        let file = File::create(path).map_err(|source| Error::Write { target: target(path), source })?;
        sim.trace_to(Box::new(BufWriter::new(file))).map_err(|source| Error::Write { target: target(path), source })?;
    }
    let r = sim.run_store(programs, programs.main, variables, |_| {});
    if let Some(path) = trace {
        sim.finish_trace().map_err(|source| Error::Write { target: target(path), source })?;
    }
    Ok(Motion {
        cycle_s: r.cycle_time_s,
        deviation_mm: r.max_dev_nm / 1e6,
        deviation_steps: r.max_dev_steps,
        deviation_line: r.max_dev_line,
        steps: r.steps,
        alarm: sim.core.alarm(),
    })
}

//! Helpers shared by the host tests: a growable recording sink, a runner that
//! drives the interpreter over a whole program, and compact action formatting.
//! The simulated machine that runs the motion core is the `sim` crate.

use interp_core::canon::{Action, Canon, CanonSink, Full};
use interp_core::program::{ProgramId, ProgramMemory, ProgramStore};
use interp_core::{Alarm, Interpreter, MachineConfig, Panel, Progress, SingleProgram};

/// A sink that records every action (never full).
#[derive(Debug, Default)]
pub struct VecSink(pub Vec<Canon>);

impl CanonSink for VecSink {
    fn push(&mut self, action: Canon) -> Result<(), Full> {
        self.0.push(action);
        Ok(())
    }
}

/// The outcome of running a program to its end.
#[derive(Debug)]
pub struct Run {
    /// Every action, in order.
    pub actions: Vec<Canon>,
    /// Every alarm, in order (the run goes on after each, like `lathe check`).
    pub alarms: Vec<Alarm>,
    /// The interpreter afterwards.
    pub interp: Interpreter,
}

impl Run {
    /// The actions only.
    pub fn kinds(&self) -> Vec<Action> {
        self.actions.iter().map(|c| c.action).collect()
    }

    /// Alarm codes with their lines.
    pub fn alarm_codes(&self) -> Vec<(u32, u16)> {
        self.alarms.iter().map(|a| (a.line, a.code())).collect()
    }
}

/// Runs `text` on machine `cfg` with switches `panel` until it ends, collecting
/// actions and alarms; M00/M01 are answered with cycle start.
pub fn run_with(text: &str, cfg: MachineConfig, panel: Panel) -> Run {
    run_interp(Interpreter::new(cfg), &SingleProgram(text.as_bytes()), &panel, 1_000_000)
}

/// Steps `interp` through the programs of `store` until the program ends or
/// `max_steps` steps have run.
pub fn run_interp<P: ProgramStore + ?Sized>(
    mut interp: Interpreter,
    store: &P,
    panel: &Panel,
    max_steps: usize,
) -> Run {
    // Both languages, as the lathe command and the F405 board have them.
    interp.plug(&interp_siemens::SINUMERIK);
    let mut sink = VecSink::default();
    let mut alarms = Vec::new();
    for _ in 0..max_steps {
        match interp.step(store, panel, &mut sink) {
            Ok(Progress::Ended) => break,
            Ok(Progress::Paused) => interp.cycle_start(),
            Ok(_) => {}
            Err(a) => alarms.push(a),
        }
    }
    Run { actions: sink.0, alarms, interp }
}

/// Program memory of the size the tests use.
pub type Memory = ProgramMemory<65_536, 64, 4_096>;

/// Program memory holding `main` (program 0 unless it has an O number) and the
/// `library` texts; returns it with the number of the main program.
pub fn memory(main: &str, library: &[&str]) -> (Box<Memory>, ProgramId) {
    let mut m = Box::new(Memory::new());
    let id = m.load(main.as_bytes(), Some(0)).expect("main program loads");
    for text in library {
        m.load(text.as_bytes(), None).expect("library program loads");
    }
    (m, id)
}

/// Runs `main` with subprograms `library` on machine `cfg` with `panel`.
pub fn run_programs(main: &str, library: &[&str], cfg: MachineConfig, panel: Panel) -> Run {
    let (store, id) = memory(main, library);
    let mut interp = Interpreter::new(cfg);
    interp.select_main(id);
    run_interp(interp, &*store, &panel, 1_000_000)
}

/// Runs `main` with subprograms `library` on the default machine.
pub fn run_lib(main: &str, library: &[&str]) -> Run {
    run_programs(main, library, MachineConfig::default(), Panel::default())
}

/// The default lathe with X and Z at `accel` mm/s² and a 10 m/min cutting feed (axes
/// and parameter 6023): the machine of the dense-program tests and benchmark.
pub fn fast_lathe(accel: i64) -> MachineConfig {
    const MM: i64 = 1_000_000;
    let mut cfg = MachineConfig::default();
    for ax in [interp_core::axis::Axis::X, interp_core::axis::Axis::Z] {
        cfg.axes[ax.index()].accel_per_s2 = accel * MM;
        cfg.axes[ax.index()].max_feed_per_min = 10_000 * MM;
    }
    cfg.params.set(interp_core::config::Param::MaxCuttingFeed, 10_000 * MM);
    cfg
}

/// Runs `text` on the default machine.
pub fn run(text: &str) -> Run {
    run_with(text, MachineConfig::default(), Panel::default())
}

/// Millimetres to internal nanometres.
pub fn mm(v: f64) -> i64 {
    (v * 1e6).round() as i64
}

/// Work end point of a motion action as (X diameter mm, Z mm).
pub fn xz(c: &Canon) -> Option<(f64, f64)> {
    c.action.endpoint().map(|e| (nm_mm(2 * e.work.0[0]), nm_mm(e.work.0[2])))
}

/// Machine end point of a motion action as (X diameter mm, Z mm).
pub fn machine_xz(c: &Canon) -> Option<(f64, f64)> {
    c.action.endpoint().map(|e| (nm_mm(2 * e.machine.0[0]), nm_mm(e.machine.0[2])))
}

/// Nanometres to millimetres.
pub fn nm_mm(nm: i64) -> f64 {
    nm as f64 / 1e6
}

/// End points (X diameter, Z) of all motion actions, work coordinates.
pub fn path(r: &Run) -> Vec<(f64, f64)> {
    r.actions.iter().filter_map(xz).collect()
}

/// A short name of each action kind, for order assertions.
pub fn kind_names(r: &Run) -> Vec<String> {
    r.actions
        .iter()
        .map(|c| match c.action {
            Action::Rapid(_) => "rapid".into(),
            Action::Linear(_) => "linear".into(),
            Action::Arc(_) => "arc".into(),
            Action::Thread(_) => "thread".into(),
            Action::Tap(_) => "tap".into(),
            Action::Dwell { ms } => format!("dwell {ms}"),
            Action::Spindle(s) => format!("spindle {:?} {:?}", s.dir, s.rpm),
            Action::Tool { tool, offset } => format!("tool {tool} {offset}"),
            Action::ToolChange(t) => format!("change T{} (manual {})", t.tool, t.manual),
            Action::Aux { m } => format!("M{m:02}"),
            Action::Stop { optional } => format!("stop {optional}"),
            Action::End { rewind } => format!("end {rewind}"),
            Action::Polygon(Some(p)) => format!("polygon {}/{}", p.q, p.p),
            Action::Polygon(None) => "polygon off".into(),
            Action::Tolerance { nm } => format!("tolerance {nm}"),
        })
        .collect()
}

/// Motion actions as (kind, X diameter mm, Z mm) with kind `r` rapid, `l` linear,
/// `a` arc, `t` thread, `p` tap, rounded to 0.001 mm.
pub fn moves(r: &Run) -> Vec<(char, f64, f64)> {
    r.actions
        .iter()
        .filter_map(|c| {
            let k = match c.action {
                Action::Rapid(_) => 'r',
                Action::Linear(_) => 'l',
                Action::Arc(_) => 'a',
                Action::Thread(_) => 't',
                Action::Tap(_) => 'p',
                _ => return None,
            };
            let (x, z) = xz(c)?;
            Some((k, round3(x), round3(z)))
        })
        .collect()
}

/// Rounds to 0.001.
pub fn round3(v: f64) -> f64 {
    (v * 1000.0).round() / 1000.0
}

/// The actions produced by the block on `line`.
pub fn on_line(r: &Run, line: u32) -> Vec<Canon> {
    r.actions.iter().filter(|c| c.line == line).copied().collect()
}

//! A simulated lathe for the motion core: step/dir drivers that count steps and
//! check the driver timing, a spindle with configurable speed, ripple and noise and
//! a quadrature encoder with index, digital outputs and a clock — the `hal` traits
//! implemented on a model. [`Sim`] runs interpreter → planner → interpolator →
//! steps on it exactly as the firmware will: one interpolation period at a time,
//! every encoder edge and step event at its own time.
//!
//! It measures the cycle time, the largest distance of the real (stepped) position
//! from the programmed path in nm and steps, and can keep a trace with one row per
//! step event: `t_s,x_mm,z_mm,spindle_deg` (work coordinates, X as a diameter,
//! the cumulative spindle angle the encoder reports at that moment).

pub mod board;
pub mod faults;
pub mod file_flash;
pub mod path;
pub mod spindle;

pub use faults::{Faults, Span};
pub use path::PathRef;
pub use spindle::{Edge, SimSpindle, SpindleModel};

use std::io::Write;

use hal::{DigitalInputs, DigitalOutputs, MonotonicClock, Rotation, SpindleDrive, SpindleEncoder, StepDir};
use interp_core::axis::{AXIS_COUNT, Axis, Pos};
use interp_core::canon::{Canon, CanonSink, Full, SpindleDir};
use interp_core::lang::fanuc::macros::Variables;
use interp_core::program::{ProgramId, ProgramStore};
use interp_core::{Alarm, Interpreter, MachineConfig, Panel, Progress, SingleProgram};
use motion_core::motion::{Event, EventKind, Feedback, MotionCore, QUEUE, State};
use motion_core::stepgen::{DriverTiming, EdgeKind};
use motion_core::sync::Due;

/// A simulated step/dir driver: counts steps and checks the timing it is given.
#[derive(Clone, Copy, Debug)]
pub struct SimAxis {
    /// Position, steps.
    pub steps: i64,
    /// Steps received.
    pub pulses: u64,
    /// Timing rule violations seen (step rate, pulse hold, direction set-up).
    pub violations: u32,
    positive: bool,
    timing: DriverTiming,
    now: u64,
    last_step: Option<u64>,
    last_dir: Option<u64>,
}

impl SimAxis {
    fn new(timing: DriverTiming, steps: i64) -> Self {
        SimAxis { steps, pulses: 0, violations: 0, positive: true, timing, now: 0, last_step: None, last_dir: None }
    }
}

impl StepDir for SimAxis {
    fn set_direction(&mut self, positive: bool) {
        if self.last_step.is_some_and(|t| self.now < t + u64::from(self.timing.pulse_ns)) {
            self.violations += 1;
        }
        self.positive = positive;
        self.last_dir = Some(self.now);
    }

    fn step(&mut self) {
        let period = self.last_step.is_some_and(|t| self.now < t + u64::from(self.timing.min_period_ns));
        let setup = self.last_dir.is_some_and(|t| self.now < t + u64::from(self.timing.dir_setup_ns));
        if period || setup {
            self.violations += 1;
        }
        self.steps += if self.positive { 1 } else { -1 };
        self.pulses += 1;
        self.last_step = Some(self.now);
    }
}

/// Simulated digital I/O: the M-code outputs and when they switched, and input
/// levels (the interpreter's M91/M92 inputs read through [`DigitalInputs`]).
#[derive(Clone, Debug, Default)]
pub struct SimIo {
    /// (time ns, output, level) in order.
    pub log: Vec<(u64, u16, bool)>,
    /// Input levels, bit n for input n (0–31).
    pub inputs: u32,
    now: u64,
}

impl DigitalOutputs for SimIo {
    fn set_output(&mut self, n: u16, on: bool) {
        self.log.push((self.now, n, on));
    }
}

impl DigitalInputs for SimIo {
    fn input(&self, n: u16) -> bool {
        n < 32 && self.inputs & (1 << n) != 0
    }
}

/// The simulation clock.
#[derive(Clone, Copy, Debug, Default)]
pub struct SimClock(pub u64);

impl MonotonicClock for SimClock {
    fn now_ns(&self) -> u64 {
        self.0
    }
}

/// One step event as the trace records it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TraceRow {
    /// Time, s.
    pub t: f64,
    /// Work X, diameter, mm.
    pub x_mm: f64,
    /// Work Z, mm.
    pub z_mm: f64,
    /// Cumulative spindle angle the encoder reports, degrees.
    pub spindle_deg: f64,
    /// Which axis stepped.
    pub axis: u8,
    /// Encoder count at that moment.
    pub count: i64,
    /// Source line running.
    pub line: u32,
}

/// One interpolation period, for kinematic checks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TickSample {
    /// Start of the period, ns.
    pub t: u64,
    /// Commanded position at its end, Q16 steps.
    pub commanded: [i64; AXIS_COUNT],
    /// Spindle speed commanded, rev/min.
    pub spindle_cmd: u32,
    /// Spindle speed measured by the motion core, rev/min.
    pub spindle_measured: f32,
    /// Core state.
    pub state: State,
    /// Line running.
    pub line: u32,
    /// Work offset of the block running.
    pub offset: Pos,
}

/// What to simulate and record.
#[derive(Clone, Copy, Debug)]
pub struct SimOptions {
    /// The spindle model.
    pub spindle: SpindleModel,
    /// Keep a trace row per step event.
    pub trace: bool,
    /// Keep a sample per interpolation period.
    pub samples: bool,
    /// Give up after this much simulated time, s.
    pub max_time_s: f64,
    /// Answer M00/M01 with cycle start at once.
    pub auto_cycle_start: bool,
    /// Spindle model time step, s.
    pub spindle_dt: f64,
    /// Where the axes stand at the start (machine, nm).
    pub start: Pos,
    /// While axes follow the spindle, hand every encoder count to the motion core
    /// (as the firmware did before issue 22). By default only the counts at which
    /// the core said something falls due are handed over
    /// ([`MotionCore::encoder_due`](motion_core::motion::MotionCore::encoder_due)),
    /// as the firmware's encoder compare does; both must step alike.
    pub every_count: bool,
}

impl Default for SimOptions {
    fn default() -> Self {
        SimOptions {
            spindle: SpindleModel::default(),
            trace: false,
            samples: false,
            max_time_s: 600.0,
            auto_cycle_start: true,
            spindle_dt: 1e-4,
            start: Pos::ZERO,
            every_count: false,
        }
    }
}

/// The outcome of a simulated run.
#[derive(Clone, Debug, Default)]
pub struct Report {
    /// Time from start to the end of the program, s.
    pub cycle_time_s: f64,
    /// Largest distance of the stepped position from the programmed path, nm.
    pub max_dev_nm: f64,
    /// The same, in steps of the axis that strays most.
    pub max_dev_steps: f64,
    /// Line where the largest deviation happened.
    pub max_dev_line: u32,
    /// When it happened, s, and where the axes were (machine, nm).
    pub max_dev_at: (f64, Pos),
    /// Step events.
    pub steps: u64,
    /// Driver timing violations seen by the simulated drivers.
    pub timing_violations: u32,
    /// Program and motion alarms.
    pub alarms: Vec<Alarm>,
    /// Queue starvations.
    pub starvations: u32,
    /// Motion blocks run.
    pub blocks: u64,
    /// The program reached M02/M30.
    pub ended: bool,
    /// Machine position at the end, nm.
    pub end: Pos,
    /// Encoder counts that came while axes followed the spindle (a thread, a tap,
    /// polygon turning), and how many of them were handed to the motion core (all
    /// with [`SimOptions::every_count`], else the due counts: what the firmware's
    /// count interrupt runs on).
    pub locked_counts: u64,
    /// See [`Report::locked_counts`].
    pub encoder_calls: u64,
}

/// Where actions come from.
enum Source<'a> {
    Program { store: &'a dyn ProgramStore, interp: Box<Interpreter>, done: bool },
    Actions { list: &'a [Canon], next: usize },
}

/// The simulated machine running the motion core.
pub struct Sim {
    /// Machine configuration.
    pub cfg: MachineConfig,
    /// The motion core under test.
    pub core: Box<MotionCore<QUEUE>>,
    /// Spindle and encoder.
    pub spindle: SimSpindle,
    /// Axis drivers.
    pub axes: [SimAxis; AXIS_COUNT],
    /// Outputs.
    pub io: SimIo,
    /// Clock.
    pub clock: SimClock,
    /// Programmed path.
    pub path: PathRef,
    /// Trace rows (with [`SimOptions::trace`]).
    pub trace: Vec<TraceRow>,
    /// Period samples (with [`SimOptions::samples`]).
    pub samples: Vec<TickSample>,
    /// Events from the motion core.
    pub events: Vec<Event>,
    /// Switches.
    pub panel: Panel,
    /// Machine faults injected (none by default).
    pub faults: Faults,
    /// Where trace rows are written as they happen (`lathe sim --trace`).
    trace_out: Option<Box<dyn Write>>,
    trace_error: Option<std::io::Error>,
    opts: SimOptions,
    report: Report,
    /// End point of the last action handed to the core.
    planned: Pos,
    count: i64,
    /// The motion core answered M00/M01 with cycle start: so must the interpreter.
    resume_program: bool,
    edges: Vec<Edge>,
    step_buf: Vec<(u64, usize, EdgeKind)>,
    /// Driven period by period from outside ([`Sim::external_period`]).
    external: bool,
}

/// The sink the interpreter feeds: the motion core, recording the path it accepts.
struct Feed<'a> {
    core: &'a mut MotionCore<QUEUE>,
    path: &'a mut PathRef,
    from: &'a mut Pos,
}

impl CanonSink for Feed<'_> {
    fn push(&mut self, c: Canon) -> Result<(), Full> {
        self.core.push(c)?;
        if let Some(e) = c.action.endpoint() {
            self.path.add(self.from, &c.action);
            *self.from = e.machine;
        }
        Ok(())
    }
}

fn rotation(d: SpindleDir) -> Rotation {
    match d {
        SpindleDir::Stop => Rotation::Stop,
        SpindleDir::Cw => Rotation::Cw,
        SpindleDir::Ccw => Rotation::Ccw,
    }
}

impl Sim {
    /// A machine `cfg` at machine zero with the spindle stopped.
    pub fn new(cfg: MachineConfig, opts: SimOptions) -> Result<Self, interp_core::AlarmKind> {
        let core = Box::new(MotionCore::new(&cfg, opts.start)?);
        let p = *core.params();
        let spindle = SimSpindle::new(SpindleModel { cpr: cfg.spindle.encoder_cpr, ..opts.spindle });
        Ok(Sim {
            axes: core::array::from_fn(|i| SimAxis::new(p.timing[i], core.steps()[i])),
            cfg,
            core,
            spindle,
            io: SimIo::default(),
            clock: SimClock(0),
            path: PathRef::default(),
            trace: Vec::new(),
            samples: Vec::new(),
            events: Vec::new(),
            panel: Panel::default(),
            faults: Faults::default(),
            trace_out: None,
            trace_error: None,
            opts,
            report: Report::default(),
            planned: opts.start,
            count: 0,
            resume_program: false,
            edges: Vec::new(),
            step_buf: Vec::new(),
            external: false,
        })
    }

    /// Runs program `text` to its end.
    pub fn run_program(&mut self, text: &str) -> Report {
        self.run_program_with(text, |_| {})
    }

    /// Runs program `text`, calling `hook` before every period (operator actions).
    pub fn run_program_with(&mut self, text: &str, hook: impl FnMut(&mut Sim)) -> Report {
        self.run_store(&SingleProgram(text.as_bytes()), 0, &Variables::new(), hook)
    }

    /// Runs program `main` of `store` (subprograms for M98 in the same store), the
    /// macro variables starting as `variables`, calling `hook` before every period.
    pub fn run_store(
        &mut self,
        store: &dyn ProgramStore,
        main: ProgramId,
        variables: &Variables,
        hook: impl FnMut(&mut Sim),
    ) -> Report {
        let mut interp = Box::new(Interpreter::new(self.cfg.clone()));
        interp.plug(&interp_siemens::SINUMERIK);
        interp.set_machine_position(self.opts.start);
        interp.select_main(main);
        *interp.variables_mut() = variables.clone();
        self.run(Source::Program { store, interp, done: false }, hook)
    }

    /// Runs canonical actions (as the interpreter would deliver them) to the end.
    pub fn run_actions(&mut self, list: &[Canon]) -> Report {
        self.run_actions_with(list, |_| {})
    }

    /// Runs canonical actions, calling `hook` before every period.
    pub fn run_actions_with(&mut self, list: &[Canon], hook: impl FnMut(&mut Sim)) -> Report {
        self.run(Source::Actions { list, next: 0 }, hook)
    }

    /// The count the encoder latched at its last index pulse (the index is at one
    /// angle: every latch is the same modulo the counts per revolution).
    pub fn spindle_index(&self) -> i64 {
        self.spindle.index_count().unwrap_or(0)
    }

    /// The spindle encoder's count now.
    pub fn spindle_count(&self) -> i64 {
        self.spindle.count()
    }

    /// Simulated time, s.
    pub fn time_s(&self) -> f64 {
        self.clock.0 as f64 / 1e9
    }

    fn run(&mut self, mut source: Source<'_>, mut hook: impl FnMut(&mut Sim)) -> Report {
        let period = u64::from(self.core.params().tick_ns);
        self.io.inputs = self.panel.inputs;
        let limit = (self.opts.max_time_s * 1e9) as u64;
        let mut end_time = None;
        while self.clock.0 < limit {
            hook(self);
            // The interpreter reads the machine's inputs through the panel.
            self.panel.inputs = (0..32).filter(|&n| self.io.input(n)).fold(0, |bits, n| bits | 1 << n);
            let fed_all = self.feed(&mut source);
            self.period(period);
            let finished = self.core.is_idle() && (self.core.ended() || fed_all || self.core.alarm().is_some());
            if finished {
                end_time.get_or_insert(self.clock.0);
                break;
            }
        }
        let mut r = std::mem::take(&mut self.report);
        r.cycle_time_s = end_time.unwrap_or(self.clock.0) as f64 / 1e9;
        r.steps = self.axes.iter().map(|a| a.pulses).sum();
        r.timing_violations = self.axes.iter().map(|a| a.violations).sum();
        r.starvations = self.core.stats().starvations;
        r.blocks = self.core.stats().blocks;
        r.ended = self.core.ended();
        r.end = self.machine_pos();
        r.alarms.extend(self.core.alarm());
        r
    }

    /// Hands the core what it will take; true when the source has nothing more.
    fn feed(&mut self, source: &mut Source<'_>) -> bool {
        let mut sink = Feed { core: &mut self.core, path: &mut self.path, from: &mut self.planned };
        match source {
            Source::Actions { list, next } => {
                while let Some(c) = list.get(*next) {
                    if sink.push(*c).is_err() {
                        return false;
                    }
                    *next += 1;
                }
                true
            }
            Source::Program { store, interp, done } => {
                for _ in 0..4 * QUEUE {
                    if *done {
                        break;
                    }
                    match interp.step(*store, &self.panel, &mut sink) {
                        Ok(Progress::Blocked | Progress::Paused) => break,
                        Ok(Progress::Ended) => *done = true,
                        Ok(_) => {}
                        Err(a) => {
                            self.report.alarms.push(a);
                            *done = true;
                        }
                    }
                }
                if std::mem::take(&mut self.resume_program) {
                    interp.cycle_start();
                }
                *done
            }
        }
    }

    /// One interpolation period driven from outside (the virtual board): the
    /// motion core's events stay in the core for whoever drives it (the board's
    /// controller takes them through its motion port), and no programmed path is
    /// kept to measure against.
    pub fn external_period(&mut self) {
        self.external = true;
        self.period(u64::from(self.core.params().tick_ns));
    }

    /// One interpolation period: the core's tick, the spindle and its encoder
    /// edges, and every step event, in time order.
    fn period(&mut self, period: u64) {
        let t = self.clock.0;
        let real = Feedback { count: self.spindle.count(), index: self.spindle.index_count() };
        let fb = self.faults.feedback(t, real);
        self.core.tick(t, fb);
        let (dir, rpm) = self.core.spindle_output();
        self.spindle.set_speed(rotation(dir), self.faults.spindle_rpm(t, rpm));
        if !self.external {
            self.handle_events();
        }
        if self.opts.samples {
            self.samples.push(TickSample {
                t,
                commanded: self.core.commanded(),
                spindle_cmd: rpm,
                spindle_measured: self.core.spindle().measured_rpm(),
                state: self.core.state(),
                line: self.core.line(),
                offset: self.core.work_offset(),
            });
        }
        let mut edges = std::mem::take(&mut self.edges);
        edges.clear();
        self.spindle.advance((t + period) as f64 / 1e9, self.opts.spindle_dt, &mut edges);
        let every = self.opts.every_count;
        let due = if every { self.core.wants_encoder_edges().then_some(Due::NONE) } else { self.core.encoder_due() };
        if let Some(mut due) = due {
            // Locked to the spindle: the counts where a step falls due (or every
            // count) go to the core at their own time, as the encoder compare
            // interrupt hands them over.
            let faults = self.faults;
            let mut from = 0;
            self.report.locked_counts += edges.len() as u64;
            for (i, e) in edges.iter().enumerate() {
                if faults.encoder_lost_at(e.t) || !(every || due.reached(e.count)) {
                    continue;
                }
                self.report.encoder_calls += 1;
                self.drain_steps(e.t, &edges[from..i]);
                from = i;
                self.count = e.count;
                self.core.on_encoder(e.t, e.count);
                if !every {
                    due = self.core.encoder_due().unwrap_or(Due::NONE);
                }
            }
            self.drain_steps(t + period, &edges[from..]);
        } else {
            self.drain_steps(t + period, &edges);
        }
        if let Some(e) = edges.last() {
            self.count = e.count;
        }
        self.edges = edges;
        self.clock.0 = t + period;
    }

    fn handle_events(&mut self) {
        while let Some(e) = self.core.pop_event() {
            self.io.now = e.t;
            match e.kind {
                EventKind::Aux { m } => self.io.set_output(m, true),
                EventKind::Stop { .. } if self.opts.auto_cycle_start => {
                    self.core.cycle_start();
                    self.resume_program = true;
                }
                _ => {}
            }
            self.events.push(e);
        }
    }

    /// Applies every step event before `until` to the drivers, in time order; the
    /// encoder `edges` of the period (if given) say what the encoder showed at each.
    fn drain_steps(&mut self, until: u64, edges: &[Edge]) {
        let mut buf = std::mem::take(&mut self.step_buf);
        buf.clear();
        for axis in 0..AXIS_COUNT {
            while let Some(e) = self.core.next_step(axis, until) {
                buf.push((e.t, axis, e.kind));
            }
        }
        buf.sort_by_key(|e| e.0);
        let mut next_edge = 0;
        for &(t, axis, kind) in &buf {
            while let Some(e) = edges.get(next_edge).filter(|e| e.t <= t) {
                self.count = e.count;
                next_edge += 1;
            }
            let drv = &mut self.axes[axis];
            drv.now = t;
            match kind {
                EdgeKind::Dir(p) => drv.set_direction(p),
                EdgeKind::Step(_) => {
                    drv.step();
                    self.after_step(t, axis);
                }
            }
        }
        self.step_buf = buf;
    }

    /// Machine position from the drivers' step counts, nm.
    pub fn machine_pos(&self) -> Pos {
        let p = self.core.params();
        Pos(core::array::from_fn(|i| if p.limits[i].present { p.scale[i].nm(self.axes[i].steps) } else { 0 }))
    }

    fn after_step(&mut self, t: u64, axis: usize) {
        if self.external && !self.opts.trace && self.trace_out.is_none() {
            return;
        }
        let mut pos = self.machine_pos();
        let c = Axis::C.index();
        if self.core.params().limits[c].present {
            // C is rotary: the core renumbers it by whole turns after polygon
            // turning (G50.2), the drive does not. While polygon turning runs C
            // follows the spindle, not the path: its path position is where it locked.
            let p = self.core.params();
            let core_c = self.core.steps()[c];
            let rev = p.scale[c].steps(360_000_000).max(1);
            let lag = self.axes[c].steps - core_c;
            let lag = lag - rev * (lag as f64 / rev as f64).round() as i64;
            let turned = self.core.polygon_steps().unwrap_or(0);
            pos.0[c] = p.scale[c].nm(core_c + lag - turned);
        }
        let err = self.path.error(&pos, self.core.stats().blocks as usize);
        let p = self.core.params();
        let nm = err.iter().map(|e| e * e).sum::<f64>().sqrt();
        let steps = (0..AXIS_COUNT)
            .filter(|&i| p.limits[i].present)
            .map(|i| err[i].abs() / p.scale[i].nm_per_step())
            .fold(0.0, f64::max);
        if nm > self.report.max_dev_nm {
            self.report.max_dev_nm = nm;
            self.report.max_dev_line = self.core.line();
            self.report.max_dev_at = (t as f64 / 1e9, pos);
        }
        self.report.max_dev_steps = self.report.max_dev_steps.max(steps);
        if self.opts.trace || self.trace_out.is_some() {
            let work = pos - self.core.work_offset();
            let row = TraceRow {
                t: t as f64 / 1e9,
                x_mm: 2.0 * work[Axis::X] as f64 / 1e6,
                z_mm: work[Axis::Z] as f64 / 1e6,
                spindle_deg: self.count as f64 * 360.0 / f64::from(self.cfg.spindle.encoder_cpr),
                axis: axis as u8,
                count: self.count,
                line: self.core.line(),
            };
            if let Some(out) = self.trace_out.as_mut()
                && let Err(e) = write_row(out, &row)
            {
                self.trace_error.get_or_insert(e);
            }
            if self.opts.trace {
                self.trace.push(row);
            }
        }
    }

    /// Streams trace rows to `out` from now on (the CSV header first).
    pub fn trace_to(&mut self, mut out: Box<dyn Write>) -> std::io::Result<()> {
        writeln!(out, "{TRACE_HEADER}")?;
        self.trace_out = Some(out);
        Ok(())
    }

    /// Flushes the streamed trace; the first write error, if any.
    pub fn finish_trace(&mut self) -> std::io::Result<()> {
        if let Some(e) = self.trace_error.take() {
            return Err(e);
        }
        self.trace_out.as_mut().map_or(Ok(()), |o| o.flush())
    }

    /// Writes the kept trace as CSV `t_s,x_mm,z_mm,spindle_deg`.
    pub fn write_trace(&self, out: &mut impl Write) -> std::io::Result<()> {
        writeln!(out, "{TRACE_HEADER}")?;
        for r in &self.trace {
            write_row(out, r)?;
        }
        Ok(())
    }
}

/// The trace's CSV header.
pub const TRACE_HEADER: &str = "t_s,x_mm,z_mm,spindle_deg";

/// One trace row: time to the ns, positions to the nm, angle to 0.0001°.
fn write_row(out: &mut (impl Write + ?Sized), r: &TraceRow) -> std::io::Result<()> {
    writeln!(out, "{:.9},{:.6},{:.6},{:.4}", r.t, r.x_mm, r.z_mm, r.spindle_deg)
}

//! The virtual board: the board's controller (the same `controller` crate the
//! firmware runs) on the simulated machine, driven by simulated time. `lathe
//! board` puts it behind a pseudo-terminal in real time; tests drive it directly
//! with bytes and simulated time, so a whole session on the wire is deterministic.
//!
//! Per simulated millisecond the controller is polled once (as the firmware's
//! controller task is); between polls the motion core runs its interpolation
//! periods on the simulated machine, exactly as [`Sim`] runs a program.

use std::path::Path;

use controller::persist::keep::{self, Saver};
use controller::persist::{self, Persist};
use controller::{Inputs, MachineIo, Mode, MotionPort, MotionStatus};
use interp_core::axis::{Axis, Pos};
use interp_core::canon::{Canon, Full, SpindleDir};
use interp_core::{AlarmKind, MachineConfig};
use motion_core::motion::{Event, MotionCore, QUEUE};

use crate::file_flash::{self, FileFlash, FileFlashError};
use crate::{Sim, SimOptions, SpindleModel};

/// How often the controller is polled, ns of simulated time.
pub const POLL_NS: u64 = 1_000_000;

/// What the simulated switches do.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Switches {
    /// Emergency stop pressed.
    pub estop: bool,
    /// Feed hold button held.
    pub feed_hold: bool,
    /// Cycle start button held.
    pub cycle_start: bool,
    /// Safety door open.
    pub door: bool,
    /// External inputs for M91/M92 (bit n).
    pub user: u32,
}

/// The motion core as the controller reaches it, recording every action it
/// accepts (the executed canonical program, for comparison with `lathe sim`).
struct Recorder<'a> {
    core: &'a mut MotionCore<QUEUE>,
    log: Option<&'a mut Vec<Canon>>,
}

impl MotionPort for Recorder<'_> {
    fn push(&mut self, c: Canon) -> Result<(), Full> {
        MotionPort::push(self.core, c)?;
        if let Some(log) = self.log.as_mut() {
            log.push(c);
        }
        Ok(())
    }
    fn feed_hold(&mut self) {
        MotionPort::feed_hold(self.core);
    }
    fn cycle_start(&mut self) {
        MotionPort::cycle_start(self.core);
    }
    fn reset(&mut self) {
        MotionPort::reset(self.core);
    }
    fn emergency_stop(&mut self) {
        MotionPort::emergency_stop(self.core);
    }
    fn set_feed_override(&mut self, pct: u16) {
        MotionPort::set_feed_override(self.core, pct);
    }
    fn set_rapid_override(&mut self, pct: u16) {
        MotionPort::set_rapid_override(self.core, pct);
    }
    fn set_spindle_override(&mut self, pct: u16) {
        MotionPort::set_spindle_override(self.core, pct);
    }
    fn set_position(&mut self, pos: Pos) -> bool {
        MotionPort::set_position(self.core, pos)
    }
    fn reconfigure(&mut self, cfg: &MachineConfig) -> Result<(), AlarmKind> {
        MotionPort::reconfigure(self.core, cfg)
    }
    fn pop_event(&mut self) -> Option<Event> {
        MotionPort::pop_event(self.core)
    }
    fn status(&self) -> MotionStatus {
        MotionPort::status(&*self.core)
    }
}

/// How long the simulated tool changer takes to change a tool by default, ns.
pub const TOOL_CHANGE_NS: u64 = 2_000_000_000;

/// The simulated automatic tool changer of a mill (behind the board's request
/// outputs, `hal::ToolChangeRequest`): it reports done `done_after` ns after a
/// request — or never (`None`: a jammed changer, to see alarm 4511) — and drops
/// done as soon as the request drops.
#[derive(Clone, Debug)]
pub struct ToolChangerModel {
    /// Time from a request to done, ns; `None`: never done.
    pub done_after: Option<u64>,
    /// (time ns, tool) of every request, (time ns, 0) of every clear.
    pub log: Vec<(u64, u16)>,
    /// The request on the outputs: tool, since when (ns).
    request: Option<(u16, u64)>,
    now: u64,
}

impl Default for ToolChangerModel {
    fn default() -> Self {
        ToolChangerModel { done_after: Some(TOOL_CHANGE_NS), log: Vec::new(), request: None, now: 0 }
    }
}

impl ToolChangerModel {
    /// The tool requested on the outputs now, if any.
    pub fn requested(&self) -> Option<u16> {
        self.request.map(|(t, _)| t)
    }

    /// The done line at `now` (ns).
    pub fn done(&self, now: u64) -> bool {
        match (self.request, self.done_after) {
            (Some((_, since)), Some(after)) => now >= since.saturating_add(after),
            _ => false,
        }
    }
}

impl hal::ToolChangeRequest for ToolChangerModel {
    fn request_tool(&mut self, tool: u16) {
        self.request = Some((tool, self.now));
        self.log.push((self.now, tool));
    }

    fn clear_request(&mut self) {
        self.request = None;
        self.log.push((self.now, 0));
    }
}

/// The outputs the controller switches: logged with their simulated time.
#[derive(Clone, Debug, Default)]
pub struct OutputLog {
    /// (time ns, M code, line) in order.
    pub m_codes: Vec<(u64, u16, u32)>,
    /// (time ns, tool, offset).
    pub tools: Vec<(u64, u16, u16)>,
    /// A mill's automatic tool changer.
    pub changer: ToolChangerModel,
    now: u64,
}

impl MachineIo for OutputLog {
    fn m_code(&mut self, m: u16, line: u32) {
        self.m_codes.push((self.now, m, line));
    }
    fn tool(&mut self, tool: u16, offset: u16) {
        self.tools.push((self.now, tool, offset));
    }
    fn tool_change_request(&mut self, tool: Option<u16>) {
        use hal::ToolChangeRequest;
        self.changer.now = self.now;
        match tool {
            Some(t) => self.changer.request_tool(t),
            None => self.changer.clear_request(),
        }
    }
    fn spindle(&mut self, _dir: SpindleDir, _rpm: u32) {}
}

/// The controller on the simulated machine.
pub struct VirtualBoard {
    /// The board's controller, as the firmware builds it.
    pub ctl: Box<controller::Board>,
    /// The simulated machine (its `core` is the motion core the controller feeds).
    pub sim: Sim,
    /// Switches the operator holds.
    pub switches: Switches,
    /// Outputs switched so far.
    pub outputs: OutputLog,
    /// Every canonical action the motion core accepted, when recording.
    pub executed: Option<Vec<Canon>>,
    /// Received bytes the controller has not taken yet (its receive buffer was full).
    pending: Vec<u8>,
    next_poll: u64,
    /// Home switches trip at reference position 1 (homing toward plus).
    home: Pos,
    /// The store on a flash file, when the board has one ([`VirtualBoard::with_flash`]).
    saver: Option<Saver<FileFlash>>,
    /// The link's clock (ns), when it is not the machine's: `lathe board` gives the
    /// wall clock, so the controller's link windows (look-ahead wait, stale line,
    /// starvation watch) are the sender's real time whatever `--speed` is. `None`:
    /// the simulated time (tests that drive the board directly).
    pub link_clock: Option<u64>,
    /// Saves written to the flash file so far, and the last one's failure.
    pub saves: u32,
    pub save_error: Option<persist::Error>,
}

/// Why [`VirtualBoard::with_flash`] could not start.
#[derive(Debug)]
pub enum FlashBoardError {
    /// The flash file.
    File(FileFlashError),
    /// The store in it (after a power cut it repairs itself; this is worse).
    Store(persist::Error),
    /// The motion core refuses the stored machine description.
    Machine(AlarmKind),
}

impl core::fmt::Display for FlashBoardError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            FlashBoardError::File(e) => write!(f, "{e}"),
            FlashBoardError::Store(e) => write!(f, "the store: {e}"),
            FlashBoardError::Machine(k) => write!(f, "the motion core refuses the stored machine description: {k}"),
        }
    }
}

/// What a board with a flash file found there at power-on.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Restored {
    /// Programs read into memory.
    pub programs: usize,
    /// Stored grbl settings the controller refused (left at their defaults).
    pub refused: Vec<u16>,
}

impl VirtualBoard {
    /// A board for machine `cfg`, the axes standing at reference position 1 (where a
    /// homed lathe stands after power-on and `$H`).
    pub fn new(cfg: MachineConfig) -> Result<Self, AlarmKind> {
        let spindle = SpindleModel {
            accel_rpm_s: f64::from(cfg.spindle.accel_rpm_per_s) * 1.25,
            cpr: cfg.spindle.encoder_cpr,
            ..SpindleModel::default()
        };
        let start = cfg.reference[0];
        let opts = SimOptions { spindle, start, max_time_s: f64::INFINITY, ..SimOptions::default() };
        let sim = Sim::new(cfg.clone(), opts)?;
        let mut ctl = Box::new(controller::Board::new(cfg, start));
        ctl.interpreter_mut().plug(&interp_siemens::SINUMERIK);
        Ok(VirtualBoard {
            ctl,
            sim,
            switches: Switches::default(),
            outputs: OutputLog::default(),
            executed: None,
            pending: Vec::new(),
            next_poll: 0,
            home: start,
            saver: None,
            link_clock: None,
            saves: 0,
            save_error: None,
        })
    }

    /// A board whose store (settings, parameters, offsets, common variables #401–
    /// #600, programs) is the flash image `path` (created erased if missing), read
    /// at power-on as the firmware reads its flash, and written while the machine
    /// is at rest as the firmware writes it.
    pub fn with_flash(mut cfg: MachineConfig, path: &Path) -> Result<(Self, Restored), FlashBoardError> {
        let flash = FileFlash::open(path).map_err(FlashBoardError::File)?;
        let mut store = Persist::new(flash, 0..file_flash::SIZE as u32).map_err(FlashBoardError::Store)?;
        let mut settings = controller::Settings::default();
        let refused = keep::load_config(&mut store, &mut cfg, &mut settings).map_err(FlashBoardError::Store)?;
        let mut board = VirtualBoard::new(cfg).map_err(FlashBoardError::Machine)?;
        *board.ctl.settings_mut() = settings;
        let mut scratch = vec![0u8; controller::BOARD_TEXT];
        let programs = keep::load_rest(&mut store, &mut board.ctl, &mut scratch).map_err(FlashBoardError::Store)?;
        board.saver = Some(Saver::new(store, &board.ctl));
        Ok((board, Restored { programs, refused: refused.to_vec() }))
    }

    /// Keeps every canonical action the motion core accepts from now on.
    pub fn record(&mut self) {
        self.executed.get_or_insert_with(Vec::new);
    }

    /// Simulated time, ns.
    pub fn now(&self) -> u64 {
        self.sim.clock.0
    }

    /// Bytes from the link. The controller takes what fits; the rest waits here
    /// (as it waits in the link task's buffer on the board) and is offered again at
    /// every poll — without the real-time bytes among it, which the controller
    /// acts on at once and removes. Lost while the link is down
    /// ([`crate::Faults::link_down`]).
    pub fn receive(&mut self, bytes: &[u8]) {
        if self.sim.faults.link_down_at(self.now()) {
            return;
        }
        self.pending.extend_from_slice(bytes);
        self.offer();
    }

    /// Bytes received but not yet taken by the controller.
    pub fn backlog(&self) -> usize {
        self.pending.len()
    }

    /// Bytes for the link (lost while the link is down).
    pub fn transmit(&mut self) -> Vec<u8> {
        let mut out = Vec::new();
        let mut buf = [0u8; 256];
        loop {
            let n = self.ctl.transmit(&mut buf);
            if n == 0 {
                return out;
            }
            if !self.sim.faults.link_down_at(self.now()) {
                out.extend_from_slice(&buf[..n]);
            }
        }
    }

    /// Runs the machine and the controller up to simulated time `until` (ns).
    pub fn advance(&mut self, until: u64) {
        while self.sim.clock.0 < until {
            if self.sim.clock.0 >= self.next_poll {
                self.poll();
                self.next_poll = self.sim.clock.0 + POLL_NS;
            }
            self.sim.external_period();
        }
    }

    /// Advances by `ns` of simulated time.
    pub fn run_for(&mut self, ns: u64) {
        self.advance(self.now() + ns);
    }

    /// Machine position of the stepped axes, nm (X radius).
    pub fn position(&self) -> Pos {
        self.sim.machine_pos()
    }

    /// The link's time now (see [`VirtualBoard::link_clock`]).
    fn link_now(&self) -> u64 {
        self.link_clock.unwrap_or(self.sim.clock.0)
    }

    fn offer(&mut self) {
        if self.pending.is_empty() {
            return;
        }
        let now = self.link_now();
        let n = self.ctl.receive(&mut self.pending, now);
        self.pending.drain(..n.min(self.pending.len()));
    }

    fn poll(&mut self) {
        self.offer();
        let inputs = self.inputs();
        self.outputs.now = self.sim.clock.0;
        let mut port = Recorder { core: &mut self.sim.core, log: self.executed.as_mut() };
        let link_now = self.link_clock.unwrap_or(self.sim.clock.0);
        self.ctl.poll(link_now, &mut port, &mut self.outputs, inputs);
        self.offer();
        self.keep();
    }

    /// Writes what changed to the flash file while the machine is at rest.
    fn keep(&mut self) {
        let Some(saver) = self.saver.as_mut() else { return };
        let (ctl, core) = (&mut self.ctl, &*self.sim.core);
        if saver.due(self.sim.clock.0, ctl, || ctl.mode(core) == Mode::Idle && MotionPort::status(core).idle) {
            self.saves += 1;
            self.save_error = saver.save(ctl).err();
        }
    }

    /// The switch inputs as the machine shows them now: the operator's switches,
    /// home switches at reference position 1, limit switches just beyond the soft
    /// limits (1 mm).
    fn inputs(&self) -> Inputs {
        let pos = self.position();
        let cfg = &self.sim.cfg;
        let beyond = |a: Axis| {
            let c = cfg.axis(a);
            c.present && (pos[a] > c.max + 1_000_000 || pos[a] < c.min - 1_000_000)
        };
        let s = self.switches;
        Inputs {
            estop: s.estop,
            limit_x: beyond(Axis::X),
            limit_y: beyond(Axis::Y),
            limit_z: beyond(Axis::Z),
            home_x: pos[Axis::X] > self.home[Axis::X],
            home_y: cfg.axis(Axis::Y).present && pos[Axis::Y] > self.home[Axis::Y],
            home_z: pos[Axis::Z] > self.home[Axis::Z],
            feed_hold: s.feed_hold,
            cycle_start: s.cycle_start,
            door: s.door,
            tool_change_done: self.outputs.changer.done(self.sim.clock.0),
            user: s.user,
        }
    }
}

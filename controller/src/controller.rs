//! The controller: bytes in ([`Controller::receive`]), bytes out
//! ([`Controller::transmit`]), and [`Controller::poll`] doing a bounded amount of
//! work with the time, the motion core's port, the outputs and the inputs as
//! arguments.

use interp_core::axis::Pos;
use interp_core::canon::{Canon, CanonSink, Full, SpindleDir};
use interp_core::program::{Cursor, ProgramMemory};
use interp_core::{Alarm, AlarmKind, Interpreter, MachineConfig, Panel, Progress};
use motion_core::motion::{EventKind, State};

use crate::framing::{Checked, LinkSeq};
use crate::homing::{Homed, Homing};
use crate::io::{Inputs, MachineIo};
use crate::lines::{self, Kind, trim};
use crate::outq::{Class, OutQueue};
use crate::port::{MotionPort, MotionStatus};
use crate::report::{Mm, Xyz};
use crate::rx::Receiver;
use crate::settings::Settings;
use crate::starve::{Attendance, StarveWatch, Starved};
use crate::tape::{self, Block, Tape};
use crate::toolchange::{ToolChangeSlot, ToolChangeStep, ToolChangeWait};
use crate::window::{Store, Window};

/// Receive buffer, bytes (the LF included): what a character-counting sender may
/// have in flight.
pub const RX: usize = 128;
/// Output queue, bytes.
pub const OUT: usize = 2048;
/// Interpreter steps one poll runs at most (each at most one NC block and 32
/// macro statements).
pub const STEPS_PER_POLL: usize = 8;
/// Received lines one poll handles at most.
pub const LINES_PER_POLL: usize = 4;
/// The welcome line senders wait for.
pub const WELCOME: &str = "Grbl 1.1h ['$' for help]";

/// XON (DC1) and XOFF (DC3).
pub(crate) const XON: u8 = 0x11;
pub(crate) const XOFF: u8 = 0x13;

/// The state a status report shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// Nothing to do.
    Idle,
    /// A program or stream is running.
    Run,
    /// Feed hold: `held` once the axes have stopped (also M00/M01).
    Hold {
        /// Stopped.
        held: bool,
    },
    /// Alarm: lines are refused until `$X` or reset.
    Alarm,
    /// `$C`: programs are interpreted without motion.
    Check,
    /// `$J=` jogging.
    Jog,
    /// `$H` homing.
    Home,
    /// Safety door: `open` while the door input is active.
    Door {
        /// The door is open.
        open: bool,
    },
    /// `$SLP`.
    Sleep,
}

/// What the interpreter is running.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Job {
    /// Nothing.
    None,
    /// Program text from the link (grbl lines or tape drip feed), program 0.
    Stream,
    /// Program O`n` from memory (`$PR=n`).
    Memory(u32),
}

/// A look-ahead waiting for text still to come.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Wait {
    /// Window bytes received when it failed.
    pub received: u64,
    /// The alarm it raises if the text never comes.
    pub alarm: Alarm,
}

/// What became of a received line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Handled {
    /// Answered; it leaves the receive buffer.
    Done,
    /// Cannot be taken yet (the window is full, a jog waits for room in the
    /// planner): it stays in the receive buffer.
    Wait,
}

/// What changed since [`Controller::take_dirty`] last asked: what the shell
/// should write to flash (see `persist`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Dirty {
    /// Settings, parameters or the machine description (`$n=`, `$Pn=`, `$RST=`).
    pub settings: bool,
    /// Startup blocks (`$N0=`, `$N1=`).
    pub startup: bool,
    /// Program memory (tape punch, `$PD=`, `$RST=*`).
    pub programs: bool,
}

/// Counters for tests and diagnostics.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counters {
    /// Lines answered `ok`.
    pub ok: u32,
    /// Lines answered `error:N`.
    pub errors: u32,
    /// Resend requests (`error:88`).
    pub resends: u32,
    /// Alarms raised.
    pub alarms: u32,
    /// Bytes the stream window dropped behind the interpreter.
    pub window_dropped: u64,
    /// Times a look-ahead (G70–G73 shape, forward GOTO, WHILE's END) waited for
    /// lines not yet received.
    pub lookahead_waits: u32,
    /// Soft resets (0x18) carried out.
    pub resets: u32,
    /// Feed holds from the link (`!`) carried out.
    pub holds: u32,
}

/// With link checksums: a partial line that got no byte for this long (ns) has
/// lost its LF (128 bytes take 11 ms at 115200 baud; a USB serial adapter may hold
/// bytes back 16 ms).
pub const STALE_LINE_NS: u64 = 50_000_000;

/// The board's controller. `W`: stream window bytes; `T`, `P`, `S`: program
/// memory text bytes, programs, indexed sequence numbers.
pub struct Controller<const W: usize, const T: usize, const P: usize, const S: usize> {
    pub(crate) interp: Interpreter,
    pub(crate) window: Window<W>,
    pub(crate) memory: ProgramMemory<T, P, S>,
    pub(crate) settings: Settings,
    pub(crate) startup: [heapless::String<80>; 2],
    pub(crate) rx: Receiver,
    pub(crate) out: OutQueue<OUT>,
    /// Feed, rapid, spindle override, %.
    pub(crate) ovr: [u16; 3],
    /// grbl alarm number in force.
    pub(crate) alarm: Option<u8>,
    pub(crate) hold: bool,
    pub(crate) paused: bool,
    pub(crate) door: bool,
    pub(crate) check: bool,
    pub(crate) sleep: bool,
    pub(crate) job: Job,
    pub(crate) jog: bool,
    /// Where the last jog move ends (machine, nm).
    pub(crate) jog_target: Pos,
    pub(crate) homing: Option<Homing>,
    /// The interpreter's position must be taken from the motion core once at rest.
    pub(crate) need_sync: bool,
    /// The interpreter reached M02/M30; the motion core's End event closes the job.
    pub(crate) interp_done: bool,
    /// The motion core reported M02/M30 done.
    pub(crate) motion_end: bool,
    pub(crate) lookahead: Option<Wait>,
    /// A line could not enter the window even after dropping old text.
    pub(crate) window_stuck: bool,
    /// The link-quiet watch of a streamed job (alarm 4601).
    pub(crate) starve: StarveWatch,
    /// Whether the stream job is a streamed program and when it was last fed or
    /// touched (`$306`).
    pub(crate) attendance: Attendance,
    /// The stream job has run a block (a job of only `%`, blank or comment lines
    /// is not open).
    pub(crate) job_worked: bool,
    /// The tape's closing `%` came: the sender has sent the whole job.
    pub(crate) record_closed: bool,
    pub(crate) now: u64,
    pub(crate) prev_inputs: Inputs,
    pub(crate) door_open: bool,
    pub(crate) tape: Option<Tape>,
    pub(crate) link: LinkSeq,
    /// The link line being answered (checksums in use): replies name it.
    answering: Option<u32>,
    pub(crate) panel: Panel,
    /// `$H` completed since power-on (G28/G30 need it when home switches are fitted).
    pub(crate) homed: bool,
    pub(crate) flood: bool,
    pub(crate) mist: bool,
    /// Startup block to run next (`$N0`, `$N1`), 2 = none.
    pub(crate) startup_next: u8,
    /// A mill's automatic tool change waiting for the changer's done.
    pub(crate) tool_change: ToolChangeSlot,
    pub(crate) counters: Counters,
    pub(crate) dirty: Dirty,
}

/// Feeds the motion core through the port.
pub(crate) struct PortSink<'a, M: MotionPort + ?Sized>(pub &'a mut M);

impl<M: MotionPort + ?Sized> CanonSink for PortSink<'_, M> {
    fn push(&mut self, c: Canon) -> Result<(), Full> {
        self.0.push(c)
    }

    fn push_ref(&mut self, c: &Canon) -> Result<(), Full> {
        self.0.push_ref(c)
    }
}

/// Check mode: takes everything, moves nothing.
pub(crate) struct Discard;

impl CanonSink for Discard {
    fn push(&mut self, _: Canon) -> Result<(), Full> {
        Ok(())
    }
}

impl<const W: usize, const T: usize, const P: usize, const S: usize> Controller<W, T, P, S> {
    /// A controller for machine `cfg` with the axes at machine position `pos`
    /// (where the motion core was built). The welcome line is queued.
    pub fn new(cfg: MachineConfig, pos: Pos) -> Self {
        let mut c = Self::parts(cfg, pos);
        c.place(pos);
        c
    }

    /// [`Controller::new`] built in `slot` (a static on the board): the parts are
    /// written as one expression straight into the slot and positioned there, so
    /// the controller (tens of KB) is never built on the stack and copied.
    pub fn new_in(slot: &mut core::mem::MaybeUninit<Self>, cfg: MachineConfig, pos: Pos) -> &mut Self {
        let c = slot.write(Self::parts(cfg, pos));
        c.place(pos);
        c
    }

    /// The state `rewind_stream` and `welcome` leave: the interpreter at the
    /// machine position and at the window's start, the welcome line queued.
    fn place(&mut self, pos: Pos) {
        self.interp.set_machine_position(pos);
        self.interp.resume_at(Cursor { program: 0, offset: 0, line: self.window.first_line() });
        self.out.line(Class::Reply, WELCOME);
    }

    /// The controller's parts as one expression, never borrowed as a whole (so the
    /// compiler can build it in its destination); [`Controller::place`] finishes it.
    fn parts(cfg: MachineConfig, pos: Pos) -> Self {
        Controller {
            interp: Interpreter::new(cfg),
            window: Window::new(),
            memory: ProgramMemory::new(),
            settings: Settings::default(),
            startup: [heapless::String::new(), heapless::String::new()],
            rx: Receiver::new(),
            out: OutQueue::default(),
            ovr: [100; 3],
            alarm: None,
            hold: false,
            paused: false,
            door: false,
            check: false,
            sleep: false,
            job: Job::None,
            jog: false,
            jog_target: pos,
            homing: None,
            need_sync: false,
            interp_done: false,
            motion_end: false,
            lookahead: None,
            window_stuck: false,
            starve: StarveWatch::default(),
            attendance: Attendance::default(),
            job_worked: false,
            record_closed: false,
            now: 0,
            prev_inputs: Inputs::default(),
            door_open: false,
            tape: None,
            link: LinkSeq::new(),
            answering: None,
            panel: Panel::default(),
            homed: false,
            flood: false,
            mist: false,
            startup_next: 0,
            tool_change: ToolChangeSlot::new(),
            counters: Counters::default(),
            dirty: Dirty::default(),
        }
    }

    /// The interpreter (modal state, variables, machine description).
    pub fn interpreter(&self) -> &Interpreter {
        &self.interp
    }

    /// The interpreter, to load common variables or edit the machine description
    /// between jobs.
    pub fn interpreter_mut(&mut self) -> &mut Interpreter {
        &mut self.interp
    }

    /// Program memory (M98 subprograms, `$PR`, tape punch).
    pub fn memory(&self) -> &ProgramMemory<T, P, S> {
        &self.memory
    }

    /// Program memory, to fill it from flash at start-up.
    pub fn memory_mut(&mut self) -> &mut ProgramMemory<T, P, S> {
        &mut self.memory
    }

    /// The controller's own settings.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// The settings, to restore them from flash at start-up.
    pub fn settings_mut(&mut self) -> &mut Settings {
        &mut self.settings
    }

    /// The startup blocks `$N0`, `$N1`.
    pub fn startup_blocks(&self) -> [&str; 2] {
        [self.startup[0].as_str(), self.startup[1].as_str()]
    }

    /// Sets startup block `i` (0 or 1), e.g. restored from flash; false if `i` is
    /// not 0 or 1 or the text is longer than 80 bytes.
    pub fn set_startup_block(&mut self, i: usize, text: &str) -> bool {
        let Some(slot) = self.startup.get_mut(i) else { return false };
        let mut s = heapless::String::new();
        if s.push_str(text).is_err() {
            return false;
        }
        *slot = s;
        true
    }

    /// What changed since the last call (and forgets it).
    pub fn take_dirty(&mut self) -> Dirty {
        core::mem::take(&mut self.dirty)
    }

    /// Counters.
    pub fn counters(&self) -> Counters {
        self.counters
    }

    /// Bytes free in the receive buffer.
    pub fn rx_free(&self) -> usize {
        RX - self.rx.len()
    }

    /// Output bytes waiting for [`Controller::transmit`].
    pub fn pending_output(&self) -> usize {
        self.out.len()
    }

    /// The grbl alarm number in force.
    pub fn alarm(&self) -> Option<u8> {
        self.alarm
    }

    /// Takes bytes from the link: real-time commands are latched at once for the
    /// next [`Controller::poll`]; other bytes go into the receive buffer. Returns how
    /// many bytes were consumed: the shell keeps `bytes[n..]` and offers it again
    /// (the buffer is full until a line leaves it). Real-time bytes are picked out
    /// of that unconsumed tail too, as grbl's receive interrupt picks them out of the
    /// stream whatever the buffer holds: a `?`, `!` or 0x18 behind bytes the buffer
    /// cannot take yet acts now, not when the buffer has room. The ones picked are
    /// removed from the tail, which is rewritten in place (what is kept moves to
    /// the end of `bytes`), so offering it again never acts on them twice; a 0x18
    /// in the tail consumes the tail up to it (it drops what came before it).
    /// Never blocks, never panics.
    pub fn receive(&mut self, bytes: &mut [u8], now: u64) -> usize {
        let n = self.rx.receive(bytes, now, self.link.active);
        self.after_receive();
        n
    }

    /// Answers what the receiver dropped and sends the flow control it asks for.
    fn after_receive(&mut self) {
        for _ in 0..self.rx.take_overlong() {
            self.refuse(11, "line longer than 127 characters");
        }
        if let Some(b) = self.rx.take_flow() {
            self.out.control(b);
        }
    }

    /// Moves output bytes into `out`; how many. Lines end with CR LF.
    pub fn transmit(&mut self, out: &mut [u8]) -> usize {
        self.out.drain(out)
    }

    /// Runs a bounded amount of work at time `now` (ns): soft reset, inputs,
    /// real-time commands, motion events, received lines, a few interpreter steps
    /// feeding `port` until it is full, job state, a status report if asked. Call it
    /// every millisecond or so, and after every `receive`.
    pub fn poll<M, I>(&mut self, now: u64, port: &mut M, io: &mut I, inputs: Inputs)
    where
        M: MotionPort + ?Sized,
        I: MachineIo + ?Sized,
    {
        self.now = now;
        self.rx.end_stale_line(now, self.link.active);
        self.after_receive();
        if core::mem::take(&mut self.rx.latched.reset) {
            self.soft_reset(port, inputs);
        }
        self.read_inputs(port, inputs);
        self.apply_realtime(port, io);
        self.motion_events(port, io);
        if interp_core::MILL {
            self.watch_tool_change(port, io, inputs);
        }
        self.sync(port);
        self.handle_lines(port);
        self.run_startup(port);
        self.run_interpreter(port);
        self.after_motion(port);
        self.watch_stream(port);
        self.rx.release();
        self.after_receive();
        if core::mem::take(&mut self.rx.latched.status) {
            self.status_report(port, inputs);
        }
        if core::mem::take(&mut self.rx.latched.link) {
            self.link_report();
        }
    }

    /// The state a status report would show now.
    pub fn mode<M: MotionPort + ?Sized>(&self, port: &M) -> Mode {
        let st = port.status();
        if self.sleep {
            Mode::Sleep
        } else if self.alarm.is_some() {
            Mode::Alarm
        } else if self.door {
            Mode::Door { open: self.door_open }
        } else if self.homing.is_some() {
            Mode::Home
        } else if self.jog {
            Mode::Jog
        } else if self.hold {
            // (Stopped: a mill's tool change the operator held meanwhile.)
            Mode::Hold { held: st.idle || st.state == State::Held || (interp_core::MILL && st.state == State::Stopped) }
        } else if self.paused && st.state == State::Stopped {
            Mode::Hold { held: true }
        } else if self.check {
            Mode::Check
        } else if !st.idle || (self.job != Job::None && self.interp_busy()) {
            Mode::Run
        } else {
            Mode::Idle
        }
    }

    /// The interpreter has work it can do now (not waiting for text or M02/M30).
    fn interp_busy(&self) -> bool {
        self.interp.has_pending() || (!self.interp_done && self.lookahead.is_none() && !self.stream_drained())
    }

    /// The stream job has run every line received so far.
    pub(crate) fn stream_drained(&self) -> bool {
        self.job == Job::Stream && self.interp.program() == 0 && self.interp.cursor().offset >= self.window.len()
    }

    // ----- received lines -----

    /// Handles complete lines in the receive buffer (a few per poll). Never inlined:
    /// see `soft_reset`.
    #[inline(never)]
    fn handle_lines<M: MotionPort + ?Sized>(&mut self, port: &mut M) {
        for _ in 0..LINES_PER_POLL {
            let mut line: heapless::Vec<u8, RX> = heapless::Vec::new();
            match self.rx.line() {
                Some(l) => {
                    let _ = line.extend_from_slice(l);
                }
                None => return,
            }
            let handled = if self.tape.is_some() { self.tape_line(&line) } else { self.line(&line, port) };
            if handled == Handled::Wait {
                return;
            }
            self.rx.consume_line();
        }
    }

    /// One grbl-mode line (without its LF): the link's framing, then what it asks.
    fn line<M: MotionPort + ?Sized>(&mut self, raw: &[u8], port: &mut M) -> Handled {
        let (text, k) = match self.link.check(trim(raw), self.job == Job::Stream) {
            Checked::Text(text, k) => (trim(text), k),
            Checked::Duplicate(k) => {
                self.answering = Some(k);
                self.ok();
                self.answering = None;
                return Handled::Done;
            }
            Checked::Resend => return self.resend(),
        };
        self.answering = k;
        // A framed line's answer is framed (also the one that switches checksums on).
        self.out.crc |= k.is_some();
        let handled = self.line_text(text, k.is_some(), port);
        self.answering = None;
        if handled == Handled::Done && k.is_some() {
            self.link.accepted();
            // Framed lines come from a sender streaming a file (`$304`, `$306`).
            self.attendance.streamed |= self.job == Job::Stream;
        }
        self.out.crc = self.link.active;
        handled
    }

    /// What a line's text (after the link's framing) asks for; `framed`: it came
    /// with a link checksum.
    fn line_text<M: MotionPort + ?Sized>(&mut self, text: &[u8], framed: bool, port: &mut M) -> Handled {
        match lines::kind(text) {
            Kind::BadByte(b) => {
                self.refuse(1, lines::bad_text(b).as_str());
                Handled::Done
            }
            // An empty line counts as a line of the stream (so its line numbers stay
            // those of the sender's file); in alarm it is just answered.
            Kind::Blank if self.alarm.is_some() => {
                self.ok();
                Handled::Done
            }
            Kind::Dollar(cmd) => {
                self.rx.grbl_seen = true;
                self.dollar(cmd, port)
            }
            // A framed `%` is a record mark: tape DNC software never frames lines.
            Kind::Percent if !framed && self.tape_starts() => {
                self.start_tape();
                Handled::Done
            }
            // Blank lines before a job's first line (a grbl sender's wake-up
            // `\r\n\r\n`) neither start nor number a job; they are grbl traffic:
            // a `%` after them is a record mark (stream.py sends the file's `%`
            // lines, racing its first `?`).
            Kind::Blank if self.job == Job::None => {
                self.rx.grbl_seen = true;
                self.ok();
                Handled::Done
            }
            Kind::Blank | Kind::Percent | Kind::Program(_) => self.program_line(text),
        }
    }

    /// `[MSG:Resend:<expected>]` + `error:88`.
    fn resend(&mut self) -> Handled {
        self.counters.resends = self.counters.resends.saturating_add(1);
        let n = self.link.expected;
        self.refuse(88, lines::resend_text(n).as_str());
        Handled::Done
    }

    /// Whether a `%` line starts tape mode now (setting `$301`): only while Idle,
    /// and by default only from a sender that has not spoken grbl since the last
    /// reset — grbl senders poll `?`, send `$` commands or wake the board with blank
    /// lines when they connect, tape DNC software does not; a grbl sender's `%` is a
    /// record mark.
    fn tape_starts(&self) -> bool {
        let idle = self.job == Job::None && self.alarm.is_none() && !self.check;
        idle && match self.settings.tape_detect {
            0 => !self.rx.grbl_seen,
            1 => true,
            _ => false,
        }
    }

    /// Program text into the window (`ok`), or an error.
    fn program_line(&mut self, text: &[u8]) -> Handled {
        if self.alarm.is_some() {
            self.refuse(9, "Alarm: $X or reset first");
            return Handled::Done;
        }
        if self.sleep || self.jog || self.homing.is_some() || matches!(self.job, Job::Memory(_)) {
            self.refuse(8, "Busy: not while sleeping, jogging, homing or running from memory");
            return Handled::Done;
        }
        let mut dwell: heapless::Vec<u8, 24> = heapless::Vec::new();
        let text = match lines::grbl_sync_dwell(text) {
            Some(seconds) if self.settings.grbl_dwell && dwell.extend_from_slice(b"G04 X").is_ok() => {
                let _ = dwell.extend_from_slice(seconds);
                &dwell[..]
            }
            _ => text,
        };
        if !self.stream_text(text) {
            return Handled::Wait;
        }
        self.ok();
        Handled::Done
    }

    /// Appends program text to the window, starting a stream job if none runs;
    /// false if it does not fit even after dropping text the run is done with.
    fn stream_text(&mut self, text: &[u8]) -> bool {
        if self.job == Job::None {
            self.window.clear();
            self.interp.rewind();
            self.rewind_stream();
            self.job = Job::Stream;
            self.job_worked = false;
            self.record_closed = false;
            self.attendance.start(self.now);
        }
        if self.window.push_line(text) {
            self.window_stuck = false;
            self.attendance.line(self.now);
            return true;
        }
        let need = text.len() + 1 - self.window.free().min(text.len() + 1);
        let keep = self.interp.earliest_offset(0).unwrap_or(self.window.len());
        // Drop at least an eighth of the window at a time (fewer moves), keeping
        // as much recent text as possible for backward jumps.
        let want = need.max(W / 8).min(keep).max(need);
        match self.window.cut_point(want, keep) {
            Some(cut) => {
                self.window.drop_front(cut);
                self.interp.rebase(0, cut);
                self.counters.window_dropped = self.counters.window_dropped.saturating_add(cut as u64);
                let pushed = self.window.push_line(text);
                self.window_stuck = !pushed;
                if pushed {
                    self.attendance.line(self.now);
                }
                pushed
            }
            None => {
                self.window_stuck = true;
                false
            }
        }
    }

    // ----- FANUC tape mode -----

    /// `%` while idle (or `$TAPE`): tape mode.
    pub(crate) fn start_tape(&mut self) {
        self.tape = Some(Tape::Undecided);
        self.rx.set_tape(Some(self.settings.parity_strip));
        self.window.clear();
        self.rewind_stream();
        self.msg(format_args!("Tape mode: XON/XOFF, no ok per block, % ends it"));
        self.ok();
        self.out.control(XON);
    }

    /// One block in tape mode: stored, run or dropped as [`Tape::block`] says.
    fn tape_line(&mut self, raw: &[u8]) -> Handled {
        let Some(tape) = self.tape else { return Handled::Done };
        let (block, next, note) = tape.block(trim(raw), self.settings.tape_mode, self.alarm.is_some());
        if let Some(note) = note {
            self.msg(format_args!("{note}"));
        }
        match block {
            Block::Skip => {}
            Block::End(t) => {
                self.end_tape(t);
                return Handled::Done;
            }
            Block::BadByte(b) => {
                self.msg(format_args!("Tape: byte 0x{b:02X} is not G-code text: block dropped"));
                return Handled::Done;
            }
            Block::Punch(text) => {
                if !self.window.push_line(text) {
                    self.msg(format_args!("Tape: program longer than the window ({W} bytes): not stored"));
                    self.tape = Some(Tape::Punch { failed: true });
                    return Handled::Done;
                }
            }
            Block::Drip { text, first } => {
                // The leading `%` is line 1 of the tape: the program's lines keep the
                // numbers they have in the sender's file.
                if first {
                    if !self.stream_text(b"") {
                        return Handled::Wait;
                    }
                    self.tape = Some(next);
                }
                if !self.stream_text(text) {
                    return Handled::Wait;
                }
                // A drip-fed tape is a program, however slow its reader (`$304`, `$306`).
                self.attendance.streamed = true;
            }
        }
        self.tape = Some(next);
        Handled::Done
    }

    /// The closing `%`: a punched program is stored.
    fn end_tape(&mut self, tape: Tape) {
        self.tape = None;
        self.rx.set_tape(None);
        self.record_closed = true;
        if tape != (Tape::Punch { failed: false }) {
            return;
        }
        if let Some(n) = tape::program_number(self.window.text()) {
            self.memory.remove(n);
        }
        match self.memory.load(self.window.text(), None) {
            Ok(n) => {
                self.dirty.programs = true;
                self.msg(format_args!("Stored O{n:04}"));
            }
            Err(e) => self.msg(format_args!("Tape: not stored: {e}")),
        }
        self.window.clear();
        self.rewind_stream();
    }

    // ----- link lost mid-stream (starve.rs) -----

    /// Once per poll: a streamed program whose link went quiet mid-run, or that was
    /// left unattended with the spindle turning, ends in alarm 4601 (see
    /// [`StarveWatch`], [`Attendance`]). Lines typed by hand (MDI) never do.
    fn watch_stream<M: MotionPort + ?Sized>(&mut self, port: &mut M) {
        let starved = self.starved(port) && self.attendance.streamed;
        let turning = self.interp.state().spindle.dir != SpindleDir::Stop || port.status().rpm != 0;
        let quiet = (self.rx.last_byte, self.settings.starve_timeout_s);
        let unattended = (self.attendance.at, if turning { self.settings.spindle_stream_timeout_s } else { 0 });
        let Some(which) = self.starve.due(self.now, starved, quiet, unattended) else { return };
        let seconds = if which == Starved::Quiet { quiet.1 } else { unattended.1 };
        if which == Starved::Unattended {
            // The sender still polls: its stream stopped, not the link.
            self.msg(format_args!(
                "No program line nor operator action for {seconds} s with the spindle turning ($306)"
            ));
        }
        let line = self.interp.cursor().line;
        let alarm = Alarm::in_program(0, line, AlarmKind::StreamStarved { seconds });
        self.program_alarm(alarm, false, port);
    }

    /// An open stream job that has run out of text and motion.
    fn starved<M: MotionPort + ?Sized>(&self, port: &M) -> bool {
        let open = self.job == Job::Stream && self.job_worked && !self.record_closed && !self.interp_done;
        let waiting = self.alarm.is_none()
            && !self.check
            && !self.hold
            && !self.paused
            && !self.door
            && !self.sleep
            && self.lookahead.is_none()
            && !self.tool_change.waiting();
        open && waiting && !self.interp.has_pending() && self.stream_drained() && port.status().idle
    }

    // ----- replies -----

    /// `ok`; `N<k> ok` for link line `k` (checksums in use).
    pub(crate) fn ok(&mut self) {
        self.counters.ok = self.counters.ok.saturating_add(1);
        match self.answering {
            Some(k) => self.out.fmt(Class::Reply, format_args!("N{k} ok")),
            None => self.out.line(Class::Reply, "ok"),
        }
    }

    /// `[MSG:why]` + `error:n` (`N<k> error:n` for link line `k`).
    pub(crate) fn refuse(&mut self, n: u8, why: &str) {
        self.counters.errors = self.counters.errors.saturating_add(1);
        self.out.fmt(Class::Info, format_args!("[MSG:{why}]"));
        match self.answering {
            Some(k) => self.out.fmt(Class::Reply, format_args!("N{k} error:{n}")),
            None => self.out.fmt(Class::Reply, format_args!("error:{n}")),
        }
    }

    pub(crate) fn msg(&mut self, text: core::fmt::Arguments<'_>) {
        self.out.fmt(Class::Info, format_args!("[MSG:{text}]"));
    }

    fn welcome(&mut self) {
        self.out.line(Class::Reply, WELCOME);
        self.startup_next = 0;
    }

    // ----- job control -----

    /// Soft reset (0x18): motion reset, interpreter reset, window and buffers
    /// cleared, welcome line. Never inlined (nor are the line handling and the
    /// status report): their locals stay out of `poll`'s frame, which is on the
    /// stack under the interpreter's deepest step.
    #[inline(never)]
    fn soft_reset<M: MotionPort + ?Sized>(&mut self, port: &mut M, inputs: Inputs) {
        self.counters.resets = self.counters.resets.saturating_add(1);
        let moving = !port.status().idle;
        port.reset();
        self.interp.reset();
        self.close_job();
        self.check = false;
        self.sleep = false;
        self.door = false;
        self.ovr = [100; 3];
        self.apply_overrides(port);
        self.link = LinkSeq::new();
        self.out.crc = false;
        self.alarm = if inputs.estop { Some(10) } else { None };
        if inputs.estop {
            port.emergency_stop();
        }
        self.welcome();
        if moving && self.alarm.is_none() {
            // Unlike grbl (ALARM:3: its steppers stop dead and may lose steps), the
            // motion core brakes on the path within the axes' acceleration: the
            // position is kept, no alarm, no homing needed.
            self.msg(format_args!("Reset in motion: braked on the path, position kept"));
        }
    }

    /// Drops the job: interpreter rewound to an empty window, holds released; the
    /// interpreter takes the position from the motion core once at rest.
    pub(crate) fn close_job(&mut self) {
        self.interp.rewind();
        self.interp.select_main(0);
        self.window.clear();
        self.rewind_stream();
        self.job = Job::None;
        self.lookahead = None;
        self.window_stuck = false;
        self.interp_done = false;
        self.motion_end = false;
        self.job_worked = false;
        self.record_closed = false;
        self.hold = false;
        self.paused = false;
        self.jog = false;
        self.homing = None;
        // An automatic tool change in progress is aborted: its request drops at
        // the next look (`watch_tool_change`).
        self.tool_change.abort();
        self.need_sync = true;
    }

    /// Positions the interpreter at the start of the window (program 0).
    pub(crate) fn rewind_stream(&mut self) {
        let start = Cursor { program: 0, offset: 0, line: self.window.first_line() };
        self.interp.resume_at(start);
    }

    /// Enters alarm `code` after `[MSG:…]` lines were sent: motion stopped, job
    /// dropped, lines refused with `error:9` until `$X` or reset.
    pub(crate) fn enter_alarm<M: MotionPort + ?Sized>(&mut self, code: u8, port: &mut M) {
        self.out.fmt(Class::Reply, format_args!("ALARM:{code}"));
        self.counters.alarms = self.counters.alarms.saturating_add(1);
        self.alarm = Some(code);
        port.reset();
        self.close_job();
    }

    /// A program or motion alarm: its message line, then `ALARM:2` (overtravel) or
    /// `ALARM:20`.
    pub(crate) fn program_alarm<M: MotionPort + ?Sized>(&mut self, a: Alarm, hint: bool, port: &mut M) {
        let code = a.code();
        match a.program {
            0 => self.msg(format_args!("ALARM {code:04} line {}: {}", a.line, a.kind)),
            p => self.msg(format_args!("ALARM {code:04} O{p:04} line {}: {}", a.line, a.kind)),
        }
        if hint {
            self.msg(format_args!("Not in the stream window: upload the program and run it from memory ($PR=n)"));
        }
        let grbl = match a.kind {
            AlarmKind::OvertravelPositive { .. } | AlarmKind::OvertravelNegative { .. } => 2,
            AlarmKind::EmergencyStop => 10,
            _ => 20,
        };
        self.enter_alarm(grbl, port);
    }

    fn read_inputs<M: MotionPort + ?Sized>(&mut self, port: &mut M, inputs: Inputs) {
        let prev = core::mem::replace(&mut self.prev_inputs, inputs);
        self.panel.inputs = inputs.user;
        self.panel.referenced = if self.homed || !self.settings.homing { 0xff } else { 0 };
        self.door_open = inputs.door;
        if inputs.estop && self.alarm != Some(10) {
            port.emergency_stop();
            self.msg(format_args!("Emergency stop"));
            self.enter_alarm(10, port);
            port.emergency_stop();
            return;
        }
        let tripped = [
            (inputs.limit_x, prev.limit_x, 'X'),
            (inputs.limit_y, prev.limit_y, 'Y'),
            (inputs.limit_z, prev.limit_z, 'Z'),
        ]
        .into_iter()
        .find(|&(now, before, _)| now && !before);
        if let Some((_, _, axis)) = tripped
            && self.settings.hard_limits
            && self.homing.is_none()
            && self.alarm.is_none()
        {
            port.emergency_stop();
            self.msg(format_args!("Hard limit {axis}"));
            self.enter_alarm(1, port);
            return;
        }
        self.rx.latched.hold |= inputs.feed_hold && !prev.feed_hold;
        self.rx.latched.resume |= inputs.cycle_start && !prev.cycle_start;
        self.rx.latched.door |= inputs.door && !prev.door;
    }

    fn apply_realtime<M: MotionPort + ?Sized, I: MachineIo + ?Sized>(&mut self, port: &mut M, io: &mut I) {
        let rt = &self.rx.latched;
        let touched = rt.hold
            || rt.resume
            || rt.door
            || rt.jog_cancel
            || rt.spindle_stop
            || rt.flood
            || rt.mist
            || !rt.overrides.is_empty();
        if touched {
            // The operator is at the machine (`$306`).
            self.attendance.action(self.now);
        }
        if core::mem::take(&mut self.rx.latched.jog_cancel) && self.jog {
            port.reset();
        }
        if core::mem::take(&mut self.rx.latched.door) && self.alarm.is_none() {
            self.door = true;
            self.hold = true;
            port.feed_hold();
        }
        if core::mem::take(&mut self.rx.latched.hold) && self.alarm.is_none() {
            self.counters.holds = self.counters.holds.saturating_add(1);
            if self.jog {
                port.reset();
            } else if self.homing.is_none() {
                self.hold = true;
                port.feed_hold();
            }
        }
        if core::mem::take(&mut self.rx.latched.resume) {
            self.resume(port);
        }
        let overrides = core::mem::take(&mut self.rx.latched.overrides);
        if !overrides.is_empty() {
            for b in overrides {
                override_byte(&mut self.ovr, b);
            }
            self.apply_overrides(port);
        }
        if core::mem::take(&mut self.rx.latched.spindle_stop) && self.hold {
            self.msg(format_args!("Spindle stop in hold is not supported"));
        }
        if core::mem::take(&mut self.rx.latched.flood) {
            self.flood = !self.flood;
            io.m_code(if self.flood { 8 } else { 9 }, 0);
        }
        if core::mem::take(&mut self.rx.latched.mist) {
            self.mist = !self.mist;
            io.m_code(if self.mist { 7 } else { 9 }, 0);
        }
    }

    /// Cycle start: out of a closed door's hold, feed hold, or M00/M01.
    fn resume<M: MotionPort + ?Sized>(&mut self, port: &mut M) {
        if self.alarm.is_some() || (self.door && self.door_open) {
            return;
        }
        self.door = false;
        if self.hold || self.paused {
            self.hold = false;
            self.paused = false;
            // During an automatic tool change only its done goes on.
            if !self.tool_change.waiting() {
                port.cycle_start();
                self.interp.cycle_start();
            }
        }
    }

    pub(crate) fn apply_overrides<M: MotionPort + ?Sized>(&mut self, port: &mut M) {
        port.set_feed_override(self.ovr[0]);
        port.set_rapid_override(self.ovr[1]);
        port.set_spindle_override(self.ovr[2]);
    }

    fn motion_events<M: MotionPort + ?Sized, I: MachineIo + ?Sized>(&mut self, port: &mut M, io: &mut I) {
        while let Some(e) = port.pop_event() {
            match e.kind {
                EventKind::Spindle { dir, rpm } => io.spindle(dir, rpm),
                EventKind::Tool { tool, offset } => io.tool(tool, offset),
                EventKind::Aux { m } => {
                    match m {
                        7 => self.mist = true,
                        8 => self.flood = true,
                        9 => (self.flood, self.mist) = (false, false),
                        _ => {}
                    }
                    io.m_code(m, e.line);
                }
                EventKind::Stop { .. } => self.paused = true,
                // A machining centre's M06 by hand: the core has stopped (and the
                // spindle); the operator loads the tool and presses cycle start.
                // (Only the mill profile makes them: a build without it leaves this out.)
                EventKind::ToolChange(_) if !interp_core::MILL => {}
                EventKind::ToolChange(t) if t.manual => {
                    self.paused = true;
                    self.msg(format_args!("Load T{:02}", t.tool));
                }
                EventKind::ToolChange(t) => self.begin_tool_change(t.tool, e.line, io),
                EventKind::End { .. } => {
                    self.motion_end = true;
                    self.try_finish();
                }
                EventKind::Starved => {}
                EventKind::Alarm(a) => {
                    if self.alarm.is_none() {
                        self.program_alarm(a, false, port);
                    }
                }
            }
        }
    }

    /// A mill's M06 by the tool changer: the motion core has stopped (and the
    /// spindle); the request goes out and [`Self::watch_tool_change`] waits.
    fn begin_tool_change<I: MachineIo + ?Sized>(&mut self, tool: u16, line: u32, io: &mut I) {
        self.msg(format_args!("Tool change T{tool:02} (tool changer)"));
        io.tool_change_request(Some(tool));
        self.tool_change.start(ToolChangeWait::new(tool, line, self.now, self.prev_inputs.tool_change_done));
    }

    /// Once per poll on a mill build: the tool changer's done ends the wait (the
    /// motion core goes on unless the operator held it meanwhile: then cycle start
    /// does), its absence for `$313` s is alarm 4511; a change aborted (reset,
    /// alarm) drops the request.
    fn watch_tool_change<M, I>(&mut self, port: &mut M, io: &mut I, inputs: Inputs)
    where
        M: MotionPort + ?Sized,
        I: MachineIo + ?Sized,
    {
        let Some(mut wait) = self.tool_change.take() else {
            if self.tool_change.take_request() {
                io.tool_change_request(None);
            }
            return;
        };
        match wait.step(self.now, inputs.tool_change_done, self.interp.config().tool_change_timeout.seconds()) {
            ToolChangeStep::Waiting => self.tool_change.put_back(wait),
            ToolChangeStep::Done => {
                self.tool_change.take_request();
                io.tool_change_request(None);
                if !self.hold {
                    port.cycle_start();
                }
            }
            ToolChangeStep::TimedOut { seconds } => {
                self.tool_change.take_request();
                io.tool_change_request(None);
                let kind = AlarmKind::ToolChangeTimeout { tool: wait.tool, seconds };
                self.program_alarm(Alarm::new(wait.line, kind), false, port);
            }
        }
    }

    /// Ends the job once the interpreter has read M02/M30 and the motion core has
    /// run it (or at once in check mode, and for M02/M30 outside a job).
    pub(crate) fn try_finish(&mut self) {
        if self.job == Job::None || (self.interp_done && (self.motion_end || self.check)) {
            self.end_job();
        }
    }

    /// M02/M30 has run: `[MSG:Pgm End]`; a stream keeps what arrived after it.
    fn end_job(&mut self) {
        self.msg(format_args!("Pgm End"));
        self.interp_done = false;
        self.job_worked = false;
        self.record_closed = false;
        self.motion_end = false;
        self.paused = false;
        match self.job {
            Job::Stream => {
                let c = self.interp.cursor();
                let rest = if c.program == 0 { c.offset.min(self.window.len()) } else { self.window.len() };
                self.window.drop_front(rest);
                if self.window.is_empty() {
                    self.window.clear();
                }
                self.interp.rewind();
                self.rewind_stream();
                self.job = if self.window.is_empty() { Job::None } else { Job::Stream };
            }
            Job::Memory(_) => {
                self.interp.select_main(0);
                self.rewind_stream();
                self.job = Job::None;
            }
            Job::None => {}
        }
    }

    /// Takes the interpreter's position from the motion core once it is at rest.
    fn sync<M: MotionPort + ?Sized>(&mut self, port: &mut M) {
        if self.need_sync {
            let st = port.status();
            if st.idle {
                self.interp.set_machine_position(st.position);
                self.need_sync = false;
            }
        }
    }

    /// Runs the startup blocks `$N0`, `$N1` (one per poll) after power-on and
    /// reset, as MDI blocks: `>block:ok` or `>block:error:20` with the alarm.
    fn run_startup<M: MotionPort + ?Sized>(&mut self, port: &mut M) {
        while self.startup_next < 2 {
            if self.alarm.is_some() || self.job != Job::None || self.need_sync || self.check {
                return;
            }
            let i = usize::from(self.startup_next);
            self.startup_next += 1;
            let text = self.startup[i].clone();
            if text.is_empty() {
                continue;
            }
            match self.interp.mdi(text.as_bytes(), &self.panel, &mut PortSink(&mut *port)) {
                Ok(Progress::Blocked) => self.startup_next -= 1,
                Ok(_) => self.out.fmt(Class::Reply, format_args!(">{text}:ok")),
                Err(a) => {
                    self.msg(format_args!("ALARM {:04}: {}", a.code(), a.kind));
                    self.out.fmt(Class::Reply, format_args!(">{text}:error:20"));
                }
            }
            return;
        }
    }

    /// Whether the interpreter may step now.
    fn may_run(&self) -> bool {
        self.alarm.is_none()
            && !self.sleep
            && !self.need_sync
            && !self.jog
            && self.homing.is_none()
            && self.job != Job::None
            && !self.interp_done
    }

    fn run_interpreter<M: MotionPort + ?Sized>(&mut self, port: &mut M) {
        for _ in 0..STEPS_PER_POLL {
            if !self.may_run() || self.waiting_for_text(port) {
                return;
            }
            let store = Store { window: &self.window, memory: &self.memory };
            // One interpreter for both sinks (a `dyn` sink: the interpreter's code
            // is not duplicated for check mode; a call per action delivered).
            let (mut discard, mut to_port) = (Discard, PortSink(&mut *port));
            let sink: &mut dyn CanonSink = if self.check { &mut discard } else { &mut to_port };
            // The non-generic entry: the interpreter's per-block path is compiled
            // in interp-core at its opt-level, not in the (size-built) firmware crate.
            let r = self.interp.step_dyn(&store, &self.panel, sink);
            if let Some((code, line)) = self.interp.take_notice() {
                // A cycle message (SINUMERIK 62xxx): shown, the job goes on (or waits
                // for cycle start where the cycle says so).
                let text = interp_core::alarm::cycle_message(code).unwrap_or("");
                self.msg(format_args!("line {line}: message {code}: {text}"));
            }
            match r {
                Ok(Progress::Blocked | Progress::Paused) => return,
                Ok(Progress::Executed { .. }) => self.job_worked = true,
                Ok(Progress::Ended) => {
                    self.interp_done = true;
                    self.try_finish();
                    return;
                }
                Ok(_) => {}
                Err(a) => {
                    self.interp_alarm(a, port);
                    return;
                }
            }
        }
    }

    /// An interpreter alarm: a look-ahead in a stream that only lacks text waits
    /// for it; anything else is a program alarm.
    fn interp_alarm<M: MotionPort + ?Sized>(&mut self, a: Alarm, port: &mut M) {
        let missing_text = a.kind.waits_for_text();
        let at = self.interp.block_start();
        let at_end = at.offset >= self.window.len();
        if self.job == Job::Stream && a.program == 0 && missing_text {
            if a.kind == AlarmKind::EndOfRecord {
                if at_end {
                    // Caught up with the sender: wait for the next line.
                    self.interp.resume_at(at);
                    return;
                }
            } else {
                self.interp.resume_at(at);
                self.lookahead = Some(Wait { received: self.window.received(), alarm: a });
                self.counters.lookahead_waits = self.counters.lookahead_waits.saturating_add(1);
                return;
            }
        }
        self.program_alarm(a, false, port);
    }

    /// A stream waits for text: at the end of what arrived, or a look-ahead waiting
    /// for more (given up when the link is quiet or the window cannot take more).
    fn waiting_for_text<M: MotionPort + ?Sized>(&mut self, port: &mut M) -> bool {
        if let Some(w) = self.lookahead {
            if self.window.received() > w.received && !self.window_stuck {
                self.lookahead = None;
                return false;
            }
            let quiet_ns = u64::from(self.settings.lookahead_wait_ms) * 1_000_000;
            if self.window_stuck || self.now.saturating_sub(self.rx.last_line_byte) >= quiet_ns {
                self.lookahead = None;
                self.program_alarm(w.alarm, true, port);
            }
            return true;
        }
        !self.interp.has_pending() && !self.interp.is_ended() && self.stream_drained()
    }

    /// Jog and homing completion.
    fn after_motion<M: MotionPort + ?Sized>(&mut self, port: &mut M) {
        if self.jog && port.status().idle {
            self.jog = false;
            self.need_sync = true;
            self.sync(port);
        }
        if let Some(h) = self.homing.as_mut() {
            let i = &self.prev_inputs;
            let home = [i.home_x, i.home_y, i.home_z];
            match h.step(&port.status(), home, self.interp.config(), &self.settings, port) {
                Homed::Busy => {}
                Homed::Failed => {
                    self.homing = None;
                    self.msg(format_args!("Homing failed: no home switch found"));
                    self.enter_alarm(9, port);
                }
                Homed::Done(pos) => {
                    self.homing = None;
                    self.homed = true;
                    self.interp.set_machine_position(pos);
                    self.msg(format_args!("Homed"));
                }
            }
        }
    }

    /// Sends `<…>` with the motion core's snapshot.
    #[inline(never)]
    fn status_report<M: MotionPort + ?Sized>(&mut self, port: &mut M, inputs: Inputs) {
        let st: MotionStatus = port.status();
        let cfg = self.interp.config();
        let mode = self.mode(port);
        let mut state: heapless::String<8> = heapless::String::new();
        let name = match mode {
            Mode::Idle => "Idle",
            Mode::Run => "Run",
            // grbl 1.1: Hold:0 = hold complete, ready to resume; Hold:1 = stopping.
            Mode::Hold { held: false } => "Hold:1",
            Mode::Hold { held: true } => "Hold:0",
            Mode::Alarm => "Alarm",
            Mode::Check => "Check",
            Mode::Jog => "Jog",
            Mode::Home => "Home",
            Mode::Door { open: true } => "Door:1",
            Mode::Door { open: false } => "Door:0",
            Mode::Sleep => "Sleep",
        };
        let _ = state.push_str(name);
        let wco = if st.idle { self.interp.state().work_to_machine(cfg) } else { st.work_offset };
        let feed = st.feed.saturating_add(500_000) / 1_000_000;
        let mut pins: heapless::String<8> = heapless::String::new();
        for (on, c) in [
            (inputs.limit_x, 'X'),
            (inputs.limit_y, 'Y'),
            (inputs.limit_z, 'Z'),
            (inputs.feed_hold, 'H'),
            (inputs.cycle_start, 'S'),
            (inputs.door, 'D'),
            (inputs.estop, 'E'),
        ] {
            if on {
                let _ = pins.push(c);
            }
        }
        let sep = if pins.is_empty() { "" } else { "|Pn:" };
        // With link checksums: the last link line accepted, so that a sender whose
        // answers were lost to line noise can find its place again.
        let mut link: heapless::String<16> = heapless::String::new();
        if self.link.active {
            let _ = core::fmt::write(&mut link, format_args!("|Lk:{}", self.link.expected.saturating_sub(1)));
        }
        self.out.fmt(
            Class::Info,
            format_args!(
                "<{state}|MPos:{}|FS:{feed},{}|Bf:{},{}|Ln:{}|WCO:{}|Ov:{},{},{}{sep}{pins}{link}>",
                Xyz::of(&st.position, cfg),
                st.rpm,
                st.capacity.saturating_sub(st.queued),
                RX - self.rx.len(),
                st.line,
                Xyz::of(&wco, cfg),
                self.ovr[0],
                self.ovr[1],
                self.ovr[2],
            ),
        );
    }

    /// `[LK:<last link line accepted>,<free receive-buffer bytes>]`, the answer to
    /// ENQ: what a checksum sender needs to find its place (its answers lost, or
    /// its lines lost on the way) in ~20 bytes that line noise spares far more
    /// often than a ~115-byte status report.
    #[inline(never)]
    fn link_report(&mut self) {
        let last = self.link.expected.saturating_sub(1);
        self.out.fmt(Class::Info, format_args!("[LK:{last},{}]", RX - self.rx.len()));
    }

    /// Mm of an internal length, for messages.
    pub(crate) fn mm(v: i64) -> Mm {
        Mm(v)
    }
}

/// Applies an override byte 0x90–0x9D to (feed, rapid, spindle) percentages.
fn override_byte(ovr: &mut [u16; 3], b: u8) {
    let step = |v: u16, d: i16, lo: u16, hi: u16| (v as i16 + d).clamp(lo as i16, hi as i16) as u16;
    match b {
        0x90 => ovr[0] = 100,
        0x91 => ovr[0] = step(ovr[0], 10, 10, 200),
        0x92 => ovr[0] = step(ovr[0], -10, 10, 200),
        0x93 => ovr[0] = step(ovr[0], 1, 10, 200),
        0x94 => ovr[0] = step(ovr[0], -1, 10, 200),
        0x95 => ovr[1] = 100,
        0x96 => ovr[1] = 50,
        0x97 => ovr[1] = 25,
        0x99 => ovr[2] = 100,
        0x9A => ovr[2] = step(ovr[2], 10, 50, 200),
        0x9B => ovr[2] = step(ovr[2], -10, 50, 200),
        0x9C => ovr[2] = step(ovr[2], 1, 50, 200),
        0x9D => ovr[2] = step(ovr[2], -1, 50, 200),
        _ => {}
    }
}

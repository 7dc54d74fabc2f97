//! A test rig: the controller driving a real `MotionCore<64>` through a port that
//! records every canonical action it accepts, a 1 ms poll/tick loop with a
//! synthetic spindle encoder (count = rpm · cpr · t), and senders.
#![allow(dead_code)]

use std::collections::VecDeque;

use controller::{Controller, Inputs, MachineIo, MotionPort, MotionStatus};
use interp_core::axis::Pos;
use interp_core::canon::{Canon, CanonSink, Full, SpindleDir};
use interp_core::program::ProgramMemory;
use interp_core::{AlarmKind, Interpreter, MachineConfig, Panel, ProgramStore, Progress, SingleProgram};
use motion_core::motion::{Event, Feedback, MotionCore};

/// The controller under test: 8 KiB window, 16 KiB program memory.
pub type Ctl = Controller<8192, 16384, 16, 512>;

/// The port: the motion core, recording what it accepted.
pub struct Rec {
    pub core: Box<MotionCore<64>>,
    pub pushed: Vec<Canon>,
}

impl MotionPort for Rec {
    fn push(&mut self, c: Canon) -> Result<(), Full> {
        MotionPort::push(&mut *self.core, c)?;
        self.pushed.push(c);
        Ok(())
    }
    fn feed_hold(&mut self) {
        self.core.feed_hold();
    }
    fn cycle_start(&mut self) {
        self.core.cycle_start();
    }
    fn reset(&mut self) {
        self.core.reset();
    }
    fn emergency_stop(&mut self) {
        self.core.emergency_stop();
    }
    fn set_feed_override(&mut self, pct: u16) {
        self.core.set_feed_override(pct);
    }
    fn set_rapid_override(&mut self, pct: u16) {
        self.core.set_rapid_override(pct);
    }
    fn set_spindle_override(&mut self, pct: u16) {
        MotionPort::set_spindle_override(&mut *self.core, pct);
    }
    fn set_position(&mut self, pos: Pos) -> bool {
        self.core.set_position(pos)
    }
    fn reconfigure(&mut self, cfg: &MachineConfig) -> Result<(), AlarmKind> {
        MotionPort::reconfigure(&mut *self.core, cfg)
    }
    fn pop_event(&mut self) -> Option<Event> {
        self.core.pop_event()
    }
    fn status(&self) -> MotionStatus {
        MotionPort::status(&*self.core)
    }
}

/// Outputs: what the motion events switched.
#[derive(Default)]
pub struct Io {
    pub m: Vec<u16>,
    pub tools: Vec<(u16, u16)>,
    pub spindle: Vec<(SpindleDir, u32)>,
    /// The tool changer's request outputs, in order (`None`: dropped).
    pub requests: Vec<Option<u16>>,
}

impl MachineIo for Io {
    fn m_code(&mut self, m: u16, _line: u32) {
        self.m.push(m);
    }
    fn tool(&mut self, tool: u16, offset: u16) {
        self.tools.push((tool, offset));
    }
    fn spindle(&mut self, dir: SpindleDir, rpm: u32) {
        self.spindle.push((dir, rpm));
    }
    fn tool_change_request(&mut self, tool: Option<u16>) {
        self.requests.push(tool);
    }
}

/// Controller + motion core + time.
pub struct Rig<C = Ctl> {
    pub ctl: Box<C>,
    pub port: Rec,
    pub io: Io,
    pub inputs: Inputs,
    /// ns.
    pub now: u64,
    /// Bytes waiting to be taken by `receive`.
    pub pending: VecDeque<u8>,
    /// Every byte the controller sent.
    pub sent: Vec<u8>,
    /// Bytes of `sent` already handed out by `take_lines`.
    taken: usize,
    spindle_count: f64,
    pub cfg: MachineConfig,
}

pub const TICK: u64 = 1_000_000;

/// The trait the rig needs of a controller type (any capacities).
pub trait Drive {
    fn receive(&mut self, b: &mut [u8], now: u64) -> usize;
    fn poll(&mut self, now: u64, port: &mut Rec, io: &mut Io, inputs: Inputs);
    fn transmit(&mut self, out: &mut [u8]) -> usize;
    fn make(cfg: MachineConfig) -> Box<Self>;
}

impl<const W: usize, const T: usize, const P: usize, const S: usize> Drive for Controller<W, T, P, S> {
    fn receive(&mut self, b: &mut [u8], now: u64) -> usize {
        Controller::receive(self, b, now)
    }
    fn poll(&mut self, now: u64, port: &mut Rec, io: &mut Io, inputs: Inputs) {
        Controller::poll(self, now, port, io, inputs)
    }
    fn transmit(&mut self, out: &mut [u8]) -> usize {
        Controller::transmit(self, out)
    }
    fn make(cfg: MachineConfig) -> Box<Self> {
        let mut c = Box::new(Controller::new(cfg, Pos::ZERO));
        c.interpreter_mut().plug(&interp_siemens::SINUMERIK);
        c
    }
}

impl Rig<Ctl> {
    pub fn new() -> Self {
        Rig::with(MachineConfig::default())
    }
}

impl<C: Drive> Rig<C> {
    pub fn with(cfg: MachineConfig) -> Self {
        let core = Box::new(MotionCore::new(&cfg, Pos::ZERO).expect("machine"));
        Rig {
            ctl: C::make(cfg.clone()),
            port: Rec { core, pushed: Vec::new() },
            io: Io::default(),
            inputs: Inputs::default(),
            now: 0,
            pending: VecDeque::new(),
            sent: Vec::new(),
            taken: 0,
            spindle_count: 0.0,
            cfg,
        }
    }

    /// Queues bytes for the controller (taken as fast as it accepts them).
    pub fn send(&mut self, bytes: &[u8]) {
        self.pending.extend(bytes);
    }

    /// Offers the pending bytes; how many it took.
    pub fn feed(&mut self) -> usize {
        let mut buf: Vec<u8> = self.pending.iter().copied().collect();
        let n = self.ctl.receive(&mut buf, self.now);
        // What was not taken, with the real-time bytes picked out of it.
        self.pending = buf.get(n..).unwrap_or_default().iter().copied().collect();
        n
    }

    /// One millisecond: bytes in, poll, motion period, steps, bytes out.
    pub fn step(&mut self) {
        self.feed();
        self.ctl.poll(self.now, &mut self.port, &mut self.io, self.inputs);
        self.tick_motion();
        let mut out = [0u8; 4096];
        let n = self.ctl.transmit(&mut out);
        self.sent.extend_from_slice(&out[..n]);
        self.now += TICK;
    }

    /// The motion core's period with a synthetic encoder at the commanded speed.
    pub fn tick_motion(&mut self) {
        let cpr = f64::from(self.cfg.spindle.encoder_cpr);
        let (dir, rpm) = self.port.core.spindle_output();
        let sign = match dir {
            SpindleDir::Cw => 1.0,
            SpindleDir::Ccw => -1.0,
            SpindleDir::Stop => 0.0,
        };
        let before = self.spindle_count;
        self.spindle_count += sign * f64::from(rpm) * cpr * (TICK as f64 / 1e9) / 60.0;
        let count = self.spindle_count.floor() as i64;
        let index = Some(count.div_euclid(cpr as i64) * cpr as i64);
        self.port.core.tick(self.now, Feedback { count, index });
        if self.port.core.wants_encoder_edges() {
            // Locked to the spindle: each count of the period with its own time, as
            // the firmware's count interrupt and sim's encoder deliver them.
            self.encoder_edges(before, self.spindle_count);
        }
        self.drain_steps(self.now + TICK);
    }

    /// The counts from `from` to `to` (the encoder's position, counts) spread
    /// evenly over the period, each given to the core after the steps due before it.
    fn encoder_edges(&mut self, from: f64, to: f64) {
        let (a, b) = (from.floor() as i64, to.floor() as i64);
        let counts: Vec<i64> = if b >= a { (a + 1..=b).collect() } else { (b..a).rev().collect() };
        let n = counts.len() as u64;
        for (i, c) in counts.into_iter().enumerate() {
            let t = self.now + TICK * (i as u64 + 1) / (n + 1);
            self.drain_steps(t);
            self.port.core.on_encoder(t, c);
        }
    }

    /// Takes every step event due before `until`.
    fn drain_steps(&mut self, until: u64) {
        for axis in 0..4 {
            while self.port.core.next_step(axis, until).is_some() {}
        }
    }

    /// Runs `ms` milliseconds.
    pub fn run_ms(&mut self, ms: u64) {
        for _ in 0..ms {
            self.step();
        }
    }

    /// Runs until `pred` holds or `ms` milliseconds passed; whether it held.
    pub fn run_until(&mut self, ms: u64, mut pred: impl FnMut(&mut Self) -> bool) -> bool {
        for _ in 0..ms {
            if pred(self) {
                return true;
            }
            self.step();
        }
        pred(self)
    }

    /// All output as text lines.
    pub fn lines(&self) -> Vec<String> {
        String::from_utf8_lossy(&self.sent)
            .split("\r\n")
            .filter(|l| !l.is_empty())
            .map(|l| unframe(l.trim_matches(|c| c == '\u{11}' || c == '\u{13}')))
            .collect()
    }

    /// Output lines not handed out before.
    pub fn take_lines(&mut self) -> Vec<String> {
        self.take_raw_lines().iter().map(|l| unframe(l)).collect()
    }

    /// The lines as the controller sent them (with link checksums: `N<k> ok*<crc>`).
    pub fn take_raw_lines(&mut self) -> Vec<String> {
        // Whole lines only, from the first byte not handed out yet.
        let rest = &self.sent[self.taken.min(self.sent.len())..];
        let Some(end) = rest.windows(2).rposition(|w| w == b"\r\n") else { return Vec::new() };
        let chunk = String::from_utf8_lossy(&rest[..end + 2]).to_string();
        self.taken += end + 2;
        chunk
            .split("\r\n")
            .filter(|l| !l.is_empty())
            .map(|l| l.trim_matches(|c| c == '\u{11}' || c == '\u{13}').to_string())
            .collect()
    }

    /// Sends `?` and returns the report (runs a few ms).
    pub fn status(&mut self) -> String {
        self.take_lines();
        self.send(b"?");
        for _ in 0..20 {
            self.step();
            if let Some(l) = self.lines().iter().rev().find(|l| l.starts_with('<')) {
                let l = l.clone();
                if self.take_lines().contains(&l) {
                    return l;
                }
            }
        }
        panic!("no status report; output: {:?}", self.lines());
    }

    /// Sends one line and runs until it is answered; the answer lines.
    pub fn command(&mut self, line: &str) -> Vec<String> {
        self.take_lines();
        self.send(line.as_bytes());
        self.send(b"\n");
        let mut got = Vec::new();
        for _ in 0..2000 {
            self.step();
            got.extend(self.take_lines());
            if got.iter().any(|l| l == "ok" || l.starts_with("error:")) {
                return got;
            }
        }
        panic!("no answer to {line:?}: {got:?}");
    }

    /// Streams `text` line by line with grbl character counting (at most 128
    /// bytes unanswered) until every line is answered and the motion is idle
    /// after `[MSG:Pgm End]` or an alarm; the answers.
    pub fn stream(&mut self, text: &str, max_ms: u64) -> Vec<String> {
        let lines: Vec<&str> = text.lines().collect();
        let mut sender = Counting::new(lines.iter().map(|l| l.to_string()).collect());
        let mut answers = Vec::new();
        for _ in 0..max_ms {
            sender.pump(self);
            self.step();
            for l in self.take_lines() {
                sender.answer(&l);
                answers.push(l);
            }
            let done = answers.iter().any(|l| l == "[MSG:Pgm End]" || l.starts_with("ALARM:"));
            if sender.finished() && done && self.port.core.is_idle() {
                return answers;
            }
        }
        answers
    }
}

/// A character-counting sender.
pub struct Counting {
    lines: VecDeque<String>,
    in_flight: VecDeque<usize>,
}

impl Counting {
    pub fn new(lines: Vec<String>) -> Self {
        Counting { lines: lines.into(), in_flight: VecDeque::new() }
    }

    /// Sends what fits into the 128 bytes.
    pub fn pump<C: Drive>(&mut self, rig: &mut Rig<C>) {
        while let Some(l) = self.lines.front() {
            let n = l.len() + 1;
            if self.in_flight.iter().sum::<usize>() + n > 128 {
                break;
            }
            rig.send(l.as_bytes());
            rig.send(b"\n");
            self.in_flight.push_back(n);
            self.lines.pop_front();
        }
    }

    pub fn answer(&mut self, line: &str) {
        if line == "ok" || line.starts_with("error:") {
            self.in_flight.pop_front();
        }
    }

    pub fn finished(&self) -> bool {
        self.lines.is_empty() && self.in_flight.is_empty()
    }
}

/// A sink that keeps everything.
#[derive(Default)]
pub struct VecSink(pub Vec<Canon>);

impl CanonSink for VecSink {
    fn push(&mut self, c: Canon) -> Result<(), Full> {
        self.0.push(c);
        Ok(())
    }
}

/// What the interpreter produces for `text` run directly (program 0), with
/// `memory` for M98; M00/M01 answered with cycle start; stops at the end or the
/// first alarm.
pub fn direct(text: &str, memory: Option<&ProgramMemory<16384, 16, 512>>) -> Vec<Canon> {
    struct Both<'a>(&'a [u8], Option<&'a ProgramMemory<16384, 16, 512>>);
    impl ProgramStore for Both<'_> {
        fn text(&self, id: u32) -> Option<&[u8]> {
            if id == 0 { Some(self.0) } else { self.1?.text(id) }
        }
        fn start(&self, id: u32) -> Option<interp_core::program::Cursor> {
            if id == 0 { SingleProgram(self.0).start(0) } else { self.1?.start(id) }
        }
        fn find_sequence(&self, n: u32, from: interp_core::program::Cursor) -> Option<interp_core::program::Cursor> {
            if from.program == 0 {
                SingleProgram(self.0).find_sequence(n, from)
            } else {
                self.1?.find_sequence(n, from)
            }
        }
    }
    let mut interp = Interpreter::new(MachineConfig::default());
    let store = Both(text.as_bytes(), memory);
    let mut sink = VecSink::default();
    for _ in 0..10_000_000 {
        match interp.step(&store, &Panel::default(), &mut sink) {
            Ok(Progress::Ended) | Err(_) => break,
            Ok(Progress::Paused) => interp.cycle_start(),
            Ok(_) => {}
        }
    }
    sink.0
}

/// The number after `key` in a status report (`MPos:` → the X value …).
pub fn field<'a>(report: &'a str, key: &str) -> &'a str {
    let start = report.find(key).map(|i| i + key.len()).unwrap_or_else(|| panic!("{key} in {report}"));
    let rest = &report[start..];
    &rest[..rest.find(['|', '>']).unwrap_or(rest.len())]
}

/// A line of the controller without its link framing (checksums in use): the
/// `*<crc>` checked and dropped, an answer's `N<k> ` dropped (`N7 ok` → `ok`).
pub fn unframe(line: &str) -> String {
    let text = match line.rsplit_once('*') {
        Some((text, crc)) if crc.len() == 4 && crc.bytes().all(|b| b.is_ascii_hexdigit()) => {
            assert_eq!(
                u16::from_str_radix(crc, 16).ok(),
                Some(controller::crc::crc16(text.as_bytes())),
                "a damaged line from the controller: {line:?}"
            );
            text
        }
        _ => line,
    };
    match text.strip_prefix('N').and_then(|t| t.split_once(' ')) {
        Some((k, reply)) if k.bytes().all(|b| b.is_ascii_digit()) && (reply == "ok" || reply.starts_with("error:")) => {
            reply.to_string()
        }
        _ => text.to_string(),
    }
}

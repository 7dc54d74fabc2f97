//! A small fake of the board for end-to-end tests of the link commands: a thread on
//! the master side of a pty pair that speaks the protocol of docs/PROTOCOL.md as far
//! as the host tools use it. It only talks bytes on the pty, so a test can swap it
//! for the real board (`lathe board`) by using that board's port path instead.
//!
//! It models the 128-byte receive buffer: bytes are taken off the pty as they come,
//! one line leaves the buffer (and is answered) every [`Script::line_period`], and the
//! most bytes ever waiting is recorded — a sender that counts correctly never makes
//! it exceed 128. A `%` line starts tape mode only when nothing grbl-like (`?`, a
//! real-time byte, a `$` line) came since the last reset ($301=0); in tape mode it
//! sends XOFF at ¾ full and XON at ¼.

use std::collections::BTreeMap;
use std::io::{Read, Write};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use lathe::link::crc::crc16;
use serialport::{SerialPort, TTYPort};

/// What the fake does besides answering `ok`.
#[derive(Clone, Debug)]
pub struct Script {
    /// How long a line takes to leave the receive buffer.
    pub line_period: Duration,
    /// Refuse the line holding this text with `error:20` and a message.
    pub refuse: Option<&'static str>,
    /// Raise a program alarm at the line holding this text.
    pub alarm: Option<&'static str>,
    /// Checksum mode: the first time this link line number arrives, treat it as damaged.
    pub damage: Option<u32>,
    /// Checksum mode: the first time this link line number arrives, it is lost on
    /// the way (no answer, not taken).
    pub lose: Option<u32>,
    /// Checksum mode: every status report arrives damaged (its CRC wrong), as a
    /// ~115-byte report mostly does under 3 % line noise — until the line lost
    /// ([`Script::lose`]) has been taken (the sender's end needs an Idle report).
    pub garble_reports: bool,
    /// Start in state Alarm (after every reset too).
    pub locked: bool,
    /// Never send the welcome line.
    pub mute: bool,
    /// Fall silent for good once this many program lines were taken (a dead link).
    pub dies_after: Option<u32>,
}

impl Default for Script {
    fn default() -> Self {
        Script {
            line_period: Duration::from_millis(2),
            refuse: None,
            alarm: None,
            damage: None,
            lose: None,
            garble_reports: false,
            locked: false,
            mute: false,
            dies_after: None,
        }
    }
}

/// What the fake saw, for the test to check afterwards.
#[derive(Clone, Debug, Default)]
pub struct Seen {
    /// Every line taken from the receive buffer, in order (grbl mode).
    pub lines: Vec<String>,
    /// The most bytes waiting in the receive buffer at once.
    pub max_buffered: usize,
    /// Soft resets received.
    pub resets: u32,
    /// Feed holds received.
    pub holds: u32,
    /// Bytes received while XOFF was in force (tape mode).
    pub after_xoff: usize,
    /// XOFFs sent.
    pub xoffs: u32,
    /// Programs stored by tape uploads: number → text.
    pub programs: BTreeMap<u32, String>,
    /// Blocks drip-fed in tape mode.
    pub drip: Vec<String>,
    /// Settings written.
    pub settings: Vec<String>,
}

/// A running fake board.
pub struct FakeBoard {
    /// The port path the host tools open.
    pub path: String,
    stop: Arc<AtomicBool>,
    seen: Arc<Mutex<Seen>>,
    thread: Option<JoinHandle<()>>,
    _slave: TTYPort,
}

impl FakeBoard {
    /// Starts a fake board following `script` on a new pty pair.
    pub fn start(script: Script) -> FakeBoard {
        let (master, slave) = TTYPort::pair().expect("a pty pair");
        let path = slave.name().expect("the pty has a name");
        let stop = Arc::new(AtomicBool::new(false));
        let seen = Arc::new(Mutex::new(Seen::default()));
        let mut state = State::new(master, script, seen.clone());
        let flag = stop.clone();
        let thread = std::thread::spawn(move || {
            while !flag.load(Ordering::Relaxed) {
                state.step();
            }
        });
        FakeBoard { path, stop, seen, thread: Some(thread), _slave: slave }
    }

    /// Stops the fake and returns what it saw.
    pub fn finish(mut self) -> Seen {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            t.join().expect("the fake board thread ends");
        }
        self.seen.lock().expect("seen").clone()
    }
}

/// The fake's machine state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Machine {
    Idle,
    Alarm,
}

/// Where tape mode is.
#[derive(Clone, Debug, PartialEq, Eq)]
enum TapeMode {
    Off,
    /// Receiving: whether the first block decided storing (Some(number)) or running.
    On {
        store: Option<Option<u32>>,
        text: String,
    },
}

/// The fake's state, owned by its thread.
struct State {
    port: TTYPort,
    script: Script,
    seen: Arc<Mutex<Seen>>,
    rx: Vec<u8>,
    machine: Machine,
    held: bool,
    busy_until: Instant,
    next_line_at: Instant,
    line_no: u32,
    expected: u32,
    /// Link checksums in use: lines carry `*<crc>`, answers `N<k> `, reports `Lk:`,
    /// real-time commands other than `?` come with a LF (swallowed).
    checksums: bool,
    /// The link line being answered.
    answering: Option<u32>,
    /// A LF after a real-time command is part of it.
    swallow_lf: bool,
    damaged: bool,
    lost: bool,
    tape: TapeMode,
    xoff: bool,
    /// Something grbl-like (`?`, a real-time byte, a `$` line) came since the last
    /// reset: a `%` is then a record mark, not the start of tape mode ($301=0).
    grbl_spoken: bool,
    /// A real-time byte came behind this many buffered bytes: it counts once they
    /// are taken (as on the board: a `?` right behind `%` leaves it tape mode's).
    grbl_after: Option<usize>,
    settings: BTreeMap<u32, String>,
}

impl State {
    fn new(mut port: TTYPort, script: Script, seen: Arc<Mutex<Seen>>) -> State {
        port.set_timeout(Duration::from_millis(1)).expect("timeout");
        let machine = if script.locked { Machine::Alarm } else { Machine::Idle };
        let settings = BTreeMap::from([(110, "6000.000".to_owned()), (300, "0".to_owned())]);
        let now = Instant::now();
        State {
            port,
            script,
            seen,
            rx: Vec::new(),
            machine,
            held: false,
            busy_until: now,
            next_line_at: now,
            line_no: 0,
            expected: 1,
            checksums: false,
            answering: None,
            swallow_lf: false,
            damaged: false,
            lost: false,
            tape: TapeMode::Off,
            xoff: false,
            grbl_spoken: false,
            grbl_after: None,
            settings,
        }
    }

    fn seen(&self) -> std::sync::MutexGuard<'_, Seen> {
        self.seen.lock().expect("seen")
    }

    fn send(&mut self, text: &str) {
        if self.script.dies_after.is_some_and(|n| self.line_no >= n) {
            return;
        }
        let _ = self.port.write_all(text.as_bytes());
    }

    fn line(&mut self, text: &str) {
        let text = match self.answering {
            Some(k) if text == "ok" || text.starts_with("error:") => format!("N{k} {text}"),
            _ => text.to_owned(),
        };
        if self.checksums {
            let crc = crc16(text.as_bytes());
            self.send(&format!("{text}*{crc:04X}\r\n"));
        } else {
            self.send(&format!("{text}\r\n"));
        }
    }

    /// One turn: read what came, act on real-time bytes, take at most one line.
    fn step(&mut self) {
        let mut buf = [0u8; 512];
        if let Ok(n) = self.port.read(&mut buf) {
            for &b in &buf[..n] {
                self.byte(b);
            }
        }
        let buffered = self.rx.len();
        let mut seen = self.seen();
        seen.max_buffered = seen.max_buffered.max(buffered);
        drop(seen);
        self.flow();
        let now = Instant::now();
        if !self.held
            && now >= self.next_line_at
            && let Some(end) = self.rx.iter().position(|&b| b == b'\n')
        {
            let raw: Vec<u8> = self.rx.drain(..=end).collect();
            let text = String::from_utf8_lossy(&raw).trim_end_matches(['\n', '\r']).to_owned();
            self.next_line_at = now + self.script.line_period;
            self.take(&text);
            // A real-time byte that came behind this line counts from now on.
            match self.grbl_after {
                Some(k) if k > raw.len() => self.grbl_after = Some(k - raw.len()),
                Some(_) => {
                    self.grbl_after = None;
                    self.grbl_spoken = true;
                }
                None => {}
            }
        }
    }

    /// A byte from the host: real-time commands at once, the rest into the buffer.
    fn byte(&mut self, b: u8) {
        if std::mem::take(&mut self.swallow_lf) && b == b'\n' {
            return;
        }
        self.swallow_lf = self.checksums && matches!(b, b'!' | b'~' | 0x18);
        match b {
            b'?' => {
                self.spoke();
                self.report();
            }
            // ENQ: the short link report.
            0x05 => {
                self.spoke();
                let free = 128usize.saturating_sub(self.rx.len());
                self.line(&format!("[LK:{},{free}]", self.expected - 1));
            }
            b'!' => {
                self.spoke();
                self.held = true;
                self.seen().holds += 1;
            }
            b'~' => {
                self.spoke();
                self.held = false;
            }
            0x18 => self.reset(),
            _ => {
                if self.xoff {
                    self.seen().after_xoff += 1;
                }
                self.rx.push(b);
            }
        }
    }

    /// A real-time byte: grbl traffic, behind what is buffered.
    fn spoke(&mut self) {
        if self.rx.is_empty() {
            self.grbl_spoken = true;
        } else {
            self.grbl_after.get_or_insert(self.rx.len());
        }
    }

    fn reset(&mut self) {
        self.seen().resets += 1;
        self.rx.clear();
        self.held = false;
        self.busy_until = Instant::now();
        self.tape = TapeMode::Off;
        self.xoff = false;
        self.grbl_spoken = false;
        self.grbl_after = None;
        self.line_no = 0;
        self.expected = 1;
        self.checksums = false;
        self.machine = if self.script.locked { Machine::Alarm } else { Machine::Idle };
        if !self.script.mute {
            self.line("\r\nGrbl 1.1h ['$' for help]");
        }
    }

    fn report(&mut self) {
        let state = match (self.machine, self.held) {
            (Machine::Alarm, _) => "Alarm",
            (_, true) => "Hold:0",
            _ if Instant::now() < self.busy_until || self.rx.contains(&b'\n') => "Run",
            _ => "Idle",
        };
        let free = 128usize.saturating_sub(self.rx.len());
        let blocks = if state == "Run" { 60 } else { 64 };
        let link = if self.checksums { format!("|Lk:{}", self.expected - 1) } else { String::new() };
        let report = format!(
            "<{state}|MPos:50.000,0.000,-2.000|FS:0,0|Bf:{blocks},{free}|Ln:{}|WCO:0.000,0.000,0.000|Ov:100,100,100{link}>",
            self.line_no
        );
        let lost_pending = self.script.lose.is_some_and(|k| self.expected <= k);
        if self.checksums && self.script.garble_reports && lost_pending {
            return self.send(&format!("{report}*0000\r\n"));
        }
        self.line(&report);
    }

    /// Tape mode flow control: XOFF at ¾ of 128 bytes, XON at ¼.
    fn flow(&mut self) {
        if !matches!(self.tape, TapeMode::On { .. }) {
            return;
        }
        if !self.xoff && self.rx.len() >= 96 {
            self.xoff = true;
            self.seen().xoffs += 1;
            self.send("\x13");
        } else if self.xoff && self.rx.len() <= 32 {
            self.xoff = false;
            self.send("\x11");
        }
    }

    /// A line leaves the receive buffer.
    fn take(&mut self, text: &str) {
        if let TapeMode::On { .. } = self.tape {
            return self.tape_line(text);
        }
        self.seen().lines.push(text.to_owned());
        if text.trim() == "%" && self.machine == Machine::Idle && !self.grbl_spoken {
            self.tape = TapeMode::On { store: None, text: String::new() };
            return;
        }
        if let Some(cmd) = text.strip_prefix('$') {
            self.grbl_spoken = true;
            return self.dollar(cmd);
        }
        if self.machine == Machine::Alarm {
            self.line("[MSG:Locked by alarm]");
            return self.line("error:9");
        }
        let Some(block) = self.unframe(text) else { return };
        self.block(&block);
        self.answering = None;
    }

    /// Checks the checksum frame when there is one; answers the resend itself.
    fn unframe(&mut self, text: &str) -> Option<String> {
        let Some(rest) = text.strip_prefix('N').filter(|_| text.contains('*')) else { return Some(text.to_owned()) };
        let (body, crc) = text.rsplit_once('*')?;
        let (k, block) = rest.split_once(' ').unwrap_or((rest, ""));
        let k: u32 = k.parse().unwrap_or(0);
        let block = block.rsplit_once('*').map_or(block, |(b, _)| b).to_owned();
        let crc_ok = u16::from_str_radix(crc, 16).ok() == Some(crc16(body.as_bytes()));
        if self.script.lose == Some(k) && !self.lost {
            self.lost = true;
            return None;
        }
        let damaged = self.script.damage == Some(k) && !self.damaged;
        if damaged {
            self.damaged = true;
        }
        if k == 1 {
            self.expected = 1;
        }
        if k < self.expected && crc_ok {
            self.checksums = true;
            self.answering = Some(k);
            self.line("ok");
            self.answering = None;
            return None;
        }
        if k != self.expected || !crc_ok || damaged {
            let e = self.expected;
            self.line(&format!("[MSG:Resend:{e}]"));
            self.line("error:88");
            return None;
        }
        self.expected += 1;
        self.checksums = true;
        self.answering = Some(k);
        Some(block)
    }

    /// A program line in grbl mode.
    fn block(&mut self, block: &str) {
        self.line_no += 1;
        if self.script.refuse.is_some_and(|t| block.contains(t)) {
            self.line("[MSG:G12.1 is not supported]");
            return self.line("error:20");
        }
        self.line("ok");
        if self.script.alarm.is_some_and(|t| block.contains(t)) {
            self.machine = Machine::Alarm;
            let n = self.line_no;
            self.line(&format!("[MSG:ALARM 0010 line {n}: G07 is not a G code of the selected G-code system]"));
            return self.line("ALARM:20");
        }
        self.busy_until = Instant::now() + Duration::from_millis(5);
        if block.contains("M30") || block.contains("M02") {
            self.busy_until += Duration::from_millis(50);
            self.line("[MSG:Pgm End]");
        }
    }

    /// A `$` command.
    fn dollar(&mut self, cmd: &str) {
        match cmd {
            "$" => {
                for (n, v) in self.settings.clone() {
                    self.line(&format!("${n}={v}"));
                }
            }
            "X" => {
                self.machine = Machine::Idle;
                self.line("[MSG:Caution: Unlocked]");
            }
            "PL" => {
                let programs = self.seen().programs.clone();
                for (n, text) in programs {
                    self.line(&format!("[PRG:O{n:04},{}]", text.len()));
                }
            }
            _ => return self.dollar_with_value(cmd),
        }
        self.line("ok");
    }

    /// `$PR=n` and `$n=value`.
    fn dollar_with_value(&mut self, cmd: &str) {
        if let Some(n) = cmd.strip_prefix("LN=").and_then(|n| n.parse::<u32>().ok()) {
            self.expected = n.max(1);
            self.checksums = n > 0;
            self.line(&format!("[LN:{n}]"));
            return self.line("ok");
        }
        if let Some(n) = cmd.strip_prefix("PR=").and_then(|n| n.parse::<u32>().ok()) {
            if !self.seen().programs.contains_key(&n) {
                self.line(&format!("[MSG:O{n:04} is not in memory]"));
                return self.line("error:3");
            }
            self.line("ok");
            self.busy_until = Instant::now() + Duration::from_millis(300);
            return self.line("[MSG:Pgm End]");
        }
        match cmd.split_once('=').and_then(|(n, v)| Some((n.parse::<u32>().ok()?, v))) {
            Some((n, v)) if self.settings.contains_key(&n) => {
                self.settings.insert(n, v.to_owned());
                self.seen().settings.push(format!("${cmd}"));
                self.line("ok");
            }
            _ => {
                self.line("[MSG:Unknown setting]");
                self.line("error:3");
            }
        }
    }

    /// A block in tape mode: the first decides storing or running; `%` ends.
    fn tape_line(&mut self, text: &str) {
        let TapeMode::On { store, text: stored } = &mut self.tape else { return };
        if text.trim() == "%" {
            if let Some(Some(n)) = *store {
                let program = stored.clone();
                self.seen().programs.insert(n, program);
            }
            self.tape = TapeMode::Off;
            self.xoff = false;
            return;
        }
        if store.is_none() && !text.trim().is_empty() {
            let t = text.trim_start();
            *store = Some(t.strip_prefix('O').and_then(|r| r.get(..4)).and_then(|d| d.parse().ok()));
        }
        match store {
            Some(Some(_)) => {
                stored.push_str(text);
                stored.push('\n');
            }
            _ => {
                let block = text.to_owned();
                self.seen().drip.push(block);
                self.busy_until = Instant::now() + Duration::from_millis(5);
            }
        }
    }
}

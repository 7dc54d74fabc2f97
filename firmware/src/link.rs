//! A stand-in for `controller::Controller` until it lands: the same three calls
//! (`receive`, `poll`, `transmit`), so the tasks in `main.rs` stay as they are when
//! the real controller replaces it. It speaks just enough of the link contract
//! (docs/PROTOCOL.md) to prove the path: the grbl welcome at start and after 0x18,
//! a `?` status report built from the motion core, `ok` for every line (echoed in a
//! `[ECHO:…]` message; nothing is executed), and it applies the motion core's
//! spindle and M-code events to the outputs. The buttons act on the motion core
//! (feed hold, cycle start; a tripped limit is an emergency stop). One command of its
//! own exercises the motion path end to end: `$MOVE X<diameter> Z<z>` (mm, machine
//! coordinates) queues a rapid there.

use core::fmt::Write as _;

use heapless::{Deque, String, Vec};
use interp_core::axis::{Axis, Pos};
use interp_core::canon::{Action, Canon, CanonSink as _, Endpoint, Feed, FeedMode, Move, SpindleSpeed};
use interp_core::motion::State;
use motion_driver::io::Switch;

use crate::io::{InputLevels, Outputs};
use crate::motion::MotionPort;

/// The welcome line senders wait for (docs/PROTOCOL.md).
pub const WELCOME: &str = "Grbl 1.1h ['$' for help]\r\n";

/// Longest line taken (the contract's 128-byte receive buffer).
const LINE_MAX: usize = 128;

/// The placeholder controller.
pub struct Placeholder {
    line: Vec<u8, LINE_MAX>,
    overflow: bool,
    out: Deque<u8, 1024>,
    status_wanted: bool,
    reset_wanted: bool,
    /// A `$MOVE` target (machine X radius, Z; nm) to queue at the next poll.
    move_wanted: Option<Pos>,
    /// Switch levels at the last poll (for edges).
    last_inputs: InputLevels,
}

impl Default for Placeholder {
    fn default() -> Self {
        Self::new()
    }
}

impl Placeholder {
    /// Starts with the welcome line queued.
    pub fn new() -> Self {
        let mut p = Placeholder {
            line: Vec::new(),
            overflow: false,
            out: Deque::new(),
            status_wanted: false,
            reset_wanted: false,
            move_wanted: None,
            last_inputs: InputLevels::default(),
        };
        p.say(WELCOME);
        p
    }

    /// Bytes from the link at time `now` (ns): real-time `?` and 0x18 act at once,
    /// lines are answered `ok`.
    pub fn receive(&mut self, bytes: &[u8], _now: u64) {
        for &b in bytes {
            match b {
                b'?' => self.status_wanted = true,
                0x18 => self.reset_wanted = true,
                b'\n' => self.end_line(),
                b'\r' => {}
                _ if self.line.push(b).is_err() => self.overflow = true,
                _ => {}
            }
        }
    }

    /// One control step at `now` (ns): applies the motion core's events to the
    /// outputs, answers a pending status request, handles a soft reset.
    pub fn poll(&mut self, _now: u64, port: &mut MotionPort, outputs: &mut Outputs, inputs: InputLevels) {
        while let Some(e) = port.lock(|m| m.core.pop_event()).flatten() {
            outputs.apply(&e);
        }
        self.buttons(port, inputs);
        if let Some(to) = self.move_wanted.take() {
            let queued = port.push(rapid(to)).is_ok();
            self.say(if queued { "ok\r\n" } else { "error:9\r\n" });
        }
        if core::mem::take(&mut self.reset_wanted) {
            port.lock(|m| m.core.reset());
            outputs.stop_all();
            self.line.clear();
            self.out.clear();
            self.say(WELCOME);
        }
        if core::mem::take(&mut self.status_wanted) {
            self.status(port, inputs);
        }
    }

    /// Moves queued output into `buf`; returns how many bytes.
    pub fn transmit(&mut self, buf: &mut [u8]) -> usize {
        let mut n = 0;
        for slot in buf.iter_mut() {
            let Some(b) = self.out.pop_front() else { break };
            *slot = b;
            n += 1;
        }
        n
    }

    /// Feed hold and cycle start on pressing; a limit tripping stops everything.
    fn buttons(&mut self, port: &mut MotionPort, inputs: InputLevels) {
        let pressed = |s: Switch| inputs.active(s) && !self.last_inputs.active(s);
        if pressed(Switch::FeedHold) {
            port.lock(|m| m.core.feed_hold());
        }
        if pressed(Switch::CycleStart) {
            port.lock(|m| m.core.cycle_start());
        }
        if pressed(Switch::XLimit) || pressed(Switch::ZLimit) {
            port.lock(|m| m.core.emergency_stop());
        }
        self.last_inputs = inputs;
    }

    fn end_line(&mut self) {
        if core::mem::take(&mut self.overflow) {
            self.say("error:11\r\n");
        } else if let Some(rest) = self.line.strip_prefix(b"$MOVE") {
            match parse_move(rest) {
                Some(to) => self.move_wanted = Some(to),
                None => self.say("error:2\r\n"),
            }
        } else {
            let mut msg: String<{ LINE_MAX + 16 }> = String::new();
            let text = core::str::from_utf8(&self.line).unwrap_or("?");
            let _ = write!(msg, "[ECHO:{text}]\r\nok\r\n");
            self.say(&msg);
        }
        self.line.clear();
    }

    fn status(&mut self, port: &mut MotionPort, inputs: InputLevels) {
        let Some((state, idle, alarm, pos, rpm, free)) = port.lock(|m| {
            let free = interp_core::motion::QUEUE - m.core.queued();
            let c = &m.core;
            (c.state(), c.is_idle(), c.alarm().is_some(), c.position(), c.spindle().measured_rpm(), free)
        }) else {
            return;
        };
        let name = match state {
            _ if alarm => "Alarm",
            State::Held => "Hold:1",
            State::Stopped => "Idle",
            _ if idle => "Idle",
            _ => "Run",
        };
        let mut s: String<160> = String::new();
        let um = |nm: i64| (nm / 1_000_000, (nm % 1_000_000).unsigned_abs() / 1_000);
        let (xd, xf) = um(2 * pos[Axis::X]);
        let (zd, zf) = um(pos[Axis::Z]);
        let sign = |nm: i64| if nm < 0 && nm > -1_000_000 { "-" } else { "" };
        let _ = write!(
            s,
            "<{name}|MPos:{}{xd}.{xf:03},0.000,{}{zd}.{zf:03}|FS:0,{}|Bf:{free},{}",
            sign(2 * pos[Axis::X]),
            sign(pos[Axis::Z]),
            rpm as u32,
            LINE_MAX - self.line.len(),
        );
        let pn = pins(inputs);
        if !pn.is_empty() {
            let _ = write!(s, "|Pn:{pn}");
        }
        let _ = write!(s, ">\r\n");
        self.say(&s);
    }

    fn say(&mut self, s: &str) {
        for &b in s.as_bytes() {
            if self.out.push_back(b).is_err() {
                break;
            }
        }
    }
}

/// The `Pn:` letters of the active inputs.
fn pins(inputs: InputLevels) -> String<8> {
    let mut s = String::new();
    for (sw, c) in [
        (Switch::XLimit, 'X'),
        (Switch::ZLimit, 'Z'),
        (Switch::FeedHold, 'H'),
        (Switch::CycleStart, 'S'),
        (Switch::EStop, 'E'),
    ] {
        if inputs.active(sw) {
            let _ = s.push(c);
        }
    }
    s
}

/// A rapid to machine position `to`.
fn rapid(to: Pos) -> Canon {
    let m = Move {
        to: Endpoint { machine: to, work: to },
        feed: Feed { mode: FeedMode::PerMin, value: 0 },
        spindle: SpindleSpeed { rpm: None, css: None, max_rpm: 0 },
        exact_stop: true,
        independent: false,
    };
    Canon { line: 0, action: Action::Rapid(m) }
}

/// `X<diameter> Z<z>` in mm (both required) as a machine position (X a radius), nm.
fn parse_move(text: &[u8]) -> Option<Pos> {
    let text = core::str::from_utf8(text).ok()?;
    let (mut x, mut z) = (None, None);
    for word in text.split_ascii_whitespace() {
        let (letter, value) = word.split_at_checked(1)?;
        let nm = mm_to_nm(value)?;
        match letter {
            "X" | "x" => x = Some(nm / 2),
            "Z" | "z" => z = Some(nm),
            _ => return None,
        }
    }
    Some(Pos::xz(x?, z?))
}

/// A decimal number of mm (up to 6 decimals) as nm.
fn mm_to_nm(s: &str) -> Option<i64> {
    let (neg, s) = match s.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, s),
    };
    let (int, frac) = s.split_once('.').unwrap_or((s, ""));
    if frac.len() > 6 || (int.is_empty() && frac.is_empty()) {
        return None;
    }
    let whole: i64 = if int.is_empty() { 0 } else { int.parse().ok()? };
    let mut nm = whole.checked_mul(1_000_000)?;
    let mut scale = 100_000;
    for c in frac.bytes() {
        let d = i64::from(c.checked_sub(b'0').filter(|d| *d <= 9)?);
        nm = nm.checked_add(d * scale)?;
        scale /= 10;
    }
    Some(if neg { -nm } else { nm })
}

//! A stand-in for `controller::Controller` until it lands: the same three calls
//! (`receive`, `poll`, `transmit`), so the tasks in `main.rs` stay as they are when
//! the real controller replaces it. It speaks just enough of the link contract
//! (docs/PROTOCOL.md) to prove the path: the grbl welcome at start and after 0x18,
//! a `?` status report built from the motion core, `ok` for every line (echoed in a
//! `[ECHO:…]` message; nothing is executed), and it applies the motion core's
//! spindle and M-code events to the outputs.

use core::fmt::Write as _;

use heapless::{Deque, String, Vec};
use interp_core::axis::Axis;
use interp_core::motion::State;

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

    fn end_line(&mut self) {
        if core::mem::take(&mut self.overflow) {
            self.say("error:11\r\n");
        } else {
            let mut msg: String<{ LINE_MAX + 16 }> = String::new();
            let text = core::str::from_utf8(&self.line).unwrap_or("?");
            let _ = write!(msg, "[ECHO:{text}]\r\nok\r\n");
            self.say(&msg);
        }
        self.line.clear();
    }

    fn status(&mut self, port: &mut MotionPort, inputs: InputLevels) {
        let Some((state, pos, rpm, free)) = port.lock(|m| {
            let state = m.core.state();
            let free = interp_core::motion::QUEUE - m.core.queued();
            (state, m.core.position(), m.core.spindle().measured_rpm(), free)
        }) else {
            return;
        };
        let name = match state {
            State::Held => "Hold:1",
            State::Stopping if m_alarm(port) => "Alarm",
            State::Idle | State::Ended | State::Stopped => "Idle",
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

/// Whether the motion core has an alarm in force.
fn m_alarm(port: &mut MotionPort) -> bool {
    port.lock(|m| m.core.alarm().is_some()).unwrap_or(false)
}

/// The `Pn:` letters of the active inputs.
fn pins(inputs: InputLevels) -> String<8> {
    use motion_driver::io::Switch;
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

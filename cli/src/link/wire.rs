//! The serial port and what comes out of it: opening a port (a pty path works),
//! splitting the board's bytes into response lines and flow-control bytes, and
//! waiting for a line with a deadline.

use std::collections::VecDeque;
use std::io::{ErrorKind, Read, Write};
use std::time::{Duration, Instant};

use serialport::SerialPort;

use super::LinkError;
use super::response::{self, Framed, Response};
use super::tape::{XOFF, XON};

/// Something the board sent.
#[derive(Clone, Debug, PartialEq)]
pub enum Incoming {
    /// A response line, without its line end.
    Line(String),
    /// A flow-control byte (DC1 XON or DC3 XOFF), wherever it came.
    Flow(u8),
}

/// Splits the board's byte stream into lines (ending at LF, CR dropped) and takes
/// XON/XOFF out wherever they appear. Empty lines are dropped.
#[derive(Clone, Debug, Default)]
pub struct LineSplitter {
    partial: Vec<u8>,
}

/// A line longer than this without LF is handed on as it is.
const MAX_LINE: usize = 1024;

/// ENQ (Ctrl-E), the board's short link query: answered `[LK:<last link line
/// accepted>,<free receive-buffer bytes>]` (docs/PROTOCOL.md, Checksums).
pub const ENQ: u8 = 0x05;

impl LineSplitter {
    /// Takes `bytes`, appending what they complete to `out`.
    pub fn push(&mut self, bytes: &[u8], out: &mut VecDeque<Incoming>) {
        for &b in bytes {
            match b {
                XON | XOFF => out.push_back(Incoming::Flow(b)),
                b'\n' => self.flush(out),
                b'\r' => {}
                _ => {
                    self.partial.push(b);
                    if self.partial.len() >= MAX_LINE {
                        self.flush(out);
                    }
                }
            }
        }
    }

    /// Hands on the partial line, unless it is empty.
    fn flush(&mut self, out: &mut VecDeque<Incoming>) {
        if !self.partial.is_empty() {
            out.push_back(Incoming::Line(String::from_utf8_lossy(&self.partial).into_owned()));
            self.partial.clear();
        }
    }
}

/// An open link to the board.
pub struct Link {
    port: Box<dyn SerialPort>,
    name: String,
    splitter: LineSplitter,
    pending: VecDeque<Incoming>,
    /// Link checksums are in use: every line of the board must carry its CRC (the
    /// welcome line excepted: a reset switches them off), and real-time commands
    /// other than `?` go out with a LF behind them.
    checked: bool,
    /// Lines dropped as damaged (a wrong CRC, or none while checked).
    damaged: u64,
    /// Soft resets sent.
    resets: u32,
    /// When the board last sent a line, damaged or not.
    heard: Instant,
}

/// How long one read waits for bytes.
const READ_SLICE: Duration = Duration::from_millis(10);

/// How long a status request waits for its answer before `?` is sent again.
const ASK_AGAIN: Duration = Duration::from_millis(300);

impl Link {
    /// Opens `path` at `baud` 8N1 without flow control (the tape's XON/XOFF is
    /// handled here, not by the driver).
    pub fn open(path: &str, baud: u32) -> Result<Link, LinkError> {
        let port = serialport::new(path, baud)
            .timeout(READ_SLICE)
            .open()
            .map_err(|e| LinkError::Open { port: path.to_owned(), message: e.to_string() })?;
        // Whatever the board said before we came (an old welcome line) is not for us.
        let _ = port.clear(serialport::ClearBuffer::Input);
        Ok(Link::from_port(port, path))
    }

    /// A link over an already open port named `name` in messages.
    pub fn from_port(port: Box<dyn SerialPort>, name: &str) -> Link {
        Link {
            port,
            name: name.to_owned(),
            splitter: LineSplitter::default(),
            pending: VecDeque::new(),
            checked: false,
            damaged: 0,
            resets: 0,
            heard: Instant::now(),
        }
    }

    /// Link checksums on or off (see [`Link::realtime`]; with them on, lines of the
    /// board without their CRC are dropped as damaged).
    pub fn set_checked(&mut self, on: bool) {
        self.checked = on;
    }

    /// Whether link checksums are in use.
    pub fn checked(&self) -> bool {
        self.checked
    }

    /// When the board last sent a line, damaged or not (a board that talks through
    /// line noise is not a dead link).
    pub fn heard(&self) -> Instant {
        self.heard
    }

    /// Soft resets sent so far.
    pub fn resets(&self) -> u32 {
        self.resets
    }

    /// Lines of the board dropped as damaged so far.
    pub fn damaged(&self) -> u64 {
        self.damaged
    }

    /// Writes the real-time command `b`: alone, or with link checksums in use (other
    /// than the queries `?` and ENQ) followed by a LF, as the board then wants it
    /// (docs/PROTOCOL.md).
    pub fn realtime(&mut self, b: u8) -> Result<(), LinkError> {
        if self.checked && b != b'?' && b != ENQ { self.write(&[b, b'\n']) } else { self.write(&[b]) }
    }

    /// A line of the board as it may be used: its framing checked and taken off;
    /// `None` for a damaged line.
    fn accept(&mut self, line: String) -> Option<String> {
        let text = match response::framing(&line) {
            Framed::Good(text) => text,
            Framed::Plain(text) if !self.checked || text.starts_with("Grbl 1.1") => text,
            Framed::Plain(_) | Framed::Bad => {
                self.damaged += 1;
                return None;
            }
        };
        Some(text.to_owned())
    }

    /// The port's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Writes all of `bytes`.
    pub fn write(&mut self, bytes: &[u8]) -> Result<(), LinkError> {
        self.port.write_all(bytes).and_then(|()| self.port.flush()).map_err(|e| self.io_error(e))
    }

    /// Writes as much of `bytes` as the port takes now; returns how many went.
    pub fn write_some(&mut self, bytes: &[u8]) -> Result<usize, LinkError> {
        match self.port.write(bytes) {
            Ok(n) => Ok(n),
            Err(e) if e.kind() == ErrorKind::TimedOut || e.kind() == ErrorKind::WouldBlock => Ok(0),
            Err(e) => Err(self.io_error(e)),
        }
    }

    /// Bytes written that have not left the port yet (0 when the driver cannot say).
    pub fn queued_out(&self) -> u32 {
        self.port.bytes_to_write().unwrap_or(0)
    }

    /// The next thing the board sent, waiting at most `wait` for it.
    pub fn poll(&mut self, wait: Duration) -> Result<Option<Incoming>, LinkError> {
        let deadline = Instant::now() + wait;
        loop {
            if let Some(i) = self.pending.pop_front() {
                match i {
                    Incoming::Line(l) => {
                        self.heard = Instant::now();
                        match self.accept(l) {
                            Some(l) => return Ok(Some(Incoming::Line(l))),
                            None => continue,
                        }
                    }
                    flow => return Ok(Some(flow)),
                }
            }
            self.read_some(deadline.saturating_duration_since(Instant::now()))?;
            if self.pending.is_empty() && Instant::now() >= deadline {
                return Ok(None);
            }
        }
    }

    /// Reads what arrives within `wait` (at most one read slice) into the pending queue.
    fn read_some(&mut self, wait: Duration) -> Result<(), LinkError> {
        self.port.set_timeout(wait.min(READ_SLICE)).map_err(|e| self.io_error(e.into()))?;
        let mut buf = [0u8; 256];
        match self.port.read(&mut buf) {
            Ok(n) => {
                self.splitter.push(buf.get(..n).unwrap_or_default(), &mut self.pending);
                Ok(())
            }
            Err(e) if matches!(e.kind(), ErrorKind::TimedOut | ErrorKind::WouldBlock | ErrorKind::Interrupted) => {
                Ok(())
            }
            Err(e) => Err(self.io_error(e)),
        }
    }

    /// The next response line before `deadline` (flow bytes are passed over);
    /// `what` names what was awaited in the timeout error.
    pub fn line_until(&mut self, deadline: Instant, what: &str) -> Result<Response, LinkError> {
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            match self.poll(left.min(READ_SLICE))? {
                Some(Incoming::Line(l)) => return Ok(response::parse(&l)),
                Some(Incoming::Flow(_)) => {}
                None if left.is_zero() => return Err(self.timeout(what)),
                None => {}
            }
        }
    }

    /// Soft reset (0x18), then the welcome line within `wait`; returns it. (Sent
    /// once: a second reset's late welcome would be taken for the next one's.)
    pub fn reset(&mut self, wait: Duration) -> Result<String, LinkError> {
        self.realtime(0x18)?;
        self.resets += 1;
        // The reset switches the board's checksums off.
        self.checked = false;
        self.welcome(wait)
    }

    /// Waits for the welcome line `Grbl 1.1…` within `wait`, passing over anything else.
    pub fn welcome(&mut self, wait: Duration) -> Result<String, LinkError> {
        let deadline = Instant::now() + wait;
        loop {
            if let Response::Welcome(w) = self.line_until(deadline, "the welcome line `Grbl 1.1h`")? {
                return Ok(w);
            }
        }
    }

    /// One status report: writes `?` and waits for the `<…>` line within `wait`
    /// (asking again after [`ASK_AGAIN`]: a `?` can be lost on a noisy line).
    pub fn status(&mut self, wait: Duration) -> Result<response::Status, LinkError> {
        let deadline = Instant::now() + wait;
        loop {
            self.realtime(b'?')?;
            let turn = deadline.min(Instant::now() + ASK_AGAIN);
            loop {
                match self.line_until(turn, "a status report") {
                    Ok(Response::Status(s)) => return Ok(s),
                    Ok(_) => {}
                    // No answer this turn: ask again until the deadline.
                    Err(LinkError::Timeout { .. }) if Instant::now() < deadline => break,
                    Err(e) => return Err(e),
                }
            }
        }
    }

    /// Sends the command `line` (a `$` command) and collects the lines before its
    /// `ok`; an `error:N` is returned as [`LinkError::Refused`] with the `[MSG:…]`
    /// that came before it.
    pub fn command(&mut self, line: &str, wait: Duration) -> Result<Vec<String>, LinkError> {
        self.write(format!("{line}\n").as_bytes())?;
        let deadline = Instant::now() + wait;
        let mut lines = Vec::new();
        let mut msg = None;
        loop {
            match self.line_until(deadline, &format!("the answer to {line}"))? {
                Response::Ok => return Ok(lines),
                Response::Error(code) => {
                    let message = msg.unwrap_or_else(|| response::error_text(code).to_owned());
                    return Err(LinkError::Refused { command: line.to_owned(), code, message });
                }
                Response::Status(_) | Response::Welcome(_) => {}
                Response::Msg(m) => {
                    lines.push(format!("[MSG:{m}]"));
                    msg = Some(m);
                }
                Response::Feedback(t) | Response::Other(t) => lines.push(t),
                Response::Alarm(code) => lines.push(format!("ALARM:{code}")),
                Response::Resend(n) => lines.push(format!("[MSG:Resend:{n}]")),
                Response::Answer(k, r) => lines.push(format!("N{k} {r:?}")),
                Response::Link(last, free) => lines.push(format!("[LK:{last},{free}]")),
            }
        }
    }

    /// A read or write error of this port.
    fn io_error(&self, e: std::io::Error) -> LinkError {
        LinkError::Io { port: self.name.clone(), message: e.to_string() }
    }

    /// The board did not send `what` in time.
    fn timeout(&self, what: &str) -> LinkError {
        LinkError::Timeout { port: self.name.clone(), what: what.to_owned() }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_end_at_lf_and_flow_bytes_are_taken_out_anywhere() {
        let mut s = LineSplitter::default();
        let mut out = VecDeque::new();
        s.push(b"o", &mut out);
        assert!(out.is_empty());
        s.push(b"k\r\n\r\n<Idle|MP\x13os:0,0,0>\r", &mut out);
        s.push(b"\n\x11", &mut out);
        assert_eq!(
            Vec::from(out),
            vec![
                Incoming::Line("ok".into()),
                Incoming::Flow(XOFF),
                Incoming::Line("<Idle|MPos:0,0,0>".into()),
                Incoming::Flow(XON)
            ]
        );
    }
}

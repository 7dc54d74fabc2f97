//! Tape mode's XON/XOFF honoured by `lathe send --tape`'s session, without a pty or
//! a thread: the board is a model behind an in-process [`SerialPort`] that takes the
//! sender's bytes the moment they are written and answers (DC3, DC1, status reports)
//! in the same order. What is checked — how many bytes came after the XOFF, how
//! full the buffer got — is then a matter of the order of reads and writes, never of
//! how the machine's scheduler ran two processes (the end-to-end test over a pty,
//! `link::tape_mode_drip_feeds_without_the_o_number`, cannot bound those).

use std::collections::VecDeque;
use std::io::{self, Read, Write};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use lathe::link::session::{Feeder, Origin, Session, Verdict};
use lathe::link::tape::{Tape, XOFF, XON};
use lathe::link::ui::Plain;
use lathe::link::wire::Link;
use serialport::{ClearBuffer, DataBits, FlowControl, Parity, SerialPort, StopBits};

/// The board's receive buffer in tape mode: XOFF at ¾ of 128 bytes, XON at ¼.
const XOFF_AT: usize = 96;
const XON_AT: usize = 32;

/// Reads of the sender the board keeps its XOFF before it takes a block: a sender
/// that ignored the XOFF would write a chunk on each of them.
const HOLD_READS: u32 = 100;

/// The board side: a machine slower than the line (it runs a block only while its
/// buffer is at the XOFF mark or the tape's closing `%` is in), so every XOFF/XON
/// cycle happens, deterministically.
#[derive(Debug, Default)]
struct Model {
    rx: Vec<u8>,
    out: VecDeque<u8>,
    xoff: bool,
    held_reads: u32,
    xoffs: u32,
    /// Bytes written while the XOFF was in force.
    after_xoff: usize,
    /// The most after any one XOFF.
    worst_after_xoff: usize,
    max_buffered: usize,
    blocks: Vec<String>,
    closed: bool,
}

impl Model {
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            if b == b'?' {
                let state = if self.rx.is_empty() { "Idle" } else { "Run" };
                let free = 128 - self.rx.len().min(128);
                let report = format!(
                    "<{state}|MPos:0.000,0.000,0.000|FS:0,0|Bf:64,{free}|Ln:0|WCO:0.000,0.000,0.000|Ov:100,100,100>\r\n"
                );
                self.out.extend(report.bytes());
                continue;
            }
            if self.xoff {
                self.after_xoff += 1;
                self.worst_after_xoff = self.worst_after_xoff.max(self.after_xoff);
            }
            self.rx.push(b);
        }
        self.max_buffered = self.max_buffered.max(self.rx.len());
        if !self.xoff && self.rx.len() >= XOFF_AT {
            self.xoff = true;
            self.xoffs += 1;
            self.after_xoff = 0;
            self.held_reads = 0;
            self.out.push_back(XOFF);
        }
    }

    /// The sender reads: the machine runs a block if it may.
    fn step(&mut self) {
        let runs = if self.xoff {
            self.held_reads += 1;
            self.held_reads > HOLD_READS
        } else {
            self.closed
        };
        if !runs {
            return;
        }
        if let Some(end) = self.rx.iter().position(|&b| b == b'\n') {
            let line: Vec<u8> = self.rx.drain(..=end).collect();
            let text = String::from_utf8_lossy(&line).trim_end().to_owned();
            if text == "%" && !self.blocks.is_empty() {
                self.closed = true;
            }
            self.blocks.push(text);
        }
        if self.xoff && self.rx.len() <= XON_AT {
            self.xoff = false;
            self.out.push_back(XON);
        }
    }

    /// Whether the closing `%` is in the buffer (the machine then runs to the end).
    fn note_close(&mut self) {
        let complete = self.rx.iter().rposition(|&b| b == b'\n').map_or(&[][..], |end| &self.rx[..end]);
        let marks = complete.split(|&b| b == b'\n').filter(|l| *l == b"%").count();
        // Before the first block is taken the opening `%` is in the buffer too.
        if marks >= if self.blocks.is_empty() { 2 } else { 1 } {
            self.closed = true;
        }
    }
}

/// The port the session talks to: every write goes to the model at once.
struct ModelPort {
    model: Arc<Mutex<Model>>,
    timeout: Duration,
}

impl Read for ModelPort {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let n = {
            let mut m = self.model.lock().expect("model");
            m.note_close();
            m.step();
            let n = buf.len().min(m.out.len());
            for (slot, b) in buf.iter_mut().zip(m.out.drain(..n)) {
                *slot = b;
            }
            n
        };
        if n == 0 {
            // Nothing to read: as a port would, let time pass (the session's tape
            // pacing and status polls are in wall-clock time; nothing checked here is).
            std::thread::sleep(self.timeout.min(Duration::from_micros(200)));
            return Err(io::ErrorKind::TimedOut.into());
        }
        Ok(n)
    }
}

impl Write for ModelPort {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.model.lock().expect("model").write(buf);
        Ok(buf.len())
    }

    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

impl SerialPort for ModelPort {
    fn name(&self) -> Option<String> {
        Some("model".into())
    }
    fn baud_rate(&self) -> serialport::Result<u32> {
        Ok(115_200)
    }
    fn data_bits(&self) -> serialport::Result<DataBits> {
        Ok(DataBits::Eight)
    }
    fn flow_control(&self) -> serialport::Result<FlowControl> {
        Ok(FlowControl::None)
    }
    fn parity(&self) -> serialport::Result<Parity> {
        Ok(Parity::None)
    }
    fn stop_bits(&self) -> serialport::Result<StopBits> {
        Ok(StopBits::One)
    }
    fn timeout(&self) -> Duration {
        self.timeout
    }
    fn set_baud_rate(&mut self, _: u32) -> serialport::Result<()> {
        Ok(())
    }
    fn set_data_bits(&mut self, _: DataBits) -> serialport::Result<()> {
        Ok(())
    }
    fn set_flow_control(&mut self, _: FlowControl) -> serialport::Result<()> {
        Ok(())
    }
    fn set_parity(&mut self, _: Parity) -> serialport::Result<()> {
        Ok(())
    }
    fn set_stop_bits(&mut self, _: StopBits) -> serialport::Result<()> {
        Ok(())
    }
    fn set_timeout(&mut self, timeout: Duration) -> serialport::Result<()> {
        self.timeout = timeout;
        Ok(())
    }
    fn write_request_to_send(&mut self, _: bool) -> serialport::Result<()> {
        Ok(())
    }
    fn write_data_terminal_ready(&mut self, _: bool) -> serialport::Result<()> {
        Ok(())
    }
    fn read_clear_to_send(&mut self) -> serialport::Result<bool> {
        Ok(true)
    }
    fn read_data_set_ready(&mut self) -> serialport::Result<bool> {
        Ok(true)
    }
    fn read_ring_indicator(&mut self) -> serialport::Result<bool> {
        Ok(false)
    }
    fn read_carrier_detect(&mut self) -> serialport::Result<bool> {
        Ok(true)
    }
    fn bytes_to_read(&self) -> serialport::Result<u32> {
        Ok(self.model.lock().expect("model").out.len() as u32)
    }
    fn bytes_to_write(&self) -> serialport::Result<u32> {
        // Written bytes reach the board at once: nothing waits in the port.
        Ok(0)
    }
    fn clear(&self, _: ClearBuffer) -> serialport::Result<()> {
        Ok(())
    }
    fn try_clone(&self) -> serialport::Result<Box<dyn SerialPort>> {
        Err(serialport::Error::new(serialport::ErrorKind::Unknown, "not cloneable"))
    }
    fn set_break(&self) -> serialport::Result<()> {
        Ok(())
    }
    fn clear_break(&self) -> serialport::Result<()> {
        Ok(())
    }
}

#[test]
fn tape_mode_honours_xoff_within_one_chunk_of_reading_it() {
    let lines: Vec<String> = (0..80).map(|i| format!("G01 X{}.5 Z-{i}.25 F0.2", 20 + i % 30)).collect();
    let model = Arc::new(Mutex::new(Model::default()));
    let port = ModelPort { model: model.clone(), timeout: Duration::from_millis(10) };
    let mut link = Link::from_port(Box::new(port), "model");
    let mut log = Vec::new();
    let mut ui = Plain::new(&mut log);
    let origin = Origin { name: "tape.nc".into(), file_lines: Vec::new(), command: None };
    let feeder = Feeder::Tape(Tape::new(&lines, 16));
    let verdict = Session::new(&mut link, &mut ui, feeder, origin, Some((64, 128))).run().expect("no link error");
    assert_eq!(verdict, Verdict::Done, "{}", String::from_utf8_lossy(&log));
    let m = model.lock().expect("model");
    // Every block, in order, once: `%`, the 80 lines, `%`.
    assert_eq!(m.blocks.len(), 82, "{:?}", m.blocks);
    assert_eq!(m.blocks[0], "%");
    assert_eq!(m.blocks[1..81], lines[..]);
    assert_eq!(m.blocks[81], "%");
    // The tape (~2 KB) fills the buffer to the XOFF mark again and again.
    assert!(m.xoffs >= 10, "{} XOFFs", m.xoffs);
    // The session writes a chunk (16 bytes), then reads what came: after the XOFF
    // it writes at most the chunk it had decided on before reading it, plus one for
    // a status report that came in the same read ahead of the DC3 — never the
    // chunk after chunk a sender ignoring XOFF would write while the board holds it.
    assert!(m.worst_after_xoff <= 32, "{} bytes came after an XOFF", m.worst_after_xoff);
    assert!(m.max_buffered <= XOFF_AT + 16 + 32, "{}", m.max_buffered);
}

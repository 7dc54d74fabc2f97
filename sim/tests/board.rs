//! The virtual board on the wire: programs streamed with grbl character counting
//! execute exactly the canonical actions the interpreter produces for the same
//! file (what `lathe sim` runs), and the board keeps answering.

use std::collections::VecDeque;

use interp_core::canon::{Canon, CanonSink, Full};
use interp_core::{Interpreter, MachineConfig, Panel, Progress, SingleProgram};
use sim::board::VirtualBoard;

/// 1 ms of simulated time.
const MS: u64 = 1_000_000;

struct Record(Vec<Canon>);

impl CanonSink for Record {
    fn push(&mut self, c: Canon) -> Result<(), Full> {
        self.0.push(c);
        Ok(())
    }
}

/// The canonical actions of `text` as `lathe sim` interprets it (from reference
/// position 1, stopping at the first alarm).
fn reference(text: &str) -> Vec<Canon> {
    let cfg = MachineConfig::default();
    let mut interp = Interpreter::new(cfg.clone());
    interp.set_machine_position(cfg.reference[0]);
    let mut rec = Record(Vec::new());
    let store = SingleProgram(text.as_bytes());
    for _ in 0..10_000_000 {
        match interp.step(&store, &Panel::default(), &mut rec) {
            Ok(Progress::Ended) | Err(_) => break,
            Ok(Progress::Paused) => interp.cycle_start(),
            Ok(_) => {}
        }
    }
    rec.0
}

/// A grbl sender with character counting: at most 128 unanswered bytes.
struct Sender {
    lines: VecDeque<String>,
    in_flight: VecDeque<usize>,
    rx: String,
    oks: usize,
    errors: Vec<String>,
    log: Vec<String>,
}

impl Sender {
    fn new(text: &str) -> Self {
        let lines = text.lines().map(|l| l.trim_end_matches('\r').to_string()).collect();
        Sender { lines, in_flight: VecDeque::new(), rx: String::new(), oks: 0, errors: Vec::new(), log: Vec::new() }
    }

    fn done(&self) -> bool {
        self.lines.is_empty() && self.in_flight.is_empty()
    }

    /// Sends what character counting allows.
    fn send(&mut self, board: &mut VirtualBoard) {
        while let Some(l) = self.lines.front() {
            let n = l.len() + 1;
            if self.in_flight.iter().sum::<usize>() + n > 128 {
                break;
            }
            let mut bytes = l.clone().into_bytes();
            bytes.push(b'\n');
            board.receive(&bytes);
            self.in_flight.push_back(n);
            self.lines.pop_front();
        }
    }

    /// Reads the board's answers.
    fn read(&mut self, board: &mut VirtualBoard) {
        self.rx.push_str(&String::from_utf8_lossy(&board.transmit()));
        while let Some(i) = self.rx.find('\n') {
            let line = self.rx[..i].trim_end_matches('\r').to_string();
            self.rx.drain(..=i);
            if line == "ok" {
                self.oks += 1;
                self.in_flight.pop_front();
            } else if line.starts_with("error:") {
                self.errors.push(line.clone());
                self.in_flight.pop_front();
            }
            self.log.push(line);
        }
    }
}

/// Streams `text` into a fresh board and runs until the board is idle again (or
/// `limit_s` of simulated time); the board and the sender afterwards.
fn stream(text: &str, limit_s: u64) -> (VirtualBoard, Sender) {
    let mut board = VirtualBoard::new(MachineConfig::default()).expect("default machine");
    board.record();
    let mut s = Sender::new(text);
    board.run_for(10 * MS);
    s.read(&mut board);
    assert!(s.log.iter().any(|l| l == "Grbl 1.1h ['$' for help]"), "welcome: {:?}", s.log);
    // A grbl sender polls the status when it connects (so a leading `%` is a record
    // mark, not tape mode).
    assert!(status(&mut board).starts_with("<Idle|MPos:300.000,0.000,250.000|"));
    let limit = limit_s * 1_000 * MS;
    while board.now() < limit {
        s.send(&mut board);
        board.run_for(MS);
        s.read(&mut board);
        if s.done() && board.sim.core.is_idle() && status(&mut board).starts_with("<Idle") {
            break;
        }
    }
    (board, s)
}

/// One `?` status report.
fn status(board: &mut VirtualBoard) -> String {
    board.receive(b"?");
    board.run_for(2 * MS);
    let out = String::from_utf8_lossy(&board.transmit()).to_string();
    out.lines().find(|l| l.starts_with('<')).unwrap_or_default().to_string()
}

fn example(name: &str) -> String {
    std::fs::read_to_string(format!("{}/../examples/{name}", env!("CARGO_MANIFEST_DIR"))).expect("example")
}

#[test]
fn streamed_examples_execute_what_lathe_sim_interprets() {
    for name in ["shaft.nc", "cycles_g71_g70.nc", "cycles_threads.nc", "cycles_g90_g94.nc", "parabola_while.nc"] {
        let text = example(name);
        let (board, s) = stream(&text, 3_000);
        assert!(s.errors.is_empty(), "{name}: {:?}", s.errors);
        assert_eq!(s.oks, text.lines().count(), "{name}: every line answered ok");
        let executed = board.executed.as_ref().expect("recording");
        let want = reference(&text);
        assert_eq!(executed.len(), want.len(), "{name}: number of actions");
        for (i, (a, b)) in executed.iter().zip(&want).enumerate() {
            assert_eq!(a, b, "{name}: action {i}");
        }
        assert!(board.sim.core.alarm().is_none(), "{name}: {:?}", board.sim.core.alarm());
    }
}

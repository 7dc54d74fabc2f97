//! The fuzz harnesses: what each cargo-fuzz target runs on its input. They live
//! here, outside the targets, so that `host-tests/tests/fuzz_corpus.rs` can replay
//! every committed corpus file through exactly the same code on stable Rust.
//!
//! - [`parser`]: arbitrary text, line by line, through the block reader (NC words,
//!   macro statements and expressions against set variables) and the block check;
//!   no interpreter, so it runs fast.
//! - [`program`]: arbitrary program text (macros, subprograms, several O programs
//!   in one file) through the interpreter into a real motion core's planner.
//! - [`cycles`]: canned cycles G70–G76 and G90/G92/G94 built around a contour and
//!   parameters taken from the input bytes, through the same path.
//! - [`board`]: arbitrary bytes on the link into the board's controller polling a
//!   real motion core; afterwards it must still answer `?` with a status report.
//!
//! Every harness is bounded (interpreter steps, polls), never allocates without
//! bound, and panics only when the code under test misbehaves.

use std::fmt::Write as _;
use std::sync::OnceLock;

use interp_core::axis::{AXIS_COUNT, Pos};
use interp_core::canon::{Canon, CanonSink, Full};
use interp_core::program::ProgramMemory;
use interp_core::{Interpreter, MachineConfig, Panel, Progress, SingleProgram};
use motion_core::motion::{Feedback, MotionCore};

/// Interpreter steps per input (a WHILE loop that never ends stops here). A step
/// runs up to one NC block and its macro statements. 500 reach every nesting limit
/// (subprograms, macro calls, WHILE) and overflow any growing variable: replaying
/// the corpus, 2 000 steps reached 4 more edges of 4 355 and took twice as long.
/// An alarm does not end the input (a later block still runs, as after a reset):
/// stopping at the 4th alarm lost 350 edges.
pub const MAX_STEPS: usize = 500;

/// Actions per input the motion core's planner takes (a cycle of a million passes
/// stops here: refused as a full queue, the interpreter stays blocked).
pub const MAX_ACTIONS: usize = 4_000;

/// Interpolation period the harnesses tick the motion core with, ns.
const TICK_NS: u64 = 1_000_000;

/// Program memory for the program target (the board's size).
type Memory = ProgramMemory<49_152, 64, 2_048>;

/// The interpreter's sink: a real motion core whose planner takes every action.
/// When its queue is full it is reset (the queue drops), so the program goes on
/// without simulating its moves; the first queue runs a few periods at the end.
/// One interpolation period of `core` at `now` with a spindle turning at its
/// command (`count`: the encoder, one index per revolution); the period's steps
/// are taken and dropped.
fn period(core: &mut MotionCore<64>, now: &mut u64, count: &mut i64) {
    let (_, rpm) = core.spindle_output();
    let cpr = i64::from(core.params().cpr);
    *count += i64::from(rpm) * cpr / 60_000;
    let fb = Feedback { count: *count, index: Some(*count - count.rem_euclid(cpr.max(1))) };
    core.tick(*now, fb);
    *now += TICK_NS;
    for axis in 0..AXIS_COUNT {
        while core.next_step(axis, *now).is_some() {}
    }
}

struct Planner {
    core: Box<MotionCore<64>>,
    now: u64,
    count: i64,
    pushed: usize,
}

impl Planner {
    fn new(cfg: &MachineConfig) -> Option<Self> {
        let core = Box::new(MotionCore::new(cfg, Pos::ZERO).ok()?);
        Some(Planner { core, now: 0, count: 0, pushed: 0 })
    }

    /// Runs `n` interpolation periods with a spindle turning at its command.
    fn run(&mut self, n: usize) {
        for _ in 0..n {
            period(&mut self.core, &mut self.now, &mut self.count);
        }
    }
}

impl CanonSink for Planner {
    fn push(&mut self, c: Canon) -> Result<(), Full> {
        if self.pushed >= MAX_ACTIONS {
            return Err(Full);
        }
        self.pushed += 1;
        if self.core.push(c).is_ok() {
            return Ok(());
        }
        self.core.reset();
        self.core.push(c)
    }
}

/// Runs the interpreter over `store` into a motion core, bounded.
fn interpret<S: interp_core::ProgramStore + ?Sized>(store: &S, main: Option<interp_core::program::ProgramId>) {
    let cfg = MachineConfig::default();
    let Some(mut sink) = Planner::new(&cfg) else { return };
    let mut interp = Box::new(Interpreter::new(cfg));
    if let Some(id) = main {
        interp.select_main(id);
    }
    let panel = Panel::default();
    let mut blocked = 0;
    for _ in 0..MAX_STEPS {
        match interp.step(store, &panel, &mut sink) {
            Ok(Progress::Ended) => break,
            Ok(Progress::Paused) => interp.cycle_start(),
            Ok(Progress::Blocked) => {
                blocked += 1;
                if blocked > 10 {
                    break;
                }
            }
            Ok(_) => {}
            Err(alarm) => {
                let _ = write!(Discard, "{alarm}");
            }
        }
    }
    sink.run(16);
}

/// A formatter target that drops the text: the alarm's message is formatted (its
/// `Display` runs on every alarm) without allocating.
struct Discard;

impl std::fmt::Write for Discard {
    fn write_str(&mut self, _: &str) -> std::fmt::Result {
        Ok(())
    }
}

/// Variables the parser target's expressions read: #1–#33 and #100–#149 set to
/// assorted values (whole, fractional, negative, large, zero), the rest null.
fn parser_vars() -> &'static interp_core::lang::fanuc::macros::Variables {
    static VARS: OnceLock<interp_core::lang::fanuc::macros::Variables> = OnceLock::new();
    VARS.get_or_init(|| {
        let mut v = interp_core::lang::fanuc::macros::Variables::new();
        let values = [1.0, -2.5, 0.0, 1e9, 0.001, 360.0, -1e-9, 45.0, 99_999_999.0, 7.0];
        for (i, n) in (1..=33).chain(100..150).enumerate() {
            let _ = v.set(n, values.get(i % values.len()).copied());
        }
        v
    })
}

/// One line through the reader and, when it is an NC block, the block check.
fn parse_line(line: &[u8], n: u32, fmt: &interp_core::units::NumberFormat) {
    use interp_core::config::Param;
    use interp_core::lang::fanuc::calls::{CallCodes, CallRead, Calls};
    use interp_core::lang::fanuc::parse::{Block, Read, read_block_into, read_program_block, skip_level};
    static CFG: OnceLock<(MachineConfig, interp_core::modal::State, CallCodes)> = OnceLock::new();
    let (cfg, state, codes) = CFG.get_or_init(|| {
        let cfg = MachineConfig::default();
        let state = interp_core::modal::State::power_on(&cfg, Pos::ZERO);
        // Odd lines are read with codes that call: G100 and M50 macros, M06 and T
        // subprograms.
        let mut p = cfg.params;
        for (param, v) in [(Param::CallG9010, 100), (Param::CallM9020, 50), (Param::SubM9001, 6), (Param::TCodeCall, 1)]
        {
            p.set(param, v);
        }
        (cfg, state, CallCodes::of(&p, 0))
    });
    let codes = if n % 2 == 1 { *codes } else { CallCodes::BUILT_IN };
    let _ = skip_level(line);
    let mut block = Block::default();
    let mut calls = Calls { codes, read: CallRead::EMPTY };
    match read_program_block(line, n, parser_vars(), fmt, &mut block, &mut calls) {
        Ok(Read::Nc) => {
            assert_eq!(block.line, n, "the block keeps its line");
            for letter in block.letters() {
                assert!(letter.is_ascii_uppercase() && block.has(letter), "address {letter}");
            }
            let mut cmd = interp_core::command::Command::EMPTY;
            if let Err(kind) = interp_core::lang::fanuc::check::check_into(&block, state, cfg, &mut cmd) {
                let _ = write!(Discard, "{kind}");
            }
        }
        Ok(Read::Macro(m)) => {
            assert_eq!(m.line, n, "the statement keeps its line");
            if m.statement == interp_core::lang::fanuc::macros::MacroStatement::Call {
                assert_eq!(calls.read.block.line, n, "the call keeps its line");
                assert!(block.is_empty(), "a call block leaves no words");
            }
        }
        Err(kind) => {
            let _ = write!(Discard, "{kind}");
        }
    }
    // Without variables: a `#` is an alarm, never a panic.
    let _ = read_block_into(line, n, &mut block);
}

/// Arbitrary text, one block per line, through the block reader and check. The
/// first byte picks the number format (bit 0 inch, bit 1 least-increment input,
/// bit 2 IS-C).
pub fn parser(data: &[u8]) {
    use interp_core::units::{IncrementSystem, InputMode, NumberFormat, Units};
    let (&head, text) = data.split_first().unwrap_or((&0, &[]));
    let fmt = NumberFormat {
        units: if head & 1 != 0 { Units::Inch } else { Units::Metric },
        input: if head & 2 != 0 { InputMode::LeastIncrement } else { InputMode::Calculator },
        increments: if head & 4 != 0 { IncrementSystem::IsC } else { IncrementSystem::IsB },
    };
    for (n, line) in (1u32..).zip(text.split(|&b| b == b'\n')) {
        parse_line(line, n, &fmt);
    }
}

/// Arbitrary program text: loaded into program memory (so M98/M99, GOTO and
/// several O programs work) when it loads, else run as one unnamed program.
pub fn program(data: &[u8]) {
    let mut mem = Box::new(Memory::new());
    match mem.load(data, Some(0)) {
        Ok(id) => interpret(&*mem, Some(id)),
        Err(_) => interpret(&SingleProgram(data), None),
    }
}

/// Reads parameters from the fuzz input; zeros once it is used up.
struct Bytes<'a>(&'a [u8]);

impl Bytes<'_> {
    fn u8(&mut self) -> u8 {
        let (&b, rest) = self.0.split_first().unwrap_or((&0, &[]));
        self.0 = rest;
        b
    }
    fn i16(&mut self) -> i16 {
        i16::from_le_bytes([self.u8(), self.u8()])
    }
    /// A length in mm, ±327.67, 0.01 resolution.
    fn mm(&mut self) -> f64 {
        f64::from(self.i16()) / 100.0
    }
    /// A small positive amount, 0–25.5.
    fn small(&mut self) -> f64 {
        f64::from(self.u8()) / 10.0
    }
}

/// One contour block from the input: G00/G01/G02/G03 to X/Z (sometimes U/W), arcs
/// with R.
fn contour_block(b: &mut Bytes<'_>, out: &mut String) {
    let kind = b.u8();
    let g = ["G00", "G01", "G02", "G03"][usize::from(kind & 3)];
    let (x, z) = if kind & 4 != 0 { ("U", "W") } else { ("X", "Z") };
    let _ = write!(out, "{g} {x}{:.2} {z}{:.2}", b.mm(), b.mm());
    if kind & 3 >= 2 {
        let _ = write!(out, " R{:.2}", b.mm());
    }
    if kind & 8 != 0 {
        let _ = write!(out, " F{:.2}", b.small());
    }
    out.push('\n');
}

/// The contour P..Q of a multiple cycle, blocks N100 to N200.
fn contour(b: &mut Bytes<'_>, out: &mut String) {
    let n = 1 + b.u8() % 8;
    out.push_str("N100 ");
    for _ in 0..n {
        contour_block(b, out);
    }
    out.push_str("N200 ");
    contour_block(b, out);
}

/// The program around a canned cycle chosen and filled in from the input.
pub fn cycle_program(data: &[u8]) -> String {
    let mut b = Bytes(data);
    let mut p = String::new();
    let head = b.u8();
    let feed = if head & 0x80 != 0 { "G98" } else { "G99" };
    let _ = writeln!(p, "{feed} G97 S{} M03 T0101", u16::from(b.u8()) * 10);
    let _ = writeln!(p, "G00 X{:.2} Z{:.2}", b.mm(), b.mm());
    match head % 9 {
        0 => {
            let _ = writeln!(p, "G71 U{:.1} R{:.1}", b.small(), b.small());
            let _ = writeln!(p, "G71 P100 Q200 U{:.2} W{:.2} F{:.2}", b.small(), b.small(), b.small());
            contour(&mut b, &mut p);
            p.push_str("G70 P100 Q200\n");
        }
        1 => {
            let _ = writeln!(p, "G72 W{:.1} R{:.1}", b.small(), b.small());
            let _ = writeln!(p, "G72 P100 Q200 U{:.2} W{:.2} F{:.2}", b.small(), b.small(), b.small());
            contour(&mut b, &mut p);
            p.push_str("G70 P100 Q200\n");
        }
        2 => {
            let _ = writeln!(p, "G73 U{:.2} W{:.2} R{}", b.mm(), b.mm(), b.u8() % 20);
            let _ = writeln!(p, "G73 P100 Q200 U{:.2} W{:.2} F{:.2}", b.small(), b.small(), b.small());
            contour(&mut b, &mut p);
            p.push_str("G70 P100 Q200\n");
        }
        3 | 4 => {
            let g = if head % 9 == 3 { "G74" } else { "G75" };
            let _ = writeln!(p, "{g} R{:.1}", b.small());
            let (x, z) = (b.mm(), b.mm());
            let (pp, q) = (u32::from(b.u8()) * 100, u32::from(b.u8()) * 100);
            let _ = writeln!(p, "{g} X{x:.2} Z{z:.2} P{pp} Q{q} R{:.2} F{:.2}", b.small(), b.small());
        }
        5 => {
            let m = b.u8() % 100;
            let r = b.u8() % 100;
            let a = [0, 29, 30, 55, 60, 80][usize::from(b.u8() % 6)];
            let _ = writeln!(p, "G76 P{m:02}{r:02}{a:02} Q{} R{:.2}", u32::from(b.u8()) * 10, b.small() / 10.0);
            let (x, z, i) = (b.mm(), b.mm(), b.mm() / 10.0);
            let (k, d) = (u32::from(b.u8()) * 10 + 1, u32::from(b.u8()) * 10 + 1);
            let _ = writeln!(p, "G76 X{x:.2} Z{z:.2} R{i:.2} P{k} Q{d} F{:.2}", b.small());
        }
        g => {
            let code = ["G90", "G92", "G94"][usize::from(g - 6)];
            let (x, z, r) = (b.mm(), b.mm(), b.mm() / 10.0);
            let _ = writeln!(p, "{code} X{x:.2} Z{z:.2} R{r:.2} F{:.2}", b.small());
            let _ = writeln!(p, "X{:.2}", b.mm());
        }
    }
    p.push_str("G00 X100 Z100\nM30\n");
    p
}

/// A canned cycle built from the input (see [`cycle_program`]), run as [`program`] runs.
pub fn cycles(data: &[u8]) {
    let text = cycle_program(data);
    interpret(&SingleProgram(text.as_bytes()), None);
}

/// The controller on a motion core, with a synthetic spindle encoder and switch
/// inputs, driven one millisecond per poll.
struct Link {
    ctl: Box<controller::Board>,
    core: Box<MotionCore<64>>,
    inputs: controller::Inputs,
    now: u64,
    count: i64,
    out: Vec<u8>,
}

impl Link {
    fn new() -> Option<Self> {
        let cfg = MachineConfig::default();
        let start = cfg.reference[0];
        let core = Box::new(MotionCore::new(&cfg, start).ok()?);
        let ctl = Box::new(controller::Board::new(cfg, start));
        Some(Link { ctl, core, inputs: controller::Inputs::default(), now: 0, count: 0, out: Vec::new() })
    }

    /// One millisecond: the core's period, the controller's poll, the output.
    fn poll(&mut self) {
        period(&mut self.core, &mut self.now, &mut self.count);
        self.ctl.poll(self.now, &mut *self.core, &mut (), self.inputs);
        let mut buf = [0u8; 256];
        loop {
            let n = self.ctl.transmit(&mut buf);
            if n == 0 {
                break;
            }
            self.out.extend_from_slice(buf.get(..n).unwrap_or(&[]));
        }
        // Keep only the tail: what the final check looks at.
        if self.out.len() > 1 << 16 {
            self.out.drain(..self.out.len() - 4096);
        }
    }

    /// Offers `bytes` until the controller took them all or `polls` polls passed
    /// (what it did not take is dropped); true if all were taken.
    fn send(&mut self, bytes: &[u8], polls: usize) -> bool {
        let mut pending = bytes.to_vec();
        for _ in 0..polls {
            self.offer(&mut pending);
            self.poll();
            if pending.is_empty() {
                return true;
            }
        }
        false
    }

    /// Offers `pending` once, as a shell does: keeps what the controller did not
    /// take, as the controller left it (real-time bytes picked out).
    fn offer(&mut self, pending: &mut Vec<u8>) {
        let n = self.ctl.receive(pending, self.now);
        pending.drain(..n.min(pending.len()));
    }
}

/// Whether `out` holds a complete status report line `<…>`. XON/XOFF (tape mode's
/// flow control, sent between any two bytes) are not part of the text.
pub fn has_status_report(out: &[u8]) -> bool {
    let text: Vec<u8> = out.iter().copied().filter(|&b| b != 0x11 && b != 0x13).collect();
    text.split(|&b| b == b'\n').any(|l| {
        let l = strip_checksum(l.trim_ascii_end());
        l.starts_with(b"<") && l.ends_with(b">")
    })
}

/// `line` without the `*<crc>` the board appends to its lines in checksum mode.
fn strip_checksum(line: &[u8]) -> &[u8] {
    match line.len().checked_sub(5).and_then(|at| line.split_at_checked(at)) {
        Some((body, tail)) if tail[0] == b'*' && tail[1..].iter().all(u8::is_ascii_hexdigit) => body,
        _ => line,
    }
}

/// `stream` with every line framed as link line `N<k> …*<crc>` (k from 1, the
/// checksum right), so the fuzzer reaches the checked-line paths without having to
/// guess a CRC.
fn framed(stream: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(stream.len() * 2);
    for (k, line) in (1u32..).zip(stream.split(|&b| b == b'\n')) {
        let start = out.len();
        let _ = write!(Out(&mut out), "N{k} ");
        out.extend_from_slice(line);
        let crc = controller::crc::crc16(out.get(start..).unwrap_or(&[]));
        let _ = writeln!(Out(&mut out), "*{crc:04X}");
    }
    out
}

/// `write!` into a byte vector.
struct Out<'a>(&'a mut Vec<u8>);

impl std::fmt::Write for Out<'_> {
    fn write_str(&mut self, s: &str) -> std::fmt::Result {
        self.0.extend_from_slice(s.as_bytes());
        Ok(())
    }
}

/// Arbitrary bytes on the link. The first byte sets the chunk size (bits 0–4),
/// whether every line goes out framed with its checksum (bit 5, see [`framed`]) and
/// which switch changes halfway (bits 6–7: none, feed hold, e-stop, door); chunks
/// arrive one per millisecond. Afterwards the controller must answer `?` with a
/// status report within a second: a line end (which ends any partial line) and
/// the `?` behind it, offered every millisecond. The `?` must act even while the
/// line end waits behind a receive buffer full of slow jogs (a sender that
/// ignored character counting): real-time bytes do not wait for buffer space.
pub fn board(data: &[u8]) {
    let Some(mut link) = Link::new() else { return };
    let (&head, stream) = data.split_first().unwrap_or((&0, &[]));
    let chunk = usize::from(head & 31) + 1;
    let framed_stream;
    let stream = if head & 32 != 0 {
        framed_stream = framed(stream);
        framed_stream.as_slice()
    } else {
        stream
    };
    let chunks: Vec<&[u8]> = stream.chunks(chunk).collect();
    for (i, c) in chunks.iter().enumerate() {
        if i == chunks.len() / 2 {
            match head >> 6 {
                1 => link.inputs.feed_hold = true,
                2 => link.inputs.estop = true,
                3 => link.inputs.door = true,
                _ => {}
            }
        }
        link.send(c, 20);
    }
    link.inputs = controller::Inputs::default();
    for _ in 0..10 {
        link.poll();
    }
    link.out.clear();
    // ENQ with the `?`: the short link report `[LK:<last>,<free>]` comes too.
    let mut pending = b"\n?\x05".to_vec();
    for _ in 0..1_000 {
        link.offer(&mut pending);
        link.poll();
        if has_status_report(&link.out) && has_link_report(&link.out) {
            return;
        }
    }
    panic!("no status report after `?` or no `[LK:…]` after ENQ: {:?}", String::from_utf8_lossy(&link.out));
}

/// Whether `out` holds a complete link report line `[LK:<last>,<free>]` (the
/// answer to ENQ), its two numbers whole and the free bytes at most 128.
pub fn has_link_report(out: &[u8]) -> bool {
    let text: Vec<u8> = out.iter().copied().filter(|&b| b != 0x11 && b != 0x13).collect();
    text.split(|&b| b == b'\n').any(|l| {
        let l = strip_checksum(l.trim_ascii_end());
        let Some(body) = l.strip_prefix(b"[LK:").and_then(|r| r.strip_suffix(b"]")) else { return false };
        let mut it =
            body.split(|&b| b == b',').map(|n| std::str::from_utf8(n).ok().and_then(|n| n.parse::<u32>().ok()));
        matches!((it.next(), it.next(), it.next()), (Some(Some(_)), Some(Some(free)), None) if free <= 128)
    })
}

//! `lathe board`: the virtual board behind a pseudo-terminal. The board's
//! controller (the `controller` crate the firmware runs) on the simulated machine
//! (`sim`), in real time or scaled time; a sender connects to the pty as it would
//! to the board's USB serial port.

use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use clap::Args;
use serialport::{SerialPort, TTYPort};
use sim::board::VirtualBoard;

use crate::error::Error;
use crate::{jsonl, machine};

/// Arguments of `lathe board`.
#[derive(Debug, Args)]
pub struct BoardArgs {
    /// Make PATH a symbolic link to the board's pseudo-terminal (replaced if it exists).
    #[arg(long, value_name = "PATH")]
    pub pty: Option<PathBuf>,
    /// Machine description (TOML); the built-in machine without it.
    #[arg(long, value_name = "FILE")]
    pub machine: Option<PathBuf>,
    /// Time scale: 2 runs the machine twice as fast as the wall clock, 0.5 half as fast.
    #[arg(long, default_value_t = 1.0, value_name = "FACTOR")]
    pub speed: f64,
    /// Stop after this many seconds of wall-clock time (tests); runs until killed without it.
    #[arg(long, value_name = "SECONDS")]
    pub exit_after: Option<f64>,
    /// Write every canonical action the motion core accepts to FILE as JSON lines, in
    /// the format of `lathe sim --format jsonl` (to compare a streamed run with it).
    #[arg(long, value_name = "FILE")]
    pub record: Option<PathBuf>,
    /// Keep the board's store (settings, parameters, offsets, common variables
    /// #401–#600, programs) in the flash image FILE, created if missing: read at
    /// start, written while the machine is at rest, as the board keeps its flash.
    #[arg(long, value_name = "FILE")]
    pub flash: Option<PathBuf>,
    /// Line noise: corrupt this percentage of the bytes received (half of them get one
    /// bit flipped, half are dropped), to test link checksums (`lathe send --checksum`).
    #[arg(long, default_value_t = 0.0, value_name = "PERCENT")]
    pub corrupt: f64,
    /// Line noise the other way: corrupt this percentage of the bytes the board sends.
    #[arg(long, default_value_t = 0.0, value_name = "PERCENT")]
    pub corrupt_out: f64,
    /// Seed of the line noise.
    #[arg(long, default_value_t = 1, value_name = "N")]
    pub seed: u64,
    /// Log the link's traffic to FILE: a line per read or write, `<ms> < ` bytes the
    /// board received, `<ms> > ` bytes it sent, both as the other side got them
    /// (after --corrupt/--corrupt-out), non-printing bytes as `\xNN`.
    #[arg(long, value_name = "FILE")]
    pub trace: Option<PathBuf>,
    /// A mill's simulated automatic tool changer (`tool_changer = "automatic"`,
    /// `$312=1`): seconds of machine time from the board's request to its done.
    #[arg(long, default_value_t = 2.0, value_name = "SECONDS")]
    pub atc_time: f64,
    /// The simulated tool changer never reports done (a jammed changer): the board
    /// raises alarm 4511 after `$313` seconds.
    #[arg(long)]
    pub atc_never: bool,
}

/// The link's traffic in a file (`--trace`).
struct Trace {
    file: std::io::BufWriter<std::fs::File>,
}

impl Trace {
    /// One chunk: `way` `<` received, `>` sent, at `ms` of wall-clock time.
    fn chunk(&mut self, ms: f64, way: char, bytes: &[u8]) -> std::io::Result<()> {
        write!(self.file, "{ms:.1} {way} ")?;
        for &b in bytes {
            match b {
                b'\\' => self.file.write_all(b"\\\\")?,
                0x20..=0x7e => self.file.write_all(&[b])?,
                b'\n' => self.file.write_all(b"\\n")?,
                b'\r' => self.file.write_all(b"\\r")?,
                _ => write!(self.file, "\\x{b:02X}")?,
            }
        }
        // Flushed per chunk: the board is usually ended by a signal (noise.py).
        self.file.write_all(b"\n")?;
        self.file.flush()
    }
}

/// Deterministic line noise on received bytes (xorshift64*).
struct Noise {
    state: u64,
    /// Probability per byte, scaled to 2^32.
    threshold: u64,
    /// Bytes flipped and dropped so far.
    flipped: u64,
    dropped: u64,
}

impl Noise {
    fn new(percent: f64, seed: u64) -> Self {
        let threshold = (percent.clamp(0.0, 100.0) / 100.0 * 4_294_967_296.0) as u64;
        Noise { state: seed.max(1).wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1, threshold, flipped: 0, dropped: 0 }
    }

    fn next(&mut self) -> u64 {
        let mut x = self.state;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.state = x;
        x.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 32
    }

    /// Passes `bytes` through the noise into `out`.
    fn apply(&mut self, bytes: &[u8], out: &mut Vec<u8>) {
        out.clear();
        for &b in bytes {
            if self.threshold == 0 || self.next() >= self.threshold {
                out.push(b);
            } else if self.next() & 1 == 0 {
                out.push(b ^ (1 << (self.next() % 8)));
                self.flipped += 1;
            } else {
                self.dropped += 1;
            }
        }
    }
}

/// The most simulated time one loop turn may catch up (a slow host falls behind the
/// wall clock instead of stalling the link).
const MAX_CATCH_UP_NS: u64 = 50_000_000;

/// Runs the virtual board until killed (or `--exit-after`).
pub fn run(args: &BoardArgs, out: &mut dyn Write) -> Result<u8, Error> {
    if !(args.speed.is_finite() && args.speed > 0.0) {
        let message = format!("--speed must be a positive number, not {}", args.speed);
        return Err(Error::Write { target: "the virtual board".into(), source: std::io::Error::other(message) });
    }
    if !(args.atc_time.is_finite() && (0.0..=3600.0).contains(&args.atc_time)) {
        let message = format!("--atc-time must be 0 to 3600 seconds, not {}", args.atc_time);
        return Err(Error::Write { target: "the virtual board".into(), source: std::io::Error::other(message) });
    }
    let cfg = machine::load_or_default(args.machine.as_deref())?;
    let machine_error = |message: String| Error::Machine {
        path: args.machine.clone().unwrap_or_else(|| "built-in machine".into()),
        message,
    };
    let (mut board, restored) = match &args.flash {
        Some(path) => VirtualBoard::with_flash(cfg, path)
            .map(|(b, r)| (b, Some(r)))
            .map_err(|e| Error::Library { path: path.display().to_string(), message: format!("flash image: {e}") })?,
        None => (VirtualBoard::new(cfg).map_err(|k| machine_error(format!("the motion core refuses it: {k}")))?, None),
    };
    board.outputs.changer.done_after = (!args.atc_never).then(|| (args.atc_time * 1e9).round() as u64);
    let (mut master, slave) = TTYPort::pair().map_err(|e| link_error("pseudo-terminal", e))?;
    let name = slave.name().unwrap_or_default();
    if let Some(link) = &args.pty {
        make_link(link, &name)?;
    }
    let shown = args.pty.as_ref().map_or(name.clone(), |l| format!("{} -> {name}", l.display()));
    if let (Some(path), Some(r)) = (&args.flash, &restored) {
        let refused = if r.refused.is_empty() { String::new() } else { format!(", settings refused: {:?}", r.refused) };
        writeln!(out, "lathe board: store {}: {} programs{refused}", path.display(), r.programs)
            .map_err(|source| Error::Write { target: "standard output".into(), source })?;
    }
    writeln!(out, "lathe board: listening on {shown} (grbl 1.1 / FANUC tape, any baud rate)")
        .and_then(|()| out.flush())
        .map_err(|source| Error::Write { target: "standard output".into(), source })?;
    master.set_timeout(Duration::from_millis(1)).map_err(|e| link_error(&name, e))?;
    let mut record = match &args.record {
        Some(path) => {
            board.record();
            let file = std::fs::File::create(path)
                .map_err(|source| Error::Write { target: path.display().to_string(), source })?;
            Some(std::io::BufWriter::new(file))
        }
        None => None,
    };
    let mut noise = [Noise::new(args.corrupt, args.seed), Noise::new(args.corrupt_out, args.seed ^ 0x5EED_0F0F)];
    let mut trace = match &args.trace {
        Some(path) => Some(Trace {
            file: std::io::BufWriter::new(
                std::fs::File::create(path)
                    .map_err(|source| Error::Write { target: path.display().to_string(), source })?,
            ),
        }),
        None => None,
    };
    let result = serve(
        &mut board,
        &mut master,
        args,
        &mut noise,
        record.as_mut().map(|w| w as &mut dyn Write),
        trace.as_mut(),
        out,
    );
    if let Some(t) = trace.as_mut() {
        let _ = t.file.flush();
    }
    for (n, way) in noise.iter().zip(["received", "sent"]) {
        if n.threshold > 0 {
            let _ =
                writeln!(out, "lathe board: line noise flipped {} and dropped {} bytes {way}", n.flipped, n.dropped);
        }
    }
    // The slave end stays open until here, so the master never sees a hang-up
    // between two senders.
    drop(slave);
    if let Some(link) = &args.pty {
        let _ = std::fs::remove_file(link);
    }
    result.map_err(|e| Error::Write { target: name, source: e })?;
    Ok(crate::app::EXIT_OK)
}

/// The loop: bytes in, simulated time up to the (scaled) wall clock, bytes out.
/// The controller's link clock is the wall clock (its windows are the sender's
/// time whatever `--speed` is). Soft resets and feed holds the board carries out
/// are printed on `log` as they happen.
fn serve(
    board: &mut VirtualBoard,
    master: &mut TTYPort,
    args: &BoardArgs,
    noise: &mut [Noise; 2],
    mut record: Option<&mut dyn Write>,
    mut trace: Option<&mut Trace>,
    log: &mut dyn Write,
) -> std::io::Result<()> {
    let start = Instant::now();
    let mut buf = [0u8; 4096];
    let mut noisy = Vec::new();
    let cfg = board.sim.cfg.clone();
    let mut seen = board.ctl.counters();
    loop {
        let elapsed = start.elapsed();
        let wall = elapsed.as_secs_f64();
        if args.exit_after.is_some_and(|s| wall >= s) {
            return Ok(());
        }
        board.link_clock = Some(u64::try_from(elapsed.as_nanos()).unwrap_or(u64::MAX));
        match master.read(&mut buf) {
            Ok(n) => {
                noise[0].apply(&buf[..n], &mut noisy);
                if let Some(t) = trace.as_mut() {
                    t.chunk(wall * 1e3, '<', &noisy)?;
                }
                board.receive(&noisy);
            }
            Err(e) if matches!(e.kind(), std::io::ErrorKind::TimedOut | std::io::ErrorKind::WouldBlock) => {}
            // EIO: no sender has the pty open right now.
            Err(e) if e.raw_os_error() == Some(5) => std::thread::sleep(Duration::from_millis(1)),
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
        let target = (wall * args.speed * 1e9) as u64;
        let until = target.min(board.now() + MAX_CATCH_UP_NS);
        board.advance(until.max(board.now()));
        let out = board.transmit();
        if !out.is_empty() {
            noise[1].apply(&out, &mut noisy);
            if let Some(t) = trace.as_mut() {
                t.chunk(wall * 1e3, '>', &noisy)?;
            }
            master.write_all(&noisy)?;
        }
        let now = board.ctl.counters();
        if (now.resets, now.holds) != (seen.resets, seen.holds) {
            // A log nobody reads (its pipe closed) is no reason to stop the board.
            for _ in seen.resets..now.resets {
                let _ = writeln!(log, "lathe board: soft reset (0x18)");
            }
            for _ in seen.holds..now.holds {
                let _ = writeln!(log, "lathe board: feed hold (!) from the link");
            }
            let _ = log.flush();
        }
        seen = now;
        if let (Some(w), Some(done)) = (record.as_mut(), board.executed.as_mut()) {
            for c in done.drain(..) {
                serde_json::to_writer(&mut **w, &jsonl::record(&c, &cfg))?;
                w.write_all(b"\n")?;
            }
            w.flush()?;
        }
    }
}

/// Points `link` at the pty `name`, replacing an old link.
fn make_link(link: &Path, name: &str) -> Result<(), Error> {
    if link.symlink_metadata().is_ok() {
        std::fs::remove_file(link).map_err(|source| Error::Write { target: link.display().to_string(), source })?;
    }
    std::os::unix::fs::symlink(name, link).map_err(|source| Error::Write { target: link.display().to_string(), source })
}

fn link_error(what: &str, e: serialport::Error) -> Error {
    Error::Write { target: what.into(), source: std::io::Error::other(e.to_string()) }
}

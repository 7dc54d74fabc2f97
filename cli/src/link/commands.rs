//! The link subcommands: `send`, `upload`, `run`, `status`, `settings`.
//!
//! Exit status: 0 done (every line `ok`, the board back to Idle or at program end,
//! no alarm); 1 the board refused a line, raised an alarm, was reset, or the user
//! aborted; 2 the command could not do its work (file, port, no answer).

use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::time::{Duration, Instant};

use clap::Args;

use super::LinkError;
use super::keys::{self, Keys};
use super::response::{Response, Status};
use super::session::{Feeder, Origin, Session, Stats, Timing, Verdict};
use super::source::{Source, SourceLine};
use super::stream::{StreamConfig, Streamer};
use super::tape::Tape;
use super::ui::{Bar, Plain, Ui};
use super::wire::Link;
use crate::Error;

/// The port options every link command takes.
#[derive(Clone, Debug, Args)]
pub struct PortArgs {
    /// Serial port of the board (e.g. /dev/ttyUSB0, or a pty of `lathe board`).
    #[arg(long, value_name = "PORT")]
    pub port: String,
    /// Baud rate (any rate works on a pty or USB CDC).
    #[arg(long, value_name = "N", default_value_t = 115_200)]
    pub baud: u32,
    /// No progress bar and no keys: plain log lines on standard output (automatic
    /// when standard error is not a terminal).
    #[arg(long, short)]
    pub quiet: bool,
}

/// Options of `lathe send`.
#[derive(Clone, Debug, Args)]
pub struct SendArgs {
    /// Program file.
    #[arg(value_name = "PROGRAM")]
    pub program: PathBuf,
    /// Port options.
    #[command(flatten)]
    pub port: PortArgs,
    /// FANUC tape mode: `%`, the program, `%` with XON/XOFF flow control (drip feed).
    #[arg(long, conflicts_with = "checksum")]
    pub tape: bool,
    /// Frame every line as `N<k> line*<CRC-16>` and resend what the board asks for.
    #[arg(long)]
    pub checksum: bool,
}

/// Options of `lathe upload`.
#[derive(Clone, Debug, Args)]
pub struct UploadArgs {
    /// Program file.
    #[arg(value_name = "PROGRAM")]
    pub program: PathBuf,
    /// Port options.
    #[command(flatten)]
    pub port: PortArgs,
    /// Store as program number N (replacing the file's own O number; needed when it has none).
    #[arg(long = "as", value_name = "N", value_parser = clap::value_parser!(u32).range(1..=9999))]
    pub number: Option<u32>,
}

/// Options of `lathe run`.
#[derive(Clone, Debug, Args)]
pub struct RunArgs {
    /// Program number in the board's memory.
    #[arg(value_name = "N", value_parser = clap::value_parser!(u32).range(1..=9999))]
    pub number: u32,
    /// Port options.
    #[command(flatten)]
    pub port: PortArgs,
}

/// Options of `lathe status`.
#[derive(Clone, Debug, Args)]
pub struct StatusArgs {
    /// Port options.
    #[command(flatten)]
    pub port: PortArgs,
    /// Keep reporting every 200 ms (one line per report that differs) until interrupted.
    #[arg(long)]
    pub watch: bool,
}

/// Options of `lathe settings`.
#[derive(Clone, Debug, Args)]
pub struct SettingsArgs {
    /// Settings to write, `$n=value` (or `n=value`), numbered parameters as
    /// `$Pn=value` (`$P6050=100`); without any, print all (`$$`).
    #[arg(value_name = "$n=value", value_parser = parse_setting)]
    pub writes: Vec<String>,
    /// Port options.
    #[command(flatten)]
    pub port: PortArgs,
    /// List the programs in the board's memory (`$PL`) instead.
    #[arg(long, conflicts_with = "writes")]
    pub programs: bool,
    /// Unlock the board after an alarm (`$X`) first.
    #[arg(long)]
    pub unlock: bool,
}

/// `$n=value` or `n=value` → `$n=value`; a parameter `$Pn=value` (`Pn=value`)
/// likewise.
fn parse_setting(s: &str) -> Result<String, String> {
    let body = s.strip_prefix('$').unwrap_or(s);
    let (key, value) = body.split_once('=').ok_or("expected $n=value")?;
    let n = key.strip_prefix(['P', 'p']).unwrap_or(key);
    if n.is_empty() || !n.bytes().all(|b| b.is_ascii_digit()) {
        return Err("the setting number must be digits, as in $110=500 (a parameter: $P6050=100)".into());
    }
    let key = if n.len() < key.len() { format!("P{n}") } else { n.to_string() };
    if value.is_empty() || !value.bytes().all(|b| b.is_ascii_graphic() && !matches!(b, b'?' | b'!' | b'~')) {
        return Err("the value must be printable characters without blanks".into());
    }
    Ok(format!("${key}={value}"))
}

/// How long a `$` command may take to be answered.
const COMMAND_WAIT: Duration = Duration::from_secs(3);
/// How long the welcome may take after a soft reset.
const WELCOME_WAIT: Duration = Duration::from_secs(3);
/// How long a status report may take.
const STATUS_WAIT: Duration = Duration::from_secs(1);
/// The states of a status report (docs/PROTOCOL.md).
const STATES: [&str; 10] = ["Idle", "Run", "Hold", "Jog", "Alarm", "Door", "Check", "Home", "Sleep", "Tool"];
/// Tape bytes written at a time.
const TAPE_CHUNK: usize = 16;

/// A board that was reset and found Idle, with its `Bf:` then (nothing queued).
struct Board {
    link: Link,
    empty: Option<(u32, u32)>,
}

/// Opens the port, soft-resets the board, waits for its welcome, and checks it is
/// Idle. The reset is tried three times (line noise may spoil it or its welcome; a
/// board left with checksums on by an earlier job needs 0x18 LF), the status report
/// asked until it names a state.
fn connect(port: &PortArgs, checksum: bool, ui: &mut dyn Ui) -> Result<Board, LinkError> {
    let mut link = Link::open(&port.port, port.baud)?;
    let mut tries = 0;
    let welcome = loop {
        tries += 1;
        link.set_checked(tries % 2 == 0);
        match link.reset(WELCOME_WAIT / 3) {
            Ok(w) => break w,
            Err(LinkError::Timeout { .. }) if tries < 4 => {}
            Err(e) => return Err(e),
        }
    };
    ui.note(&format!("connected to {}: {welcome}", port.port));
    if checksum {
        // Checked answers first: a plain status report may not come through the
        // line noise checksums are for.
        let empty = start_checksums(&mut link, ui)?;
        return Ok(Board { link, empty });
    }
    let mut s = link.status(STATUS_WAIT)?;
    for _ in 0..4 {
        let (name, sub) = s.state.split_once(':').unwrap_or((&s.state, "0"));
        if STATES.contains(&name) && matches!(sub, "0" | "1") {
            break;
        }
        s = link.status(STATUS_WAIT)?;
    }
    match s.state.as_str() {
        "Idle" => Ok(Board { link, empty: s.buffer }),
        "Alarm" => Err(LinkError::NotReady {
            state: s.state,
            hint: "clear the cause, then unlock it (lathe settings --unlock)",
        }),
        _ => Err(LinkError::NotReady { state: s.state, hint: "it must be Idle to start a job" }),
    }
}

/// The display: a bar with keys on a terminal, plain lines to `out` otherwise.
fn display<'a>(port: &PortArgs, total: usize, out: &'a mut dyn Write) -> (Box<dyn Ui + 'a>, Option<Keys>) {
    if port.quiet || !std::io::stderr().is_terminal() {
        return (Box::new(Plain::new(out)), None);
    }
    let keys = Keys::open();
    let help = if keys.is_some() { keys::HELP } else { "" };
    (Box::new(Bar::new(total, help)), keys)
}

/// Connects, runs `feeder` to its verdict, reports it; returns the exit status.
fn job(
    port: &PortArgs,
    checksum: bool,
    preamble: &[&str],
    feeder: Feeder,
    origin: Origin,
    out: &mut dyn Write,
    err: &mut dyn Write,
) -> Result<(u8, Option<Board>), Error> {
    let total = match &feeder {
        Feeder::Counting(s) => s.total(),
        Feeder::Tape(t) => t.total(),
    };
    let (mut ui, keys) = display(port, total, out);
    let mut board = connect(port, checksum, ui.as_mut())?;
    if let Feeder::Tape(_) = feeder {
        // The board chooses tape mode only when nothing grbl-like came since its last
        // reset, and connecting asked for a status report.
        board.link.reset(WELCOME_WAIT)?;
    }
    for command in preamble {
        settle(&mut board.link, command)?;
    }
    let started = Instant::now();
    let (verdict, stats) = Session::new(&mut board.link, ui.as_mut(), feeder, origin.clone(), board.empty)
        .with_keys(keys.as_ref())
        .with_timing(Timing::at_baud(port.baud))
        .run_stats()?;
    drop(keys);
    let status = verdict.exit_status();
    match verdict {
        Verdict::Done => {
            ui.note(&format!("{}: done in {:.1} s", origin.name, started.elapsed().as_secs_f64()));
            ui.note(&link_figures(&stats, checksum, board.link.resets()));
        }
        v => {
            drop(ui);
            writeln!(err, "lathe: {}: {}", origin.name, describe(&v)).map_err(write_err)?;
        }
    }
    Ok((status, Some(board)))
}

/// A verdict other than done, in words.
fn describe(v: &Verdict) -> String {
    match v {
        Verdict::Done => "done".into(),
        Verdict::Refused(t) => format!("stopped: the board refused a line ({t})"),
        Verdict::Alarm(t) => format!("stopped by an alarm ({t})"),
        Verdict::Aborted(how) => format!("stopped: {how} by the user"),
        Verdict::BoardReset => "stopped: the board was reset during the job".into(),
    }
}

/// An error writing standard error.
fn write_err(source: std::io::Error) -> Error {
    Error::Write { target: "standard error".into(), source }
}

/// The origin of `lines` of the file `name`.
fn origin(name: &str, lines: &[SourceLine]) -> Origin {
    Origin { name: name.to_owned(), file_lines: lines.iter().map(|l| l.file_line).collect(), command: None }
}

/// The texts of `lines`.
fn texts(lines: &[SourceLine]) -> Vec<String> {
    lines.iter().map(|l| l.text.clone()).collect()
}

/// `lathe send`: streams the program (grbl mode, or tape mode with `--tape`).
pub fn send(args: &SendArgs, out: &mut dyn Write, err: &mut dyn Write) -> Result<u8, Error> {
    let src = Source::read(&args.program)?;
    let (feeder, lines) = if args.tape {
        let lines = src.drip_lines();
        (Feeder::Tape(Tape::new(&texts(&lines), TAPE_CHUNK)), lines)
    } else {
        let lines = src.stream_lines();
        let cfg = StreamConfig {
            checksum: args.checksum,
            silence: StreamConfig::silence_at(args.port.baud),
            ..StreamConfig::default()
        };
        let streamer = Streamer::new(texts(&lines), cfg).map_err(|t| Error::Unsendable {
            path: args.program.clone(),
            line: lines.get(t.index).map_or(0, |l| l.file_line),
            message: format!("{} bytes framed with the checksum; the board takes at most 128", t.bytes),
        })?;
        (Feeder::Counting(streamer), lines)
    };
    // With checksums the board is told first (`$LN=1`), so the very first program
    // line is already checked: before it, a line whose framing noise has destroyed
    // would be read as plain text.
    let checksum = args.checksum && !args.tape;
    job(&args.port, checksum, &[], feeder, origin(&src.name, &lines), out, err).map(|(status, _)| status)
}

/// Switches the board's link checksums on: `$LN=1`, answered `[LN:1]` (line noise
/// can spoil an unframed `$` command — a damaged `$LN=1` could set another number —
/// or its answer; from it on the board's lines carry their CRC). Five tries, each
/// after a soft reset but the first. Then a status report, if one comes through the
/// noise within a second: the `Bf:` of the idle board.
fn start_checksums(link: &mut Link, ui: &mut dyn Ui) -> Result<Option<(u32, u32)>, LinkError> {
    let mut last = String::new();
    for attempt in 0..5 {
        if attempt > 0 {
            ui.note("soft reset (checksums not confirmed)");
            match link.reset(WELCOME_WAIT / 3) {
                Ok(_) | Err(LinkError::Timeout { .. }) => {}
                Err(e) => return Err(e),
            }
        }
        // The board's answers are framed from `$LN=1` on.
        link.set_checked(true);
        link.write(b"$LN=1\n")?;
        let deadline = Instant::now() + COMMAND_WAIT / 3;
        loop {
            match link.line_until(deadline, "[LN:1]") {
                Ok(Response::Feedback(f)) if f == "[LN:1]" => {
                    // Its `ok` follows (or was lost): the status report, when one
                    // comes through, passes over it.
                    let s = link.status(STATUS_WAIT).ok().filter(|s| s.state == "Idle");
                    return Ok(s.and_then(|s| s.buffer));
                }
                Ok(r) => last = format!("{r:?}"),
                Err(LinkError::Timeout { .. }) => break,
                Err(e) => return Err(e),
            }
        }
        // The board may have taken a damaged number and switched checksums on:
        // the next reset goes as 0x18 LF (on a board without them the LF is a blank
        // line, answered and forgotten).
        link.set_checked(true);
    }
    Err(LinkError::Timeout { port: link.name().to_owned(), what: format!("checksums switched on ($LN=1): {last}") })
}

/// How the link went, in one line: `streamed 2005 lines in 12.3 s (163 lines/s);
/// 31 resend requests, 2 resyncs, 12 damaged answers, 1 soft resets sent`.
fn link_figures(s: &Stats, checksum: bool, resets: u32) -> String {
    let time = s.streamed.map_or(0.0, |d| d.as_secs_f64());
    let rate = if time > 0.0 { s.lines as f64 / time } else { 0.0 };
    let mut t = format!("streamed {} lines in {time:.2} s ({rate:.0} lines/s)", s.lines);
    if checksum {
        t.push_str(&format!(
            "; {} resend requests, {} resyncs, {} damaged answers, {resets} soft resets sent",
            s.resend_requests, s.resyncs, s.damaged
        ));
    }
    t
}

/// Sends the `$` command `command` until the board answers `ok` (a line noise can
/// spoil a command too: three tries).
fn settle(link: &mut Link, command: &str) -> Result<(), Error> {
    let mut tries = 0;
    loop {
        tries += 1;
        match link.command(command, COMMAND_WAIT) {
            Ok(_) => return Ok(()),
            Err(LinkError::Refused { .. }) if tries < 3 => {}
            Err(e) => return Err(e.into()),
        }
    }
}

/// `lathe upload`: punches the program into the board's memory in tape mode, then
/// checks `$PL` lists it.
pub fn upload(args: &UploadArgs, out: &mut dyn Write, err: &mut dyn Write) -> Result<u8, Error> {
    let src = Source::read(&args.program)?;
    let Some(number) = args.number.or(src.o_number()) else {
        return Err(Error::Unsendable {
            path: args.program.clone(),
            line: 1,
            message: "the program has no O number; give one with --as N".into(),
        });
    };
    let lines = src.upload_lines(number);
    let feeder = Feeder::Tape(Tape::new(&texts(&lines), TAPE_CHUNK));
    let (status, board) = job(&args.port, false, &[], feeder, origin(&src.name, &lines), out, err)?;
    match board {
        Some(mut b) if status == 0 => verify_stored(&mut b.link, number, out, err),
        _ => Ok(status),
    }
}

/// Asks `$PL` whether program `number` is stored; prints it.
fn verify_stored(link: &mut Link, number: u32, out: &mut dyn Write, err: &mut dyn Write) -> Result<u8, Error> {
    let name = format!("O{number:04}");
    let listing = link.command("$PL", COMMAND_WAIT)?;
    let prefix = format!("[PRG:{name},");
    match listing.iter().find_map(|l| l.strip_prefix(&prefix)?.strip_suffix(']')) {
        Some(bytes) => {
            writeln!(out, "stored {name} ({bytes} bytes)")
                .map_err(|source| Error::Write { target: "standard output".into(), source })?;
            Ok(0)
        }
        None => {
            writeln!(err, "lathe: the board does not list {name} after the upload").map_err(write_err)?;
            Ok(1)
        }
    }
}

/// `lathe run`: `$PR=N`, then follows the program to its end like `send`.
pub fn run(args: &RunArgs, out: &mut dyn Write, err: &mut dyn Write) -> Result<u8, Error> {
    let command = format!("$PR={}", args.number);
    let streamer = Streamer::new(vec![command.clone()], StreamConfig::default()).map_err(|_| Error::Unsendable {
        path: command.clone().into(),
        line: 1,
        message: "longer than the board's receive buffer".into(),
    })?;
    let origin = Origin { name: format!("O{:04}", args.number), file_lines: Vec::new(), command: Some(command) };
    job(&args.port, false, &[], Feeder::Counting(streamer), origin, out, err).map(|(status, _)| status)
}

/// `lathe status`: one report, pretty-printed; with `--watch` one line per change.
pub fn status(args: &StatusArgs, out: &mut dyn Write) -> Result<u8, Error> {
    let mut link = Link::open(&args.port.port, args.port.baud)?;
    let s = link.status(STATUS_WAIT)?;
    let print = |out: &mut dyn Write, text: &str| {
        out.write_all(text.as_bytes())
            .and_then(|()| out.flush())
            .map_err(|source| Error::Write { target: "standard output".into(), source })
    };
    if !args.watch {
        print(out, &pretty(&s))?;
        return Ok(0);
    }
    let mut last = String::new();
    loop {
        let line = link.status(STATUS_WAIT)?.summary();
        if line != last {
            print(out, &format!("{line}\n"))?;
            last = line;
        }
        std::thread::sleep(Duration::from_millis(200));
    }
}

/// A status report as a small table.
pub fn pretty(s: &Status) -> String {
    let num = |v: Option<f64>| v.map_or("-".to_owned(), |v| format!("{v:.3}"));
    let whole = |v: Option<f64>| v.map_or("-".to_owned(), |v| format!("{v:.0}"));
    let mut t = String::new();
    t.push_str(&format!("state      {}\n", s.state));
    t.push_str(&format!("work       X {} (diameter)  Z {}\n", num(s.work(0)), num(s.work(2))));
    t.push_str(&format!("machine    X {}  Z {}\n", num(s.mpos.first().copied()), num(s.mpos.get(2).copied())));
    t.push_str(&format!("feed       {} mm/min\n", whole(s.feed)));
    t.push_str(&format!("spindle    {} rpm\n", whole(s.rpm)));
    t.push_str(&format!("line       {}\n", s.line.map_or("-".to_owned(), |l| l.to_string())));
    if let Some((f, r, sp)) = s.overrides {
        t.push_str(&format!("overrides  feed {f} %, rapid {r} %, spindle {sp} %\n"));
    }
    if let Some((blocks, bytes)) = s.buffer {
        t.push_str(&format!("free       {blocks} planner blocks, {bytes} receive bytes\n"));
    }
    t.push_str(&format!("inputs     {}\n", if s.pins.is_empty() { "none" } else { &s.pins }));
    t
}

/// `lathe settings`: prints `$$` (or `$PL` with `--programs`), or writes settings.
pub fn settings(args: &SettingsArgs, out: &mut dyn Write, err: &mut dyn Write) -> Result<u8, Error> {
    let mut link = Link::open(&args.port.port, args.port.baud)?;
    let mut commands: Vec<String> = Vec::new();
    if args.unlock {
        commands.push("$X".into());
    }
    if args.programs {
        commands.push("$PL".into());
    } else if args.writes.is_empty() {
        commands.push("$$".into());
    } else {
        commands.extend(args.writes.iter().cloned());
    }
    for c in &commands {
        match link.command(c, COMMAND_WAIT) {
            Ok(lines) => print_lines(out, c, &lines, !args.writes.is_empty())?,
            Err(e @ LinkError::Refused { .. }) => {
                writeln!(err, "lathe: {e}").map_err(write_err)?;
                return Ok(1);
            }
            Err(e) => return Err(e.into()),
        }
    }
    Ok(0)
}

/// The lines a command printed, or `command ok` for a write that printed nothing.
fn print_lines(out: &mut dyn Write, command: &str, lines: &[String], confirm: bool) -> Result<(), Error> {
    let mut text: String = lines.iter().map(|l| format!("{l}\n")).collect();
    if confirm && lines.is_empty() {
        text = format!("{command} ok\n");
    }
    out.write_all(text.as_bytes()).map_err(|source| Error::Write { target: "standard output".into(), source })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settings_are_written_with_their_dollar() {
        assert_eq!(parse_setting("$110=500"), Ok("$110=500".into()));
        assert_eq!(parse_setting("300=1"), Ok("$300=1".into()));
        assert_eq!(parse_setting("$P6050=100"), Ok("$P6050=100".into()));
        assert_eq!(parse_setting("p6001=1"), Ok("$P6001=1".into()));
        assert!(parse_setting("$P=1").is_err());
        assert!(parse_setting("$X").is_err());
        assert!(parse_setting("$1a=2").is_err());
        assert!(parse_setting("$1=").is_err());
        assert!(parse_setting("$1=2 3").is_err());
    }

    #[test]
    fn a_status_report_pretty_printed() {
        let s = Status::parse(
            "Idle|MPos:60.000,0.000,-12.500|FS:0,0|Bf:64,128|Ln:0|WCO:10.000,0.000,-2.500|Ov:100,100,100",
        );
        assert_eq!(
            pretty(&s),
            "state      Idle\n\
             work       X 50.000 (diameter)  Z -10.000\n\
             machine    X 60.000  Z -12.500\n\
             feed       0 mm/min\n\
             spindle    0 rpm\n\
             line       0\n\
             overrides  feed 100 %, rapid 100 %, spindle 100 %\n\
             free       64 planner blocks, 128 receive bytes\n\
             inputs     none\n"
        );
    }
}

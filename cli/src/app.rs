//! The command line: arguments (clap), the commands, and exit statuses.
//!
//! Exit status 0: done, no alarms; 1: the program raised an alarm; 2: an error
//! (bad arguments, unreadable file, bad machine file, output not writable).

use std::ffi::OsString;
use std::io::Write;
use std::path::{Path, PathBuf};

use clap::{Args, Parser, Subcommand, ValueEnum};
use interp_core::config::Language;
use interp_core::{MachineConfig, Panel};

use crate::error::Error;
use crate::motion::{self, Motion};
use crate::program::{OnAlarm, Programs, Run, Runaway, run_programs};
use crate::summary::Summary;
use crate::{docs, jsonl, link, machine, svg, vars};

/// Exit status: done, no alarms.
pub const EXIT_OK: u8 = 0;
/// Exit status: a program raised an alarm.
pub const EXIT_ALARM: u8 = 1;
/// Exit status: the command could not do its work.
pub const EXIT_ERROR: u8 = 2;

/// Check and simulate lathe part programs (FANUC-style, G-code systems A/B/C), and send them to the board.
#[derive(Debug, Parser)]
#[command(name = "lathe", version, max_term_width = 100)]
#[command(after_help = "Exit status: 0 no alarms (or the board's job done), 1 alarm (or the board \
                         refused, alarmed or was stopped), 2 error.")]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Interpret programs without motion and report every alarm as PROGRAM:LINE: alarm CODE: message
    ///
    /// A block with an alarm is passed over (it changes nothing) and checking goes on with
    /// the next one. Alarms go to standard output, followed by one line per program:
    /// `PROGRAM: N blocks, no alarms` (or `K alarms`). The axes start at reference position 1.
    Check {
        /// Program files.
        #[arg(required = true, value_name = "PROGRAM")]
        programs: Vec<PathBuf>,
        /// Machine description (TOML); the built-in machine without it.
        #[arg(long, value_name = "FILE")]
        machine: Option<PathBuf>,
        /// Subprograms, macro variables and inputs.
        #[command(flatten)]
        run: RunArgs,
    },
    /// Run a program as the control would, stopping at the first alarm
    ///
    /// The axes start at reference position 1, where a homed machine stands. M00, and M01
    /// with --optional-stop, are answered with cycle start. The summary (and --trace) come
    /// from running the motion core on a simulated machine: cycle time with acceleration,
    /// and how far the stepped axes strayed from the programmed path. An alarm is printed
    /// to standard error as `lathe check` prints it (exit status 1); the output up to it is
    /// still written.
    Sim(SimArgs),
    /// Print the alarm catalog as Markdown (docs/ALARMS.md)
    Alarms,
    /// Print the parameter table as Markdown (docs/PARAMETERS.md)
    Params,
    /// Print the machine description in force as TOML (the built-in one without --machine)
    Machine {
        /// Machine description (TOML) to read and print back complete.
        #[arg(long, value_name = "FILE")]
        machine: Option<PathBuf>,
    },
    /// The virtual board: the board's controller on the simulated machine behind a pty
    ///
    /// Prints the pseudo-terminal it listens on (and links --pty PATH to it); a sender
    /// (`lathe send`, or any grbl 1.1 sender) connects there exactly as to the board. Runs
    /// in real time (--speed scales it) until killed.
    Board(crate::board::BoardArgs),
    /// Stream a program to the board and follow it to its end
    ///
    /// grbl 1.1 streaming with character counting (at most 128 bytes unanswered), or FANUC
    /// tape mode with --tape. The board is soft-reset first and must come up Idle. The
    /// program goes line by line as it is (CR dropped; a leading `%` line as an empty line,
    /// nothing after a closing `%`). Keys on a terminal: ! or space feed hold, ~ or c
    /// resume, x soft reset, q abort. Exit status 0 only when every line got `ok` and the
    /// board reached program end or went back to Idle with nothing queued.
    Send(link::commands::SendArgs),
    /// Store a program in the board's memory (tape mode, `%` O-number … `%`), checked with $PL
    Upload(link::commands::UploadArgs),
    /// Run program N from the board's memory ($PR=N) and follow it to its end like send
    Run(link::commands::RunArgs),
    /// Print the board's status report (position, feed, spindle, line, buffers)
    Status(link::commands::StatusArgs),
    /// Print the board's settings ($$), write settings ($n=value …), or list its programs
    Settings(link::commands::SettingsArgs),
}

/// What programs run with besides their own text: subprograms, the common
/// variables and the external inputs (`lathe check` and `lathe sim`).
#[derive(Debug, Default, Args)]
pub struct RunArgs {
    /// Subprograms for M98: every .nc file of a directory, or one program file (a file
    /// may hold several O programs). May be given several times.
    #[arg(long, value_name = "DIR|FILE")]
    pub lib: Vec<PathBuf>,
    /// Common variables #401-#600 kept through power-off, as `#n = value` lines: `sim`
    /// reads FILE and writes it back after the run (creating it), `check` only reads it.
    #[arg(long, value_name = "FILE")]
    pub vars: Option<PathBuf>,
    /// External input N (0-31) at 0 or 1, e.g. --input 0=1 for M91/M92 (the machine's
    /// jump_input); inputs not given are 0. May be given several times.
    #[arg(long, value_name = "N=0|1", value_parser = parse_input)]
    pub input: Vec<(u8, bool)>,
    /// Language the programs are written in: `siemens` (SINUMERIK 840D) or `fanuc`.
    /// Without it, `.mpf`/`.spf` files are SINUMERIK programs and others are in the
    /// machine's power-on language (machine file `language`, FANUC by default).
    #[arg(long, value_enum, value_name = "LANG")]
    pub lang: Option<LangArg>,
}

/// The language of `--lang`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum LangArg {
    /// The FANUC-style lathe dialect (ISO).
    Fanuc,
    /// SINUMERIK 840D.
    Siemens,
}

/// `N=0` or `N=1` with N in 0–31.
fn parse_input(s: &str) -> Result<(u8, bool), String> {
    let (n, v) = s.split_once('=').ok_or("expected N=0 or N=1")?;
    let n: u8 = n.trim().parse().ok().filter(|n| *n < 32).ok_or("input number must be 0-31")?;
    match v.trim() {
        "0" => Ok((n, false)),
        "1" => Ok((n, true)),
        _ => Err("input value must be 0 or 1".into()),
    }
}

impl RunArgs {
    /// The language program file `path` is read in on machine `cfg`: `--lang`,
    /// else SINUMERIK for `.mpf`/`.spf`, else the machine's.
    pub fn language(&self, path: &Path, cfg: &MachineConfig) -> Language {
        match self.lang {
            Some(LangArg::Fanuc) => Language::Fanuc,
            Some(LangArg::Siemens) => Language::Siemens,
            None => crate::program::language_of(path).unwrap_or(cfg.language),
        }
    }

    /// The machine `cfg` with the language of `path` in force at the start.
    fn machine_for(&self, path: &Path, cfg: &MachineConfig) -> MachineConfig {
        MachineConfig { language: self.language(path, cfg), ..cfg.clone() }
    }

    /// The input bits of [`Panel::inputs`].
    fn inputs(&self) -> u32 {
        self.input.iter().fold(0, |bits, &(n, on)| if on { bits | 1 << n } else { bits & !(1 << n) })
    }

    /// The macro variables a run starts with: the commons of `--vars`.
    fn variables(&self) -> Result<interp_core::lang::fanuc::macros::Variables, Error> {
        match &self.vars {
            Some(path) => vars::read(path),
            None => Ok(interp_core::lang::fanuc::macros::Variables::new()),
        }
    }
}

/// Options of `lathe sim`.
#[derive(Debug, Args)]
pub struct SimArgs {
    /// Program file.
    #[arg(value_name = "PROGRAM")]
    pub program: PathBuf,
    /// Machine description (TOML); the built-in machine without it.
    #[arg(long, value_name = "FILE")]
    pub machine: Option<PathBuf>,
    /// Output: summary, one JSON object per action, or an X-Z drawing.
    #[arg(long, value_enum, default_value_t = Format::Summary)]
    pub format: Format,
    /// Write the output to FILE instead of standard output.
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Block skip switches on: `/` and `/1` without LEVELS, else e.g. --block-skip=1,3.
    #[arg(
        long,
        value_name = "LEVELS",
        num_args = 0..=1,
        require_equals = true,
        default_missing_value = "1",
        value_delimiter = ',',
        value_parser = clap::value_parser!(u8).range(1..=9)
    )]
    pub block_skip: Option<Vec<u8>>,
    /// Optional-stop switch on: M01 stops (and is answered with cycle start).
    #[arg(long)]
    pub optional_stop: bool,
    /// Subprograms, macro variables and inputs.
    #[command(flatten)]
    pub run: RunArgs,
    /// Write the simulated step events to FILE as CSV `t_s,x_mm,z_mm,spindle_deg`, one row
    /// per step (work coordinates, X as a diameter, the encoder's cumulative angle).
    #[arg(long, value_name = "FILE")]
    pub trace: Option<PathBuf>,
}

/// Output format of `lathe sim`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// Counts, path lengths, extents and cycle time.
    Summary,
    /// One JSON object per canonical action.
    Jsonl,
    /// The X-Z tool path as SVG.
    Svg,
}

/// Runs the command line `args` (program name first), writing to `out` and
/// `err`; returns the exit status.
pub fn main<I, T>(args: I, out: &mut dyn Write, err: &mut dyn Write) -> u8
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let cli = match Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(e) => {
            let text = e.render().to_string();
            let _ = if e.use_stderr() { err.write_all(text.as_bytes()) } else { out.write_all(text.as_bytes()) };
            return u8::try_from(e.exit_code()).unwrap_or(EXIT_ERROR);
        }
    };
    match execute(cli.command, out, err) {
        Ok(status) => status,
        Err(e) => {
            let _ = writeln!(err, "lathe: {e}");
            EXIT_ERROR
        }
    }
}

/// Runs one command.
fn execute(command: Command, out: &mut dyn Write, err: &mut dyn Write) -> Result<u8, Error> {
    match command {
        Command::Check { programs, machine, run } => check(&programs, machine.as_deref(), &run, out, err),
        Command::Sim(args) => sim(&args, out, err),
        Command::Alarms => print(out, &docs::alarms_markdown()),
        Command::Params => print(out, &docs::params_markdown()),
        Command::Machine { machine } => {
            let cfg = machine::load_or_default(machine.as_deref())?;
            let text = machine::to_toml(&cfg)
                .map_err(|e| Error::Write { target: STDOUT.into(), source: std::io::Error::other(e) })?;
            print(out, &text)
        }
        Command::Board(args) => crate::board::run(&args, out),
        Command::Send(args) => link::commands::send(&args, out, err),
        Command::Upload(args) => link::commands::upload(&args, out, err),
        Command::Run(args) => link::commands::run(&args, out, err),
        Command::Status(args) => link::commands::status(&args, out),
        Command::Settings(args) => link::commands::settings(&args, out, err),
    }
}

/// Writes `text` to standard output.
fn print(out: &mut dyn Write, text: &str) -> Result<u8, Error> {
    out.write_all(text.as_bytes()).map_err(stream_error(STDOUT))?;
    Ok(EXIT_OK)
}

/// An error writing to the standard stream `target` ("standard output" or "standard error").
fn stream_error(target: &'static str) -> impl Fn(std::io::Error) -> Error {
    move |source| Error::Write { target: target.into(), source }
}

/// The name of standard output in messages.
const STDOUT: &str = "standard output";
/// The name of standard error in messages.
const STDERR: &str = "standard error";

/// `lathe check`: every program, every alarm; a file that cannot be read is
/// reported and the others are still checked.
fn check(
    programs: &[PathBuf],
    machine: Option<&Path>,
    args: &RunArgs,
    out: &mut dyn Write,
    err: &mut dyn Write,
) -> Result<u8, Error> {
    let cfg = machine::load_or_default(machine)?;
    let variables = args.variables()?;
    let panel = Panel { inputs: args.inputs(), ..Panel::default() };
    let mut status = EXIT_OK;
    for path in programs {
        match check_one(path, &cfg, args, &panel, &variables, out) {
            Ok(alarms) if alarms > 0 => status = status.max(EXIT_ALARM),
            Ok(_) => {}
            Err(e @ Error::Write { .. }) => return Err(e),
            Err(e) => {
                writeln!(err, "lathe: {e}").map_err(stream_error(STDERR))?;
                status = EXIT_ERROR;
            }
        }
    }
    Ok(status)
}

/// Checks one program, printing its alarms and a closing line; returns the number
/// of alarms. A program that never ends gets its alarms printed, then the error.
fn check_one(
    path: &Path,
    cfg: &MachineConfig,
    args: &RunArgs,
    panel: &Panel,
    variables: &interp_core::lang::fanuc::macros::Variables,
    out: &mut dyn Write,
) -> Result<usize, Error> {
    let cfg = &args.machine_for(path, cfg);
    let programs = Programs::load(path, &args.lib, cfg.language)?;
    let name = path.display().to_string();
    let (r, runaway) = match run_programs(&programs, cfg, panel, OnAlarm::Continue, variables) {
        Ok(r) => (r, false),
        Err(Runaway(r)) => (*r, true),
    };
    let mut report = String::new();
    for &m in &r.messages {
        report.push_str(&r.message_line(&name, m));
        report.push('\n');
    }
    for a in &r.alarms {
        report.push_str(&r.alarm_line(&name, a));
        report.push('\n');
    }
    if !runaway {
        let verdict = match r.alarms.len() {
            0 => "no alarms".to_owned(),
            1 => "1 alarm".to_owned(),
            n => format!("{n} alarms"),
        };
        report.push_str(&format!("{name}: {} blocks, {verdict}\n", r.blocks));
    }
    out.write_all(report.as_bytes()).map_err(stream_error(STDOUT))?;
    if runaway {
        return Err(Error::Runaway { path: path.to_owned() });
    }
    Ok(r.alarms.len())
}

/// `lathe sim`: run, write the output (also what was produced before an alarm),
/// then report the alarm; with --vars, write the common variables back.
fn sim(args: &SimArgs, out: &mut dyn Write, err: &mut dyn Write) -> Result<u8, Error> {
    let cfg = machine::load_or_default(args.machine.as_deref())?;
    let cfg = args.run.machine_for(&args.program, &cfg);
    let programs = Programs::load(&args.program, &args.run.lib, cfg.language)?;
    let variables = args.run.variables()?;
    let name = args.program.display().to_string();
    let mut r = run_programs(&programs, &cfg, &panel(args), OnAlarm::Stop, &variables)
        .map_err(|_| Error::Runaway { path: args.program.clone() })?;
    if let Some(path) = &args.run.vars {
        vars::write(path, &r.variables)?;
    }
    let motion = if args.format == Format::Summary || args.trace.is_some() {
        let m = motion::simulate(&programs, &cfg, &panel(args), &variables, args.trace.as_deref())?;
        // A motion alarm stops the machine where the program was then.
        r.alarms.extend(m.alarm);
        r.alarms.sort_by_key(|a| (a.program, a.line));
        Some(m)
    } else {
        None
    };
    let overlay = match args.format {
        Format::Svg => compensation_overlay(&programs, &cfg, &panel(args), &variables, &r),
        _ => None,
    };
    let output =
        render(args.format, &name, &r, &cfg, motion.as_ref(), overlay.as_ref()).map_err(stream_error(STDOUT))?;
    match &args.out {
        Some(path) => std::fs::write(path, output)
            .map_err(|source| Error::Write { target: path.display().to_string(), source })?,
        None => out.write_all(&output).map_err(stream_error(STDOUT))?,
    }
    for &m in &r.messages {
        writeln!(err, "{}", r.message_line(&name, m)).map_err(stream_error(STDERR))?;
    }
    for a in &r.alarms {
        writeln!(err, "{}", r.alarm_line(&name, a)).map_err(stream_error(STDERR))?;
    }
    Ok(if r.alarms.is_empty() { EXIT_OK } else { EXIT_ALARM })
}

/// The operator's switches from the options.
fn panel(args: &SimArgs) -> Panel {
    let levels = args.block_skip.iter().flatten();
    Panel {
        block_skip: levels.fold(0, |mask, &l| mask | 1 << (l - 1)),
        optional_stop: args.optional_stop,
        inputs: args.run.inputs(),
        ..Panel::default()
    }
}

/// The programmed contour and the nose-centre path of a run that used nose radius
/// compensation (the program run again with every nose radius, then every tip
/// direction, set to 0); `None` when the contour is the machine's path.
fn compensation_overlay(
    programs: &Programs,
    cfg: &MachineConfig,
    panel: &Panel,
    variables: &interp_core::lang::fanuc::macros::Variables,
    r: &Run,
) -> Option<svg::Overlay> {
    let with = |radius: bool, tip: bool| {
        let mut c = cfg.clone();
        for n in 1..=interp_core::config::MAX_OFFSETS as u16 {
            if let Some(row) = c.tools.get_mut(n) {
                if radius {
                    row.radius = 0;
                }
                if tip {
                    row.tip = 0;
                }
            }
        }
        run_programs(programs, &c, panel, OnAlarm::Stop, variables).ok().map(|run| run.actions)
    };
    let contour = with(true, true)?;
    if contour == r.actions {
        return None;
    }
    Some(svg::Overlay { contour, centre: with(false, true)? })
}

/// The output of `lathe sim` in `format`.
fn render(
    format: Format,
    name: &str,
    r: &Run,
    cfg: &MachineConfig,
    m: Option<&Motion>,
    overlay: Option<&svg::Overlay>,
) -> std::io::Result<Vec<u8>> {
    Ok(match format {
        Format::Summary => Summary::new(name, r, cfg).with_motion(m.cloned()).to_string().into_bytes(),
        // A mill: plan (X-Y) and side (X-Z) views; a lathe: the X-Z plane.
        Format::Svg if cfg.kind == interp_core::config::MachineKind::Mill => {
            crate::svg_mill::render(name, r, cfg).into_bytes()
        }
        Format::Svg => svg::render(name, r, cfg, overlay).into_bytes(),
        Format::Jsonl => {
            let mut buf = Vec::new();
            jsonl::write(r, cfg, &mut buf)?;
            buf
        }
    })
}

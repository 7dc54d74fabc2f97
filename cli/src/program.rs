//! Reading program files and running them through the interpreter, the way
//! `lathe check` (report every alarm) and `lathe sim` (stop at the first) do.
//!
//! The main program and the library (`--lib`: subprograms for M98) are read into
//! one buffer and indexed in place ([`Programs`]); an alarm or action of a
//! subprogram is reported with the file and line it comes from.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use interp_core::canon::{Canon, CanonSink, Full};
use interp_core::config::Language;
use interp_core::lang::fanuc::macros::Variables;
use interp_core::program::{Cursor, ProgramId, ProgramIndex, ProgramStore};
use interp_core::{Alarm, Interpreter, MachineConfig, Panel, Pos, Progress, SingleProgram};

use crate::error::Error;

/// Most interpreter work of one run, in blocks and macro statements: far beyond
/// any real program, it ends a program that loops forever instead of hanging the
/// command (about 10 million statements take a few seconds).
pub const MAX_STEPS: usize = 10_000_000;

/// Most programs the main file and the library may hold together.
pub const MAX_PROGRAMS: usize = 512;
/// Most sequence numbers they may hold together.
pub const MAX_SEQUENCES: usize = 16_384;

/// The programs of a run: the main program's file and the library files, read
/// into one buffer and indexed in place.
pub struct Programs {
    space: Vec<u8>,
    index: Box<ProgramIndex<MAX_PROGRAMS, MAX_SEQUENCES>>,
    /// The file each program came from, as named in messages.
    sources: BTreeMap<ProgramId, String>,
    /// The program a run starts with: the first of the main file.
    pub main: ProgramId,
}

impl Programs {
    /// The program file `path` in `language` (its first program is the main
    /// program; one without an O number or `%_N_` header is program 0) and the
    /// library: every `.nc`, `.mpf` and `.spf` file of each directory in
    /// `library`, and each file named there (`.mpf`/`.spf` files are SINUMERIK
    /// programs, `.nc` files FANUC ones, others in `language`). The main file is
    /// not read twice when it lies in a library directory.
    pub fn load(path: &Path, library: &[PathBuf], language: Language) -> Result<Programs, Error> {
        let mut p =
            Programs { space: Vec::new(), index: Box::new(ProgramIndex::new()), sources: BTreeMap::new(), main: 0 };
        p.main = p.add(path, Some(0), language)?;
        let main_file = path.canonicalize().ok();
        for lib in library {
            for file in library_files(lib)? {
                if file.canonicalize().ok() != main_file {
                    let lang = match file.extension() {
                        Some(e) if e.eq_ignore_ascii_case("nc") => Language::Fanuc,
                        _ => language_of(&file).unwrap_or(language),
                    };
                    p.add(&file, None, lang)?;
                }
            }
        }
        Ok(p)
    }

    /// Reads and indexes one file: a SINUMERIK file by its `%_N_` headers and
    /// PROC statements, a FANUC one by its O numbers.
    fn add(&mut self, path: &Path, unnamed: Option<ProgramId>, language: Language) -> Result<ProgramId, Error> {
        let bytes = read_program(path)?;
        let name = path.display().to_string();
        let start = self.space.len();
        self.space.extend_from_slice(&bytes);
        let end = self.space.len();
        let first = match language {
            Language::Fanuc => self.index.add_file(&self.space, start, end, unnamed),
            Language::Siemens => self.index.add_named_file(&self.space, start, end, unnamed),
        }
        .map_err(|e| Error::Library { path: name.clone(), message: e.to_string() })?;
        for n in self.index.numbers() {
            self.sources.entry(n).or_insert_with(|| name.clone());
        }
        Ok(first)
    }

    /// The file program `id` came from.
    pub fn source(&self, id: ProgramId) -> Option<&str> {
        self.sources.get(&id).map(String::as_str)
    }
}

impl ProgramStore for Programs {
    fn text(&self, id: ProgramId) -> Option<&[u8]> {
        self.index.text(&self.space, id)
    }

    fn start(&self, id: ProgramId) -> Option<Cursor> {
        self.index.start(id)
    }

    fn find_sequence(&self, n: u32, from: Cursor) -> Option<Cursor> {
        self.index.find_sequence(n, from)
    }

    fn find_named(&self, name: &[u8]) -> Option<Cursor> {
        let id = self.index.find_named(&self.space, name)?;
        self.index.start(id)
    }
}

/// The language a file's extension names: SINUMERIK for `.mpf` (main program)
/// and `.spf` (subprogram), none for others.
pub fn language_of(path: &Path) -> Option<Language> {
    let ext = path.extension()?;
    (ext.eq_ignore_ascii_case("mpf") || ext.eq_ignore_ascii_case("spf")).then_some(Language::Siemens)
}

/// The program files of a `--lib` argument: the `.nc`, `.mpf` and `.spf` files of a directory
/// (sorted), or the file itself.
fn library_files(lib: &Path) -> Result<Vec<PathBuf>, Error> {
    if !lib.is_dir() {
        return Ok(vec![lib.to_owned()]);
    }
    let read_error = |source| Error::Read { path: lib.to_owned(), source };
    let mut files = Vec::new();
    for entry in std::fs::read_dir(lib).map_err(read_error)? {
        let path = entry.map_err(read_error)?.path();
        let program = |e: &std::ffi::OsStr| ["nc", "mpf", "spf"].iter().any(|x| e.eq_ignore_ascii_case(x));
        if path.is_file() && path.extension().is_some_and(program) {
            files.push(path);
        }
    }
    files.sort();
    Ok(files)
}

/// Reads a program file as bytes and makes sure it is UTF-8 text.
pub fn read_program(path: &Path) -> Result<Vec<u8>, Error> {
    let bytes = std::fs::read(path).map_err(|source| Error::Read { path: path.to_owned(), source })?;
    if let Err(e) = std::str::from_utf8(&bytes) {
        let good = &bytes[..e.valid_up_to()];
        let line_start = good.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1);
        return Err(Error::NotUtf8 {
            path: path.to_owned(),
            line: 1 + good.iter().filter(|&&b| b == b'\n').count(),
            column: 1 + good.len() - line_start,
            byte: bytes[e.valid_up_to()],
        });
    }
    Ok(bytes)
}

/// What to do when a block raises an alarm.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OnAlarm {
    /// Stop there, as the control does (`lathe sim`).
    Stop,
    /// Pass over the block and go on, to find every alarm (`lathe check`).
    Continue,
}

/// The outcome of running a program.
#[derive(Debug)]
pub struct Run {
    /// Machine position of the axes before the first block: reference position 1,
    /// where a homed machine stands.
    pub start: Pos,
    /// Every canonical action, in order.
    pub actions: Vec<Canon>,
    /// The alarms, in order (at most one with [`OnAlarm::Stop`]).
    pub alarms: Vec<Alarm>,
    /// Number of blocks executed (blank, comment, skipped blocks and macro
    /// statements not counted).
    pub blocks: usize,
    /// The program each action comes from (same length as `actions`).
    pub origins: Vec<ProgramId>,
    /// The program the run started with.
    pub main: ProgramId,
    /// The file each program came from, when the run had several files.
    pub sources: BTreeMap<ProgramId, String>,
    /// The macro variables at the end.
    pub variables: Variables,
    /// The cycle messages (SINUMERIK 62xxx, shown and the program goes on): code,
    /// line and program, in order.
    pub messages: Vec<(u16, u32, ProgramId)>,
}

impl Run {
    /// A cycle message as reported: `NAME line L: message 62100: text`.
    pub fn message_line(&self, main_name: &str, (code, line, program): (u16, u32, ProgramId)) -> String {
        let name = if program == self.main { None } else { self.sources.get(&program) };
        let text = interp_core::alarm::cycle_message(code).unwrap_or("");
        format!("{} line {line}: message {code}: {text}", name.map_or(main_name, String::as_str))
    }

    /// An alarm as reported, named after the file of the program it happened in
    /// (`main_name` for the main program).
    pub fn alarm_line(&self, main_name: &str, alarm: &Alarm) -> String {
        let name = if alarm.program == self.main { None } else { self.sources.get(&alarm.program) };
        alarm_line(name.map_or(main_name, String::as_str), alarm)
    }
}

/// The program did not end within [`MAX_STEPS`] steps; what it did until then.
#[derive(Debug)]
pub struct Runaway(pub Box<Run>);

/// A sink that keeps every action.
struct Recorder(Vec<Canon>);

impl CanonSink for Recorder {
    fn push(&mut self, action: Canon) -> Result<(), Full> {
        self.0.push(action);
        Ok(())
    }
}

/// Runs `text` on machine `cfg` with the operator's switches `panel`, starting at
/// reference position 1. Every M00/M01 is answered with cycle start.
pub fn run(text: &[u8], cfg: &MachineConfig, panel: &Panel, on_alarm: OnAlarm) -> Result<Run, Runaway> {
    run_store(&SingleProgram(text), 0, cfg, panel, on_alarm, &Variables::new())
}

/// Runs the main program of `programs` as [`run`] does, with the macro variables
/// `variables` (the commons as the machine keeps them).
pub fn run_programs(
    programs: &Programs,
    cfg: &MachineConfig,
    panel: &Panel,
    on_alarm: OnAlarm,
    variables: &Variables,
) -> Result<Run, Runaway> {
    let with_sources = |mut r: Run| {
        r.sources = programs.sources.clone();
        r
    };
    run_store(programs, programs.main, cfg, panel, on_alarm, variables)
        .map(with_sources)
        .map_err(|Runaway(r)| Runaway(Box::new(with_sources(*r))))
}

/// Runs program `main` of `store`.
fn run_store<P: ProgramStore + ?Sized>(
    store: &P,
    main: ProgramId,
    cfg: &MachineConfig,
    panel: &Panel,
    on_alarm: OnAlarm,
    variables: &Variables,
) -> Result<Run, Runaway> {
    let start = cfg.reference[0];
    let mut interp = Interpreter::new(cfg.clone());
    interp.plug(&interp_siemens::SINUMERIK);
    interp.set_machine_position(start);
    interp.select_main(main);
    *interp.variables_mut() = variables.clone();
    let mut sink = Recorder(Vec::new());
    let mut run = Run {
        start,
        actions: Vec::new(),
        alarms: Vec::new(),
        blocks: 0,
        origins: Vec::new(),
        main,
        sources: BTreeMap::new(),
        variables: Variables::new(),
        messages: Vec::new(),
    };
    let mut work = 0;
    while work < MAX_STEPS {
        let program = interp.program();
        let step = interp.step(store, panel, &mut sink);
        run.origins.resize(sink.0.len(), program);
        if let Some((code, line)) = interp.take_notice() {
            run.messages.push((code, line, program));
        }
        work += 1;
        match step {
            Ok(Progress::Ended) => break,
            Ok(Progress::Paused) => interp.cycle_start(),
            Ok(Progress::Executed { .. }) => run.blocks += 1,
            Ok(Progress::Yielded { .. }) => work += usize::from(interp.step_budget()),
            Ok(Progress::Skipped { .. } | Progress::Blocked) => {}
            Err(alarm) => {
                run.alarms.push(alarm);
                if on_alarm == OnAlarm::Stop {
                    break;
                }
            }
        }
    }
    run.actions = sink.0;
    run.variables = interp.variables().clone();
    if work >= MAX_STEPS {
        return Err(Runaway(Box::new(run)));
    }
    Ok(run)
}

/// An alarm as `lathe check` and `lathe sim` report it: `PROGRAM:LINE: alarm CODE: message`.
pub fn alarm_line(program: &str, alarm: &Alarm) -> String {
    format!("{program}:{}: alarm {:04}: {}", alarm.line, alarm.code(), alarm.kind)
}

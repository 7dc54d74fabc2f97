//! Reading a program file and running it through the interpreter, the way
//! `lathe check` (report every alarm) and `lathe sim` (stop at the first) do.

use std::path::Path;

use interp_core::canon::{Canon, CanonSink, Full};
use interp_core::{Alarm, Interpreter, MachineConfig, Panel, Pos, Progress, SingleProgram};

use crate::error::Error;

/// Most interpreter steps of one run: far beyond any real program, it ends a
/// program that loops forever instead of hanging the command.
pub const MAX_STEPS: usize = 10_000_000;

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
    /// Number of blocks executed (blank, comment and skipped blocks not counted).
    pub blocks: usize,
}

/// The program did not end within [`MAX_STEPS`] steps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Runaway;

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
    let start = cfg.reference[0];
    let mut interp = Interpreter::new(cfg.clone());
    interp.set_machine_position(start);
    let store = SingleProgram(text);
    let mut sink = Recorder(Vec::new());
    let mut run = Run { start, actions: Vec::new(), alarms: Vec::new(), blocks: 0 };
    for _ in 0..MAX_STEPS {
        match interp.step(&store, panel, &mut sink) {
            Ok(Progress::Ended) => {
                run.actions = sink.0;
                return Ok(run);
            }
            Ok(Progress::Paused) => interp.cycle_start(),
            Ok(Progress::Executed { .. }) => run.blocks += 1,
            Ok(Progress::Skipped { .. } | Progress::Yielded { .. } | Progress::Blocked) => {}
            Err(alarm) => {
                run.alarms.push(alarm);
                if on_alarm == OnAlarm::Stop {
                    run.actions = sink.0;
                    return Ok(run);
                }
            }
        }
    }
    Err(Runaway)
}

/// An alarm as `lathe check` and `lathe sim` report it: `PROGRAM:LINE: alarm CODE: message`.
pub fn alarm_line(program: &str, alarm: &Alarm) -> String {
    format!("{program}:{}: alarm {:04}: {}", alarm.line, alarm.code(), alarm.kind)
}

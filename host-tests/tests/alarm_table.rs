//! Every alarm of `lathe::docs::PROOFS` (the "proven by" column of docs/ALARMS.md),
//! raised end to end: the program raises the code on the faulty line, and the
//! faulty block moved nothing: the actions emitted before the alarm are exactly
//! those the same program emits for the blocks before it when the faulty line is
//! blank.

use host_tests::{Memory, VecSink};
use interp_core::canon::Canon;
use interp_core::{Alarm, Interpreter, MachineConfig, Panel, Progress, SingleProgram};
use lathe::docs::{PROOFS, Proof, Setup};

/// What a run produced up to its first alarm, and everything it produced.
struct Outcome {
    /// The first alarm, if any.
    alarm: Option<Alarm>,
    /// Actions emitted before the first alarm.
    before: Vec<Canon>,
    /// All actions (the run goes on after alarms, like `lathe check`).
    all: Vec<Canon>,
}

/// Steps `interp` through `store` to the program end, noting the first alarm.
fn drive<P: interp_core::program::ProgramStore + ?Sized>(mut interp: Interpreter, store: &P) -> Outcome {
    let panel = Panel::default();
    let mut sink = VecSink::default();
    let mut first: Option<(Alarm, usize)> = None;
    for _ in 0..1_000_000 {
        match interp.step(store, &panel, &mut sink) {
            Ok(Progress::Ended) => break,
            Ok(Progress::Paused) => interp.cycle_start(),
            Ok(_) => {}
            Err(a) => {
                first.get_or_insert((a, sink.0.len()));
            }
        }
    }
    let n = first.map_or(sink.0.len(), |f| f.1);
    Outcome { alarm: first.map(|f| f.0), before: sink.0[..n].to_vec(), all: sink.0 }
}

/// Runs main program `text` with subprograms `library` on `cfg`.
fn run_setup(text: &str, library: &[String], cfg: MachineConfig) -> Outcome {
    if library.is_empty() {
        return drive(Interpreter::new(cfg), &SingleProgram(text.as_bytes()));
    }
    let mut m = Box::new(Memory::new());
    let id = m.load(text.as_bytes(), Some(0)).expect("main program loads");
    for t in library {
        m.load(t.as_bytes(), None).expect("library program loads");
    }
    let mut interp = Interpreter::new(cfg);
    interp.select_main(id);
    drive(interp, &*m)
}

/// `text` with line `line` (1-based) emptied, the other lines keeping their numbers.
fn blank_line(text: &str, line: u32) -> String {
    let mut out = String::new();
    for (i, l) in text.lines().enumerate() {
        if i + 1 != line as usize {
            out.push_str(l);
        }
        out.push('\n');
    }
    out
}

/// The program of `p` as run, and the same with the faulty line blank.
fn run_proof(p: &Proof) -> (Outcome, Outcome) {
    let (cfg, library): (MachineConfig, &[&str]) = match p.setup {
        Setup::Library(lib) => (MachineConfig::default(), lib),
        Setup::Machine(toml) => (lathe::machine::parse(toml).expect("machine text parses"), &[]),
        Setup::Plain | Setup::Mdi => (MachineConfig::default(), &[]),
    };
    let lib: Vec<String> = library.iter().map(|s| s.to_string()).collect();
    let faulty = run_setup(p.program, &lib, cfg.clone());
    let clean = if p.in_program == 0 {
        run_setup(&blank_line(p.program, p.line), &lib, cfg)
    } else {
        let fixed = library.iter().map(|s| fixed_library(s, p)).collect::<Vec<_>>();
        run_setup(p.program, &fixed, cfg)
    };
    (faulty, clean)
}

/// Library program `text` with the faulty line of `p` blank if it is program `p.in_program`.
fn fixed_library(text: &str, p: &Proof) -> String {
    let header = format!("O{:04}", p.in_program);
    if text.starts_with(&header) { blank_line(text, p.line) } else { text.to_string() }
}

/// The MDI proofs: the block is refused and nothing is emitted.
fn check_mdi(p: &Proof) {
    let mut interp = Interpreter::new(MachineConfig::default());
    let mut sink = VecSink::default();
    let got = interp.mdi(p.program.as_bytes(), &Panel::default(), &mut sink);
    assert_eq!(got.map_err(|a| (a.line, a.code())), Err((p.line, p.code)), "{}", p.case);
    assert!(sink.0.is_empty(), "{}: {:?}", p.case, sink.0);
}

/// One proof: code, program and line of the alarm; no action from the faulty block;
/// the actions before it exactly those of the clean program's earlier blocks.
fn check(p: &Proof) {
    if matches!(p.setup, Setup::Mdi) {
        return check_mdi(p);
    }
    let (faulty, clean) = run_proof(p);
    let a = faulty.alarm.unwrap_or_else(|| panic!("{}: no alarm", p.case));
    assert_eq!((a.code(), a.program, a.line), (p.code, p.in_program, p.line), "{}: {a}", p.case);
    if p.in_program == 0 {
        assert!(faulty.before.iter().all(|c| c.line != p.line), "{}: the faulty block moved", p.case);
        let earlier: Vec<Canon> = clean.all.iter().filter(|c| c.line < p.line).copied().collect();
        if holds_a_move(p) {
            // Compensation holds the move before the faulty block back to see its
            // corner; on the alarm it runs to its normal (or, if it is itself the
            // fault, not at all), so only its end point may differ from the clean run.
            let n = faulty.before.iter().rposition(|c| c.action.endpoint().is_some()).unwrap_or(0);
            assert_eq!(faulty.before[..n], earlier[..n.min(earlier.len())], "{}", p.case);
        } else {
            assert_eq!(faulty.before, earlier, "{}: actions before the alarm", p.case);
        }
    } else {
        assert_eq!(faulty.before, clean.all[..faulty.before.len().min(clean.all.len())], "{}", p.case);
    }
}

/// True when nose compensation is on before the faulty block, which holds the
/// last move back in its look-ahead (2.18.3).
fn holds_a_move(p: &Proof) -> bool {
    let before: Vec<&str> = p.program.lines().take(p.line as usize - 1).collect();
    before.iter().any(|l| l.contains("G41") || l.contains("G42"))
}

#[test]
fn every_proof_raises_its_alarm_on_its_line_without_motion() {
    let mut failed = Vec::new();
    for p in PROOFS {
        if std::panic::catch_unwind(|| check(p)).is_err() {
            failed.push(p.case);
        }
    }
    assert!(failed.is_empty(), "{} proofs failed: {failed:?}", failed.len());
}

#[test]
fn blank_line_keeps_numbering() {
    assert_eq!(blank_line("A\nB\nC\n", 2), "A\n\nC\n");
    assert_eq!(blank_line("A\n", 2), "A\n");
}

//! `lathe board` (the real controller on the simulated machine behind a pty)
//! driven by `lathe send`/`upload`/`run`/`status` and by raw bytes, as a
//! machinist's sender drives the board: what runs must be exactly what `lathe
//! sim` interprets for the same file.

use std::io::{BufRead, BufReader, Read, Write};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use super::{lathe, scratch, stderr, stdout};

/// A `lathe board` process and the pty link it listens on.
struct Board {
    child: Child,
    link: String,
}

impl Board {
    /// Starts `lathe board` with `extra` arguments, linked at a scratch path.
    fn start(name: &str, extra: &[&str]) -> Board {
        let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("lathe-cli-tests");
        std::fs::create_dir_all(&dir).expect("scratch directory");
        let link = dir.join(format!("{name}.pty")).display().to_string();
        let _ = std::fs::remove_file(&link);
        let mut child = Command::new(env!("CARGO_BIN_EXE_lathe"))
            .args(["board", "--pty", &link, "--exit-after", "600"])
            .args(extra)
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .expect("lathe board starts");
        let mut out = BufReader::new(child.stdout.take().expect("stdout"));
        let mut first = String::new();
        out.read_line(&mut first).expect("banner");
        if first.starts_with("lathe board: store ") {
            first.clear();
            out.read_line(&mut first).expect("banner");
        }
        assert!(first.starts_with("lathe board: listening on"), "{first}");
        Board { child, link }
    }
}

impl Drop for Board {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// `lathe sim --format jsonl` of `program`.
fn sim_jsonl(program: &str) -> String {
    let o = lathe(&["sim", program, "--format", "jsonl"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    stdout(&o)
}

/// Waits until `file` holds `lines` lines (the board writes its record as it runs).
fn wait_lines(file: &str, lines: usize) -> String {
    let end = Instant::now() + Duration::from_secs(30);
    loop {
        let text = std::fs::read_to_string(file).unwrap_or_default();
        if text.lines().count() >= lines || Instant::now() > end {
            return text;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

fn example(name: &str) -> String {
    format!("{}/../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn a_streamed_program_runs_exactly_what_lathe_sim_interprets() {
    for name in ["cycles_g71_g70.nc", "cycles_threads.nc"] {
        let record = scratch(&format!("board-{name}.jsonl"), "");
        let board = Board::start(&format!("stream-{name}"), &["--speed", "20", "--record", &record]);
        let program = example(name);
        let o = lathe(&["send", &program, "--port", &board.link, "--quiet"]);
        assert_eq!(o.status.code(), Some(0), "{name}: {}{}", stdout(&o), stderr(&o));
        assert!(stdout(&o).contains("[MSG:Pgm End]"), "{}", stdout(&o));
        let want = sim_jsonl(&program);
        assert_eq!(wait_lines(&record, want.lines().count()), want, "{name}");
    }
}

/// 10,000 short blocks.
fn ten_thousand_blocks() -> String {
    let mut p = String::from("%\nO0100 (10000 SHORT BLOCKS)\nG21 G18 G97 G99\nG00 X40 Z2\nM03 S800\nG98 G01 F3000\n");
    for i in 0..10_000 {
        let x = 40.0 - 2.0 * (f64::from(i) / 50.0).sin();
        p.push_str(&format!("N{} X{x:.3} Z{:.3}\n", i + 1, -0.05 * f64::from(i + 1)));
    }
    p.push_str("G00 X60\nZ2\nM05\nM30\n%\n");
    p
}

#[test]
fn ten_thousand_blocks_through_one_percent_line_noise_lose_nothing() {
    let program = scratch("p10k.nc", ten_thousand_blocks());
    let want = sim_jsonl(&program);
    assert_eq!(want.lines().count(), 10_006);
    for (seed, checksum) in [("3", true), ("0", false)] {
        let record = scratch(&format!("p10k-{seed}.jsonl"), "");
        let noise = if checksum { "1" } else { "0" };
        let board = Board::start(
            &format!("noise-{seed}"),
            &["--speed", "50", "--record", &record, "--corrupt", noise, "--seed", seed],
        );
        let mut args = vec!["send", &program, "--port", &board.link, "--quiet"];
        if checksum {
            args.push("--checksum");
        }
        let o = lathe(&args);
        assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
        if checksum {
            assert!(stdout(&o).contains("resending from line"), "the noise made resends");
        }
        let got = wait_lines(&record, 10_006);
        assert!(got == want, "checksum {checksum}: the executed actions differ from lathe sim's");
    }
}

/// Heavy noise on the very first lines: `lathe send --checksum` switches the board's
/// checksums on (`$LN=1`) before the program, so even a first line whose framing the
/// noise destroyed is resent, never run or refused as plain text.
#[test]
fn heavy_noise_on_the_first_line_is_resent_too() {
    let mut text = String::from("%\nO0001\nG98 G01 F3000\n");
    for i in 0..20 {
        text.push_str(&format!("X{}.5 Z-{}.25\n", 20 + i, i));
    }
    text.push_str("M30\n%\n");
    let program = scratch("first-line.nc", text);
    let want = sim_jsonl(&program);
    for seed in ["11", "12", "13", "14", "15", "16"] {
        let record = scratch(&format!("first-line-{seed}.jsonl"), "");
        let board = Board::start(
            &format!("first-{seed}"),
            &["--speed", "50", "--record", &record, "--corrupt", "6", "--seed", seed],
        );
        let o = lathe(&["send", &program, "--port", &board.link, "--quiet", "--checksum"]);
        if stderr(&o).contains("no answer from the board: waited for the welcome line") {
            // The noise ate the connection's soft reset (not checksummed): the
            // sender gives up before a single line, and nothing ran.
            assert_eq!(o.status.code(), Some(2), "seed {seed}: {}", stderr(&o));
            std::thread::sleep(Duration::from_millis(200));
            assert_eq!(std::fs::read_to_string(&record).unwrap_or_default(), "", "seed {seed}");
            continue;
        }
        assert_eq!(o.status.code(), Some(0), "seed {seed}: {}{}", stdout(&o), stderr(&o));
        let got = wait_lines(&record, want.lines().count());
        assert!(got == want, "seed {seed}: the executed actions differ from lathe sim's");
    }
}

#[test]
fn tape_upload_then_run_from_memory_and_drip_feed() {
    let record = scratch("tape.jsonl", "");
    let board = Board::start("tape", &["--speed", "20", "--record", &record]);
    let sub = example("lib/O0201.nc");
    let o = lathe(&["upload", &sub, "--port", &board.link, "--quiet"]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    let main = example("groove_series.nc");
    let o = lathe(&["upload", &main, "--port", &board.link, "--quiet"]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    let o = lathe(&["settings", "--port", &board.link, "--programs"]);
    assert!(stdout(&o).contains("O0002") && stdout(&o).contains("O0201"), "{}", stdout(&o));
    let o = lathe(&["run", "2", "--port", &board.link, "--quiet"]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    let want = lathe(&["sim", &main, "--lib", &example("lib"), "--format", "jsonl"]);
    let want = stdout(&want);
    // Run from memory, the actions are the main program's and its subprogram's.
    let got = wait_lines(&record, want.lines().count());
    assert_eq!(got.lines().count(), want.lines().count());
    drop(board);
    // Drip feed in tape mode (XON/XOFF), on a fresh board (at reference position 1,
    // where lathe sim starts).
    let record = scratch("drip.jsonl", "");
    let board = Board::start("drip", &["--speed", "20", "--record", &record]);
    let before = 0;
    let shaft = example("shaft.nc");
    let o = lathe(&["send", &shaft, "--port", &board.link, "--quiet", "--tape"]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    let want = sim_jsonl(&shaft);
    let got = wait_lines(&record, before + want.lines().count());
    let dripped: Vec<&str> = got.lines().skip(before).collect();
    assert_eq!(dripped, want.lines().collect::<Vec<_>>());
}

/// `lathe board --flash`: programs uploaded into the board's memory are still
/// there after the board is switched off and on, and run from memory.
#[test]
fn uploaded_programs_survive_a_restart_with_a_flash_file() {
    let image = scratch("board.flash", "");
    std::fs::remove_file(&image).expect("no image yet");
    let board = Board::start("flash-1", &["--speed", "20", "--flash", &image]);
    for program in [example("lib/O0201.nc"), example("groove_series.nc")] {
        let o = lathe(&["upload", &program, "--port", &board.link, "--quiet"]);
        assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    }
    // Saved at rest within 0.5 s of machine time (25 ms at --speed 20).
    std::thread::sleep(Duration::from_millis(500));
    drop(board);

    let record = scratch("flash.jsonl", "");
    let board = Board::start("flash-2", &["--speed", "20", "--flash", &image, "--record", &record]);
    let o = lathe(&["settings", "--port", &board.link, "--programs"]);
    assert!(stdout(&o).contains("O0002") && stdout(&o).contains("O0201"), "{}", stdout(&o));
    let o = lathe(&["run", "2", "--port", &board.link, "--quiet"]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    let main = example("groove_series.nc");
    let want = lathe(&["sim", &main, "--lib", &example("lib"), "--format", "jsonl"]);
    let want = stdout(&want);
    let got = wait_lines(&record, want.lines().count());
    // Run from memory, line numbers count from the stored text (without the
    // file's leading `%`) and the subprogram is not tagged: compare the rest.
    assert_eq!(without_lines(&got), without_lines(&want));
}

/// JSON lines without their `"line"` and `"program"` fields.
fn without_lines(jsonl: &str) -> Vec<String> {
    let drop_field = |l: &str, key: &str| match l.find(key) {
        Some(at) => {
            let rest = &l[at + key.len()..];
            let end = rest.find(',').map_or(rest.len(), |e| e + 1);
            format!("{}{}", &l[..at], &rest[end..])
        }
        None => l.to_string(),
    };
    jsonl.lines().map(|l| drop_field(&drop_field(l, "\"line\":"), "\"program\":")).collect()
}

/// Raw bytes on the pty: answers collected until `until` appears (or 10 s).
struct Raw {
    port: Box<dyn serialport::SerialPort>,
    seen: String,
}

impl Raw {
    fn open(link: &str) -> Raw {
        let port = serialport::new(link, 115_200).timeout(Duration::from_millis(10)).open().expect("open pty");
        Raw { port, seen: String::new() }
    }

    fn send(&mut self, bytes: &[u8]) {
        self.port.write_all(bytes).expect("write");
    }

    fn until(&mut self, what: &str) -> String {
        let end = Instant::now() + Duration::from_secs(10);
        let mut buf = [0u8; 512];
        while !self.seen.contains(what) {
            assert!(Instant::now() < end, "no {what:?} in {:?}", self.seen);
            if let Ok(n) = self.port.read(&mut buf) {
                self.seen.push_str(&String::from_utf8_lossy(&buf[..n]));
            }
        }
        let at = self.seen.find(what).unwrap_or(0) + what.len();
        let head = self.seen[..at].to_string();
        self.seen.drain(..at);
        head
    }

    /// One status report.
    fn status(&mut self) -> String {
        self.send(b"?");
        let text = self.until(">\r\n");
        text[text.rfind('<').unwrap_or(0)..].trim_end().to_string()
    }
}

#[test]
fn hold_resume_overrides_reset_and_errors_on_the_wire() {
    let board = Board::start("raw", &["--speed", "1"]);
    let mut raw = Raw::open(&board.link);
    raw.send(b"\x18");
    raw.until("Grbl 1.1h ['$' for help]\r\n");
    assert!(raw.status().starts_with("<Idle|MPos:300.000,0.000,250.000|"));
    // A slow move; feed hold mid-move, then resume.
    raw.send(b"G98 G01 U-20 F300\n");
    raw.until("ok\r\n");
    std::thread::sleep(Duration::from_millis(300));
    raw.send(b"!");
    std::thread::sleep(Duration::from_millis(400));
    let held = raw.status();
    assert!(held.starts_with("<Hold:0|"), "{held}");
    std::thread::sleep(Duration::from_millis(200));
    assert_eq!(raw.status().split('|').nth(1), held.split('|').nth(1), "no motion while held");
    raw.send(&[b'~', 0x91, 0x91]);
    std::thread::sleep(Duration::from_millis(100));
    let s = raw.status();
    assert!(s.starts_with("<Run|") && s.contains("Ov:120,100,100"), "{s}");
    // Reset mid-move: stops, welcome, Idle where it stopped (short of X280).
    raw.send(b"\x18");
    raw.until("Grbl 1.1h ['$' for help]\r\n");
    std::thread::sleep(Duration::from_millis(100));
    let s = raw.status();
    assert!(s.starts_with("<Idle|"), "{s}");
    let x: f64 = s.split("MPos:").nth(1).and_then(|p| p.split(',').next()).and_then(|v| v.parse().ok()).unwrap_or(0.0);
    assert!(x < 300.0 && x > 280.0, "{s}");
    // Errors: garbage, an overlong line, an unknown $ command; the board keeps answering.
    raw.send(b"G01 X\x01\x02\n");
    assert!(raw.until("error:1\r\n").contains("[MSG:"));
    raw.send(&[b'X'; 200]);
    raw.send(b"\n");
    raw.until("error:11\r\n");
    raw.send(b"$QQ\n");
    raw.until("error:3\r\n");
    // A program alarm: the line and no motion from that block.
    raw.send(b"G01 X10 Z10 F0.2 G07\n");
    raw.until("ok\r\n");
    let alarm = raw.until("ALARM:");
    assert!(alarm.contains("[MSG:ALARM") && alarm.contains("line"), "{alarm}");
    let s = raw.status();
    assert!(s.starts_with("<Alarm|"), "{s}");
    raw.send(b"G00 X100\n");
    raw.until("error:9\r\n");
    raw.send(b"$X\n");
    raw.until("ok\r\n");
    assert!(raw.status().starts_with("<Idle|"));
}

/// docs/MACROS.md on the board: the macros uploaded into its memory, G100 made a
/// call by `$P6050=100` over the link, the programs that call them streamed. What
/// the board runs is what `lathe sim --lib` interprets.
#[test]
fn streamed_programs_call_macros_in_the_boards_memory() {
    let lib = example("macros/lib");
    for (name, param) in [("grooves_g66.nc", None), ("g100_wide_grooves.nc", Some("$P6050=100"))] {
        let record = scratch(&format!("board-macros-{name}.jsonl"), "");
        let board = Board::start(&format!("macros-{name}"), &["--speed", "20", "--record", &record]);
        for m in ["O9110.nc", "O9010.nc"] {
            let o = lathe(&["upload", &format!("{lib}/{m}"), "--port", &board.link, "--quiet"]);
            assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
        }
        let mut want_args = vec!["sim".to_string(), example(&format!("macros/{name}")), "--lib".into(), lib.clone()];
        if let Some(p) = param {
            let o = lathe(&["settings", p, "--port", &board.link]);
            assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
            // The board's machine with 6050 = 100 (the example's also has a C axis).
            want_args.extend(["--machine".into(), scratch("g100.toml", "[parameters]\n6050 = 100\n")]);
        }
        let program = example(&format!("macros/{name}"));
        let o = lathe(&["send", &program, "--port", &board.link, "--quiet"]);
        assert_eq!(o.status.code(), Some(0), "{name}: {}{}", stdout(&o), stderr(&o));
        assert!(stdout(&o).contains("[MSG:Pgm End]"), "{}", stdout(&o));
        want_args.extend(["--format".into(), "jsonl".into()]);
        let want = lathe(&want_args.iter().map(String::as_str).collect::<Vec<_>>());
        let want = stdout(&want);
        let got = wait_lines(&record, want.lines().count());
        // The macros' lines count from their stored text (without the file's `%`).
        assert_eq!(without_lines(&got), without_lines(&want), "{name}");
        assert!(want.contains("\"program\":9110") || want.contains("\"program\":9010"), "{name} calls a macro");
    }
}

/// A mill with the automatic tool changer (machine file `tool_changer =
/// "automatic"`, `tool_change_timeout`) on `lathe board` over the link: the board
/// stops at M06 until the simulated changer reports done (`--atc-time`) and goes
/// on; a changer that never answers (`--atc-never`) ends the job in alarm 4511.
#[test]
fn automatic_tool_changer_on_the_board_done_and_timeout() {
    let machine = scratch(
        "atc-mill.toml",
        "kind = \"mill\"\ndiameter_programming = false\ntool_changer = \"automatic\"\ntool_change_timeout = 2\n",
    );
    let shown = stdout(&lathe(&["machine", "--machine", &machine]));
    assert!(shown.contains("tool_changer = \"automatic\"") && shown.contains("tool_change_timeout = 2"), "{shown}");
    let program = b"G90 G00 X-10. Y-10.\nT02 M06\nG00 X-20.\nM30\n";

    let board = Board::start("atc-done", &["--machine", &machine, "--atc-time", "0.5"]);
    let mut raw = Raw::open(&board.link);
    raw.send(b"\x18");
    raw.until("Grbl 1.1h ['$' for help]\r\n");
    raw.send(b"$$\n");
    let settings = raw.until("ok\r\n");
    assert!(settings.contains("$312=1\r\n") && settings.contains("$313=2\r\n"), "{settings}");
    raw.send(program);
    raw.until("[MSG:Tool change T02 (tool changer)]");
    let s = raw.status();
    assert!(s.starts_with("<Run|MPos:-10.000,-10.000,"), "waiting for the changer: {s}");
    let rest = raw.until("[MSG:Pgm End]");
    assert!(!rest.contains("ALARM"), "{rest}");
    std::thread::sleep(Duration::from_millis(100));
    let s = raw.status();
    assert!(s.starts_with("<Idle|MPos:-20.000,-10.000,"), "{s}");
    drop(board);

    let board = Board::start("atc-never", &["--machine", &machine, "--atc-never"]);
    let mut raw = Raw::open(&board.link);
    raw.send(b"\x18");
    raw.until("Grbl 1.1h ['$' for help]\r\n");
    raw.send(program);
    raw.until("[MSG:Tool change T02 (tool changer)]");
    let alarm = raw.until("ALARM:20\r\n");
    assert!(
        alarm.contains("[MSG:ALARM 4511 line 2: tool changer did not report done within 2 s of the request for T02"),
        "{alarm}"
    );
    let s = raw.status();
    assert!(s.starts_with("<Alarm|MPos:-10.000,-10.000,"), "no motion after the alarm: {s}");
}

//! `lathe send`, `upload`, `run`, `status`, `settings` end to end: the binary on one
//! side of a pty pair, the fake board of [`super::fake_board`] on the other.

use super::fake_board::{FakeBoard, Script};
use super::{lathe, scratch, status, stderr, stdout};

/// A program of `n` feed moves with a leading `%` and an O number, ending in M30.
fn program(n: usize) -> String {
    let mut p = String::from("%\nO0012 (SHAFT)\nG99 M03 S800\n");
    for i in 0..n {
        p.push_str(&format!("G01 X{}.5 Z-{}.25 F0.2\n", 20 + i % 30, i));
    }
    p.push_str("M30\n%\n");
    p
}

#[test]
fn send_streams_every_line_within_the_128_byte_buffer_and_exits_0() {
    let board = FakeBoard::start(Script::default());
    let p = scratch("link-send.nc", program(60));
    let o = lathe(&["send", &p, "--port", &board.path, "--quiet"]);
    let seen = board.finish();
    assert_eq!(status(&o), 0, "{}{}", stdout(&o), stderr(&o));
    // The leading % goes as an empty comment (a blank line would not start the
    // board's job), the closing one not at all.
    assert_eq!(seen.lines.len(), 64);
    assert_eq!(seen.lines[0], "()");
    assert_eq!(seen.lines[1], "O0012 (SHAFT)");
    assert_eq!(seen.lines[63], "M30");
    assert!(seen.max_buffered <= 128, "{} bytes waited in the board's buffer", seen.max_buffered);
    assert!(seen.max_buffered > 100, "the buffer was kept full: {}", seen.max_buffered);
    assert_eq!(seen.resets, 1);
    let out = stdout(&o);
    assert!(out.starts_with(&format!("connected to {}: Grbl 1.1h ['$' for help]\n", board_path(&out))), "{out}");
    assert!(out.contains("[MSG:Pgm End]\n"), "{out}");
    assert!(out.contains(&format!("{p}: done in ")), "{out}");
    assert_eq!(stderr(&o), "");
}

/// The port named in the `connected to` line.
fn board_path(out: &str) -> &str {
    out.strip_prefix("connected to ").and_then(|r| r.split_once(':')).map_or("", |(p, _)| p)
}

#[test]
fn send_with_checksums_resends_a_damaged_line_and_still_exits_0() {
    let board = FakeBoard::start(Script { damage: Some(7), ..Script::default() });
    let p = scratch("link-send-crc.nc", program(30));
    let o = lathe(&["send", &p, "--port", &board.path, "--quiet", "--checksum"]);
    let seen = board.finish();
    assert_eq!(status(&o), 0, "{}{}", stdout(&o), stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("board asks to resend from line 7\n"), "{out}");
    assert!(out.contains("resending from line 7\n"), "{out}");
    // `$LN=1` first switches the board's checksums on, then every line is framed.
    assert_eq!(seen.lines.first().map(String::as_str), Some("$LN=1"));
    assert!(seen.lines.iter().skip(1).all(|l| l.starts_with('N') && l.contains('*')));
    // Line 7 arrived twice (damaged, then resent), everything after it at least twice
    // up to what was in flight; the last line arrived once the sequence was whole.
    let sevens = seen.lines.iter().filter(|l| l.starts_with("N7 ")).count();
    assert_eq!(sevens, 2);
    assert!(seen.lines.last().is_some_and(|l| l.starts_with("N34 M30*")), "{:?}", seen.lines.last());
    assert!(seen.max_buffered <= 128);
}

/// Issue 23 at 3 % line noise: nearly every status report arrives damaged, and the
/// job's last line is lost on the way. The sender finds it from the board's short
/// `[LK:…]` answer to ENQ (the reports never get through) and finishes.
#[test]
fn send_with_checksums_finds_a_lost_last_line_from_the_enq_answer_alone() {
    let board = FakeBoard::start(Script { lose: Some(34), garble_reports: true, ..Script::default() });
    let p = scratch("link-send-lost.nc", program(30));
    let o = lathe(&["send", &p, "--port", &board.path, "--quiet", "--checksum"]);
    let seen = board.finish();
    let out = stdout(&o);
    assert_eq!(status(&o), 0, "{out}{}", stderr(&o));
    assert!(out.contains("lines lost on the way: resending from line 34\n"), "{out}");
    assert!(out.contains("streamed 34 lines") && out.contains(", 1 resyncs,"), "{out}");
    let last: Vec<_> = seen.lines.iter().filter(|l| l.starts_with("N34 ")).collect();
    assert_eq!(last.len(), 2, "lost once, sent again: {last:?}");
}

/// A board that falls silent mid-job (a dead link) still ends the job with a clear
/// error: after 5 s without a byte and at least 20 queries (`?`, ENQ) unanswered.
#[test]
fn send_gives_up_on_a_board_that_stopped_talking_after_5_s_and_20_queries() {
    let board = FakeBoard::start(Script { dies_after: Some(10), ..Script::default() });
    let p = scratch("link-send-dies.nc", program(30));
    let t = std::time::Instant::now();
    let o = lathe(&["send", &p, "--port", &board.path, "--quiet", "--checksum"]);
    let waited = t.elapsed();
    board.finish();
    let err = stderr(&o);
    assert_eq!(status(&o), 2, "{}{err}", stdout(&o));
    assert!(err.contains("the board stopped talking: nothing for 5."), "{err}");
    let queries: u32 =
        err.split(" s, ").nth(1).and_then(|r| r.split(' ').next()).and_then(|n| n.parse().ok()).unwrap_or(0);
    assert!(queries >= 20, "{err}");
    assert!(waited >= std::time::Duration::from_secs(5) && waited < std::time::Duration::from_secs(15), "{waited:?}");
}

#[test]
fn a_refused_line_is_named_by_file_and_line_the_job_stops_and_exits_1() {
    let board = FakeBoard::start(Script { refuse: Some("G12.1"), ..Script::default() });
    let mut text = program(40);
    text = text.replacen("G01 X25.5 Z-5.25 F0.2", "G12.1", 1);
    let p = scratch("link-refuse.nc", &text);
    let o = lathe(&["send", &p, "--port", &board.path, "--quiet"]);
    let seen = board.finish();
    assert_eq!(status(&o), 1);
    // Line 9 of the file: %, O, G99, then moves 0..4 on lines 4-8.
    let msg = format!("{p}:9: error:20: G12.1 is not supported");
    assert!(stdout(&o).contains(&format!("{msg}\n")), "{}", stdout(&o));
    assert_eq!(stderr(&o), format!("lathe: {p}: stopped: the board refused a line ({msg})\n"));
    assert_eq!(seen.holds, 1, "feed hold first");
    assert_eq!(seen.resets, 2, "then a soft reset");
    assert!(seen.lines.len() < 44, "streaming stopped: {} lines", seen.lines.len());
}

#[test]
fn an_alarm_is_reported_with_its_message_and_stops_the_stream() {
    let board = FakeBoard::start(Script { alarm: Some("G07"), ..Script::default() });
    let text = program(40).replacen("G01 X30.5 Z-10.25 F0.2", "G07 X10", 1);
    let p = scratch("link-alarm.nc", &text);
    let o = lathe(&["send", &p, "--port", &board.path, "--quiet"]);
    let seen = board.finish();
    assert_eq!(status(&o), 1);
    let msg = format!("{p}:14: alarm 0010: G07 is not a G code of the selected G-code system (ALARM:20 program alarm)");
    assert!(stdout(&o).contains(&format!("{msg}\n")), "{}", stdout(&o));
    assert_eq!(stderr(&o), format!("lathe: {p}: stopped by an alarm ({msg})\n"));
    assert_eq!(seen.resets, 1, "the board is left in its alarm");
}

/// `lathe send --tape` end to end over a pty: the tape goes out whole and is
/// drip-fed. How the sender honours XOFF is checked in
/// `tape_flow::tape_mode_honours_xoff_within_one_chunk_of_reading_it`, where the
/// board answers in the order of reads and writes: here two processes share the
/// machine's cores, so how many bytes cross a DC3 on the way, or wait in the fake's
/// buffer, depends on how they were scheduled (this test failed on that with 6 busy
/// processes on 2 cores: more than 512 bytes buffered).
#[test]
fn tape_mode_drip_feeds_without_the_o_number() {
    let board = FakeBoard::start(Script { line_period: std::time::Duration::from_millis(3), ..Script::default() });
    let p = scratch("link-tape.nc", program(80));
    let o = lathe(&["send", &p, "--port", &board.path, "--quiet", "--tape"]);
    let seen = board.finish();
    assert_eq!(status(&o), 0, "{}{}", stdout(&o), stderr(&o));
    assert_eq!(seen.lines, vec!["%"], "only the opening % is a grbl-mode line");
    assert_eq!(seen.drip.len(), 83, "the blocks between the marks");
    assert_eq!(seen.drip[0], " (SHAFT)");
    assert_eq!(seen.drip[82], "M30");
    assert!(seen.programs.is_empty());
    assert_eq!(seen.resets, 2, "a second reset after the status check, so that % starts tape mode");
}

#[test]
fn upload_stores_the_program_and_run_follows_it_to_its_end() {
    let board = FakeBoard::start(Script::default());
    let p = scratch("link-upload.nc", "G00 X20 Z2\nG01 Z-10 F0.2\nM30\n");
    let o = lathe(&["upload", &p, "--port", &board.path, "--quiet", "--as", "42"]);
    assert_eq!(status(&o), 0, "{}{}", stdout(&o), stderr(&o));
    assert!(stdout(&o).ends_with("stored O0042 (35 bytes)\n"), "{}", stdout(&o));
    let o = lathe(&["run", "42", "--port", &board.path, "--quiet"]);
    assert_eq!(status(&o), 0, "{}{}", stdout(&o), stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("state Run\n") && out.contains("[MSG:Pgm End]\n"), "{out}");
    let o = lathe(&["run", "43", "--port", &board.path, "--quiet"]);
    assert_eq!(status(&o), 1);
    assert_eq!(
        stderr(&o),
        "lathe: O0043: stopped: the board refused a line ($PR=43: error:3: O0043 is not in memory)\n"
    );
    let seen = board.finish();
    assert_eq!(seen.programs[&42], "O0042\nG00 X20 Z2\nG01 Z-10 F0.2\nM30\n");
}

#[test]
fn upload_without_an_o_number_needs_as() {
    let p = scratch("link-upload-no-o.nc", "G00 X20\nM30\n");
    let o = lathe(&["upload", &p, "--port", "/nonexistent"]);
    assert_eq!(status(&o), 2);
    assert_eq!(stderr(&o), format!("lathe: {p}:1: the program has no O number; give one with --as N\n"));
}

#[test]
fn status_and_settings() {
    let board = FakeBoard::start(Script::default());
    let o = lathe(&["status", "--port", &board.path]);
    assert_eq!(status(&o), 0, "{}", stderr(&o));
    assert!(stdout(&o).starts_with("state      Idle\nwork       X 50.000 (diameter)  Z -2.000\n"), "{}", stdout(&o));
    let o = lathe(&["settings", "--port", &board.path, "$110=500", "300=1"]);
    assert_eq!(status(&o), 0, "{}", stderr(&o));
    assert_eq!(stdout(&o), "$110=500 ok\n$300=1 ok\n");
    let o = lathe(&["settings", "--port", &board.path]);
    assert_eq!(stdout(&o), "$110=500\n$300=1\n");
    let o = lathe(&["settings", "--port", &board.path, "$999=1"]);
    assert_eq!(status(&o), 1);
    assert_eq!(stderr(&o), "lathe: board refused $999=1: error:3: Unknown setting\n");
    let seen = board.finish();
    assert_eq!(seen.settings, vec!["$110=500", "$300=1"]);
    assert_eq!(seen.resets, 0, "status and settings leave the board as it is");
}

#[test]
fn a_board_in_alarm_is_not_streamed_to_and_unlock_clears_it() {
    let board = FakeBoard::start(Script { locked: true, ..Script::default() });
    let p = scratch("link-locked.nc", program(3));
    let o = lathe(&["send", &p, "--port", &board.path, "--quiet"]);
    assert_eq!(status(&o), 2);
    assert!(
        stderr(&o)
            .ends_with("the board is in state Alarm; clear the cause, then unlock it (lathe settings --unlock)\n"),
        "{}",
        stderr(&o)
    );
    let o = lathe(&["settings", "--port", &board.path, "--unlock", "--programs"]);
    assert_eq!(status(&o), 0);
    assert_eq!(stdout(&o), "[MSG:Caution: Unlocked]\n");
    let seen = board.finish();
    assert!(seen.lines.iter().all(|l| l.starts_with('$')), "{:?}", seen.lines);
}

#[test]
fn no_welcome_no_port_and_unsendable_lines_exit_2() {
    let board = FakeBoard::start(Script { mute: true, ..Script::default() });
    let p = scratch("link-mute.nc", program(3));
    let o = lathe(&["send", &p, "--port", &board.path, "--quiet"]);
    assert_eq!(status(&o), 2);
    assert!(
        stderr(&o).ends_with("no answer from the board: waited for the welcome line `Grbl 1.1h`\n"),
        "{}",
        stderr(&o)
    );
    board.finish();
    let o = lathe(&["send", &p, "--port", "/nonexistent/tty", "--quiet"]);
    assert_eq!(status(&o), 2);
    assert!(stderr(&o).starts_with("lathe: cannot open /nonexistent/tty: "), "{}", stderr(&o));
    let bad = scratch("link-bad.nc", "G00 X20\nM00 (STOP!)\nM30\n");
    let o = lathe(&["send", &bad, "--port", "/nonexistent/tty"]);
    assert_eq!(status(&o), 2);
    assert_eq!(
        stderr(&o),
        format!("lathe: {bad}:2: column 10: `!` acts as a real-time command on the link; remove it before sending\n")
    );
}

/// `lathe send` on a terminal (a pty as its standard input and error): the progress
/// bar draws, and `q` aborts gently — feed hold, then soft reset — with exit status 1.
#[test]
fn on_a_terminal_q_aborts_with_a_feed_hold_and_a_reset() {
    use std::io::{Read, Write};
    use std::process::{Command, Stdio};

    use serialport::SerialPort;

    let board = FakeBoard::start(Script { line_period: std::time::Duration::from_millis(20), ..Script::default() });
    let p = scratch("link-keys.nc", program(100));
    let (mut term, user) = serialport::TTYPort::pair().expect("a terminal pty");
    let user_path = user.name().expect("terminal name");
    let open = || std::fs::OpenOptions::new().read(true).write(true).open(&user_path).expect("terminal");
    let mut child = Command::new(env!("CARGO_BIN_EXE_lathe"))
        .args(["send", &p, "--port", &board.path])
        .stdin(Stdio::from(open()))
        .stderr(Stdio::from(open()))
        .stdout(Stdio::piped())
        .spawn()
        .expect("lathe runs");
    let mut shown = Vec::new();
    let mut buf = [0u8; 4096];
    let started = std::time::Instant::now();
    let mut pressed = false;
    term.set_timeout(std::time::Duration::from_millis(20)).expect("timeout");
    while child.try_wait().expect("wait").is_none() {
        if let Ok(n) = term.read(&mut buf) {
            shown.extend_from_slice(&buf[..n]);
        }
        if !pressed && String::from_utf8_lossy(&shown).contains("acknowledged") {
            term.write_all(b"q").expect("key");
            pressed = true;
        }
        assert!(started.elapsed().as_secs() < 20, "lathe send ends");
    }
    while let Ok(n) = term.read(&mut buf) {
        if n == 0 {
            break;
        }
        shown.extend_from_slice(&buf[..n]);
    }
    let status = child.wait().expect("exit").code();
    let seen = board.finish();
    let shown = String::from_utf8_lossy(&shown);
    assert_eq!(status, Some(1), "{shown}");
    assert!(shown.contains(&format!("lathe: {p}: stopped: aborted by the user")), "{shown}");
    assert_eq!((seen.holds, seen.resets), (1, 2));
    assert!(seen.lines.len() < 104, "streaming stopped: {} lines", seen.lines.len());
    drop(user);
}

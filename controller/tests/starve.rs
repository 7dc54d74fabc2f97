//! The stream starvation watch (`$304`, alarm 4601): a streamed job whose link
//! goes quiet mid-run ends in an alarm; a sender that finished, one that polls, a
//! program stop and a tape that closed its record never do. Times are the ones the
//! controller is given (the rig's 1 ms polls).

mod common;

use common::{Counting, Rig, TICK};
use controller::crc::crc16;

/// A rig past its welcome line, with `$304=seconds` unless `None`.
fn rig(seconds: Option<u32>) -> Rig {
    let mut r = Rig::new();
    r.run_ms(2);
    r.take_lines();
    if let Some(s) = seconds {
        assert_eq!(r.command(&format!("$304={s}")), vec!["ok"]);
    }
    r
}

/// A job of `n` short cuts with the spindle on, without its end.
fn job(n: usize) -> Vec<String> {
    let mut lines = vec!["G98 G00 X20 Z0".to_string(), "M03 S500".to_string()];
    lines.extend((0..n).map(|_| "G01 W-0.5 F600".to_string()));
    lines
}

/// Streams `lines` with character counting; `poll_ms`: a `?` every so many ms
/// (0 = never). Runs `ms` ms; returns the time of the last byte sent (ns).
fn stream_for(r: &mut Rig, lines: Vec<String>, poll_ms: u64, ms: u64) -> u64 {
    let mut sender = Counting::new(lines);
    let mut last = 0;
    for i in 0..ms {
        let before = r.pending.len();
        sender.pump(r);
        if poll_ms > 0 && i % poll_ms == 0 {
            r.send(b"?");
        }
        if r.pending.len() > before {
            last = r.now;
        }
        r.step();
        for l in r.take_lines() {
            sender.answer(&l);
        }
    }
    last
}

/// When the `ALARM:` line appeared (ns), running at most `ms`.
fn alarm_time(r: &mut Rig, ms: u64) -> Option<u64> {
    r.run_until(ms, |r| r.lines().iter().any(|l| l.starts_with("ALARM:"))).then_some(r.now)
}

#[test]
fn a_stream_cut_mid_job_alarms_4601_when_the_link_was_quiet_for_304_seconds() {
    let mut r = rig(Some(2));
    // 40 cuts of 0.5 mm at 600 mm/min: 2 s of work; the sender's bytes stop
    // after the 30th line reached the board.
    let mut lines = job(40);
    lines.truncate(32);
    let last = stream_for(&mut r, lines, 0, 200);
    assert!(!r.lines().iter().any(|l| l.starts_with("ALARM")), "{:?}", r.lines());
    assert!(r.run_until(10_000, |r| r.port.core.is_idle()), "the machine stops where the text ends");
    let stopped_at = r.now;
    let z_mm = r.port.core.position()[interp_core::Axis::Z] as f64 / 1e6;
    assert!((z_mm + 15.0).abs() < 1e-3, "stopped at the end of the last block received: {z_mm}");
    assert!(stopped_at < last + 2_000_000_000, "the last cut ends before the 2 s run out");
    let at = alarm_time(&mut r, 5_000).expect("alarm 4601");
    // Alarmed at the first poll 2 s after the last byte.
    assert!(at >= last + 2_000_000_000 && at <= last + 2_000_000_000 + 2 * TICK, "{at} vs {last}");
    let out = r.lines();
    let msg = out.iter().find(|l| l.contains("ALARM 4601")).expect("message");
    assert_eq!(
        msg,
        "[MSG:ALARM 4601 line 33: stream starved: the job is open and nothing came over the link for 2 s (link lost?)]"
    );
    assert!(out.contains(&"ALARM:20".to_string()), "{out:?}");
    assert_eq!(r.port.core.spindle_output().1, 0, "spindle stopped");
    assert!(r.status().starts_with("<Alarm"));
    // Reset, then a new job runs.
    r.send(&[0x18]);
    r.run_ms(5);
    let answers = r.stream("G98 G00 X30\nG01 Z-20 F600\nM30\n", 10_000);
    assert!(answers.iter().any(|l| l == "[MSG:Pgm End]"), "{answers:?}");
    let z_mm = r.port.core.position()[interp_core::Axis::Z] as f64 / 1e6;
    assert!((z_mm + 20.0).abs() < 1e-3, "{z_mm}");
}

#[test]
fn the_default_is_10_s_and_0_switches_the_watch_off() {
    let mut r = rig(None);
    assert!(r.command("$$").contains(&"$304=10".to_string()));
    let last = stream_for(&mut r, job(4), 0, 100);
    let at = alarm_time(&mut r, 12_000).expect("alarm 4601");
    assert!(at >= last + 10_000_000_000 && at <= last + 10_000_000_000 + 2 * TICK, "{at} vs {last}");

    let mut r = rig(Some(0));
    assert_eq!(r.command("$306=0"), vec!["ok"]);
    stream_for(&mut r, job(4), 0, 100);
    assert_eq!(alarm_time(&mut r, 40_000), None, "{:?}", r.lines());
}

#[test]
fn a_polling_sender_never_starves_and_one_that_finished_polling_neither() {
    // lathe send, CNCjs: `?` every 200 ms while connected. An interactive line
    // without M30 (an MDI move typed into the sender) with the spindle stopped
    // stays open for 30 s.
    let mut r = rig(Some(1));
    let mut lines = job(2);
    lines.push("M05".to_string());
    stream_for(&mut r, lines, 200, 30_000);
    assert!(!r.lines().iter().any(|l| l.starts_with("ALARM")), "{:?}", r.lines());
    // The sender then goes (its last `?` saw Idle): the job stays open, no alarm.
    assert_eq!(alarm_time(&mut r, 10_000), None);
    assert!(r.status().starts_with("<Idle"));
}

/// Issue 23: a sender whose count is stuck (an `ok` lost to line noise) stops
/// sending lines but goes on polling `?`; with the spindle turning the job must
/// not stay open: `$306` s (default 30) after the last program line, alarm 4601.
#[test]
fn with_the_spindle_turning_polls_alone_do_not_keep_a_stream_open() {
    let mut r = rig(Some(1));
    assert!(r.command("$$").contains(&"$306=30".to_string()));
    let mut sender = Counting::new(job(2));
    let mut last_line = 0;
    for i in 0..40_000u64 {
        let before = r.pending.len();
        sender.pump(&mut r);
        if r.pending.len() > before {
            last_line = r.now;
        }
        if i % 200 == 0 {
            r.send(b"?");
        }
        r.step();
        for l in r.take_lines() {
            sender.answer(&l);
        }
        if r.lines().iter().any(|l| l.starts_with("ALARM:")) {
            break;
        }
    }
    let at = r.now;
    assert!(at >= last_line + 30_000_000_000 && at <= last_line + 30_000_000_000 + 2 * TICK, "{at} vs {last_line}");
    let out = r.lines();
    assert!(
        out.iter().any(|l| l == "[MSG:No program line nor operator action for 30 s with the spindle turning ($306)]"),
        "{out:?}"
    );
    assert!(out.iter().any(|l| l.contains("ALARM 4601")), "{out:?}");
    assert_eq!(r.port.core.spindle_output().1, 0, "spindle stopped");
}

/// Runs `ms` ms polling `?` every 200 ms (a connected sender), calling `at(rig, i)`
/// each ms; stops at an `ALARM:` line: its time.
fn polled(r: &mut Rig, ms: u64, mut at: impl FnMut(&mut Rig, u64)) -> Option<u64> {
    for i in 0..ms {
        if i % 200 == 0 {
            r.send(b"?");
        }
        at(r, i);
        r.step();
        if r.lines().iter().any(|l| l.starts_with("ALARM:")) {
            return Some(r.now);
        }
    }
    None
}

/// A rig with `$306=5` (the rule, not the default, is tested here).
fn rig306() -> Rig {
    let mut r = rig(None);
    assert_eq!(r.command("$306=5"), vec!["ok"]);
    r
}

/// Manual work: a machinist types `M03 S500` and a few positioning moves into a
/// sender's console (lines seconds apart), jogs now and then, and stands with the
/// spindle on while the sender polls — far longer than `$306`. That is not a
/// stalled program stream: `$306` never ends it (nor does `$304`: the sender polls).
#[test]
fn manual_work_with_the_spindle_turning_is_never_ended_by_306() {
    let mut r = rig306();
    let typed = [(0, "M03 S500"), (2_000, "G98 G00 X40 Z5"), (3_500, "G01 Z-2 F100"), (5_000, "G00 Z5")];
    let jogs = [8_000, 9_000, 9_500];
    let alarm = polled(&mut r, 25_000, |r, i| {
        if let Some((_, l)) = typed.iter().find(|(t, _)| *t == i) {
            r.send(format!("{l}\n").as_bytes());
        }
        if jogs.contains(&i) {
            r.send(b"$J=G91 X-0.5 F200\n");
        }
    });
    assert_eq!(alarm, None, "{:?}", r.lines());
    assert!(r.port.core.spindle_output().1 > 0, "the spindle still turns");
    assert!(r.status().starts_with("<Idle"));
    // The same lines sent at once by a sender (a macro, a file): a streamed program.
    let mut r = rig306();
    let t0 = r.now;
    let at = polled(&mut r, 10_000, |r, i| {
        if i == 0 {
            for (_, l) in typed {
                r.send(format!("{l}\n").as_bytes());
            }
        }
    })
    .expect("alarm 4601");
    assert!(at_or_just_after(at, t0 + 5_000_000_000), "{at}");
}

/// The same manual work from a terminal that never polls (`screen`, a console
/// without status display): the link is silent for far longer than `$304`, and
/// still nothing ends it — the lines were typed, not streamed.
#[test]
fn manual_work_from_a_terminal_that_does_not_poll_is_never_ended_by_304() {
    let mut r = rig(Some(2));
    assert_eq!(r.command("$306=5"), vec!["ok"]);
    for (i, l) in ["M03 S500", "G98 G00 X40 Z5", "G01 Z-2 F100", "G00 Z5"].iter().enumerate() {
        r.send(format!("{l}\n").as_bytes());
        r.run_ms(if i == 3 { 1 } else { 1_500 });
    }
    assert_eq!(alarm_time(&mut r, 30_000), None, "{:?}", r.lines());
    assert!(r.port.core.spindle_output().1 > 0, "the spindle still turns");
    assert!(r.status().starts_with("<Idle"));
}

/// A drip-fed tape is a streamed program however slowly its reader sends (a
/// 110-baud teletype: a line every two seconds), and a framed line (`lathe send
/// --checksum`) is one from its first line: both are watched.
#[test]
fn a_slow_tape_and_framed_lines_are_streamed_programs() {
    let mut r = Rig::new();
    r.ctl.settings_mut().starve_timeout_s = 1;
    r.send(b"%\n");
    for l in job(2) {
        r.send(format!("{l}\n").as_bytes());
        r.run_ms(2_000);
    }
    assert!(alarm_time(&mut r, 5_000).is_some(), "slow tape cut mid-job: {:?}", r.lines());

    let mut r = rig(Some(2));
    assert_eq!(r.command("$LN=1"), vec!["[LN:1]", "ok"]);
    for (k, l) in ["G98 G00 X20 Z0", "M03 S500"].iter().enumerate() {
        let body = format!("N{} {l}", k + 1);
        let crc = crc16(body.as_bytes());
        r.send(format!("{body}*{crc:04X}\n").as_bytes());
        r.run_ms(1_500);
    }
    let at = alarm_time(&mut r, 5_000).expect("two framed lines seconds apart: alarm 4601");
    assert!(at > 3_000 * TICK, "{at}");
}

/// `$306` counts from the last program line or operator action: an override or a
/// jog while a stalled program stands shows that someone is at the machine.
#[test]
fn an_operator_action_restarts_the_306_time() {
    for action in [&b"\x91"[..], b"$J=G91 Z1 F300\n"] {
        let mut r = rig306();
        let mut sender = Counting::new(job(3));
        let (mut last_line, mut acted) = (0, 0);
        let alarm = polled(&mut r, 15_000, |r, i| {
            let before = r.pending.len();
            sender.pump(r);
            if r.pending.len() > before {
                last_line = r.now;
            }
            for l in r.take_lines() {
                sender.answer(&l);
            }
            if i == 3_000 {
                r.send(action);
                acted = r.now;
            }
        })
        .expect("alarm 4601");
        assert!(last_line < 1_000 * TICK && acted > last_line);
        assert!(at_or_just_after(alarm, acted + 5_000_000_000), "{alarm} vs {acted} ({action:?})");
    }
}

fn at_or_just_after(t: u64, due: u64) -> bool {
    t >= due && t <= due + 3 * TICK
}

#[test]
fn a_job_that_ended_with_m30_and_trailing_lines_is_not_open() {
    // A sender that stops after its file's last line: M30, then a record mark and
    // a comment (they start the next job, which runs nothing).
    let mut r = rig(Some(1));
    let mut lines = job(4);
    lines.extend(["M30".to_string(), "%".to_string(), "(end)".to_string()]);
    stream_for(&mut r, lines, 0, 100);
    assert_eq!(alarm_time(&mut r, 10_000), None, "{:?}", r.lines());
    assert!(r.lines().contains(&"[MSG:Pgm End]".to_string()));
}

#[test]
fn a_program_stop_or_a_feed_hold_waits_for_the_operator() {
    let mut r = rig(Some(1));
    let mut lines = job(2);
    lines.push("M00".to_string());
    stream_for(&mut r, lines, 0, 100);
    assert_eq!(alarm_time(&mut r, 5_000), None, "M00: {:?}", r.lines());
    assert!(r.status().starts_with("<Hold"));

    let mut r = rig(Some(1));
    stream_for(&mut r, job(20), 0, 300);
    r.send(b"!");
    assert_eq!(alarm_time(&mut r, 5_000), None, "feed hold: {:?}", r.lines());
}

#[test]
fn a_drip_fed_tape_alarms_when_cut_but_not_after_its_closing_percent() {
    // No grbl traffic before `%`: tape mode, no `ok`s, no polls.
    let body: String = job(4).iter().map(|l| format!("{l}\n")).collect();
    let mut r = Rig::new();
    r.ctl.settings_mut().starve_timeout_s = 1;
    r.send(format!("%\n{body}").as_bytes());
    let at = alarm_time(&mut r, 5_000).expect("cut tape: alarm 4601");
    assert!(at > TICK * 1_000, "{at}");

    let mut r = Rig::new();
    r.ctl.settings_mut().starve_timeout_s = 1;
    r.send(format!("%\n{body}%\n").as_bytes());
    assert_eq!(alarm_time(&mut r, 5_000), None, "closed tape: {:?}", r.lines());
    assert!(r.port.core.is_idle());
}

//! Real-time bytes behind a full receive buffer (fuzz finding, board target): a
//! sender that ignores character counting overfills the buffer with slow jogs;
//! a `?`, `!`, `~` or 0x18 behind the bytes the buffer cannot take yet must act at
//! once — grbl picks them out of the stream in its receive interrupt — and must
//! not act again when the shell offers the rest once more.

mod common;

use common::Rig;
use controller::{Inputs, frame_line};

/// A jog of 12 s (1 mm at F5): it holds its line in the buffer.
const SLOW_JOG: &[u8] = b"$J=G91 X1 F5\n";

/// A rig whose receive buffer is full of slow jogs, with more jog lines waiting
/// behind it (the planner holds 64 jogs, the buffer 9 lines of 13 bytes).
fn overfilled() -> Rig {
    let mut r = Rig::new();
    r.run_ms(5);
    for _ in 0..100 {
        r.send(SLOW_JOG);
    }
    r.run_ms(30);
    assert!(r.ctl.rx_free() < SLOW_JOG.len(), "the buffer is full: {} free", r.ctl.rx_free());
    assert!(r.pending.len() > 10 * SLOW_JOG.len(), "jogs wait behind it: {}", r.pending.len());
    assert!(r.status().starts_with("<Jog|"));
    r
}

/// Status reports in `lines`.
fn reports(lines: &[String]) -> usize {
    lines.iter().filter(|l| l.starts_with('<')).count()
}

#[test]
fn a_status_poll_behind_a_full_buffer_is_answered_in_the_same_poll_and_once() {
    let mut r = overfilled();
    let waiting = r.pending.len();
    r.take_lines();
    r.send(b"?");
    r.step();
    let got = r.take_lines();
    assert_eq!(reports(&got), 1, "{got:?}");
    assert!(got[0].starts_with("<Jog|"), "{got:?}");
    // The `?` left the shell's bytes; the jogs behind the buffer stayed.
    assert_eq!(r.pending.len(), waiting);
    assert!(!r.pending.contains(&b'?'));
    r.run_ms(50);
    assert_eq!(reports(&r.take_lines()), 0, "answered twice");
}

#[test]
fn a_feed_hold_behind_a_full_buffer_cancels_the_jog_in_the_same_poll() {
    let mut r = overfilled();
    assert_eq!(r.port.core.queued(), 64, "the planner is full of jogs");
    r.send(b"!");
    r.step();
    // grbl: `!` while jogging cancels the jog (planner flushed); only the jog lines
    // this poll took from the buffer are queued again.
    assert!(r.port.core.queued() <= 4, "{} jogs still queued", r.port.core.queued());
    assert!(!r.pending.contains(&b'!'));
}

#[test]
fn a_soft_reset_behind_a_full_buffer_drops_what_came_before_it_at_once() {
    let mut r = overfilled();
    r.take_lines();
    r.send(&[0x18]);
    r.send(b"?");
    r.step();
    let got = r.take_lines();
    // The reset came first (welcome), then the `?` behind it.
    let welcome = got.iter().position(|l| l.starts_with("Grbl 1.1h")).expect("welcome");
    let report = got.iter().position(|l| l.starts_with('<')).expect("report");
    assert!(welcome < report, "{got:?}");
    // Everything received before the reset is dropped: the buffer, the waiting jogs.
    assert!(r.pending.is_empty(), "{} bytes still waiting", r.pending.len());
    assert_eq!(r.ctl.rx_free(), controller::RX);
    r.run_ms(50);
    let later = r.take_lines();
    assert!(!later.iter().any(|l| l.starts_with("Grbl") || l.starts_with('<')), "acted twice: {later:?}");
}

#[test]
fn a_feed_hold_behind_a_stream_that_overfills_the_buffer_holds_at_once() {
    let mut r = Rig::new();
    r.run_ms(5);
    // A program of slow feeds sent without character counting: the stream window
    // takes what the interpreter gets to; the rest waits behind the full buffer.
    let mut text = String::from("G98 G01 F5\n");
    for i in 1..400 {
        text.push_str(&format!("X{}.{:03}\n", i / 1000, i % 1000));
    }
    r.send(text.as_bytes());
    r.run_ms(40);
    assert!(!r.pending.is_empty(), "the stream waits behind the buffer");
    assert!(r.status().starts_with("<Run|"));
    r.send(b"!?");
    r.step();
    let got = r.take_lines();
    let report = got.iter().find(|l| l.starts_with('<')).expect("report in the same poll");
    assert!(report.starts_with("<Hold:"), "{got:?}");
    r.run_ms(200);
    assert!(r.status().starts_with("<Hold:0"), "held");
    r.send(b"~");
    r.step();
    assert!(r.status().starts_with("<Run|"), "resumed");
}

/// Drives the controller directly: how `receive` rewrites the tail it keeps.
mod tail {
    use super::*;

    type Ctl = common::Ctl;

    fn ctl() -> Box<Ctl> {
        Box::new(Ctl::new(Default::default(), Default::default()))
    }

    /// `ctl` with its buffer full of complete lines (nothing polled).
    fn full(ctl: &mut Ctl) {
        let mut fill = Vec::new();
        while fill.len() + SLOW_JOG.len() <= controller::RX {
            fill.extend_from_slice(SLOW_JOG);
        }
        fill.extend_from_slice(&SLOW_JOG[..controller::RX - fill.len()]);
        let n = ctl.receive(&mut fill.clone(), 0);
        assert_eq!(n, fill.len());
        assert_eq!(ctl.rx_free(), 0);
    }

    #[test]
    fn real_time_bytes_leave_the_tail_and_the_rest_moves_to_its_end() {
        let mut c = ctl();
        full(&mut c);
        let mut bytes = b"5\n?$J=G91 X1 F5\n!~\n".to_vec();
        let n = c.receive(&mut bytes, 0);
        // `?`, `!` and `~` are gone; the line data is kept, in order, at the end.
        let kept = b"5\n$J=G91 X1 F5\n\n";
        assert_eq!(n, bytes.len() - kept.len());
        assert_eq!(&bytes[n..], kept);
        // Offered again, nothing more is picked.
        let mut again = bytes[n..].to_vec();
        assert_eq!(c.receive(&mut again, 0), 0);
        assert_eq!(again, kept);
    }

    #[test]
    fn with_checksums_only_bytes_between_lines_are_real_time_in_the_tail() {
        let mut c = ctl();
        let mut port = motion_core::motion::MotionCore::<64>::new(&Default::default(), Default::default()).unwrap();
        let line = format!("{}\n", frame_line(1, "G04 P0"));
        assert_eq!(c.receive(&mut line.clone().into_bytes(), 0), line.len());
        c.poll(1_000_000, &mut port, &mut (), Inputs::default());
        full(&mut c);
        // The buffer ends inside a line: its `!` is line data. After the LF, `?`
        // is between lines and acts alone; so is the `~` after it (`?` is no line
        // data), but with checksums a `~` acts only with the LF behind it (taken
        // with it); the `!` inside the next line is line data again.
        let mut bytes = b"!\n?~\nG1 X1!\n".to_vec();
        let n = c.receive(&mut bytes, 2_000_000);
        assert_eq!(&bytes[n..], b"!\nG1 X1!\n");
        // A `~` not followed by a LF is line data (a damaged line's first byte).
        let mut bytes = b"~G1 X1\n".to_vec();
        let n = c.receive(&mut bytes, 2_000_000);
        assert_eq!(&bytes[n..], b"~G1 X1\n");
    }

    #[test]
    fn a_reset_in_the_tail_consumes_it_and_what_follows_enters_the_buffer() {
        let mut c = ctl();
        full(&mut c);
        let mut bytes = b"X1\n?\x18G0 X1\n".to_vec();
        let n = c.receive(&mut bytes, 0);
        assert_eq!(n, bytes.len());
        assert_eq!(c.rx_free(), controller::RX - b"G0 X1\n".len());
    }
}

/// Jogs sent without character counting, in bursts, with real-time bytes between
/// the lines: every line arrives whole and in order (each answered `ok`, none
/// refused) however often the tail behind the full buffer is picked over.
#[test]
fn picking_real_time_bytes_out_of_the_tail_loses_no_line_data() {
    let mut r = Rig::new();
    r.run_ms(5);
    let jog = b"$J=G91 X0.02 F200\n";
    let lines = 300;
    let mut text = Vec::new();
    for i in 0..lines {
        text.extend_from_slice(jog);
        match i % 7 {
            0 => text.push(b'?'),
            3 => text.extend_from_slice(&[0x91, 0x90]),
            5 => text.extend_from_slice(b"?\x11"),
            _ => {}
        }
    }
    let (mut sent, mut burst, mut most_waiting) = (0, 1, 0);
    for _ in 0..20_000 {
        if sent < text.len() {
            burst = (burst * 7 + 3) % 97 + 1;
            let end = (sent + burst).min(text.len());
            r.send(&text[sent..end]);
            sent = end;
        }
        r.step();
        most_waiting = most_waiting.max(r.pending.len());
        if sent == text.len() && r.pending.is_empty() && r.port.core.is_idle() {
            break;
        }
    }
    assert!(most_waiting > 1_000, "the buffer was full, bytes waited behind it: {most_waiting}");
    r.run_ms(50);
    let got = r.take_lines();
    let oks = got.iter().filter(|l| *l == "ok").count();
    assert!(!got.iter().any(|l| l.starts_with("error") || l.starts_with("[MSG")), "{got:?}");
    assert_eq!(oks, lines);
    assert!(reports(&got) > 20, "{} reports", reports(&got));
    assert!(r.status().contains("MPos:6.000,"), "{}", r.status());
}

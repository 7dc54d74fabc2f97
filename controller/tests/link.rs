//! Checksums with a corrupting link, tape mode with XON/XOFF, random bytes.

mod common;

use std::collections::VecDeque;

use common::{Rig, direct};
use controller::frame_line;
use interp_core::program::ProgramMemory;
use proptest::prelude::*;

/// A deterministic generator (64-bit LCG).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> u32 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 33) as u32
    }
}

fn is_realtime(b: u8) -> bool {
    matches!(b, b'?' | b'!' | b'~' | 0x18 | 0x11 | 0x13 | 0x84 | 0x85 | 0x90..=0x9E | 0xA0 | 0xA1)
}

/// A sender with checksums, character counting and resend: it stops at a resend
/// request, waits until every line in flight is answered (or 0.5 s of silence)
/// and goes on from the line asked for. The link flips a bit of 0.5 % of the
/// bytes and drops another 0.5 % (never making a real-time byte: those are
/// outside the checksum by design).
struct CrcSender {
    lines: Vec<String>,
    next: usize,
    in_flight: VecDeque<usize>,
    resend: Option<u32>,
    silent_ms: u32,
    rng: Lcg,
    flipped: u32,
    dropped: u32,
}

impl CrcSender {
    fn pump(&mut self, rig: &mut Rig) {
        if let Some(k) = self.resend {
            if !self.in_flight.is_empty() && self.silent_ms < 500 {
                return;
            }
            self.in_flight.clear();
            self.next = (k as usize).saturating_sub(1);
            self.resend = None;
        }
        while let Some(l) = self.lines.get(self.next) {
            let n = l.len() + 1;
            if self.in_flight.iter().sum::<usize>() + n > 128 {
                break;
            }
            let mut bytes = Vec::new();
            for &b in l.as_bytes().iter().chain(b"\n") {
                match self.rng.next() % 1000 {
                    0..=4 => {
                        let mut c = b;
                        for bit in 0..8 {
                            c = b ^ (1 << ((self.rng.next() + bit) % 8));
                            if !is_realtime(c) {
                                break;
                            }
                        }
                        if !is_realtime(c) {
                            self.flipped += 1;
                            bytes.push(c);
                        } else {
                            bytes.push(b);
                        }
                    }
                    5..=9 => self.dropped += 1,
                    _ => bytes.push(b),
                }
            }
            rig.send(&bytes);
            self.in_flight.push_back(n);
            self.next += 1;
        }
    }

    fn answer(&mut self, line: &str) {
        self.silent_ms = 0;
        if line == "ok" || line.starts_with("error:") {
            self.in_flight.pop_front();
        }
        if let Some(k) = line.strip_prefix("[MSG:Resend:").and_then(|r| r.strip_suffix(']'))
            && self.resend.is_none()
        {
            self.resend = k.parse().ok();
        }
    }
}

#[test]
fn checksums_and_resend_lose_nothing_on_a_corrupting_link() {
    let mut program = String::from("G98 G00 X20 Z0\n");
    for i in 0..10_000 {
        let u = if i % 2 == 0 { "U0.004" } else { "U-0.004" };
        program.push_str(&format!("G01 {u} W-0.010 F3000\n"));
    }
    program.push_str("M30\n");
    let framed: Vec<String> =
        program.lines().enumerate().map(|(i, l)| frame_line(i as u32 + 1, l).to_string()).collect();
    let mut s = CrcSender {
        lines: framed,
        next: 0,
        in_flight: VecDeque::new(),
        resend: None,
        silent_ms: 0,
        rng: Lcg(7),
        flipped: 0,
        dropped: 0,
    };
    let mut r = Rig::new();
    let mut ended = false;
    for _ in 0..400_000 {
        s.pump(&mut r);
        r.step();
        s.silent_ms += 1;
        for l in r.take_lines() {
            assert!(!l.starts_with("ALARM"), "{l}");
            ended |= l == "[MSG:Pgm End]";
            s.answer(&l);
        }
        if ended && r.port.core.is_idle() {
            break;
        }
    }
    assert!(ended, "sent up to line {}", s.next);
    println!(
        "flipped {} dropped {} resends {} time {} ms",
        s.flipped,
        s.dropped,
        r.ctl.counters().resends,
        r.now / 1_000_000
    );
    assert!(s.flipped > 500 && s.dropped > 500, "{} {}", s.flipped, s.dropped);
    assert!(r.ctl.counters().resends > 500);
    let want = direct(&program, None);
    assert_eq!(want.len(), 10_002);
    assert_eq!(r.port.pushed.len(), want.len());
    assert!(r.port.pushed == want, "the canon sequence differs");
    assert!(r.status().contains("MPos:20.000,0.000,-100.000"));
}

#[test]
fn tape_punch_stores_a_program_that_m98_then_calls() {
    let mut r = Rig::new();
    r.run_ms(2);
    r.take_lines();
    r.send(b"%\nO0012 (SUB)\nG00 U2\nW-1\nM99\n%\n");
    r.run_ms(20);
    let got = r.take_lines();
    assert!(got.iter().any(|l| l == "[MSG:Stored O0012]"), "{got:?}");
    assert!(r.sent.contains(&0x11));
    let pl = r.command("$PL");
    assert!(pl[0].starts_with("[PRG:O0012,"), "{pl:?}");
    let main = "G98 G00 X20 Z0\nM98 P12 L2\nM30\n";
    let answers = r.stream(main, 20_000);
    assert!(answers.iter().any(|l| l == "[MSG:Pgm End]"), "{answers:?}");
    let mut mem = ProgramMemory::<16384, 16, 512>::new();
    mem.load(b"O0012 (SUB)\nG00 U2\nW-1\nM99\n", None).unwrap();
    assert_eq!(r.port.pushed, direct(main, Some(&mem)));
    assert!(r.status().contains("MPos:24.000,0.000,-2.000"));
    assert_eq!(r.command("$PD=12"), vec!["ok"]);
    assert_eq!(r.command("$PL"), vec!["ok"]);
}

/// A sender that polls `?` as soon as its opening `%` is written: when both arrive
/// together the `%` still starts tape mode (the `?` came after it), so an upload is
/// stored, not run; a `?` before the `%` makes it a grbl record mark as before.
#[test]
fn a_status_poll_right_behind_the_opening_percent_does_not_undo_tape_mode() {
    let mut r = Rig::new();
    r.run_ms(2);
    r.take_lines();
    r.send(b"%\n?");
    r.send(b"O0012 (SUB)\nG00 U2\nW-1\nM99\n%\n");
    r.run_ms(20);
    let got = r.take_lines();
    assert!(got.iter().any(|l| l == "[MSG:Stored O0012]"), "{got:?}");
    assert!(r.port.pushed.is_empty(), "nothing ran");

    let mut r = Rig::new();
    r.run_ms(2);
    r.take_lines();
    r.send(b"?%\n");
    r.run_ms(5);
    let got = r.take_lines();
    assert!(!got.iter().any(|l| l.contains("Stored")), "{got:?}");
    assert!(got.iter().any(|l| l == "ok"), "a record mark, answered ok: {got:?}");
}

#[test]
fn tape_drip_feed_runs_under_xon_xoff() {
    let mut program = String::from("G98 G00 X20 Z0\n");
    for i in 0..2000 {
        program.push_str(&format!("G01 W-{} F2000\n", if i % 2 == 0 { "0.2" } else { "0.1" }));
    }
    program.push_str("M30\n");
    let tape = format!("%\n{program}%\n");
    let bytes = tape.as_bytes();
    let mut r = Rig::new();
    let (mut at, mut stopped, mut seen, mut xoffs) = (0, false, 0, 0);
    let mut ended = false;
    for _ in 0..120_000 {
        // 115200 baud: about 11 bytes a millisecond, unless stopped by DC3.
        for &b in &r.sent[seen..] {
            if b == 0x13 {
                stopped = true;
                xoffs += 1;
            } else if b == 0x11 {
                stopped = false;
            }
        }
        seen = r.sent.len();
        if !stopped && at < bytes.len() {
            let n = 11.min(bytes.len() - at);
            r.send(&bytes[at..at + n]);
            at += n;
        }
        let offered = r.pending.len();
        let took = r.feed();
        assert_eq!(took, offered, "bytes refused: flow control too late");
        r.step();
        ended |= r.lines().iter().any(|l| l == "[MSG:Pgm End]");
        if ended && at == bytes.len() && r.port.core.is_idle() {
            break;
        }
    }
    assert!(ended);
    assert!(xoffs > 0);
    assert_eq!(r.lines().iter().filter(|l| *l == "ok").count(), 1, "only the opening % is answered");
    // Drip feed keeps the tape's line numbers: the leading % is line 1.
    assert_eq!(r.port.pushed, direct(&format!("%\n{program}"), None));
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn random_bytes_never_panic_and_status_still_answers(data in proptest::collection::vec(any::<u8>(), 0..3000)) {
        let mut r = Rig::new();
        for chunk in data.chunks(37) {
            r.send(chunk);
            r.step();
        }
        r.run_ms(5);
        r.pending.clear();
        r.take_lines();
        r.send(b"?");
        r.run_ms(3);
        prop_assert!(r.take_lines().iter().any(|l| l.starts_with('<')));
    }

    #[test]
    fn random_gcode_like_text_never_panics(picks in proptest::collection::vec(0usize..40, 0..1500)) {
        const TOKENS: [&str; 40] = [
            "G00 ", "G01 ", "G02 ", "G71 ", "G70 ", "X", "Z", "U", "W", "F", "R", "P", "Q", "N", "M98 ",
            "M30", "M99", "#1", "=", "[", "]", "WHILE ", "DO1", "END1", "GOTO", "IF ", " LT ", "1", "5",
            "0.", "-", "\n", "\n", "\n", ";", "%", "$", "$J=", "$H", "$X",
        ];
        let mut r = Rig::new();
        let text: String = picks.iter().map(|&i| TOKENS[i]).collect();
        for chunk in text.as_bytes().chunks(29) {
            r.send(chunk);
            r.step();
        }
        r.run_ms(50);
        r.pending.clear();
        r.send(&[0x18]);
        r.run_ms(3);
        r.take_lines();
        r.send(b"?");
        r.run_ms(3);
        prop_assert!(r.take_lines().iter().any(|l| l.starts_with('<')));
    }
}

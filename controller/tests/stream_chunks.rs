//! qemu-test's lathe program (G71/G70 and a G76 thread) streamed with grbl character counting into
//! the firmware's controller (4 KB window) the way a link delivers it: bytes in
//! random chunks at random times, polls at random times, the motion core ticking
//! every millisecond. Whatever the timing, every line is `ok`, nothing alarms, and
//! the motion core gets exactly what the interpreter makes of the program run
//! directly. `STREAM_SEEDS=n` runs n timings (default 4; a release build runs
//! thousands in minutes).

mod common;

use common::{Counting, Rig, TICK, direct};
use controller::Controller;
use interp_core::MachineConfig;
use interp_core::canon::xorshift::XorShift;

/// The firmware's controller (firmware/src/shell.rs).
type Fw = Controller<4096, 16384, 32, 512>;

/// The program firmware/qemu-test.py streams.
const PROGRAM: &str = include_str!("../../firmware/qemu-program.nc");

/// A value in `0..n` (0 for `n` = 0).
fn below(rng: &mut XorShift, n: u64) -> u64 {
    rng.next_u64() % n.max(1)
}

/// Streams PROGRAM with timing `seed`; the answers.
fn run(seed: u64) -> (Rig<Fw>, Vec<String>) {
    let mut rng = XorShift::new(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1);
    let mut r: Rig<Fw> = Rig::with(MachineConfig::default());
    let mut sender = Counting::new(PROGRAM.lines().map(String::from).collect());
    let mut answers = Vec::new();
    let mut next_tick = TICK;
    for _ in 0..2_000_000 {
        sender.pump(&mut r);
        // A chunk of what the link has: nothing, a byte, a few, or all of it.
        let k = match below(&mut rng, 4) {
            0 => 0,
            1 => 1,
            2 => below(&mut rng, 16) as usize,
            _ => r.pending.len(),
        }
        .min(r.pending.len());
        if k > 0 {
            let mut chunk: Vec<u8> = r.pending.drain(..k).collect();
            let n = r.ctl.receive(&mut chunk, r.now);
            for &b in chunk[n..].iter().rev() {
                r.pending.push_front(b);
            }
        }
        // Time moves on by 0-3 ms (0: a receive and a poll at the same instant).
        r.now += below(&mut rng, 3_000_000);
        if below(&mut rng, 3) != 0 {
            r.ctl.poll(r.now, &mut r.port, &mut r.io, r.inputs);
        }
        let now = r.now;
        while next_tick <= now {
            r.now = next_tick;
            r.tick_motion();
            next_tick += TICK;
        }
        r.now = now;
        let mut out = [0u8; 4096];
        let n = r.ctl.transmit(&mut out);
        r.sent.extend_from_slice(&out[..n]);
        for l in r.take_lines() {
            sender.answer(&l);
            answers.push(l);
        }
        let done = answers.iter().any(|l| l == "[MSG:Pgm End]" || l.starts_with("ALARM:"));
        if sender.finished() && done && r.port.core.is_idle() {
            break;
        }
    }
    (r, answers)
}

#[test]
fn qemu_tests_program_streamed_with_any_timing_runs_as_written() {
    let seeds: u64 = std::env::var("STREAM_SEEDS").ok().and_then(|s| s.parse().ok()).unwrap_or(4);
    let want = direct(PROGRAM, None);
    assert!(want.len() > 30, "{} actions", want.len());
    for seed in 0..seeds {
        let (mut r, answers) = run(seed);
        assert!(!answers.iter().any(|l| l.starts_with("ALARM") || l.contains("ALARM")), "seed {seed}: {answers:?}");
        let oks = answers.iter().filter(|l| *l == "ok").count();
        assert_eq!(oks, PROGRAM.lines().count(), "seed {seed}: {answers:?}");
        let ms = r.now / TICK;
        assert!(answers.iter().any(|l| l == "[MSG:Pgm End]"), "seed {seed} at {ms} ms: {answers:?} {}", r.status());
        assert_eq!(r.port.pushed, want, "seed {seed}");
        // Where `lathe sim` ends the program (qemu-test's PROGRAM_END).
        let s = r.status();
        assert!(s.starts_with("<Idle|MPos:50.000,0.000,20.000|"), "seed {seed}: {s}");
        // The G76 thread's passes take most of the ~17 s.
        assert!(ms > 15_000, "seed {seed}: {ms} ms");
    }
}

#[test]
fn qemu_tests_program_streamed_every_millisecond() {
    let mut r: Rig<Fw> = Rig::with(MachineConfig::default());
    let answers = r.stream(PROGRAM, 120_000);
    let ms = r.now / TICK;
    assert!(answers.iter().any(|l| l == "[MSG:Pgm End]"), "at {ms} ms: {answers:?} {}", r.status());
    assert_eq!(r.port.pushed, direct(PROGRAM, None));
}

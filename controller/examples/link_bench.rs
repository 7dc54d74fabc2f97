//! Streaming throughput over simulated links: a character-counting sender streams
//! short G01 blocks to the controller over a link at 95 % of its wire speed
//! (115,200 baud 8N1; USB full speed CDC at 19 × 64-byte bulk packets per 1 ms
//! frame), the controller feeds a real `MotionCore<64>` ticking every 1 ms.
//! Prints blocks/s executed and the planner-empty (starvation) events.
//!
//! `cargo run --release -p controller --example link_bench`

use std::collections::VecDeque;

use controller::{Board, Inputs};
use interp_core::MachineConfig;
use interp_core::axis::Pos;
use motion_core::motion::{Feedback, MotionCore};

/// A link: bytes per millisecond (fractional) each way.
struct Link {
    name: &'static str,
    bytes_per_ms: f64,
}

struct Result {
    blocks: u64,
    seconds: f64,
    starvations: u32,
    max_queued: usize,
    mean_queued: f64,
}

fn run(link: &Link, block: &str, blocks: usize) -> Result {
    let cfg = MachineConfig::default();
    let mut core: Box<MotionCore<64>> = Box::new(MotionCore::new(&cfg, Pos::ZERO).expect("machine"));
    let mut ctl: Box<Board> = Box::new(Board::new(cfg, Pos::ZERO));
    let mut lines: VecDeque<String> = VecDeque::new();
    lines.push_back("G98 G00 X20 Z0".into());
    for _ in 0..blocks {
        lines.push_back(block.to_string());
    }
    lines.push_back("M30".into());
    let mut wire: VecDeque<u8> = VecDeque::new(); // sender → board, not yet delivered
    let mut in_flight: VecDeque<usize> = VecDeque::new();
    let mut held: Vec<u8> = Vec::new(); // delivered, not yet taken by receive()
    let (mut credit, mut back_credit) = (0.0, 0.0);
    let mut back: VecDeque<u8> = VecDeque::new(); // board → sender
    let mut answer = Vec::new();
    let mut out = [0u8; 4096];
    let mut now = 0u64;
    let mut ended = false;
    let mut alarm = false;
    let (mut queued_sum, mut ticks) = (0u64, 0u64);
    while !(alarm || ended && core.is_idle()) && now < 600_000_000_000 {
        // Sender: character counting, writes into the wire queue.
        while let Some(l) = lines.front() {
            let n = l.len() + 1;
            if in_flight.iter().sum::<usize>() + n > 128 {
                break;
            }
            wire.extend(l.as_bytes());
            wire.push_back(b'\n');
            in_flight.push_back(n);
            lines.pop_front();
        }
        // The wire moves 95 % of its capacity per millisecond.
        credit += link.bytes_per_ms * 0.95;
        while credit >= 1.0 {
            let Some(b) = wire.pop_front() else { break };
            held.push(b);
            credit -= 1.0;
        }
        if wire.is_empty() {
            credit = credit.min(1.0);
        }
        let n = ctl.receive(&mut held, now);
        held.drain(..n);
        ctl.poll(now, &mut *core, &mut (), Inputs::default());
        core.tick(now, Feedback::default());
        queued_sum += core.queued() as u64;
        ticks += 1;
        for axis in 0..4 {
            while core.next_step(axis, now + 1_000_000).is_some() {}
        }
        let m = ctl.transmit(&mut out);
        back.extend(&out[..m]);
        back_credit += link.bytes_per_ms * 0.95;
        while back_credit >= 1.0 {
            let Some(b) = back.pop_front() else { break };
            back_credit -= 1.0;
            if b == b'\n' {
                let l = String::from_utf8_lossy(&answer).trim().to_string();
                if l == "ok" || l.starts_with("error") {
                    in_flight.pop_front();
                }
                ended |= l == "[MSG:Pgm End]";
                alarm |= l.starts_with("ALARM");
                answer.clear();
            } else {
                answer.push(b);
            }
        }
        if back.is_empty() {
            back_credit = back_credit.min(1.0);
        }
        now += 1_000_000;
        if std::env::var("BENCH_DEBUG").is_ok() && now.is_multiple_of(10_000_000_000) {
            eprintln!(
                "{} s: {:?} blocks {} {:?} in flight {}",
                now / 1_000_000_000,
                ctl.counters(),
                core.stats().blocks,
                core.state(),
                in_flight.len()
            );
        }
    }
    assert!(ended && !alarm, "the program did not run to its end");
    let st = core.stats();
    Result {
        blocks: st.blocks,
        seconds: now as f64 / 1e9,
        starvations: st.starvations,
        max_queued: st.max_queued,
        mean_queued: queued_sum as f64 / ticks.max(1) as f64,
    }
}

fn main() {
    let links = [
        Link { name: "UART 115200 8N1", bytes_per_ms: 115_200.0 / 10.0 / 1000.0 },
        Link { name: "USB FS CDC", bytes_per_ms: 19.0 * 64.0 },
    ];
    // Straight collinear blocks: the planner could run them at full speed, so
    // any slow-down is the link's (or the controller's).
    let blocks = [
        ("G01 W-0.020 F3000", 10_000, "0.02 mm at 3000 mm/min (0.4 ms/block)"),
        ("G01 W-0.050 F3000", 5_000, "0.05 mm at 3000 mm/min (1 ms/block)"),
        ("G01 W-0.500 F3000", 800, "0.5 mm at 3000 mm/min (10 ms/block)"),
    ];
    println!(
        "{:<18} {:<40} {:>10} {:>8} {:>12} {:>10} {:>11}",
        "link", "blocks", "blocks/s", "sim s", "starvations", "max queue", "mean queue"
    );
    for link in &links {
        for (block, count, what) in &blocks {
            let r = run(link, block, *count);
            println!(
                "{:<18} {:<40} {:>10.0} {:>8.2} {:>12} {:>10} {:>11.1}",
                link.name,
                what,
                r.blocks as f64 / r.seconds,
                r.seconds,
                r.starvations,
                r.max_queued,
                r.mean_queued
            );
        }
    }
    println!(
        "sizes: Board {} bytes, MotionCore<64> {} bytes",
        core::mem::size_of::<Board>(),
        core::mem::size_of::<MotionCore<64>>()
    );
}

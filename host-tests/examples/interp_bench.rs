//! Interpreter throughput on the host: blocks per second for a long CAM-style
//! G01/G02/G03 program, and the sizes of the interpreter's state.
//!
//! Run: `cargo run --release -p host-tests --example interp_bench`

use std::hint::black_box;
use std::time::Instant;

use interp_core::canon::{Canon, CanonSink, Full};
use interp_core::modal::State;
use interp_core::{Interpreter, MachineConfig, Panel, Progress, SingleProgram};

/// Counts actions and drops them.
struct Count(u64);

impl CanonSink for Count {
    fn push(&mut self, c: Canon) -> Result<(), Full> {
        black_box(c);
        self.0 += 1;
        Ok(())
    }
}

/// A finishing-pass style program: short G01 segments along a wavy profile with a
/// G02/G03 pair every tenth block, the way CAM posts a contour.
fn cam_program(blocks: usize) -> String {
    let mut s = String::from("%\nO1000 (CAM CONTOUR)\nG00 X40. Z2.\nG99 M3 S1200\nG01 F0.12\n");
    let mut z = 0.0f64;
    for i in 0..blocks {
        let x = 40.0 + 4.0 * (i as f64 * 0.05).sin();
        z -= 0.05;
        if i % 10 == 9 {
            let dir = if (i / 10) % 2 == 0 { "G02" } else { "G03" };
            s.push_str(&format!("N{} {dir} X{x:.3} Z{z:.3} R25.\n", i % 99999 + 1));
        } else {
            s.push_str(&format!("N{} G01 X{x:.3} Z{z:.3}\n", i % 99999 + 1));
        }
        if z < -500.0 {
            z = 0.0;
            s.push_str("G00 X60.\nZ2.\nX40.\n");
        }
    }
    s.push_str("G00 X100. Z100.\nM30\n%\n");
    s
}

fn main() {
    let blocks = 200_000;
    let text = cam_program(blocks);
    let store = SingleProgram(text.as_bytes());
    let mut best = f64::MAX;
    let mut executed = 0u64;
    let mut actions = 0u64;
    for _ in 0..5 {
        let mut interp = Interpreter::new(MachineConfig::default());
        let mut sink = Count(0);
        executed = 0;
        let t = Instant::now();
        loop {
            match interp.step(&store, &Panel::default(), &mut sink) {
                Ok(Progress::Executed { .. }) => executed += 1,
                Ok(Progress::Ended) => break,
                Ok(_) => {}
                Err(a) => panic!("benchmark program raised {a}"),
            }
        }
        best = best.min(t.elapsed().as_secs_f64());
        actions = sink.0;
    }
    println!("interpreter: {executed} blocks, {actions} canonical actions, {} bytes of text", text.len());
    println!(
        "interpreter: {:.0} blocks/s ({:.2} us/block, best of 5)",
        executed as f64 / best,
        best * 1e6 / executed as f64
    );
    println!("size of Interpreter: {} bytes", std::mem::size_of::<Interpreter>());
    println!("  of which MachineConfig: {} bytes", std::mem::size_of::<MachineConfig>());
    println!("  of which State: {} bytes", std::mem::size_of::<State>());
    println!("size of one canonical action: {} bytes", std::mem::size_of::<Canon>());
}

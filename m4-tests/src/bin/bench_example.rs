//! Instruction-count example: measures a small i64 multiply-accumulate loop on the
//! emulated Cortex-M4F. Run it through `bench.sh`, which loads the icount plugin;
//! each measured call then prints `instructions: N`.
#![no_std]
#![no_main]

use cortex_m_rt::entry;
use cortex_m_semihosting::hprintln;
use m4_tests::{exit, measure};

/// Elements per measured call.
const LEN: usize = 16;

/// Measured calls: identical counts show that nothing but the input decides them.
const RUNS: usize = 3;

/// Does nothing: measures the cost of the measurement itself (call and return).
fn empty(_: ()) {}

/// Dot product of two i32 vectors with an i64 accumulator (a `smlal` per element).
fn dot(input: (&[i32; LEN], &[i32; LEN])) -> i64 {
    let (a, b) = input;
    a.iter().zip(b.iter()).map(|(&x, &y)| i64::from(x) * i64::from(y)).sum()
}

#[entry]
fn main() -> ! {
    let a: [i32; LEN] = core::array::from_fn(|i| i as i32 * 1_000_003);
    let b: [i32; LEN] = core::array::from_fn(|i| 7 - i as i32 * 65_537);

    hprintln!("bench empty (measurement overhead)");
    measure(empty, ());
    hprintln!("bench dot, {} elements, {} runs", LEN, RUNS);
    let mut result = 0;
    for _ in 0..RUNS {
        result = measure(dot, (&a, &b));
    }
    hprintln!("dot = {}", result);
    exit(true)
}

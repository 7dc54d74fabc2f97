//! On-target tests: run on the emulated Cortex-M4F by
//! `cargo test --target thumbv7em-none-eabihf` in `m4-tests/`.
//!
//! A test is a plain `fn() -> Result<(), &'static str>`; add it to [`TESTS`].
#![no_std]
#![no_main]

use core::hint::black_box;

use cortex_m_rt::entry;
use heapless::Vec;
use m4_tests::{TestFn, run_tests, tests};

/// Every on-target test, run in this order.
const TESTS: &[(&str, TestFn)] =
    &tests![i64_arithmetic, f64_software_float_is_exact, f32_hardware_float, heapless_vec_reports_full,];

#[entry]
fn main() -> ! {
    run_tests(TESTS)
}

/// Fails with `reason` unless `ok` holds.
fn check(ok: bool, reason: &'static str) -> Result<(), &'static str> {
    if ok { Ok(()) } else { Err(reason) }
}

/// 64-bit integers, which the M4 handles in register pairs and library calls
/// (`__aeabi_ldivmod` for division).
fn i64_arithmetic() -> Result<(), &'static str> {
    let a = black_box(-7_000_000_000_123_i64);
    let b = black_box(1_000_i64);
    check(a / b == -7_000_000_000, "division truncates toward zero")?;
    check(a % b == -123, "remainder takes the dividend's sign")?;
    check(a.div_euclid(b) == -7_000_000_001, "euclidean division")?;
    check(black_box(3_037_000_500_i64).checked_mul(3_037_000_500).is_none(), "overflow detected")?;
    check(black_box(u64::MAX) >> black_box(63) == 1, "64-bit shift across the register pair")
}

/// f64 runs in software on the M4; libm must give the same bits as on the host.
fn f64_software_float_is_exact() -> Result<(), &'static str> {
    let two = black_box(2.0_f64);
    check(libm::sqrt(two) == core::f64::consts::SQRT_2, "sqrt is correctly rounded")?;
    check(libm::atan2(black_box(1.0), black_box(1.0)) == core::f64::consts::FRAC_PI_4, "atan2(1, 1) is pi/4")?;
    check(libm::hypot(black_box(3.0), black_box(4.0)) == 5.0, "hypot(3, 4) is 5")?;
    check(black_box(0.1_f64) + black_box(0.2) == 0.300_000_000_000_000_04, "0.1 + 0.2 rounds like IEEE 754")?;
    check(libm::floor(black_box(-2.5)) == -3.0 && libm::round(black_box(2.5)) == 3.0, "floor and round")
}

/// f32 runs on the FPU, which cortex-m-rt enables at reset.
fn f32_hardware_float() -> Result<(), &'static str> {
    check(black_box(1.5_f32) * black_box(2.25) == 3.375, "FPU multiply")?;
    check(libm::sqrtf(black_box(2.0)) == core::f32::consts::SQRT_2, "f32 sqrt")
}

/// A full fixed-capacity vector hands the rejected element back instead of growing.
fn heapless_vec_reports_full() -> Result<(), &'static str> {
    let mut v: Vec<u8, 4> = Vec::new();
    for i in 0..4 {
        v.push(i).map_err(|_| "push below capacity")?;
    }
    check(v.push(4) == Err(4), "push at capacity returns the element")?;
    check(v.len() == 4 && v.is_full(), "length stays at capacity")
}

//! Support for running interp-core code on an emulated Cortex-M4F (QEMU `mps2-an386`):
//! a minimal test harness whose result is the guest's exit status, and region markers
//! that the instruction-counting QEMU plugin (`qemu-plugin/icount.c`) reads.
//!
//! Output and the exit status go through semihosting, so the binaries only run under
//! a debugger or QEMU with `-semihosting-config enable=on` (see `.cargo/config.toml`).
#![no_std]

use core::hint::black_box;
use core::panic::PanicInfo;

use cortex_m_semihosting::{debug, hprint, hprintln};
// Linked now so this workspace always builds against the current interpreter core;
// its tests call into it as its API appears.
use interp_core as _;

/// One on-target test: `Err` carries a short reason shown next to `FAILED`.
pub type TestFn = fn() -> Result<(), &'static str>;

/// Builds the test list from function names: `tests![a, b]` is
/// `[("a", a as TestFn), ("b", b as TestFn)]`.
#[macro_export]
macro_rules! tests {
    ($($name:ident),+ $(,)?) => {
        [$((stringify!($name), $name as $crate::TestFn)),+]
    };
}

/// Runs every test, prints one line per test and a `N passed, N failed` summary, and
/// ends QEMU with exit status 0 only if all passed.
pub fn run_tests(tests: &[(&str, TestFn)]) -> ! {
    let mut failed = 0;
    for (name, test) in tests {
        // Printed first, so a panic report follows the name of the test that panicked.
        hprint!("test {} ... ", name);
        match test() {
            Ok(()) => hprintln!("ok"),
            Err(reason) => {
                failed += 1;
                hprintln!("FAILED: {}", reason);
            }
        }
    }
    hprintln!("{} passed, {} failed", tests.len() - failed, failed);
    exit(failed == 0)
}

/// Ends the emulation with a success or failure exit status.
pub fn exit(success: bool) -> ! {
    debug::exit(if success { debug::EXIT_SUCCESS } else { debug::EXIT_FAILURE });
    // Without a semihosting host the exit request returns: park the core.
    loop {
        cortex_m::asm::wfi();
    }
}

/// Calls `f(input)` between the start and stop markers, so the icount plugin prints
/// `instructions: N` for exactly this call.
///
/// The call goes through an opaque function pointer, so the compiler can neither
/// inline the work nor move it across a marker. `N` includes the call itself and the
/// callee's frame set-up and return: an empty function measures 4.
#[inline(never)]
pub fn measure<T, R>(f: fn(T) -> R, input: T) -> R {
    let f = black_box(f);
    let input = black_box(input);
    marker::<1>();
    let output = f(input);
    marker::<2>();
    black_box(output)
}

/// As [`measure`], but the plugin adds the count to a running sum instead of
/// printing it; [`report_sum`] prints the sum. For many short calls (every
/// interrupt of a spindle revolution), measured without their surroundings.
#[inline(never)]
pub fn measure_sum<T, R>(f: fn(T) -> R, input: T) -> R {
    let f = black_box(f);
    let input = black_box(input);
    marker::<3>();
    let output = f(input);
    marker::<4>();
    black_box(output)
}

/// Makes the plugin print `instructions: S in N regions (most M)` for the
/// [`measure_sum`] calls since the last report (each counted as [`measure`] counts).
#[inline(never)]
pub fn report_sum() {
    marker::<5>();
}

/// Region marker for the icount plugin: `DBG #1` starts a region, `DBG #2` ends it
/// (`#3`/`#4` a summed region, `#5` prints the sum).
///
/// `DBG` is a hint that executes as a no-op (on hardware too) and that compilers
/// never emit, so the plugin can recognise it by its encoding alone.
#[inline(always)]
fn marker<const ID: u8>() {
    // SAFETY: DBG is a hint with no architectural effect outside halting debug.
    unsafe { core::arch::asm!("dbg #{id}", id = const ID, options(nostack, preserves_flags)) }
}

/// Reports the panic and ends the emulation with a failure status.
#[panic_handler]
fn panic(info: &PanicInfo) -> ! {
    hprintln!("{}", info);
    exit(false)
}

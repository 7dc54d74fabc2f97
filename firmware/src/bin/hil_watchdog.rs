//! Bring-up test: the independent watchdog resets a firmware that stops feeding it.
//! First run: the test starts the watchdog with the firmware's timeout
//! (`WATCHDOG_TIMEOUT_US`, 250 ms) and stops feeding it, noting the time it has
//! survived in RAM that a reset keeps. The watchdog resets the chip; the test
//! starts again, finds the watchdog's reset flag (RCC_CSR IWDGRSTF) and its note,
//! and checks the time to the reset against the timeout on the LSI's tolerance
//! (17–47 kHz on the F405: 0.68–1.9 × nominal). No reset within 3 s fails.
//!
//! `cargo run --release --bin hil_watchdog` (probe-rs stays attached across the
//! reset; if it loses RTT, `probe-rs attach --chip STM32F405RGTx
//! target/thumbv7em-none-eabihf/release/hil_watchdog` shows the second run).
#![no_std]
#![no_main]

use core::mem::MaybeUninit;

use embassy_executor::Spawner;
use embassy_stm32::pac;
use embassy_time::Instant;
use firmware::board::{Board, WATCHDOG_TIMEOUT_US};
use firmware::hil::Report;
use {defmt_rtt as _, panic_probe as _};

/// "Watchdog armed" in [`NOTE`]'s first word.
const ARMED: u32 = 0x57_44_4F_47; // "WDOG"

/// Kept across a reset (not initialised at start-up): the mark, and how long the
/// starving run lasted, µs.
#[unsafe(link_section = ".uninit.hil_watchdog")]
static mut NOTE: MaybeUninit<[u32; 2]> = MaybeUninit::uninit();

/// Where [`NOTE`] is (a plain static of words; only this thread-mode code touches it).
fn note() -> *mut [u32; 2] {
    core::ptr::addr_of_mut!(NOTE).cast()
}

#[cfg_attr(not(feature = "qemu"), embassy_executor::main)]
#[cfg_attr(feature = "qemu", embassy_executor::task)]
async fn main(_spawner: Spawner) {
    let mut r = Report::new("hil_watchdog");
    let board = Board::new(firmware::chip::init());
    let timeout_ms = i64::from(WATCHDOG_TIMEOUT_US / 1_000);
    r.figure("watchdog timeout", timeout_ms, "ms");
    if !r.on_board("the watchdog resets a starved firmware") {
        r.finish();
    }
    let csr = pac::RCC.csr().read();
    // SAFETY: see `note`.
    let [mark, survived_us] = unsafe { note().read_volatile() };
    pac::RCC.csr().modify(|w| w.set_rmvf(true)); // clear the reset flags
    if csr.wdgrstf() && mark == ARMED {
        // SAFETY: see `note`.
        unsafe { note().write_volatile([0, 0]) };
        r.check("reset by the watchdog", true);
        r.within(
            "time to the reset",
            i64::from(survived_us) / 1_000,
            "ms",
            timeout_ms * 68 / 100,
            timeout_ms * 19 / 10 + 5,
        );
        r.finish();
    }
    r.check("not reset by the watchdog before the test (no stale flag)", !csr.wdgrstf());
    let mut watchdog = board.watchdog;
    // SAFETY: see `note`.
    unsafe { note().write_volatile([ARMED, 0]) };
    watchdog.unleash();
    let start = Instant::now();
    loop {
        let us = start.elapsed().as_micros();
        // SAFETY: see `note`.
        unsafe { note().write_volatile([ARMED, us as u32]) };
        if us > 3_000_000 {
            break;
        }
    }
    // SAFETY: see `note`.
    unsafe { note().write_volatile([0, 0]) };
    r.check("reset by the watchdog within 3 s", false);
    r.finish()
}

firmware::hil_qemu_entry!();

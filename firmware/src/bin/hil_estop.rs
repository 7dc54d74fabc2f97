//! Bring-up test: the e-stop cuts step output within one step interrupt. X steps
//! at 20 kHz (the STEP probe, TIM1 on PA8 with a jumper from X STEP PC6, counts
//! them); PC13 then drives the e-stop input PC0 high through a jumper, as an opened
//! e-stop contact does (docs/BRINGUP.md). The step interrupt reads the input
//! before every STEP rise: at most one more rise may follow (one already due in
//! that interrupt run), within one step period, and DRIVE ENABLE (PC9) must be low.
//!
//! `cargo run --release --bin hil_estop`
#![no_std]
#![no_main]

use defmt::unwrap;
use embassy_executor::Spawner;
use embassy_stm32::pac;
use firmware::board::bench::{ESTOP_DRIVE_BIT, estop_drive_pin};
use firmware::board::{Board, DRIVE_ENABLE_BIT, ESTOP_BIT, STEP_PORT, STEP_TIMER, TIMER_HZ};
use firmware::hil::moves::{self, MM};
use firmware::hil::{Report, probe};
use interp_core::axis::Axis;
use interp_core::config::MachineConfig;
use {defmt_rtt as _, panic_probe as _};

/// Step rate of the move, steps per second.
const RATE: i64 = 20_000;

#[cfg_attr(not(feature = "qemu"), embassy_executor::main)]
#[cfg_attr(feature = "qemu", embassy_executor::task)]
async fn main(_spawner: Spawner) {
    let mut r = Report::new("hil_estop");
    let mut board = Board::new(firmware::chip::init());
    let cfg = MachineConfig::default();
    estop_drive_pin();
    let started = firmware::motion::start(&cfg);
    r.check("motion core and interrupts started", started.is_ok());
    if r.on_board("STEP stops within one interrupt of the e-stop input") {
        let mut port = unwrap!(started.ok());
        embassy_time::Timer::after_millis(10).await;
        r.check("e-stop input reads released (jumper PC13 -> PC0 in place)", STEP_PORT.idr().read().0 & ESTOP_BIT == 0);
        board.drive_enable.set_high();
        probe::count_steps();
        let steps_per_mm = cfg.axes[Axis::X.index()].drive.steps;
        let x0 = cfg.reference[0].0[Axis::X.index()];
        let z0 = cfg.reference[0].0[Axis::Z.index()];
        r.check("move queued", moves::line(&mut port, x0 - 40 * MM, z0, RATE * 60 / steps_per_mm));
        embassy_time::Timer::after_millis(500).await;
        let before = probe::steps();
        r.check("stepping before the e-stop", before > 1_000);
        // E-stop: the contact opens.
        let t0 = STEP_TIMER.cnt().read();
        let at_stop = probe::steps();
        STEP_PORT.bsrr().write_value(pac::gpio::regs::Bsrr(ESTOP_DRIVE_BIT));
        let (mut last, mut last_at) = (at_stop, t0);
        while STEP_TIMER.cnt().read().wrapping_sub(t0) < TIMER_HZ / 500 {
            let n = probe::steps();
            if n != last {
                (last, last_at) = (n, STEP_TIMER.cnt().read());
            }
        }
        let after = last.wrapping_sub(at_stop);
        let latency_ns = i64::from(last_at.wrapping_sub(t0)) * 1_000_000_000 / i64::from(TIMER_HZ);
        r.within("STEP rises after the e-stop", i64::from(after), "rises", 0, 1);
        r.within("last STEP rise after the e-stop", latency_ns, "ns", 0, 1_000_000_000 / RATE);
        r.check("DRIVE ENABLE low", STEP_PORT.odr().read().0 & DRIVE_ENABLE_BIT == 0);
        STEP_PORT.bsrr().write_value(pac::gpio::regs::Bsrr(ESTOP_DRIVE_BIT << 16));
        board.drive_enable.set_low();
    }
    r.finish()
}

firmware::hil_qemu_entry!();

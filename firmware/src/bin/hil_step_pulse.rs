//! Bring-up test: X STEP pulse width and period, DIR set-up — the board's real step
//! path (motion core, period interrupt, step interrupt on TIM2, GPIOC) timed by
//! the STEP probe (TIM1 on PA8, a jumper from X STEP PC6; docs/BRINGUP.md).
//!
//! Ten 2 mm X moves back and forth at 1,500 mm/min (10 kHz, 800 steps each, a DIR
//! reversal between moves). Checks: every STEP high time between the drive's
//! pulse width and 1 µs more; no two STEP rises closer than the drive allows; the
//! axis back where it started. DIR set-up (PC10 before PC6) is for the scope; the
//! test checks that the player's timing in TIM2 ticks is never shorter than the
//! drive's figures (QEMU runs that part).
//!
//! `cargo run --release --bin hil_step_pulse` (probe-rs runner, firmware/.cargo/config.toml).
#![no_std]
#![no_main]

use defmt::unwrap;
use embassy_executor::Spawner;
use firmware::board::{Board, TIMER_HZ};
use firmware::hil::moves::{self, MM};
use firmware::hil::{Report, probe};
use interp_core::axis::Axis;
use interp_core::config::MachineConfig;
use motion_core::stepgen::DriverTiming;
use motion_driver::playback::PlayTiming;
use motion_driver::timebase::TimeBase;
use {defmt_rtt as _, panic_probe as _};

#[cfg_attr(not(feature = "qemu"), embassy_executor::main)]
#[cfg_attr(feature = "qemu", embassy_executor::task)]
async fn main(_spawner: Spawner) {
    let mut r = Report::new("hil_step_pulse");
    let mut board = Board::new(firmware::chip::init());
    let cfg = MachineConfig::default();
    let drive = cfg.axes[Axis::X.index()].drive;
    r.figure("X drive pulse width", i64::from(drive.pulse_ns), "ns");
    r.figure("X drive DIR set-up (scope: PC10 edge to PC6 rise)", i64::from(drive.dir_setup_ns), "ns");

    // The player's timing in TIM2 ticks, rounded up: never shorter than the drive's.
    let timing = unwrap!(DriverTiming::from_drive(&drive).ok());
    let tb = unwrap!(TimeBase::new(TIMER_HZ, cfg.motion.tick_ns).ok());
    let play = PlayTiming::new(timing, &tb);
    let ns = |ticks: u32| i64::try_from(tb.ns(ticks)).unwrap_or(i64::MAX);
    r.check("pulse in TIM2 ticks >= the drive's pulse", ns(play.pulse) >= i64::from(drive.pulse_ns));
    r.check("DIR set-up in TIM2 ticks >= the drive's", ns(play.dir_setup) >= i64::from(drive.dir_setup_ns));
    r.check(
        "STEP period in TIM2 ticks >= the drive's shortest",
        ns(play.min_period) >= i64::from(timing.min_period_ns),
    );

    if r.on_board("STEP pulses on PC6 timed by TIM1 on PA8") {
        let mut port = unwrap!(firmware::motion::start(&cfg).ok());
        board.drive_enable.set_high();
        probe::time_steps();
        let x0 = cfg.reference[0].0[Axis::X.index()];
        let z0 = cfg.reference[0].0[Axis::Z.index()];
        let start = moves::x_steps(&port);
        let (mut high_min, mut high_max, mut period_min, mut pulses) = (u32::MAX, 0, u32::MAX, 0u32);
        for i in 0..10 {
            let x = if i % 2 == 0 { x0 - 2 * MM } else { x0 };
            r.check("move queued", moves::line(&mut port, x, z0, 1_500));
            // Sample the probe while the move runs (every pulse is timed; the
            // registers keep the last one).
            for _ in 0..2_000 {
                if let Some((period, high)) = probe::last_pulse() {
                    pulses += 1;
                    high_min = high_min.min(high);
                    high_max = high_max.max(high);
                    if period > high {
                        period_min = period_min.min(period);
                    }
                }
                if port.peek(|m| m.core.is_idle()).unwrap_or(true) {
                    break;
                }
                embassy_time::Timer::after_micros(200).await;
            }
            r.check("move ended", moves::wait_idle(&mut port, 2_000).await);
        }
        r.check("pulses seen on the probe", pulses > 100);
        let pulse = i64::from(drive.pulse_ns);
        r.within("shortest STEP high time", probe::ns(high_min), "ns", pulse, pulse + 1_000);
        r.within("longest STEP high time", probe::ns(high_max), "ns", pulse, pulse + 1_000);
        r.within("shortest STEP period", probe::ns(period_min), "ns", i64::from(timing.min_period_ns), 1_000_000);
        r.check("X back where it started", moves::x_steps(&port) == start);
        board.drive_enable.set_low();
    }
    r.finish()
}

firmware::hil_qemu_entry!();

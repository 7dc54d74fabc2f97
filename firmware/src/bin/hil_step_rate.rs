//! Bring-up test: the step rate ceiling — how fast the board's step path (period
//! interrupt filling the edge rings, step interrupt playing them) makes X steps
//! without losing one. The STEP probe (TIM1 on PA8, a jumper from X STEP PC6;
//! docs/BRINGUP.md) counts every rise.
//!
//! With the drives disconnected, X is given a 1 µs pulse, a 500 kHz limit and a
//! steep acceleration, and runs 12,000-step moves (30 mm) at rising rates, from
//! 25 kHz to 400 kHz. At each rate the probe's count must equal the steps the
//! motion core commanded; the ceiling is the highest rate with an exact count, and
//! it must reach the 100 kHz of the board's default drive. The time each move took
//! gives the rate achieved (acceleration included).
//!
//! `cargo run --release --bin hil_step_rate`
#![no_std]
#![no_main]

use defmt::unwrap;
use embassy_executor::Spawner;
use firmware::board::{Board, STEP_TIMER, TIMER_HZ};
use firmware::hil::moves::{self, MM};
use firmware::hil::{Report, probe};
use interp_core::axis::Axis;
use interp_core::config::MachineConfig;
use {defmt_rtt as _, panic_probe as _};

/// Rates tried, steps per second.
const RATES: [u32; 8] = [25_000, 50_000, 100_000, 150_000, 200_000, 250_000, 300_000, 400_000];
/// Steps per move (under the probe's 16-bit count).
const STEPS: i64 = 12_000;

#[cfg_attr(not(feature = "qemu"), embassy_executor::main)]
#[cfg_attr(feature = "qemu", embassy_executor::task)]
async fn main(_spawner: Spawner) {
    let mut r = Report::new("hil_step_rate");
    let mut board = Board::new(firmware::chip::init());
    let mut cfg = MachineConfig::default();
    let x = &mut cfg.axes[Axis::X.index()];
    x.drive.pulse_ns = 1_000;
    x.drive.dir_setup_ns = 1_000;
    x.drive.max_step_hz = 500_000;
    let steps_per_mm = x.drive.steps;
    x.max_feed_per_min = 500_000 * 60 / steps_per_mm * MM;
    x.rapid_per_min = x.max_feed_per_min;
    x.accel_per_s2 = 20_000 * MM;
    r.check("test machine description accepted", cfg.validate().is_ok());
    if r.on_board("X STEP counted by TIM1 on PA8 at 25-400 kHz") {
        let mut port = unwrap!(firmware::motion::start(&cfg).ok());
        board.drive_enable.set_high();
        probe::count_steps();
        let x0 = cfg.reference[0].0[Axis::X.index()];
        let z0 = cfg.reference[0].0[Axis::Z.index()];
        let distance = STEPS * MM / steps_per_mm;
        let mut ceiling = 0;
        for (i, &rate) in RATES.iter().enumerate() {
            let to = if i % 2 == 0 { x0 - distance } else { x0 };
            let mm_min = i64::from(rate) * 60 / steps_per_mm;
            let (before, counted) = (moves::x_steps(&port), probe::steps());
            let t0 = STEP_TIMER.cnt().read();
            let queued = moves::line(&mut port, to, z0, mm_min);
            let ended = moves::wait_idle(&mut port, 5_000).await;
            let ticks = STEP_TIMER.cnt().read().wrapping_sub(t0);
            let commanded = (moves::x_steps(&port) - before).unsigned_abs();
            let seen = u64::from(probe::steps().wrapping_sub(counted));
            let exact = queued && ended && commanded == STEPS.unsigned_abs() && seen == commanded;
            r.figure("commanded rate", i64::from(rate), "Hz");
            r.figure("  steps counted", seen as i64, "steps");
            r.figure(
                "  rate achieved over the move",
                (seen * u64::from(TIMER_HZ) / u64::from(ticks.max(1))) as i64,
                "Hz",
            );
            if exact && ceiling == i64::from(RATES.get(i.wrapping_sub(1)).copied().unwrap_or(0)) {
                ceiling = i64::from(rate);
            }
        }
        r.figure("step rate ceiling (exact counts up to)", ceiling, "Hz");
        r.within("step rate ceiling", ceiling, "Hz", 100_000, 1_000_000);
        board.drive_enable.set_low();
    }
    r.finish()
}

firmware::hil_qemu_entry!();

//! Bring-up test: spindle encoder counting and index latch. TIM8 generates
//! quadrature on PC6/PC7 (jumpers to the encoder inputs PA0/PA1) in bursts of
//! exactly 512 counts, and a GPIO pulse on PC8 (jumper to the index input PD2)
//! follows each burst (docs/BRINGUP.md). TIM5 (the firmware's encoder timer, with
//! its input filter) must count every edge, up with A leading and down with B
//! leading, and the index interrupt must latch TIM5's count at each pulse. Then
//! the count rate is raised burst by burst to find the fastest exact one (the
//! firmware needs 204,800 counts/s: 3,000 rpm × 4,096 counts).
//!
//! `cargo run --release --bin hil_encoder`
#![no_std]
#![no_main]

use embassy_executor::Spawner;
use embassy_stm32::pac;
use embassy_stm32::pac::timer::vals::Ocm;
use firmware::board::bench::{INDEX_DRIVE_BIT, QUAD_TIMER as Q, QUAD_TIMER_HZ, quadrature_pins};
use firmware::board::{Board, ENCODER_TIMER, STEP_PORT};
use firmware::hil::{Report, spin_us};
use interp_core::config::MachineConfig;
use {defmt_rtt as _, panic_probe as _};

/// Counts per burst: 256 timer periods, each toggling A and B once.
const BURST: i64 = 512;

#[cfg_attr(not(feature = "qemu"), embassy_executor::main)]
#[cfg_attr(feature = "qemu", embassy_executor::task)]
async fn main(_spawner: Spawner) {
    let mut r = Report::new("hil_encoder");
    let _board = Board::new(firmware::chip::init());
    let cfg = MachineConfig::default();
    let needed = i64::from(cfg.spindle.max_rpm) * i64::from(cfg.spindle.encoder_cpr) / 60;
    r.figure("counts/s at the top speed", needed, "counts/s");
    // The motion interrupts own the index latch (EXTI2).
    let started = firmware::motion::start(&cfg);
    r.check("motion core and interrupts started", started.is_ok());
    if r.on_board("quadrature from TIM8 counted by TIM5, index latched") {
        quadrature_pins();
        let rate = 409_600; // twice the top speed
        for (lead_a, sign) in [(true, 1), (false, -1)] {
            let before = count();
            for _ in 0..8 {
                burst(rate, lead_a);
            }
            r.within(
                if lead_a { "8 bursts, A leading" } else { "8 bursts, B leading" },
                count() - before,
                "counts",
                8 * BURST * sign,
                8 * BURST * sign,
            );
        }
        let mut latched = 0;
        for _ in 0..4 {
            burst(rate, true);
            let raw = ENCODER_TIMER.cnt().read();
            index_pulse();
            if firmware::motion::index_latch() == Some(raw) {
                latched += 1;
            }
        }
        r.within("index pulses latched at the count", latched, "of 4", 4, 4);
        let mut fastest = 0;
        for rate in [409_600, 1_000_000, 2_000_000, 4_000_000] {
            let before = count();
            burst(rate, true);
            if count() - before == BURST && fastest == prev(rate) {
                fastest = rate;
            }
        }
        r.figure("fastest exact count rate", fastest, "counts/s");
        r.within("count rate with margin over the top speed", fastest, "counts/s", 2 * needed, i64::MAX);
    }
    r.finish()
}

/// The rate before `rate` in the list tried (0 for the first).
fn prev(rate: i64) -> i64 {
    match rate {
        1_000_000 => 409_600,
        2_000_000 => 1_000_000,
        4_000_000 => 2_000_000,
        _ => 0,
    }
}

/// TIM5's count, widened to i64 from a reading that never moves more than 2³¹.
fn count() -> i64 {
    i64::from(ENCODER_TIMER.cnt().read() as i32)
}

/// One burst of [`BURST`] counts at `rate` counts/s: TIM8 in one-pulse mode for
/// 256 periods (repetition counter), A and B each toggling once per period, a
/// quarter period apart (A at ¼, B at ¾: A leads), or the other way round.
fn burst(rate: i64, lead_a: bool) {
    let period = (i64::from(QUAD_TIMER_HZ) * 2 / rate).clamp(8, 65_535) as u16;
    let (a, b) = if lead_a { (period / 4, period * 3 / 4) } else { (period * 3 / 4, period / 4) };
    Q.cr1().write(|w| w.set_opm(true));
    Q.psc().write_value(0);
    Q.arr().write(|w| w.set_arr(period - 1));
    Q.rcr().write(|w| w.set_rep(255));
    Q.ccmr_output(0).write(|w| {
        w.set_ocm(0, Ocm::TOGGLE);
        w.set_ocm(1, Ocm::TOGGLE);
    });
    Q.ccr(0).write(|w| w.set_ccr(a));
    Q.ccr(1).write(|w| w.set_ccr(b));
    Q.ccer().write(|w| {
        w.set_cce(0, true);
        w.set_cce(1, true);
    });
    Q.bdtr().write(|w| w.set_moe(true));
    Q.egr().write(|w| w.set_ug(true)); // loads the repetition counter
    Q.sr().write_value(pac::timer::regs::SrAdv(0));
    Q.cr1().write(|w| {
        w.set_opm(true);
        w.set_cen(true);
    });
    while Q.cr1().read().cen() {}
    spin_us(5); // the input filter's delay
}

/// A 5 µs index pulse on PC8.
fn index_pulse() {
    STEP_PORT.bsrr().write_value(pac::gpio::regs::Bsrr(INDEX_DRIVE_BIT));
    spin_us(5);
    STEP_PORT.bsrr().write_value(pac::gpio::regs::Bsrr(INDEX_DRIVE_BIT << 16));
    spin_us(5);
}

firmware::hil_qemu_entry!();

//! Firmware entry point: clocks, board bring-up and the task set.
#![no_std]
#![no_main]

use defmt::{info, unwrap};
use embassy_executor::Spawner;
use embassy_stm32::gpio::Output;
use embassy_stm32::rcc::{
    AHBPrescaler, APBPrescaler, Hse, HseMode, Pll, PllMul, PllPDiv, PllPreDiv, PllQDiv, PllSource, Sysclk,
};
use embassy_stm32::time::Hertz;
use embassy_time::Timer;
use firmware::board::Board;
use static_cell::StaticCell;
use {defmt_rtt as _, panic_probe as _};
// The interpreter core and the hardware traits are linked in now so the target build
// checks that they stay no_std; the DNC/interpreter task that drives them arrives with
// the firmware issue.
use {hal as _, interp_core as _};

/// The board lives for the whole run, so its pins keep their configured (safe) levels.
static BOARD: StaticCell<Board> = StaticCell::new();

/// System clock from the board's 8 MHz crystal: 168 MHz core, 42 MHz APB1
/// (84 MHz timers), 84 MHz APB2 (168 MHz timers), 48 MHz for USB.
fn clock_config() -> embassy_stm32::Config {
    let mut config = embassy_stm32::Config::default();
    let rcc = &mut config.rcc;
    rcc.hse = Some(Hse { freq: Hertz::mhz(8), mode: HseMode::Oscillator });
    rcc.pll_src = PllSource::HSE;
    rcc.pll = Some(Pll {
        prediv: PllPreDiv::DIV4,   // 2 MHz PLL input
        mul: PllMul::MUL168,       // 336 MHz VCO
        divp: Some(PllPDiv::DIV2), // 168 MHz system clock
        divq: Some(PllQDiv::DIV7), // 48 MHz USB/SDIO clock
        divr: None,
    });
    rcc.sys = Sysclk::PLL1_P;
    rcc.ahb_pre = AHBPrescaler::DIV1;
    rcc.apb1_pre = APBPrescaler::DIV4;
    rcc.apb2_pre = APBPrescaler::DIV2;
    config
}

#[embassy_executor::main]
async fn main(spawner: Spawner) {
    let board = BOARD.init(Board::new(embassy_stm32::init(clock_config())));
    info!("lathe motion board up");
    spawner.spawn(unwrap!(heartbeat(&mut board.status_led)));
}

/// Blinks the status LED at 1 Hz: visible proof that the executor and time driver run.
#[embassy_executor::task]
async fn heartbeat(led: &'static mut Output<'static>) {
    loop {
        led.toggle();
        Timer::after_millis(500).await;
    }
}

//! The chip's start: the clock tree of the board's 8 MHz crystal, and in the QEMU
//! build the workarounds its STM32F405 model needs before and after
//! `embassy_stm32::init` (`qemu.rs`). The firmware and every bring-up test binary
//! (`src/bin/hil_*.rs`) start with [`init`].

use embassy_stm32::Peripherals;

/// Clocks up: the HAL's peripherals. Call once, first.
///
/// # Panics
///
/// If called twice.
pub fn init() -> Peripherals {
    #[cfg(feature = "qemu")]
    let mut cp = {
        crate::qemu::rcc_workaround();
        let mut cp = defmt::unwrap!(cortex_m::Peripherals::take());
        crate::qemu::trap_pwr(&mut cp.MPU);
        cp
    };
    let p = embassy_stm32::init(clock_config());
    #[cfg(feature = "qemu")]
    {
        crate::qemu::untrap_pwr(&mut cp.MPU);
        crate::qemu::start_time_driver(&mut cp.SYST);
    }
    p
}

/// System clock from the board's 8 MHz crystal: 168 MHz core, 42 MHz APB1
/// (84 MHz timers), 84 MHz APB2 (168 MHz timers), 48 MHz for USB. Same on the F446.
#[cfg(not(feature = "qemu"))]
pub fn clock_config() -> embassy_stm32::Config {
    use embassy_stm32::rcc::{
        AHBPrescaler, APBPrescaler, Hse, HseMode, Pll, PllMul, PllPDiv, PllPreDiv, PllQDiv, PllSource, Sysclk,
    };
    use embassy_stm32::time::Hertz;
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

/// QEMU: the reset clocks (HSI 16 MHz) and no backup domain (QEMU's PWR never
/// acknowledges DBP).
#[cfg(feature = "qemu")]
pub fn clock_config() -> embassy_stm32::Config {
    let mut config = embassy_stm32::Config::default();
    config.rcc.ls = embassy_stm32::rcc::LsConfig::off();
    config
}

//! The motion board's pin map: the only file that names MCU pins and the peripherals
//! tied to them. [`Board::new`] turns the HAL's peripherals into typed drivers, each
//! output at its safe (off) level, so the rest of the firmware never sees a pin name.
//!
//! Pin map for the STM32F405RG (LQFP64):
//!
//! | Pin  | Function       | Notes                                                     |
//! |------|----------------|-----------------------------------------------------------|
//! | PC6  | X STEP         | step interrupt via GPIOC BSRR; TIM8_CH1 capable (AF3)     |
//! | PC7  | Z STEP         | TIM8_CH2 capable (AF3)                                    |
//! | PC8  | C / Y STEP     | third channel (TIM8_CH3 capable, AF3): C on a lathe, Y on a mill |
//! | PC9  | DRIVE ENABLE   | shared by all step drivers; high = enabled                |
//! | PC10 | X DIR          | same port as the steps: one BSRR write sets DIR and STEP  |
//! | PC11 | Z DIR          |                                                           |
//! | PC12 | C / Y DIR      | third channel: C on a lathe, Y on a mill ($311)           |
//! | PA0  | SPINDLE ENC A  | TIM5_CH1 (AF2), 32-bit timer in encoder mode              |
//! | PA1  | SPINDLE ENC B  | TIM5_CH2 (AF2)                                            |
//! | PD2  | SPINDLE INDEX  | EXTI2 (own IRQ vector): latches TIM5's count in its ISR   |
//! | PA6  | SPINDLE PWM    | TIM3_CH1 (AF2), 1 kHz into a PWM-to-0–10 V converter     |
//! | PB0  | SPINDLE CW     | M03: VFD forward run                                      |
//! | PB1  | SPINDLE CCW    | M04: VFD reverse run                                      |
//! | PB6  | COOLANT FLOOD  | M08                                                       |
//! | PB7  | COOLANT MIST   | M07 (air/mist)                                            |
//! | PB8  | CHUCK CLAMP    | high = clamp                                              |
//! | PB9  | TAILSTOCK      | high = quill forward                                      |
//! | PB10 | LUBE           | way-lube pump                                             |
//! | PB5  | STATUS LED     | heartbeat                                                 |
//! | PC0  | E-STOP         | NC contact, high = stop; read raw in the motion ISRs      |
//! | PC1  | FEED HOLD      | NO button to GND, low = pressed                           |
//! | PC3  | CYCLE START    | NO button to GND, low = pressed                           |
//! | PB12 | X LIMIT        | both ends in series, NC, high = tripped                   |
//! | PB13 | Z LIMIT        | both ends in series, NC, high = tripped                   |
//! | PB14 | X HOME         | high = on the switch                                      |
//! | PB15 | Z HOME         |                                                           |
//! | PC2  | Y LIMIT        | a mill's; both ends in series, NC, high = tripped (no PB11 on the F446RE) |
//! | PA8  | Y HOME         | a mill's; high = on the switch                            |
//! | PC4  | ATC T1         | a mill's tool changer (feature `mill`): tool number bit 0  |
//! | PC5  | ATC T2         | tool number bit 1                                         |
//! | PA4  | ATC T4         | tool number bit 2                                         |
//! | PA5  | ATC T8         | tool number bit 3                                         |
//! | PA15 | ATC T16        | tool number bit 4 (JTDI pull-up until configured: no harm, the request is low) |
//! | PA7  | ATC REQUEST    | high = change to the tool on T1–T16 (set before it rises)  |
//! | PB4  | ATC DONE       | changer's done: contact/open collector to GND, low = done |
//! | PA2  | DNC TX         | USART2_TX (AF7)                                           |
//! | PA3  | DNC RX         | USART2_RX (AF7)                                           |
//! | PA11 | USB D−         | OTG_FS_DM (AF10): the fast link, CDC-ACM (feature `usb`)  |
//! | PA12 | USB D+         | OTG_FS_DP (AF10); no VBUS sensing (PA9 is USART1's)       |
//!
//! Outputs are active high at the MCU pin (opto/relay drivers on the board) and all
//! start low, so a reset leaves the spindle, coolant and drives off. Switch inputs use
//! the internal pull-ups; normally-closed safety contacts read high when open, so a
//! broken wire looks like a tripped switch. Switches are sampled every millisecond and
//! debounced by the control task; the e-stop is also read raw by the step and motion
//! interrupts (same port as the STEP pins: one IDR read).
//!
//! Kept free on purpose: PA13/PA14 (SWD), PB3 (SWO), PH0/PH1 (8 MHz HSE crystal),
//! PC14/PC15 (LSE), PB2 (BOOT1), PA9/PA10 (USART1: ROM bootloader, service console).
//! Spare: PC13; on a build without the mill profile also the ATC pins PA4/PA5
//! (DAC outputs, an alternative to PWM for the 0–10 V speed signal), PA7, PA15,
//! PB4, PC4, PC5 (ADC, e.g. override potentiometers).
//!
//! The automatic tool changer (docs/MILL-BOARD.md): at a mill's M06 with `$312=1`
//! the board sets the tool number on ATC T1–T16 (binary, tools 1–31), raises ATC
//! REQUEST and waits for ATC DONE; done drops the request and the program goes on,
//! no done within `$313` s is alarm 4511 (request dropped). A tool above 31 is
//! never requested (the board cannot say it): the wait ends in alarm 4511.
//!
//! The third step channel drives the machine kind's third axis (`$311`,
//! docs/MILL-BOARD.md): the C axis of a lathe or the Y axis of a mill — a mill's Y
//! drive is wired to PC8/PC12. Its edges pass through the same ring as C's would:
//! a fourth ring (2 KB) does not fit the static RAM budget. On a mill the spindle
//! encoder is optional (M29 rigid tapping and M19 orientation need it).
//!
//! Timers: TIM2 (32-bit, 84 MHz, no pins) step time base and step-edge compare, TIM7
//! interpolation period, TIM5 spindle encoder (32-bit) with compares at the due counts, TIM3
//! spindle PWM, TIM4 embassy time driver (no pins); TIM8 (for hardware step pulses
//! later), TIM1 and TIM6 are free.
//!
//! Flash: sectors 0–9 (768 KB) program, sectors 10–11 (0x080C0000..0x08100000,
//! 256 KB) the controller's store ([`STORE_START`], `saved.rs`); on the F446RE
//! (512 KB) sector 0 holds the vector table, sectors 1–3 (48 KB) the store and
//! sectors 4–7 (448 KB) the program. See `memory-f405/memory.x` and `memory-f446/memory.x`.

use defmt::unwrap;
use embassy_stm32::flash::{Blocking, Flash};
use embassy_stm32::gpio::{Input, Level, Output, OutputType, Pin, Pull, Speed};
use embassy_stm32::peripherals::{IWDG, TIM2, TIM3, TIM5, TIM7};
use embassy_stm32::time::Hertz;
use embassy_stm32::timer::low_level::{CountingMode, Timer};
use embassy_stm32::timer::qei::{self, Qei};
use embassy_stm32::timer::simple_pwm::{PwmPin, SimplePwm, SimplePwmChannel};
use embassy_stm32::usart::{self, BufferedUart};
use embassy_stm32::wdg::IndependentWatchdog;
use embassy_stm32::{Peri, Peripherals, bind_interrupts, pac, peripherals};
use motion_driver::playback::AxisPins;
use static_cell::ConstStaticCell;

/// Baud rate of the DNC serial link.
pub const DNC_BAUD: u32 = 115_200;

/// Carrier frequency of the spindle speed PWM (typical PWM-to-0–10 V modules take 1–3 kHz).
pub const SPINDLE_PWM_FREQ: Hertz = Hertz(1_000);

/// Clock of TIM2/TIM5/TIM7 (APB1 timers at 2 × 42 MHz with the 168 MHz clock tree).
pub const TIMER_HZ: u32 = 84_000_000;

/// STEP/DIR pins of X, Z and the third channel (C on a lathe, Y on a mill) on port
/// C (the step interrupt writes GPIOC's BSRR).
pub const STEP_PINS: [AxisPins; 3] =
    [AxisPins { step: 6, dir: 10 }, AxisPins { step: 7, dir: 11 }, AxisPins { step: 8, dir: 12 }];

/// The port of the STEP/DIR pins and the e-stop input.
pub const STEP_PORT: pac::gpio::Gpio = pac::GPIOC;

/// E-stop input bit in [`STEP_PORT`]'s IDR (PC0, high = stop).
pub const ESTOP_BIT: u32 = 1 << 0;

/// Drive enable bit in [`STEP_PORT`]'s BSRR (PC9, high = enabled).
pub const DRIVE_ENABLE_BIT: u32 = 1 << 9;

/// The spindle encoder timer (TIM5, 32-bit, encoder mode).
pub const ENCODER_TIMER: pac::timer::TimGp32 = pac::TIM5;

/// The step time base and step-edge compare timer (TIM2, 32-bit, free running).
pub const STEP_TIMER: pac::timer::TimGp32 = pac::TIM2;

/// The interpolation period timer (TIM7).
pub const PERIOD_TIMER: pac::timer::TimBasic = pac::TIM7;

/// First byte of the flash region reserved for the controller's store (see
/// `memory-f405/memory.x`):
/// STM32F405 sectors 10–11.
#[cfg(feature = "f405")]
pub const STORE_START: u32 = 0x080C_0000;
/// Size of the store region: two 128 KB sectors.
#[cfg(feature = "f405")]
pub const STORE_SIZE: u32 = 256 * 1024;
/// First byte of the store on the STM32F446RE (`memory-f446/memory.x`): sectors
/// 1–3, between the vector table in sector 0 and the program from sector 4 on.
#[cfg(feature = "f446")]
pub const STORE_START: u32 = 0x0800_4000;
/// Size of the F446RE's store: three 16 KB sectors.
#[cfg(feature = "f446")]
pub const STORE_SIZE: u32 = 48 * 1024;

bind_interrupts!(
    /// Interrupt vectors bound to embassy drivers (the motion interrupts are in
    /// `motion.rs`). USART2 runs [`TcGuard`] first, then embassy's handler.
    struct Irqs {
        USART2 => TcGuard, usart::BufferedInterruptHandler<peripherals::USART2>;
    }
);

/// TC (transmission complete) in USART_SR.
const SR_TC: u32 = 1 << 6;

/// Takes the transmission-complete interrupt of the DNC link away from embassy's
/// `BufferedUart` handler, which loses received bytes. embassy-stm32 0.6 (usart
/// v1/v2) clears TC with a read-modify-write of SR (`sr.modify(|w| w.set_tc(false))`):
/// a byte received between its read (RXNE 0) and its write has RXNE written back 0,
/// which clears it (RXNE is rc_w0), so the byte is never read and the next one
/// overwrites it. That happens at the end of every transmission — every `ok` —
/// while the sender streams the next line. In QEMU (its SR write takes the value
/// written) a loaded host lost about one byte in 8 KB that way (a line's first
/// byte cost `qemu-test.py` its G-code line: alarm 0004); on the board the window
/// is a few cycles per `ok`.
///
/// Run before embassy's handler, this clears TC by writing every other SR bit as 1
/// (as ST's HAL does, `SR = ~TC`: rc_w0 bits written 1 stay as they are, and QEMU
/// ANDs a value above 0x3FF into SR) and TCIE, so embassy's TC branch never runs.
/// That branch also woke a transmit waiting for room in the ring and set the flag
/// `flush` waits for: `link_tx` retries a waiting write every millisecond and the
/// firmware never calls `flush`.
pub struct TcGuard;

impl embassy_stm32::interrupt::typelevel::Handler<embassy_stm32::interrupt::typelevel::USART2> for TcGuard {
    unsafe fn on_interrupt() {
        let r = pac::USART2;
        if r.sr().read().tc() && r.cr1().read().tcie() {
            r.sr().write_value(pac::usart::regs::Sr(!SR_TC));
            r.cr1().modify(|w| w.set_tcie(false));
        }
    }
}

/// The USB OTG FS interrupt, bound to embassy's driver (the fast link).
#[cfg(feature = "usb")]
mod usb_irq {
    use embassy_stm32::{bind_interrupts, peripherals, usb};

    bind_interrupts!(
        /// OTG_FS → embassy's USB driver.
        pub struct UsbIrqs {
            OTG_FS => usb::InterruptHandler<peripherals::USB_OTG_FS>;
        }
    );
}

/// The USB driver of the fast link (OTG_FS on PA11/PA12).
#[cfg(feature = "usb")]
pub type UsbDriver = embassy_stm32::usb::Driver<'static, peripherals::USB_OTG_FS>;

/// Receive buffer of the USB OUT endpoints: one packet each of the control
/// endpoint and the CDC-ACM data endpoint (64 bytes).
#[cfg(feature = "usb")]
static USB_EP_OUT: ConstStaticCell<[u8; 128]> = ConstStaticCell::new([0; 128]);

/// Receive buffer of the DNC link: room for a few program blocks while the
/// interpreter is busy.
static DNC_RX_BUF: ConstStaticCell<[u8; 1024]> = ConstStaticCell::new([0; 1024]);
/// Transmit buffer of the DNC link (acknowledgements, status reports).
static DNC_TX_BUF: ConstStaticCell<[u8; 256]> = ConstStaticCell::new([0; 256]);

/// STEP and DIR outputs of one stepper/servo drive. The step interrupt drives them
/// through the port's BSRR; these handles keep the pins configured.
pub struct Axis {
    /// One pulse per step.
    pub step: Output<'static>,
    /// Direction level, set before the first step pulse of a move.
    pub dir: Output<'static>,
}

/// Spindle feedback and command signals.
pub struct Spindle {
    /// Quadrature decoder on TIM5 (pins and encoder mode); the count is read in 32
    /// bits from [`ENCODER_TIMER`] (embassy's `Qei::count` reads 16).
    pub encoder: Qei<'static, TIM5>,
    /// Once-per-revolution index pulse (EXTI2, rising edge, handled in `motion.rs`).
    pub index: Input<'static>,
    /// Speed command: duty cycle 0–100 % maps to 0–10 V at the VFD.
    pub speed: SimplePwmChannel<'static, TIM3>,
    /// Run forward (M03).
    pub cw: Output<'static>,
    /// Run reverse (M04).
    pub ccw: Output<'static>,
}

/// Machine auxiliaries switched by M codes.
pub struct Aux {
    /// Flood coolant (M08).
    pub coolant_flood: Output<'static>,
    /// Air/mist coolant (M07).
    pub coolant_mist: Output<'static>,
    /// Chuck clamp (M10/M11).
    pub chuck_clamp: Output<'static>,
    /// Tailstock quill forward (M12/M13).
    pub tailstock: Output<'static>,
    /// Way-lube pump (M32/M33).
    pub lube: Output<'static>,
    /// A mill's automatic tool changer outputs.
    #[cfg(feature = "mill")]
    pub tool_changer: ToolChangerOutputs,
}

/// The tool changer's tool-number outputs (ATC T1, T2, T4, T8, T16: binary).
#[cfg(feature = "mill")]
pub const TOOL_BITS: usize = 5;

// The machine file refuses a `tool_count` above what these outputs carry (canon's
// `MAX_CHANGER_TOOL`): the two limits are one.
#[cfg(feature = "mill")]
const _: () = assert!((1 << TOOL_BITS) - 1 == interp_core::config::MAX_CHANGER_TOOL as usize);

/// The request outputs of a mill's automatic tool changer (its done line is a
/// switch, [`Switches::tool_change_done`]).
#[cfg(feature = "mill")]
pub struct ToolChangerOutputs {
    /// Tool number, binary: bit 0 (T1) first.
    pub tool_bits: [Output<'static>; TOOL_BITS],
    /// Change request (strobe), high = change.
    pub request: Output<'static>,
}

/// Operator and machine switch inputs (pull-ups; sampled and debounced by the control task).
pub struct Switches {
    /// Emergency stop (normally closed; high = stop).
    pub estop: Input<'static>,
    /// Feed hold button (low = pressed).
    pub feed_hold: Input<'static>,
    /// Cycle start button (low = pressed).
    pub cycle_start: Input<'static>,
    /// X travel limits, both ends in series (high = tripped).
    pub x_limit: Input<'static>,
    /// Z travel limits, both ends in series (high = tripped).
    pub z_limit: Input<'static>,
    /// Y travel limits of a mill, both ends in series (high = tripped).
    pub y_limit: Input<'static>,
    /// X home switch (high = on the switch).
    pub x_home: Input<'static>,
    /// Z home switch (high = on the switch).
    pub z_home: Input<'static>,
    /// Y home switch of a mill (high = on the switch).
    pub y_home: Input<'static>,
    /// A mill's tool changer reports done (low = done).
    #[cfg(feature = "mill")]
    pub tool_change_done: Input<'static>,
}

/// The timers of the motion interrupts, clocked and reset; `motion::start` programs them.
pub struct MotionTimers {
    /// Step time base and step-edge compare (TIM2).
    pub step: Timer<'static, TIM2>,
    /// Interpolation period (TIM7).
    pub period: Timer<'static, TIM7>,
}

/// Every board signal as a driver, built once at start-up.
pub struct Board {
    /// Cross slide (diameter) axis.
    pub x: Axis,
    /// Carriage (length) axis.
    pub z: Axis,
    /// The third channel: a lathe's optional rotary (spindle-as-axis) drive C, a
    /// mill's Y.
    pub c: Axis,
    /// Enable line shared by all drives (high = enabled).
    pub drive_enable: Output<'static>,
    /// Spindle encoder and VFD signals.
    pub spindle: Spindle,
    /// Coolant, chuck, tailstock and lube outputs.
    pub aux: Aux,
    /// Limit, home and operator inputs.
    pub switches: Switches,
    /// Serial DNC link to the host.
    pub dnc: BufferedUart<'static>,
    /// USB full-speed device (OTG_FS): the fast link, CDC-ACM.
    #[cfg(feature = "usb")]
    pub usb: UsbDriver,
    /// Heartbeat LED.
    pub status_led: Output<'static>,
    /// Timers of the step and period interrupts.
    pub timers: MotionTimers,
    /// Independent watchdog (started by the control task, fed by its loop).
    pub watchdog: IndependentWatchdog<'static, IWDG>,
    /// Flash for the controller's store (region [`STORE_START`], [`STORE_SIZE`]).
    pub flash: Flash<'static, Blocking>,
}

/// Watchdog timeout: ten periods of the control loop's slowest step.
pub const WATCHDOG_TIMEOUT_US: u32 = 250_000;

impl Board {
    /// Configures every pin of the board from the HAL's peripherals.
    ///
    /// # Panics
    ///
    /// If called twice (the DNC buffers are handed out once).
    pub fn new(p: Peripherals) -> Self {
        Self {
            x: Axis { step: step_output(p.PC6), dir: step_output(p.PC10) },
            z: Axis { step: step_output(p.PC7), dir: step_output(p.PC11) },
            c: Axis { step: step_output(p.PC8), dir: step_output(p.PC12) },
            drive_enable: relay_output(p.PC9),
            spindle: Spindle {
                encoder: encoder(Qei::new(p.TIM5, p.PA0, p.PA1, qei::Config::default())),
                index: Input::new(p.PD2, Pull::Up),
                speed: spindle_pwm(p.TIM3, p.PA6),
                cw: relay_output(p.PB0),
                ccw: relay_output(p.PB1),
            },
            aux: Aux {
                coolant_flood: relay_output(p.PB6),
                coolant_mist: relay_output(p.PB7),
                chuck_clamp: relay_output(p.PB8),
                tailstock: relay_output(p.PB9),
                lube: relay_output(p.PB10),
                #[cfg(feature = "mill")]
                tool_changer: ToolChangerOutputs {
                    tool_bits: [
                        relay_output(p.PC4),
                        relay_output(p.PC5),
                        relay_output(p.PA4),
                        relay_output(p.PA5),
                        relay_output(p.PA15),
                    ],
                    request: relay_output(p.PA7),
                },
            },
            switches: Switches {
                estop: Input::new(p.PC0, Pull::Up),
                feed_hold: Input::new(p.PC1, Pull::Up),
                cycle_start: Input::new(p.PC3, Pull::Up),
                x_limit: Input::new(p.PB12, Pull::Up),
                z_limit: Input::new(p.PB13, Pull::Up),
                x_home: Input::new(p.PB14, Pull::Up),
                z_home: Input::new(p.PB15, Pull::Up),
                y_limit: Input::new(p.PC2, Pull::Up),
                y_home: Input::new(p.PA8, Pull::Up),
                #[cfg(feature = "mill")]
                tool_change_done: Input::new(p.PB4, Pull::Up),
            },
            dnc: {
                let mut config = usart::Config::default();
                config.baudrate = DNC_BAUD;
                // Wake the reader at every byte (QEMU never signals line idle).
                config.eager_reads = Some(1);
                unwrap!(BufferedUart::new(p.USART2, p.PA3, p.PA2, DNC_TX_BUF.take(), DNC_RX_BUF.take(), Irqs, config))
            },
            #[cfg(feature = "usb")]
            usb: usb_driver(p.USB_OTG_FS, p.PA12, p.PA11),
            status_led: relay_output(p.PB5),
            timers: MotionTimers { step: Timer::new(p.TIM2), period: Timer::new(p.TIM7) },
            watchdog: IndependentWatchdog::new(p.IWDG, WATCHDOG_TIMEOUT_US),
            flash: Flash::new_blocking(p.FLASH),
        }
    }
}

/// The encoder timer counting all 32 bits, inputs filtered (8 samples at 84 MHz:
/// pulses under 95 ns are noise; a 2000 rpm × 4096 count edge lasts 7.3 µs), and the
/// index line (PD2 → EXTI2, rising edge) routed for the index interrupt.
fn encoder(qei: Qei<'static, TIM5>) -> Qei<'static, TIM5> {
    ENCODER_TIMER.arr().write_value(u32::MAX);
    ENCODER_TIMER.ccmr_input(0).modify(|w| {
        w.set_icf(0, pac::timer::vals::FilterValue::FCK_INT_N8);
        w.set_icf(1, pac::timer::vals::FilterValue::FCK_INT_N8);
    });
    ENCODER_TIMER.egr().write(|w| w.set_ug(true));
    pac::RCC.apb2enr().modify(|w| w.set_syscfgen(true));
    pac::SYSCFG.exticr(0).modify(|w| w.set_exti(2, 3)); // line 2 ← port D
    pac::EXTI.rtsr(0).modify(|w| w.set_line(2, true));
    pac::EXTI.pr(0).write(|w| w.set_line(2, true));
    pac::EXTI.imr(0).modify(|w| w.set_line(2, true));
    qei
}

/// The OTG_FS device on PA12 (D+) and PA11 (D−). Without VBUS sensing (PA9 stays
/// USART1's): the device keeps its D+ pull-up on and the host sees it when the
/// cable is plugged in.
#[cfg(feature = "usb")]
fn usb_driver(
    otg: Peri<'static, peripherals::USB_OTG_FS>,
    dp: Peri<'static, peripherals::PA12>,
    dm: Peri<'static, peripherals::PA11>,
) -> UsbDriver {
    let mut config = embassy_stm32::usb::Config::default();
    config.vbus_detection = false;
    embassy_stm32::usb::Driver::new_fs(otg, usb_irq::UsbIrqs, dp, dm, USB_EP_OUT.take(), config)
}

/// TIM3 channel 1 on PA6 at [`SPINDLE_PWM_FREQ`], starting at 0 % (spindle stopped).
fn spindle_pwm(tim: Peri<'static, TIM3>, pin: Peri<'static, peripherals::PA6>) -> SimplePwmChannel<'static, TIM3> {
    let pin = PwmPin::new(pin, OutputType::PushPull);
    let pwm = SimplePwm::new(tim, Some(pin), None, None, None, SPINDLE_PWM_FREQ, CountingMode::EdgeAlignedUp);
    let mut speed = pwm.split().ch1;
    speed.set_duty_cycle_fully_off();
    speed.enable();
    speed
}

/// A STEP or DIR output: fast edges for pulse rates of 100 kHz and more.
fn step_output(pin: Peri<'static, impl Pin>) -> Output<'static> {
    Output::new(pin, Level::Low, Speed::VeryHigh)
}

/// A slow on/off output (relay, solid-state relay, LED), starting off.
fn relay_output(pin: Peri<'static, impl Pin>) -> Output<'static> {
    Output::new(pin, Level::Low, Speed::Low)
}

/// The bring-up bench's wiring (docs/BRINGUP.md): jumpers from board outputs back to
/// spare inputs, used only by the `hil_*` test binaries (never by the firmware).
///
/// | Jumper       | From → to  | Used by                                   |
/// |--------------|------------|-------------------------------------------|
/// | STEP probe   | PC6 → PA8  | TIM1_CH1 (AF1): counts or times X STEP     |
/// | E-stop drive | PC13 → PC0 | a GPIO output plays the e-stop contact     |
/// | Quadrature A | PC6 → PA0  | TIM8_CH1 (AF3) drives encoder input A      |
/// | Quadrature B | PC7 → PA1  | TIM8_CH2 (AF3) drives encoder input B      |
/// | Index        | PC8 → PD2  | a GPIO output plays the index pulse        |
///
/// The quadrature jumpers use the X and Z STEP pins (`hil_encoder` re-purposes them;
/// PA8 is then unplugged from PC6). Disconnect the drives and the e-stop chain first.
pub mod bench {
    use embassy_stm32::pac;
    use embassy_stm32::pac::gpio::vals::Moder;

    /// The STEP probe: TIM1 (16-bit, 168 MHz on APB2), channel 1 on PA8.
    pub const PROBE_TIMER: pac::timer::TimAdv = pac::TIM1;
    /// TIM1's clock.
    pub const PROBE_TIMER_HZ: u32 = 168_000_000;
    /// The quadrature generator: TIM8 (168 MHz), channels 1 and 2 on PC6 and PC7.
    pub const QUAD_TIMER: pac::timer::TimAdv = pac::TIM8;
    /// TIM8's clock.
    pub const QUAD_TIMER_HZ: u32 = 168_000_000;
    /// PC13 in port C's BSRR/ODR: drives the e-stop input (PC0) through its jumper.
    pub const ESTOP_DRIVE_BIT: u32 = 1 << 13;
    /// PC8 (C STEP) in port C's BSRR/ODR: drives the index input (PD2).
    pub const INDEX_DRIVE_BIT: u32 = 1 << 8;

    /// PA8 as TIM1_CH1 (AF1) and TIM1 clocked.
    pub fn probe_pin() {
        pac::RCC.apb2enr().modify(|w| w.set_tim1en(true));
        pac::GPIOA.afr(1).modify(|w| w.set_afr(0, 1));
        pac::GPIOA.moder().modify(|w| w.set_moder(8, Moder::ALTERNATE));
    }

    /// PC13 as a push-pull output, low (e-stop released).
    pub fn estop_drive_pin() {
        pac::GPIOC.bsrr().write(|w| w.set_br(13, true));
        pac::GPIOC.moder().modify(|w| w.set_moder(13, Moder::OUTPUT));
    }

    /// PC6/PC7 as TIM8_CH1/CH2 (AF3) and TIM8 clocked; PC8 stays a GPIO output.
    pub fn quadrature_pins() {
        pac::RCC.apb2enr().modify(|w| w.set_tim8en(true));
        pac::GPIOC.afr(0).modify(|w| {
            w.set_afr(6, 3);
            w.set_afr(7, 3);
        });
        pac::GPIOC.moder().modify(|w| {
            w.set_moder(6, Moder::ALTERNATE);
            w.set_moder(7, Moder::ALTERNATE);
        });
    }
}

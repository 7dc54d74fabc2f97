//! The motion board's pin map: the only file that names MCU pins and the peripherals
//! tied to them. [`Board::new`] turns the HAL's peripherals into typed drivers, each
//! output at its safe (off) level, so the rest of the firmware never sees a pin name.
//!
//! Pin map for the STM32F405RG (LQFP64):
//!
//! | Pin  | Function       | Notes                                                     |
//! |------|----------------|-----------------------------------------------------------|
//! | PC6  | X STEP         | TIM8_CH1 capable (AF3) for hardware pulse generation      |
//! | PC7  | Z STEP         | TIM8_CH2 capable (AF3)                                    |
//! | PC8  | C STEP         | TIM8_CH3 capable (AF3); optional rotary axis              |
//! | PC9  | DRIVE ENABLE   | shared by all step drivers; high = enabled                |
//! | PC10 | X DIR          | same port as the steps: one BSRR write sets DIR and STEP  |
//! | PC11 | Z DIR          |                                                           |
//! | PC12 | C DIR          |                                                           |
//! | PA0  | SPINDLE ENC A  | TIM5_CH1 (AF2), 32-bit timer in encoder mode              |
//! | PA1  | SPINDLE ENC B  | TIM5_CH2 (AF2)                                            |
//! | PD2  | SPINDLE INDEX  | EXTI2 (own IRQ vector): once-per-rev pulse for threading  |
//! | PA6  | SPINDLE PWM    | TIM3_CH1 (AF2), 1 kHz into a PWM-to-0–10 V converter     |
//! | PB0  | SPINDLE CW     | M03: VFD forward run                                      |
//! | PB1  | SPINDLE CCW    | M04: VFD reverse run                                      |
//! | PB6  | COOLANT FLOOD  | M08                                                       |
//! | PB7  | COOLANT MIST   | M07 (air/mist)                                            |
//! | PB8  | CHUCK CLAMP    | high = clamp                                              |
//! | PB9  | TAILSTOCK      | high = quill forward                                      |
//! | PB10 | LUBE           | way-lube pump                                             |
//! | PB5  | STATUS LED     | heartbeat                                                 |
//! | PC0  | E-STOP         | EXTI0 (own IRQ vector); NC contact, high = stop           |
//! | PC1  | FEED HOLD      | EXTI1; NO button to GND, low = pressed                    |
//! | PC3  | CYCLE START    | EXTI3; NO button to GND, low = pressed                    |
//! | PB12 | X LIMIT        | EXTI12; both ends in series, NC, high = tripped           |
//! | PB13 | Z LIMIT        | EXTI13; both ends in series, NC, high = tripped           |
//! | PB14 | X HOME         | EXTI14                                                    |
//! | PB15 | Z HOME         | EXTI15                                                    |
//! | PA2  | DNC TX         | USART2_TX (AF7)                                           |
//! | PA3  | DNC RX         | USART2_RX (AF7)                                           |
//!
//! Outputs are active high at the MCU pin (opto/relay drivers on the board) and all
//! start low, so a reset leaves the spindle, coolant and drives off. Switch inputs use
//! the internal pull-ups; normally-closed safety contacts read high when open, so a
//! broken wire looks like a tripped switch. Every switch sits on its own EXTI line.
//!
//! Kept free on purpose: PA13/PA14 (SWD), PB3 (SWO), PH0/PH1 (8 MHz HSE crystal),
//! PC14/PC15 (LSE), PB2 (BOOT1), PA9/PA10 (USART1: ROM bootloader, service console),
//! PA11/PA12 (USB FS, for a USB DNC link later). Spare: PA4/PA5 (DAC outputs, an
//! alternative to PWM for the 0–10 V speed signal), PA7, PA8, PA15, PB4, PB11, PC2,
//! PC4, PC5 (ADC, e.g. override potentiometers), PC13.
//!
//! Timers: TIM5 spindle encoder, TIM3 spindle PWM, TIM4 embassy time driver (no pins),
//! TIM8 reserved for step pulses; TIM1, TIM2, TIM6 and TIM7 are free.

use defmt::unwrap;
use embassy_stm32::exti::{self, ExtiInput};
use embassy_stm32::gpio::{Level, Output, OutputType, Pin, Pull, Speed};
use embassy_stm32::interrupt::typelevel::{EXTI0, EXTI1, EXTI2, EXTI3, EXTI15_10};
use embassy_stm32::mode::Async;
use embassy_stm32::peripherals::{TIM3, TIM5};
use embassy_stm32::time::Hertz;
use embassy_stm32::timer::low_level::CountingMode;
use embassy_stm32::timer::qei::{self, Qei};
use embassy_stm32::timer::simple_pwm::{PwmPin, SimplePwm, SimplePwmChannel};
use embassy_stm32::usart::{self, BufferedUart};
use embassy_stm32::{Peri, Peripherals, bind_interrupts, peripherals};
use static_cell::ConstStaticCell;

/// Baud rate of the DNC serial link.
pub const DNC_BAUD: u32 = 115_200;

/// Carrier frequency of the spindle speed PWM (typical PWM-to-0–10 V modules take 1–3 kHz).
pub const SPINDLE_PWM_FREQ: Hertz = Hertz(1_000);

bind_interrupts!(
    /// Interrupt vectors used by the board's drivers.
    struct Irqs {
        USART2 => usart::BufferedInterruptHandler<peripherals::USART2>;
        EXTI0 => exti::InterruptHandler<EXTI0>;
        EXTI1 => exti::InterruptHandler<EXTI1>;
        EXTI2 => exti::InterruptHandler<EXTI2>;
        EXTI3 => exti::InterruptHandler<EXTI3>;
        EXTI15_10 => exti::InterruptHandler<EXTI15_10>;
    }
);

/// Receive buffer of the DNC link: room for a few program blocks while the
/// interpreter is busy.
static DNC_RX_BUF: ConstStaticCell<[u8; 1024]> = ConstStaticCell::new([0; 1024]);
/// Transmit buffer of the DNC link (acknowledgements, status reports).
static DNC_TX_BUF: ConstStaticCell<[u8; 256]> = ConstStaticCell::new([0; 256]);

/// STEP and DIR outputs of one stepper/servo drive.
pub struct Axis {
    /// One pulse per step.
    pub step: Output<'static>,
    /// Direction level, set before the first step pulse of a move.
    pub dir: Output<'static>,
}

/// Spindle feedback and command signals.
pub struct Spindle {
    /// Quadrature count of the spindle encoder (TIM5). TIM5 counts in 32 bits, but
    /// `Qei::count` returns the low 16: widen in software or read TIM5's CNT.
    pub encoder: Qei<'static, TIM5>,
    /// Once-per-revolution index pulse.
    pub index: ExtiInput<'static, Async>,
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
    /// Chuck clamp.
    pub chuck_clamp: Output<'static>,
    /// Tailstock quill forward.
    pub tailstock: Output<'static>,
    /// Way-lube pump.
    pub lube: Output<'static>,
}

/// Operator and machine switch inputs, each on its own EXTI line.
pub struct Switches {
    /// Emergency stop (normally closed; high = stop).
    pub estop: ExtiInput<'static, Async>,
    /// Feed hold button (low = pressed).
    pub feed_hold: ExtiInput<'static, Async>,
    /// Cycle start button (low = pressed).
    pub cycle_start: ExtiInput<'static, Async>,
    /// X travel limits, both ends in series (high = tripped).
    pub x_limit: ExtiInput<'static, Async>,
    /// Z travel limits, both ends in series (high = tripped).
    pub z_limit: ExtiInput<'static, Async>,
    /// X home switch.
    pub x_home: ExtiInput<'static, Async>,
    /// Z home switch.
    pub z_home: ExtiInput<'static, Async>,
}

/// Every board signal as a driver, built once at start-up.
pub struct Board {
    /// Cross slide (diameter) axis.
    pub x: Axis,
    /// Carriage (length) axis.
    pub z: Axis,
    /// Optional rotary (spindle-as-axis) drive.
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
    /// Heartbeat LED.
    pub status_led: Output<'static>,
}

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
                encoder: Qei::new(p.TIM5, p.PA0, p.PA1, qei::Config::default()),
                index: ExtiInput::new(p.PD2, p.EXTI2, Pull::Up, Irqs),
                speed: {
                    let pin = PwmPin::new(p.PA6, OutputType::PushPull);
                    let pwm = SimplePwm::new(
                        p.TIM3,
                        Some(pin),
                        None,
                        None,
                        None,
                        SPINDLE_PWM_FREQ,
                        CountingMode::EdgeAlignedUp,
                    );
                    let mut speed = pwm.split().ch1;
                    speed.set_duty_cycle_fully_off();
                    speed.enable();
                    speed
                },
                cw: relay_output(p.PB0),
                ccw: relay_output(p.PB1),
            },
            aux: Aux {
                coolant_flood: relay_output(p.PB6),
                coolant_mist: relay_output(p.PB7),
                chuck_clamp: relay_output(p.PB8),
                tailstock: relay_output(p.PB9),
                lube: relay_output(p.PB10),
            },
            switches: Switches {
                estop: ExtiInput::new(p.PC0, p.EXTI0, Pull::Up, Irqs),
                feed_hold: ExtiInput::new(p.PC1, p.EXTI1, Pull::Up, Irqs),
                cycle_start: ExtiInput::new(p.PC3, p.EXTI3, Pull::Up, Irqs),
                x_limit: ExtiInput::new(p.PB12, p.EXTI12, Pull::Up, Irqs),
                z_limit: ExtiInput::new(p.PB13, p.EXTI13, Pull::Up, Irqs),
                x_home: ExtiInput::new(p.PB14, p.EXTI14, Pull::Up, Irqs),
                z_home: ExtiInput::new(p.PB15, p.EXTI15, Pull::Up, Irqs),
            },
            dnc: {
                let mut config = usart::Config::default();
                config.baudrate = DNC_BAUD;
                unwrap!(BufferedUart::new(p.USART2, p.PA3, p.PA2, DNC_TX_BUF.take(), DNC_RX_BUF.take(), Irqs, config))
            },
            status_led: relay_output(p.PB5),
        }
    }
}

/// A STEP or DIR output: fast edges for pulse rates of 100 kHz and more.
fn step_output(pin: Peri<'static, impl Pin>) -> Output<'static> {
    Output::new(pin, Level::Low, Speed::VeryHigh)
}

/// A slow on/off output (relay, solid-state relay, LED), starting off.
fn relay_output(pin: Peri<'static, impl Pin>) -> Output<'static> {
    Output::new(pin, Level::Low, Speed::Low)
}

//! The board's outputs and inputs as the `hal` traits and the controller's
//! `MachineIo`: what the controller's `poll` gets to switch the spindle, coolant,
//! chuck, tailstock and lube, the debounced
//! switch levels it reads, the spindle encoder and the clock. (`hal::StepDir` has no
//! implementation here on purpose: steps are timed edges the step interrupt plays,
//! not calls.)

use core::cell::Cell;

use embassy_stm32::gpio::Output;
use embassy_stm32::peripherals::TIM3;
use embassy_stm32::timer::simple_pwm::SimplePwmChannel;
use embassy_time::Instant;
use hal::{DigitalInputs, DigitalOutputs, MonotonicClock, Rotation, SpindleDrive, SpindleEncoder};
use interp_core::canon::SpindleDir;
use motion_driver::encoder::Encoder;
use motion_driver::io::{AuxOut, Debounce, Switch, aux_switches, spindle_duty};

use crate::board::{Aux, ENCODER_TIMER, Switches};
use crate::motion::index_latch;

/// Samples a switch must hold before its debounced level changes (ms at 1 kHz).
pub const DEBOUNCE_SAMPLES: u8 = 5;

/// The spindle drive and the M-code outputs.
pub struct Outputs {
    aux: Aux,
    cw: Output<'static>,
    ccw: Output<'static>,
    speed: SimplePwmChannel<'static, TIM3>,
    drive_enable: Output<'static>,
    max_rpm: u32,
}

impl Outputs {
    /// The outputs, everything off; `max_rpm` is the speed at full PWM (10 V).
    pub fn new(
        aux: Aux,
        cw: Output<'static>,
        ccw: Output<'static>,
        speed: SimplePwmChannel<'static, TIM3>,
        drive_enable: Output<'static>,
        max_rpm: u32,
    ) -> Self {
        Outputs { aux, cw, ccw, speed, drive_enable, max_rpm }
    }

    /// The output pin of `o`.
    fn pin(&mut self, o: AuxOut) -> &mut Output<'static> {
        match o {
            AuxOut::Flood => &mut self.aux.coolant_flood,
            AuxOut::Mist => &mut self.aux.coolant_mist,
            AuxOut::Chuck => &mut self.aux.chuck_clamp,
            AuxOut::Tailstock => &mut self.aux.tailstock,
            AuxOut::Lube => &mut self.aux.lube,
        }
    }

    /// Switches what M code `m` switches on this board (nothing for other codes).
    pub fn m_code(&mut self, m: u16) {
        for &(o, on) in aux_switches(m) {
            self.pin(o).set_level(on.into());
        }
    }

    /// Step drives on or off (off at e-stop; the step interrupt also drops it).
    pub fn enable_drives(&mut self, on: bool) {
        self.drive_enable.set_level(on.into());
    }

    /// Everything off: spindle, coolant, lube, drives (chuck and tailstock keep their
    /// state: a released chuck must not drop the part).
    pub fn stop_all(&mut self) {
        self.set_speed(Rotation::Stop, 0);
        self.m_code(9);
        self.m_code(33);
        self.enable_drives(false);
    }
}

/// What the controller switches as the program reaches it: M codes to the outputs
/// ([`aux_switches`]), a mill's tool changer request ([`hal::ToolChangeRequest`]),
/// lathe turret indexes logged (the board has no turret output). The
/// spindle drive follows the motion core's output instead
/// (`shell::SpindleFollower`), so G96 speed changes along a cut reach it too.
impl controller::MachineIo for Outputs {
    fn m_code(&mut self, m: u16, _line: u32) {
        Outputs::m_code(self, m);
    }

    fn tool(&mut self, tool: u16, offset: u16) {
        defmt::info!("tool {} offset {}", tool, offset);
    }

    #[cfg(feature = "mill")]
    fn tool_change_request(&mut self, tool: Option<u16>) {
        use hal::ToolChangeRequest;
        match tool {
            Some(t) => self.request_tool(t),
            None => self.clear_request(),
        }
    }
}

/// A mill's tool changer: the tool number on ATC T1–T16, then ATC REQUEST.
#[cfg(feature = "mill")]
impl hal::ToolChangeRequest for Outputs {
    /// A tool the five bits cannot carry (above 31) is not requested: the
    /// controller's wait ends in alarm 4511, never in the wrong tool.
    fn request_tool(&mut self, tool: u16) {
        let tc = &mut self.aux.tool_changer;
        if usize::from(tool) >= 1 << tc.tool_bits.len() {
            defmt::warn!("tool {} is beyond the tool changer outputs (T1-T31)", tool);
            return;
        }
        for (bit, pin) in tc.tool_bits.iter_mut().enumerate() {
            pin.set_level((tool >> bit & 1 != 0).into());
        }
        tc.request.set_high();
    }

    fn clear_request(&mut self) {
        let tc = &mut self.aux.tool_changer;
        tc.request.set_low();
        tc.tool_bits.iter_mut().for_each(Output::set_low);
    }
}

/// The hal rotation of a motion-core spindle direction.
pub fn rotation(dir: SpindleDir) -> Rotation {
    match dir {
        SpindleDir::Cw => Rotation::Cw,
        SpindleDir::Ccw => Rotation::Ccw,
        SpindleDir::Stop => Rotation::Stop,
    }
}

impl DigitalOutputs for Outputs {
    /// Output `n` of [`AuxOut::ALL`] (0 flood, 1 mist, 2 chuck, 3 tailstock, 4 lube).
    fn set_output(&mut self, n: u16, on: bool) {
        if let Some(o) = AuxOut::from_number(n) {
            self.pin(o).set_level(on.into());
        }
    }
}

impl SpindleDrive for Outputs {
    /// Direction outputs (never both) and the PWM duty for `rpm`.
    fn set_speed(&mut self, rotation: Rotation, rpm: u32) {
        let rpm = if rotation == Rotation::Stop { 0 } else { rpm };
        self.cw.set_level((rotation == Rotation::Cw).into());
        self.ccw.set_level((rotation == Rotation::Ccw).into());
        let duty = spindle_duty(rpm, self.max_rpm, self.speed.max_duty_cycle());
        self.speed.set_duty_cycle(duty);
    }
}

/// The switch inputs, sampled and debounced.
pub struct Inputs {
    switches: Switches,
    debounce: Debounce<DEBOUNCE_SAMPLES>,
}

impl Inputs {
    /// Starts from the switches' current levels.
    pub fn new(switches: Switches) -> Self {
        let raw = raw_levels(&switches);
        Inputs { switches, debounce: Debounce::new(raw) }
    }

    /// Takes one sample (call every millisecond); returns the debounced levels.
    pub fn sample(&mut self) -> InputLevels {
        InputLevels(self.debounce.sample(raw_levels(&self.switches)))
    }
}

/// Active levels now, one bit per [`Switch`] (normally-closed contacts and buttons
/// to ground converted so that a set bit means tripped / pressed).
#[cfg(not(feature = "qemu"))]
fn raw_levels(s: &Switches) -> u16 {
    let pins = [
        (Switch::EStop, s.estop.is_high()),
        (Switch::FeedHold, s.feed_hold.is_low()),
        (Switch::CycleStart, s.cycle_start.is_low()),
        (Switch::XLimit, s.x_limit.is_high()),
        (Switch::ZLimit, s.z_limit.is_high()),
        (Switch::XHome, s.x_home.is_high()),
        (Switch::ZHome, s.z_home.is_high()),
        (Switch::YLimit, s.y_limit.is_high()),
        (Switch::YHome, s.y_home.is_high()),
        #[cfg(feature = "mill")]
        (Switch::ToolChangeDone, s.tool_change_done.is_low()),
    ];
    pins.iter().filter(|(_, on)| *on).fold(0, |acc, (sw, _)| acc | sw.bit())
}

/// QEMU models no GPIO (every pin reads low, which would be two pressed buttons):
/// every switch is inactive there.
#[cfg(feature = "qemu")]
fn raw_levels(_: &Switches) -> u16 {
    0
}

/// Debounced switch levels at one moment (bit set = active).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, defmt::Format)]
pub struct InputLevels(pub u16);

impl InputLevels {
    /// Whether `s` is active.
    pub fn active(self, s: Switch) -> bool {
        self.0 & s.bit() != 0
    }
}

impl DigitalInputs for InputLevels {
    /// Input `n` of [`Switch::ALL`] (0 e-stop, 1 feed hold, 2 cycle start, 3 X limit,
    /// 4 Z limit, 5 X home, 6 Z home, 7 Y limit, 8 Y home, 9 tool changer done).
    fn input(&self, n: u16) -> bool {
        Switch::ALL.get(usize::from(n)).is_some_and(|s| self.active(*s))
    }
}

/// The spindle encoder as thread mode reads it (displays, the controller): TIM5's
/// 32-bit count widened on every read, the index count from the index interrupt.
/// Independent of the motion interrupts' own widening (same counter, same result up
/// to the starting offset).
pub struct EncoderReader {
    encoder: Cell<Encoder>,
}

impl EncoderReader {
    /// Count 0 is the counter's value now.
    pub fn new() -> Self {
        EncoderReader { encoder: Cell::new(Encoder::new(ENCODER_TIMER.cnt().read())) }
    }
}

impl Default for EncoderReader {
    fn default() -> Self {
        Self::new()
    }
}

impl SpindleEncoder for EncoderReader {
    fn count(&self) -> i64 {
        let mut e = self.encoder.get();
        let c = e.update(ENCODER_TIMER.cnt().read());
        self.encoder.set(e);
        c
    }

    fn index_count(&self) -> Option<i64> {
        let _ = self.count();
        index_latch().map(|raw| self.encoder.get().widen(raw))
    }
}

/// Embassy's time as the hal clock (ns since boot; µs resolution).
#[derive(Clone, Copy, Debug, Default)]
pub struct Clock;

impl MonotonicClock for Clock {
    fn now_ns(&self) -> u64 {
        Instant::now().as_micros() * 1_000
    }
}

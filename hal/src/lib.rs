//! Hardware capability traits: one small trait per capability. The firmware
//! implements them on the STM32 board; the host simulator implements them on its
//! simulated machine. The motion logic itself (interp-core) never touches them: it
//! takes readings and time as arguments and returns what to do, and a thin driver
//! moves the values between these traits and the core.
#![no_std]
#![forbid(unsafe_code)]

/// Step and direction outputs of one axis.
pub trait StepDir {
    /// Sets the direction line (true = positive direction).
    fn set_direction(&mut self, positive: bool);
    /// Emits one step pulse; the pulse width is the implementation's (a one-pulse
    /// timer on the board).
    fn step(&mut self);
}

/// The spindle encoder: a quadrature counter with an index (once-per-revolution)
/// input that latches the count.
pub trait SpindleEncoder {
    /// Counts since power-on, quadrature-decoded (four per line), signed.
    fn count(&self) -> i64;
    /// The count latched at the most recent index pulse, if there was one.
    fn index_count(&self) -> Option<i64>;
}

/// Spindle rotation as the drive is told.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rotation {
    /// Stopped.
    Stop,
    /// Clockwise (M03).
    Cw,
    /// Counter-clockwise (M04).
    Ccw,
}

/// The spindle drive's speed and direction input (analog 0–10 V and two
/// direction outputs on a typical inverter).
pub trait SpindleDrive {
    /// Commands direction and speed, rev/min.
    fn set_speed(&mut self, rotation: Rotation, rpm: u32);
}

/// Digital outputs (coolant, chuck, tailstock, turret …).
pub trait DigitalOutputs {
    /// Switches output `n`.
    fn set_output(&mut self, n: u16, on: bool);
}

/// Digital inputs (limit switches, M91/M92 inputs, e-stop …).
pub trait DigitalInputs {
    /// Level of input `n` (false if there is no such input).
    fn input(&self, n: u16) -> bool;
}

/// A monotonic clock.
pub trait MonotonicClock {
    /// Nanoseconds since an arbitrary start; never goes back.
    fn now_ns(&self) -> u64;
}

/// The request side of an automatic tool changer's handshake (a machining
/// centre's M06): the board puts the tool number on binary-coded outputs and
/// raises a request (strobe) line, as a retrofit ATC controller or the machine's
/// PLC expects of a T function; the changer answers on its "done" line, a switch
/// input read like the others ([`DigitalInputs`]), and the board drops the
/// request when done has come (or the change is aborted).
pub trait ToolChangeRequest {
    /// Sets the tool-number outputs to `tool` (binary, as many bits as the board
    /// has), then raises the request line.
    fn request_tool(&mut self, tool: u16);
    /// Drops the request line and the tool-number outputs.
    fn clear_request(&mut self);
}

//! Motion settings: how each axis's motor is driven, and the motion core's
//! interpolation period, junction and tolerance settings.

/// An axis motor drive: the exact ratio between steps and travel, and the step
/// driver's timing requirements.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Drive {
    /// `steps` steps move the axis `per_nm` nanometres (X: of radius). Kept as an
    /// exact ratio so step positions never drift from nanometre positions.
    pub steps: i64,
    /// The travel of `steps` steps, nm.
    pub per_nm: i64,
    /// Shortest step pulse (high time) the driver sees, ns.
    pub pulse_ns: u32,
    /// Time the direction line must be stable before a step edge, ns.
    pub dir_setup_ns: u32,
    /// Highest step rate the driver accepts, steps per second.
    pub max_step_hz: u32,
}

impl Drive {
    /// `steps` steps per millimetre with the timing of a common microstepping driver
    /// (2.5 µs pulses, 5 µs direction set-up, 100 kHz).
    pub const fn per_mm(steps: i64) -> Self {
        Drive { steps, per_nm: 1_000_000, pulse_ns: 2_500, dir_setup_ns: 5_000, max_step_hz: 100_000 }
    }
}

/// Settings of the motion core (planner, interpolator, spindle synchronisation).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MotionConfig {
    /// Interpolation period, ns: the planner's speed profile and the axis targets
    /// are updated once per period; steps are timed exactly within it.
    pub tick_ns: u32,
    /// Junction deviation (nm): how far a virtual arc through a G64 corner may stray
    /// from the corner; sets the cornering speed with the axes' acceleration.
    pub junction_deviation: i64,
    /// Chord tolerance (nm): how far the straight step path between two
    /// interpolation points may stray from an arc or a blended corner.
    pub chord_tolerance: i64,
    /// Interpolation periods over which the spindle speed is measured from the encoder.
    pub speed_window_ticks: u16,
    /// The spindle is "at speed" within this percentage of its command.
    pub at_speed_pct: u8,
    /// Longest wait for the spindle to reach speed before alarm 4504, ms.
    pub at_speed_timeout_ms: u32,
    /// Headroom for spindle speed ripple in the thread speed check and the thread
    /// acceleration ramp, percent of the measured speed.
    pub thread_margin_pct: u8,
    /// A thread, rigid tap or G99 cut whose spindle encoder shows no count for this
    /// long (ms; at least four count intervals at the commanded speed) raises alarm
    /// 4503 and stops: the encoder signal is lost or the spindle stalled.
    pub encoder_timeout_ms: u32,
}

impl Default for MotionConfig {
    fn default() -> Self {
        MotionConfig {
            tick_ns: 1_000_000,
            junction_deviation: 10_000,
            chord_tolerance: 1_000,
            speed_window_ticks: 16,
            at_speed_pct: 10,
            at_speed_timeout_ms: 10_000,
            thread_margin_pct: 10,
            encoder_timeout_ms: 100,
        }
    }
}

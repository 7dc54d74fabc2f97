//! The spindle as the motion core sees it: the direction and speed it commands
//! (constant surface speed follows |X| along the cut) and the speed it measures
//! from the encoder count, once per interpolation period, over a sliding window.

use crate::canon::SpindleDir;
use crate::planner::MotionParams;

/// Longest measuring window, periods.
pub const MAX_WINDOW: usize = 64;

/// Commanded and measured spindle state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spindle {
    /// Commanded direction.
    pub dir: SpindleDir,
    /// Commanded speed, rev/min.
    pub rpm: u32,
    /// Encoder counts of the last `window + 1` periods (a ring of `len` entries).
    counts: [i64; MAX_WINDOW + 1],
    head: usize,
    len: usize,
    filled: usize,
    /// Counts over the window → revolutions per period, Q48.
    rev_q48: u64,
    /// Counts over the window → rev/min.
    rpm_per_count: f32,
    /// Last encoder count and the count latched at the last index pulse.
    pub count: i64,
    pub index: Option<i64>,
}

impl Spindle {
    /// Stopped, measuring over `window` periods.
    pub fn new(p: &MotionParams, window: u16) -> Self {
        let window = usize::from(window).clamp(1, MAX_WINDOW);
        let counts_per_window = u64::from(p.cpr) * window as u64;
        Spindle {
            dir: SpindleDir::Stop,
            rpm: 0,
            counts: [0; MAX_WINDOW + 1],
            head: 0,
            len: window + 1,
            filled: 0,
            rev_q48: (1u64 << 48) / counts_per_window,
            rpm_per_count: (60e9 / (counts_per_window as f64 * f64::from(p.tick_ns))) as f32,
            count: 0,
            index: None,
        }
    }

    /// Takes this period's encoder reading.
    pub fn sample(&mut self, count: i64, index: Option<i64>) {
        self.head = if self.head + 1 == self.len { 0 } else { self.head + 1 };
        self.counts[self.head] = count;
        self.filled = (self.filled + 1).min(self.len);
        self.count = count;
        self.index = index;
    }

    /// Counts over the window (signed; positive when counting up).
    fn delta(&self) -> i64 {
        if self.filled < self.len {
            return 0;
        }
        let oldest = if self.head + 1 == self.len { 0 } else { self.head + 1 };
        self.count - self.counts[oldest]
    }

    /// Measured speed in revolutions per period, Q32 (magnitude).
    pub fn rev_per_tick(&self) -> u64 {
        self.delta().unsigned_abs().saturating_mul(self.rev_q48) >> 16
    }

    /// Measured speed, rev/min; positive when the count goes up.
    pub fn measured_rpm(&self) -> f32 {
        self.delta() as f32 * self.rpm_per_count
    }

    /// Encoder counts per period at the measured speed (magnitude).
    pub fn counts_per_tick(&self) -> f32 {
        self.delta().unsigned_abs() as f32 / (self.len - 1) as f32
    }

    /// Commands direction and speed; true if either changed by more than `pct` %.
    pub fn command(&mut self, dir: SpindleDir, rpm: u32, pct: u8) -> bool {
        let rpm = if dir == SpindleDir::Stop { 0 } else { rpm };
        let big = dir != self.dir || rpm.abs_diff(self.rpm) as u64 * 100 > u64::from(pct) * u64::from(self.rpm);
        self.dir = dir;
        self.rpm = rpm;
        big
    }

    /// Whether the measured speed is within `pct` % of the command (stopped counts
    /// as there when commanded stopped).
    pub fn at_speed(&self, pct: u8) -> bool {
        self.at_speed_of(self.rpm, pct)
    }

    /// Whether the measured speed is within `pct` % of `rpm` in the commanded
    /// direction's sense (the drive's speed under a spindle override).
    pub fn at_speed_of(&self, rpm: u32, pct: u8) -> bool {
        let want = if self.dir == SpindleDir::Stop { 0.0 } else { rpm as f32 };
        (self.measured_rpm().abs() - want).abs() <= want * f32::from(pct) / 100.0 + 1.0
    }
}

//! The machine in the motion core's units: each axis's exact step scale, its speed
//! and acceleration limits per interpolation period, the driver timing, and the
//! spindle encoder. Derived once from [`MachineConfig`]; every motion layer reads it.

use super::bend;
use crate::alarm::AlarmKind;
use crate::axis::AXIS_COUNT;
use crate::canon::units::IncrementSystem;
use crate::config::{ConfigError, Drive, MachineConfig, Param};
use crate::fixed::{Divisor, STEP_FRAC, gcd, mul_shr};
use crate::stepgen::DriverTiming;

/// Exact conversion between nanometres (µdeg for C) and motor steps of one axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AxisScale {
    /// Steps per `per_nm` nanometres, reduced.
    steps: i64,
    per_nm: i64,
    /// `per_nm / 2` (rounds a position to the nearest step).
    half: i64,
    /// Steps per nanometre in Q48 (for interpolated points).
    spn_q48: i64,
    /// Nanometres per step in Q32.
    nm_q32: i64,
    /// `per_nm` prepared for division by multiplication.
    div: Divisor,
    /// Nanometres per step (display and measurement only).
    nm_per_step: f64,
}

impl AxisScale {
    /// The scale of `drive`; alarm 4508 for a zero or negative ratio.
    pub fn new(drive: &Drive) -> Result<Self, AlarmKind> {
        if drive.steps <= 0 || drive.per_nm <= 0 {
            return Err(AlarmKind::MotionConfigInvalid { what: "steps and travel per step ratio must be positive" });
        }
        let g = gcd(drive.steps, drive.per_nm);
        let (steps, per_nm) = (drive.steps / g, drive.per_nm / g);
        let spn = ((i128::from(steps) << 49) / i128::from(per_nm) + 1) / 2;
        let spn_q48 =
            i64::try_from(spn).map_err(|_| AlarmKind::MotionConfigInvalid { what: "more than 2^15 steps per nm" })?;
        let nm_q32 = i64::try_from((i128::from(per_nm) << 32) / i128::from(steps))
            .map_err(|_| AlarmKind::MotionConfigInvalid { what: "more than 2^31 nm per step" })?;
        Ok(AxisScale {
            steps,
            per_nm,
            half: per_nm / 2,
            spn_q48,
            nm_q32,
            div: Divisor::new(per_nm as u64),
            nm_per_step: per_nm as f64 / steps as f64,
        })
    }

    /// The whole step nearest to position `nm` (halves away from −∞): exact, no drift.
    pub fn steps(&self, nm: i64) -> i64 {
        // Within ±2^31 nm (±2.1 m) and below 2^31 steps per `per_nm` the product and
        // the half (below 2^62 each) cannot overflow: no saturating 128-bit checks.
        if let Ok(n) = i32::try_from(nm)
            && self.steps < 1 << 31
        {
            return self.div.div_floor(i64::from(n) * self.steps + self.half);
        }
        self.div.div_floor(nm.saturating_mul(self.steps).saturating_add(self.half))
    }

    /// The nanometre nearest to whole step `s`.
    pub fn nm(&self, s: i64) -> i64 {
        (s.saturating_mul(self.per_nm) + self.steps / 2).div_euclid(self.steps)
    }

    /// Position `nm` in Q16 steps, rounded (interpolated points).
    pub fn q16(&self, nm: i64) -> i64 {
        mul_shr(nm, self.spn_q48, 16).saturating_add(1 << 15) >> 16
    }

    /// `steps` as a length in Q8 nm (to 2^-24 nm per step), by one multiply.
    pub fn q8_nm(&self, steps: u64) -> u64 {
        ((u128::from(steps) * self.nm_q32 as u128) >> 24) as u64
    }

    /// A Q16 step position as nanometres, by one multiply.
    pub fn nm_of_q16(&self, q16: i64) -> i64 {
        mul_shr(q16, self.nm_q32, 48)
    }

    /// Nanometres per step.
    pub fn nm_per_step(&self) -> f64 {
        self.nm_per_step
    }

    /// Steps per nanometre.
    pub fn steps_per_nm(&self) -> f64 {
        self.steps as f64 / self.per_nm as f64
    }

    /// The reduced ratio `(steps, per_nm)`.
    pub fn ratio(&self) -> (i64, i64) {
        (self.steps, self.per_nm)
    }
}

/// Speed and acceleration limits of one axis per interpolation period.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AxisLimits {
    /// Whether the machine has the axis.
    pub present: bool,
    /// Highest cutting speed, nm per period (the axis's feed limit or its step rate).
    pub feed: f32,
    /// Rapid speed, nm per period (the rapid rate or the step rate).
    pub rapid: f32,
    /// Acceleration, nm per period².
    pub accel: f32,
    /// Largest speed jump at a blended junction, nm per period.
    pub jump: f32,
}

/// Everything the motion layers need to know about the machine, in their units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MotionParams {
    /// Interpolation period, ns.
    pub tick_ns: u32,
    /// Step scale of each axis.
    pub scale: [AxisScale; AXIS_COUNT],
    /// Limits of each axis.
    pub limits: [AxisLimits; AXIS_COUNT],
    /// Driver timing of each axis.
    pub timing: [DriverTiming; AXIS_COUNT],
    /// Highest cutting feed along the path (parameter 6023), nm per period.
    pub path_feed: f32,
    /// Junction deviation, nm.
    pub junction_deviation: f32,
    /// Chord tolerance, nm.
    pub chord_tolerance: f32,
    /// The machine's own junction deviation and chord tolerance, nm: what
    /// [`MotionParams::set_tolerance`] puts back.
    own_tolerance: [f32; 2],
    /// Smallest acceleration of the present axes, nm per period².
    pub accel_min: f32,
    /// Spindle encoder counts per revolution.
    pub cpr: u32,
    /// Spindle acceleration, rev/min per second.
    pub spindle_accel_rpm_s: u32,
    /// Speed ripple margin of the thread checks (1.10 for 10 %).
    pub thread_margin: f32,
    /// How far the path of a blended chain must be known beyond a junction before
    /// the curvature there is settled, nm (see [`bend`](super::bend)).
    pub settle_len: f32,
    /// Half the input increment (metric), nm: how far programmed points stray
    /// from the curve they sample.
    pub input_noise: f32,
    /// nm/min → nm per period.
    per_min: f32,
    /// nm/min → Q8 nm per period, in Q32.
    rate_q32: i64,
}

impl MotionParams {
    /// The motion view of `cfg`; alarm 4508 if it is unusable.
    pub fn new(cfg: &MachineConfig) -> Result<Self, AlarmKind> {
        let m = &cfg.motion;
        if m.tick_ns < 10_000 || m.tick_ns > 100_000_000 {
            return Err(AlarmKind::MotionConfigInvalid { what: "interpolation period outside 10 us .. 100 ms" });
        }
        if cfg.spindle.encoder_cpr == 0 {
            return Err(AlarmKind::MotionConfigInvalid { what: "spindle encoder counts per revolution is zero" });
        }
        let per_min = f64::from(m.tick_ns) / 60e9;
        let per_s = f64::from(m.tick_ns) / 1e9;
        let mut scale = [AxisScale::new(&Drive::per_mm(1))?; AXIS_COUNT];
        let mut timing = [DriverTiming::from_drive(&Drive::per_mm(1))?; AXIS_COUNT];
        let mut limits = [AxisLimits { present: false, feed: 0.0, rapid: 0.0, accel: 0.0, jump: 0.0 }; AXIS_COUNT];
        let mut accel_min = f32::MAX;
        for (i, ax) in cfg.axes.iter().enumerate() {
            if !ax.present {
                continue;
            }
            scale[i] = AxisScale::new(&ax.drive)?;
            timing[i] = DriverTiming::from_drive(&ax.drive)?;
            if ax.accel_per_s2 <= 0 || ax.rapid_per_min <= 0 || ax.max_feed_per_min <= 0 {
                return Err(AlarmKind::MotionConfigInvalid { what: "axis rate or acceleration not positive" });
            }
            // 95 % of the step rate, so rounding never makes a step wait.
            let step_rate = 0.95e9 / f64::from(timing[i].min_period_ns) * scale[i].nm_per_step() * per_s;
            let accel = (ax.accel_per_s2 as f64 * per_s * per_s) as f32;
            limits[i] = AxisLimits {
                present: true,
                feed: (ax.max_feed_per_min as f64 * per_min).min(step_rate) as f32,
                rapid: (ax.rapid_per_min as f64 * per_min).min(step_rate) as f32,
                accel,
                jump: (ax.max_jump_per_min.max(0) as f64 * per_min) as f32,
            };
            accel_min = accel_min.min(accel);
        }
        let path_feed = cfg.params.get(Param::MaxCuttingFeed);
        let path_feed = if path_feed > 0 { (path_feed as f64 * per_min) as f32 } else { f32::MAX };
        let input_noise = match cfg.increments {
            IncrementSystem::IsB => 500.0,
            IncrementSystem::IsC => 50.0,
        };
        let fastest = limits.iter().filter(|l| l.present).map(|l| l.feed).fold(0.0f32, f32::max);
        let settle_len = bend::settle_len(path_feed.min(fastest * core::f32::consts::SQRT_2), accel_min, input_noise);
        let own_tolerance = [m.junction_deviation.max(0) as f32, m.chord_tolerance.max(1) as f32];
        Ok(MotionParams {
            tick_ns: m.tick_ns,
            scale,
            limits,
            timing,
            path_feed,
            junction_deviation: own_tolerance[0],
            chord_tolerance: own_tolerance[1],
            own_tolerance,
            accel_min,
            cpr: cfg.spindle.encoder_cpr,
            spindle_accel_rpm_s: cfg.spindle.accel_rpm_per_s.max(1),
            thread_margin: 1.0 + f32::from(m.thread_margin_pct) / 100.0,
            settle_len,
            input_noise,
            per_min: per_min as f32,
            rate_q32: libm::round(per_min * 256.0 * 4_294_967_296.0) as i64,
        })
    }

    /// Plans from now on with the path tolerance `nm` (SINUMERIK CYCLE832,
    /// `canon::Action::Tolerance`) as junction deviation and chord tolerance;
    /// 0 puts the machine's own back.
    #[inline(never)]
    pub fn set_tolerance(&mut self, nm: u32) {
        let t = nm as f32;
        [self.junction_deviation, self.chord_tolerance] = if nm == 0 { self.own_tolerance } else { [t, t] };
    }

    /// A speed in nm/min as nm per interpolation period.
    pub fn per_tick(&self, nm_per_min: f32) -> f32 {
        nm_per_min * self.per_min
    }

    /// A feed in nm/min as Q8 nm per interpolation period (exact to 2^-32).
    pub fn rate_q8(&self, nm_per_min: i64) -> i64 {
        mul_shr(nm_per_min, self.rate_q32, 32)
    }

    /// Interpolation periods per second.
    pub fn ticks_per_s(&self) -> f64 {
        1e9 / f64::from(self.tick_ns)
    }

    /// The Q16 position of whole step `s`.
    pub const fn q16_of_steps(s: i64) -> i64 {
        s << STEP_FRAC
    }
}

/// Checks the motion settings of `cfg` (after [`MachineConfig::validate`]): what
/// [`MotionParams::new`] refuses, as the machine file's error.
pub fn check_config(cfg: &MachineConfig) -> Result<(), ConfigError> {
    match MotionParams::new(cfg) {
        Err(AlarmKind::MotionConfigInvalid { what }) => Err(ConfigError::Motion { what }),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn step_scale_is_exact_and_rounds_to_nearest() {
        let s = AxisScale::new(&Drive::per_mm(320)).unwrap();
        assert_eq!(s.ratio(), (1, 3_125));
        assert_eq!(s.steps(1_000_000), 320);
        assert_eq!(s.steps(1_562), 0);
        assert_eq!(s.steps(1_563), 1);
        assert_eq!(s.steps(-1_563), -1);
        assert_eq!(s.nm(320), 1_000_000);
        assert_eq!(s.q16(3_125), 1 << 16);
        assert_eq!(s.q16(-6_250), -(2 << 16));
        // A million blocks of 1.000001 mm end where the nanometres say: no drift.
        assert_eq!(s.steps(1_000_001 * 1_000_000), 320_000_320);
        assert!(AxisScale::new(&Drive { steps: 0, ..Drive::per_mm(1) }).is_err());
    }

    /// The short path of `steps` (positions within ±2^31 nm) against the exact
    /// `⌊(nm·steps + ⌊per_nm/2⌋) / per_nm⌋` in 128 bits, for ratios of every size.
    #[test]
    fn steps_equal_the_exact_rounding() {
        let mut rng = canon::xorshift::XorShift::new(0x5851_f42d_4c95_7f2d);
        let ratios = [
            (320, 1_000_000),
            (1, 1),
            (3, 7),
            (200, 5_000_000),
            (1_073_741_823, 131_073),
            (7_000, 1 << 40),
            (4_294_967_311, 1 << 20),
        ];
        for (k, (steps, per)) in ratios.into_iter().enumerate() {
            let s = AxisScale::new(&Drive { steps, per_nm: per, ..Drive::per_mm(1) }).unwrap();
            let (st, pn) = s.ratio();
            for i in 0..20_000 {
                let m = [1_000i64, 1 << 20, i32::MAX as i64, 1 << 33, 1 << 50][i % 5];
                let nm = match i % 97 {
                    0 => i32::MAX as i64,
                    1 => i32::MIN as i64,
                    2 => i32::MIN as i64 - 1,
                    _ => rng.signed(m),
                };
                let exact = (i128::from(nm) * i128::from(st) + i128::from(pn / 2)).div_euclid(i128::from(pn));
                let exact = exact.clamp(i128::from(i64::MIN), i128::from(i64::MAX)) as i64;
                if nm.checked_mul(st).and_then(|v| v.checked_add(pn / 2)).is_some() {
                    assert_eq!(s.steps(nm), exact, "ratio {k}: {nm}");
                }
            }
        }
    }

    #[test]
    fn limits_come_from_the_configuration_per_period() {
        let p = MotionParams::new(&MachineConfig::default()).unwrap();
        // Z: 8000 mm/min rapid = 133.3 µm per ms; 500 mm/s² = 500 nm per ms².
        assert!((p.limits[2].rapid - 133_333.33).abs() < 1.0);
        assert!((p.limits[2].accel - 500.0).abs() < 1e-3);
        assert!((p.limits[0].feed - 83_333.33).abs() < 1.0);
        assert!(!p.limits[1].present);
        assert_eq!(p.cpr, 4_096);
    }

    #[test]
    fn check_config_names_what_the_motion_core_refuses() {
        assert_eq!(check_config(&MachineConfig::default()), Ok(()));
        let mut c = MachineConfig::default();
        c.spindle.encoder_cpr = 0;
        assert_eq!(
            check_config(&c),
            Err(ConfigError::Motion { what: "spindle encoder counts per revolution is zero" })
        );
    }
}

//! The simulated spindle: a drive that slews to its commanded speed, a speed with
//! ripple and noise (seeded, deterministic), and a quadrature encoder with an index
//! that reports every count edge with its exact time.

use hal::{Rotation, SpindleDrive, SpindleEncoder};

/// How the simulated spindle behaves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpindleModel {
    /// Drive acceleration, rev/min per second.
    pub accel_rpm_s: f64,
    /// Speed ripple amplitude as a fraction of the speed (0.05 = ±5 %).
    pub ripple: f64,
    /// Ripple frequency, Hz.
    pub ripple_hz: f64,
    /// Speed noise, fraction of the speed (standard deviation, low-pass filtered).
    pub noise: f64,
    /// Seed of the noise.
    pub seed: u64,
    /// Encoder counts per revolution (quadrature-decoded).
    pub cpr: u32,
    /// Angle of the index mark, revolutions.
    pub index_at: f64,
    /// Whether the encoder has an index output at all.
    pub index: bool,
    /// M03 makes the encoder count up (false: down).
    pub cw_counts_up: bool,
}

impl Default for SpindleModel {
    fn default() -> Self {
        SpindleModel {
            accel_rpm_s: 2_500.0,
            ripple: 0.0,
            ripple_hz: 2.0,
            noise: 0.0,
            seed: 1,
            cpr: 4_096,
            index_at: 0.3,
            index: true,
            cw_counts_up: true,
        }
    }
}

/// splitmix64: a small deterministic generator for the noise.
#[derive(Clone, Copy, Debug)]
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [-1, 1).
    fn uniform(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// The spindle and its encoder.
#[derive(Clone, Debug)]
pub struct SimSpindle {
    model: SpindleModel,
    rng: Rng,
    /// Commanded speed, rev/min, signed (+ = the encoder's up direction).
    command: f64,
    /// Drive speed before ripple and noise, signed.
    base: f64,
    noise: f64,
    /// Angle, revolutions, signed cumulative.
    angle: f64,
    /// Decoded count and the quadrature phase it came from.
    count: i64,
    index: Option<i64>,
    t: f64,
}

/// One encoder count edge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Edge {
    /// Time, ns.
    pub t: u64,
    /// Count after the edge.
    pub count: i64,
}

/// Quadrature state (A, B) of phase 0..4.
fn quadrature(phase: i64) -> (bool, bool) {
    match phase.rem_euclid(4) {
        0 => (false, false),
        1 => (true, false),
        2 => (true, true),
        _ => (false, true),
    }
}

/// The decoder's step for a transition between two quadrature states.
fn decode(from: (bool, bool), to: (bool, bool)) -> i64 {
    let order = |s: (bool, bool)| -> i64 {
        match s {
            (false, false) => 0,
            (true, false) => 1,
            (true, true) => 2,
            (false, true) => 3,
        }
    };
    match (order(to) - order(from)).rem_euclid(4) {
        1 => 1,
        3 => -1,
        _ => 0,
    }
}

impl SimSpindle {
    /// A stopped spindle at angle 0.
    pub fn new(model: SpindleModel) -> Self {
        SimSpindle {
            model,
            rng: Rng(model.seed),
            command: 0.0,
            base: 0.0,
            noise: 0.0,
            angle: 0.0,
            count: 0,
            index: None,
            t: 0.0,
        }
    }

    /// The model.
    pub fn model(&self) -> &SpindleModel {
        &self.model
    }

    /// Actual speed now, rev/min (signed).
    pub fn rpm(&self) -> f64 {
        self.base
            * (1.0 + self.model.ripple * (core::f64::consts::TAU * self.model.ripple_hz * self.t).sin() + self.noise)
    }

    /// Cumulative angle the encoder reports, degrees.
    pub fn encoder_degrees(&self) -> f64 {
        self.count as f64 * 360.0 / f64::from(self.model.cpr)
    }

    /// Runs the spindle from its time to `until` (s) in steps of `dt`, returning every
    /// encoder edge in order.
    pub fn advance(&mut self, until: f64, dt: f64, edges: &mut Vec<Edge>) {
        while self.t < until - 1e-12 {
            let h = dt.min(until - self.t);
            self.slew(h);
            let w = self.rpm() / 60.0; // rev/s over this step
            let next = self.angle + w * h;
            self.edges_between(self.angle, next, w, edges);
            self.angle = next;
            self.t += h;
        }
    }

    fn slew(&mut self, h: f64) {
        let step = self.model.accel_rpm_s * h;
        self.base += (self.command - self.base).clamp(-step, step);
        // Low-pass filtered noise (10 ms).
        let a = (h / 0.01).min(1.0);
        self.noise += a * (self.model.noise * 1.732 * self.rng.uniform() - self.noise);
    }

    /// Encoder edges for the angle moving from `a` to `b` at `w` rev/s.
    fn edges_between(&mut self, a: f64, b: f64, w: f64, edges: &mut Vec<Edge>) {
        let cpr = f64::from(self.model.cpr);
        let (pa, pb) = ((a * cpr).floor() as i64, (b * cpr).floor() as i64);
        if pa == pb || w == 0.0 {
            return;
        }
        let dir = if pb > pa { 1 } else { -1 };
        let mut phase = pa;
        while phase != pb {
            let next = phase + dir;
            // The boundary crossed: the lower edge of `next` going up, of `phase` going down.
            let boundary = if dir > 0 { next } else { phase } as f64 / cpr;
            let t = self.t + (boundary - a) / w;
            self.count += decode(quadrature(phase), quadrature(next));
            self.index_check(phase, next);
            edges.push(Edge { t: (t * 1e9).round() as u64, count: self.count });
            phase = next;
        }
    }

    /// Latches the count when the angle passes the index mark (either direction).
    fn index_check(&mut self, from: i64, to: i64) {
        let cpr = i64::from(self.model.cpr);
        let mark = (self.model.index_at * cpr as f64).round() as i64;
        let at = |p: i64| (p - mark).rem_euclid(cpr) == 0;
        if self.model.index && ((to > from && at(to)) || (to < from && at(from))) {
            self.index = Some(self.count);
        }
    }
}

impl SpindleDrive for SimSpindle {
    fn set_speed(&mut self, rotation: Rotation, rpm: u32) {
        let sign = if self.model.cw_counts_up { 1.0 } else { -1.0 };
        self.command = match rotation {
            Rotation::Stop => 0.0,
            Rotation::Cw => sign * f64::from(rpm),
            Rotation::Ccw => -sign * f64::from(rpm),
        };
    }
}

impl SpindleEncoder for SimSpindle {
    fn count(&self) -> i64 {
        self.count
    }

    fn index_count(&self) -> Option<i64> {
        self.index
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encoder_counts_revolutions_with_timed_edges_and_index() {
        let mut s = SimSpindle::new(SpindleModel { accel_rpm_s: 1e9, ..SpindleModel::default() });
        s.set_speed(Rotation::Cw, 600); // 10 rev/s
        let mut edges = Vec::new();
        s.advance(0.100_01, 1e-4, &mut edges);
        assert_eq!(s.count(), 4_096);
        assert_eq!(edges.len(), 4_096);
        // Edge k at k / 40960 s.
        assert!(edges[99].t.abs_diff(100 * 1_000_000_000 / 40_960) <= 2);
        let idx = s.index_count().unwrap();
        assert_eq!(idx, (0.3f64 * 4_096.0).round() as i64);
        s.set_speed(Rotation::Ccw, 600);
        s.advance(0.25, 1e-4, &mut edges);
        assert_eq!(s.count(), 4_096 - 6_144);
    }

    #[test]
    fn ripple_and_noise_are_bounded_and_repeatable() {
        let model = SpindleModel { ripple: 0.05, noise: 0.005, seed: 7, ..SpindleModel::default() };
        let run = || {
            let mut s = SimSpindle::new(model);
            s.set_speed(Rotation::Cw, 1_000);
            let mut edges = Vec::new();
            let mut rpms = Vec::new();
            for k in 1..2_000 {
                s.advance(k as f64 * 1e-3, 1e-4, &mut edges);
                rpms.push(s.rpm());
            }
            (edges.len(), rpms)
        };
        let (n1, r1) = run();
        let (n2, r2) = run();
        assert_eq!((n1, &r1), (n2, &r2));
        let late = &r1[800..];
        let max = late.iter().cloned().fold(0.0, f64::max);
        let min = late.iter().cloned().fold(f64::MAX, f64::min);
        assert!(max > 1_040.0 && max < 1_070.0 && min < 960.0 && min > 930.0, "{min}..{max}");
    }
}

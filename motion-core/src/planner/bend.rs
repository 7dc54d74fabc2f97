//! The curvature of a chain of short blocks, as a speed limit at its junctions.
//!
//! CAM output samples a curve with thousands of 0.01–0.05 mm blocks. At full feed
//! an interpolation period then spans several junctions: the axes follow the
//! curve's curvature `κ` with a normal acceleration `v²·κ`, and the period's chord
//! strays `v²·κ/8` from the curve. No junction rule sees this: each junction's
//! angle is tiny, and it cannot tell `κ` either, because the programmed points are
//! rounded to the input increment (±0.5 µm in IS-B): such a rounding turns a
//! 0.02 mm block by 0.025 rad, the angle a 0.8 mm radius would give it.
//!
//! So the curvature is measured on the path itself, at sample points of the chain
//! (junctions at least `settle_len / 2` apart): the circle through the sample, a
//! point at least `settle_len` before it (or the chain's start) and the chain's end
//! as it stands, `s_b` and `s_f` of path away. A rounding of `δ` changes that
//! estimate by at most `ν = 4·δ / (s_b·s_f)`, so `κ + ν` bounds the curvature from
//! above, and a junction after the sample may be passed at
//! `v² ≤ min(8·tol, a_n) / (κ + ν)` (chord tolerance and normal acceleration
//! `a_n`, half the smallest axis acceleration, as on an arc). The bound is safe at
//! once, while the chain's end is just past the junction, and rises as the path
//! beyond arrives; a junction's limit only ever rises. With both spans at least
//! `settle_len = 4·v_max·√(δ / a_n)` (`v_max` the fastest cutting feed) `ν` is at
//! most `a_n / (4·v_max²)`: rounding alone (which also moves the measured `κ` by up
//! to `ν`) never asks for less than `√2·v_max`, and a curve that allows `v_max`
//! gets at least 0.8 `v_max`. Near the end of the queue the limit is lower, but
//! never below the speed there: braking to rest at the queue's end at `a` leaves
//! `v² ≈ 2a·s_f` at `s_f` from it, and the bound allows `v² ≥ a_n·s_b·s_f / 4δ`,
//! more for any `s_b` above `16·δ`.
//!
//! Only *dense* junctions take part: where a block next to the junction is shorter
//! than twice the junction's own limit per period, so that a period may span two
//! junctions. Elsewhere a period crosses one junction at a time and the corner
//! rules of [`lookahead`](super::lookahead) are exact; such a junction starts the
//! chain anew, and the junctions within the chain's first `settle_len / 2` each
//! get their own bound, from the chain's start, the junction and the block's end.

use crate::axis::{AXIS_COUNT, Pos};
use crate::fixed::{f32_of, minf, sqrtf};

/// Sample points kept: the span behind the newest and the ones still rising.
const SAMPLES: usize = 8;

/// `settle_len` for the fastest cutting feed `v_max` (nm/period), the smallest
/// axis acceleration `accel_min` (nm/period²) and the input rounding `noise` (nm),
/// within 20 µm … 4 mm.
pub fn settle_len(v_max: f32, accel_min: f32, noise: f32) -> f32 {
    let a_n = accel_min * 0.5;
    let len = if a_n > 0.0 { 4.0 * v_max * sqrtf(noise / a_n) } else { f32::MAX };
    len.clamp(20_000.0, 4_000_000.0)
}

/// What the curvature limit depends on, from [`MotionParams`](super::MotionParams).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits {
    /// `settle_len`, nm.
    pub settle_len: f32,
    /// Input rounding `δ`, nm.
    pub noise: f32,
    /// Chord tolerance, nm.
    pub tol: f32,
    /// Normal acceleration, nm/period².
    pub a_n: f32,
}

impl Limits {
    /// The speed (nm/period) a curvature `kappa` (1/nm) allows.
    pub fn speed(&self, kappa: f32) -> f32 {
        if kappa <= 0.0 { f32::MAX } else { sqrtf(minf(8.0 * self.tol, self.a_n) / kappa) }
    }

    /// The speed the circle through `a`, `b`, `c` allows, `s_b` and `s_f` of path
    /// between them, with the rounding's bound added to its curvature.
    fn bound(&self, a: &Pos, b: &Pos, c: &Pos, s_b: f32, s_f: f32) -> f32 {
        if s_b <= 0.0 || s_f <= 0.0 {
            return 0.0;
        }
        self.speed(curvature(a, b, c) + 4.0 * self.noise / (s_b * s_f))
    }
}

/// A sample point of the chain (a junction).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Sample {
    at: Pos,
    /// Path length from the chain's start, nm.
    s: f32,
    /// The speed its junctions may pass at (nm/period), rising.
    speed: f32,
    /// Junctions from this sample up to the next one.
    count: u16,
    /// Whether `speed` may still rise (the path beyond is shorter than `settle_len`).
    open: bool,
}

/// The chain of dense junctions at the queue's end.
#[derive(Clone, Debug)]
pub struct Bend {
    samples: heapless::Deque<Sample, SAMPLES>,
    /// The chain's start (taken at its first dense junction: `fresh` until
    /// then), its end (the last block's end) and its path length, nm.
    start: Pos,
    fresh: bool,
    end: Pos,
    s_end: f32,
}

impl Default for Bend {
    fn default() -> Self {
        Bend { samples: heapless::Deque::new(), start: Pos::ZERO, fresh: true, end: Pos::ZERO, s_end: 0.0 }
    }
}

/// The curvature (1/nm) of the circle through `a`, `b`, `c`: `2·|ab × bc| / (|ab|·|bc|·|ac|)`.
pub fn curvature(a: &Pos, b: &Pos, c: &Pos) -> f32 {
    let d = |p: &Pos, q: &Pos| -> [f32; AXIS_COUNT] { core::array::from_fn(|i| f32_of(q.0[i].wrapping_sub(p.0[i]))) };
    let (u, w) = (d(a, b), d(b, c));
    let x: [f32; AXIS_COUNT] = core::array::from_fn(|i| u[i] + w[i]);
    let norm2 = |v: &[f32; AXIS_COUNT]| v.iter().map(|c| c * c).sum::<f32>();
    // |u × w|² as the sum of the squared 2×2 minors (exact in any dimension).
    let mut cross2 = 0.0;
    for i in 0..AXIS_COUNT {
        for j in i + 1..AXIS_COUNT {
            let m = u[i] * w[j] - u[j] * w[i];
            cross2 += m * m;
        }
    }
    let den2 = norm2(&u) * norm2(&w) * norm2(&x);
    if den2 <= 0.0 { 0.0 } else { 2.0 * sqrtf(cross2 / den2) }
}

impl Bend {
    /// Forgets the chain.
    pub fn clear(&mut self) {
        self.samples.clear();
        (self.fresh, self.s_end) = (true, 0.0);
    }

    /// A block `len` nm long whose junction with the block before is not dense
    /// (or that starts from rest): it starts a new chain.
    #[inline]
    pub fn restart(&mut self, len: f32) {
        if !self.fresh {
            self.samples.clear();
            self.fresh = true;
        }
        self.s_end = len;
    }

    /// A block from `start` to `end`, `len` nm long, whose junction with the
    /// block before (which started at `before`) is a dense junction of the chain.
    /// Returns the speed its junction may pass at now, and calls
    /// `raise(from_end, count, speed)` for every earlier stretch of junctions
    /// whose speed rose: the `count` junctions (blocks) starting `from_end`
    /// entries before the queue's end (the new block is its last entry).
    pub fn push(
        &mut self,
        before: &Pos,
        start: &Pos,
        end: &Pos,
        len: f32,
        lim: &Limits,
        mut raise: impl FnMut(usize, usize, f32),
    ) -> f32 {
        if self.fresh {
            // The chain's first block is the one before this junction.
            (self.start, self.fresh) = (*before, false);
        }
        let s_j = self.s_end;
        let spacing = lim.settle_len * 0.5;
        let new_sample = match self.samples.back() {
            None => s_j >= spacing,
            Some(b) => s_j - b.s >= spacing,
        };
        if new_sample {
            if self.samples.is_full() {
                self.samples.pop_front();
            }
            let _ = self.samples.push_back(Sample { at: *start, s: s_j, speed: 0.0, count: 0, open: true });
        }
        self.end = *end;
        self.s_end += len;
        let n = self.samples.len();
        let Some(newest) = self.samples.back_mut() else {
            // Within the chain's first stretch: a bound of its own.
            return lim.bound(&self.start, start, end, s_j, len);
        };
        newest.count += 1;
        // The open samples' bounds, with the path known to the new end: the newest
        // at every block, the older ones when a sample is added.
        let mut from_end = 0;
        for k in (0..n).rev() {
            let Some(s) = self.samples.get(k).copied() else { break };
            from_end += usize::from(s.count);
            if !s.open || (k + 1 < n && !new_sample) {
                continue;
            }
            let s_f = self.s_end - s.s;
            // The newest sample at least `settle_len` before, or the chain's start.
            let mut back = (self.start, s.s);
            for i in (0..k).rev() {
                if let Some(b) = self.samples.get(i).filter(|b| s.s - b.s >= lim.settle_len) {
                    back = (b.at, s.s - b.s);
                    break;
                }
            }
            let v = lim.bound(&back.0, &s.at, &self.end, back.1, s_f);
            let Some(m) = self.samples.get_mut(k) else { break };
            m.open = s_f < lim.settle_len;
            if v > m.speed {
                m.speed = v;
                // The new junction takes it from the return value.
                let count = usize::from(s.count) - usize::from(k + 1 == n);
                if count > 0 {
                    raise(from_end, count, v);
                }
            }
        }
        self.samples.back().map_or(0.0, |s| s.speed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f64, z: f64) -> Pos {
        Pos::xz(x as i64, z as i64)
    }

    fn limits(settle_len: f32) -> Limits {
        Limits { settle_len, noise: 500.0, tol: 1_000.0, a_n: 250.0 }
    }

    #[test]
    fn the_circle_through_three_points() {
        let r = 40_000_000.0;
        let at = |t: f64| p(r * t.cos(), r * t.sin());
        let k = curvature(&at(0.0), &at(0.01), &at(0.02));
        assert!((k * r as f32 - 1.0).abs() < 1e-3, "{k}");
        assert_eq!(curvature(&p(0.0, 0.0), &p(0.0, 1e6), &p(0.0, 2e6)), 0.0);
        assert_eq!(curvature(&p(0.0, 0.0), &p(0.0, 0.0), &p(0.0, 2e6)), 0.0);
    }

    /// Runs a chain of points; returns every junction's speed as the queue would
    /// hold it at the end (its last value: given at push, raised later).
    fn run(points: &[Pos], lim: &Limits) -> std::vec::Vec<f32> {
        let mut bend = Bend::default();
        let mut speeds: std::vec::Vec<f32> = std::vec::Vec::new();
        for (k, w) in points.windows(2).enumerate() {
            let len = curvature_len(&w[0], &w[1]);
            // The queue holds every block so far; the new one is its last entry.
            speeds.push(0.0);
            if k == 0 {
                bend.restart(len);
                continue;
            }
            let v = bend.push(&points[k - 1], &w[0], &w[1], len, lim, |from_end, count, v| {
                let first = speeds.len() - from_end;
                for s in &mut speeds[first..first + count] {
                    assert!(v >= *s, "a junction's speed fell");
                    *s = v;
                }
            });
            *speeds.last_mut().unwrap() = v;
        }
        speeds
    }

    fn curvature_len(a: &Pos, b: &Pos) -> f32 {
        let d = (0..AXIS_COUNT).map(|i| ((b.0[i] - a.0[i]) as f64).powi(2)).sum::<f64>();
        d.sqrt() as f32
    }

    /// A chain of 0.02 mm blocks along a 50 mm radius: once the path beyond is
    /// known, every junction's speed is the radius's (within the rounding bound
    /// of whole nanometres), and no junction's speed ever falls.
    #[test]
    fn a_radius_gets_its_speed_once_the_path_beyond_is_known() {
        let r = 50_000_000.0f64;
        let lim = limits(settle_len(83_333.0, 500.0, 500.0));
        let points: std::vec::Vec<Pos> =
            (0..600).map(|k| p(r * (k as f64 * 20_000.0 / r).cos(), r * (k as f64 * 20_000.0 / r).sin())).collect();
        let speeds = run(&points, &lim);
        let want = lim.speed(1.0 / r as f32);
        // Past the chain's first `settle_len` and before its last one: the radius
        // allows 106 µm per period, more than the fastest feed; the bound gives
        // at least 0.8 of it.
        for (k, v) in speeds.iter().enumerate().skip(24).take(540) {
            assert!(*v <= want * 1.001 && *v >= want * 0.8, "junction {k}: {v} vs {want}");
        }
        // At the chain's end the bound is low but never zero.
        assert!(speeds[598] > 0.0 && speeds[598] < want);
    }

    /// A straight chain rounded to whole micrometres (IS-B): rounding alone never
    /// asks for less than the fastest feed once the path beyond is known.
    #[test]
    fn rounding_noise_never_asks_for_less_than_the_fastest_feed() {
        let settle_len = settle_len(83_333.0, 500.0, 500.0);
        assert!((settle_len - 471_404.0).abs() < 20.0, "{settle_len}");
        let lim = limits(settle_len);
        let points: std::vec::Vec<Pos> = (0..800)
            .map(|k| {
                let z = -(k as f64) * 20_000.0;
                // A 3° line, rounded to 1 µm.
                p((40e6 + 0.0524 * z / 1000.0).round() * 1000.0, z)
            })
            .collect();
        let speeds = run(&points, &lim);
        for (k, v) in speeds.iter().enumerate().skip(24).take(740) {
            assert!(*v >= 83_333.0 * 1.41, "junction {k}: {v}");
        }
    }
}

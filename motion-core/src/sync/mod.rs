//! Spindle synchronisation: the electronic gearbox of thread passes and rigid
//! tapping. While a pass runs, every axis position is an exact integer function of
//! the spindle encoder count — no speed estimate, no control loop — updated at
//! every encoder count, so the axes lag the spindle by nothing but the interrupt.
//!
//! **The gearing.** After `c` counts from the synchronised start (index + Q) the
//! long axis is at `(n1·c + n2·c²) / den` steps ([`Gearing`]). A constant lead (G32,
//! G92, G76) has `n2 = 0` and `n1/den = N/D` = `lead × steps / (travel per steps ×
//! counts per rev)`, reduced. A variable lead (G34, 2.17.2) is `z(θ) = F·θ + K·θ²/2`
//! after θ revolutions: the lead `dz/dθ = F + K·θ` is F at the start and grows by K
//! per revolution, so each revolution is K longer than the one before (the manual's
//! `K = F2 − F1`). With `θ = c/CPR` and `s` steps per `p` nm this is
//! `n1 = 2·F·CPR·s`, `n2 = K·s`, `den = 2·p·CPR²`, reduced. No count divides or
//! multiplies out the square: the long axis follows the count through an integer
//! accumulator that adds the first difference `n1 + n2·(2c − 1)` of the position,
//! and that difference grows by the constant `2·n2` per count (a second-order DDA;
//! remainders carried exactly, the position rounded to the nearest step). The other
//! axis of a taper follows the long axis by a rounding DDA.
//!
//! **Thread ramp compensation.** A pass cannot start at full speed. With `m` the
//! counts since the ramp started and `R` (even) the ramp length in counts, the
//! linear part moves `n1·m²/(2R·den)` steps for `m ≤ R`, then `n1·(m − R/2)/den`:
//! the same line as a tool that started at full speed `R/2` counts after the ramp
//! began. The quadratic part of a G34 starts at that count itself, where its speed is
//! zero. The ramp is started `R/2` counts before the synchronisation count (index +
//! Q), so after it the tool is exactly where a tool started at full speed at the
//! index + Q would be — at any speed, because nothing here depends on time. `R` only
//! has to be long enough for the axis's acceleration at the measured speed
//! ([`ramp_counts`]). The end of the pass decelerates from the speed it has, `w` (in
//! `1/den` step per count), evenly to rest over `R` counts (`w·R/2` steps, `w·R²` in
//! accumulator units): it starts on the count where continuing would leave less than
//! that, with the one increment that lands exactly where the deceleration must
//! start, and ends exactly on the end point. For a constant lead that is `R/2` counts
//! before and after the virtual end.
//!
//! Everything is integer in units of `1/(2R·den)` step (threads) or `1/(2·den)` step
//! (taps): a locked count adds `2R·w` and `2·n2` to `w`, a ramp count a few products
//! more; no division.
//!
//! **Only the counts where something falls due.** Most counts move nothing: at a
//! 2 mm lead on 3.125 µm steps a step falls due every 6.4 counts. [`Gear::glide`]
//! applies, in a tight loop of additions, the counts ahead that only add to the
//! accumulators (no step, no change of phase, no deceleration start) and returns
//! the raw count at which the next count must be taken ([`Due`]); the firmware sets
//! the encoder timer's compare there and is interrupted only then. Applying a
//! count before the spindle reaches it is safe because such a count changes no
//! output and a thread's position depends only on the furthest count reached;
//! an announced next leg ([`Gear::set_next`]) cannot change what those counts did
//! (it only adds room before the end). At a constant lead the count that starts
//! the deceleration is found once, on entering the ramp zone (`Gear::find_decel`:
//! a binary search over products, no division), so the counts before it glide as
//! anywhere else instead of each testing the distance. A tap and the polygon gearbox
//! ([`crate::motion::polygon`]) follow the spindle both ways, so they apply
//! nothing ahead and name a count either side.

use crate::alarm::AlarmKind;
use crate::axis::AXIS_COUNT;
use crate::fixed::gcd;

/// One leg of a locked sequence: whole-step start and end points and the long axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Leg {
    /// Start, whole steps per axis.
    pub start: [i64; AXIS_COUNT],
    /// End, whole steps per axis.
    pub end: [i64; AXIS_COUNT],
    /// Index of the long (lead) axis.
    pub long: usize,
}

/// The raw encoder counts at which a gearbox must next be given the count: when the
/// counter, counting up, reaches [`Due::up`], or, counting down, reaches
/// [`Due::down`]. Counts strictly between them move nothing. (Kept as two plain
/// counts, `i64::MAX` / `i64::MIN` for "nothing that way": the count interrupt
/// merges and compares them.)
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Due {
    up: i64,
    down: i64,
}

impl Default for Due {
    fn default() -> Self {
        Due::NONE
    }
}

impl Due {
    /// Nothing falls due either way.
    pub const NONE: Due = Due { up: i64::MAX, down: i64::MIN };

    /// The count to wait for counting up (`None`: nothing falls due that way), and
    /// counting down.
    pub const fn new(up: Option<i64>, down: Option<i64>) -> Due {
        Due {
            up: match up {
                Some(u) => u,
                None => i64::MAX,
            },
            down: match down {
                Some(d) => d,
                None => i64::MIN,
            },
        }
    }

    /// The count to wait for while counting up.
    pub fn up(&self) -> Option<i64> {
        (self.up != i64::MAX).then_some(self.up)
    }

    /// The count to wait for while counting down.
    pub fn down(&self) -> Option<i64> {
        (self.down != i64::MIN).then_some(self.down)
    }

    /// From counts in a gearbox's forward sense: forward count `f` is raw count
    /// `sigma·(f + origin)`; `ahead` and `back` are the forward counts due going
    /// forward and back.
    #[inline]
    pub fn forward(sigma: i64, origin: i64, ahead: Option<i64>, back: Option<i64>) -> Due {
        let raw = |f: i64| signed(sigma, f + origin);
        if sigma < 0 { Due::new(back.map(raw), ahead.map(raw)) } else { Due::new(ahead.map(raw), back.map(raw)) }
    }

    /// The nearer of both dues each way (two gearboxes on one encoder).
    #[inline]
    pub fn merge(self, other: Due) -> Due {
        Due { up: self.up.min(other.up), down: self.down.max(other.down) }
    }

    /// Whether raw count `c` has reached either due count.
    #[inline]
    pub fn reached(&self, c: i64) -> bool {
        c >= self.up || c <= self.down
    }
}

/// Counts one [`Gear::glide`] applies at most: it bounds the count interrupt's time
/// (a few instructions a count) where steps are far apart, as at the start of a long
/// ramp; the interrupt at the count where it stopped glides on.
const GLIDE_MAX: u32 = 1_024;

/// `v` in the direction `sigma` (±1): a negation, not a 64-bit multiplication.
#[inline]
pub(crate) fn signed(sigma: i64, v: i64) -> i64 {
    if sigma < 0 { -v } else { v }
}

/// Long-axis steps per encoder count, `n / d`, reduced.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Ratio {
    /// Numerator.
    pub n: i64,
    /// Denominator.
    pub d: i64,
}

impl Ratio {
    /// `lead` nm per revolution on an axis of `steps` steps per `per_nm` nm, with
    /// `cpr` encoder counts per revolution.
    pub fn new(lead: i64, steps: i64, per_nm: i64, cpr: u32) -> Result<Self, AlarmKind> {
        let n = lead.checked_mul(steps).ok_or(AlarmKind::Overflow)?;
        let d = per_nm.checked_mul(i64::from(cpr)).ok_or(AlarmKind::Overflow)?;
        if n <= 0 || d <= 0 {
            return Err(AlarmKind::FeedZero);
        }
        let g = gcd(n, d);
        Ok(Ratio { n: n / g, d: d / g })
    }

    /// Steps per count as a float (checks and reports only).
    pub fn steps_per_count(&self) -> f64 {
        self.n as f64 / self.d as f64
    }
}

/// Long-axis position as an exact function of the encoder count `c` since the
/// synchronised start: `(n1·c + n2·c²) / den` steps (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Gearing {
    /// Linear coefficient: the lead at the start.
    pub n1: i64,
    /// Quadratic coefficient: half the lead's change per count (0: constant lead).
    pub n2: i64,
    /// Denominator, positive.
    pub den: i64,
}

impl Gearing {
    /// A lead of `lead` nm per revolution at the start changing by `delta` nm per
    /// revolution per revolution (G34 K; 0 for a constant lead), on an axis of
    /// `steps` steps per `per_nm` nm with `cpr` encoder counts per revolution.
    /// Alarm 0011 for a lead that is not positive, 4017 for numbers out of range.
    pub fn new(lead: i64, delta: i64, steps: i64, per_nm: i64, cpr: u32) -> Result<Self, AlarmKind> {
        if lead <= 0 || steps <= 0 || per_nm <= 0 || cpr == 0 {
            return Err(AlarmKind::FeedZero);
        }
        let mul = |a: i128, b: i128| a.checked_mul(b).ok_or(AlarmKind::Overflow);
        let cpr = i128::from(cpr);
        let n1 = mul(mul(2 * i128::from(lead), cpr)?, i128::from(steps))?;
        let n2 = mul(i128::from(delta), i128::from(steps))?;
        let den = mul(mul(2 * i128::from(per_nm), cpr)?, cpr)?;
        let g = gcd_u128(gcd_u128(n1.unsigned_abs(), n2.unsigned_abs()), den.unsigned_abs()) as i128;
        Ok(Gearing { n1: reduced(n1, g)?, n2: reduced(n2, g)?, den: reduced(den, g)? })
    }

    /// Speed at the synchronised start, steps per count (checks and reports only).
    pub fn steps_per_count(&self) -> f64 {
        self.n1 as f64 / self.den as f64
    }

    /// Change of the speed per count, steps per count² (checks and reports only).
    pub fn accel(&self) -> f64 {
        2.0 * self.n2 as f64 / self.den as f64
    }

    /// The same gearing over a denominator `f` times larger.
    fn scaled(self, f: i64) -> Option<Self> {
        Some(Gearing { n1: self.n1.checked_mul(f)?, n2: self.n2.checked_mul(f)?, den: self.den.checked_mul(f)? })
    }
}

/// `v / g` as an i64 (alarm 4017 when it does not fit). Out of line: a 128-bit
/// division inlined three times in `Gearing::new` cost 3 KB of firmware flash.
#[inline(never)]
fn reduced(v: i128, g: i128) -> Result<i64, AlarmKind> {
    i64::try_from(v / g).map_err(|_| AlarmKind::Overflow)
}

impl From<Ratio> for Gearing {
    fn from(r: Ratio) -> Self {
        Gearing { n1: r.n, n2: 0, den: r.d }
    }
}

fn gcd_u128(mut a: u128, mut b: u128) -> u128 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a.max(1)
}

/// Length in counts (even, at least 2) of a thread pass's ramps, such that the
/// ramp-up (the lead's own ramp plus a G34's constant K acceleration) and the
/// deceleration from the lead it ends with stay within the axis's acceleration.
/// `lead` is the lead at the synchronised start and `lead_end` the largest the pass
/// decelerates from, nm per count; `k` the lead's change, nm per count²; `cpt`
/// counts per period; `accel` nm per period² along the long axis. `None` when K alone
/// takes more than half the acceleration (alarm 4510).
pub fn ramp_counts(lead: f32, lead_end: f32, k: f32, cpt: f32, accel: f32) -> Option<i64> {
    let kc = k * cpt * cpt;
    if kc.is_nan() || kc.abs() > accel / 2.0 {
        return None;
    }
    let up = if kc > 0.0 { lead * cpt * cpt / (accel - kc) } else { lead * cpt * cpt / accel };
    let down = lead_end * cpt * cpt / accel;
    Some((up.max(down) as i64 + 2) & !1)
}

/// Long-axis steps the ramp-up of `ramp` counts takes with gearing `g`: the linear
/// part's `v·R/2` and the quadratic part's `a·(R/2)²/2` (when the lead grows).
pub fn ramp_up_steps(g: &Gearing, ramp: i64) -> f64 {
    let r = ramp as f64;
    g.steps_per_count() * r / 2.0 + g.accel().max(0.0) * r * r / 8.0
}

/// Long-axis steps the deceleration of a ramp of `ramp` counts may need, doubled,
/// plus a margin, at up to `v` steps per count (computed once: no division per count).
fn ramp_zone(v: f64, ramp: i64) -> i64 {
    (v * ramp as f64) as i64 + 4
}

/// Whether the accumulator of unit `unit` (`two_r·den`) stays far from overflow for
/// speeds up to `v` steps per count and the ramp's products with gearing `g`.
fn fits(unit: i64, two_r: i64, g: &Gearing, ramp: i64, v: f64) -> bool {
    let (unit, two_r) = (unit as f64, two_r as f64);
    let top =
        unit * (v + 1.0) + two_r * (g.n1.unsigned_abs() as f64 + g.n2.unsigned_abs() as f64 * (ramp as f64 + 2.0));
    (top + unit) * 8.0 < i64::MAX as f64
}

/// Speed at the end of a leg of `len` steps entered at `v0` steps per count with
/// gearing `g`, or alarm 0014 if the lead would reach zero before the end.
fn speed_after(v0: f64, g: &Gearing, len: i64) -> Result<f64, AlarmKind> {
    let sq = v0 * v0 + 2.0 * g.accel() * len as f64;
    if sq > 0.0 { Ok(libm::sqrt(sq)) } else { Err(AlarmKind::IllegalLead) }
}

/// Where a thread pass is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Phase {
    /// Waiting for the encoder to reach the count where the ramp starts.
    Waiting,
    /// Accelerating; `k` ramp counts done.
    RampUp {
        /// Counts done.
        k: i64,
    },
    /// Locked at the lead.
    Locked,
    /// Decelerating onto the end point; `u` counts left.
    RampDown {
        /// Counts left.
        u: i64,
    },
    /// On the end point of the sequence.
    Done,
}

/// Which relation the gearbox follows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
enum Mode {
    /// A thread pass: forward counts only, ramps at both ends.
    Thread,
    /// Rigid tapping: linear in the count, both directions.
    Tap,
}

/// The announced leg that continues the running one without re-synchronising.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
struct Next {
    leg: Leg,
    /// Its gearing over the denominator common to both legs.
    gearing: Gearing,
    /// What the running leg's numbers are multiplied by to reach that denominator.
    scale: i64,
    /// It continues from the lead reached (after a G34) instead of its own lead.
    keep_lead: bool,
    /// Same long axis and the same motion going on (a pull-out at the same lead, a
    /// G34 continued with the same K): the deceleration may span both legs.
    same_motion: bool,
    /// Its long-axis length, steps.
    len: i64,
    /// Its [`ramp_zone`] and the speed it ends with, steps per count.
    ramp_zone: i64,
    end_speed: f64,
}

/// The electronic gearbox.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Gear {
    mode: Mode,
    phase: Phase,
    /// The running leg's gearing.
    gearing: Gearing,
    /// Ramp length in counts (even and positive, so `ramp >> 1` is its half; 1 for
    /// taps) and twice it.
    ramp: i64,
    two_r: i64,
    /// Accumulator unit: one long-axis step is `unit` = `2R·den` (`2·den` for taps).
    unit: i64,
    /// Long-axis steps from the end within which the deceleration may start (twice
    /// the largest deceleration, plus a margin): below it the exact test runs.
    ramp_zone: i64,
    /// Remainder of the long axis's exact position, `[0, unit)` (rounded: starts at half).
    acc: i64,
    /// Ramping up: the next count's increment and its change per count. Locked: the
    /// next count's increment over `2R` (the first difference of `n1·c + n2·c²`) and
    /// its change per count, `2·n2`. Decelerating: the `w` the deceleration started
    /// from.
    w: i64,
    dw: i64,
    /// Within the ramp zone of the last leg: how far (units) the deceleration start
    /// is, `unit·left − now − w·R²`, kept up to date by one subtraction of
    /// `2R·w + dw·R²` a count (the second number); `None` until the exact test first
    /// runs (or when the numbers do not fit: then the exact test runs every count).
    to_start: Option<(i64, i64)>,
    /// The long-axis step count `p` from which the ramp zone begins in this leg
    /// (`decel_left() ≤ ramp_zone` exactly when `p ≥ zone_p`; `i64::MAX` when the
    /// pass does not decelerate in this leg): one comparison a step instead of the
    /// distance to the end worked out twice.
    zone_p: i64,
    /// Locked at a constant lead, the deceleration's first count, found once on
    /// entering the ramp zone ([`Gear::find_decel`]; `i64::MAX` until then): the
    /// forward count that starts it and the increment that count adds. Up to it
    /// the counts glide as anywhere else: no test a count.
    dec_at: i64,
    dec_jump: i64,
    /// The counts from one step to the next the last glide found (the next is the
    /// same, one more or one fewer, nearly always): where the next glide looks first.
    spacing: u32,
    /// Speed at the end of the running leg, steps per count (checks only).
    end_speed: f64,
    /// Long-axis steps from the leg's start, and the leg's length and direction.
    p: i64,
    delta: i64,
    long_sign: i64,
    leg: Leg,
    /// Legs completed in this sequence.
    legs_done: u32,
    /// The leg that follows without re-synchronising, if known, and whether the
    /// sequence ends with it.
    next: Option<Next>,
    next_last: bool,
    /// The other moving axis (a taper), its direction and DDA.
    follower: Option<(usize, i64, Follower)>,
    /// Encoder direction of forward rotation (+1 counts up, −1 down).
    sigma: i64,
    /// Forward count where the pass started (ramp start, or tap start).
    origin: i64,
    /// Forward counts since `origin`, and the most reached (threads ignore reversals).
    m: i64,
    m_max: i64,
    /// A tap on its way out.
    way_out: bool,
}

/// A rounding DDA: `pos = round(p · num / den)` kept up to date as `p` steps ±1.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
struct Follower {
    num2: i64,
    den2: i64,
    acc: i64,
    pos: i64,
}

impl Follower {
    fn new(num: i64, den: i64) -> Self {
        let den = den.max(1);
        Follower { num2: 2 * num, den2: 2 * den, acc: den, pos: 0 }
    }

    fn up(&mut self) {
        self.acc += self.num2;
        while self.acc >= self.den2 {
            self.acc -= self.den2;
            self.pos += 1;
        }
    }

    fn down(&mut self) {
        self.acc -= self.num2;
        while self.acc < 0 {
            self.acc += self.den2;
            self.pos -= 1;
        }
    }
}

/// A stretch of counts for [`Gear::glide`]: count `j` adds `a + j·d` units; they
/// glide while their sum stays below `room`, at most `most`, and with `end` =
/// `(x, step)` while `x − sum − j·step` stays positive.
#[derive(Clone, Copy)]
struct Run {
    room: i64,
    a: i64,
    d: i64,
    most: u32,
    end: Option<(i64, i64)>,
}

impl Run {
    /// Whether the counts' sums only grow (every increment at least zero; near the
    /// end the distance falls every count) and the products of [`Run::glides`] stay
    /// inside i64 (plain multiplications: a checked 64-bit product is a library
    /// call on the M4). Then whether `n` counts glide is monotone in `n`; else the
    /// counts go one by one (huge G34 denominators, an increment below zero).
    #[inline]
    fn monotone(&self) -> bool {
        const A: i64 = 1 << 50;
        const D: i64 = 1 << 40;
        let (x, step) = self.end.unwrap_or((0, 0));
        if !(0..A).contains(&self.a) || !(-D..D).contains(&self.d) || !(-A..A).contains(&step) || x >= 1 << 61 {
            return false;
        }
        // The increments and the distance's fall are straight lines in the count:
        // at least zero (positive) at both ends of the stretch, so all along it.
        let last = self.a + self.d * i64::from(self.most);
        last >= 0 && (self.end.is_none() || (self.a + step > 0 && last + step > 0))
    }

    /// What the first `n` counts add: `n·a + d·n(n − 1)/2`.
    #[inline]
    fn sum(&self, n: u32) -> i64 {
        let n = i64::from(n);
        n * self.a + self.d * (n * (n - 1) / 2)
    }

    /// How many counts glide (a [`Run::monotone`] run): `hint`, one more or one
    /// fewer when one of them is it (two or three sums), else a binary search (at
    /// most 11 sums for GLIDE_MAX).
    fn search(&self, hint: u32) -> u32 {
        let h = hint;
        match (self.glides(h), self.glides(h + 1)) {
            (true, false) => h,
            (true, true) if !self.glides(h + 2) => h + 1,
            (false, _) if h > 0 && self.glides(h - 1) => h - 1,
            _ => {
                let (mut lo, mut hi) = (0, self.most + 1);
                while hi - lo > 1 {
                    let mid = lo + (hi - lo) / 2;
                    if self.glides(mid) { lo = mid } else { hi = mid }
                }
                lo
            }
        }
    }

    /// How many counts glide and what they add, count by count (additions and
    /// checked subtractions: any run). An increment below zero could step back:
    /// it ends the glide.
    fn one_by_one(&self) -> (u32, i64) {
        let (mut n, mut sum, mut inc) = (0u32, 0i64, self.a);
        let (mut x, step) = self.end.unwrap_or((i64::MAX, 0));
        while n < self.most && inc >= 0 && sum + inc < self.room {
            match x.checked_sub(inc).and_then(|v| v.checked_sub(step)) {
                Some(after) if after > 0 => x = if self.end.is_some() { after } else { x },
                _ => break,
            }
            sum += inc;
            inc += self.d;
            n += 1;
        }
        (n, sum)
    }

    /// Whether the first `n` counts all glide (for a [`Run::monotone`] run).
    #[inline]
    fn glides(&self, n: u32) -> bool {
        if n > self.most {
            return false;
        }
        let s = self.sum(n);
        s < self.room && self.end.is_none_or(|(x, step)| x - s - step * i64::from(n) > 0)
    }
}

impl Gear {
    fn new(mode: Mode, leg: Leg, gearing: Gearing, ramp: i64, sigma: i64, origin: i64) -> Result<Self, AlarmKind> {
        if gearing.n1 <= 0 || gearing.den <= 0 {
            return Err(AlarmKind::FeedZero);
        }
        let two_r = 2i64.checked_mul(ramp.max(1)).ok_or(AlarmKind::Overflow)?;
        let unit = two_r.checked_mul(gearing.den).ok_or(AlarmKind::Overflow)?;
        let v0 = gearing.steps_per_count();
        let end_speed = speed_after(v0, &gearing, (leg.end[leg.long] - leg.start[leg.long]).saturating_abs())?;
        let v_max = v0.max(end_speed);
        if !fits(unit, two_r, &gearing, ramp, v_max) {
            return Err(AlarmKind::Overflow);
        }
        let mut g = Gear {
            mode,
            phase: if mode == Mode::Thread { Phase::Waiting } else { Phase::Locked },
            gearing,
            ramp,
            two_r,
            unit,
            ramp_zone: ramp_zone(v_max, ramp),
            acc: unit / 2,
            w: gearing.n1,
            dw: 2 * gearing.n1,
            to_start: None,
            zone_p: i64::MAX,
            dec_at: i64::MAX,
            dec_jump: 0,
            spacing: 0,
            end_speed,
            p: 0,
            delta: 0,
            long_sign: 1,
            leg,
            legs_done: 0,
            next: None,
            next_last: true,
            follower: None,
            sigma: if sigma < 0 { -1 } else { 1 },
            origin,
            m: 0,
            m_max: 0,
            way_out: false,
        };
        g.set_leg(leg);
        Ok(g)
    }

    /// A thread pass along `leg` whose acceleration ramp of `ramp` counts (made even,
    /// at least 2) starts at raw encoder count `ramp_start`; forward rotation makes
    /// the count go in direction `sigma`. The tool is where a tool started at full
    /// speed at `ramp_start + sigma·ramp/2` would be once the ramp is over. Alarm 0014
    /// if a variable lead would reach zero before the end of the leg.
    pub fn thread(
        leg: Leg,
        gearing: impl Into<Gearing>,
        ramp: i64,
        sigma: i64,
        ramp_start: i64,
    ) -> Result<Self, AlarmKind> {
        let ramp = (ramp.clamp(2, i64::MAX / 4) + 1) & !1;
        let sigma = if sigma < 0 { -1 } else { 1 };
        Gear::new(Mode::Thread, leg, gearing.into(), ramp, sigma, sigma * ramp_start)
    }

    /// Rigid tapping along `leg` (the way in), locked from raw count `count` on;
    /// forward rotation (counts in direction `sigma`) moves towards the bottom.
    pub fn tap(leg: Leg, ratio: impl Into<Gearing>, sigma: i64, count: i64) -> Result<Self, AlarmKind> {
        let sigma = if sigma < 0 { -1 } else { 1 };
        let gearing = ratio.into();
        if gearing.n2 != 0 {
            return Err(AlarmKind::IllegalLead);
        }
        Gear::new(Mode::Tap, leg, gearing, 1, sigma, sigma * count)
    }

    fn set_leg(&mut self, leg: Leg) {
        let d = leg.end[leg.long] - leg.start[leg.long];
        self.leg = leg;
        self.delta = d.abs();
        self.long_sign = if d < 0 { -1 } else { 1 };
        self.p = 0;
        self.follower = (0..AXIS_COUNT).rfind(|&i| i != leg.long && leg.end[i] != leg.start[i]).map(|i| {
            let ds = leg.end[i] - leg.start[i];
            (i, ds.signum(), Follower::new(ds.abs(), self.delta))
        });
        self.update_zone();
    }

    /// After a change of the leg, of the announced next one or of the ramp zone:
    /// where the ramp zone begins, and the deceleration start to be found again.
    fn update_zone(&mut self) {
        self.to_start = None;
        self.dec_at = i64::MAX;
        self.zone_p = match self.decel_left() {
            Some(left) => (self.p + left).saturating_sub(self.ramp_zone),
            None => i64::MAX,
        };
    }

    /// Announces the thread leg that continues this one without re-synchronising
    /// (2.17.1 note 2); `last` if the sequence ends with it. It starts at its own
    /// lead, or with `keep_lead` at the lead the running leg has reached (the blocks
    /// after a G34), and its gearing's K applies from there. Without one, the pass
    /// decelerates onto the current leg's end. A last leg on the same axis
    /// continuing the same motion (a pull-out at the same lead) shares the
    /// deceleration with the leg before it, so a short pull-out still ends exactly
    /// on its end point. Alarm 4507 when the pass is already decelerating or done,
    /// 4502 when what is left cannot hold the ramps, 0014 when the lead would reach
    /// zero.
    pub fn set_next(
        &mut self,
        leg: Leg,
        gearing: impl Into<Gearing>,
        last: bool,
        keep_lead: bool,
    ) -> Result<(), AlarmKind> {
        let gearing = gearing.into();
        if self.mode != Mode::Thread
            || matches!(self.phase, Phase::RampDown { .. } | Phase::Done)
            || leg.start != self.leg.end
            || leg.end[leg.long] == leg.start[leg.long]
            || gearing.den <= 0
            || (gearing.n1 <= 0 && !keep_lead)
        {
            return Err(AlarmKind::SyncSequenceBroken);
        }
        // Both legs over one denominator: the running leg's state is multiplied by
        // `scale` when the next takes over (exact, no rounding).
        let g = gcd(self.gearing.den, gearing.den);
        let scale = gearing.den / g;
        let next = gearing.scaled(self.gearing.den / g).ok_or(AlarmKind::Overflow)?;
        let unit = self.two_r.checked_mul(next.den).ok_or(AlarmKind::Overflow)?;
        let len = (leg.end[leg.long] - leg.start[leg.long]).saturating_abs();
        let v0 = if keep_lead { self.end_speed } else { gearing.steps_per_count() };
        let end_speed = speed_after(v0, &gearing, len)?;
        let v_max = v0.max(end_speed).max(self.end_speed);
        let running = self.gearing.scaled(scale).ok_or(AlarmKind::Overflow)?;
        if !fits(unit, self.two_r, &next, self.ramp, v_max) || !fits(unit, self.two_r, &running, self.ramp, v_max) {
            return Err(AlarmKind::Overflow);
        }
        let same_motion = leg.long == self.leg.long
            && scale == 1
            && if keep_lead { next.n2 == self.gearing.n2 } else { next == self.gearing && next.n2 == 0 };
        let down = (end_speed * self.ramp as f64 / 2.0) as i64 + 1;
        let starting = matches!(self.phase, Phase::Waiting | Phase::RampUp { .. });
        let room = if same_motion { len + self.delta - self.p } else { len };
        let need =
            if same_motion && starting { down + ramp_up_steps(&self.gearing, self.ramp) as i64 + 1 } else { down };
        if last && room < need {
            return Err(AlarmKind::ThreadRampTooLong);
        }
        let zone = ramp_zone(v_max, self.ramp);
        if same_motion && last {
            self.ramp_zone = self.ramp_zone.max(zone);
        }
        self.next = Some(Next { leg, gearing: next, scale, keep_lead, same_motion, len, ramp_zone: zone, end_speed });
        self.next_last = last;
        self.update_zone();
        Ok(())
    }

    /// Whether a continuing leg has been announced.
    pub fn has_next(&self) -> bool {
        self.next.is_some()
    }

    /// The rigid tap's way out: `leg` must lead back from the bottom to where the tap
    /// started (alarm 4507 otherwise); the relation to the spindle stays the same.
    pub fn way_out(&mut self, leg: &Leg) -> Result<(), AlarmKind> {
        if self.mode != Mode::Tap || leg.end != self.leg.start || leg.start != self.leg.end {
            return Err(AlarmKind::SyncSequenceBroken);
        }
        self.way_out = true;
        Ok(())
    }

    /// The thread pass's phase.
    pub fn phase(&self) -> Phase {
        self.phase
    }

    /// Ramp length in counts.
    pub fn ramp(&self) -> i64 {
        self.ramp
    }

    /// The running leg's gearing.
    pub fn gearing(&self) -> Gearing {
        self.gearing
    }

    /// The long axis's speed now, steps per count: the lead it has reached in a
    /// thread pass (what a stop brakes from), the tap's ratio.
    pub fn steps_per_count(&self) -> f64 {
        let unit = self.unit as f64;
        let g = &self.gearing;
        match (self.mode, self.phase) {
            (Mode::Tap, _) => g.steps_per_count(),
            (_, Phase::Waiting | Phase::Done) => 0.0,
            (_, Phase::RampUp { .. }) => self.w as f64 / unit,
            (_, Phase::Locked) => self.w as f64 / g.den as f64,
            (_, Phase::RampDown { u }) => self.w as f64 * (2 * u) as f64 / unit,
        }
    }

    /// Legs finished so far in this sequence.
    pub fn legs_done(&self) -> u32 {
        self.legs_done
    }

    /// Raw encoder count where the pass started: the ramp start of a thread, the
    /// lock of a tap.
    pub fn origin(&self) -> i64 {
        self.sigma * self.origin
    }

    /// Encoder direction of forward rotation.
    pub fn sigma(&self) -> i64 {
        self.sigma
    }

    /// Forward counts since the pass started (negative while waiting).
    pub fn counts(&self) -> i64 {
        self.m
    }

    /// Whether the sequence is over: the thread on its last end point, the tap back
    /// at its start (or at the bottom, before its way out is known).
    pub fn finished(&self) -> bool {
        match self.mode {
            Mode::Thread => matches!(self.phase, Phase::Done),
            Mode::Tap if self.way_out => self.p <= 0,
            Mode::Tap => self.p >= self.delta,
        }
    }

    /// The long axis and the other axis of a taper, if any: the axes the gearbox drives.
    pub fn axes(&self) -> (usize, Option<usize>) {
        (self.leg.long, self.follower.map(|f| f.0))
    }

    /// The leg running.
    pub fn leg(&self) -> &Leg {
        &self.leg
    }

    /// Whether this is a rigid tap (and not a thread pass).
    pub fn is_tap(&self) -> bool {
        self.mode == Mode::Tap
    }

    /// Whether a tap is on its way out.
    pub fn is_way_out(&self) -> bool {
        self.way_out
    }

    /// Long-axis steps left to the end of the leg (tap: to the bottom, or back to
    /// the start on the way out).
    pub fn remaining(&self) -> i64 {
        if self.way_out { self.p } else { self.delta - self.p }
    }

    /// Whole-step position of the long axis, and of the taper's follower (its
    /// index and position) if there is one: the axes the gearbox moves.
    #[inline]
    pub fn driven(&self) -> (i64, Option<(usize, i64)>) {
        let leg = &self.leg;
        let long = leg.start[leg.long] + signed(self.long_sign, self.p);
        (long, self.follower.as_ref().map(|(i, sign, f)| (*i, leg.start[*i] + signed(*sign, f.pos))))
    }

    /// Whole-step position of every axis: the leg's start, with the long axis and
    /// the taper's follower where the spindle has taken them.
    pub fn positions(&self, out: &mut [i64; AXIS_COUNT]) {
        let leg = &self.leg;
        *out = leg.start;
        out[leg.long] = leg.start[leg.long] + self.long_sign * self.p;
        if let Some((i, sign, f)) = &self.follower {
            out[*i] = leg.start[*i] + sign * f.pos;
        }
    }

    /// Processes raw encoder count `c`, one count at a time; true if an axis moved.
    pub fn on_count(&mut self, c: i64) -> bool {
        let fwd = signed(self.sigma, c) - self.origin;
        let mut moved = false;
        match self.mode {
            Mode::Tap => {
                while self.m != fwd {
                    let dir = (fwd - self.m).signum();
                    self.m += dir;
                    moved |= self.add(2 * self.gearing.n1 * dir);
                }
            }
            Mode::Thread => {
                // Counts up to `m_max` were taken (or applied ahead by `glide`):
                // a thread follows the furthest count reached, never back.
                while self.m_max < fwd {
                    self.m_max += 1;
                    moved |= self.thread_count();
                }
                self.m = fwd;
            }
        }
        moved
    }

    /// Applies the counts ahead that move nothing (a thread's counts that only add
    /// to the accumulators: no step, no change of phase, no deceleration start) and
    /// returns the raw counts at which the next count must be taken. A tap follows
    /// the spindle both ways: nothing is applied ahead, and the counts of the next
    /// step either way are named. No division: the counts to the next step are
    /// the last glide's, one more or one fewer (checked by a few products), else
    /// found by a binary search over the sums of the increments, else (numbers
    /// that could leave 64 bits) counted one by one; at most [`GLIDE_MAX`].
    #[inline]
    pub fn glide(&mut self) -> Due {
        if let Some(due) = self.glide_constant() {
            return due;
        }
        match self.glide_ramp() {
            Some(due) => due,
            None => self.glide_any(),
        }
    }

    /// [`Gear::glide`] in a ramp (up or down), kept small: the counts to the step
    /// as many as the last time, one more or one fewer, checked on the sums
    /// `S(n) = n·a + d·n(n − 1)/2` of the ramp's increments. `None` otherwise.
    #[inline(always)]
    fn glide_ramp(&mut self) -> Option<Due> {
        // Count j from now adds a + j·d; `most` counts before the next special one
        // (only a thread ramps: no check of the mode).
        let (a, d, most, at, down) = match self.phase {
            Phase::RampUp { k } => {
                let stop = if k < self.ramp >> 1 { self.ramp >> 1 } else { self.ramp };
                (self.w, self.dw, stop - 1 - k, k, false)
            }
            Phase::RampDown { u } => (self.w * (2 * u - 1), -2 * self.w, u - 1, u, true),
            _ => return None,
        };
        // 1 ≤ h, h + 1 below `most` and GLIDE_MAX, 0 ≤ a < 2^50, |d| ≤ 2^40: the
        // products below stay far inside i64 (h < 2^10).
        let h = self.spacing.wrapping_sub(1);
        if h.wrapping_sub(1) >= GLIDE_MAX - 2
            || i64::from(h) + 1 >= most
            || a as u64 >= 1 << 50
            || d.wrapping_add(1 << 40) as u64 > 1 << 41
        {
            return None;
        }
        let room = self.unit - self.acc;
        // Exactly n glide: S(n) < room ≤ S(n + 1), with every increment to the
        // (n+1)-th at least zero. S(h) once, its neighbours by one increment.
        let inc = a + d * i64::from(h);
        let s = i64::from(h) * a + d * i64::from(h * (h - 1) / 2);
        let (n, glided) = if s < room && s + inc >= room && inc >= 0 {
            (h, s)
        } else if s + inc < room && s + 2 * inc + d >= room && inc + d >= 0 {
            (h + 1, s + inc)
        } else if s >= room && s - inc + d < room && inc >= d {
            (h - 1, s - inc + d)
        } else {
            return None;
        };
        self.remember(n);
        let n = i64::from(n);
        self.acc += glided;
        self.m_max += n;
        self.phase = if down {
            Phase::RampDown { u: at - n }
        } else {
            self.w += n * self.dw;
            Phase::RampUp { k: at + n }
        };
        Some(self.due())
    }

    /// [`Gear::glide`] for nearly every interrupt, kept small: locked at a constant
    /// lead, the step after as many counts as the last one, one more or one fewer.
    /// `None` otherwise.
    #[inline(always)]
    fn glide_constant(&mut self) -> Option<Due> {
        if self.mode != Mode::Thread || !matches!(self.phase, Phase::Locked) || self.dw != 0 {
            return None;
        }
        // In the ramp zone the deceleration's first count must be known (found
        // once by `glide_any`); no count from it on glides.
        if self.dec_at == i64::MAX && self.p >= self.zone_p {
            return None;
        }
        let (inc, room, k) = (self.two_r * self.w, self.unit - self.acc, self.spacing);
        if !(2..GLIDE_MAX).contains(&k) || !(1..1 << 52).contains(&inc) {
            return None;
        }
        // k − 1 counts glide and the k-th steps: (k − 1)·inc < room ≤ k·inc (room > 0).
        let steps_at = |k: u32| room <= i64::from(k) * inc;
        let k = match (steps_at(k - 1), steps_at(k)) {
            (false, true) => k,
            (false, false) if steps_at(k + 1) => k + 1,
            (true, _) if !steps_at(k - 2) => k - 1,
            _ => return None,
        };
        let n = i64::from(k - 1);
        if self.m_max + n >= self.dec_at {
            // The deceleration starts before the step: the slow way, to it.
            return None;
        }
        let glided = n * inc;
        self.remember(k - 1);
        self.acc += glided;
        self.m_max += n;
        Some(self.due())
    }

    /// [`Gear::glide`] in every case.
    #[inline(never)]
    fn glide_any(&mut self) -> Due {
        if self.mode == Mode::Tap {
            let (up, down) = self.tap_due();
            return Due::forward(self.sigma, self.origin, Some(self.m + up), Some(self.m - down));
        }
        let room = self.unit - self.acc;
        let n = match self.phase {
            Phase::RampUp { k } => {
                // Up to the synchronised count (R/2) and the lock (R), which change
                // the increments; count k + 1 adds w, each next one dw more.
                let stop = if k < self.ramp >> 1 { self.ramp >> 1 } else { self.ramp };
                let most = (stop - 1 - k).clamp(0, i64::from(GLIDE_MAX)) as u32;
                let (n, sum) = self.glide_by(Run { room, a: self.w, d: self.dw, most, end: None });
                let n = i64::from(n);
                (self.acc, self.w, self.phase) = (self.acc + sum, self.w + n * self.dw, Phase::RampUp { k: k + n });
                n
            }
            Phase::Locked => {
                // Near the end, at a constant lead, the counts glide up to the
                // deceleration's first count, found once; at a varying lead each
                // count also takes `inc + dw·R²` off the distance to the
                // deceleration start (as `near_end`), which must stay positive.
                let mut most = GLIDE_MAX;
                let end = match self.decel_left() {
                    Some(left) if left <= self.ramp_zone => {
                        if self.dec_at == i64::MAX && !self.find_decel(left, self.m_max + 1) && self.to_start.is_none()
                        {
                            self.to_start = self.exact_to_start(left);
                        }
                        if self.dec_at != i64::MAX {
                            most = (self.dec_at - self.m_max - 1).clamp(0, i64::from(GLIDE_MAX)) as u32;
                            None
                        } else {
                            let Some(end) = self.to_start else { return self.due() };
                            Some(end)
                        }
                    }
                    _ => None,
                };
                let run = Run { room, a: self.two_r * self.w, d: self.two_r * self.dw, most, end };
                let (n, sum) = self.glide_by(run);
                let n = i64::from(n);
                if let Some((x, step)) = end {
                    self.to_start = Some((x - sum - n * step, step));
                }
                (self.acc, self.w) = (self.acc + sum, self.w + n * self.dw);
                n
            }
            Phase::RampDown { u } => {
                // Count u adds w·(2u − 1), each next one 2w less; the last (u = 1) ends.
                let most = (u - 1).clamp(0, i64::from(GLIDE_MAX)) as u32;
                let run = Run { room, a: self.w * (2 * u - 1), d: -2 * self.w, most, end: None };
                let (n, sum) = self.glide_by(run);
                let n = i64::from(n);
                (self.acc, self.phase) = (self.acc + sum, Phase::RampDown { u: u - n });
                n
            }
            Phase::Waiting | Phase::Done => 0,
        };
        self.m_max += n;
        self.due()
    }

    /// The raw count of a thread's next count to take (none once done).
    /// `#[inline]`: its callers are inlined into the encoder-count interrupt's
    /// body (`motion_driver::board::window`), which the link-time optimisation of
    /// the size-built firmware would not inline it into.
    #[inline]
    fn due(&self) -> Due {
        let ahead = (!matches!(self.phase, Phase::Done)).then_some(self.m_max + 1);
        Due::forward(self.sigma, self.origin, ahead, None)
    }

    /// How many of the counts ahead glide, and what they add: count `j` (from 0)
    /// adds `a + j·d` to the accumulator, and glides while the sum stays below
    /// `room` (no step) and, with `end` = `(x, step)`, while `x` less the sum and
    /// `step` a count stays positive (no deceleration start); at most `most`.
    /// From the sums `S(n) = n·a + d·n(n − 1)/2` (a few products): the last
    /// glide's count, one more or one fewer, else a binary search; counts one by
    /// one only where the sums could leave i64 or shrink.
    fn glide_by(&mut self, r: Run) -> (u32, i64) {
        let n = if r.monotone() { r.search(self.spacing.saturating_sub(1)) } else { r.one_by_one().0 };
        self.remember(n);
        (n, r.sum(n))
    }

    /// Keeps the spacing of steps a glide of `n` counts found (a glide that finds
    /// the next count due at once, as a second glide before any count does, tells
    /// nothing about it).
    #[inline]
    fn remember(&mut self, n: u32) {
        if n > 0 {
            self.spacing = n + 1;
        }
    }

    /// A tap's counts to its next step forward and back (its increment is constant).
    fn tap_due(&self) -> (i64, i64) {
        let inc = 2 * self.gearing.n1;
        let (mut up, mut a) = (1, self.acc + inc);
        while a < self.unit {
            a += inc;
            up += 1;
        }
        let (mut down, mut b) = (1, self.acc - inc);
        while b >= 0 {
            b -= inc;
            down += 1;
        }
        (up, down)
    }

    /// One forward count of a thread pass.
    fn thread_count(&mut self) -> bool {
        match self.phase {
            Phase::Waiting | Phase::RampUp { .. } => self.ramp_up_count(),
            Phase::Locked => {
                let inc = self.two_r * self.w;
                let jump = if self.m_max == self.dec_at {
                    Some(self.dec_jump)
                } else if self.p >= self.zone_p && self.dec_at == i64::MAX {
                    self.ramp_down_jump(inc)
                } else {
                    None
                };
                match jump {
                    Some(jump) => {
                        self.phase = Phase::RampDown { u: self.ramp };
                        self.dec_at = i64::MAX;
                        self.add(jump)
                    }
                    None => {
                        self.w += self.dw;
                        self.add(inc)
                    }
                }
            }
            Phase::RampDown { u } => {
                let moved = self.add(self.w * (2 * u - 1));
                if u <= 1 {
                    if self.next.is_some() {
                        // Rounding left the last leg's first step undone: finish on it.
                        self.take_next();
                    }
                    self.phase = Phase::Done;
                    self.p = self.delta;
                    self.acc = self.unit / 2;
                } else {
                    self.phase = Phase::RampDown { u: u - 1 };
                }
                moved
            }
            Phase::Done => false,
        }
    }

    /// One count of the ramp-up, `m = k + 1` since the ramp started and `c = m − R/2`
    /// since the synchronised start: the linear part's `n1·(2m − 1)` and, from the
    /// synchronised start on, the quadratic part's `2R·n2·(2c − 1)`, both kept by
    /// additions (`w` the increment, `dw` its change: `2·n1`, plus `4R·n2` from the
    /// synchronised start on). After the last one the gearbox is locked with the next
    /// count's `w = n1 + n2·(2c + 1)`.
    fn ramp_up_count(&mut self) -> bool {
        let k = if let Phase::RampUp { k } = self.phase { k } else { 0 };
        let inc = self.w;
        let m = k + 1;
        if m >= self.ramp {
            self.phase = Phase::Locked;
            self.lock();
        } else {
            self.phase = Phase::RampUp { k: m };
            self.w += self.dw;
            if m == self.ramp >> 1 {
                self.start_quadratic();
            }
        }
        self.add(inc)
    }

    /// The synchronised count is reached: the quadratic part starts (its first
    /// increment `2R·n2`, then `4R·n2` more each count).
    #[inline(never)]
    fn start_quadratic(&mut self) {
        let q = self.two_r * self.gearing.n2;
        self.w += q;
        self.dw += 2 * q;
    }

    /// The ramp is over: the next count is `c = R/2 + 1` since the synchronised start.
    #[inline(never)]
    fn lock(&mut self) {
        let g = self.gearing;
        self.w = g.n1 + g.n2 * (self.ramp + 1);
        self.dw = 2 * g.n2;
    }

    /// Near the end of the last leg: the increment that lands exactly where the
    /// deceleration from this count's speed must start (`unit·left − now − w·R²` in
    /// accumulator units), on the count where going on at `inc` would leave less
    /// than the next count's speed needs to stop: `rem − inc ≤ (w + dw)·R²`.
    /// Out of line: the locked count's fast path stays small.
    #[inline(never)]
    fn ramp_down_jump(&mut self, inc: i64) -> Option<i64> {
        let left = self.decel_left()?;
        // Far from the end the products below could overflow; the ramp is short.
        if left > self.ramp_zone {
            return None;
        }
        // The count being taken is `m_max`.
        if self.dw == 0 && self.find_decel(left, self.m_max) {
            return (self.m_max == self.dec_at).then_some(self.dec_jump);
        }
        self.near_end(left, inc)
    }

    /// Locked at a constant lead in the ramp zone, `left` steps from the end with
    /// forward count `first` next to take: finds once the count that starts the
    /// deceleration ([`Gear::dec_at`]) and the increment it adds, what
    /// [`Gear::near_end`] would find a count at a time. Each count takes the same
    /// `inc = 2R·w` off the distance `x` to the deceleration start, and count `j`
    /// (from 1) starts it when `x − j·inc ≤ 0`, adding `x − (j − 1)·inc`: the
    /// smallest such `j` by a binary search over its bits (products checked
    /// against 64 bits by their lengths; no division). False (nothing found) for a
    /// varying lead or numbers that do not fit: then the test runs every count.
    #[inline(never)]
    fn find_decel(&mut self, left: i64, first: i64) -> bool {
        let inc = self.two_r * self.w;
        if self.dw != 0 || inc <= 0 || !matches!(self.phase, Phase::Locked) {
            return false;
        }
        let Some((x, 0)) = self.exact_to_start(left) else { return false };
        // q: the most counts with q·inc < x (none if x ≤ 0); the (q + 1)-th starts.
        let mut q = 0u64;
        if x > 0 {
            let (x, inc) = (x as u64, inc as u64);
            let top = (inc.leading_zeros() + 1).saturating_sub(x.leading_zeros());
            for b in (0..top).rev() {
                // c < 2^top ≤ 2^(65 − len(inc) − lz(x)): c·inc < 2^64, no overflow.
                let c = q | 1 << b;
                if c * inc < x {
                    q = c;
                }
            }
        }
        let q = q as i64;
        self.dec_at = first + q;
        self.dec_jump = (x - q * inc).max(0);
        true
    }

    /// Long-axis steps to where the pass must be at rest, when it decelerates in
    /// this leg (no next leg, or a last one continuing the same motion).
    fn decel_left(&self) -> Option<i64> {
        match self.next {
            None => Some(self.delta - self.p),
            Some(n) if self.next_last && n.same_motion => Some(self.delta - self.p + n.len),
            Some(_) => None,
        }
    }

    /// [`Gear::ramp_down_jump`] in the ramp zone, `left` steps from the end. The
    /// distance to the deceleration start is computed once, then follows by one
    /// subtraction a count (`rem` drops by `inc`, `w·R²` grows by `dw·R²`). Out of
    /// line: the locked count's fast path stays small.
    #[inline(never)]
    fn near_end(&mut self, left: i64, inc: i64) -> Option<i64> {
        if self.to_start.is_none() {
            self.to_start = self.exact_to_start(left);
        }
        let Some((x, step)) = self.to_start else { return self.exact_jump(left, inc) };
        match x.checked_sub(inc).and_then(|v| v.checked_sub(step)) {
            Some(after) if after > 0 => {
                self.to_start = Some((after, step));
                None
            }
            Some(_) => {
                self.to_start = None;
                Some(x.max(0))
            }
            None => {
                self.to_start = None;
                self.exact_jump(left, inc)
            }
        }
    }

    /// `unit·left − now − w·R²` and `dw·R²`, if they fit the fast test.
    #[inline(never)]
    fn exact_to_start(&self, left: i64) -> Option<(i64, i64)> {
        let r2 = i128::from(self.ramp) * i128::from(self.ramp);
        let now = i128::from(self.acc - self.unit / 2);
        let x = i128::from(self.unit) * i128::from(left) - now - i128::from(self.w) * r2;
        Some((i64::try_from(x).ok()?, i64::try_from(i128::from(self.dw) * r2).ok()?))
    }

    /// The deceleration test in 128 bits, from scratch.
    #[inline(never)]
    fn exact_jump(&self, left: i64, inc: i64) -> Option<i64> {
        let r2 = i128::from(self.ramp) * i128::from(self.ramp);
        let w = i128::from(self.w);
        let rem = i128::from(self.unit) * i128::from(left) - i128::from(self.acc - self.unit / 2);
        (rem - i128::from(inc) <= (w + i128::from(self.dw)) * r2).then(|| (rem - w * r2).max(0) as i64)
    }

    /// Adds `inc` units to the long axis's exact position; moves whole steps. Out
    /// of line: its step and leg change would be copied into every caller.
    #[inline(never)]
    fn add(&mut self, inc: i64) -> bool {
        self.acc += inc;
        let mut moved = false;
        while self.acc >= self.unit {
            self.acc -= self.unit;
            self.step(1);
            moved = true;
        }
        while self.acc < 0 {
            self.acc += self.unit;
            self.step(-1);
            moved = true;
        }
        moved
    }

    /// One long-axis step along the leg (or back), with its follower; at the end of
    /// a thread leg the announced next leg takes over.
    fn step(&mut self, dir: i64) {
        self.p += dir;
        if let Some((_, _, f)) = &mut self.follower {
            if dir > 0 { f.up() } else { f.down() }
        }
        if self.mode == Mode::Thread && self.p >= self.delta && self.next.is_some() {
            self.take_next();
        }
    }

    /// The announced leg takes over: the state goes to the common denominator
    /// (multiplications only) and, while locked, the speed goes on from the lead
    /// reached (`keep_lead`: the running leg's next increment less its own half
    /// change plus the new one's) or starts at the new leg's own lead.
    #[inline(never)]
    fn take_next(&mut self) {
        let Some(n) = self.next.take() else { return };
        self.legs_done += 1;
        let s = n.scale;
        if s != 1 {
            self.acc *= s;
            self.unit *= s;
            self.w *= s;
        }
        if matches!(self.phase, Phase::Locked) {
            let g = &n.gearing;
            self.w = if n.keep_lead { self.w - self.gearing.n2 * s + g.n2 } else { g.n1 + g.n2 };
            self.dw = 2 * g.n2;
        }
        self.gearing = n.gearing;
        self.ramp_zone = n.ramp_zone;
        self.end_speed = n.end_speed;
        self.set_leg(n.leg);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const CPR: u32 = 4_096;

    /// Z from 0 to -`len` steps (the long axis), X from 0 to `x` steps.
    fn leg(len: i64, x: i64) -> Leg {
        Leg { start: [0; AXIS_COUNT], end: [x, 0, -len, 0], long: 2 }
    }

    /// Runs `g` count by count from `from` to `to` (raw counts); returns (count, Z, X)
    /// after every count.
    fn run(g: &mut Gear, from: i64, to: i64) -> std::vec::Vec<(i64, i64, i64)> {
        let mut out = std::vec::Vec::new();
        let mut pos = [0; AXIS_COUNT];
        let step = if to >= from { 1 } else { -1 };
        let mut c = from;
        while c != to {
            c += step;
            g.on_count(c);
            g.positions(&mut pos);
            out.push((c, pos[2], pos[0]));
        }
        out
    }

    /// Drives `a` with every raw count of `path` and `b` only at the counts its
    /// [`Gear::glide`] names (as the encoder compare does; with `late`, only at
    /// every `late`-th count of the path, as an interrupt held up would); `hook`
    /// runs on both after each count (an announcement from the period). Asserts
    /// that both put the axes at the same place after every count `b` has seen, and
    /// that what `b` names next is never a count already reached. Returns how many
    /// counts `b` took.
    fn same_as_every_count(
        a: &mut Gear,
        b: &mut Gear,
        path: impl IntoIterator<Item = i64>,
        late: usize,
        mut hook: impl FnMut(i64, &mut Gear),
    ) -> usize {
        let (mut pa, mut pb) = ([0; AXIS_COUNT], [0; AXIS_COUNT]);
        let mut due = b.glide();
        let mut taken = 0;
        for (k, c) in path.into_iter().enumerate() {
            a.on_count(c);
            if due.reached(c) && k % late.max(1) == 0 {
                b.on_count(c);
                due = b.glide();
                taken += 1;
                assert!(!due.reached(c), "count {c}: due again at once ({due:?})");
            }
            hook(c, a);
            hook(c, b);
            due = b.glide();
            if k % late.max(1) == 0 {
                a.positions(&mut pa);
                b.positions(&mut pb);
                assert_eq!(pa, pb, "count {c}");
            }
        }
        assert_eq!(a.phase(), b.phase());
        taken
    }

    fn up(from: i64, to: i64) -> impl Iterator<Item = i64> {
        from..=to
    }

    #[test]
    fn gliding_steps_at_exactly_the_counts_every_count_would() {
        let ratio = Ratio { n: 5, d: 32 };
        let g34 = Gearing::new(2_000_000, 100_000, 1, 3_125, CPR).unwrap();
        let shrinking = Gearing::new(2_000_000, -20_000, 1, 3_125, CPR).unwrap();
        let coarse = Gearing::new(6_000_000, 0, 1, 3_125, CPR).unwrap();
        // 0.05 mm: 256 counts a step; a G34 on an odd scale whose numbers are too
        // big for the glide's products (the counts go one by one).
        let fine = Gearing::new(50_000, 0, 1, 3_125, CPR).unwrap();
        let odd = Gearing::new(1_234_567, 7_654, 7, 3_331, CPR).unwrap();
        assert!(odd.den > 1 << 30, "{odd:?}");
        for (name, gearing, ramp, x) in [
            ("fine lead", fine, 20_000, 0),
            ("G34 with a huge denominator", odd, 30_000, 0),
            ("constant lead", Gearing::from(ratio), 2_000, 0),
            ("taper", Gearing::from(ratio), 400, 1_000),
            ("G34 growing", g34, 2_000, 3_000),
            ("G34 shrinking", shrinking, 8_000, 0),
            ("6 mm lead: more than a step some counts", coarse, 30_000, -500),
        ] {
            for late in [1, 3] {
                let len = if name == "fine lead" { 400 } else { 20_000 };
                let mut a = Gear::thread(leg(len, x), gearing, ramp, 1, 5_000).unwrap();
                let mut b = a;
                let taken = same_as_every_count(&mut a, &mut b, up(4_000, 500_000), late, |_, _| {});
                assert_eq!(a.phase(), Phase::Done, "{name}");
                let mut end = [0; AXIS_COUNT];
                b.positions(&mut end);
                assert_eq!((end[2], end[0]), (-len, x), "{name}");
                // A step (or a change of phase) at each count taken, few others.
                // (the fine lead: and a checkpoint every GLIDE_MAX counts of its ramps)
                assert!(taken <= len as usize + x.unsigned_abs() as usize + 40, "{name}: {taken} counts taken");
                assert_eq!(b.glide(), Due::NONE, "{name}: nothing more falls due");
            }
        }
    }

    #[test]
    fn the_deceleration_found_once_starts_where_the_test_at_every_count_would() {
        // Before each count of a constant lead's ramp zone, the 128-bit test from
        // scratch (what ran at every count before the start was found once) says
        // whether this count starts the deceleration and with which increment.
        let coarse = Gearing::new(6_000_000, 0, 1, 3_125, CPR).unwrap();
        let fine = Gearing::new(50_000, 0, 1, 3_125, CPR).unwrap();
        let lead_1_5 = Gearing::new(1_500_000, 0, 1, 3_125, CPR).unwrap();
        let mut starts = 0;
        for (gearing, ramp, len) in [
            (Gearing::from(Ratio { n: 5, d: 32 }), 2_000, 20_000),
            (lead_1_5, 35_066, 14_400),
            (lead_1_5, 2, 300),
            (coarse, 30_000, 20_000),
            (fine, 20_000, 400),
        ] {
            for start in [0, 5_000, 77] {
                let mut g = Gear::thread(leg(len, 0), gearing, ramp, 1, start).unwrap();
                let mut c = start;
                while g.phase() != Phase::Done {
                    c += 1;
                    let before = g;
                    let expect = match (before.phase, before.decel_left()) {
                        (Phase::Locked, Some(left)) if left <= before.ramp_zone => {
                            before.exact_jump(left, before.two_r * before.w)
                        }
                        _ => None,
                    };
                    g.on_count(c);
                    if let Some(jump) = expect {
                        let mut old = before;
                        old.m_max += 1;
                        old.phase = Phase::RampDown { u: old.ramp };
                        old.add(jump);
                        assert_eq!((g.phase, g.acc, g.p), (old.phase, old.acc, old.p), "ramp {ramp}, count {c}");
                        starts += 1;
                    } else if before.phase == Phase::Locked {
                        assert_eq!(g.phase, Phase::Locked, "ramp {ramp}, count {c}: started early");
                    }
                }
            }
        }
        assert_eq!(starts, 15);
    }

    #[test]
    fn gliding_a_reversed_encoder_names_the_count_below() {
        // Forward rotation counts down (sigma −1): the due count is below.
        let ratio = Ratio { n: 5, d: 32 };
        let mut a = Gear::thread(leg(6_400, 0), ratio, 1_000, -1, -2_000).unwrap();
        let mut b = a;
        let due = b.glide();
        assert_eq!(due, Due::new(None, Some(-2_001)));
        same_as_every_count(&mut a, &mut b, (-120_000..=-1_000).rev(), 1, |_, _| {});
        assert_eq!(b.phase(), Phase::Done);
    }

    #[test]
    fn a_thread_ignores_counts_back_and_goes_on_where_it_was() {
        let ratio = Ratio { n: 5, d: 32 };
        let mut a = Gear::thread(leg(6_400, 0), ratio, 1_000, 1, 0).unwrap();
        let mut b = a;
        // Forward, back 300 counts (a spindle that jerked back), forward again.
        let path = (1..=20_000).chain((19_700..20_000).rev()).chain(19_700..=60_000);
        same_as_every_count(&mut a, &mut b, path, 1, |_, _| {});
        assert_eq!(b.phase(), Phase::Done);
    }

    #[test]
    fn a_leg_announced_while_gliding_is_taken_as_count_by_count() {
        // The next leg is announced at a count the glide may already have passed
        // (the period's announcement comes at any count): a continuation, a short
        // pull-out sharing the deceleration, and a G34 continued at the lead reached.
        let ratio = Ratio { n: 5, d: 32 };
        let g34 = Gearing::new(2_000_000, 100_000, 1, 3_125, CPR).unwrap();
        let first = leg(8_000, 0);
        let cases = [
            (Gearing::from(ratio), Leg { start: first.end, end: [800, 0, -16_000, 0], long: 2 }, true, false),
            (Gearing::from(ratio), Leg { start: first.end, end: [80, 0, -8_100, 0], long: 2 }, true, false),
            (g34, Leg { start: first.end, end: [0, 0, -20_000, 0], long: 2 }, true, true),
            (Gearing::from(ratio), Leg { start: first.end, end: [0, -900, -14_000, 0], long: 2 }, false, false),
        ];
        for (k, (gearing, next, last, keep)) in cases.into_iter().enumerate() {
            for at in [3_000, 20_001, 37_777, 47_000] {
                let mut a = Gear::thread(first, gearing, 400, 1, 0).unwrap();
                let mut b = a;
                let announce = |c: i64, g: &mut Gear| {
                    if c == at {
                        let _ = g.set_next(next, gearing, last, keep);
                    }
                };
                same_as_every_count(&mut a, &mut b, up(1, 300_000), 1, announce);
                assert_eq!(a.legs_done(), b.legs_done(), "case {k} at {at}");
            }
        }
    }

    #[test]
    fn a_tap_glides_both_ways_without_applying_anything_ahead() {
        let ratio = Ratio::new(1_500_000, 1, 3_125, CPR).unwrap();
        let way_in = leg(3_200, 400);
        let mut a = Gear::tap(way_in, ratio, 1, 500).unwrap();
        let mut b = a;
        // In, a jitter around the bottom, out (the spindle reverses), with back
        // and forth on the way.
        let path = (501..=28_000)
            .chain((27_000..28_000).rev())
            .chain(27_000..=27_900)
            .chain((27_890..27_900).rev())
            .chain(27_890..=27_895)
            .chain((500..27_895).rev());
        same_as_every_count(&mut a, &mut b, path, 1, |_, _| {});
        let mut end = [0; AXIS_COUNT];
        b.positions(&mut end);
        assert_eq!((end[2], end[0]), (0, 0));
        // The due counts are those of the next step either way.
        let due = b.glide();
        let (u, d) = (due.up().unwrap(), due.down().unwrap());
        let mut probe = b;
        assert!((501..u).all(|c| !probe.on_count(c)) && probe.on_count(u));
        let mut probe = b;
        assert!((d + 1..500).rev().all(|c| !probe.on_count(c)) && probe.on_count(d));
    }

    #[test]
    fn the_glide_search_finds_what_counting_one_by_one_finds() {
        // Runs of every shape the gearbox makes: constant, growing (ramp-up, G34),
        // shrinking (the deceleration), near the end (a distance that must stay
        // positive), each from every hint.
        let mut rng = canon::xorshift::XorShift::new(22);
        let mut next = || rng.next_u64();
        let mut searched = [0; 2];
        for k in 0..3_000 {
            let most = 1 + (next() % u64::from(GLIDE_MAX)) as u32;
            let a = (next() % 200_000) as i64;
            let d = (next() % 2_000) as i64 - if k % 2 == 0 { 0 } else { 1_000 };
            let room = 1 + (next() % 50_000_000) as i64;
            let end = (k % 3 == 0).then(|| ((next() % 60_000_000) as i64, (next() % 3_000) as i64));
            let r = Run { room, a, d, most, end };
            let (n, sum) = r.one_by_one();
            if r.monotone() {
                searched[usize::from(end.is_some())] += 1;
                for hint in [0, n.saturating_sub(1), n, n + 1, most / 2, most] {
                    assert_eq!(r.search(hint), n, "{k}: hint {hint}");
                }
                assert_eq!(r.sum(n), sum);
            }
        }
        assert!(searched[0] > 1_000 && searched[1] > 500, "{searched:?}");
    }

    #[test]
    fn dues_merge_to_the_nearer_count_each_way() {
        let a = Due::new(Some(10), None);
        let b = Due::new(Some(7), Some(-3));
        assert_eq!(a.merge(b), b);
        assert_eq!((a.up(), a.down()), (Some(10), None));
        assert_eq!(Due::NONE.merge(a), a);
        assert!(b.reached(7) && b.reached(-3) && !b.reached(0));
        assert_eq!(Due::forward(-1, 100, Some(5), Some(-2)), Due::new(Some(-98), Some(-105)));
    }

    #[test]
    fn ratio_is_exact_and_reduced() {
        // 2 mm lead, 320 steps/mm, 4096 counts: 640 steps per 4096 counts = 5/32.
        assert_eq!(Ratio::new(2_000_000, 1, 3_125, CPR).unwrap(), Ratio { n: 5, d: 32 });
        assert!(Ratio::new(0, 1, 3_125, CPR).is_err());
    }

    #[test]
    fn after_the_ramp_the_phase_does_not_depend_on_the_ramp_length() {
        let ratio = Ratio { n: 5, d: 32 };
        let sync = 10_000; // raw count of index + Q
        let mut reference = None;
        for ramp in [100, 2_000, 18_000] {
            let start = sync - ramp / 2;
            let mut g = Gear::thread(leg(6_400, 0), ratio, ramp, 1, start).unwrap();
            let trace = run(&mut g, start - 50, sync + 60_000);
            // Everything after the ramp lies on round((c - sync)·N/D).
            for &(c, z, _) in trace.iter().filter(|t| t.0 > start + ramp && -t.1 < 6_400 - 2_000) {
                let ideal = ((c - sync) as f64 * 5.0 / 32.0).round() as i64;
                assert_eq!(-z, ideal, "ramp {ramp} count {c}");
            }
            // The count at which Z reaches -3000 steps is the same for every ramp.
            let at = trace.iter().find(|t| t.1 == -3_000).unwrap().0;
            assert_eq!(*reference.get_or_insert(at), at, "ramp {ramp}");
            // The pass ends exactly on the end point, at rest.
            assert_eq!(trace.last().unwrap().1, -6_400);
            assert_eq!(g.phase(), Phase::Done);
        }
    }

    #[test]
    fn the_ramp_accelerates_evenly_in_counts() {
        let ratio = Ratio { n: 5, d: 32 };
        let mut g = Gear::thread(leg(6_400, 0), ratio, 1_000, 1, 0).unwrap();
        let trace = run(&mut g, 0, 1_000);
        // z(m) = N m² / (2 R D), rounded.
        for &(m, z, _) in &trace {
            let ideal = (5.0 * (m * m) as f64 / (2.0 * 1_000.0 * 32.0)).round() as i64;
            assert!((-z - ideal).abs() <= 1, "m {m}: {z} vs {ideal}");
        }
        assert_eq!(g.phase(), Phase::Locked);
    }

    #[test]
    fn a_taper_follows_the_long_axis_within_a_step() {
        let ratio = Ratio { n: 5, d: 32 };
        let mut g = Gear::thread(leg(6_400, 1_000), ratio, 400, 1, 0).unwrap();
        let trace = run(&mut g, 0, 50_000);
        for &(_, z, x) in &trace {
            let ideal = -z as f64 * 1_000.0 / 6_400.0;
            assert!((x as f64 - ideal).abs() <= 0.51, "{z} {x}");
        }
        assert_eq!(trace.last().map(|t| (t.1, t.2)), Some((-6_400, 1_000)));
    }

    #[test]
    fn a_continuing_leg_takes_over_without_resynchronising() {
        let ratio = Ratio { n: 5, d: 32 };
        let first = leg(3_200, 0);
        let second = Leg { start: first.end, end: [800, 0, -6_400, 0], long: 2 };
        let mut g = Gear::thread(first, ratio, 200, 1, 0).unwrap();
        g.set_next(second, ratio, true, false).unwrap();
        let trace = run(&mut g, 0, 60_000);
        assert_eq!(g.legs_done(), 1);
        // The lead is continuous across the junction: Z keeps N/D per count.
        for &(c, z, _) in trace.iter().filter(|t| t.0 > 200 && -t.1 < 6_000) {
            let ideal = ((c - 100) as f64 * 5.0 / 32.0).round() as i64;
            assert_eq!(-z, ideal, "count {c}");
        }
        assert_eq!(trace.last().map(|t| (t.1, t.2)), Some((-6_400, 800)));
    }

    #[test]
    fn a_short_pull_out_shares_the_deceleration_and_ends_exactly() {
        // Ramp of 4000 counts: 5/32 × 4000 / 2 = 312 steps to stop; the pull-out has 100.
        let ratio = Ratio { n: 5, d: 32 };
        let first = leg(400, 0);
        let pull = Leg { start: first.end, end: [80, 0, -500, 0], long: 2 };
        let mut g = Gear::thread(first, ratio, 4_000, 1, 0).unwrap();
        assert_eq!(g.set_next(pull, ratio, true, false), Err(AlarmKind::ThreadRampTooLong), "ramps need 626 steps");
        let first = leg(6_400, 0);
        let pull = Leg { start: first.end, end: [80, 0, -6_500, 0], long: 2 };
        let mut g = Gear::thread(first, ratio, 4_000, 1, 0).unwrap();
        g.set_next(pull, ratio, true, false).unwrap();
        let trace = run(&mut g, 0, 80_000);
        assert_eq!(g.phase(), Phase::Done);
        assert_eq!(trace.last().map(|t| (t.1, t.2)), Some((-6_500, 80)));
        // It slowed down smoothly: never more than one step per count, never backwards.
        for w in trace.windows(2) {
            assert!((0..=1).contains(&(w[0].1 - w[1].1)), "{:?}", w);
        }
    }

    #[test]
    fn a_g34_gearing_is_f_theta_plus_k_theta_squared_over_two() {
        // F 4 mm, K 0.2 mm/rev per rev on 3.125 µm steps, 4096 counts:
        // steps(c) = (163840·c + c²) / 524288.
        let g = Gearing::new(4_000_000, 200_000, 1, 3_125, CPR).unwrap();
        assert_eq!(g, Gearing { n1: 163_840, n2: 1, den: 524_288 });
        // One revolution: z(1) = F + K/2 = 4.1 mm = 1312 steps; ten: 40 + 10 mm.
        let z = |c: i64| (g.n1 * c + g.n2 * c * c) as f64 / g.den as f64;
        assert_eq!(z(4_096), 1_312.0);
        assert_eq!(z(40_960), 16_000.0);
        // A constant lead is the reduced ratio.
        let c = Gearing::new(2_000_000, 0, 1, 3_125, CPR).unwrap();
        assert_eq!(c, Gearing::from(Ratio::new(2_000_000, 1, 3_125, CPR).unwrap()));
        assert_eq!(Gearing::new(0, 100, 1, 3_125, CPR), Err(AlarmKind::FeedZero));
    }

    /// Exact position `round((n1·c + n2·c²)/den)` (halves up) of gearing `g` at count `c`.
    fn ideal(g: &Gearing, c: i64) -> i64 {
        let num = 2 * (i128::from(g.n1) * i128::from(c) + i128::from(g.n2) * i128::from(c) * i128::from(c));
        (num + i128::from(g.den)).div_euclid(2 * i128::from(g.den)) as i64
    }

    #[test]
    fn a_g34_pass_is_exact_after_the_ramp_at_any_ramp_length_and_ends_on_its_end_point() {
        // F 2 mm, K ±0.1 mm/rev per rev, 20000 steps (62.5 mm) of Z.
        for k in [100_000, -20_000] {
            let g = Gearing::new(2_000_000, k, 1, 3_125, CPR).unwrap();
            let sync = 10_000;
            let mut reference = None;
            for ramp in [100, 2_000, 8_000] {
                let start = sync - ramp / 2;
                let mut gear = Gear::thread(leg(20_000, 3_000), g, ramp, 1, start).unwrap();
                let trace = run(&mut gear, start - 50, sync + 200_000);
                for &(c, z, _) in trace.iter().filter(|t| t.0 > start + ramp && -t.1 < 20_000 - 1_500) {
                    assert_eq!(-z, ideal(&g, c - sync), "K {k} ramp {ramp} count {c}");
                }
                let at = trace.iter().find(|t| t.1 == -10_000).unwrap().0;
                assert_eq!(*reference.get_or_insert(at), at, "K {k} ramp {ramp}");
                // Never backwards, never more than a step per count; on the end point.
                assert!(trace.windows(2).all(|w| (0..=1).contains(&(w[0].1 - w[1].1))));
                assert_eq!(trace.last().map(|t| (t.1, t.2)), Some((-20_000, 3_000)));
                assert_eq!(gear.phase(), Phase::Done);
            }
        }
    }

    #[test]
    fn a_g34_ramp_has_its_linear_part_only_before_the_synchronised_start() {
        let g = Gearing::new(2_000_000, 400_000, 1, 3_125, CPR).unwrap();
        let mut gear = Gear::thread(leg(20_000, 0), g, 1_000, 1, 0).unwrap();
        let trace = run(&mut gear, 0, 1_000);
        // m ≤ R/2: n1·m²/(2R·den); after it the quadratic part adds n2·(m − R/2)²/den.
        for &(m, z, _) in &trace {
            let c = (m - 500).max(0) as f64;
            let exact = (g.n1 as f64 * (m * m) as f64 / 2_000.0 + g.n2 as f64 * c * c) / g.den as f64;
            assert!((-z as f64 - exact).abs() <= 0.5 + 1e-9, "m {m}: {z} vs {exact}");
        }
        assert_eq!(gear.phase(), Phase::Locked);
    }

    #[test]
    fn a_lead_that_would_reach_zero_is_alarm_0014() {
        // F 1 mm, K -0.1 mm: after 5 mm the lead is zero; the leg is 10 mm.
        let g = Gearing::new(1_000_000, -100_000, 1, 3_125, CPR).unwrap();
        assert_eq!(Gear::thread(leg(3_200, 0), g, 100, 1, 0), Err(AlarmKind::IllegalLead));
        let mut gear = Gear::thread(leg(320, 0), g, 100, 1, 0).unwrap();
        let next = Leg { start: leg(320, 0).end, end: [0, 0, -3_200, 0], long: 2 };
        assert_eq!(gear.set_next(next, g, true, true), Err(AlarmKind::IllegalLead));
    }

    #[test]
    fn blocks_after_a_g34_continue_from_the_lead_reached() {
        let g = Gearing::new(2_000_000, 100_000, 1, 3_125, CPR).unwrap();
        let first = leg(8_000, 0);
        let second = Leg { start: first.end, end: [0, 0, -20_000, 0], long: 2 };
        // The same K: one exact parabola across the junction.
        let mut gear = Gear::thread(first, g, 400, 1, -200).unwrap();
        gear.set_next(second, g, true, true).unwrap();
        let trace = run(&mut gear, -200, 200_000);
        assert_eq!(gear.legs_done(), 1);
        for &(c, z, _) in trace.iter().filter(|t| t.0 > 200 && -t.1 < 19_000) {
            assert_eq!(-z, ideal(&g, c), "count {c}");
        }
        assert_eq!(trace.last().unwrap().1, -20_000);
        // A constant lead after it (another denominator): the lead it had reached.
        let constant = Gearing::new(2_000_000, 0, 1, 3_125, CPR).unwrap();
        assert_ne!(constant.den, g.den);
        let mut gear = Gear::thread(first, g, 400, 1, -200).unwrap();
        gear.set_next(second, constant, true, true).unwrap();
        let trace = run(&mut gear, -200, 200_000);
        let cj = trace.iter().find(|t| t.1 == -8_000).unwrap().0;
        let slope = (g.n1 + 2 * g.n2 * cj) as f64 / g.den as f64;
        for &(c, z, _) in trace.iter().filter(|t| t.0 > 200 && -t.1 < 19_000) {
            let exact = if c <= cj {
                ideal(&g, c) as f64
            } else {
                (g.n1 * cj + g.n2 * cj * cj) as f64 / g.den as f64 + slope * (c - cj) as f64
            };
            assert!((-z as f64 - exact).abs() <= 1.0, "count {c}: {z} vs {exact}");
        }
        assert_eq!(trace.last().unwrap().1, -20_000);
        assert_eq!(gear.phase(), Phase::Done);
    }

    #[test]
    fn a_tap_is_locked_both_ways_and_returns_exactly() {
        // 1.5 mm lead on Z at 320 steps/mm: 480 steps per 4096 counts = 15/128.
        let ratio = Ratio::new(1_500_000, 1, 3_125, CPR).unwrap();
        let way_in = leg(3_200, 0);
        let mut g = Gear::tap(way_in, ratio, 1, 500).unwrap();
        let trace = run(&mut g, 500, 500 + 27_400);
        for &(c, z, _) in &trace {
            assert_eq!(-z, ((c - 500) as f64 * 15.0 / 128.0).round() as i64);
        }
        assert!(g.finished(), "at the bottom (and 12 steps past it)");
        let out = Leg { start: way_in.end, end: way_in.start, long: 2 };
        g.way_out(&out).unwrap();
        assert!(!g.finished());
        let back = run(&mut g, 500 + 27_400, 500);
        for &(c, z, _) in &back {
            assert_eq!(-z, ((c - 500) as f64 * 15.0 / 128.0).round() as i64);
        }
        assert!(g.finished());
        assert_eq!(back.last().unwrap().1, 0);
        assert!(g.way_out(&leg(100, 0)).is_err());
    }
}

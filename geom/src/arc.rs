//! Arc centres and extents. Coordinates are the plane's two axes `(a, b)` in the
//! order of [`canon::Plane::axes`], so G02 is clockwise with `a` right, `b` up.

use canon::alarm::AlarmKind;
use canon::units::{f32_of, f64_of_u128, sqrt_u64};

/// A point in a plane, nanometres.
pub type P2 = (i64, i64);

/// Centre of an arc of radius `r` from `start` to `end` (2.3 note 6: `r < 0` takes
/// the arc of more than 180°). A chord longer than `2|r|` by no more than `tol`
/// gives a half circle; longer still raises alarm 0020.
///
/// The chord² and `(2h)² = 4r² − chord²` (h: centre to chord) are exact integers,
/// so the tolerance test is exact and a near half circle loses nothing to
/// cancellation; one division and one square root in f64 then give `h / chord`,
/// and the centre is rounded to whole nanometres.
pub fn center_from_radius(start: P2, end: P2, r: i64, cw: bool, tol: i64) -> Result<P2, AlarmKind> {
    // Every square below is under 2^126 and every sum under 2^128: no overflow.
    // (Differences saturate at ±2^63 nm, radii at 2^62 nm: far beyond any machine.)
    const CAP: u64 = 1 << 62;
    let (da, db) = (end.0.saturating_sub(start.0), end.1.saturating_sub(start.1));
    let sq = |v: u64| u128::from(v) * u128::from(v);
    let c2 = sq(da.unsigned_abs()) + sq(db.unsigned_abs());
    let radius = r.unsigned_abs().min(CAP);
    let reach = i128::from(radius) + i128::from(tol);
    // Alarm when half the chord exceeds the radius by more than `tol`.
    if reach < 0 || c2 > 4 * sq(reach.min(i128::from(CAP)) as u64) {
        let excess = libm::sqrt(f64_of_u128(c2)) / 2.0 - radius as f64;
        return Err(AlarmKind::ArcRadiusTolerance { excess_nm: excess as i64 });
    }
    let disc = (4 * sq(radius)).saturating_sub(c2);
    // s = 2h / chord; the centre is the chord's middle plus s/2 times the chord
    // turned a quarter: (db, −da) to the right of it.
    let s = super::sqrt::sqrt(f64_of_u128(disc) / f64_of_u128(c2));
    // Clockwise arcs of up to 180° have their centre to the right of the chord.
    let right = cw == (r > 0);
    let (na, nb) = if right { (db, da.wrapping_neg()) } else { (db.wrapping_neg(), da) };
    Ok((
        half_sum(start.0, da, na, s).unwrap_or_else(|| half_sum_f64(start.0, da, na, s)),
        half_sum(start.1, db, nb, s).unwrap_or_else(|| half_sum_f64(start.1, db, nb, s)),
    ))
}

/// `round(p + (d + s·n) / 2)`, half away from zero, exactly (`s` as the f64 it is,
/// `s ≥ 0`): `s` is its 53-bit mantissa `m` over `2^sh`, so with `n·m = A·2^sh + B`
/// (`0 ≤ B < 2^sh`) the sum is `(U + B/2^sh)/2` for the integer `U = 2p + d + A`,
/// and since `B/2^sh < 1` its rounding depends only on `U` and whether `B` is 0 —
/// one 128-bit product and one shift, no soft-float arithmetic. `None` for `s`
/// beyond 2^-120..2^52 (then [`half_sum_f64`]).
fn half_sum(p: i64, d: i64, n: i64, s: f64) -> Option<i64> {
    let (m, sh) = mantissa_shift(s)?;
    if !(0..=120).contains(&sh) {
        return None;
    }
    // |n|·m as a 64 × 64 → 128-bit unsigned product (four multiplies on the M4;
    // the signed 128-bit product is a full 128 × 128 multiplication), then signed.
    let t = (u128::from(n.unsigned_abs()) * u128::from(m)) as i128;
    let t = if n < 0 { -t } else { t };
    // |U| < 2^65 + 2^116: no overflow.
    let u = 2 * i128::from(p) + i128::from(d) + (t >> sh);
    let q = if u >= 0 {
        (u + 1) >> 1
    } else if t.trailing_zeros() >= sh as u32 {
        -((1 - u) >> 1)
    } else {
        -((-u) >> 1)
    };
    Some(q.clamp(i128::from(i64::MIN), i128::from(i64::MAX)) as i64)
}

/// `s ≥ 0` as `m / 2^sh`: its 53-bit mantissa and the power of two it is divided
/// by (`None` for an infinity or NaN).
fn mantissa_shift(s: f64) -> Option<(u64, i32)> {
    let bits = s.to_bits();
    let exp = ((bits >> 52) & 0x7ff) as i32;
    match exp {
        0 => Some((bits & ((1 << 52) - 1), 1074)),
        0x7ff => None,
        _ => Some(((bits & ((1 << 52) - 1)) | 1 << 52, 1075 - exp)),
    }
}

/// [`half_sum`] in f64 (how it was computed before), for what does not fit in 128
/// bits: coordinates near 2^63 nm or `s` beyond 2^-120..2^52.
#[cold]
#[inline(never)]
fn half_sum_f64(p: i64, d: i64, n: i64, s: f64) -> i64 {
    libm::round(p as f64 + d as f64 / 2.0 + s / 2.0 * n as f64) as i64
}

/// Centre from I/J/K offsets; the end point must lie on the circle within `tol`
/// (alarm 0020 otherwise).
pub fn center_from_offsets(start: P2, end: P2, off: P2, tol: i64) -> Result<P2, AlarmKind> {
    let c = (start.0.saturating_add(off.0), start.1.saturating_add(off.1));
    let rs = dist(start, c);
    let re = dist(end, c);
    let diff = (rs - re).abs();
    if diff > tol as f64 {
        return Err(AlarmKind::ArcRadiusTolerance { excess_nm: diff as i64 });
    }
    Ok(c)
}

fn dist(p: P2, q: P2) -> f64 {
    norm((p.0 - q.0) as f64, (p.1 - q.1) as f64)
}

/// `√(a² + b²)` without `hypot`'s care for overflow and the last ulp, which cost
/// ~40 soft-float operations on the Cortex-M4: lengths here are at most a few
/// metres in nm (< 2^43), their squares far from f64's range, and the results are
/// rounded to whole nanometres.
fn norm(a: f64, b: f64) -> f64 {
    libm::sqrt(a * a + b * b)
}

/// `|p − q|` rounded to whole nanometres: the squares summed exactly in 128 bits,
/// then rounded exactly by an integer root below 2^64 nm² (4.29 m; what
/// `round(dist(p, q))` gives, without its roundings), else one f64 square root.
fn radius_nm(p: P2, q: P2) -> i64 {
    let sq = |v: u64| u128::from(v) * u128::from(v);
    let d2 = sq(p.0.abs_diff(q.0)) + sq(p.1.abs_diff(q.1));
    match u64::try_from(d2) {
        Ok(x) => sqrt_u64(x).0 as i64,
        Err(_) => libm::round(libm::sqrt(f64_of_u128(d2))) as i64,
    }
}

/// Bounding box of a path in the plane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Extents {
    /// Smallest and largest `a`.
    pub a: (i64, i64),
    /// Smallest and largest `b`.
    pub b: (i64, i64),
}

/// Bounding box of the arc from `start` to `end` around `center`: the end points
/// plus every quadrant point (0°, 90°, 180°, 270°) the arc passes.
pub fn arc_extents(start: P2, end: P2, center: P2, cw: bool, full: bool) -> Extents {
    let e = Extents { a: (start.0.min(end.0), start.0.max(end.0)), b: (start.1.min(end.1), start.1.max(end.1)) };
    let rel = |p: P2| (p.0.wrapping_sub(center.0), p.1.wrapping_sub(center.1));
    if !full && inside_one_quadrant(rel(start), rel(end), cw) {
        return e;
    }
    by_quarter_turns(e, start, end, center, cw, full)
}

/// [`arc_extents`] from the end points' box `e`, with the quadrant points passed
/// found by the ends' pseudo-angles in f32.
fn by_quarter_turns(e: Extents, start: P2, end: P2, center: P2, cw: bool, full: bool) -> Extents {
    let rel = |p: P2| (p.0.wrapping_sub(center.0), p.1.wrapping_sub(center.1));
    let (s, t) = (pseudo_angle(rel(start)), pseudo_angle(rel(end)));
    // Sweep counter-clockwise from `from` to `to`, in quarter turns.
    let (from, to) = if cw { (t, s) } else { (s, t) };
    let mut sweep = wrap4(to - from);
    if full || sweep == 0.0 {
        sweep = 4.0;
    }
    // Which quadrant points the arc passes (bit q: the point at q quarter turns),
    // decided in f32 alone; short arcs mostly pass none, and then neither the
    // radius (a square root) nor the loop below is paid.
    let mut passed = 0u8;
    for q in 0..4u8 {
        if wrap4(f32::from(q) - from) <= sweep {
            passed |= 1 << q;
        }
    }
    if passed == 0 {
        return e;
    }
    with_quadrant_points(e, start, center, passed)
}

/// `e` grown by the quadrant points in `passed` (bit q: the point at q quarter
/// turns) of the circle around `center` through `start`.
#[inline(never)]
fn with_quadrant_points(mut e: Extents, start: P2, center: P2, passed: u8) -> Extents {
    let r = radius_nm(start, center);
    for (q, (da, db)) in [(1, 0), (0, 1), (-1, 0), (0, -1)].into_iter().enumerate() {
        if passed & (1 << q) != 0 {
            let (pa, pb) = (center.0 + da * r, center.1 + db * r);
            e.a = (e.a.0.min(pa), e.a.1.max(pa));
            e.b = (e.b.0.min(pb), e.b.1.max(pb));
        }
    }
    e
}

/// Whether the arc from `s` to `t` (both relative to the centre) stays inside one
/// open quadrant: both off the axes in the same quadrant, and the arc going the
/// short way from one to the other (clockwise if `cw`), decided exactly by the
/// sign of the cross product in integers (|s×t| < 2^62: no overflow). Such an arc passes no quadrant point,
/// and most short arcs of a contour are such arcs. The f32 test below agrees
/// except for arcs too short for f32 to order their ends, which it takes for full
/// circles; this test gives them their own box.
fn inside_one_quadrant(s: P2, t: P2, cw: bool) -> bool {
    // Radii under 2^31 nm (2.1 m) — every lathe arc — keep the products in 64
    // bits (two 32 × 32 multiplies); larger ones go the f32 way.
    let small = |v: i64| i32::try_from(v).ok().filter(|&v| v != 0).map(i64::from);
    let (Some(sa), Some(sb), Some(ta), Some(tb)) = (small(s.0), small(s.1), small(t.0), small(t.1)) else {
        return false;
    };
    if (sa > 0, sb > 0) != (ta > 0, tb > 0) {
        return false;
    }
    // The cross product s × t: positive when t lies counter-clockwise of s.
    let cross = (sa * tb).cmp(&(sb * ta));
    cross == if cw { core::cmp::Ordering::Less } else { core::cmp::Ordering::Greater }
}

/// A monotonic stand-in for the angle of `v` in quarter turns, `[0, 4)`: exact at
/// the four axis directions, which is all the extents need. f32 is enough (it only
/// classifies directions) and is hardware on the Cortex-M4F.
fn pseudo_angle(v: P2) -> f32 {
    let (x, y) = (f32_of(v.0), f32_of(v.1));
    let (ax, ay) = (x.abs(), y.abs());
    if ax + ay == 0.0 {
        return 0.0;
    }
    let f = ay / (ax + ay);
    match (x >= 0.0, y >= 0.0) {
        (true, true) => f,
        (false, true) => 2.0 - f,
        (false, false) => 2.0 + f,
        (true, false) => 4.0 - f,
    }
}

/// `x` wrapped into `[0, 4)`.
fn wrap4(x: f32) -> f32 {
    if x < 0.0 {
        x + 4.0
    } else if x >= 4.0 {
        x - 4.0
    } else {
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use canon::xorshift::XorShift;

    const MM: i64 = 1_000_000;

    /// The integer radius of the extents against the f64 one it replaced, up to
    /// 2 m: the same in every case.
    #[test]
    fn integer_radius_equals_the_f64_one() {
        let mut rng = XorShift::new(0x9e37_79b9_7f4a_7c15);
        let mut next = |m: i64| rng.signed(m);
        for i in 0..40_000 {
            let m = [1_000, 1_000_000, 100_000_000, 2_000_000_000][i % 4];
            let (p, q) = ((next(m), next(m)), (next(m), next(m)));
            let old = libm::round(dist(p, q)) as i64;
            assert_eq!(radius_nm(p, q), old, "{p:?} {q:?}");
        }
    }

    #[test]
    fn radius_centres_follow_direction_and_sign() {
        // Half-chord 1 mm, R = 1 mm: half circle, centre on the chord.
        assert_eq!(center_from_radius((0, 0), (2 * MM, 0), MM, true, 0), Ok((MM, 0)));
        // R 5 mm from (0,0) to (6,0): h = 4. CW small arc: centre below the chord.
        assert_eq!(center_from_radius((0, 0), (6 * MM, 0), 5 * MM, true, 0), Ok((3 * MM, -4 * MM)));
        assert_eq!(center_from_radius((0, 0), (6 * MM, 0), 5 * MM, false, 0), Ok((3 * MM, 4 * MM)));
        // R < 0: the large arc, centre on the other side.
        assert_eq!(center_from_radius((0, 0), (6 * MM, 0), -5 * MM, true, 0), Ok((3 * MM, 4 * MM)));
    }

    #[test]
    fn radius_too_small_is_alarm_0020_unless_within_tolerance() {
        assert!(matches!(
            center_from_radius((0, 0), (10 * MM, 0), 4 * MM, true, 10_000),
            Err(AlarmKind::ArcRadiusTolerance { excess_nm: 1_000_000 })
        ));
        assert_eq!(center_from_radius((0, 0), (10 * MM, 0), 5 * MM - 5_000, true, 10_000), Ok((5 * MM, 0)));
    }

    #[test]
    fn extreme_values_do_not_overflow() {
        for (s, e, r, tol) in [
            ((i64::MIN, i64::MIN), (i64::MAX, i64::MAX), i64::MIN, i64::MAX),
            ((i64::MAX, 0), (i64::MIN, 0), i64::MAX, 0),
            ((0, 0), (1, 0), i64::MAX, i64::MIN),
            ((0, 0), (1, 1), 1, -5),
        ] {
            let _ = center_from_radius(s, e, r, true, tol);
            let _ = center_from_radius(s, e, r, false, tol);
        }
    }

    #[test]
    fn offsets_must_put_the_end_on_the_circle() {
        assert_eq!(center_from_offsets((0, 0), (10 * MM, 0), (5 * MM, 0), 10_000), Ok((5 * MM, 0)));
        assert!(center_from_offsets((0, 0), (11 * MM, 0), (5 * MM, 0), 10_000).is_err());
    }

    #[test]
    fn extents_include_the_quadrant_points_passed() {
        // CCW half circle from (10,0) around (0,0) to (-10,0) passes (0,10).
        let e = arc_extents((10 * MM, 0), (-10 * MM, 0), (0, 0), false, false);
        assert_eq!(e.b, (0, 10 * MM));
        // The CW one passes (0,-10).
        let e = arc_extents((10 * MM, 0), (-10 * MM, 0), (0, 0), true, false);
        assert_eq!(e.b, (-10 * MM, 0));
        let e = arc_extents((10 * MM, 0), (10 * MM, 0), (0, 0), true, true);
        assert_eq!(e, Extents { a: (-10 * MM, 10 * MM), b: (-10 * MM, 10 * MM) });
    }

    /// The centre as computed before `norm` replaced `libm::hypot`.
    fn centre_with_hypot(start: P2, end: P2, r: i64, cw: bool) -> P2 {
        let (sa, sb) = (start.0 as f64, start.1 as f64);
        let (da, db) = ((end.0 - start.0) as f64, (end.1 - start.1) as f64);
        let chord = libm::hypot(da, db);
        let half = chord / 2.0;
        let radius = (r as f64).abs();
        let h = libm::sqrt((radius * radius - half * half).max(0.0));
        let s = if cw == (r > 0) { 1.0 } else { -1.0 };
        let (ua, ub) = (db / chord, -da / chord);
        (libm::round(sa + da / 2.0 + s * h * ua) as i64, libm::round(sb + db / 2.0 + s * h * ub) as i64)
    }

    /// The centre as computed before the sum went to 128-bit integers (f64 throughout).
    fn centre_f64(start: P2, end: P2, r: i64, cw: bool) -> P2 {
        let (da, db) = (end.0.saturating_sub(start.0), end.1.saturating_sub(start.1));
        let sq = |v: u64| u128::from(v) * u128::from(v);
        let c2 = sq(da.unsigned_abs()) + sq(db.unsigned_abs());
        let disc = (4 * sq(r.unsigned_abs())).saturating_sub(c2);
        let k = libm::sqrt(disc as f64 / c2 as f64) / 2.0;
        let k = if cw == (r > 0) { k } else { -k };
        let (da, db) = (da as f64, db as f64);
        let ca = start.0 as f64 + da / 2.0 + k * db;
        let cb = start.1 as f64 + db / 2.0 - k * da;
        (libm::round(ca) as i64, libm::round(cb) as i64)
    }

    /// How [`half_sum`] was computed before: the whole sum in 128 bits.
    /// `round(p + (d + s·n) / 2)`, half away from zero, exactly (`s` as the f64 it is,
    /// `s ≥ 0`): `s` is its 53-bit mantissa times a power of two, so the sum is an
    /// integer over that power of two in 128 bits — no soft-float arithmetic.
    /// `None` when it does not fit.
    fn half_sum_wide(p: i64, d: i64, n: i64, s: f64) -> Option<i64> {
        let (m, sh) = mantissa_shift(s)?;
        let base = 2 * i128::from(p) + i128::from(d);
        // `base · 2^sh` below 2^126, `n·m` below 2^117: the sum fits.
        if !(0..=120).contains(&sh) || base.unsigned_abs().leading_zeros() < 2 + sh as u32 {
            return None;
        }
        let total = (base << sh) + i128::from(n) * i128::from(m);
        let half = 1u128 << sh;
        let q = ((total.unsigned_abs() + half) >> (sh + 1)) as i128;
        let q = if total < 0 { -q } else { q };
        Some(q.clamp(i128::from(i64::MIN), i128::from(i64::MAX)) as i64)
    }

    /// The split sum against the whole 128-bit one over random points, offsets
    /// and factors of every size, and the ties.
    #[test]
    fn half_sum_equals_the_whole_sum() {
        let mut rng = XorShift::new(0x2545_f491_4f6c_dd1d);
        let mut next = || rng.next_u64();
        let mut compared = 0;
        for i in 0..200_000 {
            let size = |v: u64, k: u32| (v as i64) >> (v % u64::from(k)) as u32;
            let (p, d, n) = (size(next(), 64), size(next(), 64), size(next(), 64));
            let s = f64::from_bits(next() >> 2) * (1u64 << (next() % 60)) as f64;
            let s = if i % 7 == 0 { (next() % 5) as f64 / 2.0 } else { s };
            if let Some(want) = half_sum_wide(p, d, n, s) {
                assert_eq!(half_sum(p, d, n, s), Some(want), "{p} {d} {n} {s:e}");
                compared += 1;
            }
        }
        assert!(compared > 20_000, "{compared}");
        for (p, d, n, s) in
            [(0, 3, 0, 0.0), (0, -3, 0, 0.0), (5, -1, 1, 0.5), (-5, 1, -1, 0.5), (0, 0, 1, 1.0), (0, 0, -1, 1.0)]
        {
            assert_eq!(half_sum(p, d, n, s), half_sum_wide(p, d, n, s), "{p} {d} {n} {s}");
        }
    }

    #[test]
    fn integer_centres_equal_the_f64_ones() {
        // The same spread as below plus near half circles and exact ties.
        let mut rng = XorShift::new(0x9e37_79b9_7f4a_7c15);
        let mut next = |m: i64| rng.signed(m);
        let mut differ = 0;
        for i in 0..40_000 {
            let scale = [1_000, 100_000, 10 * MM, 1_000 * MM][i % 4];
            let start = (next(500 * MM), next(500 * MM));
            let end = (start.0 + next(scale), start.1 + next(scale));
            if start == end {
                continue;
            }
            let chord = libm::hypot((end.0 - start.0) as f64, (end.1 - start.1) as f64);
            let spread = if i % 5 == 0 { 1e-6 * next(1_000).abs() as f64 } else { (next(1_000) + 1_000) as f64 / 20.0 };
            let r = (chord / 2.0 * (1.0 + spread)) as i64 + 1;
            let r = if i % 3 == 0 { -r } else { r };
            let cw = i % 2 == 0;
            let c = center_from_radius(start, end, r, cw, 2).unwrap_or((i64::MAX, 0));
            let want = centre_f64(start, end, r, cw);
            assert!((c.0 - want.0).abs() <= 1 && (c.1 - want.1).abs() <= 1, "{start:?} {end:?} R{r}");
            if c != want {
                differ += 1;
            }
        }
        // Half circles with an odd chord: the centre is a tie, rounded away from zero.
        assert_eq!(center_from_radius((0, 0), (-3, 0), 1, true, 1), Ok((-2, 0)));
        assert_eq!(center_from_radius((0, 1), (3, 1), 1, true, 1), Ok((2, 1)));
        assert_eq!(differ, 0, "integer centres differ from the f64 ones");
    }

    /// The integer test for arcs inside one quadrant against the f32 pseudo-angles:
    /// the same box for every arc it takes, except arcs too short for f32 to order
    /// their ends (the f32 way then boxes the whole circle).
    #[test]
    fn quadrant_test_agrees_with_the_f32_one() {
        let mut rng = XorShift::new(0x6a09_e667_f3bc_c908);
        let (mut inside, mut tiny) = (0, 0);
        for i in 0..100_000 {
            let r = [2_000, 200_000, 20 * MM, 1_000 * MM][i % 4] + rng.signed(1_000).abs();
            let centre = (rng.signed(300 * MM), rng.signed(300 * MM));
            let on_circle = |rng: &mut XorShift| {
                let a = rng.signed(1 << 30) as f64 / f64::from(1u32 << 30) * core::f64::consts::PI;
                let p = (centre.0 + (r as f64 * libm::cos(a)) as i64, centre.1 + (r as f64 * libm::sin(a)) as i64);
                (p, a)
            };
            let ((start, a0), (end, a1)) = (on_circle(&mut rng), on_circle(&mut rng));
            let cw = i % 2 == 1;
            let e =
                Extents { a: (start.0.min(end.0), start.0.max(end.0)), b: (start.1.min(end.1), start.1.max(end.1)) };
            let rel = |p: P2| (p.0 - centre.0, p.1 - centre.1);
            if !inside_one_quadrant(rel(start), rel(end), cw) {
                continue;
            }
            inside += 1;
            let by_f32 = by_quarter_turns(e, start, end, centre, cw, false);
            if (a1 - a0).abs() < 1e-6 && by_f32 != e {
                tiny += 1;
                continue;
            }
            assert_eq!(arc_extents(start, end, centre, cw, false), e);
            assert_eq!(by_f32, e, "{start:?} {end:?} around {centre:?}, cw {cw}");
        }
        assert!(inside > 10_000, "{inside} arcs inside one quadrant");
        assert!(tiny < 10, "{tiny} arcs too short for f32");
        // An arc of 1.4 nm at R100 ccw: its ends' pseudo-angles are the same f32
        // (sweep 0), which the f32 way took for a whole circle. Its own box now.
        let (c, s0, e0) = ((0, 0), (70_710_678, 70_710_678), (70_710_677, 70_710_679));
        assert_eq!(by_quarter_turns(Extents { a: (0, 0), b: (0, 0) }, s0, e0, c, false, false).a.0, -100 * MM);
        assert_eq!(
            arc_extents(s0, e0, c, false, false),
            Extents { a: (70_710_677, 70_710_678), b: (70_710_678, 70_710_679) }
        );
        // Through the axes, or the long way round: the quadrant points count.
        let e = arc_extents((10 * MM, 1), (1, 10 * MM), (0, 0), true, false);
        assert_eq!(e, Extents { a: (-10 * MM, 10 * MM), b: (-10 * MM, 10 * MM) });
        assert_eq!(arc_extents((10 * MM, 1), (1, 10 * MM), (0, 0), false, false).a, (1, 10 * MM));
    }

    #[test]
    fn centres_and_extents_match_hypot_within_a_nanometre() {
        // A deterministic spread of arcs: chords from 1 µm to 1 m, radii from just
        // over half the chord to 100 times it, both directions and signs.
        let mut rng = XorShift::new(0x2545_f491_4f6c_dd1d);
        let mut next = |m: i64| rng.signed(m);
        let mut far = 0;
        for i in 0..20_000 {
            let scale = [1_000, 100_000, 10 * MM, 1_000 * MM][i % 4];
            let start = (next(500 * MM), next(500 * MM));
            let end = (start.0 + next(scale), start.1 + next(scale));
            if start == end {
                continue;
            }
            let chord = libm::hypot((end.0 - start.0) as f64, (end.1 - start.1) as f64);
            let r = (chord / 2.0 * (1.0 + (next(1_000) + 1_000) as f64 / 20.0)) as i64 + 1;
            let r = if i % 3 == 0 { -r } else { r };
            let cw = i % 2 == 0;
            let c = center_from_radius(start, end, r, cw, 0).unwrap_or((i64::MAX, 0));
            let want = centre_with_hypot(start, end, r, cw);
            let off = |c: P2| {
                let d = |p: P2| libm::hypot((p.0 - c.0) as f64, (p.1 - c.1) as f64) - r.abs() as f64;
                d(start).abs().max(d(end).abs())
            };
            let close = (c.0 - want.0).abs() <= 1 && (c.1 - want.1).abs() <= 1;
            // Where the two differ (near half circles, where the old f64
            // `r² − (c/2)²` cancelled) the new centre must lie closer to the circle.
            assert!(close || off(c) <= off(want), "{start:?} {end:?} R{r}: {c:?} vs {want:?}");
            if !close {
                far += 1;
            }
            assert_eq!(radius_nm(start, c), libm::round(dist(start, c)) as i64, "{start:?} {c:?}");
            let rel = (start.0 - c.0, start.1 - c.1);
            let radius = libm::round(libm::hypot(rel.0 as f64, rel.1 as f64)) as i64;
            assert!((libm::round(dist(start, c)) as i64 - radius).abs() <= 1);
        }
        assert_eq!(far, 0, "centres more than 1 nm from the hypot ones");
    }
}

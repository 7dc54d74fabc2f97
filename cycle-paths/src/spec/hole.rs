//! What a hole cycle is asked to do, in the engine's terms: the specification of
//! the one hole generator (`cycles::hole`) that FANUC's G83–G89 (lathe), G73–G89
//! (machining centre) and SINUMERIK's CYCLE81–CYCLE89/CYCLE840 fill in. Defined
//! here, below the languages (data down); the generator is in `crate::cycles`.

use crate::axis::{Axis, Pos};
use crate::canon::{Plane, SpindleDir};

/// What is done at the hole.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HoleWork {
    /// Drill to the bottom, pecking by `q` if non-zero: `deep` = back to R after
    /// each peck (lathe 5101 = 1, FANUC M G83), else back by `d` (high speed:
    /// lathe 5101 = 0, FANUC M G73).
    Drill {
        /// Peck depth (0 = no pecking).
        q: i64,
        /// Deep-hole pecking.
        deep: bool,
        /// Return d (high speed) or clearance d (deep).
        d: i64,
    },
    /// Feed in, dwell, feed out (lathe G85/G89, FANUC M G85/G89).
    Bore,
    /// Feed in, dwell, spindle stop, rapid out, spindle on again in `restart`
    /// (FANUC M G86).
    BoreStop {
        /// Direction the spindle turned in before the hole.
        restart: SpindleDir,
    },
    /// Feed in, dwell, spindle stop, a stop for the operator (who may retract by
    /// hand), then rapid out and the spindle on again (FANUC M G88).
    BoreManual {
        /// Direction the spindle turned in before the hole.
        restart: SpindleDir,
    },
    /// Feed in, dwell, oriented spindle stop (M19), shift away from the wall by
    /// `shift`, rapid out, shift back, spindle on (FANUC M G76).
    FineBore {
        /// The shift, a vector in the positioning plane (work coordinates).
        shift: Pos,
        /// Direction the spindle turned in before the hole.
        restart: SpindleDir,
    },
    /// Back boring (FANUC M G87): at the hole position oriented stop and shift,
    /// rapid down to the R level (below the hole's far end), shift back, spindle
    /// on, feed up to the bottom level, oriented stop, shift, rapid to the initial
    /// level, shift back, spindle on. Always back to the initial level.
    BackBore {
        /// The shift, a vector in the positioning plane (work coordinates).
        shift: Pos,
        /// Direction the spindle turns in while cutting.
        restart: SpindleDir,
    },
    /// Rigid tapping (M29): every move in the hole locked to the spindle.
    RigidTap {
        /// Lead, nm/rev.
        lead: i64,
        /// Peck depth (0 = none).
        q: i64,
        /// Deep peck: back to R after each peck.
        deep: bool,
        /// Return d of pecking.
        d: i64,
        /// Spindle direction into the hole.
        dir: SpindleDir,
        /// Dwell at R after tapping (lathe parameter 7013).
        dwell_r_ms: u32,
        /// Spindle direction after the hole (⑦ of the lathe; stopped on a mill,
        /// whose spindle stays in position control until G80).
        restore: SpindleDir,
    },
    /// Floating tapping: the spindle turns `dir` into the hole and the other way
    /// out; the feed follows the spindle.
    FloatTap {
        /// Lead, nm/rev.
        lead: i64,
        /// Direction into the hole.
        dir: SpindleDir,
        /// Whether the spindle already turns that way (then ① outputs nothing).
        turning: bool,
        /// The spindle after the hole: stopped (lathe, 2.22.3: M05 at R and M03/M04
        /// again before the next hole) or `dir` again (FANUC M G84/G74: forward
        /// again at R).
        after: SpindleDir,
        /// The spindle stops at the bottom before it reverses (lathe 2.22.3); a
        /// mill reverses directly.
        stop_at_bottom: bool,
    },
    /// Deep-hole drilling with a degressive infeed, chip breaking or chip
    /// removal (SINUMERIK CYCLE83).
    DeepDrill(DeepDrill),
    /// Boring with a feed of its own in and out (SINUMERIK CYCLE85: FFR, RFF),
    /// in the cycle's feed mode.
    BoreFeeds {
        /// Feed into the hole.
        feed_in: i64,
        /// Feed out to the R level.
        feed_out: i64,
    },
}

/// What a hole cycle is asked to do.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HoleSpec {
    /// Work at the hole.
    pub work: HoleWork,
    /// Drilling axis: the normal of `plane`.
    pub axis: Axis,
    /// Positioning plane: the plane the hole positions are given in (G17 for a
    /// machining centre's holes; a lathe's face holes are positioned in X and C,
    /// its side holes in Z and C). Rotary axes position along with it.
    pub plane: Plane,
    /// First hole position (work coordinates); on the drilling axis the level the
    /// tool is on when the hole is positioned.
    pub position: Pos,
    /// Position change per repetition.
    pub step: Pos,
    /// Initial level on the drilling axis, where G98 (or a lathe's hole) returns:
    /// on a machining centre the level the cycle mode started on, remembered across
    /// its G99 holes (seed 004 @7537).
    pub initial: i64,
    /// R level on the drilling axis.
    pub r_level: i64,
    /// Bottom on the drilling axis (the far end of the cut: for back boring the
    /// level the cut ends on, above R).
    pub bottom: i64,
    /// Dwell at the bottom.
    pub dwell_ms: u32,
    /// G99: return to the R level only.
    pub stay_at_r: bool,
    /// K.
    pub repeat: u32,
}

/// The depths of a deep hole drilled in strokes (SINUMERIK CYCLE83, seed 001
/// lines 1784-1831): the first stroke, then strokes that shrink by an amount or a
/// factor down to a minimum; the last two strokes share what is left equally.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DeepDrill {
    /// First drilling depth (FDEP/FDPR from the reference plane), nm, > 0: the
    /// first stroke the later ones shrink from.
    pub first: i64,
    /// From the R level to the reference plane (SDIS), nm: the first stroke
    /// starts at R and ends at the first depth.
    pub approach: i64,
    /// How the strokes after the first shrink.
    pub degression: Degression,
    /// Chip removal (VARI = 1): back to the R level after each stroke; else chip
    /// breaking (VARI = 0): back by `retract` at the cutting feed.
    pub chip_removal: bool,
    /// Chip breaking's retract (_VRT; 1 mm when not given), nm.
    pub retract: i64,
    /// Chip removal's anticipation distance before the depth reached (_DIS1), nm;
    /// 0 = the cycle's own: 0.6 mm up to 30 mm deep, else depth / 50, at most 7 mm.
    pub anticipation: i64,
    /// Dwell at each intermediate depth (DTB), ms.
    pub dwell_depth_ms: u32,
    /// Dwell at the R level after each chip-removal retract (DTS), ms.
    pub dwell_start_ms: u32,
    /// Feed of the first stroke (the programmed feed × FRF), in the feed mode in force.
    pub first_feed: i64,
    /// Feed of the other strokes (the programmed feed).
    pub feed: i64,
}

/// How the strokes of a [`DeepDrill`] shrink (DAM).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Degression {
    /// DAM = 0: every stroke is the first stroke's length.
    None,
    /// DAM > 0: each stroke the one before less this amount, at least the amount.
    Amount(i64),
    /// DAM < 0: each stroke the one before times `ppm` / 10⁶, at least `min` (_MDEP).
    Factor {
        /// The factor in millionths (0 < ppm ≤ 10⁶).
        ppm: i64,
        /// Minimum stroke, nm.
        min: i64,
    },
}

/// 0.6 mm: CYCLE83's anticipation distance up to 30 mm deep (line 1909).
const ANTICIPATION_SHALLOW: i64 = 600_000;
/// 30 mm.
const SHALLOW: i64 = 30_000_000;
/// 7 mm: the largest anticipation distance the cycle computes (line 1910).
const ANTICIPATION_MAX: i64 = 7_000_000;

impl DeepDrill {
    /// The stroke after the `n`th (0 = the first) of length `prev`, with `left` to
    /// the bottom: the degressive length; when what is left is at most twice that,
    /// half of it (the last two strokes equal, each more than half a stroke); when
    /// it is at most one stroke, all of it.
    pub fn stroke(&self, n: u32, prev: i64, left: i64) -> i64 {
        let next = match (n, self.degression) {
            (0, _) | (_, Degression::None) => self.first,
            (_, Degression::Amount(a)) => (prev - a).max(a),
            (_, Degression::Factor { ppm, min }) => scale_ppm(prev, ppm).max(min),
        }
        .max(1);
        if left <= next || n == 0 || self.degression == Degression::None {
            next.min(left)
        } else if left <= 2 * next {
            (left + 1) / 2
        } else {
            next
        }
    }

    /// The anticipation distance with the tool `depth` below the R level.
    pub fn anticipation_at(&self, depth: i64) -> i64 {
        if self.anticipation > 0 {
            self.anticipation
        } else if depth <= SHALLOW {
            ANTICIPATION_SHALLOW
        } else {
            (depth / 50).min(ANTICIPATION_MAX)
        }
    }
}

/// `v · ppm / 10⁶` rounded towards zero, exactly for every `v` and 0 ≤ `ppm` ≤ 10⁶
/// (the whole millions and the rest apart, both products in 64 bits: the 128-bit
/// product and division cost the Cortex-M4 ~0.8 KB of code); saturating beyond.
fn scale_ppm(v: i64, ppm: i64) -> i64 {
    const M: i64 = 1_000_000;
    (v / M).saturating_mul(ppm).saturating_add((v % M).saturating_mul(ppm) / M)
}

#[cfg(test)]
mod tests {
    use super::scale_ppm;

    #[test]
    fn scaling_by_a_factor_is_the_128_bit_quotient() {
        let wide = |v: i64, ppm: i64| i64::try_from(i128::from(v) * i128::from(ppm) / 1_000_000).unwrap();
        let mut v: i64 = 1;
        let mut seed: u64 = 0x9e37_79b9_7f4a_7c15;
        for _ in 0..20_000 {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let ppm = (seed % 1_000_001) as i64;
            let v2 = (seed >> 20) as i64 % 1_000_000_000_000_000;
            for x in [v, v2, -v2, 999_999, 1_000_000, 1_000_001, i64::MAX / 2_000_000] {
                assert_eq!(scale_ppm(x, ppm), wide(x, ppm), "{x} x {ppm} ppm");
            }
            v = v.wrapping_mul(3).wrapping_add(1) % 4_000_000_000_000_000;
        }
        assert_eq!(scale_ppm(i64::MAX, 1_000_000), i64::MAX);
        assert_eq!(scale_ppm(7_500_000, 800_000), 6_000_000);
    }
}

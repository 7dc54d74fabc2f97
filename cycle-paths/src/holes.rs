//! SINUMERIK drilling patterns (seed 001 chapter 2.3): the positions of HOLES1
//! (a row), HOLES2 (a circle) and CYCLE801 (a grid) in the working plane, in
//! the order the document gives. The front end reads the parameters; the driver
//! positions to each point with G0 and calls the modal drilling cycle (MCALL)
//! there. Positions are work coordinates in nm (abscissa, ordinate of the plane).
//!
//! - **HOLES1** (lines 3113-3244): hole k (0-based) at the reference point plus
//!   (FDIS + k·DBH) along the direction STA1. The row starts with the first or the
//!   last hole, whichever is nearer to where the tool is (lines 3140-3146).
//! - **HOLES2** (lines 3246-3325): hole k at the centre plus RAD at the angle
//!   STA1 + k·INDA; INDA = 0 spreads NUM holes evenly over the full circle
//!   (360°/NUM, lines 3296-3298).
//! - **CYCLE801** (lines 3327-3397): point (c, r) at the reference point plus
//!   c·_DIS1 along _STA and r·_DIS2 at right angles to it. The grid starts at the
//!   corner nearest to where the tool is (one of the four, lines 3359-3363) and is
//!   run line by line along the smaller spacing (rows if _DIS1 ≤ _DIS2, else
//!   columns, line 3380), each line back the way the previous one came (meander):
//!   the least idle travel.

/// The shape of a drilling pattern; lengths in nm, angles in degrees.
// `Listed` (512 B) is only in builds with a heap (CYCLE73, feature `listed`); a
// pattern is kept once, in the SINUMERIK front end's state.
#[cfg_attr(feature = "listed", allow(clippy::large_enum_variant))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Layout {
    /// HOLES1: reference point, angle, first distance, spacing.
    Row { at: (i64, i64), angle: f64, first: i64, spacing: i64 },
    /// HOLES2: centre, radius, start angle, increment (0 already replaced).
    Circle { centre: (i64, i64), radius: i64, start: f64, step: f64 },
    /// CYCLE801: reference point, angle, column and row spacing, column count.
    Grid { at: (i64, i64), angle: f64, dis1: i64, dis2: i64, columns: u32 },
    /// CYCLE73's pre-drilling (`_VARI` units 5): the insertion points of its
    /// clearing, in the order they are cut.
    #[cfg(feature = "listed")]
    Listed { points: [(i64, i64); LISTED_MAX] },
}

/// Most points a listed pattern holds (CYCLE73 pre-drilling: a pocket divided into
/// more parts is 61911 "more insertion points required").
#[cfg(feature = "listed")]
pub const LISTED_MAX: usize = 32;

/// A drilling pattern being run: its layout, its hole count, the order chosen
/// and the next hole.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HolePattern {
    pub layout: Layout,
    /// Number of holes (rows × columns for a grid).
    pub count: u32,
    /// The order: HOLES1 from the last hole; CYCLE801 the corner and line
    /// direction (bit 0 columns reversed, bit 1 rows reversed, bit 2 by columns).
    order: u8,
    /// Next hole to position to.
    pub next: u32,
    /// Source line of the pattern call.
    pub line: u32,
}

impl HolePattern {
    /// HOLES1 with `num` holes, started from the end nearer to `here`.
    pub fn row(at: (i64, i64), angle: f64, first: i64, spacing: i64, num: u32, here: (i64, i64), line: u32) -> Self {
        let mut p =
            HolePattern { layout: Layout::Row { at, angle, first, spacing }, count: num, order: 0, next: 0, line };
        let first_hole = p.natural(0);
        let last_hole = p.natural(num.saturating_sub(1));
        if dist2(here, last_hole) < dist2(here, first_hole) {
            p.order = 1;
        }
        p
    }

    /// HOLES2 with `num` holes; `step` 0 spreads them over the full circle.
    pub fn circle(centre: (i64, i64), radius: i64, start: f64, step: f64, num: u32, line: u32) -> Self {
        let step = if step == 0.0 { 360.0 / f64::from(num.max(1)) } else { step };
        HolePattern { layout: Layout::Circle { centre, radius, start, step }, count: num, order: 0, next: 0, line }
    }

    /// The points `list` in order; `None` beyond [`LISTED_MAX`].
    #[cfg(feature = "listed")]
    pub fn listed(list: &[(i64, i64)], line: u32) -> Option<Self> {
        let mut points = [(0, 0); LISTED_MAX];
        points.get_mut(..list.len())?.copy_from_slice(list);
        Some(HolePattern { layout: Layout::Listed { points }, count: list.len() as u32, order: 0, next: 0, line })
    }

    /// CYCLE801 with `columns` × `rows` points, started at the corner nearest `here`.
    #[allow(clippy::too_many_arguments)]
    pub fn grid(
        at: (i64, i64),
        angle: f64,
        dis1: i64,
        dis2: i64,
        columns: u32,
        rows: u32,
        here: (i64, i64),
        line: u32,
    ) -> Self {
        let layout = Layout::Grid { at, angle, dis1, dis2, columns };
        let mut p = HolePattern { layout, count: columns * rows, order: 0, next: 0, line };
        let (cl, rl) = (columns.saturating_sub(1), rows.saturating_sub(1));
        let corners = [(0, 0), (cl, 0), (0, rl), (cl, rl)];
        let mut best = 0;
        let mut best_d = f64::INFINITY;
        for (i, &(c, r)) in corners.iter().enumerate() {
            let d = dist2(here, p.grid_point(c, r));
            if d < best_d {
                best = i;
                best_d = d;
            }
        }
        p.order = best as u8 | if dis1 > dis2 { 4 } else { 0 };
        p
    }

    /// The position of hole `k` of the run (0-based, in the order chosen).
    pub fn point(&self, k: u32) -> (i64, i64) {
        match self.layout {
            Layout::Row { .. } => self.natural(if self.order & 1 != 0 { self.count - 1 - k } else { k }),
            Layout::Circle { .. } => self.natural(k),
            #[cfg(feature = "listed")]
            Layout::Listed { points } => points.get(k as usize).copied().unwrap_or_default(),
            Layout::Grid { columns, .. } => {
                let rows = self.count / columns.max(1);
                let by_columns = self.order & 4 != 0;
                let (len, _) = if by_columns { (rows, columns) } else { (columns, rows) };
                let (line, mut pos) = (k / len, k % len);
                if line % 2 == 1 {
                    pos = len - 1 - pos;
                }
                let (mut c, mut r) = if by_columns { (line, pos) } else { (pos, line) };
                if self.order & 1 != 0 {
                    c = columns - 1 - c;
                }
                if self.order & 2 != 0 {
                    r = rows - 1 - r;
                }
                self.grid_point(c, r)
            }
        }
    }

    /// Hole `k` of a row or circle in the document's numbering.
    fn natural(&self, k: u32) -> (i64, i64) {
        let k = f64::from(k);
        match self.layout {
            Layout::Row { at, angle, first, spacing } => along(at, angle, first as f64 + k * spacing as f64, 0.0),
            Layout::Circle { centre, radius, start, step } => along(centre, start + k * step, radius as f64, 0.0),
            _ => (0, 0),
        }
    }

    /// Grid point of column `c`, row `r` (0-based from the reference point).
    fn grid_point(&self, c: u32, r: u32) -> (i64, i64) {
        let Layout::Grid { at, angle, dis1, dis2, .. } = self.layout else { return (0, 0) };
        along(at, angle, f64::from(c) * dis1 as f64, f64::from(r) * dis2 as f64)
    }

    /// The next position, or `None` when every hole has been approached.
    pub fn advance(&mut self) -> Option<(i64, i64)> {
        if self.next >= self.count {
            return None;
        }
        let p = self.point(self.next);
        self.next += 1;
        Some(p)
    }
}

/// `at` moved `u` along the direction `deg` and `v` at right angles to it (nm).
fn along(at: (i64, i64), deg: f64, u: f64, v: f64) -> (i64, i64) {
    let a = deg.to_radians();
    let (s, c) = crate::geom::sin_cos(a);
    (at.0 + crate::geom::round_i64(u * c - v * s), at.1 + crate::geom::round_i64(u * s + v * c))
}

/// Squared distance between two points (nm², as f64).
fn dist2(a: (i64, i64), b: (i64, i64)) -> f64 {
    let (dx, dy) = ((a.0 - b.0) as f64, (a.1 - b.1) as f64);
    dx * dx + dy * dy
}

#[cfg(test)]
mod tests {
    use super::*;
    const MM: i64 = 1_000_000;

    #[test]
    fn row_from_the_nearer_end() {
        let p = HolePattern::row((30 * MM, 20 * MM), 0.0, 10 * MM, 20 * MM, 5, (30 * MM, 20 * MM), 1);
        let pts: [(i64, i64); 5] = core::array::from_fn(|k| p.point(k as u32));
        assert_eq!(pts[0], (40 * MM, 20 * MM));
        assert_eq!(pts[4], (120 * MM, 20 * MM));
        let q = HolePattern::row((30 * MM, 20 * MM), 0.0, 10 * MM, 20 * MM, 5, (105 * MM, 30 * MM), 1);
        assert_eq!(q.point(0), (120 * MM, 20 * MM));
        assert_eq!(q.point(4), (40 * MM, 20 * MM));
    }

    #[test]
    fn grid_meanders_from_the_nearest_corner() {
        let mut p = HolePattern::grid((30 * MM, 20 * MM), 0.0, 10 * MM, 15 * MM, 5, 3, (0, 0), 1);
        let mut got = [(0, 0); 15];
        for g in got.iter_mut() {
            *g = p.advance().unwrap();
        }
        assert_eq!(p.advance(), None);
        assert_eq!(got[0], (30 * MM, 20 * MM));
        assert_eq!(got[4], (70 * MM, 20 * MM));
        assert_eq!(got[5], (70 * MM, 35 * MM));
        assert_eq!(got[14], (70 * MM, 50 * MM));
    }
}

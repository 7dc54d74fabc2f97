//! Stored stroke check 2, G22/G23 (2.10): a box in machine coordinates whose inside
//! (parameter 1002 = 0) or outside (1002 = 1) the tool may not enter. Every move
//! is checked before it is staged, lines and arcs along their whole path, like the
//! soft limits; a block that would enter the forbidden area raises alarm 0502/0503
//! and does not move.

use crate::alarm::AlarmKind;
use crate::axis::{Axis, Pos};
use crate::canon::{Action, Canon};
use crate::command::Command;
use crate::config::{MachineConfig, Param};
use crate::geom::path::{Elem, V2};
use crate::modal::{State, StrokeArea};

/// The linear axes the check covers.
const LINEAR: [Axis; 3] = [Axis::X, Axis::Y, Axis::Z];

/// The bound of an axis the box does not limit (far beyond any travel, small
/// enough for exact f64 arithmetic).
const UNLIMITED: i64 = 1 << 52;

/// G22 / G23 of `cmd` applied to `st` (2.10): G22 takes the box from the block's
/// X/Y/Z (plus) and I/J/K (minus) words, axis by axis, else from parameters
/// 1360–1362 / 1370–1372. A box given in the wrong order switches the check off
/// (note 8). With the outside forbidden and the tool already there, the alarm
/// comes at once (note 7).
pub(crate) fn apply(cmd: &Command, st: &mut State, cfg: &MachineConfig) -> Result<(), AlarmKind> {
    match cmd.g.stroke {
        Some(false) => st.stroke = None,
        Some(true) => {
            let area = area_of(cmd, cfg);
            let ordered = LINEAR.into_iter().all(|a| area.lo[a] <= area.hi[a]);
            st.stroke = ordered.then_some(area);
            if let Some(a) = st.stroke
                && a.outside
                && let Some(k) = outside_at(&a, &xyz(&st.pos))
            {
                return Err(k);
            }
        }
        None => {}
    }
    Ok(())
}

fn area_of(cmd: &Command, cfg: &MachineConfig) -> StrokeArea {
    let p = &cfg.params;
    let params = [
        (Axis::X, Param::Stroke2PlusX, Param::Stroke2MinusX),
        (Axis::Y, Param::Stroke2PlusY, Param::Stroke2MinusY),
        (Axis::Z, Param::Stroke2PlusZ, Param::Stroke2MinusZ),
    ];
    let (mut lo, mut hi) = (Pos::ZERO, Pos::ZERO);
    for (axis, plus, minus) in params {
        // X values are diameters, in the words and in the parameters.
        let scale = |v: i64| if axis == Axis::X && cfg.diameter_x { v / 2 } else { v };
        hi[axis] = cmd.axes[axis.index()].map_or(scale(p.get(plus)), |w| w.value);
        lo[axis] = cmd.center[axis.index()].map_or(scale(p.get(minus)), scale);
        // An axis the machine lacks, or one with no extent given, is not limited.
        if !cfg.axis(axis).present || lo[axis] == hi[axis] {
            (lo[axis], hi[axis]) = (-UNLIMITED, UNLIMITED);
        }
    }
    StrokeArea { lo, hi, outside: p.flag(Param::Stroke2Outside) }
}

/// The alarm for point `p` lying outside the box (by more than the rounding of a
/// nanometre), if it does.
fn outside_at(a: &StrokeArea, p: &[f64; 3]) -> Option<AlarmKind> {
    LINEAR.into_iter().enumerate().find_map(|(i, x)| {
        if p[i] > a.hi[x] as f64 + 0.5 {
            Some(AlarmKind::StrokeLimit2 { letter: x.letter(), plus: true })
        } else if p[i] < a.lo[x] as f64 - 0.5 {
            Some(AlarmKind::StrokeLimit2 { letter: x.letter(), plus: false })
        } else {
            None
        }
    })
}

/// Whether `p` lies inside the box by more than the rounding of a nanometre (a
/// move along a face does not enter).
fn strictly_inside(a: &StrokeArea, p: &[f64; 3]) -> bool {
    LINEAR.into_iter().enumerate().all(|(i, x)| p[i] > a.lo[x] as f64 + 0.5 && p[i] < a.hi[x] as f64 - 0.5)
}

/// Checks the moves staged in `acts`, the first starting at `from`. Always inlined
/// into the per-block paths (see `contour::after_block`).
#[inline(always)]
pub(crate) fn check_actions<'a, I>(st: &State, from: Pos, acts: I) -> Result<(), AlarmKind>
where
    I: Iterator<Item = &'a Canon>,
{
    let Some(area) = st.stroke else { return Ok(()) };
    let mut pos = from;
    for c in acts {
        if let Some(e) = c.action.endpoint() {
            check_move(&area, pos, &c.action)?;
            pos = e.machine;
        }
    }
    Ok(())
}

/// Checks one move from `from` against `area`.
pub fn check_move(area: &StrokeArea, from: Pos, action: &Action) -> Result<(), AlarmKind> {
    let Some(to) = action.endpoint().map(|e| e.machine) else { return Ok(()) };
    let path = Path::of(from, action);
    if area.outside {
        // The box is convex: the path stays in it when its end points and extents do.
        for p in path.extremes() {
            if let Some(k) = outside_at(area, &p) {
                return Err(k);
            }
        }
        return Ok(());
    }
    // Split the path where it crosses a face of the box; a piece with its middle
    // strictly inside enters the forbidden area.
    let mut cuts: heapless::Vec<f64, 16> = heapless::Vec::new();
    let _ = cuts.push(0.0);
    let _ = cuts.push(1.0);
    for (i, x) in LINEAR.into_iter().enumerate() {
        for v in [area.lo[x], area.hi[x]] {
            for t in path.crossings(i, v as f64) {
                let _ = cuts.push(t);
            }
        }
    }
    crate::sort::heap_sort_by(&mut cuts, |a, b| a.total_cmp(b).is_lt());
    for w in cuts.windows(2) {
        if w[1] - w[0] > 1e-12 && strictly_inside(area, &path.at((w[0] + w[1]) / 2.0)) {
            return Err(if w[0] > 0.0 { face_alarm(area, &path.at(w[0])) } else { start_alarm(&from, &to) });
        }
    }
    Ok(())
}

/// The alarm for entering the box at point `p` on its surface: the face `p` lies
/// on; entering through the minus face means moving in +.
fn face_alarm(area: &StrokeArea, p: &[f64; 3]) -> AlarmKind {
    let mut best = (Axis::X, true, f64::MAX);
    for (i, x) in LINEAR.into_iter().enumerate() {
        for (bound, plus) in [(area.lo[x], true), (area.hi[x], false)] {
            let d = libm::fabs(p[i] - bound as f64);
            if d < best.2 {
                best = (x, plus, d);
            }
        }
    }
    AlarmKind::StrokeLimit2 { letter: best.0.letter(), plus: best.1 }
}

/// The alarm for a move starting inside the box (2.10 note 7): its main direction.
fn start_alarm(from: &Pos, to: &Pos) -> AlarmKind {
    let mut best = (Axis::X, true, -1i64);
    for x in LINEAR {
        let d = to[x] - from[x];
        let plus = d > 0;
        if d.abs() > best.2 {
            best = (x, plus, d.abs());
        }
    }
    AlarmKind::StrokeLimit2 { letter: best.0.letter(), plus: best.1 }
}

/// A move's path as a function of t ∈ [0, 1] over the three linear axes.
enum Path {
    Line { a: [f64; 3], b: [f64; 3] },
    Arc { arc: Elem, axes: (usize, usize), fixed: [f64; 3] },
}

fn xyz(p: &Pos) -> [f64; 3] {
    [p[Axis::X] as f64, p[Axis::Y] as f64, p[Axis::Z] as f64]
}

/// Index of a linear axis in [`LINEAR`].
fn slot(a: Axis) -> usize {
    match a {
        Axis::X => 0,
        Axis::Y => 1,
        _ => 2,
    }
}

impl Path {
    fn of(from: Pos, action: &Action) -> Path {
        let to = action.endpoint().map_or(from, |e| e.machine);
        match action {
            Action::Arc(m) => {
                let (pa, pb) = m.plane.axes();
                let v = |p: &Pos| V2::new(p[pa] as f64, p[pb] as f64);
                let arc = if m.full_circle {
                    // A full circle: its extremes are the four quadrant points.
                    Elem::Arc { start: v(&from), end: v(&from), center: v(&m.center.machine), ccw: !m.cw }
                } else {
                    Elem::Arc { start: v(&from), end: v(&to), center: v(&m.center.machine), ccw: !m.cw }
                };
                Path::Arc { arc, axes: (slot(pa), slot(pb)), fixed: xyz(&to) }
            }
            _ => Path::Line { a: xyz(&from), b: xyz(&to) },
        }
    }

    #[inline(never)]
    fn at(&self, t: f64) -> [f64; 3] {
        match self {
            Path::Line { a, b } => core::array::from_fn(|i| a[i] + t * (b[i] - a[i])),
            Path::Arc { arc, axes, fixed } => {
                let p = arc.point_at(t * arc.length());
                let mut out = *fixed;
                out[axes.0] = p.a;
                out[axes.1] = p.b;
                out
            }
        }
    }

    /// Parameters where axis slot `i` equals `v`.
    fn crossings(&self, i: usize, v: f64) -> heapless::Vec<f64, 2> {
        let mut out = heapless::Vec::new();
        match self {
            Path::Line { a, b } => {
                if b[i] != a[i] {
                    let t = (v - a[i]) / (b[i] - a[i]);
                    if t > 0.0 && t < 1.0 {
                        let _ = out.push(t);
                    }
                }
            }
            Path::Arc { arc, axes, .. } => {
                let len = arc.length();
                if len <= 0.0 || (i != axes.0 && i != axes.1) {
                    return out;
                }
                for p in arc.crossings_at(i == axes.0, v) {
                    let t = arc.along(p) / len;
                    if t > 0.0 && t < 1.0 {
                        let _ = out.push(t);
                    }
                }
            }
        }
        out
    }

    /// End points and, for an arc, the quadrant points it passes.
    fn extremes(&self) -> heapless::Vec<[f64; 3], 6> {
        let mut out = heapless::Vec::new();
        let _ = out.push(self.at(0.0));
        let _ = out.push(self.at(1.0));
        if let Path::Arc { arc, .. } = self {
            let len = arc.length();
            if let Elem::Arc { center, .. } = arc {
                let r = arc.radius();
                for d in [V2::new(r, 0.0), V2::new(0.0, r), V2::new(-r, 0.0), V2::new(0.0, -r)] {
                    let q = center.plus(d);
                    let s = arc.along(q);
                    if s > 0.0 && s < len {
                        let _ = out.push(self.at(s / len));
                    }
                }
            }
        }
        out
    }
}

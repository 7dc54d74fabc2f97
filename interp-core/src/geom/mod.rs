//! Per-block geometry in a plane: arc centres from R or I/J/K, arc extents, the
//! points and segments of the ZX plane the turning cycles plan with; the numeric
//! functions in degrees both languages share ([`deg`]).
//! Uses f64 (libm) for the computation, returns integer nanometres.

mod arc;
pub mod deg;
pub mod path;
mod seg;
mod sqrt;

pub use arc::{Extents, P2, arc_extents, center_from_offsets, center_from_radius};
pub use seg::{Pt, Seg, SegKind};

/// `libm::round(x) as i64`: half away from zero, saturating (NaN gives 0). Out
/// of line: the saturating conversion is ~40 bytes of soft-float calls at every
/// site, and the cold transformations (G68, G51, G16, polar) round at many.
#[inline(never)]
pub fn round_i64(x: f64) -> i64 {
    libm::round(x) as i64
}

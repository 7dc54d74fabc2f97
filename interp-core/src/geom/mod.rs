//! Per-block geometry in a plane: arc centres from R or I/J/K, arc extents.
//! Uses f64 (libm) for the computation, returns integer nanometres.

mod arc;
pub mod path;
mod sqrt;

pub use arc::{Extents, P2, arc_extents, center_from_offsets, center_from_radius};

/// `libm::round(x) as i64`: half away from zero, saturating (NaN gives 0). Out
/// of line: the saturating conversion is ~40 bytes of soft-float calls at every
/// site, and the cold transformations (G68, G51, G16, polar) round at many.
#[inline(never)]
pub fn round_i64(x: f64) -> i64 {
    libm::round(x) as i64
}

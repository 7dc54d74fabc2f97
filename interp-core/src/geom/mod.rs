//! Per-block geometry in a plane: arc centres from R or I/J/K, arc extents, and the
//! points and segments of the ZX plane the turning cycles plan with.
//! Uses f64 (libm) for the computation, returns integer nanometres.

mod arc;
pub mod path;
mod seg;
mod sqrt;

pub use arc::{Extents, P2, arc_extents, center_from_offsets, center_from_radius};
pub use seg::{Pt, Seg, SegKind};

//! The finishing shape of G70–G73 (and CYCLE95's contour) as the roughing
//! generators see it: segments in work coordinates. The interpreter reads it from
//! the program (`interp_core::cycles::profile`).

pub use crate::geom::{Seg, SegKind};

/// Most segments a finishing shape may have (alarm 4035 beyond).
pub const PROFILE_MAX: usize = 48;

/// The finishing shape A → B → … → C.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Profile {
    /// The segments in order; the first is the ns block's move from A.
    pub segs: heapless::Vec<Seg, PROFILE_MAX>,
    /// The ns block commanded X (or U).
    pub ns_x: bool,
    /// The ns block commanded Z (or W).
    pub ns_z: bool,
    /// The ns block is G00 (else G01).
    pub ns_rapid: bool,
}

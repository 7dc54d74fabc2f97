//! A machining centre's modal data beyond the lathe's (seed 004): tool length
//! compensation, the H/D numbers and the tool selected for M06, G28's
//! intermediate point, the initial level of a hole-cycle mode and the programmable
//! transformations (G16 polar coordinates, G51.1 mirror, G51 scaling, G68
//! rotation). Their logic is in [`crate::moves::frame`] and `exec`; the data lives
//! here, in the [`State`](super::State), so a failed block undoes it too.

use crate::alarm::AlarmKind;
use crate::axis::{Axis, AxisSet, Pos};
use crate::canon::Plane;

/// A coordinate of the machining centre's modal data, kept in 32 bits (±2,147 mm
/// or ±2,147°: beyond any machine this board drives) so that the data, copied
/// with the state four times in the interpreter, stays small. `None` (alarm 4017)
/// for a value beyond it.
pub fn narrow(v: i64) -> Result<i32, AlarmKind> {
    i32::try_from(v).map_err(|_| AlarmKind::Overflow)
}

/// Three coordinates narrowed ([`narrow`]).
pub fn narrow3(v: [i64; 3]) -> Result<[i32; 3], AlarmKind> {
    Ok([narrow(v[0])?, narrow(v[1])?, narrow(v[2])?])
}

/// Three coordinates widened.
pub fn wide3(v: [i32; 3]) -> [i64; 3] {
    v.map(i64::from)
}

/// An angle in µdeg brought into ±360° (what a G91 angle adds up to).
pub fn turn(udeg: i64) -> i32 {
    (udeg % 360_000_000) as i32
}

/// The modal data of a machining centre.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Mill {
    /// G43 (+1), G44 (−1) or G49 (0).
    pub length_sign: i8,
    /// The axis tool length compensation acts along: the normal of the plane in
    /// force when G43/G44 was given (FANUC's type B).
    pub length_axis: Axis,
    /// H in force (0 = none).
    pub h: u16,
    /// D in force (0 = none).
    pub d: u16,
    /// The tool T selected for the next M06.
    pub selected: u16,
    /// G28's intermediate point, work coordinates of X, Y, Z (those in `g28_axes`).
    pub g28: [i32; 3],
    /// The axes G28 has given an intermediate point since power-on or reset.
    pub g28_axes: AxisSet,
    /// The initial level of the hole-cycle mode in force, on the drilling axis
    /// (programmed): remembered from the mode's first hole to G80 or G00–G03.
    pub initial: Option<i32>,
    /// The programmable transformations.
    pub frame: Frame,
}

impl Default for Mill {
    fn default() -> Self {
        Mill {
            length_sign: 0,
            length_axis: Axis::Z,
            h: 0,
            d: 0,
            selected: 0,
            g28: [0; 3],
            g28_axes: AxisSet::EMPTY,
            initial: None,
            frame: Frame::default(),
        }
    }
}

/// What [`Frame::active`] holds: one bit per transformation in force.
pub mod on {
    /// G16: the plane's axis words are radius and angle.
    pub const POLAR: u8 = 1;
    /// G51.1: mirror image about `mirror_at` on the axes of `mirror`.
    pub const MIRROR: u8 = 2;
    /// G51: scaling about `scale_at` by `scale`.
    pub const SCALE: u8 = 4;
    /// G68: rotation by `rot_udeg` about `rot_at` in `rot_plane`.
    pub const ROTATE: u8 = 8;
}

/// The linear axes the transformations act on.
pub const FRAME_AXES: [Axis; 3] = [Axis::X, Axis::Y, Axis::Z];

/// The programmable transformations in force, in the order they apply to a
/// programmed point (FANUC 0i-M; seed 004 @5212, @5293): polar coordinates (an
/// input format), mirror image, scaling, rotation; then cutter and length
/// compensation (the contour layer and the work frame).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Frame {
    /// Bits of [`on`]: 0 when none is in force (the one test a block pays).
    pub active: u8,
    /// G51.1: the mirrored axes (bit per X, Y, Z).
    pub mirror: u8,
    /// G51.1: the mirror positions (programmed coordinates).
    pub mirror_at: [i32; 3],
    /// G51: the centre (programmed coordinates, mirrored).
    pub scale_at: [i32; 3],
    /// G51: the factors of X, Y, Z in thousandths (negative mirrors).
    pub scale: [i32; 3],
    /// G68: the centre in the plane (after mirror and scaling).
    pub rot_at: [i32; 2],
    /// G68: the angle, µdeg, counter-clockwise positive (within ±360°).
    pub rot_udeg: i32,
    /// G68: the plane of the rotation.
    pub rot_plane: Plane,
    /// G16: radius of the last polar command, nm.
    pub polar_r: i32,
    /// G16: angle of the last polar command, µdeg (within ±360°).
    pub polar_udeg: i32,
    /// The programmed position (before the transformations), work coordinates:
    /// what G91 adds to while a transformation is in force.
    pub prog: [i32; 3],
}

impl Default for Frame {
    fn default() -> Self {
        Frame {
            active: 0,
            mirror: 0,
            mirror_at: [0; 3],
            scale_at: [0; 3],
            scale: [1_000; 3],
            rot_at: [0; 2],
            rot_udeg: 0,
            rot_plane: Plane::Xy,
            polar_r: 0,
            polar_udeg: 0,
            prog: [0; 3],
        }
    }
}

impl Frame {
    /// Whether the transformations reverse the turning sense in `plane` (an odd
    /// number of mirrored axes of the plane): G02/G03 and G41/G42 swap.
    pub fn mirrors(&self, plane: Plane) -> bool {
        let (a, b) = plane.axes();
        let flips = |x: Axis| {
            let i = x.index();
            let m = self.active & on::MIRROR != 0 && self.mirror & (1 << i) != 0;
            let s = self.active & on::SCALE != 0 && self.scale.get(i).is_some_and(|k| *k < 0);
            m != s
        };
        flips(a) != flips(b)
    }
}

/// The mill's `Pos` with only X, Y and Z.
pub fn xyz(p: &Pos) -> [i64; 3] {
    [p[Axis::X], p[Axis::Y], p[Axis::Z]]
}

impl Frame {
    /// The programmed position.
    pub fn prog(&self) -> [i64; 3] {
        wide3(self.prog)
    }

    /// Sets the programmed position (alarm 4017 beyond ±2,147 mm).
    pub fn set_prog(&mut self, p: [i64; 3]) -> Result<(), AlarmKind> {
        self.prog = narrow3(p)?;
        Ok(())
    }
}

//! Axes and positions. One array indexed by [`Axis`] replaces per-axis copies of code.

use core::ops::{Add, Index, IndexMut, Sub};

/// A machine axis. X is the cross slide (radius internally), Z the carriage,
/// Y an optional cross axis (turning centres), C the spindle as a rotary axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Axis {
    /// Cross slide; positions are radii internally, programmed as diameters.
    X = 0,
    /// Optional Y axis (G17/G19 planes).
    Y = 1,
    /// Carriage, along the spindle axis.
    Z = 2,
    /// Spindle as a rotary axis, in micro-degrees.
    C = 3,
}

/// Number of axes a [`Pos`] holds.
pub const AXIS_COUNT: usize = 4;

impl Axis {
    /// All axes, in index order.
    pub const ALL: [Axis; AXIS_COUNT] = [Axis::X, Axis::Y, Axis::Z, Axis::C];

    /// The absolute-address letter (`X`, `Y`, `Z`, `C`).
    #[inline]
    pub const fn letter(self) -> u8 {
        match self {
            Axis::X => b'X',
            Axis::Y => b'Y',
            Axis::Z => b'Z',
            Axis::C => b'C',
        }
    }

    /// The incremental-address letter of system A (`U`, `V`, `W`, `H`).
    #[inline]
    pub const fn incremental_letter(self) -> u8 {
        match self {
            Axis::X => b'U',
            Axis::Y => b'V',
            Axis::Z => b'W',
            Axis::C => b'H',
        }
    }

    /// The arc-centre letter of this axis (`I`, `J`, `K`), none for C.
    #[inline]
    pub const fn center_letter(self) -> Option<u8> {
        match self {
            Axis::X => Some(b'I'),
            Axis::Y => Some(b'J'),
            Axis::Z => Some(b'K'),
            Axis::C => None,
        }
    }

    /// Whether the axis is rotary (values in micro-degrees).
    #[inline]
    pub const fn is_rotary(self) -> bool {
        matches!(self, Axis::C)
    }

    /// Index into a [`Pos`].
    #[inline]
    pub const fn index(self) -> usize {
        self as usize
    }
}

/// A position or displacement of all axes in internal units (nm, µdeg; X radius).
#[derive(Clone, Copy, Debug, Default, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Pos(pub [i64; AXIS_COUNT]);

/// Axis by axis without branches: the derived comparison of the array is a
/// `memcmp` call (~40 instructions on the M4) and positions are compared for
/// every move.
impl PartialEq for Pos {
    #[inline]
    fn eq(&self, other: &Pos) -> bool {
        let mut diff = 0;
        for (a, b) in self.0.iter().zip(&other.0) {
            diff |= a ^ b;
        }
        diff == 0
    }
}

impl Pos {
    /// All axes zero.
    pub const ZERO: Pos = Pos([0; AXIS_COUNT]);

    /// A position with X and Z set, the other axes zero.
    #[inline]
    pub const fn xz(x: i64, z: i64) -> Pos {
        Pos([x, 0, z, 0])
    }

    /// Component-wise checked addition.
    #[inline]
    pub fn checked_add(self, o: Pos) -> Option<Pos> {
        let mut r = [0; AXIS_COUNT];
        for (i, v) in r.iter_mut().enumerate() {
            *v = self.0[i].checked_add(o.0[i])?;
        }
        Some(Pos(r))
    }
}

impl Index<Axis> for Pos {
    type Output = i64;
    #[inline]
    fn index(&self, a: Axis) -> &i64 {
        &self.0[a.index()]
    }
}

impl IndexMut<Axis> for Pos {
    #[inline]
    fn index_mut(&mut self, a: Axis) -> &mut i64 {
        &mut self.0[a.index()]
    }
}

impl Add for Pos {
    type Output = Pos;
    #[inline]
    fn add(self, o: Pos) -> Pos {
        Pos(core::array::from_fn(|i| self.0[i].wrapping_add(o.0[i])))
    }
}

impl Sub for Pos {
    type Output = Pos;
    #[inline]
    fn sub(self, o: Pos) -> Pos {
        Pos(core::array::from_fn(|i| self.0[i].wrapping_sub(o.0[i])))
    }
}

/// A set of axes (bit per axis).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AxisSet(pub u8);

impl AxisSet {
    /// No axis.
    pub const EMPTY: AxisSet = AxisSet(0);

    /// Adds an axis.
    #[inline]
    pub fn insert(&mut self, a: Axis) {
        self.0 |= 1 << a.index();
    }

    /// Whether the set holds `a`.
    #[inline]
    pub const fn contains(self, a: Axis) -> bool {
        self.0 & (1 << a as u8) != 0
    }

    /// Whether the set is empty.
    #[inline]
    pub const fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// The axes of the set, in index order.
    #[inline]
    pub fn iter(self) -> impl Iterator<Item = Axis> {
        Axis::ALL.into_iter().filter(move |a| self.contains(*a))
    }
}

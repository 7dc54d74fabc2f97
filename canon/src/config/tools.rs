//! The tool offset table: what a lathe's T word offset number selects, and a
//! machining centre's H (length) and D (radius) numbers.

/// Number of offset rows (offset numbers 1..=MAX_OFFSETS; 0 means no offset).
pub const MAX_OFFSETS: usize = 32;

/// Largest magnitude of an offset value G10 may write: 999.999 mm (FANUC's
/// offset range in IS-B).
pub const MAX_OFFSET_VALUE: i64 = 999_999_000;

/// One row of the offset table, internal units (X values are radii).
///
/// A machining centre uses the rows as FANUC's offset memory C: H*n* and D*n*
/// both select row *n*, whose tool length (H, geometry and wear) and cutter
/// radius (D, geometry and wear) are the mill's offset pages. The length is kept
/// in `z`/`z_wear` (it acts along the tool axis), the radius in `radius`, the
/// radius wear in `x_wear` (a mill has no X tool offset); use the accessors
/// [`ToolOffset::length`], [`ToolOffset::cutter_radius`] and the `set_mill`
/// setter rather than these fields on a mill.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ToolOffset {
    /// Geometry offset of X (radius, nm).
    pub x: i64,
    /// Geometry offset of Z (nm).
    pub z: i64,
    /// Wear offset of X (radius, nm).
    pub x_wear: i64,
    /// Wear offset of Z (nm).
    pub z_wear: i64,
    /// Nose radius (nm), for nose radius compensation.
    pub radius: i64,
    /// Imaginary tip direction 0–9 (2.18.1); the SINUMERIK cutting edge position.
    pub tip: u8,
    /// Clearance (free cutting) angle of the edge, µdeg, 0–90°: the SINUMERIK
    /// offset parameter P24 (`$TC_DP24`) the turning cycles check undercuts against
    /// (seed 001 lines 10163–10184); 0 = no check.
    pub clearance_udeg: u32,
}

impl ToolOffset {
    /// Total shift of X (geometry + wear).
    #[inline]
    pub const fn total_x(&self) -> i64 {
        self.x + self.x_wear
    }

    /// Total shift of Z (geometry + wear).
    #[inline]
    pub const fn total_z(&self) -> i64 {
        self.z + self.z_wear
    }

    /// Mill: the tool length of H (geometry + wear).
    #[inline]
    pub const fn length(&self) -> i64 {
        self.z + self.z_wear
    }

    /// Mill: the cutter radius of D (geometry + wear).
    #[inline]
    pub const fn cutter_radius(&self) -> i64 {
        self.radius + self.x_wear
    }

    /// Mill: one column of the offset pages (what G10 L10–L13 write).
    pub fn mill_value(&self, page: MillPage) -> i64 {
        match page {
            MillPage::Length => self.z,
            MillPage::LengthWear => self.z_wear,
            MillPage::Radius => self.radius,
            MillPage::RadiusWear => self.x_wear,
        }
    }

    /// Mill: sets one column of the offset pages.
    pub fn set_mill(&mut self, page: MillPage, v: i64) {
        match page {
            MillPage::Length => self.z = v,
            MillPage::LengthWear => self.z_wear = v,
            MillPage::Radius => self.radius = v,
            MillPage::RadiusWear => self.x_wear = v,
        }
    }
}

/// A column of a machining centre's offset pages (G10 L10–L13, seed 004 @2152).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum MillPage {
    /// L10: tool length, geometry (H).
    Length,
    /// L11: tool length, wear (H).
    LengthWear,
    /// L12: cutter radius, geometry (D).
    Radius,
    /// L13: cutter radius, wear (D).
    RadiusWear,
}

/// The offset table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ToolTable {
    rows: [ToolOffset; MAX_OFFSETS],
}

impl Default for ToolTable {
    fn default() -> Self {
        ToolTable { rows: [ToolOffset::default(); MAX_OFFSETS] }
    }
}

impl ToolTable {
    /// Row `number` (1-based); `None` for 0 or past the table.
    #[inline]
    pub fn get(&self, number: u16) -> Option<&ToolOffset> {
        let i = usize::from(number).checked_sub(1)?;
        self.rows.get(i)
    }

    /// Mutable row `number` (1-based).
    #[inline]
    pub fn get_mut(&mut self, number: u16) -> Option<&mut ToolOffset> {
        let i = usize::from(number).checked_sub(1)?;
        self.rows.get_mut(i)
    }
}

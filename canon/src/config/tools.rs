//! The tool offset table: what a T word's offset number selects.

/// Number of offset rows (offset numbers 1..=MAX_OFFSETS; 0 means no offset).
pub const MAX_OFFSETS: usize = 32;

/// One row of the offset table, internal units (X values are radii).
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

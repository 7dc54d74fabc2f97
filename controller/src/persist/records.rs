//! Fixed-size records: numbered parameters, common variables #401–#600, work and
//! tool offsets.

use embedded_storage::nor_flash::{MultiwriteNorFlash, NorFlash};
use interp_core::Pos;
use interp_core::axis::AXIS_COUNT;
use interp_core::config::{EXTRA_FRAMES, ExtraOffsets, MAX_OFFSETS, ToolOffset, ToolTable};
use interp_core::lang::fanuc::macros::{COMMON_COUNT, CommonStore, FIRST_COMMON, LAST_COMMON, Value};

use super::keys::{self, Kind};
use super::{Error, Persist};

/// Number of work offsets (G54–G59).
const WORK_OFFSETS: usize = 6;
/// Record index of the external work offset among the work offset records.
const EXTERNAL: u16 = WORK_OFFSETS as u16;
/// Bytes of a stored position.
const POS_LEN: usize = 8 * AXIS_COUNT;
/// Bytes of a stored tool offset row.
const TOOL_LEN: usize = 8 * 5 + 4 + 1;
/// A tool record written before the clearance angle was stored (read as 0°).
const TOOL_LEN_OLD: usize = 8 * 5 + 1;
/// Bytes of a stored G54.1 offset: X, Y, Z as `i32` nm, as the interpreter holds them.
const EXTRA_LEN: usize = 4 * 3;

/// The offsets that survive power-off: G54–G59, the external work offset, the
/// tool offset table (all in nanometres, X as radius).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Offsets {
    /// G54–G59.
    pub work: [Pos; WORK_OFFSETS],
    /// The external work offset, added to all six.
    pub external: Pos,
    /// Tool offset rows 1–32.
    pub tools: ToolTable,
}

fn encode_pos(p: &Pos) -> [u8; POS_LEN] {
    let mut out = [0; POS_LEN];
    for (dst, v) in out.chunks_exact_mut(8).zip(p.0) {
        dst.copy_from_slice(&v.to_le_bytes());
    }
    out
}

fn decode_i64s<const N: usize>(bytes: &[u8]) -> [i64; N] {
    let mut out = [0; N];
    for (v, src) in out.iter_mut().zip(bytes.chunks_exact(8)) {
        let mut b = [0; 8];
        b.copy_from_slice(src);
        *v = i64::from_le_bytes(b);
    }
    out
}

fn encode_extra(row: [i32; 3]) -> [u8; EXTRA_LEN] {
    let mut out = [0; EXTRA_LEN];
    for (dst, v) in out.chunks_exact_mut(4).zip(row) {
        dst.copy_from_slice(&v.to_le_bytes());
    }
    out
}

fn decode_extra(bytes: &[u8]) -> [i32; 3] {
    let mut row = [0; 3];
    for (v, src) in row.iter_mut().zip(bytes.chunks_exact(4)) {
        let mut b = [0; 4];
        b.copy_from_slice(src);
        *v = i32::from_le_bytes(b);
    }
    row
}

fn encode_tool(t: &ToolOffset) -> [u8; TOOL_LEN] {
    let mut out = [0; TOOL_LEN];
    for (dst, v) in out.chunks_exact_mut(8).zip([t.x, t.z, t.x_wear, t.z_wear, t.radius]) {
        dst.copy_from_slice(&v.to_le_bytes());
    }
    out[40..44].copy_from_slice(&t.clearance_udeg.to_le_bytes());
    out[TOOL_LEN - 1] = t.tip;
    out
}

fn decode_tool(bytes: &[u8]) -> ToolOffset {
    let [x, z, x_wear, z_wear, radius] = decode_i64s::<5>(bytes);
    let clearance_udeg = match bytes.get(40..44) {
        Some(b) if bytes.len() == TOOL_LEN => u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        _ => 0,
    };
    ToolOffset { x, z, x_wear, z_wear, radius, tip: bytes.last().copied().unwrap_or(0), clearance_udeg }
}

/// `f64` bits of a variable value: NaN for null.
fn value_bits(v: Value) -> u64 {
    v.unwrap_or(f64::NAN).to_bits()
}

impl<F: NorFlash + MultiwriteNorFlash> Persist<F> {
    /// Stores parameter (setting) `n` = `value` (internal units), unless that is
    /// its stored value already.
    pub fn save_param(&mut self, n: u16, value: i64) -> Result<(), Error> {
        self.ready()?;
        self.put_if_changed(keys::param(n), &value.to_le_bytes())
    }

    /// Calls `f(n, value)` for the stored parameters, oldest record first: a
    /// number may come more than once, and its last call carries its current
    /// value (so applying every call in turn leaves the current values). One pass
    /// over the flash.
    pub fn load_params(&mut self, mut f: impl FnMut(u16, i64)) -> Result<(), Error> {
        self.ready()?;
        self.for_each_item(|key, value| {
            if keys::kind(key) == Some(Kind::Param) && value.len() == 8 {
                let [v] = decode_i64s::<1>(value);
                f(keys::number(key), v);
            }
        })
    }

    /// Stores the offsets that differ from the stored ones (one record per work
    /// offset and per tool row; each record is updated atomically).
    pub fn save_offsets(&mut self, offsets: &Offsets) -> Result<(), Error> {
        for (i, p) in (0u16..).zip(offsets.work.iter().chain([&offsets.external])) {
            self.save_work_offset(i, p)?;
        }
        for n in 1..=MAX_OFFSETS as u16 {
            if let Some(t) = offsets.tools.get(n) {
                self.save_tool_offset(n, t)?;
            }
        }
        Ok(())
    }

    /// Stores work offset `index` (0–5 = G54–G59, 6 = the external offset) unless
    /// unchanged.
    pub fn save_work_offset(&mut self, index: u16, p: &Pos) -> Result<(), Error> {
        if index > EXTERNAL {
            return Err(Error::BadNumber);
        }
        self.ready()?;
        self.put_if_changed(keys::work_offset(index), &encode_pos(p))
    }

    /// Stores tool offset row `n` (1–32) unless unchanged.
    pub fn save_tool_offset(&mut self, n: u16, t: &ToolOffset) -> Result<(), Error> {
        if !(1..=MAX_OFFSETS as u16).contains(&n) {
            return Err(Error::BadNumber);
        }
        self.ready()?;
        self.put_if_changed(keys::tool_offset(n), &encode_tool(t))
    }

    /// Stores the G54.1 P1–P48 offsets that differ from the stored ones (one
    /// record each, updated atomically); a row never stored that is still zero is
    /// not written (absent reads as zero). Nothing in a build without the mill
    /// profile (`interp_core::MILL`).
    pub fn save_extra_offsets(&mut self, extra: &ExtraOffsets) -> Result<(), Error> {
        if !interp_core::MILL {
            return Ok(());
        }
        self.ready()?;
        for p in 1..=EXTRA_FRAMES as u8 {
            let Some(row) = extra.row(p) else { continue };
            let bytes = encode_extra(row);
            match self.with_value(keys::extra_offset(p), |old| old == bytes)? {
                Some(true) => {}
                None if row == [0; 3] => {}
                _ => self.put(keys::extra_offset(p), &bytes)?,
            }
        }
        Ok(())
    }

    /// Reads the stored G54.1 offsets into `extra` (rows never stored keep their
    /// value). One pass over the flash; nothing without the mill profile.
    pub fn load_extra_offsets(&mut self, extra: &mut ExtraOffsets) -> Result<(), Error> {
        if !interp_core::MILL {
            return Ok(());
        }
        self.ready()?;
        self.for_each_item(|key, value| {
            if keys::kind(key) == Some(Kind::ExtraOffset) && value.len() == EXTRA_LEN {
                // A key outside P1–P48 (none is ever written) is skipped.
                let _ = u8::try_from(keys::number(key)).map(|p| extra.set_row(p, decode_extra(value)));
            }
        })
    }

    /// Reads the stored offsets into `offsets` (records never stored leave their
    /// field as it was). One pass over the flash.
    pub fn load_offsets(&mut self, offsets: &mut Offsets) -> Result<(), Error> {
        self.ready()?;
        self.for_each_item(|key, value| match keys::kind(key) {
            Some(Kind::WorkOffset) if value.len() == POS_LEN => {
                let n = keys::number(key);
                let p = Pos(decode_i64s::<AXIS_COUNT>(value));
                if n == EXTERNAL {
                    offsets.external = p;
                } else if let Some(slot) = offsets.work.get_mut(usize::from(n)) {
                    *slot = p;
                }
            }
            Some(Kind::ToolOffset) if value.len() == TOOL_LEN || value.len() == TOOL_LEN_OLD => {
                if let Some(row) = offsets.tools.get_mut(keys::number(key)) {
                    *row = decode_tool(value);
                }
            }
            _ => {}
        })
    }

    /// The commons mirror, read from flash in one pass the first time.
    fn commons(&mut self) -> Result<&mut [u64; COMMON_COUNT], Error> {
        if self.commons.is_none() {
            self.ready()?;
            let mut mirror = [f64::NAN.to_bits(); COMMON_COUNT];
            self.for_each_item(|key, value| {
                let slot = usize::from(keys::number(key)).checked_sub(usize::from(FIRST_COMMON));
                if keys::kind(key) == Some(Kind::Common)
                    && let (Some(slot), Ok(bits)) = (slot.and_then(|i| mirror.get_mut(i)), <[u8; 8]>::try_from(value))
                {
                    *slot = u64::from_le_bytes(bits);
                }
            })?;
            self.commons = Some(mirror);
        }
        self.commons.as_mut().ok_or(Error::Internal)
    }
}

/// Common variables #401–#600: read from the RAM mirror, written through to flash
/// only when the value changes.
impl<F: NorFlash + MultiwriteNorFlash> CommonStore for Persist<F> {
    type Error = Error;

    fn load(&mut self, number: u16) -> Result<Value, Error> {
        let i = common_index(number)?;
        let bits = *self.commons()?.get(i).ok_or(Error::BadNumber)?;
        let v = f64::from_bits(bits);
        Ok(if v.is_nan() { None } else { Some(v) })
    }

    fn store(&mut self, number: u16, value: Value) -> Result<(), Error> {
        let i = common_index(number)?;
        let bits = value_bits(value);
        if *self.commons()?.get(i).ok_or(Error::BadNumber)? == bits {
            return Ok(());
        }
        self.put(keys::common(number), &bits.to_le_bytes())?;
        if let Some(slot) = self.commons.as_mut().and_then(|m| m.get_mut(i)) {
            *slot = bits;
        }
        Ok(())
    }
}

/// Index of common variable `n` in the mirror.
fn common_index(n: u16) -> Result<usize, Error> {
    if (FIRST_COMMON..=LAST_COMMON).contains(&n) { Ok(usize::from(n - FIRST_COMMON)) } else { Err(Error::BadNumber) }
}

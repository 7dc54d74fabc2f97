//! A simulated NOR flash for host tests and the host's virtual board, with
//! power-cut injection. The firmware does not use it (and so does not link it).
//!
//! It behaves like the STM32F4's embedded flash as the store sees it: erased bytes
//! read `0xFF`; programming can only clear bits (a word programmed twice holds the
//! AND of both values); programming goes by `WRITE`-byte words at `WRITE`-aligned
//! offsets; erasing goes by whole `ERASE`-byte sectors.
//!
//! Every programmed word and every erased sector counts as one operation. With
//! [`SimFlash::cut_power_at`] the `k`-th operation is interrupted half-way — a word
//! partly programmed, a sector partly erased — and fails, as does every access after
//! it until [`SimFlash::restore_power`]: a power cut, then a restart.

use embedded_storage::nor_flash::{
    ErrorType, MultiwriteNorFlash, NorFlash, NorFlashError, NorFlashErrorKind, ReadNorFlash,
};

/// Most sectors a [`SimFlash`] tracks erase counts for.
pub const MAX_SIM_SECTORS: usize = 64;

/// What went wrong in the simulated flash.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SimError {
    /// Power is off: the operation was cut or came after the cut.
    PowerLost,
    /// Offset or length not a multiple of the write or erase size.
    NotAligned,
    /// Past the end of the flash.
    OutOfBounds,
}

impl NorFlashError for SimError {
    fn kind(&self) -> NorFlashErrorKind {
        match self {
            SimError::PowerLost => NorFlashErrorKind::Other,
            SimError::NotAligned => NorFlashErrorKind::NotAligned,
            SimError::OutOfBounds => NorFlashErrorKind::OutOfBounds,
        }
    }
}

/// `SIZE` bytes of simulated flash in `ERASE`-byte sectors, programmed in
/// `WRITE`-byte words. `SIZE` must be a multiple of `ERASE`, with at most
/// [`MAX_SIM_SECTORS`] sectors.
#[derive(Clone, Debug)]
pub struct SimFlash<const SIZE: usize, const ERASE: usize, const WRITE: usize> {
    bytes: [u8; SIZE],
    /// Operations (word programs, sector erases) started so far.
    ops: u64,
    /// The operation that loses power, if one is armed.
    cut_at: Option<u64>,
    powered: bool,
    erases: [u32; MAX_SIM_SECTORS],
    /// Words programmed with a 1 over a 0 (which programming cannot set).
    ones_over_zeros: u64,
}

impl<const SIZE: usize, const ERASE: usize, const WRITE: usize> Default for SimFlash<SIZE, ERASE, WRITE> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const SIZE: usize, const ERASE: usize, const WRITE: usize> SimFlash<SIZE, ERASE, WRITE> {
    const GEOMETRY_OK: () = assert!(
        ERASE > 0
            && WRITE > 0
            && SIZE.is_multiple_of(ERASE)
            && ERASE.is_multiple_of(WRITE)
            && SIZE / ERASE <= MAX_SIM_SECTORS
    );

    /// Erased flash, powered, no cut armed.
    pub const fn new() -> Self {
        let () = Self::GEOMETRY_OK;
        SimFlash {
            bytes: [0xFF; SIZE],
            ops: 0,
            cut_at: None,
            powered: true,
            erases: [0; MAX_SIM_SECTORS],
            ones_over_zeros: 0,
        }
    }

    /// Operations started so far (each programmed word, each erased sector).
    pub const fn ops(&self) -> u64 {
        self.ops
    }

    /// Arms a power cut: operation number `k` (counting from 1 at creation, as
    /// [`Self::ops`] counts) is done half-way and fails, and so does every access
    /// after it.
    pub fn cut_power_at(&mut self, k: u64) {
        self.cut_at = Some(k);
    }

    /// Power back on (a restart): accesses work again, no cut is armed.
    pub fn restore_power(&mut self) {
        self.cut_at = None;
        self.powered = true;
    }

    /// Whether a cut has happened and power is still off.
    pub const fn power_lost(&self) -> bool {
        !self.powered
    }

    /// How often each sector was erased, sector 0 first.
    pub fn erase_counts(&self) -> &[u32] {
        self.erases.get(..SIZE / ERASE).unwrap_or(&[])
    }

    /// Words programmed with a 1 bit over a 0 bit (a store bug if not 0).
    pub const fn ones_over_zeros(&self) -> u64 {
        self.ones_over_zeros
    }

    /// The raw contents.
    pub fn contents(&self) -> &[u8] {
        &self.bytes
    }

    /// Starts the next operation: `Ok(true)` to do it, `Ok(false)` to do it
    /// half-way (the cut), `Err` when power is off.
    fn begin_op(&mut self) -> Result<bool, SimError> {
        if !self.powered {
            return Err(SimError::PowerLost);
        }
        self.ops += 1;
        if self.cut_at == Some(self.ops) {
            self.powered = false;
            return Ok(false);
        }
        Ok(true)
    }

    /// Programs one word at `at` (in bounds, aligned); `variant` picks how much
    /// of a cut word gets programmed.
    fn program_word(&mut self, at: usize, word: &[u8], whole: bool) {
        let variant = self.ops % 3;
        let Some(cells) = self.bytes.get_mut(at..at + word.len()) else { return };
        for (i, (cell, new)) in cells.iter_mut().zip(word).enumerate() {
            if *new & !*cell != 0 {
                self.ones_over_zeros += 1;
            }
            let programmed = match (whole, variant) {
                (true, _) | (false, 2) => *new,
                // The first half of the word's bytes (the low nibble of a 1-byte word).
                (false, 1) if WRITE == 1 => *new | 0xF0,
                (false, 1) if i < WRITE / 2 => *new,
                _ => 0xFF,
            };
            *cell &= programmed;
        }
    }

    /// Erases the sector at `at` (in bounds, aligned), half-way if `whole` is
    /// false: nothing, the first half, or every other 64-byte block.
    fn erase_sector(&mut self, at: usize, whole: bool) {
        let variant = self.ops % 3;
        if let Some(count) = self.erases.get_mut(at / ERASE) {
            *count += 1;
        }
        let Some(cells) = self.bytes.get_mut(at..at + ERASE) else { return };
        for (i, cell) in cells.iter_mut().enumerate() {
            let erase = match (whole, variant) {
                (true, _) => true,
                (false, 1) => i < ERASE / 2,
                (false, 2) => (i / 64) % 2 == 0,
                _ => false,
            };
            if erase {
                *cell = 0xFF;
            }
        }
    }
}

impl<const SIZE: usize, const ERASE: usize, const WRITE: usize> ErrorType for SimFlash<SIZE, ERASE, WRITE> {
    type Error = SimError;
}

impl<const SIZE: usize, const ERASE: usize, const WRITE: usize> ReadNorFlash for SimFlash<SIZE, ERASE, WRITE> {
    const READ_SIZE: usize = 1;

    fn read(&mut self, offset: u32, bytes: &mut [u8]) -> Result<(), Self::Error> {
        if !self.powered {
            return Err(SimError::PowerLost);
        }
        let start = offset as usize;
        let end = start.checked_add(bytes.len()).ok_or(SimError::OutOfBounds)?;
        let src = self.bytes.get(start..end).ok_or(SimError::OutOfBounds)?;
        bytes.copy_from_slice(src);
        Ok(())
    }

    fn capacity(&self) -> usize {
        SIZE
    }
}

impl<const SIZE: usize, const ERASE: usize, const WRITE: usize> NorFlash for SimFlash<SIZE, ERASE, WRITE> {
    const WRITE_SIZE: usize = WRITE;
    const ERASE_SIZE: usize = ERASE;

    fn erase(&mut self, from: u32, to: u32) -> Result<(), Self::Error> {
        let (from, to) = (from as usize, to as usize);
        if !from.is_multiple_of(ERASE) || !to.is_multiple_of(ERASE) || from > to {
            return Err(SimError::NotAligned);
        }
        if to > SIZE {
            return Err(SimError::OutOfBounds);
        }
        for at in (from..to).step_by(ERASE) {
            let whole = self.begin_op()?;
            self.erase_sector(at, whole);
            if !whole {
                return Err(SimError::PowerLost);
            }
        }
        Ok(())
    }

    fn write(&mut self, offset: u32, bytes: &[u8]) -> Result<(), Self::Error> {
        let start = offset as usize;
        if !start.is_multiple_of(WRITE) || !bytes.len().is_multiple_of(WRITE) {
            return Err(SimError::NotAligned);
        }
        if start.checked_add(bytes.len()).is_none_or(|end| end > SIZE) {
            return Err(SimError::OutOfBounds);
        }
        for (i, word) in bytes.chunks(WRITE).enumerate() {
            let whole = self.begin_op()?;
            self.program_word(start + i * WRITE, word, whole);
            if !whole {
                return Err(SimError::PowerLost);
            }
        }
        Ok(())
    }
}

/// Programming only clears bits, as on the STM32F4.
impl<const SIZE: usize, const ERASE: usize, const WRITE: usize> MultiwriteNorFlash for SimFlash<SIZE, ERASE, WRITE> {}

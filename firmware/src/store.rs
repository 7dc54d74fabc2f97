//! The flash region reserved for the controller's store (settings, offsets, common
//! variables, programs): `embedded_storage::nor_flash::NorFlash` with offsets
//! counted from the region's start, so the store cannot touch the program.
//!
//! Region (memory.x keeps the linker out of it): STM32F405RG sectors 10–11,
//! 0x080C0000..0x08100000; STM32F446RE sectors 6–7, 0x08040000..0x08080000. Both are
//! two 128 KB sectors (`ERASE_SIZE`), written in 4-byte words.
//!
//! Erasing or writing flash stalls instruction fetches from flash, interrupts
//! included (a 128 KB sector erase takes 1–2 s): the controller must write the store
//! only while the machine is idle (no motion, spindle stopped).

use embassy_stm32::flash::{Blocking, Error, Flash};
use embedded_storage::nor_flash::{ErrorType, NorFlash, NorFlashError, NorFlashErrorKind, ReadNorFlash};

use crate::board::{STORE_SIZE, STORE_START};

/// Flash base address (offset 0 of embassy's `Flash`).
const FLASH_BASE: u32 = 0x0800_0000;

/// The store region of the on-chip flash.
pub struct Store {
    flash: Flash<'static, Blocking>,
}

/// A store access failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, defmt::Format)]
pub enum StoreError {
    /// Offset or length outside the region.
    OutOfBounds,
    /// Not aligned to the write or erase size.
    NotAligned,
    /// The flash controller reported an error.
    Flash,
}

impl NorFlashError for StoreError {
    fn kind(&self) -> NorFlashErrorKind {
        match self {
            StoreError::OutOfBounds => NorFlashErrorKind::OutOfBounds,
            StoreError::NotAligned => NorFlashErrorKind::NotAligned,
            StoreError::Flash => NorFlashErrorKind::Other,
        }
    }
}

impl From<Error> for StoreError {
    fn from(e: Error) -> Self {
        match e {
            Error::Size => StoreError::OutOfBounds,
            Error::Unaligned => StoreError::NotAligned,
            _ => StoreError::Flash,
        }
    }
}

impl Store {
    /// The store on the board's flash.
    pub fn new(flash: Flash<'static, Blocking>) -> Self {
        Store { flash }
    }

    /// The flash offset of region offset `offset` for `len` bytes, if inside.
    fn at(offset: u32, len: usize) -> Result<u32, StoreError> {
        let len = u32::try_from(len).map_err(|_| StoreError::OutOfBounds)?;
        match offset.checked_add(len) {
            Some(end) if end <= STORE_SIZE => Ok(STORE_START - FLASH_BASE + offset),
            _ => Err(StoreError::OutOfBounds),
        }
    }
}

impl ErrorType for Store {
    type Error = StoreError;
}

impl ReadNorFlash for Store {
    const READ_SIZE: usize = 1;

    fn read(&mut self, offset: u32, bytes: &mut [u8]) -> Result<(), StoreError> {
        let at = Self::at(offset, bytes.len())?;
        Ok(self.flash.blocking_read(at, bytes)?)
    }

    fn capacity(&self) -> usize {
        STORE_SIZE as usize
    }
}

impl NorFlash for Store {
    const WRITE_SIZE: usize = 4;
    const ERASE_SIZE: usize = 128 * 1024;

    fn write(&mut self, offset: u32, bytes: &[u8]) -> Result<(), StoreError> {
        let at = Self::at(offset, bytes.len())?;
        Ok(self.flash.blocking_write(at, bytes)?)
    }

    fn erase(&mut self, from: u32, to: u32) -> Result<(), StoreError> {
        let len = to.checked_sub(from).ok_or(StoreError::OutOfBounds)?;
        let at = Self::at(from, len as usize)?;
        Ok(self.flash.blocking_erase(at, at + len)?)
    }
}

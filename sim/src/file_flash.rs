//! A NOR flash kept in a file: the virtual board's store (`lathe board --flash`),
//! with the geometry of the F405's store (two 128 KB sectors), so that what the
//! board keeps (settings, offsets, common variables, programs) survives a restart
//! of the virtual board as it survives power-off on the real one. Every erase and
//! write goes to the file at once.

use std::fs::{File, OpenOptions};
use std::io::{Read, Seek, SeekFrom, Write};
use std::path::Path;

use embedded_storage::nor_flash::{
    ErrorType, MultiwriteNorFlash, NorFlash, NorFlashError, NorFlashErrorKind, ReadNorFlash, check_erase, check_read,
    check_write,
};

/// Sector size, bytes (the F405's sectors 10 and 11).
pub const SECTOR: usize = 128 * 1024;
/// Size of the store, bytes.
pub const SIZE: usize = 2 * SECTOR;

/// What can go wrong with the flash file.
#[derive(Debug)]
pub enum FileFlashError {
    /// Not a flash operation the geometry allows.
    Geometry(NorFlashErrorKind),
    /// The file could not be read or written.
    Io(std::io::Error),
    /// The file exists but is not a store image of [`SIZE`] bytes.
    WrongSize(u64),
}

impl core::fmt::Display for FileFlashError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            FileFlashError::Geometry(k) => write!(f, "flash access outside the store: {k:?}"),
            FileFlashError::Io(e) => write!(f, "{e}"),
            FileFlashError::WrongSize(n) => write!(f, "{n} bytes: a store image is {SIZE} bytes"),
        }
    }
}

impl std::error::Error for FileFlashError {}

impl NorFlashError for FileFlashError {
    fn kind(&self) -> NorFlashErrorKind {
        match self {
            FileFlashError::Geometry(k) => *k,
            _ => NorFlashErrorKind::Other,
        }
    }
}

/// The flash: its bytes in memory, written through to the file.
pub struct FileFlash {
    bytes: Vec<u8>,
    file: File,
}

impl FileFlash {
    /// Opens the store image at `path`, or creates an erased one.
    pub fn open(path: &Path) -> Result<Self, FileFlashError> {
        let mut file = OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(path)
            .map_err(FileFlashError::Io)?;
        let len = file.metadata().map_err(FileFlashError::Io)?.len();
        let mut bytes = vec![0xFF; SIZE];
        match len {
            0 => file.write_all(&bytes).map_err(FileFlashError::Io)?,
            n if n == SIZE as u64 => file.read_exact(&mut bytes).map_err(FileFlashError::Io)?,
            n => return Err(FileFlashError::WrongSize(n)),
        }
        Ok(FileFlash { bytes, file })
    }

    /// Writes `bytes[from..to]` to the file.
    fn sync(&mut self, from: usize, to: usize) -> Result<(), FileFlashError> {
        let part = self.bytes.get(from..to).ok_or(FileFlashError::Geometry(NorFlashErrorKind::OutOfBounds))?;
        self.file.seek(SeekFrom::Start(from as u64)).map_err(FileFlashError::Io)?;
        self.file.write_all(part).map_err(FileFlashError::Io)
    }
}

impl ErrorType for FileFlash {
    type Error = FileFlashError;
}

impl ReadNorFlash for FileFlash {
    const READ_SIZE: usize = 1;

    fn read(&mut self, offset: u32, out: &mut [u8]) -> Result<(), Self::Error> {
        check_read(self, offset, out.len()).map_err(FileFlashError::Geometry)?;
        let from = offset as usize;
        let src =
            self.bytes.get(from..from + out.len()).ok_or(FileFlashError::Geometry(NorFlashErrorKind::OutOfBounds))?;
        out.copy_from_slice(src);
        Ok(())
    }

    fn capacity(&self) -> usize {
        SIZE
    }
}

impl NorFlash for FileFlash {
    const WRITE_SIZE: usize = 4;
    const ERASE_SIZE: usize = SECTOR;

    fn erase(&mut self, from: u32, to: u32) -> Result<(), Self::Error> {
        check_erase(self, from, to).map_err(FileFlashError::Geometry)?;
        let (from, to) = (from as usize, to as usize);
        self.bytes.get_mut(from..to).ok_or(FileFlashError::Geometry(NorFlashErrorKind::OutOfBounds))?.fill(0xFF);
        self.sync(from, to)
    }

    /// Programming clears bits only, as on NOR flash.
    fn write(&mut self, offset: u32, data: &[u8]) -> Result<(), Self::Error> {
        check_write(self, offset, data.len()).map_err(FileFlashError::Geometry)?;
        let from = offset as usize;
        let dst = self
            .bytes
            .get_mut(from..from + data.len())
            .ok_or(FileFlashError::Geometry(NorFlashErrorKind::OutOfBounds))?;
        dst.iter_mut().zip(data).for_each(|(d, s)| *d &= *s);
        self.sync(from, from + data.len())
    }
}

/// Words can be programmed again (with bits only cleared), as the STM32F4's can.
impl MultiwriteNorFlash for FileFlash {}

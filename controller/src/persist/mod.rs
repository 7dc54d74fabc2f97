//! Persistence: what survives power-off (settings, offsets, common variables
//! #401–#600, the program store) on NOR flash.
//!
//! [`Persist`] keeps every record as an item of a `sequential-storage` map: a
//! wear-levelling, power-fail-safe key-value log over whole flash pages (sectors).
//! Writing a record appends a new item; a full page is closed and the next one
//! opened; before a page is reused, its items that are still current are copied
//! forward and the page is erased — pages are used in turn, so all wear alike.
//! Every item carries CRCs: an item cut short by a power loss reads as absent and
//! the previous value stays. See [`keys`] for what each record holds.
//!
//! Each parameter, common variable and offset record is one item, so an update of
//! one is atomic. A program text is split into chunks (items of at most
//! [`MAX_CHUNK`] bytes) written under a new *generation*, then committed by one
//! header item (length, CRC-32, generation); the old generation's chunks are then
//! deleted. A one-item journal records the update in flight, so a restart finishes
//! or undoes it: a program reads back as the old text or the new, never a mix.
//!
//! # Flash layout and size
//! The range given to [`Persist::new`] is whole erase sectors of equal size, at
//! least two, at most [`MAX_PAGES`], in the flash driver's offsets. The map keeps
//! one page erased for moving live items, so what is stored must fit into the
//! other pages (each item costs 8 bytes of header and a 4-byte key, padded to the
//! flash word), and replacing a program needs room for its old and new text at
//! once. Records: a parameter or common ~24 B, a work offset ~48 B, a G54.1 offset ~24 B, a tool row
//! ~56 B (39 offset records ~2 KB), a program its length plus ~16 B per chunk.
//!
//! On the STM32F405 use **sectors 10–11** (`0x080C_0000..0x0810_0000`, 2 × 128 KB):
//! 128 KB of live data. Measured on the simulated F405 sectors: 200 commons, 100
//! parameters, four 20 KB programs each replaced once, then 40 KB more — 120 KB of
//! program text in all. Sectors 8–11 (4 × 128 KB) would hold ~380 KB; sectors 1–3
//! (3 × 16 KB) only ~30 KB, too little for programs. Erasing a 128 KB sector takes
//! 1–2 s on the F4 and stalls the CPU (as does programming): persist when idle.
//!
//! # On the board
//! embassy-stm32's blocking `Flash` (offsets from `0x0800_0000`, erase size 128 KB)
//! implements the blocking `NorFlash`; wrap it in [`Rewritable`] (the F4 may program
//! a word twice, which the store uses to mark items deleted):
//! `Persist::new(Rewritable(Flash::new_blocking(p.FLASH)), 0xC_0000..0x10_0000)`.
//! The first call after power-on settles an update a power cut interrupted. If a
//! call returns [`Error::Corrupted`] the pages are beyond repair: [`Persist::format`].
//!
//! # RAM and stack
//! `Persist` is ~4.9 KB: the item buffer ([`MAX_CHUNK`] + 64 B), the mirror of the
//! 200 commons (1.6 KB), the key-location cache ([`KEY_CACHE`] × 8 B). Each call
//! runs the storage crate's future to completion on the caller's stack (< 1 KB).
//!
//! # Host tests
//! [`sim::SimFlash`] is a simulated NOR flash with power-cut injection; the
//! firmware does not use it, so it is not linked there.
//!
//! # Example
//! ```
//! use controller::persist::sim::SimFlash;
//! use controller::persist::{Offsets, Persist};
//! use interp_core::lang::fanuc::macros::Variables;
//!
//! let mut flash = SimFlash::<{ 4 * 2048 }, 2048, 4>::new();
//! let mut store = Persist::new(&mut flash, 0..4 * 2048)?;
//! store.save_param(5147, 1_500_000)?;
//! store.save_program(1, b"O0001\nG00 X10 Z2\nM30\n")?;
//! let mut vars = Variables::new();
//! vars.set(401, Some(2.5)).unwrap();
//! vars.flush_commons(&mut store)?; // writes only the commons that changed
//!
//! // After a restart:
//! let mut store = Persist::new(&mut flash, 0..4 * 2048)?;
//! let mut vars = Variables::new();
//! vars.load_commons(&mut store)?;
//! assert_eq!(vars.get(401).unwrap(), Some(2.5));
//! store.load_params(|n, v| assert_eq!((n, v), (5147, 1_500_000)))?;
//! let mut offsets = Offsets::default();
//! store.load_offsets(&mut offsets)?;
//! let mut text = [0u8; 64];
//! let len = store.load_program(1, &mut text)?;
//! assert_eq!(&text[..len], b"O0001\nG00 X10 Z2\nM30\n");
//! assert_eq!(store.programs::<8>()?.len(), 1);
//! # Ok::<(), controller::persist::Error>(())
//! ```

mod flash;
pub mod keep;
pub mod keys;
mod programs;
mod records;
pub mod sim;

use core::fmt;
use core::ops::Range;

use embassy_futures::block_on;
use embedded_storage::nor_flash::{MultiwriteNorFlash, NorFlash, NorFlashError, NorFlashErrorKind};
use interp_core::lang::fanuc::macros::COMMON_COUNT;
use sequential_storage::cache::Cache;
use sequential_storage::cache::key_pointers::ArrayKeyPointers;
use sequential_storage::cache::page_pointers::ArrayPagePointers;
use sequential_storage::cache::page_states::ArrayPageStates;
use sequential_storage::map::{MapConfig, MapStorage};

use flash::AsAsync;
pub use flash::Rewritable;
pub use programs::{MAX_PROGRAM_NUMBER, ProgramInfo};
pub use records::Offsets;

/// Most pages (erase sectors) the flash range may have.
pub const MAX_PAGES: usize = 16;
/// Keys whose flash location is cached in RAM (8 bytes each); more keys work,
/// just slower (a lookup of an uncached key scans the pages).
pub const KEY_CACHE: usize = 256;
/// Largest program chunk (one map item) in bytes; smaller on small pages
/// (an eighth of a page).
pub const MAX_CHUNK: usize = 1024;
/// Item buffer: a chunk plus key, rounded up for any flash word size.
const BUF_LEN: usize = MAX_CHUNK + 64;

/// Why a persistence operation failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Error {
    /// The flash reported an error (on the simulated flash: a power cut).
    Flash(NorFlashErrorKind),
    /// Not enough free space for the record; what was stored before stays.
    Full,
    /// The store's pages are corrupt beyond automatic repair: [`Persist::format`].
    Corrupted,
    /// The flash range is not whole sectors, fewer than two, more than
    /// [`MAX_PAGES`], or past the end of the flash.
    BadRange,
    /// A parameter, variable, offset or program number out of range.
    BadNumber,
    /// A program text longer than the store can ever hold.
    TooBig,
    /// The caller's buffer is smaller than the program.
    BufferTooSmall {
        /// Bytes needed.
        needed: usize,
    },
    /// No program with this O number is stored.
    NoProgram {
        /// Its O number.
        program: u16,
    },
    /// More stored programs than the caller's list or program memory holds.
    TooManyPrograms,
    /// A stored program does not match its header (length or CRC).
    Damaged {
        /// Its O number.
        program: u16,
    },
    /// The storage crate reported a logic or serialisation error.
    Internal,
}

/// The board's log of a store error, without `core::fmt` (written by hand: the flash
/// error kind has no `defmt::Format`).
#[cfg(feature = "defmt")]
impl defmt::Format for Error {
    fn format(&self, f: defmt::Formatter<'_>) {
        match self {
            Error::Flash(NorFlashErrorKind::NotAligned) => defmt::write!(f, "flash error: not aligned"),
            Error::Flash(NorFlashErrorKind::OutOfBounds) => defmt::write!(f, "flash error: out of bounds"),
            Error::Flash(_) => defmt::write!(f, "flash error"),
            Error::Full => defmt::write!(f, "persistent storage is full"),
            Error::Corrupted => defmt::write!(f, "persistent storage is corrupted: format it"),
            Error::BadRange => defmt::write!(f, "bad flash range for persistent storage"),
            Error::BadNumber => defmt::write!(f, "number out of range"),
            Error::TooBig => defmt::write!(f, "program too big for persistent storage"),
            Error::BufferTooSmall { needed } => defmt::write!(f, "buffer too small: {} bytes needed", needed),
            Error::NoProgram { program } => defmt::write!(f, "program O{=u16} is not stored", program),
            Error::TooManyPrograms => defmt::write!(f, "more stored programs than room for them"),
            Error::Damaged { program } => defmt::write!(f, "stored program O{=u16} is damaged", program),
            Error::Internal => defmt::write!(f, "internal storage error"),
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Flash(kind) => write!(f, "flash error: {kind:?}"),
            Error::Full => write!(f, "persistent storage is full"),
            Error::Corrupted => write!(f, "persistent storage is corrupted: format it"),
            Error::BadRange => write!(f, "bad flash range for persistent storage"),
            Error::BadNumber => write!(f, "number out of range"),
            Error::TooBig => write!(f, "program too big for persistent storage"),
            Error::BufferTooSmall { needed } => write!(f, "buffer too small: {needed} bytes needed"),
            Error::NoProgram { program } => write!(f, "program O{program:04} is not stored"),
            Error::TooManyPrograms => write!(f, "more stored programs than room for them"),
            Error::Damaged { program } => write!(f, "stored program O{program:04} is damaged"),
            Error::Internal => write!(f, "internal storage error"),
        }
    }
}

impl<E: NorFlashError> From<sequential_storage::Error<E>> for Error {
    fn from(e: sequential_storage::Error<E>) -> Self {
        match e {
            sequential_storage::Error::Storage { value, .. } => Error::Flash(value.kind()),
            sequential_storage::Error::FullStorage => Error::Full,
            sequential_storage::Error::Corrupted { .. } => Error::Corrupted,
            sequential_storage::Error::ItemTooBig => Error::TooBig,
            _ => Error::Internal,
        }
    }
}

type StoreCache =
    Cache<ArrayPageStates<MAX_PAGES>, ArrayPagePointers<MAX_PAGES>, ArrayKeyPointers<u32, KEY_CACHE>, u32>;
type Map<F> = MapStorage<u32, AsAsync<F>, StoreCache>;

/// The item buffer, aligned for flash drivers that want aligned sources.
#[repr(align(16))]
struct Buf([u8; BUF_LEN]);

/// The persistent store on a NOR flash range (see the module docs for layout).
/// Blocking: each call returns when the flash is written.
pub struct Persist<F: NorFlash + MultiwriteNorFlash> {
    /// Always `Some` except inside [`Persist::format`].
    map: Option<Map<F>>,
    buf: Buf,
    /// Chunk size of programs saved from now on.
    chunk: usize,
    /// Commons #401–#600 as `f64` bits (NaN = null), once read from flash.
    commons: Option<[u64; COMMON_COUNT]>,
    /// Whether the journal was checked since the store was opened.
    journal_done: bool,
}

impl<F: NorFlash + MultiwriteNorFlash> Persist<F> {
    /// The store over `range` (byte offsets as the flash driver counts them) of
    /// `flash`. Reads nothing yet: the first operation finishes or undoes an update
    /// a power cut interrupted.
    pub fn new(flash: F, range: Range<u32>) -> Result<Self, Error> {
        if range.start >= range.end {
            return Err(Error::BadRange);
        }
        let config = MapConfig::<AsAsync<F>>::try_new(range.clone()).map_err(|_| Error::BadRange)?;
        let pages = (range.end - range.start) as usize / F::ERASE_SIZE.max(1);
        if pages > MAX_PAGES || range.end as usize > flash.capacity() {
            return Err(Error::BadRange);
        }
        let chunk = (F::ERASE_SIZE / 8 / 16 * 16).clamp(16, MAX_CHUNK);
        Ok(Persist {
            map: Some(MapStorage::new(AsAsync(flash), config, new_cache())),
            buf: Buf([0; BUF_LEN]),
            chunk,
            commons: None,
            journal_done: false,
        })
    }

    /// Gives the flash back (always `Some`: the store is only ever without its
    /// flash inside [`Self::format`]).
    pub fn release(self) -> Option<F> {
        self.map.map(|m| m.destroy().0.0)
    }

    /// Erases the whole range: everything stored is gone.
    pub fn format(&mut self) -> Result<(), Error> {
        self.commons = None;
        let range = self.map.as_ref().ok_or(Error::Internal)?.flash_range();
        let config = MapConfig::<AsAsync<F>>::try_new(range).map_err(|_| Error::BadRange)?;
        // Nothing can fail between taking the map out and putting the new one in.
        let (flash, _) = self.map.take().ok_or(Error::Internal)?.destroy();
        // A fresh cache: the old one describes what is about to be erased.
        let map = self.map.insert(MapStorage::new(flash, config, new_cache()));
        block_on(map.erase_all())?;
        self.journal_done = true;
        Ok(())
    }

    /// Calls `f` with the current value of `key`; `None` if absent.
    fn with_value<R>(&mut self, key: u32, f: impl FnOnce(&[u8]) -> R) -> Result<Option<R>, Error> {
        let Persist { map, buf, .. } = self;
        let map = map.as_mut().ok_or(Error::Internal)?;
        Ok(block_on(map.fetch_item::<&[u8]>(&mut buf.0, &key))?.map(f))
    }

    /// Stores `value` under `key`.
    fn put(&mut self, key: u32, value: &[u8]) -> Result<(), Error> {
        let Persist { map, buf, .. } = self;
        let map = map.as_mut().ok_or(Error::Internal)?;
        block_on(map.store_item(&mut buf.0, &key, &value))?;
        Ok(())
    }

    /// Stores `value` under `key` unless that is its current value already.
    fn put_if_changed(&mut self, key: u32, value: &[u8]) -> Result<(), Error> {
        if self.with_value(key, |old| old == value)? == Some(true) {
            return Ok(());
        }
        self.put(key, value)
    }

    /// Deletes every item of `key` (a no-op for an absent key).
    fn delete(&mut self, key: u32) -> Result<(), Error> {
        let Persist { map, buf, .. } = self;
        let map = map.as_mut().ok_or(Error::Internal)?;
        block_on(map.remove_item(&mut buf.0, &key))?;
        Ok(())
    }

    /// Calls `f(key, value)` for every stored item, oldest first. A key may come
    /// more than once: its last call carries its current value.
    fn for_each_item(&mut self, mut f: impl FnMut(u32, &[u8])) -> Result<(), Error> {
        let Persist { map, buf, .. } = self;
        let map = map.as_mut().ok_or(Error::Internal)?;
        block_on(async {
            let mut items = map.fetch_all_items(&mut buf.0).await?;
            while let Some((key, value)) = items.next::<&[u8]>(&mut buf.0).await? {
                f(key, value);
            }
            Ok::<(), sequential_storage::Error<F::Error>>(())
        })?;
        Ok(())
    }
}

/// An empty cache (for a store just opened or erased).
fn new_cache() -> StoreCache {
    Cache::new(ArrayPageStates::new(), ArrayPagePointers::new(), ArrayKeyPointers::new())
}

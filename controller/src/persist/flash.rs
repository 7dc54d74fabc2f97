//! Flash adapters: the blocking embedded-storage NOR-flash traits (what
//! embassy-stm32's blocking flash regions implement) seen through the async traits
//! `sequential-storage` is written against, and a marker for flash that may program
//! a word more than once.

use embedded_storage::nor_flash::{
    ErrorType, MultiwriteNorFlash as BlockingMultiwrite, NorFlash as BlockingNorFlash,
    ReadNorFlash as BlockingReadNorFlash,
};
use embedded_storage_async::nor_flash::{MultiwriteNorFlash, NorFlash, ReadNorFlash};

/// A blocking flash driven through the async traits: every future completes on its
/// first poll (the blocking call runs inside it), so `embassy_futures::block_on`
/// finishes each storage operation without an executor.
pub(crate) struct AsAsync<F>(pub(crate) F);

impl<F: ErrorType> ErrorType for AsAsync<F> {
    type Error = F::Error;
}

impl<F: BlockingReadNorFlash> ReadNorFlash for AsAsync<F> {
    const READ_SIZE: usize = F::READ_SIZE;

    async fn read(&mut self, offset: u32, bytes: &mut [u8]) -> Result<(), Self::Error> {
        self.0.read(offset, bytes)
    }

    fn capacity(&self) -> usize {
        self.0.capacity()
    }
}

impl<F: BlockingNorFlash> NorFlash for AsAsync<F> {
    const WRITE_SIZE: usize = F::WRITE_SIZE;
    const ERASE_SIZE: usize = F::ERASE_SIZE;

    async fn erase(&mut self, from: u32, to: u32) -> Result<(), Self::Error> {
        self.0.erase(from, to)
    }

    async fn write(&mut self, offset: u32, bytes: &[u8]) -> Result<(), Self::Error> {
        self.0.write(offset, bytes)
    }
}

impl<F: BlockingMultiwrite> MultiwriteNorFlash for AsAsync<F> {}

/// A flash that may program an already programmed word again, clearing more bits
/// (1 → 0) — what the store needs to mark deleted items.
///
/// The STM32F4 allows this (RM0090 §3.5.4: "Successive write operations are
/// possible without the need of an erase operation when changing bits from '1' to
/// '0'"), but embassy-stm32's flash regions do not declare it (not every STM32 can:
/// parts with ECC flash cannot). Wrap the F405's region in this to say so. Do not
/// wrap the flash of a part with ECC (STM32L4/G4/H7/U5…).
#[derive(Debug)]
pub struct Rewritable<F>(pub F);

impl<F: ErrorType> ErrorType for Rewritable<F> {
    type Error = F::Error;
}

impl<F: BlockingReadNorFlash> BlockingReadNorFlash for Rewritable<F> {
    const READ_SIZE: usize = F::READ_SIZE;

    fn read(&mut self, offset: u32, bytes: &mut [u8]) -> Result<(), Self::Error> {
        self.0.read(offset, bytes)
    }

    fn capacity(&self) -> usize {
        self.0.capacity()
    }
}

impl<F: BlockingNorFlash> BlockingNorFlash for Rewritable<F> {
    const WRITE_SIZE: usize = F::WRITE_SIZE;
    const ERASE_SIZE: usize = F::ERASE_SIZE;

    fn erase(&mut self, from: u32, to: u32) -> Result<(), Self::Error> {
        self.0.erase(from, to)
    }

    fn write(&mut self, offset: u32, bytes: &[u8]) -> Result<(), Self::Error> {
        self.0.write(offset, bytes)
    }
}

impl<F: BlockingNorFlash> BlockingMultiwrite for Rewritable<F> {}

//! The program store: program texts by O number, each saved atomically.
//!
//! A text is split into chunks of the store's chunk size, each an item keyed by
//! (O number, generation, index). The *header* item of the O number (length,
//! CRC-32 of the text, chunk size, generation) says which generation is the
//! program: writing it commits an update. The one-item *journal* names the update
//! in flight (O number, old and new generation and chunk counts) from before the
//! first chunk is written until the old generation is deleted, so the first
//! operation after a restart either finishes it (header committed: delete the old
//! chunks) or undoes it (delete the new chunks) — no orphaned chunks are left to
//! fill the flash.

use embedded_storage::nor_flash::{MultiwriteNorFlash, NorFlash};
use interp_core::program::{ProgramId, ProgramMemory};

use super::keys::{self, GENERATIONS, Kind};
use super::{Error, Persist};

/// Highest O number.
pub const MAX_PROGRAM_NUMBER: ProgramId = 9999;
/// Most chunks of one program (the chunk index is 8 bits of the key).
const MAX_CHUNKS: usize = 255;
/// Bytes of a stored header.
const HEADER_LEN: usize = 12;
/// Bytes of a stored journal intent.
const INTENT_LEN: usize = 10;

/// A stored program: its O number and text length.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ProgramInfo {
    /// O number.
    pub number: ProgramId,
    /// Text length in bytes.
    pub len: u32,
}

/// The committed version of a program.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Header {
    len: u32,
    crc: u32,
    chunk_len: u16,
    generation: u8,
}

impl Header {
    fn encode(&self) -> [u8; HEADER_LEN] {
        let mut out = [0; HEADER_LEN];
        out[0..4].copy_from_slice(&self.len.to_le_bytes());
        out[4..8].copy_from_slice(&self.crc.to_le_bytes());
        out[8..10].copy_from_slice(&self.chunk_len.to_le_bytes());
        out[10] = self.generation;
        out
    }

    fn decode(b: &[u8]) -> Option<Header> {
        let b: &[u8; HEADER_LEN] = b.try_into().ok()?;
        let [l0, l1, l2, l3, c0, c1, c2, c3, k0, k1, generation, _] = *b;
        let chunk_len = u16::from_le_bytes([k0, k1]);
        (chunk_len > 0).then_some(Header {
            len: u32::from_le_bytes([l0, l1, l2, l3]),
            crc: u32::from_le_bytes([c0, c1, c2, c3]),
            chunk_len,
            generation,
        })
    }

    /// Number of chunks.
    fn chunks(&self) -> u16 {
        self.len.div_ceil(u32::from(self.chunk_len)).min(MAX_CHUNKS as u32) as u16
    }
}

/// One generation's chunks: generation and count.
type Generation = (u8, u16);

/// The update in flight: a save (`new` is `Some`) or a delete.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Intent {
    o: u16,
    old: Option<Generation>,
    new: Option<Generation>,
}

impl Intent {
    fn encode(&self) -> [u8; INTENT_LEN] {
        let (og, oc) = self.old.unwrap_or((0, 0));
        let (ng, nc) = self.new.unwrap_or((0, 0));
        let flags = u8::from(self.old.is_some()) | u8::from(self.new.is_some()) << 1;
        let [o0, o1] = self.o.to_le_bytes();
        let [a0, a1] = oc.to_le_bytes();
        let [b0, b1] = nc.to_le_bytes();
        [o0, o1, flags, og, ng, 0, a0, a1, b0, b1]
    }

    /// The intent, or `None` for an idle (empty) or unreadable journal.
    fn decode(b: &[u8]) -> Option<Intent> {
        let b: &[u8; INTENT_LEN] = b.try_into().ok()?;
        let [o0, o1, flags, og, ng, _, a0, a1, b0, b1] = *b;
        Some(Intent {
            o: u16::from_le_bytes([o0, o1]),
            old: (flags & 1 != 0).then_some((og, u16::from_le_bytes([a0, a1]))),
            new: (flags & 2 != 0).then_some((ng, u16::from_le_bytes([b0, b1]))),
        })
    }
}

/// CRC-32 (IEEE 802.3, reflected) of `data`.
fn crc32(data: &[u8]) -> u32 {
    let mut crc = !0u32;
    for byte in data {
        crc ^= u32::from(*byte);
        for _ in 0..8 {
            crc = if crc & 1 != 0 { (crc >> 1) ^ 0xEDB8_8320 } else { crc >> 1 };
        }
    }
    !crc
}

/// The O number as a key part; `BadNumber` outside 1–9999.
fn program_number(o: ProgramId) -> Result<u16, Error> {
    if (1..=MAX_PROGRAM_NUMBER).contains(&o) {
        u16::try_from(o).map_err(|_| Error::BadNumber)
    } else {
        Err(Error::BadNumber)
    }
}

impl<F: NorFlash + MultiwriteNorFlash> Persist<F> {
    /// Stores program `o` (1–9999) with `text`, replacing any stored one, unless
    /// the stored text is the same already. Atomic: after a power cut the program
    /// reads back as the old text or the new. `TooBig` beyond 255 chunks
    /// (255 KB on 128 KB sectors), `Full` when the flash has no room for the old
    /// and new text at once (the old one stays).
    pub fn save_program(&mut self, o: ProgramId, text: &[u8]) -> Result<(), Error> {
        let o = program_number(o)?;
        self.ready()?;
        let chunk_len = self.chunk;
        let count = text.len().div_ceil(chunk_len);
        let (Ok(len), true) = (u32::try_from(text.len()), count <= MAX_CHUNKS) else {
            return Err(Error::TooBig);
        };
        let old = self.header(o)?;
        let crc = crc32(text);
        if let Some(h) = old
            && h.len == len
            && h.crc == crc
            && self.text_equals(o, &h, text)?
        {
            return Ok(());
        }
        let generation = old.map_or(0, |h| (h.generation + 1) % GENERATIONS);
        let header = Header { len, crc, chunk_len: chunk_len as u16, generation };
        let intent = Intent { o, old: old.map(|h| (h.generation, h.chunks())), new: Some((generation, count as u16)) };
        self.put(keys::JOURNAL, &intent.encode())?;
        self.journal_done = false;
        let written = self.write_generation(o, &header, text);
        // Commit or not, settle the journal now (on failure: drop the new chunks).
        let settled = self.recover();
        written.and(settled)
    }

    /// Writes the chunks of `text` as generation `header.generation`, then the
    /// header (the commit).
    fn write_generation(&mut self, o: u16, header: &Header, text: &[u8]) -> Result<(), Error> {
        for (i, piece) in (0u8..).zip(text.chunks(usize::from(header.chunk_len))) {
            self.put(keys::program_chunk(o, header.generation, i), piece)?;
        }
        self.put(keys::program_header(o), &header.encode())
    }

    /// Deletes program `o`; whether it was stored. Atomic like a save.
    pub fn delete_program(&mut self, o: ProgramId) -> Result<bool, Error> {
        let o = program_number(o)?;
        self.ready()?;
        let Some(h) = self.header(o)? else { return Ok(false) };
        let intent = Intent { o, old: Some((h.generation, h.chunks())), new: None };
        self.put(keys::JOURNAL, &intent.encode())?;
        self.journal_done = false;
        let deleted = self.delete(keys::program_header(o));
        let settled = self.recover();
        deleted.and(settled).map(|()| true)
    }

    /// Copies the text of program `o` into `buf`; its length. `NoProgram` if it is
    /// not stored, `BufferTooSmall` if `buf` is shorter, `Damaged` if the chunks
    /// do not match the header.
    pub fn load_program(&mut self, o: ProgramId, buf: &mut [u8]) -> Result<usize, Error> {
        let o = program_number(o)?;
        self.ready()?;
        let h = self.header(o)?.ok_or(Error::NoProgram { program: o })?;
        let len = h.len as usize;
        let out = buf.get_mut(..len).ok_or(Error::BufferTooSmall { needed: len })?;
        for (i, piece) in (0u8..).zip(out.chunks_mut(usize::from(h.chunk_len))) {
            let copied = self.with_value(keys::program_chunk(o, h.generation, i), |v| {
                let fits = v.len() == piece.len();
                if fits {
                    piece.copy_from_slice(v);
                }
                fits
            })?;
            if copied != Some(true) {
                return Err(Error::Damaged { program: o });
            }
        }
        if crc32(out) != h.crc {
            return Err(Error::Damaged { program: o });
        }
        Ok(len)
    }

    /// The stored programs, ascending by O number. One pass over the flash.
    pub fn programs<const N: usize>(&mut self) -> Result<heapless::Vec<ProgramInfo, N>, Error> {
        self.ready()?;
        let mut list = heapless::Vec::<ProgramInfo, N>::new();
        let mut overflow = false;
        self.for_each_item(|key, value| {
            if keys::kind(key) != Some(Kind::ProgramHeader) {
                return;
            }
            let (number, Some(h)) = (ProgramId::from(keys::number(key)), Header::decode(value)) else { return };
            let info = ProgramInfo { number, len: h.len };
            match list.binary_search_by_key(&number, |p| p.number) {
                Ok(i) => {
                    if let Some(slot) = list.get_mut(i) {
                        *slot = info;
                    }
                }
                Err(i) => overflow |= list.insert(i, info).is_err(),
            }
        })?;
        if overflow { Err(Error::TooManyPrograms) } else { Ok(list) }
    }

    /// Loads every stored program into `memory` (each text through `scratch`,
    /// which must hold the longest); how many. `TooManyPrograms` if they do not
    /// fit (text, programs or sequence numbers).
    pub fn load_all_programs<const T: usize, const P: usize, const S: usize>(
        &mut self,
        memory: &mut ProgramMemory<T, P, S>,
        scratch: &mut [u8],
    ) -> Result<usize, Error> {
        let list = self.programs::<P>()?;
        for p in &list {
            let len = self.load_program(p.number, scratch)?;
            let text = scratch.get(..len).ok_or(Error::Internal)?;
            memory.load(text, Some(p.number)).map_err(|_| Error::TooManyPrograms)?;
        }
        Ok(list.len())
    }

    /// The committed header of program `o`.
    fn header(&mut self, o: u16) -> Result<Option<Header>, Error> {
        Ok(self.with_value(keys::program_header(o), Header::decode)?.flatten())
    }

    /// Whether the stored text of `o` (header `h`) is `text`.
    fn text_equals(&mut self, o: u16, h: &Header, text: &[u8]) -> Result<bool, Error> {
        for (i, piece) in (0u8..).zip(text.chunks(usize::from(h.chunk_len))) {
            if self.with_value(keys::program_chunk(o, h.generation, i), |v| v == piece)? != Some(true) {
                return Ok(false);
            }
        }
        Ok(true)
    }

    /// Finishes or undoes a program update a power cut (or an error) interrupted,
    /// once after opening. Every public operation calls this first.
    pub(crate) fn ready(&mut self) -> Result<(), Error> {
        if self.journal_done { Ok(()) } else { self.recover() }
    }

    /// Settles the journal: if its update was committed, deletes the old
    /// generation's chunks, else the new one's; then marks the journal idle.
    fn recover(&mut self) -> Result<(), Error> {
        let Some(intent) = self.with_value(keys::JOURNAL, Intent::decode)?.flatten() else {
            self.journal_done = true;
            return Ok(());
        };
        let current = self.header(intent.o)?.map(|h| h.generation);
        let committed = match intent.new {
            Some((generation, _)) => current == Some(generation),
            None => current.is_none(),
        };
        if let Some((generation, count)) = if committed { intent.old } else { intent.new } {
            for i in 0..count.min(MAX_CHUNKS as u16) as u8 {
                self.delete(keys::program_chunk(intent.o, generation, i))?;
            }
        }
        self.put(keys::JOURNAL, &[])?;
        self.journal_done = true;
        Ok(())
    }
}

//! Map keys: one `u32` per stored record, its kind in the top four bits.
//!
//! | kind | key                                        | value                          |
//! |------|--------------------------------------------|--------------------------------|
//! | 1    | parameter number n (low 16 bits)           | `i64` LE (8 bytes)             |
//! | 2    | common variable n, 401–600                 | `f64` bits LE, NaN = null      |
//! | 3    | work offset 0–5 (G54–G59), 6 = external    | 4 × `i64` LE (32 bytes)        |
//! | 4    | tool offset row n, 1–32                    | 5 × `i64` + tip `u8` (41 bytes)|
//! | 5    | program header, O number                   | [`super::programs`] header     |
//! | 6    | program chunk: O (14 bits), generation (6), chunk index (8) | text bytes    |
//! | 7    | the program journal (one key)              | empty = idle, or an intent     |
//! | 8    | G54.1 work offset P, 1–48 (a mill's)       | 3 × `i32` LE X, Y, Z (12 bytes)|

/// The kind of a key.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    Param,
    Common,
    WorkOffset,
    ToolOffset,
    ProgramHeader,
    ProgramChunk,
    Journal,
    ExtraOffset,
}

const KIND_SHIFT: u32 = 28;

const fn tagged(kind: u32, low: u32) -> u32 {
    (kind << KIND_SHIFT) | low
}

/// The kind of `key`, `None` for a key this layout does not use.
pub(crate) const fn kind(key: u32) -> Option<Kind> {
    Some(match key >> KIND_SHIFT {
        1 => Kind::Param,
        2 => Kind::Common,
        3 => Kind::WorkOffset,
        4 => Kind::ToolOffset,
        5 => Kind::ProgramHeader,
        6 => Kind::ProgramChunk,
        7 => Kind::Journal,
        8 => Kind::ExtraOffset,
        _ => return None,
    })
}

/// The low 16 bits: the number of a parameter, variable, offset or program.
pub(crate) const fn number(key: u32) -> u16 {
    (key & 0xFFFF) as u16
}

pub(crate) const fn param(n: u16) -> u32 {
    tagged(1, n as u32)
}

pub(crate) const fn common(n: u16) -> u32 {
    tagged(2, n as u32)
}

/// Work offset `index` 0–5 (G54–G59) or 6 (the external offset).
pub(crate) const fn work_offset(index: u16) -> u32 {
    tagged(3, index as u32)
}

pub(crate) const fn tool_offset(n: u16) -> u32 {
    tagged(4, n as u32)
}

pub(crate) const fn program_header(o: u16) -> u32 {
    tagged(5, o as u32)
}

/// Generations wrap at this count (6 bits of the chunk key).
pub(crate) const GENERATIONS: u8 = 64;

/// Chunk `index` of generation `generation` of program `o` (O < 16384).
pub(crate) const fn program_chunk(o: u16, generation: u8, index: u8) -> u32 {
    tagged(6, ((o as u32 & 0x3FFF) << 14) | ((generation as u32 % GENERATIONS as u32) << 8) | index as u32)
}

/// G54.1 P`p` (1–48), a machining centre's additional work offset.
pub(crate) const fn extra_offset(p: u8) -> u32 {
    tagged(8, p as u32)
}

pub(crate) const JOURNAL: u32 = tagged(7, 0);

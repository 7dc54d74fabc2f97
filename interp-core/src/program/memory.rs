//! Program memory: programs by O number with an index of their sequence numbers,
//! in fixed capacity (text bytes, programs, indexed sequence numbers as const
//! parameters). The firmware keeps one in RAM filled from flash; the host fills one
//! from files.

use core::fmt;

use super::lines::{self, NamedProgram};
use super::{Cursor, ProgramId, ProgramStore, leading_sequence, next_block, starts_program};

/// The first id a named (SINUMERIK) program gets: named programs are numbered
/// from here in the order they are loaded, above every O number.
pub const NAMED_BASE: ProgramId = 100_000;

/// One stored program.
#[derive(Clone, Copy, Debug)]
struct Stored {
    /// O number.
    number: ProgramId,
    /// Offset of the text it was loaded with (its file) in the store's text.
    file: u32,
    /// Offset of the program's first block, relative to `file`.
    start: u32,
    /// Offset of the end of the program, relative to `file`.
    end: u32,
    /// Line of the first block.
    line: u32,
    /// Its entries in the sequence index.
    seq_first: u32,
    /// How many.
    seq_count: u32,
}

/// One sequence number of a program: the block's offset (relative to the file) and
/// line. A program's entries are sorted by number, then offset.
#[derive(Clone, Copy, Debug)]
struct SeqEntry {
    n: u32,
    offset: u32,
    line: u32,
}

/// Why text could not be loaded. Nothing of it was stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LoadError {
    /// The text does not fit into the remaining text capacity.
    TextFull,
    /// More programs than the store holds.
    TooManyPrograms,
    /// More sequence numbers than the index holds.
    TooManySequences,
    /// A program with this O number is already stored (or twice in the text).
    Duplicate {
        /// The O number.
        program: ProgramId,
    },
    /// Blocks before the first O number, and no number was given for them.
    NoProgramNumber {
        /// Line of the first such block.
        line: u32,
    },
    /// An O block whose number is not 1–9999.
    BadProgramNumber {
        /// Its line.
        line: u32,
    },
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LoadError::TextFull => write!(f, "program memory is full"),
            LoadError::TooManyPrograms => write!(f, "too many programs for program memory"),
            LoadError::TooManySequences => write!(f, "too many sequence numbers for the index"),
            LoadError::Duplicate { program } => write!(f, "program O{program:04} is already in memory"),
            LoadError::NoProgramNumber { line } => write!(f, "line {line}: blocks before the first O number"),
            LoadError::BadProgramNumber { line } => write!(f, "line {line}: program number must be O1-O9999"),
        }
    }
}

/// The index of the programs in a text space: where each program begins and ends,
/// and its sequence numbers sorted for binary search. Up to `PROGRAMS` programs and
/// `SEQUENCES` sequence numbers; `28·PROGRAMS + 12·SEQUENCES` bytes.
///
/// The text itself lives elsewhere — in a [`ProgramMemory`] (RAM), or in a slice
/// of memory-mapped flash or a host buffer ([`ProgramArea`]).
#[derive(Clone, Debug)]
pub struct ProgramIndex<const PROGRAMS: usize, const SEQUENCES: usize> {
    /// Sorted by O number.
    programs: heapless::Vec<Stored, PROGRAMS>,
    sequences: heapless::Vec<SeqEntry, SEQUENCES>,
}

impl<const P: usize, const S: usize> Default for ProgramIndex<P, S> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const P: usize, const S: usize> ProgramIndex<P, S> {
    /// An empty index.
    pub const fn new() -> Self {
        ProgramIndex { programs: heapless::Vec::new(), sequences: heapless::Vec::new() }
    }

    /// Indexes the file `space[file..end]`: one or more programs, each starting at
    /// its `O` block and ending before the next `O` block or the closing `%` (after
    /// which nothing is read). Blocks before the first `O` (other than blanks,
    /// comments and a leading `%`) form program `unnamed` — a main program file
    /// without an O number; an empty file is an empty program `unnamed` — or are an
    /// error if `unnamed` is `None`. Line numbers count from the start of the file.
    ///
    /// Returns the number of the file's first program. All or nothing: on an error
    /// the index is as before.
    pub fn add_file(
        &mut self,
        space: &[u8],
        file: usize,
        end: usize,
        unnamed: Option<ProgramId>,
    ) -> Result<ProgramId, LoadError> {
        let (p, s) = (self.programs.len(), self.sequences.len());
        let text = space.get(file..end).ok_or(LoadError::TextFull)?;
        if u32::try_from(end).is_err() {
            return Err(LoadError::TextFull);
        }
        let r = self.add_programs(text, file, unnamed);
        if r.is_err() {
            self.programs.truncate(p);
            self.sequences.truncate(s);
        }
        r
    }

    fn add_programs(&mut self, text: &[u8], file: usize, unnamed: Option<ProgramId>) -> Result<ProgramId, LoadError> {
        let mut first = None;
        let mut cur = Cursor::start(0);
        // The program being collected: number and start cursor.
        let mut open: Option<(ProgramId, Cursor)> = None;
        loop {
            let at = cur;
            let Some(block) = next_block(text, &mut cur) else { break };
            let starts = starts_program(block.text);
            if (starts || block.percent)
                && let Some((n, c)) = open.take()
            {
                self.add(n, file, c, at.offset, text)?;
            }
            if block.percent && first.is_some() {
                // The closing record mark: what follows is not read (end of tape).
                break;
            }
            if starts {
                let n = program_number(block.text).ok_or(LoadError::BadProgramNumber { line: block.line })?;
                open = Some((n, at));
                first.get_or_insert(n);
            } else if open.is_none() && !block.percent && !is_blank(block.text) {
                let n = unnamed.ok_or(LoadError::NoProgramNumber { line: block.line })?;
                open = Some((n, Cursor::start(n)));
                first = Some(n);
            }
        }
        if let Some((n, c)) = open {
            self.add(n, file, c, text.len(), text)?;
        }
        match (first, unnamed) {
            (Some(n), _) => Ok(n),
            // A main program file with nothing in it is an empty program.
            (None, Some(n)) => self.add(n, file, Cursor::start(n), text.len(), text).map(|()| n),
            (None, None) => Err(LoadError::NoProgramNumber { line: 1 }),
        }
    }

    /// Indexes the SINUMERIK file `space[file..end]`: one or more programs named
    /// by `%_N_NAME_MPF`/`_SPF` headers or PROC statements
    /// ([`lines::split_programs`]). The first program gets the id `unnamed` if
    /// given (a main program file), the others — and all of a library file's —
    /// ids from [`NAMED_BASE`] on. Sequence numbers are the `N` numbers lines
    /// start with (a `;` comment is no block end here). Returns the first
    /// program's id. All or nothing.
    pub fn add_named_file(
        &mut self,
        space: &[u8],
        file: usize,
        end: usize,
        unnamed: Option<ProgramId>,
    ) -> Result<ProgramId, LoadError> {
        let (p, s) = (self.programs.len(), self.sequences.len());
        let text = space.get(file..end).ok_or(LoadError::TextFull)?;
        if u32::try_from(end).is_err() {
            return Err(LoadError::TextFull);
        }
        let mut next =
            self.programs.iter().map(|q| q.number + 1).filter(|&n| n > NAMED_BASE).max().unwrap_or(NAMED_BASE);
        let mut first = None;
        let r = lines::split_programs(text, |prog: NamedProgram<'_>| {
            let id = match (first, unnamed) {
                (None, Some(id)) => id,
                _ => {
                    next += 1;
                    next - 1
                }
            };
            first.get_or_insert(id);
            let start = Cursor { program: id, ..prog.start };
            self.add_lines(id, file, start, prog.end, text)
        });
        if r.is_err() {
            self.programs.truncate(p);
            self.sequences.truncate(s);
        }
        r.map(|()| first.unwrap_or(0))
    }

    /// The first program whose name (from its `%_N_…` header or PROC line) is
    /// `name`, ignoring case.
    pub fn find_named(&self, space: &[u8], name: &[u8]) -> Option<ProgramId> {
        self.programs
            .iter()
            .find(|p| {
                space.get(p.file as usize..(p.file + p.end) as usize).is_some_and(|t| {
                    let mut cur = Cursor { program: p.number, offset: p.start as usize, line: p.line };
                    // The name is on the header or the PROC line, before any statement.
                    while let Some(l) = lines::next_line(t, &mut cur) {
                        if let Some(n) = lines::header_name(l.text).or_else(|| lines::proc_name(l.text)) {
                            if n.eq_ignore_ascii_case(name) {
                                return true;
                            }
                            if lines::proc_name(l.text).is_some() {
                                return false;
                            }
                        } else if lines::has_statement(l.text) {
                            return false;
                        }
                    }
                    false
                })
            })
            .map(|p| p.number)
    }

    /// [`ProgramIndex::add`] for a SINUMERIK program: sequence numbers by line.
    fn add_lines(
        &mut self,
        n: ProgramId,
        file: usize,
        start: Cursor,
        end: usize,
        text: &[u8],
    ) -> Result<(), LoadError> {
        self.add_with(n, file, start, end, text, true)
    }

    /// Registers program `n` spanning `start..end` of `text` (the file at `file`)
    /// and indexes its sequence numbers.
    fn add(&mut self, n: ProgramId, file: usize, start: Cursor, end: usize, text: &[u8]) -> Result<(), LoadError> {
        self.add_with(n, file, start, end, text, false)
    }

    /// [`ProgramIndex::add`] with the language's way of cutting blocks and reading
    /// their sequence numbers (`siemens`: by line).
    fn add_with(
        &mut self,
        n: ProgramId,
        file: usize,
        start: Cursor,
        end: usize,
        text: &[u8],
        siemens: bool,
    ) -> Result<(), LoadError> {
        type Cut = for<'t> fn(&'t [u8], &mut Cursor) -> Option<super::RawBlock<'t>>;
        type SeqOf = fn(&[u8]) -> Option<u32>;
        let (cut, seq_of): (Cut, SeqOf) =
            if siemens { (lines::next_line, lines::line_number) } else { (next_block, leading_sequence) };
        let slot = match self.programs.binary_search_by_key(&n, |p| p.number) {
            Ok(_) => return Err(LoadError::Duplicate { program: n }),
            Err(i) => i,
        };
        let seq_first = self.sequences.len();
        let body = &text[..end];
        let mut cur = start;
        loop {
            let at = cur;
            let Some(block) = cut(body, &mut cur) else { break };
            if let Some(s) = seq_of(block.text) {
                let e = SeqEntry { n: s, offset: at.offset as u32, line: at.line };
                self.sequences.push(e).map_err(|_| LoadError::TooManySequences)?;
            }
        }
        if let Some(entries) = self.sequences.get_mut(seq_first..) {
            crate::sort::heap_sort_by(entries, |a, b| (a.n, a.offset) < (b.n, b.offset));
        }
        let stored = Stored {
            number: n,
            file: file as u32,
            start: start.offset as u32,
            end: end as u32,
            line: start.line,
            seq_first: seq_first as u32,
            seq_count: (self.sequences.len() - seq_first) as u32,
        };
        self.programs.insert(slot, stored).map_err(|_| LoadError::TooManyPrograms)
    }

    /// Forgets every program.
    pub fn clear(&mut self) {
        self.programs.clear();
        self.sequences.clear();
    }

    /// Forgets program `id`: its file offset and whether another program shares
    /// the file; `None` if it is not indexed.
    fn remove(&mut self, id: ProgramId) -> Option<(u32, bool)> {
        let i = self.programs.binary_search_by_key(&id, |p| p.number).ok()?;
        let p = self.programs.remove(i);
        let (first, count) = (p.seq_first as usize, p.seq_count as usize);
        let len = self.sequences.len();
        if let Some(tail) = self.sequences.get_mut(first..) {
            tail.rotate_left(count.min(tail.len()));
        }
        self.sequences.truncate(len.saturating_sub(count));
        for q in self.programs.iter_mut().filter(|q| q.seq_first > p.seq_first) {
            q.seq_first -= p.seq_count;
        }
        Some((p.file, self.programs.iter().any(|q| q.file == p.file)))
    }

    /// The O numbers indexed, ascending.
    pub fn numbers(&self) -> impl Iterator<Item = ProgramId> + '_ {
        self.programs.iter().map(|p| p.number)
    }

    fn program(&self, id: ProgramId) -> Option<&Stored> {
        let i = self.programs.binary_search_by_key(&id, |p| p.number).ok()?;
        self.programs.get(i)
    }

    /// The text of program `id` in `space`: from the start of its file to the end
    /// of the program (cursors index into it).
    pub fn text<'a>(&self, space: &'a [u8], id: ProgramId) -> Option<&'a [u8]> {
        let p = self.program(id)?;
        space.get(p.file as usize..(p.file + p.end) as usize)
    }

    /// Where program `id` begins.
    pub fn start(&self, id: ProgramId) -> Option<Cursor> {
        let p = self.program(id)?;
        Some(Cursor { program: id, offset: p.start as usize, line: p.line })
    }

    /// [`ProgramStore::find_sequence`] by binary search: O(log n).
    pub fn find_sequence(&self, n: u32, from: Cursor) -> Option<Cursor> {
        let p = self.program(from.program)?;
        let all = self.sequences.get(p.seq_first as usize..(p.seq_first + p.seq_count) as usize)?;
        let lo = all.partition_point(|e| e.n < n);
        let hi = all.partition_point(|e| e.n <= n);
        let same = all.get(lo..hi)?;
        let e = same.iter().find(|e| e.offset as usize >= from.offset).or(same.first())?;
        Some(Cursor { program: from.program, offset: e.offset as usize, line: e.line })
    }
}

/// Programs in RAM: `TEXT` bytes of program text, up to `PROGRAMS` programs and
/// `SEQUENCES` indexed sequence numbers. Size: `TEXT + 28·PROGRAMS + 12·SEQUENCES`
/// bytes plus three lengths.
#[derive(Clone, Debug)]
pub struct ProgramMemory<const TEXT: usize, const PROGRAMS: usize, const SEQUENCES: usize> {
    text: heapless::Vec<u8, TEXT>,
    index: ProgramIndex<PROGRAMS, SEQUENCES>,
}

impl<const T: usize, const P: usize, const S: usize> Default for ProgramMemory<T, P, S> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const T: usize, const P: usize, const S: usize> ProgramMemory<T, P, S> {
    /// Empty program memory.
    pub const fn new() -> Self {
        ProgramMemory { text: heapless::Vec::new(), index: ProgramIndex::new() }
    }

    /// Copies in a text (a file) holding one or more programs and indexes them, as
    /// [`ProgramIndex::add_file`] describes. All or nothing.
    pub fn load(&mut self, text: &[u8], unnamed: Option<ProgramId>) -> Result<ProgramId, LoadError> {
        let file = self.text.len();
        self.text.extend_from_slice(text).map_err(|_| LoadError::TextFull)?;
        let r = self.index.add_file(&self.text, file, self.text.len(), unnamed);
        if r.is_err() {
            self.text.truncate(file);
        }
        r
    }

    /// Copies in a SINUMERIK text (a file) holding one or more named programs and
    /// indexes them ([`ProgramIndex::add_named_file`]). All or nothing.
    pub fn load_named(&mut self, text: &[u8], unnamed: Option<ProgramId>) -> Result<ProgramId, LoadError> {
        let file = self.text.len();
        self.text.extend_from_slice(text).map_err(|_| LoadError::TextFull)?;
        let r = self.index.add_named_file(&self.text, file, self.text.len(), unnamed);
        if r.is_err() {
            self.text.truncate(file);
        }
        r
    }

    /// Removes every program.
    pub fn clear(&mut self) {
        self.text.clear();
        self.index.clear();
    }

    /// Removes program `id` (the board's `$PD`, or before storing a new version);
    /// its text is freed unless another program was loaded with it in one file.
    /// False if there is no such program.
    pub fn remove(&mut self, id: ProgramId) -> bool {
        let Some((file, shared)) = self.index.remove(id) else { return false };
        if !shared {
            let later = self.index.programs.iter().map(|q| q.file).filter(|&f| f > file).min();
            let end = later.unwrap_or(self.text.len() as u32);
            let n = end.saturating_sub(file);
            let len = self.text.len();
            if let Some(tail) = self.text.get_mut(file as usize..) {
                tail.rotate_left((n as usize).min(tail.len()));
            }
            self.text.truncate(len.saturating_sub(n as usize));
            for q in self.index.programs.iter_mut().filter(|q| q.file > file) {
                q.file -= n;
            }
        }
        true
    }

    /// The O numbers stored, ascending.
    pub fn numbers(&self) -> impl Iterator<Item = ProgramId> + '_ {
        self.index.numbers()
    }

    /// Bytes of text stored.
    pub fn text_used(&self) -> usize {
        self.text.len()
    }
}

impl<const T: usize, const P: usize, const S: usize> ProgramStore for ProgramMemory<T, P, S> {
    fn text(&self, id: ProgramId) -> Option<&[u8]> {
        self.index.text(&self.text, id)
    }

    fn find_named(&self, name: &[u8]) -> Option<Cursor> {
        self.index.find_named(&self.text, name).and_then(|id| self.index.start(id))
    }

    fn start(&self, id: ProgramId) -> Option<Cursor> {
        self.index.start(id)
    }

    fn find_sequence(&self, n: u32, from: Cursor) -> Option<Cursor> {
        self.index.find_sequence(n, from)
    }
}

/// Programs in text that stays where it is — memory-mapped flash on the board, a
/// buffer of files on the host — with an index in `28·PROGRAMS + 12·SEQUENCES`
/// bytes: nothing is copied.
#[derive(Clone, Debug)]
pub struct ProgramArea<'a, const PROGRAMS: usize, const SEQUENCES: usize> {
    space: &'a [u8],
    index: ProgramIndex<PROGRAMS, SEQUENCES>,
}

impl<'a, const P: usize, const S: usize> ProgramArea<'a, P, S> {
    /// An area over `space` with nothing indexed yet.
    pub const fn new(space: &'a [u8]) -> Self {
        ProgramArea { space, index: ProgramIndex::new() }
    }

    /// Indexes the file at `space[file..end]` ([`ProgramIndex::add_file`]).
    pub fn add_file(&mut self, file: usize, end: usize, unnamed: Option<ProgramId>) -> Result<ProgramId, LoadError> {
        self.index.add_file(self.space, file, end, unnamed)
    }

    /// Indexes the SINUMERIK file at `space[file..end]` ([`ProgramIndex::add_named_file`]).
    pub fn add_named_file(
        &mut self,
        file: usize,
        end: usize,
        unnamed: Option<ProgramId>,
    ) -> Result<ProgramId, LoadError> {
        self.index.add_named_file(self.space, file, end, unnamed)
    }

    /// The O numbers indexed, ascending.
    pub fn numbers(&self) -> impl Iterator<Item = ProgramId> + '_ {
        self.index.numbers()
    }
}

impl<const P: usize, const S: usize> ProgramStore for ProgramArea<'_, P, S> {
    fn text(&self, id: ProgramId) -> Option<&[u8]> {
        self.index.text(self.space, id)
    }

    fn find_named(&self, name: &[u8]) -> Option<Cursor> {
        self.index.find_named(self.space, name).and_then(|id| self.index.start(id))
    }

    fn start(&self, id: ProgramId) -> Option<Cursor> {
        self.index.start(id)
    }

    fn find_sequence(&self, n: u32, from: Cursor) -> Option<Cursor> {
        self.index.find_sequence(n, from)
    }
}

/// The number of an `O` block: 1–9999.
fn program_number(text: &[u8]) -> Option<ProgramId> {
    let i = text.iter().position(|c| matches!(c, b'O' | b'o'))? + 1;
    let digits = text[i..].iter().skip_while(|c| **c == b' ').take_while(|c| c.is_ascii_digit());
    let mut n: u32 = 0;
    for d in digits {
        n = n.saturating_mul(10).saturating_add(u32::from(d - b'0'));
    }
    (1..=9999).contains(&n).then_some(n)
}

/// Whether a block holds nothing but blanks and comments.
fn is_blank(text: &[u8]) -> bool {
    let mut in_comment = false;
    text.iter().all(|&c| match c {
        b'(' => {
            in_comment = true;
            true
        }
        b')' => {
            in_comment = false;
            true
        }
        b' ' | b'\t' | b'\r' => true,
        _ => in_comment,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    type Small = ProgramMemory<1024, 8, 32>;

    const FILE: &[u8] = b"%\nO0001 (main)\nN10 G00 X10\nN20 M98 P12\nN10 X20\nM30\nO0012\nN5 G01 X1 F1\nN7 M99\n%\n";

    #[test]
    fn a_file_with_two_programs_keeps_the_files_lines() {
        let mut m = Small::new();
        assert_eq!(m.load(FILE, None), Ok(1));
        assert_eq!(m.numbers().collect::<heapless::Vec<_, 4>>().as_slice(), &[1, 12]);
        let s1 = m.start(1).unwrap();
        assert_eq!((s1.offset, s1.line), (2, 2));
        let s12 = m.start(12).unwrap();
        assert_eq!(s12.line, 7);
        let t12 = m.text(12).unwrap();
        assert_eq!(&t12[s12.offset..], b"O0012\nN5 G01 X1 F1\nN7 M99\n");
        assert!(m.text(1).unwrap().ends_with(b"M30\n"), "program 1 ends before O0012");
        assert_eq!(m.text(3), None);
    }

    #[test]
    fn sequence_lookup_forward_then_from_the_start_and_first_of_duplicates() {
        let mut m = Small::new();
        m.load(FILE, None).unwrap();
        let start = m.start(1).unwrap();
        let first10 = m.find_sequence(10, start).unwrap();
        assert_eq!(first10.line, 3);
        let after20 = m.find_sequence(20, start).unwrap();
        assert_eq!(after20.line, 4);
        // From after N20, the next N10 is the second one; from after that, back to the first.
        let past = Cursor { line: 5, offset: after20.offset + 12, program: 1 };
        assert_eq!(m.find_sequence(10, past).unwrap().line, 5);
        let end = Cursor { line: 6, offset: past.offset + 8, program: 1 };
        assert_eq!(m.find_sequence(10, end).unwrap().line, 3);
        assert_eq!(m.find_sequence(5, start), None, "N5 belongs to O0012");
        assert_eq!(m.find_sequence(5, m.start(12).unwrap()).unwrap().line, 8);
        // The scanning default of the trait agrees.
        let single = crate::program::SingleProgram(b"N10 X1\nN20 X2\nN10 X3\n");
        let s = single.start(0).unwrap();
        assert_eq!(single.find_sequence(10, s).unwrap().line, 1);
        let after = Cursor { program: 0, offset: 7, line: 2 };
        assert_eq!(single.find_sequence(10, after).unwrap().line, 3);
        let last = Cursor { program: 0, offset: 21, line: 4 };
        assert_eq!(single.find_sequence(10, last).unwrap().line, 1);
    }

    #[test]
    fn unnamed_main_program_and_load_errors_change_nothing() {
        let mut m = Small::new();
        assert_eq!(m.load(b"G00 X1\nN3 M30\nO0012\nM99\n", Some(0)), Ok(0));
        assert_eq!(m.start(0).unwrap().line, 1);
        assert!(m.text(0).unwrap().ends_with(b"M30\n"));
        let used = m.text_used();
        assert_eq!(m.load(b"O0012\nM99\n", None), Err(LoadError::Duplicate { program: 12 }));
        assert_eq!(m.load(b"G00 X1\n", None), Err(LoadError::NoProgramNumber { line: 1 }));
        assert_eq!(m.load(b"(only a comment)\n", None), Err(LoadError::NoProgramNumber { line: 1 }));
        assert_eq!(m.load(b"O0000\n", None), Err(LoadError::BadProgramNumber { line: 1 }));
        assert_eq!(m.load(b"O7\nM99\nO7\nM99\n", None), Err(LoadError::Duplicate { program: 7 }));
        assert_eq!(m.text_used(), used);
        assert_eq!(m.numbers().count(), 2);
        let mut tiny = ProgramMemory::<16, 1, 1>::new();
        assert_eq!(tiny.load(b"O1\nN1\nN2\n", None), Err(LoadError::TooManySequences));
        assert_eq!(tiny.load(b"O1\nO2\n", None), Err(LoadError::TooManyPrograms));
        assert_eq!(tiny.load(b"O1\nG00 X100 Z200\n", None), Err(LoadError::TextFull));
        assert_eq!(tiny.text_used(), 0);
    }

    #[test]
    fn the_closing_percent_ends_the_file_and_an_empty_main_is_a_program() {
        let mut m = Small::new();
        assert_eq!(m.load(b"%\nO0005\nM30\n%\nanything (not read)\nO0006\n", None), Ok(5));
        assert_eq!(m.numbers().collect::<heapless::Vec<_, 4>>().as_slice(), &[5]);
        assert_eq!(m.load(b"%\n(nothing)\n%\n", Some(0)), Ok(0));
        assert_eq!(m.start(0), Some(Cursor::start(0)));
    }

    #[test]
    fn named_programs_are_found_by_name_and_keep_their_lines() {
        let mut m = Small::new();
        let main = b"; CYCLE95 example 1\nN10 G0 X81\nN50 M30\nPROC KONTUR_1\nN100 G1 Z120 X37\nN220 M17\n";
        assert_eq!(m.load_named(main, Some(0)), Ok(0));
        let lib = b"%_N_ZYKL1_SPF\n; $PATH=/_N_CUS_DIR\n; VERSION: 01.02.03\nPROC ZYKL1 (REAL PAR1)\nN1 M17\n";
        assert_eq!(m.load_named(lib, None), Ok(NAMED_BASE + 1));
        assert_eq!(m.numbers().collect::<heapless::Vec<_, 4>>().as_slice(), &[0, NAMED_BASE, NAMED_BASE + 1]);
        let k = m.find_named(b"kontur_1").unwrap();
        assert_eq!((k.program, k.line), (NAMED_BASE, 4));
        assert_eq!(m.find_named(b"ZYKL1").map(|c| (c.program, c.line)), Some((NAMED_BASE + 1, 1)));
        assert_eq!(m.find_named(b"ZYKL"), None);
        assert_eq!(m.find_named(b"PAR1"), None);
        // Sequence numbers by line: a `;` comment is no block end.
        assert_eq!(m.find_sequence(220, m.start(NAMED_BASE).unwrap()).map(|c| c.line), Some(6));
        assert_eq!(m.find_sequence(50, m.start(0).unwrap()).map(|c| c.line), Some(3));
        let single = crate::program::SingleProgram(main);
        assert_eq!(single.find_named(b"KONTUR_1").map(|c| (c.program, c.line, c.offset)), Some((0, 4, 39)));
    }

    #[test]
    fn an_area_indexes_files_in_place() {
        // Two files side by side in one buffer (flash, or files read on the host).
        let space = b"O0001\nN1 M98 P2\nM30\nO0002\nN1 M99\n";
        let mut a = ProgramArea::<4, 8>::new(space);
        assert_eq!(a.add_file(0, 20, None), Ok(1));
        assert_eq!(a.add_file(20, space.len(), None), Ok(2));
        assert_eq!(a.start(2), Some(Cursor { program: 2, offset: 0, line: 1 }), "lines of its own file");
        assert_eq!(a.text(2), Some(&b"O0002\nN1 M99\n"[..]));
        assert_eq!(a.find_sequence(1, a.start(2).unwrap()).map(|c| (c.offset, c.line)), Some((6, 2)));
        assert_eq!(a.add_file(0, 20, None), Err(LoadError::Duplicate { program: 1 }));
        assert_eq!(a.add_file(0, 99, None), Err(LoadError::TextFull));
        assert_eq!(a.numbers().count(), 2);
    }
}

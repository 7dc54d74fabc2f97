//! Packed texts: the alarm texts as the board stores them.
//!
//! The texts stay readable in the source: a [`text_table!`] lists them, one row per
//! alarm, next to the arguments its placeholders take. At compile time a `const fn`
//! packs the table into one byte string: a word of [`WORDS`] at the start of a word
//! becomes one byte (`0x80 + index`), a `{}` becomes the number of its argument
//! (`0x01`, `0x02`), every other byte stays itself (ASCII). One small decoder,
//! [`Text::write`], writes a text out to any `fmt::Write`, expanding words and
//! arguments: the board, `lathe` and the simulator print the same bytes as the
//! `write!` format strings this replaced (a test pins every alarm text), from
//! ~40 % fewer bytes and without a `core::fmt::Arguments` set-up per text.
//! `tools/text-dict.py` chose the words from the tables.

use core::fmt;

/// A G code number in tenths (G01 = 10, G02.1 = 21, G12.1 = 121), for messages.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct GNum(pub u16);

impl fmt::Display for GNum {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.is_multiple_of(10) {
            write!(f, "G{:02}", self.0 / 10)
        } else {
            write!(f, "G{:02}.{}", self.0 / 10, self.0 % 10)
        }
    }
}

/// The dictionary: the words (with the space after them where that is how they
/// are used) that save most when packed, most useful first (`tools/text-dict.py`).
/// At most 127: a word is one byte `0x80 + index`.
const WORDS: [&str; 127] = [
    "the ",
    "defined incorrectly",
    "not ",
    "program",
    "radius compensation ",
    "of ",
    "finishing shape ",
    "spindle",
    "address ",
    "thread",
    "axis ",
    "in ",
    "or ",
    "is ",
    "block",
    "cannot be ",
    "than ",
    "tool ",
    "and ",
    "number ",
    "variable",
    "parameter",
    "range",
    "move",
    "out of ",
    "subprogram",
    "before ",
    "with",
    "contour",
    "turning ",
    "too many ",
    "incorrect",
    "plane",
    "value ",
    "must be ",
    "cycle",
    "programmed ",
    "nested deeper ",
    "direction",
    "point",
    "sequence ",
    "offset ",
    "this ",
    "only",
    "start",
    "acceleration ",
    "corner ",
    "for",
    "no ",
    "cutting ",
    "argument",
    "macro",
    "wrong ",
    "absolute coordinates ",
    "active",
    "needs ",
    "while ",
    "type ",
    "polar interpolation ",
    "controller",
    "chamfer",
    "too small ",
    "its ",
    "speed",
    "call",
    "has ",
    "takes ",
    "change",
    "illegal ",
    "defined ",
    "monotone along ",
    "polygon ",
    "between ",
    "finished part ",
    "G51",
    "given",
    "first",
    "more ",
    "depth",
    "limit",
    "arc",
    "does not ",
    "not found",
    "I/J/K",
    "degrees",
    "zero",
    "is not ",
    "used ",
    "description ",
    "levels",
    "tap",
    "cancel",
    "after ",
    "M code",
    "angle ",
    "M29 ",
    "revolution",
    "without ",
    "contradict",
    "feed ",
    "position ",
    "under",
    "G50",
    "other",
    "an ",
    "work ",
    "modal",
    "input",
    "error",
    "exist",
    "reference",
    "twice",
    "G20/G21 ",
    "CYCLE840",
    "plane selection ",
    "allowed ",
    "are",
    "machine",
    "VARI",
    "G84/G88",
    "END",
    "move exceeds ",
    "motion ",
    "mm off ",
    "section",
    "out",
    "infeed ",
];

/// The words as the decoder reads them: one after another, the last byte of each
/// with bit 7 set (the texts are ASCII).
static WORD_BYTES: [u8; words_len()] = word_bytes();

const fn words_len() -> usize {
    let mut n = 0;
    let mut i = 0;
    while i < WORDS.len() {
        n += WORDS[i].len();
        i += 1;
    }
    n
}

const fn word_bytes() -> [u8; words_len()] {
    let mut out = [0; words_len()];
    let mut n = 0;
    let mut i = 0;
    while i < WORDS.len() {
        let w = WORDS[i].as_bytes();
        let mut j = 0;
        while j < w.len() {
            out[n] = w[j];
            n += 1;
            j += 1;
        }
        out[n - 1] |= 0x80;
        i += 1;
    }
    out
}

/// The first code of an argument placeholder (`{}`): `ARG + n` is argument `n`.
const ARG: u8 = 0x01;

/// The packed code at `t[i..]` and how many bytes of `t` it stands for.
/// `arg` is the number of the `{}` placeholders before `i`.
const fn code_at(t: &[u8], i: usize, arg: u8) -> (u8, usize) {
    let b = t[i];
    if b == b'{' {
        assert!(i + 1 < t.len() && t[i + 1] == b'}', "a text may hold `{{}}` only");
        assert!(arg < 2, "a text takes at most two arguments");
        return (ARG + arg, 2);
    }
    assert!(b >= 0x20 && b < 0x7f && b != b'}', "texts are printable ASCII");
    if i == 0 || !t[i - 1].is_ascii_alphanumeric() {
        let mut best = 0;
        let mut code = 0;
        let mut k = 0;
        while k < WORDS.len() {
            let w = WORDS[k].as_bytes();
            if w.len() > best && w[0] == b && starts_with(t, i, w) {
                best = w.len();
                code = 0x80 | k as u8;
            }
            k += 1;
        }
        if best > 0 {
            return (code, best);
        }
    }
    (b, 1)
}

const fn starts_with(t: &[u8], i: usize, w: &[u8]) -> bool {
    if t.len() - i < w.len() {
        return false;
    }
    let mut j = 0;
    while j < w.len() {
        if t[i + j] != w[j] {
            return false;
        }
        j += 1;
    }
    true
}

/// Packs `t` into `out` from `at` (or only counts, when `out` is too short);
/// returns the end.
const fn pack_one(t: &[u8], out: &mut [u8], mut at: usize) -> usize {
    let mut i = 0;
    let mut arg = 0;
    while i < t.len() {
        let (code, len) = code_at(t, i, arg);
        if code == ARG + arg {
            arg += 1;
        }
        if at < out.len() {
            out[at] = code;
        }
        at += 1;
        i += len;
    }
    at
}

/// The bytes of `texts` packed one after another.
pub const fn packed_len(texts: &[&str]) -> usize {
    let mut at = 0;
    let mut i = 0;
    while i < texts.len() {
        at = pack_one(texts[i].as_bytes(), &mut [], at);
        i += 1;
    }
    at
}

/// `texts` packed one after another (`N` is [`packed_len`]).
pub const fn pack<const N: usize>(texts: &[&str]) -> [u8; N] {
    let mut out = [0; N];
    let mut at = 0;
    let mut i = 0;
    while i < texts.len() {
        at = pack_one(texts[i].as_bytes(), &mut out, at);
        i += 1;
    }
    out
}

/// Where each text of `texts` starts in [`pack`]'s bytes, and their end (`K` is
/// one more than the texts).
pub const fn starts<const K: usize>(texts: &[&str]) -> [u16; K] {
    assert!(K == texts.len() + 1);
    let mut out = [0; K];
    let mut i = 0;
    while i < texts.len() {
        let end = pack_one(texts[i].as_bytes(), &mut [], out[i] as usize);
        assert!(end <= u16::MAX as usize, "a table holds at most 64 KB");
        out[i + 1] = end as u16;
        i += 1;
    }
    out
}

/// A table of packed texts (made by [`text_table!`]).
pub struct Table {
    /// The texts packed one after another.
    pub bytes: &'static [u8],
    /// Where text `n` starts; `starts[n + 1]` is its end.
    pub starts: &'static [u16],
    /// The texts as written (tests prove each unpacks to its row).
    #[cfg(test)]
    pub source: &'static [&'static str],
}

impl Table {
    /// Text `id` packed.
    fn get(&self, id: u8) -> &[u8] {
        let id = usize::from(id);
        match (self.starts.get(id), self.starts.get(id + 1)) {
            (Some(&a), Some(&b)) => self.bytes.get(usize::from(a)..usize::from(b)).unwrap_or(&[]),
            _ => &[],
        }
    }
}

/// A value a text's placeholder stands for, with how it is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Arg {
    /// Nothing (a text with fewer placeholders).
    None,
    /// A letter or symbol as written in the program; `0xNN` when not printable.
    Ch(u8),
    /// A whole number.
    Num(i64),
    /// A whole number in at least two digits (`M05`).
    Z2(i64),
    /// A whole number in at least four digits (`O0012`).
    Z4(i64),
    /// A name or phrase of the caller.
    Str(&'static str),
    /// A G code (`G01`, `G12.1`).
    G(GNum),
    /// Nanometres as millimetres with three decimals (`0.012`).
    Mm(i64),
}

impl Arg {
    fn write(self, w: &mut dyn fmt::Write) -> fmt::Result {
        match self {
            Arg::None => Ok(()),
            Arg::Ch(c) if c.is_ascii_graphic() => w.write_char(char::from(c)),
            Arg::Ch(c) => write!(w, "0x{c:02X}"),
            Arg::Num(n) => write!(w, "{n}"),
            Arg::Z2(n) => write!(w, "{n:02}"),
            Arg::Z4(n) => write!(w, "{n:04}"),
            Arg::Str(s) => w.write_str(s),
            Arg::G(g) => write!(w, "{g}"),
            Arg::Mm(nm) => write!(w, "{}.{:03}", nm / 1_000_000, (nm % 1_000_000) / 1_000),
        }
    }
}

/// One text of a table with its arguments: what an alarm says.
#[derive(Clone, Copy)]
pub struct Text {
    /// The table the text is in.
    pub table: &'static Table,
    /// Its row.
    pub id: u8,
    /// What its placeholders stand for, in order.
    pub args: [Arg; 2],
}

impl Text {
    /// Writes the text out: words and arguments expanded.
    pub fn write(&self, w: &mut dyn fmt::Write) -> fmt::Result {
        let packed = self.table.get(self.id);
        let mut run = 0;
        for (i, &b) in packed.iter().enumerate() {
            if !(ARG + 2..0x80).contains(&b) {
                w.write_str(ascii(packed.get(run..i).unwrap_or(&[])))?;
                run = i + 1;
                if b >= 0x80 {
                    write_word(w, b & 0x7f)?;
                } else if let Some(a) = self.args.get(usize::from(b.wrapping_sub(ARG))) {
                    a.write(w)?;
                }
            }
        }
        w.write_str(ascii(packed.get(run..).unwrap_or(&[])))
    }
}

impl fmt::Display for Text {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.write(f)
    }
}

/// ASCII bytes as a `str` (packed literals are ASCII: [`code_at`] asserts it).
fn ascii(b: &[u8]) -> &str {
    core::str::from_utf8(b).unwrap_or_default()
}

/// Writes word `k` of the dictionary.
fn write_word(w: &mut dyn fmt::Write, k: u8) -> fmt::Result {
    let mut start = 0;
    let mut n = 0;
    for (i, &b) in WORD_BYTES.iter().enumerate() {
        if b & 0x80 != 0 {
            if n == k {
                w.write_str(ascii(WORD_BYTES.get(start..i).unwrap_or(&[])))?;
                return w.write_char(char::from(b & 0x7f));
            }
            n += 1;
            start = i + 1;
        }
    }
    Ok(())
}

/// A table of texts for the variants of an enum, and the method that gives a
/// value's [`Text`]. Each row: a pattern of one variant (`Name { field }`, `Name {}`
/// for one without fields), `=>`, its text with `{}` for each argument, and the
/// arguments as [`Arg`] variants of expressions of the fields:
///
/// ```ignore
/// text_table! {
///     /// The FANUC alarms' texts.
///     AlarmKind, fn fanuc_text, static FANUC {
///         TooManyDigits { letter } => "too many digits in {} word", Ch(letter);
///         FeedZero {} => "cutting feed F is zero or was never given";
///     }
/// }
/// ```
///
/// A variant without a row gets an empty text from the method (another table has it).
macro_rules! text_table {
    (
        $(#[$meta:meta])*
        $kind:ident, fn $method:ident, static $table:ident {
            $($var:ident $fields:tt => $text:literal $(, $ak:ident($av:expr))* ;)*
        }
    ) => {
        $(#[$meta])*
        static $table: $crate::text::Table = $crate::text::Table {
            bytes: &$crate::text::pack::<{ $crate::text::packed_len(&[$($text),*]) }>(&[$($text),*]),
            starts: &$crate::text::starts::<{ [$($text),*].len() + 1 }>(&[$($text),*]),
            #[cfg(test)]
            source: &[$($text),*],
        };

        impl $kind {
            $(#[$meta])*
            fn $method(&self) -> $crate::text::Text {
                #[allow(clippy::enum_variant_names)]
                #[repr(u8)]
                enum Id {
                    $($var,)*
                }
                #[allow(unused_imports)]
                use $kind::*;
                #[allow(unreachable_patterns)]
                let (id, args) = match *self {
                    $($var $fields => (Id::$var as u8, $crate::text::text_table!(@args $($ak($av)),*)),)*
                    _ => return $crate::text::Text::EMPTY,
                };
                $crate::text::Text { table: &$table, id, args }
            }
        }
    };
    (@args) => { [$crate::text::Arg::None, $crate::text::Arg::None] };
    (@args $a:ident($x:expr)) => {
        [$crate::text::Arg::$a(::core::convert::Into::into($x)), $crate::text::Arg::None]
    };
    (@args $a:ident($x:expr), $b:ident($y:expr)) => {
        [$crate::text::Arg::$a(::core::convert::Into::into($x)), $crate::text::Arg::$b(::core::convert::Into::into($y))]
    };
}
pub(crate) use text_table;

impl Text {
    /// No text (a variant another table writes).
    pub const EMPTY: Text = Text {
        table: &Table {
            bytes: &[],
            starts: &[],
            #[cfg(test)]
            source: &[],
        },
        id: 0,
        args: [Arg::None, Arg::None],
    };
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::string::String;

    /// Writes text `id` of `table` with `{}` for each argument.
    fn unpacked(table: &'static Table, id: u8) -> String {
        let mut s = String::new();
        let t = Text { table, id, args: [Arg::Str("{}"), Arg::Str("{}")] };
        t.write(&mut s).unwrap();
        s
    }

    /// Every text of every table unpacks to its row, byte for byte.
    #[test]
    fn every_text_round_trips() {
        let mut n = 0;
        for table in crate::alarm::TABLES {
            assert_eq!(table.starts.len(), table.source.len() + 1);
            for (id, row) in table.source.iter().enumerate() {
                assert_eq!(unpacked(table, id as u8), *row);
                n += 1;
            }
        }
        assert!(n > 100, "{n} texts");
    }

    #[test]
    fn words_are_ascii_and_fit_one_byte() {
        assert!(WORDS.len() <= 127);
        for w in WORDS {
            assert!(!w.is_empty() && w.bytes().all(|b| (0x20..0x7f).contains(&b) && b != b'{'), "{w:?}");
        }
        for (k, w) in WORDS.iter().enumerate() {
            let mut s = String::new();
            write_word(&mut s, k as u8).unwrap();
            assert_eq!(s, *w);
        }
    }

    #[test]
    fn arguments_are_written_as_the_format_strings_wrote_them() {
        static T: Table = Table {
            bytes: &pack::<{ packed_len(&["{} and {}"]) }>(&["{} and {}"]),
            starts: &starts::<2>(&["{} and {}"]),
            source: &["{} and {}"],
        };
        let cases: [(Arg, Arg, &str); 5] = [
            (Arg::Ch(b'X'), Arg::Ch(0x7f), "X and 0x7F"),
            (Arg::Z2(3), Arg::Z4(12), "03 and 0012"),
            (Arg::Num(-7), Arg::G(GNum(121)), "-7 and G12.1"),
            (Arg::Mm(12_345_678), Arg::Mm(-2_004_000), "12.345 and -2.-04"),
            (Arg::Str("G00"), Arg::None, "G00 and "),
        ];
        for (a, b, want) in cases {
            let mut s = String::new();
            Text { table: &T, id: 0, args: [a, b] }.write(&mut s).unwrap();
            assert_eq!(s, want);
        }
    }
}

//! The head of one block's text — blanks, comments, a `/n` skip mark, `N` and its
//! digits — read the same way by the program memory (sequence search) and by the
//! macro reader (where a statement begins). Below both, so neither looks up at
//! the other.

/// Where the statement of a block begins: after blanks, comments, a `/n` skip mark
/// and a sequence number.
pub(crate) fn statement_start(text: &[u8]) -> usize {
    block_head(text).1
}

/// The N number a block starts with, if any (after blanks, comments and a `/n`
/// skip mark, as FANUC searches it).
pub(crate) fn leading_sequence(text: &[u8]) -> Option<u32> {
    block_head(text).0
}

/// Reads the head of a block — blanks, comments, a `/n` skip mark, `N` and its
/// digits — and returns the sequence number and where the statement begins.
fn block_head(text: &[u8]) -> (Option<u32>, usize) {
    let mut i = 0;
    let skip = |i: &mut usize| {
        loop {
            while matches!(text.get(*i), Some(b' ' | b'\t' | b'\r')) {
                *i += 1;
            }
            if text.get(*i) != Some(&b'(') {
                return;
            }
            match text[*i..].iter().position(|&c| c == b')') {
                Some(n) => *i += n + 1,
                None => return,
            }
        }
    };
    skip(&mut i);
    if text.get(i) == Some(&b'/') {
        i += 1;
        if text.get(i).is_some_and(u8::is_ascii_digit) {
            i += 1;
        }
        skip(&mut i);
    }
    let mut seq = None;
    if matches!(text.get(i), Some(b'N' | b'n')) {
        i += 1;
        skip(&mut i);
        let mut v: u32 = 0;
        let mut digits = 0;
        while let Some(d) = text.get(i).filter(|c| c.is_ascii_digit()) {
            if digits < 6 {
                v = v * 10 + u32::from(d - b'0');
            }
            digits += 1;
            i += 1;
        }
        seq = (digits > 0).then_some(v);
        skip(&mut i);
    }
    (seq, i)
}

//! What a received line is, before the controller acts on it: blanks trimmed,
//! bytes that cannot be program text, `$` commands, a lone `%`, a grbl sender's
//! sync dwell. Pure functions of the text.

/// What a line (after the link's framing) asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind<'a> {
    /// It holds a byte that cannot be G-code text: refused whole.
    BadByte(u8),
    /// Empty (blank or only CR).
    Blank,
    /// A `$` command: the text after the `$`.
    Dollar(&'a [u8]),
    /// A line that is only `%` (a record mark, or the start of tape mode).
    Percent,
    /// Program text.
    Program(&'a [u8]),
}

/// What `text` (trimmed) asks for.
pub(crate) fn kind(text: &[u8]) -> Kind<'_> {
    if let Some(b) = bad_byte(text) {
        return Kind::BadByte(b);
    }
    match text.first() {
        None => Kind::Blank,
        Some(b'$') => Kind::Dollar(text.get(1..).unwrap_or(&[])),
        Some(b'%') if text == b"%" => Kind::Percent,
        Some(_) => Kind::Program(text),
    }
}

/// The first byte of `line` that cannot be program text (control characters other
/// than TAB and CR, DEL, bytes ≥ 0x80).
fn bad_byte(line: &[u8]) -> Option<u8> {
    line.iter().copied().find(|&b| (b < 0x20 && b != b'\t' && b != b'\r') || b >= 0x7f)
}

/// A line without surrounding blanks and CR.
pub(crate) fn trim(mut s: &[u8]) -> &[u8] {
    while let [b' ' | b'\t' | b'\r', rest @ ..] = s {
        s = rest;
    }
    while let [rest @ .., b' ' | b'\t' | b'\r'] = s {
        s = rest;
    }
    s
}

pub(crate) fn resend_text(n: u32) -> heapless::String<32> {
    let mut s = heapless::String::new();
    let _ = core::fmt::write(&mut s, format_args!("Resend:{n}"));
    s
}

pub(crate) fn bad_text(b: u8) -> heapless::String<48> {
    let mut s = heapless::String::new();
    let _ = core::fmt::write(&mut s, format_args!("Byte 0x{b:02X} is not G-code text: line refused"));
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_are_trimmed_and_sorted() {
        assert_eq!(trim(b"  G1 \r"), b"G1");
        assert_eq!(kind(b""), Kind::Blank);
        assert_eq!(kind(b"$X"), Kind::Dollar(b"X"));
        assert_eq!(kind(b"%"), Kind::Percent);
        assert_eq!(kind(b"%1"), Kind::Program(b"%1"));
        assert_eq!(kind(b"G1 \x01"), Kind::BadByte(1));
    }
}

/// A grbl sender's sync dwell: a line that is only `G4 P<seconds>` with a decimal
/// point (CNCjs ends every job with `G4 P0.5`). In the board's language G04 P is in
/// milliseconds without a decimal point (a decimal point is alarm 0007), so such a
/// line can only mean grbl's dwell in seconds; with `$303=1` (the default) it runs as
/// `G04 X<seconds>`. Returns the seconds' text.
pub(crate) fn grbl_sync_dwell(text: &[u8]) -> Option<&[u8]> {
    let t: &[u8] = trim(text);
    let rest = t.strip_prefix(b"G4").or_else(|| t.strip_prefix(b"G04"))?;
    let rest = trim(rest);
    let value = trim(rest.strip_prefix(b"P")?);
    let digits_and_point = value.iter().all(|b| b.is_ascii_digit() || *b == b'.');
    let one_point = value.iter().filter(|&&b| b == b'.').count() == 1;
    (digits_and_point && one_point && value.len() <= 12).then_some(value)
}

#[cfg(test)]
mod dwell_tests {
    use super::grbl_sync_dwell;

    #[test]
    fn only_a_lone_g4_p_with_a_decimal_point_is_a_grbl_dwell() {
        assert_eq!(grbl_sync_dwell(b"G4 P0.5"), Some(&b"0.5"[..]));
        assert_eq!(grbl_sync_dwell(b"G04P1."), Some(&b"1."[..]));
        assert_eq!(grbl_sync_dwell(b"G4 P500"), None, "FANUC milliseconds stay as they are");
        assert_eq!(grbl_sync_dwell(b"G4 P0.5 X1"), None);
        assert_eq!(grbl_sync_dwell(b"G01 X1"), None);
    }
}

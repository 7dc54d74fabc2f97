//! Decimal numbers as the link writes them (`$110=6000.5`, `$J=X-1.5 F100`),
//! read without `core`'s `f64::from_str`: its correctly rounding algorithm and
//! tables are ~15 KB of flash on the board, for settings that need no more than
//! the 15 significant digits this reads exactly.

/// Significant digits kept; later ones are dropped (a setting has far fewer).
const DIGITS: u32 = 19;

/// The powers of ten a double holds exactly (10^0 … 10^22).
fn exact_pow10(e: u32) -> f64 {
    let mut p = 1.0;
    for _ in 0..e {
        p *= 10.0;
    }
    p
}

/// `m × 10^e`, exact (correctly rounded) when `m < 2^53` and `|e| ≤ 22`.
fn scale(m: u64, e: i32) -> f64 {
    let mut v = m as f64;
    let mut left = e;
    while left != 0 {
        let step = left.unsigned_abs().min(22);
        let p = exact_pow10(step);
        if left > 0 {
            v *= p;
            left -= step as i32;
        } else {
            v /= p;
            left += step as i32;
        }
    }
    v
}

/// A decimal number with optional blanks around it, an optional sign, digits with
/// at most one decimal point (`5`, `-1.25`, `.5`, `2.`) and an optional exponent
/// (`1e3`); `None` for anything else or a value beyond `f64`.
pub fn decimal(s: &[u8]) -> Option<f64> {
    let s = s.trim_ascii();
    let (negative, s) = match s.split_first() {
        Some((b'-', rest)) => (true, rest),
        Some((b'+', rest)) => (false, rest),
        _ => (false, s),
    };
    let (mut m, mut exp, mut kept, mut any, mut point) = (0u64, 0i32, 0u32, false, false);
    let mut i = 0;
    while let Some(&c) = s.get(i) {
        match c {
            b'0'..=b'9' => {
                any = true;
                if kept < DIGITS {
                    m = m * 10 + u64::from(c - b'0');
                    if m != 0 {
                        kept += 1;
                    }
                    exp -= i32::from(point);
                } else {
                    exp += i32::from(!point);
                }
            }
            b'.' if !point => point = true,
            _ => break,
        }
        i += 1;
    }
    if !any {
        return None;
    }
    if let Some(rest) = s.get(i..).filter(|r| !r.is_empty()) {
        let (e_rest, rest) = match rest.split_first() {
            Some((b'e' | b'E', r)) => (true, r),
            _ => (false, rest),
        };
        if !e_rest {
            return None;
        }
        let (e_neg, digits) = match rest.split_first() {
            Some((b'-', r)) => (true, r),
            Some((b'+', r)) => (false, r),
            _ => (false, rest),
        };
        if digits.is_empty() || !digits.iter().all(u8::is_ascii_digit) {
            return None;
        }
        let e = digits.iter().fold(0i32, |e, d| e.saturating_mul(10).saturating_add(i32::from(d - b'0')));
        exp = exp.saturating_add(if e_neg { -e } else { e });
    }
    // Far beyond any value a double holds: 0 or infinite without the loop.
    let v = if m == 0 || exp < -400 {
        0.0
    } else if exp > 400 {
        f64::INFINITY
    } else {
        scale(m, exp)
    };
    let v = if negative { -v } else { v };
    v.is_finite().then_some(v)
}

#[cfg(test)]
mod tests {
    use super::decimal;

    #[test]
    fn reads_what_the_standard_parser_reads() {
        for s in [
            "0",
            "5",
            "-1.25",
            "+3",
            ".5",
            "2.",
            "6000.5",
            "0.001",
            "-0.0004",
            "  12.75 ",
            "1e3",
            "2.5E-2",
            "123456789012345",
            "0.1",
            "0.3",
            "1.797693134862315",
            "99999.999",
            "1e22",
            "1e-22",
            "000123.4500",
        ] {
            assert_eq!(decimal(s.as_bytes()), s.trim().parse::<f64>().ok(), "{s}");
        }
    }

    #[test]
    fn refuses_what_is_not_a_finite_number() {
        for s in ["", " ", "-", ".", "+.", "1.2.3", "1,5", "abc", "1e", "1e+", "inf", "NaN", "1e999", "5x", "--1"] {
            assert_eq!(decimal(s.as_bytes()), None, "{s}");
        }
    }

    #[test]
    fn long_numbers_are_close() {
        let s = "3.14159265358979323846264338";
        let v = decimal(s.as_bytes()).unwrap_or(0.0);
        assert!((v - core::f64::consts::PI).abs() < 1e-15, "{v}");
        assert_eq!(decimal(b"12345678901234567890123"), Some(1.2345678901234568e22));
        assert_eq!(decimal(b"1e-400"), Some(0.0));
        let v = decimal(b"1.7976931348623157").unwrap_or(0.0);
        assert!((v - 1.7976931348623157).abs() < 1e-15, "{v}");
    }
}

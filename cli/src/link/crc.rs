//! The optional per-line checksum of the link (docs/PROTOCOL.md, Checksums):
//! `N<k> <line>*<crc>` with CRC-16/CCITT-FALSE over every byte before the `*`.

/// CRC-16/CCITT-FALSE (polynomial 0x1021, initial value 0xFFFF, no reflection, no
/// final XOR) of `bytes`.
pub fn crc16(bytes: &[u8]) -> u16 {
    bytes.iter().fold(0xFFFF_u16, |crc, &b| {
        (0..8).fold(crc ^ (u16::from(b) << 8), |c, _| if c & 0x8000 != 0 { (c << 1) ^ 0x1021 } else { c << 1 })
    })
}

/// `text` framed as link line number `k`: `N<k> <text>*<CRC as 4 upper-case hex digits>`.
pub fn frame(k: usize, text: &str) -> String {
    let body = format!("N{k} {text}");
    let crc = crc16(body.as_bytes());
    format!("{body}*{crc:04X}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crc_matches_the_standard_check_value() {
        // The catalogue check value of CRC-16/CCITT-FALSE over "123456789".
        assert_eq!(crc16(b"123456789"), 0x29B1);
        assert_eq!(crc16(b""), 0xFFFF);
    }

    #[test]
    fn frame_numbers_the_line_and_appends_the_crc_of_everything_before_the_star() {
        let f = frame(12, "G01 X20 F0.2");
        let (body, crc) = f.split_once('*').unwrap();
        assert_eq!(body, "N12 G01 X20 F0.2");
        assert_eq!(crc, format!("{:04X}", crc16(b"N12 G01 X20 F0.2")));
        assert_eq!(crc.len(), 4);
        assert_eq!(frame(1, ""), format!("N1 *{:04X}", crc16(b"N1 ")));
    }
}

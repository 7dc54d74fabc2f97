//! The board's response lines (docs/PROTOCOL.md, Responses and Status report)
//! parsed into values the host tools act on.

/// One line from the board.
#[derive(Clone, Debug, PartialEq)]
pub enum Response {
    /// `ok`: the oldest line in flight was accepted.
    Ok,
    /// `error:N`: the oldest line in flight was refused.
    Error(u16),
    /// `N<k> ok` / `N<k> error:N` (link checksums in use): the answer to link line `k`.
    Answer(u32, Result<(), u16>),
    /// `ALARM:N`: the board stopped in state Alarm.
    Alarm(u16),
    /// `Grbl 1.1h ['$' for help]`: the board (re)started.
    Welcome(String),
    /// `<…>`: a status report.
    Status(Status),
    /// `[MSG:Resend:n]`: the board expects link line `n` next (checksum mode).
    Resend(u32),
    /// `[LK:<last>,<free>]`, the answer to ENQ (0x05): the last link line the board
    /// accepted and its free receive-buffer bytes.
    Link(u32, u32),
    /// `[MSG:text]` other than a resend request.
    Msg(String),
    /// Any other `[…]` feedback line (`[PRG:…]`, `[GC:…]`, `[VER:…]` …), brackets kept.
    Feedback(String),
    /// Anything else (`$n=value` lines of `$$`, help text).
    Other(String),
}

/// A line of the board as its link framing says (docs/PROTOCOL.md, Checksums:
/// with checksums in use every line ends in `*<CRC-16 of the text>`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Framed<'a> {
    /// No `*<crc>` at its end.
    Plain(&'a str),
    /// `text*<crc>` with the right CRC: the text.
    Good(&'a str),
    /// `*<crc>` that does not match: damaged on the way.
    Bad,
}

/// Reads the framing of a board line (without its line end).
pub fn framing(line: &str) -> Framed<'_> {
    let line = line.trim_end_matches(['\r', ' ']);
    match line.rsplit_once('*') {
        Some((text, crc)) if crc.len() == 4 && crc.bytes().all(|b| b.is_ascii_hexdigit()) => {
            if u16::from_str_radix(crc, 16).ok() == Some(super::crc::crc16(text.as_bytes())) {
                Framed::Good(text)
            } else {
                Framed::Bad
            }
        }
        _ => Framed::Plain(line),
    }
}

/// Parses one response line (without its line end or link framing).
pub fn parse(line: &str) -> Response {
    let line = line.trim();
    if line == "ok" {
        return Response::Ok;
    }
    if let Some((k, reply)) = line.strip_prefix('N').and_then(|t| t.split_once(' '))
        && let Ok(k) = k.parse::<u32>()
    {
        if reply == "ok" {
            return Response::Answer(k, Ok(()));
        }
        if let Some(code) = reply.strip_prefix("error:").and_then(|n| n.trim().parse().ok()) {
            return Response::Answer(k, Err(code));
        }
    }
    if let Some(code) = line.strip_prefix("error:").and_then(|n| n.trim().parse().ok()) {
        return Response::Error(code);
    }
    if let Some(code) = line.strip_prefix("ALARM:").and_then(|n| n.trim().parse().ok()) {
        return Response::Alarm(code);
    }
    if line.starts_with("Grbl ") {
        return Response::Welcome(line.to_owned());
    }
    if let Some(status) = line.strip_prefix('<').and_then(|r| r.strip_suffix('>')) {
        return Response::Status(Status::parse(status));
    }
    if let Some(msg) = line.strip_prefix("[MSG:").and_then(|r| r.strip_suffix(']')) {
        return match msg.strip_prefix("Resend:").and_then(|n| n.trim().parse().ok()) {
            Some(n) => Response::Resend(n),
            None => Response::Msg(msg.to_owned()),
        };
    }
    if let Some((last, free)) = line.strip_prefix("[LK:").and_then(|r| r.strip_suffix(']')).and_then(pair) {
        return Response::Link(last, free);
    }
    if line.starts_with('[') {
        return Response::Feedback(line.to_owned());
    }
    Response::Other(line.to_owned())
}

/// A status report `<State|MPos:x,y,z|FS:feed,rpm|Bf:blocks,bytes|Ln:line|WCO:x,y,z|Ov:f,r,s|Pn:…>`.
/// Fields the board left out are `None` (or empty).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Status {
    /// `Idle`, `Run`, `Hold:0`, `Hold:1`, `Alarm`, …
    pub state: String,
    /// Machine position, mm: X diameter, Y (always 0), Z, and C in degrees when present.
    pub mpos: Vec<f64>,
    /// Work offset of the block running (MPos − WPos), same axes.
    pub wco: Vec<f64>,
    /// Current feed, mm/min.
    pub feed: Option<f64>,
    /// Measured spindle speed, rev/min.
    pub rpm: Option<f64>,
    /// Free planner blocks and free receive-buffer bytes.
    pub buffer: Option<(u32, u32)>,
    /// Program line the motion is executing.
    pub line: Option<u32>,
    /// Overrides: feed, rapid, spindle, %.
    pub overrides: Option<(u32, u32, u32)>,
    /// Active inputs (`Pn:` letters), empty when none.
    pub pins: String,
    /// `Lk:` (link checksums in use): the last link line the board accepted.
    pub link: Option<u32>,
}

impl Status {
    /// Parses the text between `<` and `>`.
    pub fn parse(text: &str) -> Status {
        let mut fields = text.split('|');
        let mut s = Status { state: fields.next().unwrap_or_default().to_owned(), ..Status::default() };
        for field in fields {
            let Some((key, value)) = field.split_once(':') else { continue };
            match key {
                "MPos" => s.mpos = numbers(value),
                "WCO" => s.wco = numbers(value),
                "FS" | "F" => {
                    let v = numbers(value);
                    s.feed = v.first().copied();
                    s.rpm = v.get(1).copied();
                }
                "Bf" => s.buffer = pair(value),
                "Ln" => s.line = value.trim().parse().ok(),
                "Ov" => s.overrides = triple(value),
                "Pn" => s.pins = value.to_owned(),
                "Lk" => s.link = value.trim().parse().ok(),
                _ => {}
            }
        }
        s
    }

    /// Work position of axis `i` (0 X diameter, 2 Z): MPos − WCO (MPos alone without WCO).
    pub fn work(&self, i: usize) -> Option<f64> {
        let m = self.mpos.get(i)?;
        Some(m - self.wco.get(i).copied().unwrap_or(0.0))
    }

    /// One line for a live display: `Run  X 25.000  Z -10.500  F 120  S 800  Ln 12`.
    pub fn summary(&self) -> String {
        let num = |v: Option<f64>, decimals: usize| v.map_or("-".to_owned(), |v| format!("{v:.decimals$}"));
        format!(
            "{:<7} X {}  Z {}  F {}  S {}  Ln {}",
            self.state,
            num(self.work(0), 3),
            num(self.work(2), 3),
            num(self.feed, 0),
            num(self.rpm, 0),
            self.line.map_or("-".to_owned(), |l| l.to_string())
        )
    }

    /// Whether the board is idle with nothing queued: state `Idle` and, when the report
    /// has `Bf:`, at least the free planner blocks and receive bytes of `empty` (what
    /// the idle board reported at the start; without it, any `Bf:` counts).
    pub fn idle_and_empty(&self, empty: Option<(u32, u32)>) -> bool {
        self.state == "Idle"
            && match (self.buffer, empty) {
                (Some((b, r)), Some((eb, er))) => b >= eb && r >= er,
                _ => true,
            }
    }
}

/// Comma-separated numbers; a field that is not a number is left out.
fn numbers(text: &str) -> Vec<f64> {
    text.split(',').filter_map(|v| v.trim().parse().ok()).collect()
}

/// Two comma-separated whole numbers.
fn pair(text: &str) -> Option<(u32, u32)> {
    let (a, b) = text.split_once(',')?;
    Some((a.trim().parse().ok()?, b.trim().parse().ok()?))
}

/// Three comma-separated whole numbers.
fn triple(text: &str) -> Option<(u32, u32, u32)> {
    let mut it = text.split(',').map(|v| v.trim().parse().ok());
    Some((it.next()??, it.next()??, it.next()??))
}

/// The text of a grbl error number, for `error:N` that came without a `[MSG:…]`.
pub fn error_text(code: u16) -> &'static str {
    match code {
        1 => "bad character or letter",
        2 => "bad number",
        3 => "unknown $ command",
        8 => "the command needs the board idle",
        9 => "locked by an alarm ($X or soft reset unlocks)",
        11 => "line too long",
        15 => "jog beyond the soft limits",
        16 => "bad jog line",
        20 => "unsupported code",
        88 => "link checksum or line number wrong",
        _ => "refused",
    }
}

/// The meaning of an `ALARM:N` number.
pub fn alarm_text(code: u16) -> &'static str {
    match code {
        1 => "hard limit",
        2 => "soft limit",
        3 => "reset while moving",
        6 | 8 | 9 => "homing failed",
        10 => "emergency stop",
        20 => "program alarm",
        _ => "alarm",
    }
}

/// A `[MSG:ALARM <code> line <n>: <message>]` text split into (code, line, message).
pub fn program_alarm(msg: &str) -> Option<(&str, u32, &str)> {
    let rest = msg.strip_prefix("ALARM ")?;
    let (code, rest) = rest.split_once(" line ")?;
    let (line, message) = rest.split_once(':')?;
    Some((code.trim(), line.trim().parse().ok()?, message.trim()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn answers_alarms_and_welcome() {
        assert_eq!(parse("ok\r"), Response::Ok);
        assert_eq!(parse("error:20"), Response::Error(20));
        assert_eq!(parse("ALARM:2"), Response::Alarm(2));
        assert_eq!(parse("Grbl 1.1h ['$' for help]"), Response::Welcome("Grbl 1.1h ['$' for help]".into()));
        assert_eq!(parse("[MSG:Resend:17]"), Response::Resend(17));
        assert_eq!(parse("[MSG:Pgm End]"), Response::Msg("Pgm End".into()));
        assert_eq!(parse("[PRG:O0001,230]"), Response::Feedback("[PRG:O0001,230]".into()));
        assert_eq!(parse("$110=500.000"), Response::Other("$110=500.000".into()));
        assert_eq!(parse("error:x"), Response::Other("error:x".into()));
    }

    #[test]
    fn framed_lines_and_numbered_answers() {
        let good = format!("N12 ok*{:04X}", super::super::crc::crc16(b"N12 ok"));
        assert_eq!(framing(&good), Framed::Good("N12 ok"));
        assert_eq!(parse("N12 ok"), Response::Answer(12, Ok(())));
        assert_eq!(parse("N3 error:1"), Response::Answer(3, Err(1)));
        let mut bad = good.clone().into_bytes();
        bad[1] = b'3';
        assert_eq!(framing(std::str::from_utf8(&bad).unwrap()), Framed::Bad);
        assert_eq!(framing("ok"), Framed::Plain("ok"));
        assert_eq!(Status::parse("Idle|Bf:64,128|Lk:17").link, Some(17));
        assert_eq!(parse("[LK:1999,93]"), Response::Link(1999, 93));
        assert_eq!(parse("[LK:19x,93]"), Response::Feedback("[LK:19x,93]".into()));
    }

    #[test]
    fn a_full_status_report() {
        let Response::Status(s) = parse(
            "<Run|MPos:60.000,0.000,-12.500|FS:120,812|Bf:60,100|Ln:14|WCO:10.000,0.000,-2.500|Ov:100,50,110|Pn:XH>",
        ) else {
            panic!("a status report")
        };
        assert_eq!(s.state, "Run");
        assert_eq!(s.mpos, vec![60.0, 0.0, -12.5]);
        assert_eq!(s.work(0), Some(50.0));
        assert_eq!(s.work(2), Some(-10.0));
        assert_eq!((s.feed, s.rpm), (Some(120.0), Some(812.0)));
        assert_eq!(s.buffer, Some((60, 100)));
        assert_eq!(s.line, Some(14));
        assert_eq!(s.overrides, Some((100, 50, 110)));
        assert_eq!(s.pins, "XH");
        assert_eq!(s.summary(), "Run     X 50.000  Z -10.000  F 120  S 812  Ln 14");
        assert!(!s.idle_and_empty(Some((64, 128))));
    }

    #[test]
    fn idle_and_empty_needs_every_block_and_byte_free() {
        let s = Status::parse("Idle|MPos:0,0,0|Bf:64,128");
        assert!(s.idle_and_empty(Some((64, 128))));
        assert!(!s.idle_and_empty(Some((65, 128))));
        assert!(!s.idle_and_empty(Some((64, 129))));
        assert!(Status::parse("Idle|Bf:15,127").idle_and_empty(Some((15, 127))), "a board that reports 127");
        assert!(Status::parse("Idle|MPos:0,0,0").idle_and_empty(Some((64, 128))));
        assert!(!Status::parse("Hold:1|Bf:64,128").idle_and_empty(None));
    }

    #[test]
    fn program_alarm_messages_split_into_code_line_and_text() {
        assert_eq!(program_alarm("ALARM 0010 line 4: G07 is not a G code"), Some(("0010", 4, "G07 is not a G code")));
        assert_eq!(program_alarm("Pgm End"), None);
    }
}

//! The character-counting streamer of grbl mode as a state machine without a port:
//! the caller asks it which line to write next, tells it each answer (`ok` /
//! `error:N`) and resend request, and the time; it never has more than the board's
//! receive buffer (128 bytes, each line counted with its LF) unanswered in flight.
//!
//! With checksums every line goes out as `N<k> <text>*<crc>` (k = its 1-based index)
//! and a `[MSG:Resend:n]` makes it stop, wait until every line in flight is answered
//! or [`StreamConfig::silence`] passes without an answer, and go on from line n.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use super::crc;

/// The board's receive buffer, bytes (docs/PROTOCOL.md: the LF included).
pub const RX_BUFFER: usize = 128;

/// How the streamer frames and paces lines.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StreamConfig {
    /// Bytes that may be in flight unanswered.
    pub buffer: usize,
    /// Frame every line as `N<k> <text>*<crc>`.
    pub checksum: bool,
    /// After a resend request, how long without an answer counts as "all answered".
    pub silence: Duration,
}

impl StreamConfig {
    /// How long without an answer, after a resend request, counts as "every line in
    /// flight answered" at `baud`: the time 256 characters take on the wire (128
    /// bytes in flight to the board, its answers back) and 10 ms for the board and
    /// the host (the board answers a line within a millisecond of its LF): 32 ms at
    /// 115200 baud, 277 ms at 9600.
    pub fn silence_at(baud: u32) -> Duration {
        Duration::from_secs(10) * 256 / baud.max(1) + Duration::from_millis(10)
    }
}

impl Default for StreamConfig {
    fn default() -> Self {
        StreamConfig { buffer: RX_BUFFER, checksum: false, silence: Duration::from_millis(100) }
    }
}

/// A line that cannot be streamed: framed with its LF it does not fit the buffer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TooLong {
    /// 0-based index of the line.
    pub index: usize,
    /// Its framed length with the LF.
    pub bytes: usize,
}

/// What an answer meant.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Line `index` (0-based) was accepted.
    Accepted(usize),
    /// Line `index` was refused with `error:code`.
    Refused(usize, u16),
    /// An answer to a line that the pending resend will send again (not an error).
    Superseded(usize),
    /// An answer with nothing in flight (the board answered a line it never got from us).
    Unexpected,
}

/// A line written and not yet answered.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct InFlight {
    index: usize,
    bytes: usize,
}

/// A pending resend: from which line, and when the last answer came.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Resend {
    from: usize,
    last_answer: Instant,
}

/// The streamer: the lines, the cursor, what is in flight.
#[derive(Clone, Debug)]
pub struct Streamer {
    lines: Vec<String>,
    cfg: StreamConfig,
    next: usize,
    accepted: usize,
    in_flight: VecDeque<InFlight>,
    in_flight_bytes: usize,
    resend: Option<Resend>,
    stopped: bool,
}

impl Streamer {
    /// A streamer of `lines` (text without line ends); refuses a line that framed
    /// with its LF is longer than the buffer.
    pub fn new(lines: Vec<String>, cfg: StreamConfig) -> Result<Streamer, TooLong> {
        let s = Streamer {
            lines,
            cfg,
            next: 0,
            accepted: 0,
            in_flight: VecDeque::new(),
            in_flight_bytes: 0,
            resend: None,
            stopped: false,
        };
        for index in 0..s.lines.len() {
            let bytes = s.framed(index).map_or(0, |f| f.len());
            if bytes > cfg.buffer {
                return Err(TooLong { index, bytes });
            }
        }
        Ok(s)
    }

    /// Line `index` as it goes on the wire, LF included.
    fn framed(&self, index: usize) -> Option<String> {
        let text = self.lines.get(index)?;
        Some(if self.cfg.checksum { format!("{}\n", crc::frame(index + 1, text)) } else { format!("{text}\n") })
    }

    /// The next line to write now, if there is one and it fits in the buffer; it
    /// counts as in flight from here on.
    pub fn next_line(&mut self) -> Option<String> {
        if self.stopped || self.resend.is_some() {
            return None;
        }
        let line = self.framed(self.next)?;
        if self.in_flight_bytes + line.len() > self.cfg.buffer {
            return None;
        }
        self.in_flight.push_back(InFlight { index: self.next, bytes: line.len() });
        self.in_flight_bytes += line.len();
        self.next += 1;
        Some(line)
    }

    /// The board answered the oldest line in flight: `Ok(())` for `ok`, `Err(code)`
    /// for `error:code`.
    pub fn answer(&mut self, answer: Result<(), u16>, now: Instant) -> Outcome {
        let Some(line) = self.in_flight.pop_front() else { return Outcome::Unexpected };
        self.in_flight_bytes -= line.bytes;
        if let Some(r) = &mut self.resend {
            r.last_answer = now;
            if line.index >= r.from {
                return Outcome::Superseded(line.index);
            }
        }
        if self.cfg.checksum && answer == Err(88) {
            // A link error is never a refusal: the `[MSG:Resend:n]` before it says
            // what to send again. (After line noise has eaten a line end, answers
            // and lines in flight may be out of step; the board's number rules.)
            // When line noise ate that message, the line was still not taken: it is
            // sent again (were it taken after all, the board answers the duplicate
            // `N<k> ok` and drops it). Without this, a refused last line whose
            // request was lost left nothing in flight and nothing to resend: the
            // job never ended (noise soak, 1 % both ways, run 97 of 100).
            match &mut self.resend {
                Some(r) => r.from = r.from.min(line.index),
                None => self.resend = Some(Resend { from: line.index, last_answer: now }),
            }
            return Outcome::Superseded(line.index);
        }
        match answer {
            Ok(()) => {
                self.accepted = self.accepted.max(line.index + 1);
                Outcome::Accepted(line.index)
            }
            Err(code) => Outcome::Refused(line.index, code),
        }
    }

    /// `N<k> ok` / `N<k> error:N` (checksums): the board's answer to link line `k`
    /// (1-based). The board takes link lines strictly in order, so every line in
    /// flight before `k` was taken too: their answers were lost on the way (line
    /// noise) and they count as accepted. An answer to a line not in flight (a
    /// duplicate's) changes nothing.
    pub fn answer_line(&mut self, k: u32, answer: Result<(), u16>, now: Instant) -> Outcome {
        let Some(index) = usize::try_from(k).ok().and_then(|k| k.checked_sub(1)) else { return Outcome::Unexpected };
        if let Some(r) = &mut self.resend {
            r.last_answer = now;
        }
        self.taken_before(index);
        if self.in_flight.front().is_none_or(|l| l.index != index) {
            return Outcome::Superseded(index);
        }
        self.pop_front();
        match answer {
            Ok(()) => {
                self.taken_before(index + 1);
                Outcome::Accepted(index)
            }
            Err(code) => Outcome::Refused(index, code),
        }
    }

    /// The board reports (`Lk:`) that it took every link line up to `last`: lines in
    /// flight up to it count as accepted (their answers were lost).
    pub fn taken_up_to(&mut self, last: u32) {
        self.taken_before(usize::try_from(last).unwrap_or(usize::MAX));
    }

    /// Lines before index `end` were taken by the board.
    fn taken_before(&mut self, end: usize) {
        while self.in_flight.front().is_some_and(|l| l.index < end) {
            self.pop_front();
        }
        let end = end.min(self.next);
        self.accepted = self.accepted.max(end);
        if let Some(r) = &mut self.resend {
            r.from = r.from.max(end);
        }
    }

    fn pop_front(&mut self) {
        if let Some(line) = self.in_flight.pop_front() {
            self.in_flight_bytes -= line.bytes;
        }
    }

    /// The lines in flight were lost (the board reports its buffer empty and has
    /// not taken them, and no answer comes): sending goes on from the first line the
    /// board has not taken (0-based `from`). Returns it.
    pub fn lost_in_flight(&mut self, from: usize) -> usize {
        let from = from.max(self.accepted).min(self.next);
        self.in_flight.clear();
        self.in_flight_bytes = 0;
        self.resend = None;
        self.next = from;
        self.accepted = from;
        from
    }

    /// `[MSG:Resend:n]`: the board expects link line `n` (1-based) next. Sending
    /// stops until the lines in flight are answered or [`StreamConfig::silence`]
    /// passes; see [`Streamer::tick`]. A number beyond the lines sent is ignored
    /// (returns false).
    pub fn resend_request(&mut self, n: u32, now: Instant) -> bool {
        let Some(from) = usize::try_from(n).ok().and_then(|n| n.checked_sub(1)) else { return false };
        if from > self.next {
            return false;
        }
        self.resend = Some(Resend { from, last_answer: now });
        true
    }

    /// Lets time pass: a pending resend starts once nothing is in flight, or when no
    /// answer came for [`StreamConfig::silence`] (lines the board lost are given up).
    /// Returns the line it resends from, when it does.
    pub fn tick(&mut self, now: Instant) -> Option<usize> {
        let r = self.resend?;
        if !self.in_flight.is_empty() && now.saturating_duration_since(r.last_answer) < self.cfg.silence {
            return None;
        }
        self.in_flight.clear();
        self.in_flight_bytes = 0;
        self.resend = None;
        self.next = r.from;
        self.accepted = r.from;
        Some(r.from)
    }

    /// Sends nothing more (after an error, an alarm or an abort).
    pub fn stop(&mut self) {
        self.stopped = true;
    }

    /// Bytes written and not yet answered.
    pub fn in_flight_bytes(&self) -> usize {
        self.in_flight_bytes
    }

    /// Lines written so far (the cursor; it moves back on a resend).
    pub fn sent(&self) -> usize {
        self.next
    }

    /// Lines accepted: every line before this index got `ok`.
    pub fn accepted(&self) -> usize {
        self.accepted
    }

    /// Number of lines.
    pub fn total(&self) -> usize {
        self.lines.len()
    }

    /// Every line was accepted.
    pub fn all_accepted(&self) -> bool {
        self.accepted == self.lines.len() && self.in_flight.is_empty() && self.resend.is_none()
    }

    /// A resend is pending.
    pub fn resending(&self) -> bool {
        self.resend.is_some()
    }

    /// Lines are in flight, unanswered.
    pub fn waiting(&self) -> bool {
        !self.in_flight.is_empty()
    }

    /// Lines are framed with checksums.
    pub fn checksum(&self) -> bool {
        self.cfg.checksum
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lines(n: usize, len: usize) -> Vec<String> {
        (0..n).map(|i| format!("G01 X{i:0width$}", width = len.saturating_sub(5))).collect()
    }

    fn drain(s: &mut Streamer) -> Vec<String> {
        std::iter::from_fn(|| s.next_line()).collect()
    }

    #[test]
    fn counting_fills_the_buffer_and_never_exceeds_it() {
        // 30-byte lines with LF: four fit (120 bytes), a fifth would make 150.
        let mut s = Streamer::new(lines(10, 29), StreamConfig::default()).unwrap();
        let first = drain(&mut s);
        assert_eq!(first.len(), 4);
        assert!(first.iter().all(|l| l.len() == 30 && l.ends_with('\n')));
        assert_eq!(s.in_flight_bytes(), 120);
        let t = Instant::now();
        assert_eq!(s.answer(Ok(()), t), Outcome::Accepted(0));
        assert_eq!(drain(&mut s).len(), 1);
        assert_eq!(s.in_flight_bytes(), 120);
        assert_eq!((s.sent(), s.accepted()), (5, 1));
    }

    #[test]
    fn in_flight_bytes_stay_within_128_whatever_the_line_lengths() {
        let texts: Vec<String> = (0..200).map(|i| "X".repeat((i * 37) % 127)).collect();
        let total = texts.len();
        let mut s = Streamer::new(texts, StreamConfig::default()).unwrap();
        let t = Instant::now();
        let mut answered = 0;
        while answered < total {
            while s.next_line().is_some() {
                assert!(s.in_flight_bytes() <= RX_BUFFER);
            }
            // Answer one or two at a time, as a board draining its buffer would.
            for _ in 0..1 + answered % 2 {
                if matches!(s.answer(Ok(()), t), Outcome::Accepted(_)) {
                    answered += 1;
                }
            }
        }
        assert!(s.all_accepted());
        assert_eq!(s.in_flight_bytes(), 0);
    }

    #[test]
    fn a_127_character_line_fits_alone_and_a_128_character_one_is_refused() {
        let mut s = Streamer::new(vec!["X".repeat(127), "Y".into()], StreamConfig::default()).unwrap();
        assert_eq!(drain(&mut s).len(), 1, "the 128-byte line fills the buffer");
        assert_eq!(
            Streamer::new(vec!["X".repeat(128)], StreamConfig::default()).unwrap_err(),
            TooLong { index: 0, bytes: 129 }
        );
        let cfg = StreamConfig { checksum: true, ..StreamConfig::default() };
        assert_eq!(Streamer::new(vec!["X".repeat(120)], cfg).unwrap_err().bytes, 3 + 120 + 5 + 1);
    }

    #[test]
    fn errors_name_the_line_they_answer() {
        let mut s = Streamer::new(lines(3, 10), StreamConfig::default()).unwrap();
        drain(&mut s);
        let t = Instant::now();
        assert_eq!(s.answer(Ok(()), t), Outcome::Accepted(0));
        assert_eq!(s.answer(Err(20), t), Outcome::Refused(1, 20));
        s.stop();
        assert_eq!(s.next_line(), None);
        assert_eq!(s.answer(Ok(()), t), Outcome::Accepted(2));
        assert_eq!(s.answer(Ok(()), t), Outcome::Unexpected);
    }

    #[test]
    fn checksum_lines_are_numbered_from_1() {
        let cfg = StreamConfig { checksum: true, ..StreamConfig::default() };
        let mut s = Streamer::new(vec!["G00 X20".into(), "M30".into()], cfg).unwrap();
        assert_eq!(s.next_line().unwrap(), format!("{}\n", crc::frame(1, "G00 X20")));
        assert!(s.next_line().unwrap().starts_with("N2 M30*"));
    }

    #[test]
    fn resend_waits_for_the_answers_in_flight_then_goes_on_from_the_line_asked() {
        let cfg = StreamConfig { checksum: true, ..StreamConfig::default() };
        let mut s = Streamer::new(lines(8, 16), cfg).unwrap();
        let t = Instant::now();
        assert_eq!(drain(&mut s).len(), 5, "five 25-byte framed lines");
        assert_eq!(s.answer(Ok(()), t), Outcome::Accepted(0));
        // Line 2 arrived damaged: the board asks for it and refuses the rest.
        assert!(s.resend_request(2, t));
        assert_eq!(s.answer(Err(88), t), Outcome::Superseded(1));
        assert_eq!(s.next_line(), None, "nothing is sent while answers are due");
        assert_eq!(s.tick(t), None);
        assert_eq!(s.answer(Err(88), t), Outcome::Superseded(2));
        assert_eq!(s.answer(Err(88), t), Outcome::Superseded(3));
        assert_eq!(s.tick(t), None);
        assert_eq!(s.answer(Err(88), t), Outcome::Superseded(4));
        assert_eq!(s.tick(t), Some(1));
        assert_eq!((s.sent(), s.accepted()), (1, 1));
        let again = drain(&mut s);
        assert!(again[0].starts_with("N2 "), "{again:?}");
        assert_eq!(again.len(), 5);
    }

    #[test]
    fn resend_after_a_tenth_of_a_second_of_silence_gives_up_lost_answers() {
        let cfg = StreamConfig { checksum: true, ..StreamConfig::default() };
        let mut s = Streamer::new(lines(6, 10), cfg).unwrap();
        let t = Instant::now();
        drain(&mut s);
        // Lines 1 and 2 merged on the wire: one answer for two lines, then nothing.
        assert!(s.resend_request(1, t));
        assert_eq!(s.answer(Err(88), t), Outcome::Superseded(0));
        for i in 2..5 {
            assert_eq!(s.answer(Err(88), t), Outcome::Superseded(i - 1));
        }
        assert_eq!(s.tick(t + Duration::from_millis(99)), None);
        assert_eq!(s.tick(t + Duration::from_millis(100)), Some(0));
        assert_eq!(s.in_flight_bytes(), 0);
        assert!(s.next_line().unwrap().starts_with("N1 "));
    }

    #[test]
    fn numbered_answers_account_for_answers_lost_before_them() {
        let cfg = StreamConfig { checksum: true, ..StreamConfig::default() };
        let mut s = Streamer::new(lines(8, 10), cfg).unwrap();
        let t = Instant::now();
        assert_eq!(drain(&mut s).len(), 6);
        // The answers to lines 1 and 2 were lost; line 3's came.
        assert_eq!(s.answer_line(3, Ok(()), t), Outcome::Accepted(2));
        assert_eq!(s.accepted(), 3);
        assert_eq!(s.in_flight_bytes(), 3 * 19);
        // A duplicate's answer changes nothing.
        assert_eq!(s.answer_line(2, Ok(()), t), Outcome::Superseded(1));
        assert_eq!(s.answer_line(4, Err(1), t), Outcome::Refused(3, 1));
        // Line 6's answer lost too: the status report says the board took it.
        s.taken_up_to(6);
        assert_eq!((s.accepted(), s.in_flight_bytes()), (6, 0));
        assert_eq!(drain(&mut s).len(), 2);
        // Both lost on the way to the board: go on from the first it has not taken.
        assert_eq!(s.lost_in_flight(6), 6);
        assert!(s.next_line().unwrap().starts_with("N7 "));
    }

    #[test]
    fn an_error_88_whose_resend_request_was_lost_resends_its_line() {
        let cfg = StreamConfig { checksum: true, ..StreamConfig::default() };
        let mut s = Streamer::new(lines(3, 10), cfg).unwrap();
        let t = Instant::now();
        assert_eq!(drain(&mut s).len(), 3);
        assert_eq!(s.answer_line(1, Ok(()), t), Outcome::Accepted(0));
        assert_eq!(s.answer_line(2, Ok(()), t), Outcome::Accepted(1));
        // Line 3 arrived damaged; `[MSG:Resend:3]` was damaged on the way back and
        // dropped, the plain `error:88` came through.
        assert_eq!(s.answer(Err(88), t), Outcome::Superseded(2));
        assert!(s.resending());
        assert!(!s.all_accepted());
        assert_eq!(s.tick(t), Some(2), "nothing left in flight: resend at once");
        assert!(s.next_line().unwrap().starts_with("N3 "));
        assert_eq!(s.answer_line(3, Ok(()), t), Outcome::Accepted(2));
        assert!(s.all_accepted());
    }

    #[test]
    fn a_resend_request_beyond_what_was_sent_is_ignored() {
        let cfg = StreamConfig { checksum: true, ..StreamConfig::default() };
        let mut s = Streamer::new(lines(6, 10), cfg).unwrap();
        let t = Instant::now();
        s.next_line();
        assert!(!s.resend_request(3, t));
        assert!(!s.resend_request(0, t));
        assert!(!s.resending());
    }
}

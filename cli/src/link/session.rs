//! One job on the board followed to its end: lines fed by a [`Feeder`] (the
//! counting streamer or the tape), a status report asked every 200 ms, keys
//! acted on, every board message shown, and a [`Verdict`] at the end.
//!
//! In tape mode nothing is asked before the opening `%` has gone out (a board that
//! heard a `?` since its reset takes `%` for the program's record mark).
//!
//! The job is done when every line was accepted (or the whole tape went out) and
//! the board is Idle with empty queues afterwards: once after `[MSG:Pgm End]`,
//! twice in a row without it. An `error:N` stops the job gently (feed hold, then
//! soft reset once held); an alarm stops it where the board stopped.

use std::time::{Duration, Instant};

use super::LinkError;
use super::keys::{Key, Keys};
use super::response::{self, Response, Status};
use super::stream::{Outcome, Streamer};
use super::tape::Tape;
use super::ui::Ui;
use super::wire::{ENQ, Incoming, Link};

/// What feeds the board.
#[derive(Debug)]
pub enum Feeder {
    /// grbl mode: character counting, `ok` per line.
    Counting(Streamer),
    /// FANUC tape mode: XON/XOFF, no answers per line.
    Tape(Tape),
}

/// How a job ended.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// Every line accepted and the board back to Idle (or at program end).
    Done,
    /// A line was refused: where (`file:line`), the error number, the message.
    Refused(String),
    /// The board raised an alarm: the report.
    Alarm(String),
    /// The user stopped it.
    Aborted(&'static str),
    /// The board restarted (welcome line) during the job.
    BoardReset,
}

impl Verdict {
    /// The exit status: 0 only for [`Verdict::Done`].
    pub fn exit_status(&self) -> u8 {
        if *self == Verdict::Done { 0 } else { 1 }
    }
}

/// Where the lines of a job come from, to name them in messages.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Origin {
    /// File name (or `O0012` for a program in memory).
    pub name: String,
    /// File line of each line sent (index = board line − 1); empty: board lines are file lines.
    pub file_lines: Vec<usize>,
    /// The command that started the job, when it is not program text (`$PR=12`): a
    /// refusal names it instead of a line.
    pub command: Option<String>,
}

impl Origin {
    /// `name:line` for board line `n` (1-based); just `name` when the line is not in the file.
    pub fn place(&self, n: u32) -> String {
        let line = if self.file_lines.is_empty() {
            Some(n as usize)
        } else {
            (n as usize).checked_sub(1).and_then(|i| self.file_lines.get(i).copied())
        };
        match line.filter(|&l| l > 0) {
            Some(l) => format!("{}:{l}", self.name),
            None => self.name.clone(),
        }
    }
}

/// Timing of a session.
#[derive(Clone, Copy, Debug)]
pub struct Timing {
    /// Status report period.
    pub poll: Duration,
    /// Nothing at all from the board for this long is a dead link.
    pub dead: Duration,
    /// How long a gentle stop waits for the hold before resetting.
    pub hold_wait: Duration,
    /// How long to wait for the welcome after a soft reset.
    pub welcome_wait: Duration,
    /// Time of one character on the wire (10 bits): the tape is never written faster,
    /// so that on a pty, as on a real line, an XOFF stops it within a few characters.
    pub char_time: Duration,
}

impl Timing {
    /// The default timing at `baud` (8N1: 10 bits a character).
    pub fn at_baud(baud: u32) -> Timing {
        Timing { char_time: Duration::from_secs(10) / baud.max(1), ..Timing::default() }
    }
}

impl Default for Timing {
    fn default() -> Self {
        Timing {
            poll: Duration::from_millis(200),
            dead: Duration::from_secs(5),
            hold_wait: Duration::from_secs(10),
            welcome_wait: Duration::from_secs(3),
            char_time: Duration::from_secs(10) / 115_200,
        }
    }
}

/// A job in progress.
pub struct Session<'a> {
    link: &'a mut Link,
    ui: &'a mut dyn Ui,
    keys: Option<&'a Keys>,
    feeder: Feeder,
    origin: Origin,
    timing: Timing,
    /// Free planner blocks and receive bytes of the idle board (its first status report).
    empty: Option<(u32, u32)>,
    last_msg: Option<String>,
    alarm_msg: Option<String>,
    pgm_end: bool,
    fed_at: Option<Instant>,
    /// When the wire is free for the next tape chunk.
    tape_free_at: Instant,
    polled_at: Instant,
    /// When ENQ was last sent.
    enquired_at: Instant,
    /// Queries (`?`, ENQ) sent since the board was last heard: with
    /// [`Timing::dead`] what makes a dead link (time alone is not: see `run_loop`).
    unanswered_queries: u32,
    heard_at: Instant,
    idle_reports: u32,
    last_progress: (usize, usize),
    /// When the board last answered a line (`ok`, `error`, a resend request).
    answered_at: Instant,
    /// When a line was last written.
    written_at: Instant,
    /// Times the lines in flight were found lost and sent again (checksums).
    resyncs: u32,
    /// A status report showed the board's receive buffer empty with lines in
    /// flight: when, and its `Lk:`.
    empty_seen: Option<(Instant, u32)>,
    /// Resend requests of the board (a request per damaged line, however many
    /// answers repeat it).
    resend_requests: u32,
}

/// How the link went during a job.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Lines of the job.
    pub lines: usize,
    /// From the start until every line was accepted.
    pub streamed: Option<Duration>,
    /// Resend requests of the board (checksums).
    pub resend_requests: u32,
    /// Lines in flight found lost from the status report and sent again.
    pub resyncs: u32,
    /// Lines of the board dropped as damaged.
    pub damaged: u64,
}

impl<'a> Session<'a> {
    /// A job feeding `feeder` over `link`; `empty` is the `Bf:` of the idle board
    /// (free planner blocks, free receive bytes), when known.
    pub fn new(
        link: &'a mut Link,
        ui: &'a mut dyn Ui,
        feeder: Feeder,
        origin: Origin,
        empty: Option<(u32, u32)>,
    ) -> Self {
        let now = Instant::now();
        Session {
            link,
            ui,
            keys: None,
            feeder,
            origin,
            timing: Timing::default(),
            empty,
            last_msg: None,
            alarm_msg: None,
            pgm_end: false,
            fed_at: None,
            tape_free_at: now,
            polled_at: now.checked_sub(Duration::from_secs(1)).unwrap_or(now),
            enquired_at: now,
            unanswered_queries: 0,
            heard_at: now,
            idle_reports: 0,
            last_progress: (usize::MAX, usize::MAX),
            answered_at: now,
            written_at: now,
            resyncs: 0,
            empty_seen: None,
            resend_requests: 0,
        }
    }

    /// Reads keys from `keys`.
    pub fn with_keys(mut self, keys: Option<&'a Keys>) -> Self {
        self.keys = keys;
        self
    }

    /// Uses `timing` instead of the defaults.
    pub fn with_timing(mut self, timing: Timing) -> Self {
        self.timing = timing;
        self
    }

    /// Runs the job to its verdict.
    pub fn run(self) -> Result<Verdict, LinkError> {
        self.run_stats().map(|(v, _)| v)
    }

    /// Runs the job to its verdict, with figures of how the link went.
    pub fn run_stats(mut self) -> Result<(Verdict, Stats), LinkError> {
        let started = Instant::now();
        let damaged = self.link.damaged();
        let verdict = self.run_loop();
        self.ui.finish();
        let stats = Stats {
            lines: match &self.feeder {
                Feeder::Counting(s) => s.total(),
                Feeder::Tape(t) => t.total(),
            },
            streamed: self.fed_at.map(|t| t.duration_since(started)),
            resend_requests: self.resend_requests,
            resyncs: self.resyncs,
            damaged: self.link.damaged() - damaged,
        };
        verdict.map(|v| (v, stats))
    }

    /// The loop: keys, status poll, feed, one incoming item, end checks.
    fn run_loop(&mut self) -> Result<Verdict, LinkError> {
        loop {
            if let Some(v) = self.keys_step()? {
                return Ok(v);
            }
            let now = Instant::now();
            if self.may_poll() && now.duration_since(self.polled_at) >= self.poll_period() {
                self.link.realtime(b'?')?;
                self.polled_at = now;
                self.unanswered_queries += 1;
            }
            if self.stalled(now) && now.duration_since(self.enquired_at) >= STALLED {
                self.link.realtime(ENQ)?;
                self.enquired_at = now;
                self.unanswered_queries += 1;
            }
            self.feed(now)?;
            let wait = self.idle_wait(now);
            if let Some(item) = self.link.poll(wait)? {
                self.heard_at = Instant::now();
                self.unanswered_queries = 0;
                if let Some(v) = self.incoming(item)? {
                    return Ok(v);
                }
            } else if self.link.heard() > self.heard_at {
                // A damaged line: the board talks.
                self.heard_at = self.link.heard();
                self.unanswered_queries = 0;
            } else if self.heard_at.elapsed() >= self.timing.dead && self.unanswered_queries >= DEAD_QUERIES {
                // Both: a host so loaded that this process (or the board's, on a
                // virtual board) did not run for seconds has not asked much in
                // that time, and queries still waiting in the port get answered.
                return Err(LinkError::Timeout {
                    port: self.link.name().to_owned(),
                    what: format!(
                        "any answer (the board stopped talking: nothing for {:.1} s, {} queries unanswered)",
                        self.heard_at.elapsed().as_secs_f64(),
                        self.unanswered_queries
                    ),
                });
            }
            if self.finished() {
                return Ok(Verdict::Done);
            }
        }
    }

    /// Acts on a key, if one was pressed.
    fn keys_step(&mut self) -> Result<Option<Verdict>, LinkError> {
        let Some(key) = self.keys.and_then(Keys::poll) else { return Ok(None) };
        match key {
            Key::Hold => {
                self.link.realtime(b'!')?;
                self.ui.note("feed hold");
            }
            Key::Resume => {
                self.link.realtime(b'~')?;
                self.ui.note("resume");
            }
            Key::Reset => {
                self.stop_feeding();
                self.reset()?;
                return Ok(Some(Verdict::Aborted("soft reset")));
            }
            Key::Quit => return self.stop_gently(Verdict::Aborted("aborted")).map(Some),
        }
        Ok(None)
    }

    /// How often to ask for a status report: [`Timing::poll`], or with checksums
    /// [`STALLED`] once every line is accepted (the end is an Idle report, which
    /// line noise may spoil).
    fn poll_period(&self) -> Duration {
        match &self.feeder {
            Feeder::Counting(s) if s.checksum() && self.fed_at.is_some() => STALLED,
            _ => self.timing.poll,
        }
    }

    /// With checksums: lines are in flight and the board has not answered for
    /// [`STALLED`] — an answer, or the lines, may have been lost. The session then
    /// asks ENQ every [`STALLED`]: its ~20-byte `[LK:…]` answer says where the
    /// board is and gets through line noise far more often than a status report
    /// (at 3 % per byte: 54 % against 3 %).
    fn stalled(&self, now: Instant) -> bool {
        matches!(&self.feeder, Feeder::Counting(s) if s.checksum() && s.waiting())
            && now.duration_since(self.answered_at) >= STALLED
    }

    /// Whether a status report may be asked: not before a tape's opening `%` (a `?`
    /// first would make the board take the `%` for a record mark).
    fn may_poll(&self) -> bool {
        match &self.feeder {
            Feeder::Counting(_) => true,
            Feeder::Tape(t) => t.opened(),
        }
    }

    /// How long to wait for the board before the loop turns again: until the wire is
    /// free when the tape has more to write, else 10 ms.
    fn idle_wait(&self, now: Instant) -> Duration {
        let slice = Duration::from_millis(10);
        match &self.feeder {
            Feeder::Tape(t) if t.next_chunk().is_some() => self.tape_free_at.saturating_duration_since(now).min(slice),
            _ => slice,
        }
    }

    /// Writes what the feeder allows, reports progress, notes when feeding is complete.
    fn feed(&mut self, now: Instant) -> Result<(), LinkError> {
        match &mut self.feeder {
            Feeder::Counting(s) => {
                if let Some(from) = s.tick(now) {
                    self.ui.note(&format!("resending from line {}", from + 1));
                }
                while let Some(line) = s.next_line() {
                    self.link.write(line.as_bytes())?;
                    self.written_at = now;
                }
            }
            Feeder::Tape(t) => {
                if let Some(chunk) = t.next_chunk()
                    && now >= self.tape_free_at
                    && self.link.queued_out() < TAPE_QUEUE
                {
                    let n = self.link.write_some(chunk)?;
                    t.wrote(n);
                    self.tape_free_at = now.max(self.tape_free_at) + self.timing.char_time * n as u32;
                }
            }
        }
        self.show_progress();
        if self.fed_at.is_none() && self.fed() {
            self.fed_at = Some(now);
        }
        Ok(())
    }

    /// Updates the progress display when the counts changed.
    fn show_progress(&mut self) {
        let (sent, accepted, total) = match &self.feeder {
            Feeder::Counting(s) => (s.sent(), s.accepted(), s.total()),
            Feeder::Tape(t) => (t.lines_sent(), t.lines_sent(), t.total()),
        };
        if (sent, accepted) != self.last_progress {
            self.last_progress = (sent, accepted);
            self.ui.progress(sent, accepted, total);
        }
    }

    /// Every line accepted, or the whole tape out.
    fn fed(&self) -> bool {
        match &self.feeder {
            Feeder::Counting(s) => s.all_accepted(),
            Feeder::Tape(t) => t.done(),
        }
    }

    /// Fed, and Idle with empty queues often enough since.
    fn finished(&self) -> bool {
        self.fed_at.is_some() && self.idle_reports >= if self.pgm_end { 1 } else { 2 }
    }

    /// Handles one thing from the board.
    fn incoming(&mut self, item: Incoming) -> Result<Option<Verdict>, LinkError> {
        match item {
            Incoming::Flow(b) => {
                if let Feeder::Tape(t) = &mut self.feeder {
                    t.flow(b);
                }
                Ok(None)
            }
            Incoming::Line(l) => self.response(response::parse(&l)),
        }
    }

    /// Handles one response line.
    fn response(&mut self, r: Response) -> Result<Option<Verdict>, LinkError> {
        match r {
            // With checksums the board numbers its answers to program lines; a bare
            // `ok` is not one of them.
            Response::Ok if self.link.checked() => Ok(None),
            Response::Ok => self.answer(Ok(())),
            Response::Error(code) => self.answer(Err(code)),
            Response::Answer(k, a) => self.answer_line(k, a),
            Response::Resend(n) => {
                self.answered_at = Instant::now();
                // Every line in flight after a damaged one is answered with the same
                // request: it is shown once.
                if let Feeder::Counting(s) = &mut self.feeder {
                    let pending = s.resending();
                    if s.resend_request(n, Instant::now()) && !pending {
                        self.resend_requests += 1;
                        self.ui.note(&format!("board asks to resend from line {n}"));
                    }
                }
                Ok(None)
            }
            Response::Msg(m) => {
                self.message(m);
                Ok(None)
            }
            Response::Alarm(code) => Ok(Some(self.alarm(code))),
            Response::Welcome(w) => {
                self.ui.note(&w);
                Ok(Some(Verdict::BoardReset))
            }
            Response::Status(s) => {
                self.status(&s);
                if s.state == "Alarm" {
                    // Its `ALARM:N` line was lost to line noise.
                    return Ok(Some(self.alarm(0)));
                }
                Ok(None)
            }
            Response::Link(last, free) => {
                self.board_at(last, Some(free));
                Ok(None)
            }
            Response::Feedback(t) | Response::Other(t) => {
                self.ui.note(&t);
                Ok(None)
            }
        }
    }

    /// A `[MSG:…]`: shown (a program alarm's is shown with its `ALARM:N`), remembered.
    fn message(&mut self, m: String) {
        if m == "Pgm End" {
            self.pgm_end = true;
        }
        if response::program_alarm(&m).is_some() {
            self.alarm_msg = Some(m.clone());
        } else {
            self.ui.note(&format!("[MSG:{m}]"));
            if let Some(tool) = m.strip_prefix("Load T") {
                // A machining centre's M06 by hand: the board waits, spindle
                // stopped, for cycle start.
                self.ui.note(&format!(
                    "tool change: put tool T{tool} in the spindle, then press c or ~ here (or the board's cycle start)"
                ));
            }
        }
        self.last_msg = Some(m);
    }

    /// `N<k> ok` or `N<k> error:N` (checksums).
    fn answer_line(&mut self, k: u32, a: Result<(), u16>) -> Result<Option<Verdict>, LinkError> {
        self.answered_at = Instant::now();
        let outcome = match &mut self.feeder {
            Feeder::Counting(s) => s.answer_line(k, a, Instant::now()),
            Feeder::Tape(_) => return Ok(None),
        };
        self.outcome(outcome)
    }

    /// `ok` or `error:N`.
    fn answer(&mut self, a: Result<(), u16>) -> Result<Option<Verdict>, LinkError> {
        self.answered_at = Instant::now();
        let outcome = match &mut self.feeder {
            Feeder::Counting(s) => s.answer(a, Instant::now()),
            Feeder::Tape(_) => match a {
                Ok(()) => return Ok(None),
                Err(code) => Outcome::Refused(usize::MAX, code),
            },
        };
        self.outcome(outcome)
    }

    /// What an answer meant, acted on.
    fn outcome(&mut self, outcome: Outcome) -> Result<Option<Verdict>, LinkError> {
        match outcome {
            Outcome::Refused(index, code) => {
                let line = index.checked_add(1).and_then(|n| u32::try_from(n).ok());
                let place = match (&self.origin.command, line) {
                    (Some(c), _) => c.clone(),
                    (None, Some(n)) => self.origin.place(n),
                    (None, None) => self.origin.name.clone(),
                };
                let message = self.last_msg.take().unwrap_or_else(|| response::error_text(code).to_owned());
                let text = format!("{place}: error:{code}: {message}");
                self.ui.note(&text);
                self.stop_gently(Verdict::Refused(text)).map(Some)
            }
            Outcome::Unexpected => {
                self.ui.note("board answered a line that was not sent");
                Ok(None)
            }
            Outcome::Accepted(_) | Outcome::Superseded(_) => Ok(None),
        }
    }

    /// `ALARM:N`, with the program alarm's `[MSG:…]` before it when there was one.
    fn alarm(&mut self, code: u16) -> Verdict {
        self.stop_feeding();
        let kind = match code {
            0 => "state Alarm (its ALARM line was lost on the way)".to_owned(),
            _ => format!("ALARM:{code} {}", response::alarm_text(code)),
        };
        let text = match self.alarm_msg.as_deref().and_then(response::program_alarm) {
            Some((number, line, message)) => format!("{}: alarm {number}: {message} ({kind})", self.origin.place(line)),
            None => format!("{}: {kind}", self.origin.name),
        };
        self.ui.note(&text);
        Verdict::Alarm(text)
    }

    /// A status report: shown; counted when Idle with empty queues after feeding;
    /// with checksums its `Lk:` and `Bf:` say where the board is ([`Session::board_at`]).
    fn status(&mut self, s: &Status) {
        self.ui.status(s);
        if let Some(last) = s.link {
            self.board_at(last, s.buffer.map(|(_, free)| free));
        }
        let asked_after_fed = self.fed_at.is_some_and(|t| self.polled_at > t);
        if asked_after_fed && s.idle_and_empty(self.empty) {
            self.idle_reports += 1;
        } else if s.state != "Idle" {
            self.idle_reports = 0;
        }
    }

    /// Where the board is (checksums: a status report's `Lk:` and `Bf:`, or the
    /// `[LK:last,free]` answer to ENQ): `last` is the last link line it took,
    /// `rx_free` its free receive-buffer bytes. Accounts for answers lost on the
    /// way; lines in flight that the board has not taken while its receive buffer
    /// is empty and nothing was answered for a while were lost on the way to it:
    /// they are sent again.
    fn board_at(&mut self, last: u32, rx_free: Option<u32>) {
        let Feeder::Counting(streamer) = &mut self.feeder else { return };
        streamer.taken_up_to(last);
        let now = Instant::now();
        let rx_empty = match (rx_free, self.empty) {
            (Some(free), Some((_, empty))) => free >= empty,
            (Some(free), None) => free >= super::stream::RX_BUFFER as u32,
            _ => false,
        };
        // Lines the board holds behind a full receive buffer do not show in one
        // report's `Bf:`: it takes two, far enough apart, with nothing answered.
        let quiet = self.timing.char_time * (2 * super::stream::RX_BUFFER as u32) + LOST_AFTER;
        let stalled = now.duration_since(self.answered_at) >= quiet && now.duration_since(self.written_at) >= quiet;
        if !(streamer.waiting() && rx_empty && stalled && !streamer.resending()) {
            self.empty_seen = None;
        } else {
            match self.empty_seen {
                Some((at, lk)) if lk == last && now.duration_since(at) >= LOST_AFTER && at > self.answered_at => {
                    let from = streamer.lost_in_flight(last as usize);
                    self.resyncs += 1;
                    self.ui.note(&format!("lines lost on the way: resending from line {}", from + 1));
                    self.answered_at = now;
                    self.empty_seen = None;
                }
                Some((_, lk)) if lk == last => {}
                _ => self.empty_seen = Some((now, last)),
            }
        }
    }

    /// Nothing more is written.
    fn stop_feeding(&mut self) {
        if let Feeder::Counting(s) = &mut self.feeder {
            s.stop();
        }
        if let Feeder::Tape(t) = &mut self.feeder {
            t.flow(super::tape::XOFF);
        }
    }

    /// Stops writing, holds the feed, waits until the board is held (or idle, or in
    /// alarm, or [`Timing::hold_wait`] passed), then soft-resets it; returns `verdict`.
    fn stop_gently(&mut self, verdict: Verdict) -> Result<Verdict, LinkError> {
        self.stop_feeding();
        self.link.realtime(b'!')?;
        let deadline = Instant::now() + self.timing.hold_wait;
        while Instant::now() < deadline {
            self.link.realtime(b'?')?;
            let wait = Instant::now() + self.timing.poll;
            while let Ok(r) = self.link.line_until(wait, "a status report") {
                if let Response::Status(s) = r
                    && matches!(s.state.as_str(), "Hold:0" | "Idle" | "Alarm")
                {
                    self.reset()?;
                    return Ok(verdict);
                }
            }
        }
        self.reset()?;
        Ok(verdict)
    }

    /// Soft reset and its welcome (a missing welcome is only noted).
    fn reset(&mut self) -> Result<(), LinkError> {
        self.ui.note("soft reset");
        match self.link.reset(self.timing.welcome_wait) {
            Ok(_) => Ok(()),
            Err(e @ LinkError::Timeout { .. }) => {
                self.ui.note(&e.to_string());
                Ok(())
            }
            Err(e) => Err(e),
        }
    }
}

/// With checksums: no answer for this long while lines are in flight makes the
/// session ask for a status report this often.
const STALLED: Duration = Duration::from_millis(50);

/// With checksums: lines in flight count as lost when the board's receive buffer is
/// empty and neither an answer came nor a line was written for this long (plus the
/// time 256 characters take on the wire).
const LOST_AFTER: Duration = Duration::from_millis(100);

/// With checksums: the board counts as stopped talking only when it sent nothing
/// for [`Timing::dead`] and at least this many queries (`?`, ENQ) went out meanwhile
/// without an answer.
const DEAD_QUERIES: u32 = 20;

/// Tape mode writes only while fewer bytes than this wait in the port's output queue,
/// so that an XOFF takes effect within a few characters.
const TAPE_QUEUE: u32 = 16;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn places_map_board_lines_to_file_lines() {
        let o = Origin { name: "p.nc".into(), file_lines: vec![2, 3, 5], command: None };
        assert_eq!(o.place(1), "p.nc:2");
        assert_eq!(o.place(3), "p.nc:5");
        assert_eq!(o.place(4), "p.nc");
        assert_eq!(o.place(0), "p.nc");
        let mem = Origin { name: "O0012".into(), file_lines: vec![], command: Some("$PR=12".into()) };
        assert_eq!(mem.place(7), "O0012:7");
    }
}

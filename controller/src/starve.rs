//! The stream starvation watch: a streamed program whose link went quiet mid-run
//! ends in alarm 4601 instead of standing open forever with the spindle turning.
//!
//! Both watches concern a *streamed program* only — a file a sender streams (see
//! [`Attendance`]), never lines a machinist types (MDI) — and a grbl line is
//! complete in itself and a sender owes the board nothing after its last line, so
//! "the job is open" needs evidence that more was coming:
//! - the job ran a block and has not reached M02/M30 (trailing `%`, blank or
//!   comment lines after an M30 open nothing), nor its tape's closing `%`;
//! - its text and motion ran out (the interpreter waits at the end of the window,
//!   nothing queued or moving, no hold, stop or look-ahead wait);
//! - the last byte of any kind — a line, a `?` status poll, a real-time byte —
//!   came *before* it ran out, and none since for `$304` seconds.
//!
//! A sender that finished stops after the job did: it polls `?` until it sees
//! Idle (`lathe send`, CNCjs, which polls as long as it is connected), so its last
//! byte comes after the run-out and nothing fires. A lost link silences the
//! sender while the board still runs what it had received.
//!
//! With the spindle turning, status polls do not keep a *streamed program* open: a
//! sender whose stream stopped (its character count stuck on an `ok` that line
//! noise ate) may go on polling `?` for ever. Then `$306` seconds without a program
//! line and without an operator's action end the job too (see [`Attendance`]).
//! Manual work — lines typed into a sender's console (`M03 S500`, a `G00` to a
//! position), jogging — is never ended by `$306` nor by `$304`, polls or not.

/// One second, ns.
const SECOND_NS: u64 = 1_000_000_000;

/// A job is a streamed program once this many of its program lines arrived within
/// [`STREAMED_WITHIN_NS`]: faster than anyone types.
pub(crate) const STREAMED_LINES: usize = 4;

/// See [`STREAMED_LINES`]: one second (a sender on a 2,400-baud line still sends
/// eight 30-byte lines a second; a person typing MDI lines sends one every few).
pub(crate) const STREAMED_WITHIN_NS: u64 = SECOND_NS;

/// Which watch ended a starved job.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Starved {
    /// `$304`: nothing at all came over the link.
    Quiet,
    /// `$306`: a streamed program with the spindle turning got no program line and
    /// no operator action (only status polls, or nothing).
    Unattended,
}

/// When the stream job ran out of text and motion.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct StarveWatch {
    starved_at: Option<u64>,
}

impl StarveWatch {
    /// Once per poll at `now`: `starved`, the open stream job has run out of text
    /// and motion; `quiet`: when the link was last heard from and `$304` (0 never);
    /// `unattended`: when the job was last fed or touched ([`Attendance::at`]) and
    /// `$306` (0 when it does not apply). The `$304` silence counts only when it began
    /// before the run-out (a sender that finished polls after it); the `$306` time
    /// counts from the last line or action, whenever it was.
    pub fn due(&mut self, now: u64, starved: bool, quiet: (u64, u32), unattended: (u64, u32)) -> Option<Starved> {
        if !starved {
            self.starved_at = None;
            return None;
        }
        let since = *self.starved_at.get_or_insert(now);
        let over = |last: u64, s: u32| s != 0 && now.saturating_sub(last) >= u64::from(s) * SECOND_NS;
        let which = if quiet.0 < since && over(quiet.0, quiet.1) {
            Starved::Quiet
        } else if over(unattended.0, unattended.1) {
            Starved::Unattended
        } else {
            return None;
        };
        self.starved_at = None;
        Some(which)
    }
}

/// Whether a stream job is a program that a sender streams — not lines a person
/// types — and when someone last fed or touched it: what `$306` watches.
///
/// A job is a streamed program when its lines are framed (link checksums: `lathe
/// send --checksum`), when it is a drip-fed tape, or once [`STREAMED_LINES`] of
/// its lines arrived within a second: a sender streaming a file sends its lines
/// back to back (the next on each `ok`, which comes as soon as a line is stored,
/// long before it has run), at any usual baud rate. A machinist typing MDI lines
/// into a sender's console never does, however long the manual work goes on, so
/// `M03 S500` and jogging is never ended by `$306` or `$304`. (A sender macro that
/// sends several lines at once counts as streamed.)
///
/// Attended: the last program line, jog line or real-time command other than `?`
/// (feed hold, cycle start, overrides, coolant toggles, from the link or the
/// panel's buttons): the operator is at the machine. Status polls and `$` queries
/// (`$G`, which some senders poll) are not.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Attendance {
    /// Arrival times of the job's last program lines, oldest first once full.
    recent: [u64; STREAMED_LINES - 1],
    /// Lines in `recent` (up to its length).
    seen: usize,
    /// The job's lines came as a sender streams a file.
    pub streamed: bool,
    /// The last program line, jog or real-time command other than `?`, ns.
    pub at: u64,
}

impl Attendance {
    /// A new job: nothing streamed, attended `now`.
    pub fn start(&mut self, now: u64) {
        *self = Attendance { at: now, ..Attendance::default() };
    }

    /// A program line of the job arrived at `now`.
    pub fn line(&mut self, now: u64) {
        self.at = now;
        if self.seen == self.recent.len() {
            let oldest = self.recent[0];
            self.streamed |= now.saturating_sub(oldest) <= STREAMED_WITHIN_NS;
            self.recent.rotate_left(1);
            if let Some(last) = self.recent.last_mut() {
                *last = now;
            }
        } else if let Some(slot) = self.recent.get_mut(self.seen) {
            *slot = now;
            self.seen += 1;
        }
    }

    /// The operator did something at `now` (jog, hold, resume, override …).
    pub fn action(&mut self, now: u64) {
        self.at = now;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: u64 = 1_000_000;

    #[test]
    fn four_lines_within_a_second_are_a_stream_typed_lines_are_not() {
        let mut a = Attendance::default();
        for t in [0, 2_000, 5_000, 6_500, 9_000, 9_900] {
            a.line(t * MS);
        }
        assert!(!a.streamed, "lines typed a second or more apart");
        a.line(10_300 * MS);
        assert!(!a.streamed, "four lines in 1.3 s");
        a.line(10_700 * MS);
        assert!(!a.streamed, "three in a second");
        a.line(10_800 * MS);
        assert!(a.streamed, "four within a second: 9.9, 10.3, 10.7, 10.8 s");
        a.start(20_000 * MS);
        assert!(!a.streamed);
        for i in 0..4 {
            a.line((20_000 + i * 30) * MS);
        }
        assert!(a.streamed, "a burst of four lines");
    }

    #[test]
    fn polls_do_not_start_the_unattended_time_again_actions_do() {
        let mut w = StarveWatch::default();
        let s = SECOND_NS;
        // Ran out at 2 s; the last line came at 1 s; polls go on (quiet stays recent).
        assert_eq!(w.due(2 * s, true, (2 * s, 10), (s, 30)), None);
        assert_eq!(w.due(30 * s, true, (30 * s, 10), (s, 30)), None);
        // An override at 20 s: 30 s from there.
        assert_eq!(w.due(31 * s, true, (31 * s, 10), (20 * s, 30)), None);
        assert_eq!(w.due(50 * s, true, (50 * s, 10), (20 * s, 30)), Some(Starved::Unattended));
        // Link silent since before the run-out: $304.
        let mut w = StarveWatch::default();
        assert_eq!(w.due(2 * s, true, (s, 10), (s, 0)), None);
        assert_eq!(w.due(11 * s, true, (s, 10), (s, 0)), Some(Starved::Quiet));
    }
}

//! The stream starvation watch: a streamed job whose link went quiet mid-run ends
//! in alarm 4601 instead of standing open forever with the spindle turning.
//!
//! A grbl line is complete in itself and a sender owes the board nothing after its
//! last line, so "the job is open" needs evidence that more was coming:
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

/// One second, ns.
const SECOND_NS: u64 = 1_000_000_000;

/// When the stream job ran out of text and motion.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct StarveWatch {
    starved_at: Option<u64>,
}

impl StarveWatch {
    /// Once per poll at `now`: `starved`, the open stream job has run out of text
    /// and motion; `last_byte`, when the last byte of any kind arrived; `timeout_s`,
    /// setting `$304` (0 off). True when the job is to end in alarm 4601: the link
    /// has been quiet since before it ran out for `timeout_s` seconds.
    pub fn due(&mut self, now: u64, starved: bool, last_byte: u64, timeout_s: u32) -> bool {
        if !starved {
            self.starved_at = None;
            return false;
        }
        let since = *self.starved_at.get_or_insert(now);
        let quiet = now.saturating_sub(last_byte);
        if timeout_s == 0 || last_byte >= since || quiet < u64::from(timeout_s) * SECOND_NS {
            return false;
        }
        self.starved_at = None;
        true
    }
}

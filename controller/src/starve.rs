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
//!
//! With the spindle turning, status polls do not keep the job open: a sender whose
//! stream stopped (its character count stuck on an `ok` that line noise ate) may
//! go on polling `?` for ever. Then `$306` seconds without a program line since
//! before the run-out end the job too.

/// One second, ns.
const SECOND_NS: u64 = 1_000_000_000;

/// When the stream job ran out of text and motion.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct StarveWatch {
    starved_at: Option<u64>,
}

impl StarveWatch {
    /// Once per poll at `now`: `starved`, the open stream job has run out of text
    /// and motion; `heard`, when the link was last heard from and how many seconds
    /// of silence since before the run-out end the job (0 never): the first whose
    /// time is up, if any.
    pub fn due(&mut self, now: u64, starved: bool, heard: [(u64, u32); 2]) -> Option<usize> {
        if !starved {
            self.starved_at = None;
            return None;
        }
        let since = *self.starved_at.get_or_insert(now);
        let up = |&(last, timeout_s): &(u64, u32)| {
            timeout_s != 0 && last < since && now.saturating_sub(last) >= u64::from(timeout_s) * SECOND_NS
        };
        let which = heard.iter().position(up)?;
        self.starved_at = None;
        Some(which)
    }
}

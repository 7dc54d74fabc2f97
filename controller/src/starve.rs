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

use interp_core::Alarm;
use interp_core::alarm::AlarmKind;

use crate::controller::{Controller, Job};
use crate::port::MotionPort;

/// One second, ns.
const SECOND_NS: u64 = 1_000_000_000;

impl<const W: usize, const T: usize, const P: usize, const S: usize> Controller<W, T, P, S> {
    /// Once per poll: notes when the stream job ran out of text and motion, and
    /// raises alarm 4601 when the link has been quiet since before that for `$304`
    /// seconds.
    pub(crate) fn watch_stream<M: MotionPort + ?Sized>(&mut self, port: &mut M) {
        if !self.starved(port) {
            self.starved_at = None;
            return;
        }
        let since = *self.starved_at.get_or_insert(self.now);
        let timeout_s = self.settings.starve_timeout_s;
        let quiet = self.now.saturating_sub(self.last_byte);
        if timeout_s == 0 || self.last_byte >= since || quiet < u64::from(timeout_s) * SECOND_NS {
            return;
        }
        self.starved_at = None;
        let line = self.interp.cursor().line;
        let alarm = Alarm::in_program(0, line, AlarmKind::StreamStarved { seconds: timeout_s });
        self.program_alarm(alarm, false, port);
    }

    /// An open stream job that has run out of text and motion.
    fn starved<M: MotionPort + ?Sized>(&self, port: &M) -> bool {
        let open = self.job == Job::Stream && self.job_worked && !self.record_closed && !self.interp_done;
        let waiting = self.alarm.is_none()
            && !self.check
            && !self.hold
            && !self.paused
            && !self.door
            && !self.sleep
            && self.lookahead.is_none();
        open && waiting && !self.interp.has_pending() && self.stream_drained() && port.status().idle
    }
}

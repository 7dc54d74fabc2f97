//! A machining centre's automatic tool change (M06 with `$312=1`, machine file
//! `tool_changer = "automatic"`): the motion core has stopped the axes and the
//! spindle at the M06; the board puts the tool number and the request on the tool
//! changer's outputs (`hal::ToolChangeRequest`) and waits for its "done" input.
//! Done drops the request and gives the motion core its cycle start (the spindle
//! starts again as it was, the program goes on); no done within `$313` seconds is
//! alarm 4511. The time is an argument: the wait is tested on the host.

/// An automatic tool change the board is waiting for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct ToolChangeWait {
    /// The tool requested.
    pub tool: u16,
    /// Program line of the M06.
    pub line: u32,
    /// When the request went out, ms (wrapping: a wait is far shorter than the
    /// 49 days a `u32` of ms spans).
    since_ms: u32,
    /// The done line was low at some moment since the request: a done still high
    /// from the last change (a changer that never drops it) is not this change's.
    armed: bool,
}

/// `now` (ns) in wrapping milliseconds.
fn ms(now: u64) -> u32 {
    (now / 1_000_000) as u32
}

/// What a look at the done line came to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum ToolChangeStep {
    /// Still changing.
    Waiting,
    /// The changer reported done.
    Done,
    /// No done within this many seconds.
    TimedOut { seconds: u16 },
}

impl ToolChangeWait {
    /// The request for `tool` (M06 on `line`) went out at `now`; `done` is the done
    /// line then.
    pub fn new(tool: u16, line: u32, now: u64, done: bool) -> Self {
        ToolChangeWait { tool, line, since_ms: ms(now), armed: !done }
    }

    /// At `now`, with the done line at `done`, the changer allowed `timeout_s`.
    pub fn step(&mut self, now: u64, done: bool, timeout_s: u16) -> ToolChangeStep {
        if done && self.armed {
            return ToolChangeStep::Done;
        }
        self.armed |= !done;
        if ms(now).wrapping_sub(self.since_ms) >= u32::from(timeout_s) * 1_000 {
            ToolChangeStep::TimedOut { seconds: timeout_s }
        } else {
            ToolChangeStep::Waiting
        }
    }
}

/// Room for the state: one with the mill profile, none without.
const SLOTS: usize = interp_core::MILL as usize;

/// The controller's automatic tool change: the wait in progress, and whether the
/// request is on the outputs. Zero bytes in a build without the mill profile (the
/// F446's), where every method is a constant.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct ToolChangeSlot([(Option<ToolChangeWait>, bool); SLOTS]);

impl ToolChangeSlot {
    /// No change, no request.
    pub const fn new() -> Self {
        ToolChangeSlot([(None, false); SLOTS])
    }

    /// Whether a change waits for the changer's done.
    pub fn waiting(&self) -> bool {
        self.0.iter().any(|s| s.0.is_some())
    }

    /// A change starts: `wait`, its request on the outputs.
    pub fn start(&mut self, wait: ToolChangeWait) {
        if let Some(s) = self.0.first_mut() {
            *s = (Some(wait), true);
        }
    }

    /// The change waiting, taken out (put it back if it still waits); the request
    /// stays marked as on the outputs.
    pub fn take(&mut self) -> Option<ToolChangeWait> {
        self.0.first_mut().and_then(|s| s.0.take())
    }

    /// Puts a change still waiting back.
    pub fn put_back(&mut self, wait: ToolChangeWait) {
        if let Some(s) = self.0.first_mut() {
            s.0 = Some(wait);
        }
    }

    /// Aborts the change (reset, alarm): its request drops at the next look.
    pub fn abort(&mut self) {
        if let Some(s) = self.0.first_mut() {
            s.0 = None;
        }
    }

    /// Whether the request was on the outputs (and now counts as dropped).
    pub fn take_request(&mut self) -> bool {
        self.0.first_mut().is_some_and(|s| core::mem::take(&mut s.1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const S: u64 = 1_000_000_000;

    #[test]
    fn done_within_the_time_ends_the_wait() {
        let mut w = ToolChangeWait::new(2, 7, 10 * S, false);
        assert_eq!(w.step(11 * S, false, 30), ToolChangeStep::Waiting);
        assert_eq!(w.step(39 * S, true, 30), ToolChangeStep::Done);
    }

    #[test]
    fn no_done_is_a_timeout_at_the_set_seconds() {
        let mut w = ToolChangeWait::new(2, 7, 10 * S, false);
        assert_eq!(w.step(40 * S - 1, false, 30), ToolChangeStep::Waiting);
        assert_eq!(w.step(40 * S, false, 30), ToolChangeStep::TimedOut { seconds: 30 });
    }

    #[test]
    fn a_done_left_high_counts_only_after_it_dropped() {
        let mut w = ToolChangeWait::new(5, 1, 0, true);
        assert_eq!(w.step(S, true, 30), ToolChangeStep::Waiting);
        assert_eq!(w.step(2 * S, false, 30), ToolChangeStep::Waiting);
        assert_eq!(w.step(3 * S, true, 30), ToolChangeStep::Done);
        let mut stuck = ToolChangeWait::new(5, 1, 0, true);
        assert_eq!(stuck.step(30 * S, true, 30), ToolChangeStep::TimedOut { seconds: 30 });
    }
}

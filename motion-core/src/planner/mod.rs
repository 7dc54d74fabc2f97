//! The motion planner: a fixed-capacity look-ahead queue holding prepared motion
//! blocks and the non-motion commands between them, in stream order.
//!
//! Each canonical action is prepared once when it arrives ([`block`]), its entry
//! speed is limited by the junction with the block before it, and the entry speeds
//! of the queue are re-planned backwards ([`lookahead`]) so that the last block
//! always ends at rest: whatever the interpreter has not delivered yet, the
//! machine can stop in time. A command (spindle, coolant, dwell, stop …) is a
//! barrier: the motion before it ends at rest and it runs when that motion has.

pub mod bend;
pub mod block;
pub mod lookahead;
pub mod machine;

pub use block::{ArcGeom, Block, BlockKind, Exec, FeedSpec, TapSpec, ThreadSpec};
pub use machine::{AxisLimits, AxisScale, MotionParams};

use crate::alarm::AlarmKind;
use crate::axis::{AXIS_COUNT, Axis, Pos};
use crate::canon::{Action, Canon, SpindleCommand, ThreadSync};
use crate::fixed::minf;
use block::{Dir, Prepared};

/// A non-motion action, run when the motion before it has finished.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Command {
    /// Spindle direction and speed.
    Spindle(SpindleCommand),
    /// Turret index and offset.
    Tool {
        /// Station.
        tool: u16,
        /// Offset number.
        offset: u16,
    },
    /// An M-code output.
    Aux {
        /// The M number.
        m: u16,
    },
    /// Dwell (0 = exact stop only).
    Dwell {
        /// Milliseconds.
        ms: u32,
    },
    /// M00/M01: wait for cycle start.
    Stop {
        /// M01.
        optional: bool,
    },
    /// M02/M30.
    End {
        /// M30.
        rewind: bool,
    },
    /// G51.2/G50.2: the C axis locked to the spindle at Q/P, or released.
    Polygon(Option<crate::canon::PolygonSync>),
    /// A machining centre's M06 (after the motion before it has finished).
    ToolChange(crate::canon::ToolChange),
}

/// One entry of the queue. Entries live inline in the fixed-capacity queue (no
/// allocation), so a command takes a block's room; commands are few.
#[derive(Clone, Copy, Debug, PartialEq)]
#[allow(clippy::large_enum_variant)]
pub enum Item {
    /// A motion block.
    Motion(Block),
    /// A command and its source line.
    Command {
        /// Source line.
        line: u32,
        /// The command.
        cmd: Command,
    },
}

impl Item {
    /// Source line.
    pub fn line(&self) -> u32 {
        match self {
            Item::Motion(b) => b.line,
            Item::Command { line, .. } => *line,
        }
    }
}

/// Why a push was refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PushError {
    /// The queue is full: offer the action again later.
    Full,
    /// The action is unusable; nothing was queued.
    Alarm(AlarmKind),
}

/// How the next block may join the queue's last motion.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Tail {
    /// Where the last motion ends (machine, nm) — `ends[cur]` — and where it
    /// started, `ends[cur ^ 1]` (the end before: a new end goes into the other
    /// slot, so the start stays known for one more block without a copy).
    ends: [Pos; 2],
    cur: usize,
    /// Direction at its end.
    dir: Dir,
    /// Its programmed speed.
    nominal: f32,
    /// Whether the next block may blend with it (G64 cutting move without exact stop).
    blend: bool,
    /// Its length, nm (the curvature of a chain of short blocks).
    len: f32,
    /// The long axis of a thread block (a continuing thread may follow).
    thread: Option<Axis>,
    /// The lead a thread sequence with a G34 in it ends with, nm/rev: a block
    /// continuing it starts there.
    thread_lead: Option<i64>,
}

/// The look-ahead queue; `N` blocks and commands.
#[derive(Clone, Debug)]
pub struct Planner<const N: usize> {
    queue: heapless::Deque<Item, N>,
    tail: Tail,
    /// Motion blocks taken out so far.
    taken: u64,
    /// How many entries at the queue's end are blended blocks of one acceleration
    /// (`run_accel_q8`): the interpolator's braking test for one boundary among them
    /// holds for all later ones.
    run: usize,
    run_accel_q8: u32,
    /// The chain at the queue's end: its curvature and waiting junctions.
    bend: bend::Bend,
}

impl Tail {
    /// Where the last motion ends.
    #[inline(always)]
    fn end(&self) -> &Pos {
        &self.ends[self.cur & 1]
    }

    /// Where the last motion started.
    #[inline(always)]
    fn start(&self) -> &Pos {
        &self.ends[(self.cur ^ 1) & 1]
    }
}

impl<const N: usize> Planner<N> {
    /// An empty queue with the axes at `pos` (machine, nm).
    pub fn new(pos: Pos) -> Self {
        Planner {
            queue: heapless::Deque::new(),
            tail: Self::rest(pos),
            taken: 0,
            run: 0,
            run_accel_q8: 0,
            bend: bend::Bend::default(),
        }
    }

    fn rest(end: Pos) -> Tail {
        Tail {
            ends: [end; 2],
            cur: 0,
            dir: [0.0; AXIS_COUNT],
            nominal: 0.0,
            blend: false,
            len: 0.0,
            thread: None,
            thread_lead: None,
        }
    }

    /// Drops everything queued; the next block starts from `pos`.
    pub fn clear(&mut self, pos: Pos) {
        self.queue.clear();
        self.tail = Self::rest(pos);
        self.run = 0;
        self.bend.clear();
    }

    /// Whether no more can be queued.
    pub fn is_full(&self) -> bool {
        self.queue.is_full()
    }

    /// Whether nothing is queued.
    pub fn is_empty(&self) -> bool {
        self.queue.is_empty()
    }

    /// Entries queued.
    pub fn len(&self) -> usize {
        self.queue.len()
    }

    /// Where the queued motion ends (machine, nm).
    pub fn tail_end(&self) -> Pos {
        *self.tail.end()
    }

    /// The next entry.
    pub fn front(&self) -> Option<&Item> {
        self.queue.front()
    }

    /// The entry after the next.
    pub fn second(&self) -> Option<&Item> {
        self.queue.get(1)
    }

    /// The entries in queue order.
    pub fn iter(&self) -> impl Iterator<Item = &Item> {
        self.queue.iter()
    }

    /// Takes the next entry.
    pub fn pop(&mut self) -> Option<Item> {
        let item = self.queue.pop_front();
        if let Some(Item::Motion(_)) = item {
            self.taken += 1;
        }
        item
    }

    /// Motion blocks taken out of the queue so far.
    pub fn taken(&self) -> u64 {
        self.taken
    }

    /// The blended run at the queue's end: the queue index from which every entry
    /// is a blended block of one acceleration, and that acceleration (Q8
    /// nm/period²). Its entry speeds chain exactly at that acceleration
    /// ([`lookahead`]).
    pub fn uniform_run(&self) -> (usize, u32) {
        (self.queue.len() - self.run.min(self.queue.len()), self.run_accel_q8)
    }

    /// Prepares `c` and queues it, re-planning the entry speeds.
    pub fn push(&mut self, c: &Canon, p: &MotionParams) -> Result<(), PushError> {
        if self.queue.is_full() {
            return Err(PushError::Full);
        }
        let full_circle = matches!(c.action, Action::Arc(a) if a.full_circle);
        if c.action.endpoint().is_some_and(|e| e.machine == *self.tail.end()) && !full_circle {
            return Ok(()); // no motion
        }
        if !matches!(
            c.action,
            Action::Rapid(_) | Action::Linear(_) | Action::Arc(_) | Action::Thread(_) | Action::Tap(_)
        ) {
            return self.push_command(c.line, &c.action);
        }
        // The block is prepared in its queue slot, held meanwhile by a small
        // placeholder and given up again if the block is refused.
        let placeholder = Item::Command { line: c.line, cmd: Command::Dwell { ms: 0 } };
        if self.queue.push_back(placeholder).is_err() {
            return Err(PushError::Full);
        }
        let Planner { queue, tail, .. } = self;
        let Some(slot) = queue.back_mut() else { return Err(PushError::Full) };
        let start = tail.end();
        let prepared = match &c.action {
            Action::Rapid(m) => block::line(start, m, true, p, c.line, slot),
            Action::Linear(m) => block::line(start, m, false, p, c.line, slot),
            Action::Arc(a) => block::arc(start, a, p, c.line, slot),
            Action::Thread(t) => {
                let mut t = *t;
                // A continuing thread needs a thread to continue (2.17.1 note 2).
                if tail.thread.is_none() {
                    t.sync = ThreadSync::Index;
                }
                block::thread(start, &t, tail.thread, tail.thread_lead, p, c.line, slot)
            }
            Action::Tap(t) => block::tap(start, t, p, c.line, slot),
            // Not reached: only motion gets here.
            _ => {
                queue.pop_back();
                return Ok(());
            }
        };
        match &prepared {
            Ok(prep) => {
                self.push_motion(prep, p);
                Ok(())
            }
            Err(e) => {
                self.queue.pop_back();
                Err(PushError::Alarm(*e))
            }
        }
    }

    fn push_command(&mut self, line: u32, a: &Action) -> Result<(), PushError> {
        let cmd = match *a {
            Action::Dwell { ms } => Command::Dwell { ms },
            Action::Spindle(s) => Command::Spindle(s),
            Action::Tool { tool, offset } => Command::Tool { tool, offset },
            Action::Aux { m } => Command::Aux { m },
            Action::Stop { optional } => Command::Stop { optional },
            Action::End { rewind } => Command::End { rewind },
            Action::Polygon(p) => Command::Polygon(p),
            Action::ToolChange(t) if canon::MILL => Command::ToolChange(t),
            _ => return Ok(()),
        };
        self.queue.push_back(Item::Command { line, cmd }).map_err(|_| PushError::Full)?;
        self.bend.clear();
        self.run = 0;
        self.tail.blend = false;
        self.tail.thread = None;
        self.tail.thread_lead = None;
        Ok(())
    }

    /// Plans the block just written into the queue's last slot, which ends at
    /// `prep.end`.
    fn push_motion(&mut self, prep: &Prepared, p: &MotionParams) {
        let Planner { queue, tail, bend, run, run_accel_q8, .. } = self;
        let Some(Item::Motion(b)) = queue.back_mut() else { return };
        let blends = matches!(b.kind, BlockKind::Line | BlockKind::Arc(_)) && b.feed != FeedSpec::Rapid;
        let len = prep.len;
        let joins = tail.blend && blends;
        // Dense: a block at the junction is shorter than two periods at its speed,
        // so a period may span two junctions; the chain's curvature then limits it
        // too (below). Elsewhere the junction's own limit is all.
        let mut dense = false;
        if joins {
            let v = lookahead::junction_speed(&tail.dir, &prep.dir_in, minf(tail.len, len), p);
            let pending = minf(minf(v, tail.nominal), minf(b.plan.nominal, b.plan.cap));
            b.plan.pending = pending;
            lookahead::set_floor(&mut b.plan, *run_accel_q8);
            dense = len < 2.0 * pending || tail.len < 2.0 * pending;
            if !dense {
                lookahead::set_max_entry(b, pending);
            }
        }
        // The run of one acceleration at the queue's end, counted through dense
        // junctions (where the interpolator's test needs it).
        *run = if dense && b.plan.accel_q8 == *run_accel_q8 { *run + 1 } else { 1 };
        *run_accel_q8 = b.plan.accel_q8;
        let nominal = b.plan.nominal;
        let blend = blends && !b.exact_stop;
        let (thread, thread_lead) = match b.kind {
            BlockKind::Thread(t) => (Some(t.long), (t.lead_delta != 0 || t.keep_lead).then_some(t.lead_end)),
            _ => (None, None),
        };
        // The chain's curvature: this junction's limit now, and earlier ones raised
        // as the path beyond them becomes known.
        if dense {
            let lim = bend::Limits {
                settle_len: p.settle_len,
                noise: p.input_noise,
                tol: p.chord_tolerance,
                a_n: p.accel_min * 0.5,
            };
            let curve = bend.push(tail.start(), tail.end(), &prep.end, len, &lim, |from_end, count, v| {
                raise(queue, from_end, count, v)
            });
            raise(queue, 1, 1, curve);
        } else {
            bend.restart(len);
        }
        let cur = (tail.cur ^ 1) & 1;
        tail.ends[cur] = prep.end;
        (tail.cur, tail.dir, tail.nominal, tail.blend, tail.len) = (cur, prep.dir_out, nominal, blend, len);
        (tail.thread, tail.thread_lead) = (thread, thread_lead);
        let (front, back) = self.queue.as_mut_slices();
        lookahead::backward_pass(front, back);
    }
}

/// Raises the highest entry of `count` queued blocks, starting `from_end` entries
/// before the queue's end, to the smaller of their junction's own limit and the
/// chain's curvature speed `curve` (nm/period), where that is higher than before.
fn raise<const N: usize>(queue: &mut heapless::Deque<Item, N>, from_end: usize, count: usize, curve: f32) {
    let len = queue.len();
    for i in len.saturating_sub(from_end)..(len + count).saturating_sub(from_end) {
        if let Some(Item::Motion(b)) = queue.get_mut(i) {
            let u = lookahead::max_u(&b.plan, minf(b.plan.pending, curve));
            if u > b.plan.max_u {
                b.plan.max_u = u;
                b.entry_at_max = false;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::canon::{Endpoint, Feed, FeedMode, Move, SpindleSpeed};
    use crate::config::MachineConfig;
    use canon::xorshift::XorShift;

    /// The entries of `queue` re-planned from rest at its end without stopping
    /// early (the pass as it would be without its early stops), from the
    /// definition: `u = min(u_max, (e' − a/2)² + 2aL)`, 0 below the junction's floor.
    fn full_replan(queue: &[Block]) -> std::vec::Vec<u64> {
        let mut exit_q8 = 0u64;
        let mut out = std::vec::Vec::new();
        for b in queue.iter().rev() {
            let h = b.plan.half_q8();
            let d = if exit_q8 == 0 { h } else { exit_q8.abs_diff(h) };
            let u = (d * d + b.plan.two_a_len).min(b.plan.max_u);
            let u = if u < b.plan.floor_u { 0 } else { u };
            exit_q8 = if u == 0 { 0 } else { h + canon::units::sqrt_u64(u).0 };
            out.push(u);
        }
        out.reverse();
        out
    }

    /// Random chains of short and long cutting moves (gentle and sharp corners):
    /// after every push each entry equals the full re-plan's, so stopping at an
    /// unchanged or junction-limited entry loses nothing.
    #[test]
    fn early_stops_equal_a_full_replan() {
        let p = MotionParams::new(&MachineConfig::default()).unwrap();
        let mut rng = XorShift::new(0x1234_5678_9abc_def1);
        let mut capped = 0;
        for _ in 0..40 {
            let mut planner: Planner<16> = Planner::new(Pos::ZERO);
            let mut at = (40_000_000i64, 0i64);
            for k in 0..15 {
                let len = [50_000, 400_000, 5_000_000][k % 3];
                at = (at.0 + rng.signed(len), at.1 - rng.signed(len).abs() - 1);
                let to = Pos::xz(at.0, at.1);
                let feed = Feed { mode: FeedMode::PerMin, value: 100_000 * (1 + rng.signed(40).abs()) * 1_000 };
                let spindle = SpindleSpeed { rpm: Some(1_000), css: None, max_rpm: 3_000 };
                let m = Move {
                    to: Endpoint { machine: to, work: to },
                    feed,
                    spindle,
                    exact_stop: false,
                    independent: false,
                };
                planner.push(&Canon { line: k as u32, action: Action::Linear(m) }, &p).unwrap();
                let blocks: std::vec::Vec<Block> = planner
                    .iter()
                    .filter_map(|i| match i {
                        Item::Motion(b) => Some(*b),
                        Item::Command { .. } => None,
                    })
                    .collect();
                let want = full_replan(&blocks);
                for (b, w) in blocks.iter().zip(&want) {
                    // Equal where the acceleration does not change from one block to
                    // the next (no root taken), within the root's rounding where it does.
                    let tol = 2 * canon::units::sqrt_u64(b.plan.entry_u).0 + 2;
                    assert!(b.plan.entry_u.abs_diff(*w) <= tol, "push {k}: {} vs {w}", b.plan.entry_u);
                    capped += usize::from(b.entry_at_max && b.plan.max_u > 0);
                }
            }
        }
        // Junction-limited entries were met (the early stop was exercised).
        assert!(capped > 100, "{capped}");
    }
}

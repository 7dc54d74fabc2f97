//! The contour look-ahead's data, held in the [`State`](super::State): the moves
//! held back for their corner (chamfer or corner R, 2.23) and for nose radius
//! compensation (2.18). The logic that fills and empties it is the contour layer
//! ([`crate::contour`]); the data lives here so the modal state (and the check
//! that reads it) sits below that layer.

use crate::alarm::AlarmKind;
use crate::axis::{Axis, Pos};
use crate::canon::{Action, Canon, Endpoint, Feed, FeedMode, Move, Plane, SpindleSpeed};

/// What `,C` or `,R` asks for at the end of a block's move (2.23).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Corner {
    /// `,C`: a straight chamfer from the point this far (nm, straight line) before
    /// the imaginary corner to the point this far after it.
    Chamfer(i64),
    /// `,R`: a corner arc of this radius (nm) tangent to both moves.
    Round(i64),
    /// SINUMERIK `CHF=`: a straight chamfer this long (nm), its ends equally far
    /// from the imaginary corner (`CHR=` gives that distance: [`Corner::Chamfer`]).
    ChamferLength(i64),
}

/// G41 or G42.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Side {
    /// G41: the tool left of the direction of travel.
    Left,
    /// G42: the tool right of it.
    Right,
}

/// The compensation's own state in the contour layer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Comp {
    /// G41/G42 in force (`None` = G40).
    pub side: Option<Side>,
    /// Nose radius (nm), taken when the offset starts up.
    pub radius: i64,
    /// Imaginary tip direction 0–9.
    pub tip: u8,
    /// The plane the offset works in.
    pub plane: Plane,
    /// Whether the tool is on the offset path; `false` before start-up and after a
    /// temporary cancel (the next move starts up again).
    pub engaged: bool,
    /// Nose-centre start (plane, nm) of the held move.
    pub centre: (i64, i64),
    /// The held move is the start-up move (it starts off the offset path: no
    /// interference check on it).
    pub starting: bool,
    /// After a temporary cancel the tool stands at `centre`, an offset point, not
    /// at the programmed point: a move along the plane's normal keeps it there.
    pub off_path: bool,
}

impl Default for Comp {
    fn default() -> Self {
        Comp {
            side: None,
            radius: 0,
            tip: 0,
            plane: Plane::Zx,
            engaged: false,
            centre: (0, 0),
            starting: false,
            off_path: false,
        }
    }
}

/// Most non-motion actions one stage holds behind its move (a G04 between a
/// chamfered block and its follower, M codes of blocks without motion …).
pub const HOLD: usize = 4;

/// A non-motion action waiting behind a held move, kept small (the state is
/// copied for every block).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
enum Aside {
    Dwell {
        ms: u32,
    },
    Spindle(crate::canon::SpindleCommand),
    Tool {
        tool: u16,
        offset: u16,
    },
    Aux {
        m: u16,
    },
    Stop {
        optional: bool,
    },
    End {
        rewind: bool,
    },
    Tolerance {
        nm: u32,
    },
    Polygon(Option<crate::canon::PolygonSync>),
    /// A move along the compensation plane's normal only (a mill's plunge or
    /// retract between compensated moves): made where the compensated path is
    /// when its turn comes, at the corner. Its machine coordinate on the normal,
    /// its feed with the [`PLUNGE_RAPID`]/[`PLUNGE_PER_REV`]/[`PLUNGE_EXACT`]
    /// flags in the top byte; the 64-bit values in halves, so the entry keeps the
    /// 4-byte alignment and the size of the others.
    Plunge {
        to: [u32; 2],
        feed: [u32; 2],
    },
}

/// An `i64` in two halves (see [`Aside::Plunge`]).
fn halves(v: i64) -> [u32; 2] {
    let u = v as u64;
    [u as u32, (u >> 32) as u32]
}

/// The `i64` of [`halves`].
fn whole(h: [u32; 2]) -> i64 {
    (u64::from(h[0]) | (u64::from(h[1]) << 32)) as i64
}

/// [`Aside::Plunge`] flag: a rapid.
const PLUNGE_RAPID: u8 = 1;
/// [`Aside::Plunge`] flag: feed per revolution.
const PLUNGE_PER_REV: u8 = 2;
/// [`Aside::Plunge`] flag: exact stop at its end.
const PLUNGE_EXACT: u8 = 4;
/// The bits of [`Aside::Plunge`]'s feed that hold the feed (nm/min or nm/rev, far
/// below 2^56).
const FEED_BITS: i64 = (1 << 56) - 1;

impl Aside {
    fn of(a: &Action) -> Option<Aside> {
        Some(match *a {
            Action::Dwell { ms } => Aside::Dwell { ms },
            Action::Spindle(s) => Aside::Spindle(s),
            Action::Tool { tool, offset } => Aside::Tool { tool, offset },
            Action::Aux { m } => Aside::Aux { m },
            Action::Stop { optional } => Aside::Stop { optional },
            Action::End { rewind } => Aside::End { rewind },
            Action::Tolerance { nm } => Aside::Tolerance { nm },
            Action::Polygon(p) => Aside::Polygon(p),
            _ => return None,
        })
    }

    /// The action; a plunge ends at `at` (where the compensated path is, machine and
    /// work) with its own coordinate on `normal`.
    fn action(self, at: &Endpoint, normal: Axis, spindle: SpindleSpeed) -> Action {
        match self {
            Aside::Dwell { ms } => Action::Dwell { ms },
            Aside::Spindle(s) => Action::Spindle(s),
            Aside::Tool { tool, offset } => Action::Tool { tool, offset },
            Aside::Aux { m } => Action::Aux { m },
            Aside::Stop { optional } => Action::Stop { optional },
            Aside::End { rewind } => Action::End { rewind },
            Aside::Tolerance { nm } => Action::Tolerance { nm },
            Aside::Polygon(p) => Action::Polygon(p),
            // Only a mill's compensation makes plunges (`contour::comp::plunge`):
            // without the profile the arm below is all that is compiled.
            Aside::Plunge { .. } if !crate::MILL => Action::Dwell { ms: 0 },
            Aside::Plunge { to, feed } => {
                let (to, packed) = (whole(to), whole(feed));
                let (feed, flags) = (packed & FEED_BITS, (packed >> 56) as u8);
                let mut ep = *at;
                let shift = ep.machine[normal] - ep.work[normal];
                ep.machine[normal] = to;
                ep.work[normal] = to - shift;
                let mode = if flags & PLUNGE_PER_REV != 0 { FeedMode::PerRev } else { FeedMode::PerMin };
                let m = Move {
                    to: ep,
                    feed: Feed { mode, value: feed },
                    spindle,
                    exact_stop: flags & PLUNGE_EXACT != 0,
                    independent: false,
                };
                if flags & PLUNGE_RAPID != 0 { Action::Rapid(m) } else { Action::Linear(m) }
            }
        }
    }

    /// A plunge of move `c` (a rapid or a line) along `normal`.
    fn plunge(c: &Canon, normal: Axis) -> Option<Aside> {
        let (m, rapid) = match c.action {
            Action::Rapid(m) => (m, true),
            Action::Linear(m) => (m, false),
            _ => return None,
        };
        let mut flags = if rapid { PLUNGE_RAPID } else { 0 };
        if m.feed.mode == FeedMode::PerRev {
            flags |= PLUNGE_PER_REV;
        }
        if m.exact_stop {
            flags |= PLUNGE_EXACT;
        }
        let feed = (m.feed.value & FEED_BITS) | (i64::from(flags) << 56);
        Some(Aside::Plunge { to: halves(m.to.machine[normal]), feed: halves(feed) })
    }
}

/// An action waiting behind a held move, with its line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct Waiting {
    line: u32,
    aside: Aside,
}

impl Waiting {
    /// The action, a plunge made at `at` (see [`Aside::action`]).
    pub(crate) fn canon(self, at: &Endpoint, normal: Axis, spindle: SpindleSpeed) -> Canon {
        Canon { line: self.line, action: self.aside.action(at, normal, spindle) }
    }

    /// The action of a waiting non-motion action (never a plunge: those wait only
    /// in the compensation's stage, which emits them with [`Waiting::canon`]).
    pub(crate) fn plain(self) -> Canon {
        let at = Endpoint { machine: Pos::ZERO, work: Pos::ZERO };
        let none = SpindleSpeed { rpm: None, css: None, max_rpm: 0 };
        self.canon(&at, Axis::Z, none)
    }
}

/// One stage's buffer: a held move, where it starts, and the actions after it.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Buffer {
    /// The held move.
    pub(crate) held: Option<Canon>,
    /// Machine position where the held move starts (as programmed).
    pub(crate) start: Pos,
    /// The actions after it (with their lines), in order.
    after: [Option<Waiting>; HOLD],
}

impl Default for Buffer {
    fn default() -> Self {
        Buffer { held: None, start: Pos::ZERO, after: [None; HOLD] }
    }
}

impl Buffer {
    /// Whether a move is held back.
    pub fn is_holding(&self) -> bool {
        self.held.is_some()
    }

    pub(crate) fn hold(&mut self, c: Canon, start: Pos) {
        *self = Buffer { held: Some(c), start, after: [None; HOLD] };
    }

    /// Appends a non-motion action behind the held move (alarm 4044 when full).
    pub(crate) fn push(&mut self, c: Canon) -> Result<(), AlarmKind> {
        let aside = Aside::of(&c.action).ok_or(AlarmKind::ContourBufferFull)?;
        self.wait(c.line, aside)
    }

    /// Appends move `c`, which moves along `normal` only, behind the held move
    /// (alarm 4044 when full); false if it is no rapid or line.
    pub(crate) fn push_plunge(&mut self, c: Canon, normal: Axis) -> Result<bool, AlarmKind> {
        let Some(aside) = Aside::plunge(&c, normal) else { return Ok(false) };
        self.wait(c.line, aside)?;
        Ok(true)
    }

    fn wait(&mut self, line: u32, aside: Aside) -> Result<(), AlarmKind> {
        let slot = self.after.iter_mut().find(|s| s.is_none()).ok_or(AlarmKind::ContourBufferFull)?;
        *slot = Some(Waiting { line, aside });
        Ok(())
    }

    /// Takes the held move and the actions after it, leaving the buffer empty.
    pub(crate) fn take(&mut self) -> (Option<Canon>, impl Iterator<Item = Waiting> + use<>) {
        let (held, after) = (self.held, self.after);
        *self = Buffer::default();
        (held, after.into_iter().flatten())
    }
}

/// The look-ahead of both stages.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Contour {
    /// Stage 1: the move waiting for its chamfer or corner R.
    pub(crate) shape: Buffer,
    /// The corner requested at the end of stage 1's held move.
    pub(crate) corner: Option<Corner>,
    /// Blocks without motion read since stage 1's held move (2.23 note 2 allows one G04).
    pub(crate) idle_blocks: u8,
    /// Stage 2: the move waiting for its compensated corner.
    pub(crate) offset: Buffer,
    /// Nose radius compensation in force.
    pub comp: Comp,
    /// Compensation suppressed: G71–G73 read their shape without it (2.16.7 note 5).
    pub no_comp: bool,
}

// Every field compares exactly (integers only).
impl Eq for Contour {}

impl Contour {
    /// Whether a move is held back in either stage.
    pub fn is_holding(&self) -> bool {
        self.shape.is_holding() || self.offset.is_holding()
    }

    /// The corner the held move waits for, if any.
    pub fn pending_corner(&self) -> Option<Corner> {
        self.corner
    }

    /// Drops everything held and cancels compensation (rewind, reset).
    pub fn clear(&mut self) {
        *self = Contour::default();
    }

    /// The small fields [`Contour::restore`] needs to undo a block. While a move
    /// is held, the caller keeps a copy of the whole look-ahead as well.
    pub fn marks(&self) -> Marks {
        Marks { corner: self.corner, idle_blocks: self.idle_blocks, comp: self.comp, no_comp: self.no_comp }
    }

    /// Puts the look-ahead back as it was when `marks` were taken: `held` is the
    /// copy taken then if a move was held; otherwise both buffers were empty.
    pub fn restore(&mut self, marks: &Marks, held: Option<&Contour>) {
        if let Some(c) = held {
            *self = *c;
            return;
        }
        if self.is_holding() {
            self.shape = Buffer::default();
            self.offset = Buffer::default();
        }
        self.corner = marks.corner;
        self.idle_blocks = marks.idle_blocks;
        self.comp = marks.comp;
        self.no_comp = marks.no_comp;
    }
}

/// The small fields of a [`Contour`], to undo a block (see [`Contour::marks`]).
#[derive(Clone, Copy, Debug)]
pub struct Marks {
    corner: Option<Corner>,
    idle_blocks: u8,
    comp: Comp,
    no_comp: bool,
}

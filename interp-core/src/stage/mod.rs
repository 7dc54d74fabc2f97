//! Staging: what a block does is held back until the whole block has succeeded.
//! Its actions wait in the [`Outbox`] ([`Staged`]); its changes to the modal
//! [`State`] are undone from a [`Saved`] copy when it fails. Below the layers that
//! execute blocks (`moves`, `contour`, `cycles`, `exec`), above `check`.

use crate::alarm::AlarmKind;
use crate::axis::Pos;
use crate::canon::{Action, Canon};
use crate::config::Param;
use crate::modal::{
    Contour, CycleMemory, FeedMemory, Frames, Marks, Mill, Modal, Polar, RigidTap, SpindleState, State, StrokeArea,
    ToolState,
};

/// Most actions one block produces.
pub const STAGE: usize = 16;

/// The queue a block's actions are staged in. The interpreter runs a block only
/// when its outbox is empty and empties it again if the block fails, so staged
/// actions reach the sink only when the whole block succeeded.
pub type Outbox = heapless::Deque<Canon, STAGE>;

/// Actions of the block being executed, staged in the (empty) outbox, and what a
/// cycle block hands to the interpreter (the cycle itself goes into the
/// interpreter's expansion slot, [`crate::cycles::CycleStage`]).
#[derive(Debug)]
pub struct Staged<'a> {
    line: u32,
    /// The staged actions, in order.
    pub actions: &'a mut Outbox,
    /// The program the block is in: G70–G73 read their ns–nf blocks from it.
    pub program: crate::lang::ProgramText<'a>,
    /// Index in `actions` where the cycle's moves belong: actions staged after it
    /// (M05, M30 …) are delivered after the cycle.
    pub split: Option<usize>,
    /// Settings the block writes into the machine configuration (G71 U(Δd) →
    /// parameter 5147, a mill's G10 offsets …), written only if it succeeds.
    pub writes: heapless::Vec<(Setting, i64), 8>,
    /// Where the program goes on after the block if not with the next block: after
    /// the nf block of G71–G73 (the shape's blocks are not executed).
    pub resume: Option<crate::program::Cursor>,
    /// Line of a held move that nose compensation found faulty (its offset runs
    /// against it, 3605) while the block ran: on the alarm the machine stops before
    /// that move instead of after it ([`crate::contour::stop_on_alarm`]).
    pub faulty_move: Option<u32>,
}

impl<'a> Staged<'a> {
    /// Stages the actions of the block on `line` in `outbox`.
    pub fn new(line: u32, outbox: &'a mut Outbox) -> Self {
        Staged {
            line,
            actions: outbox,
            program: crate::lang::ProgramText::NONE,
            split: None,
            writes: heapless::Vec::new(),
            resume: None,
            faulty_move: None,
        }
    }

    /// Stages one action.
    pub fn emit(&mut self, action: Action) -> Result<(), AlarmKind> {
        self.actions.push_back(Canon { line: self.line, action }).map_err(|_| AlarmKind::Overflow)
    }
}

/// A value of the machine configuration a block writes ([`Staged::writes`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Setting {
    /// A numbered parameter (internal units).
    Param(Param),
    /// One axis of a work offset (machine coordinates): frames 0–5 are G54–G59,
    /// 6–53 G54.1 P1–P48, [`Setting::EXTERNAL`] the external offset.
    WorkOffset {
        /// The frame.
        frame: u8,
        /// The axis.
        axis: crate::axis::Axis,
    },
    /// One column of a mill's offset pages (G10 L10–L13).
    Offset {
        /// The row (H/D number).
        row: u16,
        /// The column.
        page: crate::config::MillPage,
    },
}

impl Setting {
    /// [`Setting::WorkOffset`]'s frame number of the external work offset (G10 L2 P0).
    pub const EXTERNAL: u8 = u8::MAX;

    /// Writes `v` into `cfg`.
    pub fn apply(self, cfg: &mut crate::config::MachineConfig, v: i64) {
        match self {
            Setting::Param(p) => cfg.params.set(p, v),
            // The offsets are written only by a machining centre's G10.
            _ if !crate::MILL => {}
            Setting::WorkOffset { frame: Setting::EXTERNAL, axis } => cfg.external_offset[axis] = v,
            Setting::WorkOffset { frame, axis } => match cfg.work_offsets.get_mut(usize::from(frame)) {
                Some(p) => p[axis] = v,
                None => {
                    let p = frame.saturating_sub(5);
                    if let Some(mut pos) = cfg.extra_offsets.get(p) {
                        pos[axis] = v;
                        cfg.extra_offsets.set(p, pos);
                    }
                }
            },
            Setting::Offset { row, page } => {
                if let Some(r) = cfg.tools.get_mut(row) {
                    r.set_mill(page, v);
                }
            }
        }
    }
}

/// What the interpreter does after a block.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Flow {
    /// Go on with the next block.
    Continue,
    /// M00, or M01 with the optional-stop switch on: wait for cycle start.
    Stop,
    /// M02/M30.
    End,
    /// M98 (or an M or T code that calls): call subprogram `program` `repeats`
    /// times, after the block's other codes.
    Call {
        /// O number.
        program: u32,
        /// Repetitions.
        repeats: u16,
        /// M98 or a code.
        by: crate::command::CallBy,
    },
    /// M99: return to the caller (at sequence `seq`), or restart a main program.
    Return {
        /// Sequence number in the caller.
        seq: Option<u32>,
    },
    /// M91/M92 whose input condition held: go to sequence `seq`.
    Jump {
        /// Sequence number in this program.
        seq: u32,
    },
    /// G290/G291: read the following blocks in `Language`.
    Language(crate::config::Language),
}

/// A [`State`] as it was before a block (see [`State::save`]).
#[derive(Clone, Copy, Debug)]
pub struct Saved {
    modal: Modal,
    pos: Pos,
    feed: FeedMemory,
    spindle: SpindleState,
    moved: bool,
    cycle: Option<CycleMemory>,
    rare: Option<Rare>,
    contour: Marks,
}

/// Whether block `cmd` leaves the canned-cycle memory `cycle` as it is: a G00–G03
/// block (no group 00 code, no drilling code in the block or in force, no M29)
/// runs no cycle, and with no G90/G92/G94 values kept, no thread chained and no
/// rigid tapping pending, [`crate::cycles::before_block`] changes nothing either
/// (it clears exactly those). Debug builds check every undone block against a
/// whole copy of the state.
fn plain_for_cycles(cmd: &crate::command::Command, modal: &Modal, cycle: &CycleMemory) -> bool {
    use crate::codes::GCode;
    use crate::command::cycle::is_hole;
    let motion = cmd.g.motion.unwrap_or(modal.motion);
    matches!(motion, GCode::Rapid | GCode::Linear | GCode::ArcCw | GCode::ArcCcw)
        && cmd.g.one_shot.is_none()
        && cmd.g.drilling.is_none()
        && !is_hole(modal.drilling)
        && cycle.single.is_none()
        && !cycle.thread_chain
        && cycle.rigid == RigidTap::Off
        && !cmd.m.iter().any(|&(m, _)| m == 29)
}

/// The parts of a [`State`] few blocks change (see [`State::save`]).
#[derive(Clone, Copy, Debug)]
struct Rare {
    frames: Frames,
    tool: ToolState,
    polar: Option<Polar>,
    stroke: Option<StrokeArea>,
    mill: Mill,
}

impl State {
    /// What [`State::restore`] needs to undo block `cmd` executed in place:
    /// everything but the contour look-ahead's buffers, which the caller copies
    /// only while a move is held ([`Contour::is_holding`]),
    /// and the frames, tool, polar, stroke-check and machining-centre state, which
    /// only a block with G50/G52, T, G22/G23 or G12.1/G13.1 (or any block in polar
    /// mode) or one the mill's checker marks ([`crate::command::GSet::mill`]) changes.
    ///
    /// The canned-cycle memory (96 bytes) is saved only when the block can change
    /// it: see [`plain_for_cycles`].
    pub fn save(&self, cmd: &crate::command::Command) -> Saved {
        use crate::codes::GCode::{LocalFrame, SetCoordinates};
        // Destructured so that a new field cannot be forgotten here.
        let State {
            modal,
            pos,
            frames,
            tool,
            own_offsets: _,
            feed,
            spindle,
            moved,
            cycle,
            polar,
            stroke,
            contour,
            mill,
        } = self;
        // A machining centre's checker marks every block that may change its data.
        let rare = matches!(cmd.g.one_shot, Some(SetCoordinates | LocalFrame))
            || cmd.tool.is_some()
            || cmd.g.stroke.is_some()
            || cmd.g.polar.is_some()
            || cmd.g.mill
            || polar.is_some();
        let mut saved = Saved {
            modal: *modal,
            pos: *pos,
            feed: *feed,
            spindle: *spindle,
            moved: *moved,
            cycle: None,
            rare: None,
            contour: contour.marks(),
        };
        if rare || !plain_for_cycles(cmd, modal, cycle) {
            saved.cycle = Some(*cycle);
        }
        if rare {
            saved.rare = Some(Rare { frames: *frames, tool: *tool, polar: *polar, stroke: *stroke, mill: *mill });
        }
        saved
    }

    /// [`State::save`] of everything (a SINUMERIK cycle call, which may change
    /// what only few blocks change, such as its tool edge).
    pub fn save_all(&self) -> Saved {
        let State {
            modal,
            pos,
            frames,
            tool,
            own_offsets: _,
            feed,
            spindle,
            moved,
            cycle,
            polar,
            stroke,
            contour,
            mill,
        } = self;
        Saved {
            modal: *modal,
            pos: *pos,
            feed: *feed,
            spindle: *spindle,
            moved: *moved,
            cycle: Some(*cycle),
            rare: Some(Rare { frames: *frames, tool: *tool, polar: *polar, stroke: *stroke, mill: *mill }),
            contour: contour.marks(),
        }
    }

    /// Puts the state back as it was when `saved` was taken; `held` is the copy of
    /// the contour look-ahead taken then if it held a move.
    pub fn restore(&mut self, saved: &Saved, held: Option<&Contour>) {
        self.modal = saved.modal;
        self.pos = saved.pos;
        self.feed = saved.feed;
        self.spindle = saved.spindle;
        self.moved = saved.moved;
        if let Some(c) = &saved.cycle {
            self.cycle = *c;
        }
        if let Some(r) = &saved.rare {
            self.frames = r.frames;
            self.tool = r.tool;
            self.polar = r.polar;
            self.stroke = r.stroke;
            self.mill = r.mill;
            self.sum_own_offsets();
        }
        self.contour.restore(&saved.contour, held);
    }
}

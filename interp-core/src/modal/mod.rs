//! The interpreter's state: one field per modal group, the current position, the
//! coordinate frames, the tool, and the remembered feed and spindle values.
//! Below every layer that uses it: `check` reads a block against it, `stage` saves
//! and restores it around a block, the execution layers change it. It holds the
//! data of the layers above (polar mode, the stroke check area, the contour
//! look-ahead's buffers in [`lookahead`]); their logic stays with them.

pub mod lookahead;
pub mod mill;

pub use lookahead::{Buffer, Comp, Contour, Corner, HOLD, Marks, Side};
pub use mill::Mill;

use crate::axis::{Axis, Pos};
use crate::canon::{FeedMode, Plane, SpindleDir};
use crate::codes::GCode;
use crate::config::{MachineConfig, MachineKind, Param};
use crate::units::{NM_PER_MM, Units};

/// One field per modal group (table 1.1), with the power-on states of the notes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Modal {
    /// Group 01: G00 or G01 at power-on (parameter 5153), G02/G03, later the cycles.
    pub motion: GCode,
    /// Group 16: G18 at power-on on a lathe (2.13 note 3), G17 on a machining centre.
    pub plane: Plane,
    /// Group 06: G21 unless parameter 10 says inch (2.9 note 1).
    pub units: Units,
    /// Group 03 (systems B/C): G91 incremental X/Z.
    pub incremental: bool,
    /// Group 05: G98 or G99 at power-on (parameter 5154).
    pub feed_mode: FeedMode,
    /// Group 02: G96 on; G97 at power-on (2.19 note 1).
    pub css: bool,
    /// Group 07: G40 at power-on.
    pub nose_comp: GCode,
    /// Group 14: G54 (frame 0) at power-on (2.12.2 note 1): G54–G59 are 0–5. A
    /// machining centre's G54.1 P1–P48 leave it at 0 and set `extra_frame`.
    pub work_frame: u8,
    /// G54.1 P1–P48 in force (0 = none): its offset, less G54's, is in
    /// [`Frames::extra`] (the work frame of every move stays one array index).
    pub extra_frame: u8,
    /// Group 15: G61 exact-stop mode; G64 at power-on (2.14).
    pub exact_stop_mode: bool,
    /// Group 10: drilling cycle in force; G80 at power-on.
    pub drilling: GCode,
    /// Group 11 (systems B/C): G99 return to R level; G98 at power-on.
    pub return_to_r: bool,
    /// Polygon turning in force (G51.2, 2.8): its ratio; `None` = G50.2.
    pub polygon: Option<crate::canon::PolygonSync>,
    /// X values are diameters: the machine's `diameter_x` at power-on. SINUMERIK
    /// DIAMON/DIAMOF switch it (group 29); the SINUMERIK cycles read their
    /// plane-axis parameters (SPD, DM1 …) and MID (`_ZSD[0]` = 0) by it.
    pub diameter: bool,
}

/// Shifts that together with the work offsets make up the work frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Frames {
    /// Shift set by G50 X/Z: moves all six work frames alike (2.12.2 note 4).
    pub shift: Pos,
    /// G52 local frame origin in work coordinates (2.12.3).
    pub local: Pos,
    /// G54.1 P in force: its offset minus G54's ([`Modal::extra_frame`]), kept with
    /// the state's own offsets so every move reads one work offset.
    pub extra: Pos,
}

/// The tool in the turret position and the offset in force.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ToolState {
    /// Turret station.
    pub tool: u16,
    /// Offset number (0 = none).
    pub offset_number: u16,
    /// Geometry + wear shift of the offset in force (X radius).
    pub offset: Pos,
    /// Nose radius of the offset in force, for compensation.
    pub nose_radius: i64,
    /// Imaginary tip direction of the offset in force.
    pub tip: u8,
}

/// Spindle memory (2.19).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SpindleState {
    /// Direction commanded by M03/M04/M05.
    pub dir: SpindleDir,
    /// S of G97 in rev/min.
    pub rpm: u32,
    /// S of G96 as a surface speed in mm/min; kept while in G97 (note 2).
    pub css: Option<u32>,
    /// G50 S clamp in rev/min; `None` = no clamp given since power-on.
    pub clamp: Option<u32>,
    /// Gear selected by M41–M44 (0 = none).
    pub gear: u8,
}

/// Feed memory: G98 and G99 remember their own F (2.20 note 4).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FeedMemory {
    /// Last F of G98, nm/min.
    pub per_min: i64,
    /// Last F of G99, nm/rev.
    pub per_rev: i64,
}

impl FeedMemory {
    /// The F in force for `mode`.
    pub fn get(&self, mode: FeedMode) -> i64 {
        match mode {
            FeedMode::PerMin => self.per_min,
            FeedMode::PerRev => self.per_rev,
        }
    }

    /// Sets the F of `mode`.
    pub fn set(&mut self, mode: FeedMode, v: i64) {
        match mode {
            FeedMode::PerMin => self.per_min = v,
            FeedMode::PerRev => self.per_rev = v,
        }
    }
}

/// X/Z end point and taper R of a G90/G92/G94 cycle, kept for the following blocks
/// of the same cycle until another code clears them (2.15 note 2). Work
/// coordinates, X as a radius.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SingleMemory {
    /// End point X (radius).
    pub x: i64,
    /// End point Z.
    pub z: i64,
    /// Taper R (radius for G90/G92, Z for G94).
    pub r: i64,
}

/// Hole data of G83–G89 kept until G80 (2.21.3).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct HoleMemory {
    /// Hole bottom along the drilling axis (work, absolute); `None` until given.
    pub bottom: Option<i64>,
    /// Signed distance initial level → R level (radius value); on a machining
    /// centre the R level itself (programmed coordinates).
    pub r: i64,
    /// Peck depth Q (0 = no pecking); a machining centre's G76/G87 shift.
    pub q: i64,
    /// Dwell at the bottom, ms.
    pub dwell_ms: u32,
    /// A machining centre's R has been given in the mode (a hole needs it).
    pub r_set: bool,
}

/// Rigid tapping mode (2.22.1).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum RigidTap {
    /// Not selected: G84/G88 tap floating.
    #[default]
    Off,
    /// M29 S given; the next G84/G88 taps rigidly.
    Pending {
        /// S of the M29 block.
        rpm: u32,
        /// Spindle direction before M29, restored after each hole.
        before: SpindleDir,
    },
    /// A rigid G84/G88 is in force until G80.
    Active {
        /// S of the M29 block.
        rpm: u32,
        /// Spindle direction before M29.
        before: SpindleDir,
    },
}

/// What the canned cycles remember from one block to the next.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct CycleMemory {
    /// Retained X/Z/R of G90/G92/G94 (2.15 note 2).
    pub single: Option<SingleMemory>,
    /// Thread lead in force for G32/G34/G92/G76, nm per revolution (2.17.1: F is kept).
    pub lead: i64,
    /// The last block was a thread block: the next thread block continues without
    /// waiting for the spindle index (2.17.1 note 2).
    pub thread_chain: bool,
    /// Drilling and tapping data (G83–G89).
    pub hole: HoleMemory,
    /// Rigid tapping (M29).
    pub rigid: RigidTap,
    /// Direction floating tapping turns the spindle into the hole (2.22.3 note 2).
    pub tap_dir: SpindleDir,
    /// SINUMERIK cycle setting data `_ZSD[0..7]` (GUD7, seed 001 lines 3522-3536,
    /// 10139-10161): [0] CYCLE95 MID radius/diameter, [4] CYCLE93 retract after
    /// the first groove, [5] CYCLE88 M5/M0, [6] CYCLE93 offsets under mirroring.
    /// All 0 by default; the SINUMERIK front end writes them.
    pub zsd: [i16; 8],
    /// Thread re-cutting (SINUMERIK 4.9): where the tool was synchronised in an
    /// existing thread; CYCLE97/CYCLE98 start their thread so that it runs through it.
    pub recut: Option<ThreadRecut>,
}

/// A synchronisation point for thread re-cutting (seed 001 4.9, lines 11439–11509):
/// with the threading tool set into the existing thread, the work Z and the spindle
/// angle after the index there. The cycles add the angle that makes the thread
/// they cut run through this point to the start offset NSP.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ThreadRecut {
    /// Work Z of the synchronisation point, nm.
    pub z: i64,
    /// Spindle angle after the index at that point, µdeg (0–360°).
    pub angle_udeg: i64,
}

impl Default for CycleMemory {
    fn default() -> Self {
        CycleMemory {
            single: None,
            lead: 0,
            thread_chain: false,
            hole: HoleMemory::default(),
            rigid: RigidTap::Off,
            tap_dir: SpindleDir::Stop,
            zsd: [0; 8],
            recut: None,
        }
    }
}

/// Polar interpolation in force (G12.1, [`crate::moves::polar`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Polar {
    /// The plane before G12.1, restored by G13.1 (note 2).
    pub plane: Plane,
    /// The programmed point in the polar plane: x (radius, nm), c (nm), work Z.
    pub x: i64,
    /// Second coordinate of the polar plane, nm.
    pub c: i64,
    /// Z (work), nm.
    pub z: i64,
}

impl Polar {
    /// The programmed point as a virtual position (X, Y = c, Z).
    pub fn virtual_pos(&self) -> Pos {
        Pos([self.x, self.c, self.z, 0])
    }
}

/// The area of stored stroke check 2 in force (G22, [`crate::moves::stroke`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct StrokeArea {
    /// Minus corner (I, J, K), machine coordinates, X as a radius.
    pub lo: Pos,
    /// Plus corner (X, Y, Z).
    pub hi: Pos,
    /// True: the outside of the box is forbidden (parameter 1002 = 1).
    pub outside: bool,
}

/// Everything that persists from one block to the next.
///
/// In declaration order (`repr(C)`): the fields every block reads first, the large
/// ones last, so the hot ones stay within the Cortex-M4's short load offsets
/// (LDRD reaches 1,020 bytes) whatever the large ones grow to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(C)]
pub struct State {
    /// Modal groups.
    pub modal: Modal,
    /// Machine position of the axes at the end of the last block.
    pub pos: Pos,
    /// G50 shift and G52 local frame.
    pub frames: Frames,
    /// Tool and offset.
    pub tool: ToolState,
    /// `frames.shift + frames.local + tool.offset`: the part of
    /// [`State::work_to_machine`] the state owns, summed when one of them changes
    /// ([`State::sum_own_offsets`]) instead of in every move.
    pub own_offsets: Pos,
    /// Remembered F values.
    pub feed: FeedMemory,
    /// Spindle memory.
    pub spindle: SpindleState,
    /// Whether any axis has moved since the program started (G20/G21 rule, 2.9 note 2).
    pub moved: bool,
    /// Canned cycle memory.
    pub cycle: CycleMemory,
    /// Polar coordinate interpolation (G12.1) in force.
    pub polar: Option<Polar>,
    /// Stored stroke check 2 (G22) in force; `None` under G23.
    pub stroke: Option<StrokeArea>,
    /// The contour look-ahead: a move held back until the next one is known.
    pub contour: Contour,
    /// A machining centre's modal data (tool length, H/D, G28 point, hole-cycle
    /// initial level, transformations); unused on a lathe.
    pub mill: Mill,
}

impl State {
    /// The power-on state for machine `cfg` with the axes at machine position `pos`.
    #[inline(never)]
    pub fn power_on(cfg: &MachineConfig, pos: Pos) -> Self {
        let p = &cfg.params;
        let f0 = p.get(Param::InitialFeed);
        State {
            modal: Modal {
                motion: if p.flag(Param::InitialLinear) { GCode::Linear } else { GCode::Rapid },
                plane: if cfg.kind == MachineKind::Mill { Plane::Xy } else { Plane::Zx },
                units: if p.flag(Param::InchAtPowerOn) { Units::Inch } else { Units::Metric },
                incremental: false,
                feed_mode: if p.flag(Param::InitialPerRev) { FeedMode::PerRev } else { FeedMode::PerMin },
                css: false,
                nose_comp: GCode::NoseCompOff,
                work_frame: 0,
                extra_frame: 0,
                exact_stop_mode: false,
                drilling: GCode::DrillCancel,
                return_to_r: false,
                polygon: None,
                diameter: cfg.diameter_x,
            },
            pos,
            frames: Frames::default(),
            tool: ToolState::default(),
            own_offsets: Pos::ZERO,
            feed: FeedMemory { per_min: f0 * NM_PER_MM, per_rev: f0 * NM_PER_MM },
            spindle: SpindleState { dir: SpindleDir::Stop, rpm: 0, css: None, clamp: None, gear: 0 },
            moved: false,
            cycle: CycleMemory::default(),
            polar: None,
            stroke: None,
            contour: Contour::default(),
            mill: Mill::default(),
        }
    }

    /// Sums [`State::own_offsets`] again; called wherever the G50 shift, the G52
    /// frame, the G54.1 frame or the tool offset change.
    pub fn sum_own_offsets(&mut self) {
        self.own_offsets = self.frames.shift + self.frames.local + self.frames.extra + self.tool.offset;
    }

    /// [`Frames::extra`] of the G54.1 frame in force from `cfg` (after the frame or
    /// the offsets changed: G54.1, G10, a rewind).
    pub fn refresh_extra_frame(&mut self, cfg: &MachineConfig) {
        let extra = match self.modal.extra_frame {
            0 => Pos::ZERO,
            p => cfg.extra_offsets.get(p).unwrap_or(Pos::ZERO) - cfg.work_offsets[0],
        };
        if extra != self.frames.extra {
            self.frames.extra = extra;
            self.sum_own_offsets();
        }
    }

    /// What is added to a work position to get the machine position of the axes:
    /// work offset of G54–G59 + external offset + G50 shift + G52 local origin +
    /// (G54.1's offset − G54's) + tool offset.
    #[inline]
    pub fn work_to_machine(&self, cfg: &MachineConfig) -> Pos {
        // Tests (debug builds) check the kept sum at every use.
        debug_assert_eq!(
            self.own_offsets,
            self.frames.shift + self.frames.local + self.frames.extra + self.tool.offset,
            "own offsets not summed again after a change"
        );
        cfg.work_offsets[usize::from(self.modal.work_frame)] + cfg.external_offset + self.own_offsets
    }

    /// The current position in work coordinates.
    pub fn work_pos(&self, cfg: &MachineConfig) -> Pos {
        self.pos - self.work_to_machine(cfg)
    }

    /// Current work coordinate of one axis.
    pub fn work_axis(&self, cfg: &MachineConfig, a: Axis) -> i64 {
        self.work_pos(cfg)[a]
    }
}

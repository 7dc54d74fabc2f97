//! The vocabulary the lathe interpreter and the motion core share, and nothing else:
//! the canonical machining actions (this module), the axes and positions
//! ([`axis`]), the alarms ([`alarm`]), the machine description ([`config`]) and the
//! internal units ([`units`]). `no_std`, no allocation, no unsafe code; it depends
//! on no other crate of the workspace, and both `interp-core` (the language) and
//! `motion-core` (planner to step events) depend on it.
//!
//! # The canonical machining actions: the only way the interpreter affects the world
//!
//! The interpreter turns blocks into a stream of [`Canon`] actions and offers them
//! to a [`CanonSink`]. A recording sink makes golden tests trivial, the motion
//! planner is another sink, `lathe sim` prints them. Every position is given twice:
//! in machine coordinates (what the axes must do, tool offset included) and in work
//! coordinates (what the program said), so no consumer has to track frames.

#![no_std]
#![forbid(unsafe_code)]

#[cfg(test)]
extern crate std;

/// Whether this build carries the FANUC 0i-M machining-centre profile (feature
/// `mill`, set by interp-core's): without it no helical arc and no M06 reach the
/// motion core, which then leaves their code out (`interp_core::MILL` is this).
pub const MILL: bool = cfg!(feature = "mill");

pub mod alarm;
pub mod axis;
pub mod config;
pub mod text;
pub mod units;
pub mod xorshift;

mod record;

pub use record::RecordingSink;

pub use alarm::{Alarm, AlarmKind};
pub use axis::{Axis, Pos};
pub use config::MachineConfig;

/// One canonical action and the program line that produced it.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Canon {
    /// 1-based source line of the block (for cycles: of the cycle block).
    pub line: u32,
    /// What to do.
    pub action: Action,
}

/// A canonical machining action.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Action {
    /// Positioning at rapid rate.
    Rapid(Move),
    /// Straight cutting move at the commanded feed.
    Linear(Move),
    /// Circular cutting move.
    Arc(ArcMove),
    /// Spindle-synchronised thread move (G32/G34/G92/G76).
    Thread(ThreadMove),
    /// Rigid-tapping move locked to the spindle (M29 G84/G88).
    Tap(TapMove),
    /// Dwell in milliseconds; 0 is an exact stop between blocks (G04 note 1).
    Dwell {
        /// Duration.
        ms: u32,
    },
    /// Spindle direction and speed change.
    Spindle(SpindleCommand),
    /// Tool change: turret station and offset number (0 = offset cancelled).
    Tool {
        /// Turret station.
        tool: u16,
        /// Offset number now in effect.
        offset: u16,
    },
    /// A machine output switched by an M code (coolant, chuck, tailstock, gears …).
    Aux {
        /// The M number.
        m: u16,
    },
    /// Program stop (M00) or optional stop (M01 with the switch on): wait for cycle start.
    Stop {
        /// True for M01.
        optional: bool,
    },
    /// End of program (M02, M30): spindle, coolant and feed stop.
    End {
        /// True for M30 (rewind).
        rewind: bool,
    },
    /// Tool change of a machining centre (M06 after T, seed 004 @813): the tool T
    /// selected goes into the spindle — by the tool changer, or by the operator
    /// after a stop ("load T02", cycle start to go on), as the machine file says.
    ToolChange(ToolChange),
    /// Polygon turning (G51.2/G50.2, 2.8): from the next spindle index on, the C
    /// axis (the tool spindle) turns Q/P revolutions per work-spindle revolution,
    /// locked to the encoder; `None` (G50.2) ends it once C is a whole number of
    /// revolutions from where it locked.
    Polygon(Option<PolygonSync>),
    /// The path tolerance (SINUMERIK CYCLE832 `_TOL`) the motion core plans with
    /// from the next block on: it is the junction deviation of G64 corners and
    /// the chord tolerance of corners and arcs ([`config::MotionConfig`]). 0
    /// puts the machine's own back, as M02/M30 and reset do.
    Tolerance {
        /// The tolerance, nm (0: the machine's).
        nm: u32,
    },
}

/// A machining centre's tool change (M06): what the board needs to drive a tool
/// changer or to stop for a change by hand.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ToolChange {
    /// The tool to put in the spindle: the T selected before M06 (0 empties it).
    pub tool: u16,
    /// The tool in the spindle until now (0 = none).
    pub previous: u16,
    /// A change by hand: the machine stops, the operator is asked to load `tool`,
    /// cycle start goes on. Otherwise the tool changer (ATC) changes it and reports
    /// done (machine file `tool_changer`).
    pub manual: bool,
}

/// The ratio of polygon turning (G51.2 P Q, 2.8).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PolygonSync {
    /// P: work-spindle turns (1–999).
    pub p: u16,
    /// Q: tool-spindle turns (1–999) for P work-spindle turns.
    pub q: u16,
}

/// Where a move ends, in both coordinate systems (internal units, X radius).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Endpoint {
    /// Axis positions in machine coordinates, tool offset included.
    pub machine: Pos,
    /// The programmed point in the coordinates the program uses: the work frame in
    /// force (G54–G59 with the G50 shift) and, when set, the G52 local frame.
    pub work: Pos,
}

/// Feed per minute or per revolution.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum FeedMode {
    /// G98: nm per minute.
    PerMin,
    /// G99: nm per spindle revolution.
    PerRev,
}

/// A commanded feed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Feed {
    /// Per minute or per revolution.
    pub mode: FeedMode,
    /// nm/min or nm/rev along the path.
    pub value: i64,
}

/// The spindle speed the control commands while a move runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SpindleSpeed {
    /// Commanded speed in rev/min (at the end point under G96), `None` if stopped.
    pub rpm: Option<u32>,
    /// Surface speed in mm/min under G96 (the speed follows |X| along the move).
    pub css: Option<u32>,
    /// Speed cap of G96 (G50 S and the gear limit), rev/min.
    pub max_rpm: u32,
}

impl SpindleSpeed {
    /// The speed commanded with the tool at work X radius `x` (nm): under G96 the
    /// surface speed over π·|X| capped at `max_rpm`, otherwise the fixed speed.
    /// The interpreter, the planner and the simulator all use this one formula.
    pub fn rpm_at(&self, x: i64) -> Option<u32> {
        match (self.rpm, self.css) {
            (Some(_), Some(css)) => Some(css_rpm(css, x).min(self.max_rpm)),
            (rpm, _) => rpm,
        }
    }
}

/// rev/min for surface speed `css` (mm/min) at radius `x` (nm), rounded (2.19:
/// surface speed = rpm × π × |X| / 1000 with X a diameter); at the centre the speed
/// is unbounded (`u32::MAX`) and the caller's cap applies (2.19 note 7).
///
/// f32 (hardware on the Cortex-M4F) is plenty: a speed, not a position, and its
/// 24-bit mantissa keeps the rounding error far below one rev/min.
#[inline(never)]
pub fn css_rpm(css: u32, x: i64) -> u32 {
    // The radius through u32 (capped at 4.29 m, beyond any lathe): u32 → f32 is one
    // instruction, u64 → f32 a library call of some 60 (this runs every G96 block).
    let r = x.unsigned_abs().min(u64::from(u32::MAX)) as u32;
    let d_mm = 2.0 * (r as f32) / 1e6;
    if d_mm == 0.0 {
        return u32::MAX;
    }
    let rpm = (css as f32 / (core::f32::consts::PI * d_mm)).min(u32::MAX as f32);
    // Rounded half away from zero as `libm::roundf` (rpm is positive: its whole
    // part by the saturating cast, the fraction exact), without its call: the
    // size-built firmware's link-time optimisation does not inline it. (Never
    // inlined itself: its callers' code stays as it was with the call.)
    let whole = rpm as u32;
    if rpm - whole as f32 >= 0.5 { whole.saturating_add(1) } else { whole }
}

/// A straight move (rapid or cutting).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Move {
    /// End point.
    pub to: Endpoint,
    /// The feed in force. A cutting move runs at it; a rapid ignores it (the axes'
    /// rapid rates apply) and carries it only to tell the modal feed mode.
    pub feed: Feed,
    /// Spindle during the move.
    pub spindle: SpindleSpeed,
    /// Stop exactly at the end before the next block (G09, G61, rapids, G04 …).
    pub exact_stop: bool,
    /// Rapids: each axis at its own rate, not interpolated (G28/G30, dog-leg G00).
    pub independent: bool,
}

/// The working plane of an arc (G17/G18/G19).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Plane {
    /// G17: X–Y.
    Xy,
    /// G18: Z–X, the lathe's plane.
    Zx,
    /// G19: Y–Z.
    Yz,
}

impl Plane {
    /// The plane's two axes in the order that makes G02 clockwise when the plane is
    /// seen from the positive side of its normal (G18: Z right, X up, Y towards you).
    #[inline]
    pub const fn axes(self) -> (Axis, Axis) {
        match self {
            Plane::Xy => (Axis::X, Axis::Y),
            Plane::Zx => (Axis::Z, Axis::X),
            Plane::Yz => (Axis::Y, Axis::Z),
        }
    }

    /// The axis normal to the plane (G17: Z, G18: Y, G19: X): a machining centre's
    /// tool axis, along which G43/G44 put the tool length.
    #[inline]
    pub const fn normal(self) -> Axis {
        match self {
            Plane::Xy => Axis::Z,
            Plane::Zx => Axis::Y,
            Plane::Yz => Axis::X,
        }
    }

    /// Whether `a` lies in the plane.
    #[inline]
    pub fn contains(self, a: Axis) -> bool {
        let (p, q) = self.axes();
        a == p || a == q
    }
}

/// A circular move in a plane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ArcMove {
    /// End point.
    pub to: Endpoint,
    /// Centre (the plane's two axes are meaningful, the others equal the end point).
    pub center: Endpoint,
    /// The plane.
    pub plane: Plane,
    /// G02 (clockwise) or G03.
    pub cw: bool,
    /// A full circle (start = end given with I/J/K).
    pub full_circle: bool,
    /// Feed.
    pub feed: Feed,
    /// Spindle during the move.
    pub spindle: SpindleSpeed,
    /// Stop exactly at the end.
    pub exact_stop: bool,
}

/// How a thread pass starts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ThreadSync {
    /// Wait for the spindle index (plus the start angle), then lock to the spindle.
    Index,
    /// Continue locked from the previous thread block without re-synchronising.
    Continue,
}

/// A spindle-synchronised thread move (G32/G34 blocks, G92 and G76 passes).
///
/// The start is where the previous motion ended. The long axis is Z when the move
/// travels further in Z than in X (radius), else X; `lead` is along it and the
/// other axis follows proportionally (tapers). A G92/G76 pass with a pull-out
/// (chamfer, parameters 5130/5131) is two thread moves: the thread to where the
/// pull-out starts (`Index`), then the pull-out to the end point with the same lead
/// (`Continue`): the long axis keeps its lead while the short axis pulls out.
/// Multi-start threads (G92 H) are passes with `start_udeg` 360°/H apart.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ThreadMove {
    /// End point.
    pub to: Endpoint,
    /// Lead in nm per spindle revolution along the long axis (X as a radius).
    pub lead: i64,
    /// Lead change per revolution (G34 K), nm/rev per rev; the lead after n
    /// revolutions is `lead + n·lead_delta`.
    pub lead_delta: i64,
    /// Spindle angle after the index where the pass starts, micro-degrees (G32 Q,
    /// G92 H offsets); meaningless for `Continue`.
    pub start_udeg: u32,
    /// Index-synchronised or continuing.
    pub sync: ThreadSync,
    /// Spindle during the move.
    pub spindle: SpindleSpeed,
}

/// Spindle direction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SpindleDir {
    /// M03.
    Cw,
    /// M04.
    Ccw,
    /// M05.
    Stop,
}

/// A rigid-tapping move (M29 G84/G88): the tapping axis locked to the spindle
/// position, `lead` per revolution, into the hole and out of it (the spindle
/// reverses: `dir` is the direction during this move). Floating tapping is not a
/// tap move: it is feed-per-revolution linear moves between spindle commands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct TapMove {
    /// End point.
    pub to: Endpoint,
    /// Lead in nm per spindle revolution.
    pub lead: i64,
    /// Spindle direction during this move (reverses on the way out).
    pub dir: SpindleDir,
    /// Spindle during the move.
    pub spindle: SpindleSpeed,
}

/// A spindle command.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SpindleCommand {
    /// Direction.
    pub dir: SpindleDir,
    /// Speed now commanded, rev/min (`None` when stopped).
    pub rpm: Option<u32>,
    /// Surface speed in mm/min under G96.
    pub css: Option<u32>,
}

impl Action {
    /// The end point of a motion action.
    #[inline]
    pub fn endpoint(&self) -> Option<&Endpoint> {
        match self {
            Action::Rapid(m) | Action::Linear(m) => Some(&m.to),
            Action::Arc(a) => Some(&a.to),
            Action::Thread(t) => Some(&t.to),
            Action::Tap(t) => Some(&t.to),
            _ => None,
        }
    }
}

/// The sink cannot take an action now; offer it again later.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Full;

/// Consumer of canonical actions.
pub trait CanonSink {
    /// Takes one action, or returns [`Full`] to apply back-pressure; the
    /// interpreter keeps the action and offers it again on its next step.
    fn push(&mut self, action: Canon) -> Result<(), Full>;

    /// [`CanonSink::push`] of an action the caller keeps (the interpreter offers
    /// its waiting actions in place). A sink that only reads the action (the motion
    /// planner) overrides this to skip the copy — 176 bytes for an arc, about as
    /// many instructions on the Cortex-M4; the default copies it into `push`.
    #[inline]
    fn push_ref(&mut self, action: &Canon) -> Result<(), Full> {
        self.push(*action)
    }
}

impl<S: CanonSink + ?Sized> CanonSink for &mut S {
    #[inline]
    fn push(&mut self, action: Canon) -> Result<(), Full> {
        (**self).push(action)
    }

    #[inline]
    fn push_ref(&mut self, action: &Canon) -> Result<(), Full> {
        (**self).push_ref(action)
    }
}

#[cfg(test)]
mod css_tests {
    use super::css_rpm;

    /// The spindle speed G96 commands is rounded exactly as `libm::roundf` rounds
    /// it, over surface speeds and radii from 1 nm to beyond any lathe.
    #[test]
    fn css_rpm_rounds_as_roundf() {
        let radii =
            (0..4_000u32).map(|k| i64::from(k) * 997 + 1).chain([7_958_000, 1_000_000_000, i64::MAX, -25_000_000]);
        for x in radii {
            for css in [1u32, 2, 7, 100, 157, 200, 250, 999, 1_000, 12_345, 65_535, 1 << 24, u32::MAX] {
                let r = x.unsigned_abs().min(u64::from(u32::MAX)) as u32;
                let d_mm = 2.0 * (r as f32) / 1e6;
                let rpm = css as f32 / (core::f32::consts::PI * d_mm);
                let want = libm::roundf(rpm.min(u32::MAX as f32)) as u32;
                assert_eq!(css_rpm(css, x), want, "css {css} x {x}");
            }
        }
        assert_eq!(css_rpm(200, 0), u32::MAX);
    }
}

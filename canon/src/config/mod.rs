//! The machine description: axes, reference positions, work offsets, tool table,
//! spindle limits and the numbered parameters. Built with defaults that run every
//! example of the manual; the host reads it from a TOML machine file, the firmware
//! from flash.

pub mod motion;
pub mod params;
pub mod tools;

pub use motion::{Drive, MotionConfig};
pub use params::{CALL_G, CALL_M, PARAMS, Param, ParamDef, ParamError, ParamUnit, Parameters, SUB_M};
pub use tools::{MAX_OFFSET_VALUE, MAX_OFFSETS, MillPage, ToolOffset, ToolTable};

use crate::axis::{AXIS_COUNT, Axis, Pos};
use crate::units::{IncrementSystem, InputMode};

/// Which G-code table of 1.1 the programs are written in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum GCodeSystem {
    /// System A: the manual's own (G90 turning cycle, G98/G99 feed modes, U/W incremental).
    A,
    /// System B: G90/G91 absolute/incremental, G94/G95 feed modes, G77/G78/G79 cycles.
    B,
    /// System C: as B with G20/G21/G24 cycles and G70/G71 inch/metric.
    C,
}

/// The language programs are written in: which front end reads them.
///
/// A machine setting gives the language at power-on and after a reset; in a
/// program or on the link `G290` switches to SINUMERIK mode and `G291` back to the
/// FANUC-style (ISO) dialect, as the 840D switches to and from its ISO dialect.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Language {
    /// The FANUC-style dialect of the ELESY-E3TA manual, with custom macro B.
    #[default]
    Fanuc,
    /// SINUMERIK 840D: R parameters, DEF variables, labels, PROC, the standard cycles.
    Siemens,
}

/// The kind of machine: the profile that selects the G-code table, the address
/// letters, the power-on modes, the tool model and the axes the language speaks of.
/// Everything below the language (planner, interpolator, steps, job control, link,
/// program memory, persistence) is the same for every kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum MachineKind {
    /// A lathe: X (diameter) and Z, C optional; turret T with offsets (T0101);
    /// the T-series codes of table 1.1 (systems A/B/C).
    #[default]
    Lathe,
    /// A machining centre (FANUC 0i-M, seed 004): X, Y, Z in radius, optional 4th
    /// rotary; T selects, M06 changes; H length and D radius offsets; M-series codes.
    Mill,
}

/// The G-code table a block is read in: the machine kind's table, for a lathe in
/// the G-code system chosen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum CodeTable {
    /// A lathe's table 1.1 in system A, B or C.
    Lathe(GCodeSystem),
    /// The M series of a machining centre.
    Mill,
}

/// How a machining centre changes tools at M06.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ToolChanger {
    /// By hand: the machine stops and asks the operator to load the tool.
    #[default]
    Manual,
    /// An automatic tool changer driven by the board's outputs.
    Automatic,
}

/// The automatic tool changer's default time to answer a request, s: a
/// carousel or arm changer of a small machining centre takes 5–15 s.
pub const DEFAULT_TOOL_CHANGE_TIMEOUT_S: u16 = 30;

/// The highest tool the automatic tool changer can be asked for: the board puts the
/// number out on five bits (ATC T1–T16, docs/MILL-BOARD.md).
pub const MAX_CHANGER_TOOL: u16 = 31;

/// Longest wait for the automatic tool changer that can be set, s.
pub const MAX_TOOL_CHANGE_TIMEOUT_S: u16 = 3_600;

/// How long a machining centre's automatic tool changer may take to report done
/// after the board's request, 1–3600 s. Held only with the mill profile: without
/// it (the F446 build) it takes no byte of the machine description (whose layout,
/// and so the code that reaches into it, stays as it was) and reads as the default.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ToolChangeTimeout {
    #[cfg(feature = "mill")]
    seconds: u16,
}

impl ToolChangeTimeout {
    /// [`DEFAULT_TOOL_CHANGE_TIMEOUT_S`].
    pub const DEFAULT: Self = ToolChangeTimeout {
        #[cfg(feature = "mill")]
        seconds: DEFAULT_TOOL_CHANGE_TIMEOUT_S,
    };

    /// The time, s.
    pub const fn seconds(self) -> u16 {
        #[cfg(feature = "mill")]
        return self.seconds;
        #[cfg(not(feature = "mill"))]
        DEFAULT_TOOL_CHANGE_TIMEOUT_S
    }

    /// Sets the time; false (unchanged) outside 1–3600 s or without the mill profile.
    pub fn set(&mut self, seconds: u16) -> bool {
        #[cfg(feature = "mill")]
        if (1..=MAX_TOOL_CHANGE_TIMEOUT_S).contains(&seconds) {
            self.seconds = seconds;
            return true;
        }
        let _ = seconds;
        false
    }
}

/// Number of additional work coordinate systems (G54.1 P1–P48, seed 004 @2112).
pub const EXTRA_FRAMES: usize = 48;

/// The 48 additional work offsets of G54.1 P1–P48 (a machining centre's; set by
/// G10 L20). X, Y and Z of each, machine coordinates, held as `i32` nanometres
/// (±2,147 mm, beyond any machine this board drives) to keep them within the
/// board's RAM: 576 bytes instead of 1,536.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ExtraOffsets {
    rows: [[i32; 3]; EXTRA_FRAMES],
}

impl Default for ExtraOffsets {
    fn default() -> Self {
        ExtraOffsets { rows: [[0; 3]; EXTRA_FRAMES] }
    }
}

impl ExtraOffsets {
    /// The three linear axes an extra offset holds.
    const AXES: [Axis; 3] = [Axis::X, Axis::Y, Axis::Z];

    /// Offset `p` (1–48) as a position (C zero); `None` outside 1–48.
    pub fn get(&self, p: u8) -> Option<Pos> {
        let row = self.rows.get(usize::from(p).checked_sub(1)?)?;
        let mut out = Pos::ZERO;
        for (a, v) in Self::AXES.into_iter().zip(row) {
            out[a] = i64::from(*v);
        }
        Some(out)
    }

    /// Sets offset `p` (1–48) to `pos` (X, Y, Z); false if `p` is outside 1–48 or a
    /// coordinate outside ±2,147 mm (nothing is changed then).
    pub fn set(&mut self, p: u8, pos: Pos) -> bool {
        let Some(i) = usize::from(p).checked_sub(1).filter(|i| *i < EXTRA_FRAMES) else { return false };
        let mut row = [0i32; 3];
        for (slot, a) in row.iter_mut().zip(Self::AXES) {
            match i32::try_from(pos[a]) {
                Ok(v) => *slot = v,
                Err(_) => return false,
            }
        }
        self.rows[i] = row;
        true
    }

    /// Row `p` (1–48) as held: X, Y, Z in nanometres; `None` outside 1–48 (what
    /// the board's flash stores).
    pub fn row(&self, p: u8) -> Option<[i32; 3]> {
        self.rows.get(usize::from(p).checked_sub(1)?).copied()
    }

    /// Sets row `p` (1–48) as held (X, Y, Z nm; restored from flash); false outside 1–48.
    pub fn set_row(&mut self, p: u8, row: [i32; 3]) -> bool {
        match usize::from(p).checked_sub(1).and_then(|i| self.rows.get_mut(i)) {
            Some(slot) => {
                *slot = row;
                true
            }
            None => false,
        }
    }
}

/// Limits and rates of one axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AxisConfig {
    /// Whether the machine has this axis (X and Z always; Y and C optional).
    pub present: bool,
    /// Negative soft limit, machine coordinates, internal units (X radius).
    pub min: i64,
    /// Positive soft limit, machine coordinates, internal units (X radius).
    pub max: i64,
    /// Rapid rate (parameters 6032–6035), internal units per minute.
    pub rapid_per_min: i64,
    /// Maximum cutting feed of this axis (parameters 6040–6043), units per minute.
    pub max_feed_per_min: i64,
    /// Acceleration, internal units per second squared.
    pub accel_per_s2: i64,
    /// Largest instantaneous change of this axis's speed at a junction between two
    /// blended blocks (G64), units per minute.
    pub max_jump_per_min: i64,
    /// Motor drive: exact steps-per-length ratio and driver timing.
    pub drive: Drive,
}

impl AxisConfig {
    /// A linear axis with the given travel (mm, as stored: X radius) and rates.
    pub const fn linear(min_mm: i64, max_mm: i64, rapid_mm_min: i64) -> Self {
        AxisConfig {
            present: true,
            min: min_mm * 1_000_000,
            max: max_mm * 1_000_000,
            rapid_per_min: rapid_mm_min * 1_000_000,
            max_feed_per_min: 5_000 * 1_000_000,
            accel_per_s2: 500 * 1_000_000,
            max_jump_per_min: 300 * 1_000_000,
            drive: Drive::per_mm(400),
        }
    }

    /// An axis the machine does not have.
    pub const ABSENT: AxisConfig = AxisConfig {
        present: false,
        min: 0,
        max: 0,
        rapid_per_min: 0,
        max_feed_per_min: 0,
        accel_per_s2: 0,
        max_jump_per_min: 300 * 1_000_000,
        drive: Drive::per_mm(400),
    };
}

/// Spindle limits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SpindleConfig {
    /// Speed at full output (10 V): the cap of every commanded speed (2.19 note 7).
    pub max_rpm: u32,
    /// Lowest speed G96 commands when no surface speed was ever given (2.19 note 2).
    pub css_min_rpm: u32,
    /// Top speed of gears 1–4 (M41–M44); 0 = no gear limit (2.19 note 5).
    pub gear_max_rpm: [u32; 4],
    /// Spindle encoder counts per revolution after quadrature decoding (4 × lines).
    pub encoder_cpr: u32,
    /// How fast the spindle drive changes speed, rev/min per second (rigid tapping
    /// plans its reversal with it).
    pub accel_rpm_per_s: u32,
}

/// When an M code's action happens relative to the motion of its block.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum MTiming {
    /// Before the block's motion starts (M03, M08 …).
    Before,
    /// After the block's motion has finished (M05, M09 …).
    After,
}

/// An M code the machine builder wired to an output beyond the manual's tables.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UserMCode {
    /// The M number.
    pub m: u16,
    /// Before or after the motion of its block.
    pub timing: MTiming,
}

/// Capacity of the user M-code list.
pub const MAX_USER_M: usize = 16;

/// Everything the interpreter needs to know about the machine.
#[derive(Clone, Debug, PartialEq)]
pub struct MachineConfig {
    /// Lathe or mill: the profile the language is read in.
    pub kind: MachineKind,
    /// The language at power-on and after a reset (`G290`/`G291` switch it).
    pub language: Language,
    /// G-code system A, B or C (table 1.1) of a lathe.
    pub gcode_system: GCodeSystem,
    /// IS-B or IS-C least increments.
    pub increments: IncrementSystem,
    /// Whether X is programmed as a diameter (the manual's convention).
    pub diameter_x: bool,
    /// Whether G00 moves each axis at its own rapid rate (dog-leg path) instead of
    /// interpolating a straight line. G28/G30 always move the axes independently.
    pub rapid_independent: bool,
    /// Axis limits and rates, indexed by [`Axis`].
    pub axes: [AxisConfig; AXIS_COUNT],
    /// Reference positions 1–4 (G28 = 1; G30 P1–P4), machine coordinates.
    pub reference: [Pos; 4],
    /// Work offsets of G54–G59, machine coordinates of each work zero.
    pub work_offsets: [Pos; 6],
    /// External work offset, added to all six (and to G54.1's).
    pub external_offset: Pos,
    /// Work offsets of G54.1 P1–P48 (a machining centre's).
    pub extra_offsets: ExtraOffsets,
    /// How M06 changes tools on a machining centre.
    pub tool_changer: ToolChanger,
    /// How long the board waits for the automatic tool changer's "done" after
    /// its request (alarm 4511 when it does not come).
    pub tool_change_timeout: ToolChangeTimeout,
    /// Highest tool (turret station) number.
    pub tool_count: u16,
    /// Tool offsets: geometry, wear, nose radius, tip direction.
    pub tools: ToolTable,
    /// Spindle limits.
    pub spindle: SpindleConfig,
    /// M codes configured as user outputs.
    pub user_m_codes: heapless::Vec<UserMCode, MAX_USER_M>,
    /// The external input M91/M92 test (3.1.5 speaks of "the input signal" without
    /// naming one; this machine wires it to `interp_core::Environment::input` number
    /// `jump_input`, 0 by default).
    pub jump_input: u16,
    /// Numbered parameters.
    pub params: Parameters,
    /// Motion core settings: interpolation period, junctions, tolerances.
    pub motion: MotionConfig,
}

impl Default for MachineConfig {
    fn default() -> Self {
        // X: 400 steps per mm of radius (2.5 um); Z: 320 steps per mm (5 mm screw, 1600 steps/rev).
        let x = AxisConfig::linear(-5, 160, 6_000);
        let z = AxisConfig { drive: Drive::per_mm(320), ..AxisConfig::linear(-600, 300, 8_000) };
        MachineConfig {
            kind: MachineKind::Lathe,
            language: Language::Fanuc,
            gcode_system: GCodeSystem::A,
            increments: IncrementSystem::IsB,
            diameter_x: true,
            rapid_independent: false,
            axes: [x, AxisConfig::ABSENT, z, AxisConfig::ABSENT],
            reference: [Pos::xz(150_000_000, 250_000_000); 4],
            work_offsets: [Pos::ZERO; 6],
            external_offset: Pos::ZERO,
            extra_offsets: ExtraOffsets::default(),
            tool_changer: ToolChanger::Manual,
            tool_change_timeout: ToolChangeTimeout::DEFAULT,
            tool_count: 12,
            tools: ToolTable::default(),
            spindle: SpindleConfig {
                max_rpm: 3_000,
                css_min_rpm: 50,
                gear_max_rpm: [0; 4],
                encoder_cpr: 4_096,
                accel_rpm_per_s: 2_000,
            },
            user_m_codes: heapless::Vec::new(),
            jump_input: 0,
            params: Parameters::default(),
            motion: MotionConfig::default(),
        }
    }
}

impl MachineConfig {
    /// The configuration of axis `a`.
    #[inline]
    pub fn axis(&self, a: Axis) -> &AxisConfig {
        &self.axes[a.index()]
    }

    /// The machine-coordinate origin of work frame `frame`: G54–G59 (0–5), G54.1
    /// P1–P48 (6–53); without the external offset.
    pub fn work_offset(&self, frame: u8) -> Pos {
        match self.work_offsets.get(usize::from(frame)) {
            Some(p) => *p,
            None => self.extra_offsets.get(frame.saturating_sub(5)).unwrap_or(Pos::ZERO),
        }
    }

    /// A machining centre with X, Y, Z in radius (travel X −500–0, Y −400–0,
    /// Z −400–0 mm from the reference position at machine zero), the M-series codes
    /// and the built-in rates: what the tests and `examples/machines/mill.toml`
    /// start from.
    pub fn mill() -> Self {
        let mut c =
            MachineConfig { kind: MachineKind::Mill, diameter_x: false, tool_count: 24, ..MachineConfig::default() };
        c.axes[Axis::X.index()] = AxisConfig::linear(-500, 0, 8_000);
        c.axes[Axis::Y.index()] = AxisConfig::linear(-400, 0, 8_000);
        c.axes[Axis::Z.index()] = AxisConfig::linear(-400, 0, 6_000);
        c.reference = [Pos::ZERO; 4];
        c
    }

    /// The G-code table blocks are read in.
    #[inline]
    pub fn code_table(&self) -> CodeTable {
        match self.kind {
            MachineKind::Lathe => CodeTable::Lathe(self.gcode_system),
            MachineKind::Mill => CodeTable::Mill,
        }
    }

    /// Input mode from parameter 3401.
    #[inline]
    pub fn input_mode(&self) -> InputMode {
        if self.params.flag(Param::CalculatorInput) { InputMode::Calculator } else { InputMode::LeastIncrement }
    }

    /// The user M code `m`, if configured.
    #[inline]
    pub fn user_m(&self, m: u16) -> Option<UserMCode> {
        self.user_m_codes.iter().copied().find(|u| u.m == m)
    }

    /// Checks the machine's shape: X and Z present, every present linear axis with
    /// travel (min below max) and positive rates, spindle speeds set. The layers
    /// above check what only they know, in this order after it: the motion core's
    /// settings (`motion_core::planner::machine::check_config`), then the user M
    /// codes new and unique (`interp_core::codes::check_user_m_codes`).
    pub fn validate(&self) -> Result<(), ConfigError> {
        for a in [Axis::X, Axis::Z] {
            if !self.axis(a).present {
                return Err(ConfigError::AxisMissing { axis: a });
            }
        }
        for a in Axis::ALL {
            let ax = self.axis(a);
            if !ax.present {
                continue;
            }
            if !a.is_rotary() && ax.min >= ax.max {
                return Err(ConfigError::NoTravel { axis: a });
            }
            if ax.rapid_per_min <= 0 || ax.max_feed_per_min <= 0 || ax.accel_per_s2 <= 0 {
                return Err(ConfigError::RateNotPositive { axis: a });
            }
        }
        if self.spindle.max_rpm == 0 {
            return Err(ConfigError::SpindleMaxZero);
        }
        if self.kind == MachineKind::Mill
            && self.tool_changer == ToolChanger::Automatic
            && self.tool_count > MAX_CHANGER_TOOL
        {
            return Err(ConfigError::ToolsBeyondChanger { count: self.tool_count });
        }
        Ok(())
    }
}

/// A machine description the controller cannot run with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ConfigError {
    /// X or Z is missing: every lathe has both.
    AxisMissing {
        /// The axis.
        axis: Axis,
    },
    /// An axis's negative limit is not below its positive limit.
    NoTravel {
        /// The axis.
        axis: Axis,
    },
    /// An axis's rapid rate, maximum feed or acceleration is not positive.
    RateNotPositive {
        /// The axis.
        axis: Axis,
    },
    /// The spindle's top speed is zero.
    SpindleMaxZero,
    /// A user M code that the manual's tables already define.
    UserMStandard {
        /// The M number.
        m: u16,
    },
    /// A user M code listed twice.
    UserMTwice {
        /// The M number.
        m: u16,
    },
    /// More tools than the automatic tool changer's five number outputs can name
    /// (T1–T31): a T above 31 would never be changed.
    ToolsBeyondChanger {
        /// The tool count given.
        count: u16,
    },
    /// A motion setting the motion core cannot work with (step ratio, driver
    /// timing, encoder, interpolation period).
    Motion {
        /// What is wrong.
        what: &'static str,
    },
}

impl core::fmt::Display for ConfigError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let name = |a: &Axis| (a.letter() as char).to_ascii_lowercase();
        match self {
            ConfigError::AxisMissing { axis } => write!(f, "axes.{}: a lathe needs this axis", name(axis)),
            ConfigError::NoTravel { axis } => write!(f, "axes.{}: min must be below max", name(axis)),
            ConfigError::RateNotPositive { axis } => {
                write!(f, "axes.{}: rapid, max_feed and accel must be positive", name(axis))
            }
            ConfigError::SpindleMaxZero => write!(f, "spindle.max_rpm must be positive"),
            ConfigError::UserMStandard { m } => write!(f, "user_m_codes: M{m:02} is a standard M code"),
            ConfigError::UserMTwice { m } => write!(f, "user_m_codes: M{m:02} given twice"),
            ConfigError::ToolsBeyondChanger { count } => write!(
                f,
                "tool_count = {count}: the automatic tool changer's outputs name tools 1 to {MAX_CHANGER_TOOL}"
            ),
            ConfigError::Motion { what } => write!(f, "motion: {what}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_machine_is_valid_and_mistakes_are_named() {
        assert_eq!(MachineConfig::default().validate(), Ok(()));
        let mut c = MachineConfig::default();
        c.axes[Axis::Z.index()].max = c.axes[Axis::Z.index()].min;
        assert_eq!(c.validate(), Err(ConfigError::NoTravel { axis: Axis::Z }));
        let mut c = MachineConfig::default();
        c.axes[Axis::X.index()].rapid_per_min = 0;
        assert_eq!(c.validate(), Err(ConfigError::RateNotPositive { axis: Axis::X }));
        let mut c = MachineConfig::default();
        c.axes[Axis::Z.index()] = AxisConfig::ABSENT;
        assert_eq!(c.validate(), Err(ConfigError::AxisMissing { axis: Axis::Z }));
        let mut c = MachineConfig::mill();
        c.tool_changer = ToolChanger::Automatic;
        c.tool_count = MAX_CHANGER_TOOL;
        assert_eq!(c.validate(), Ok(()));
        c.tool_count = MAX_CHANGER_TOOL + 1;
        assert_eq!(c.validate(), Err(ConfigError::ToolsBeyondChanger { count: 32 }));
        c.tool_changer = ToolChanger::Manual;
        assert_eq!(c.validate(), Ok(()), "a manual change names the tool on the screen, any number");
    }
}

//! The TOML machine file as serde types. Every field is optional (a missing one
//! keeps the built-in value) and unknown fields are errors, so a typo cannot pass
//! unnoticed. Values are what a machinist reads on the control: mm, mm/min,
//! degrees, and X positions as diameters.

use std::cmp::Ordering;
use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

/// A whole machine file.
#[derive(Clone, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MachineFile {
    /// `lathe` or `mill`: the profile programs are read in (G-code table, letters,
    /// power-on modes, tool model).
    pub kind: Option<KindName>,
    /// `fanuc` or `siemens`: the language at power-on and after a reset.
    pub language: Option<LanguageName>,
    /// `A`, `B` or `C`.
    pub gcode_system: Option<GCodeSystemName>,
    /// `IS-B` or `IS-C`.
    pub increment_system: Option<IncrementName>,
    /// `calculator` or `least_increment` (parameter 3401).
    pub input: Option<InputName>,
    /// X programmed as a diameter.
    pub diameter_programming: Option<bool>,
    /// G00 moves each axis at its own rate.
    pub rapid_independent: Option<bool>,
    /// Highest turret station (a mill's highest tool number).
    pub tool_count: Option<u16>,
    /// A mill's tool change at M06: `manual` (a stop: the operator loads the tool)
    /// or `automatic` (the tool changer).
    pub tool_changer: Option<ToolChangerName>,
    /// A mill's automatic tool changer: seconds it may take to report done after
    /// the board's request (1–3600, default 30; `$313`; alarm 4511 beyond).
    pub tool_change_timeout: Option<u16>,
    /// Reference positions 1–4, machine coordinates; fewer than 4: the rest equal the first.
    pub reference: Option<Vec<Point>>,
    /// Travel and rates per axis.
    pub axes: Option<Axes>,
    /// G54–G59 and the external offset.
    pub work_offsets: Option<WorkOffsets>,
    /// Tool offset rows.
    pub offsets: Option<Vec<Offset>>,
    /// Spindle limits.
    pub spindle: Option<Spindle>,
    /// M codes wired to machine outputs.
    pub user_m_codes: Option<Vec<UserM>>,
    /// The external input M91/M92 test (3.1.5).
    pub jump_input: Option<u16>,
    /// Numbered parameters by number, in file units.
    pub parameters: Option<BTreeMap<ParamKey, f64>>,
    /// Motion core settings.
    pub motion: Option<MotionFile>,
}

/// The motion core's settings.
#[derive(Clone, Copy, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MotionFile {
    /// Interpolation period, µs.
    pub period_us: Option<u32>,
    /// Junction deviation of blended corners, mm.
    pub junction_deviation: Option<f64>,
    /// Chord tolerance of arcs and blended corners, mm.
    pub chord_tolerance: Option<f64>,
    /// Periods over which the spindle speed is measured.
    pub speed_window: Option<u16>,
    /// Spindle at-speed band, percent of the command.
    pub at_speed: Option<u8>,
    /// Longest wait for the spindle to reach speed, s.
    pub at_speed_timeout: Option<f64>,
    /// Spindle speed ripple margin of the thread checks, percent.
    pub thread_margin: Option<u8>,
}

/// A `[parameters]` key: the number as written, ordered as a number (so a
/// written file lists 405 before 3401).
#[derive(Clone, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(transparent)]
pub struct ParamKey(pub String);

impl Ord for ParamKey {
    fn cmp(&self, other: &Self) -> Ordering {
        (self.0.len(), &self.0).cmp(&(other.0.len(), &other.0))
    }
}

impl PartialOrd for ParamKey {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// Machine kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum KindName {
    /// A lathe (T series).
    Lathe,
    /// A machining centre (M series).
    Mill,
}

/// How a mill changes tools.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ToolChangerName {
    /// By hand, after a stop.
    Manual,
    /// By the tool changer.
    Automatic,
}

/// Programming language.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LanguageName {
    /// The FANUC-style dialect.
    Fanuc,
    /// SINUMERIK 840D.
    Siemens,
}

/// G-code system.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
pub enum GCodeSystemName {
    /// System A.
    A,
    /// System B.
    B,
    /// System C.
    C,
}

/// Increment system.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
pub enum IncrementName {
    /// 0.001 mm.
    #[serde(rename = "IS-B")]
    IsB,
    /// 0.0001 mm.
    #[serde(rename = "IS-C")]
    IsC,
}

/// How numbers without a decimal point are read.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum InputName {
    /// `X60` is 60 mm.
    Calculator,
    /// `X60` is 60 least increments.
    LeastIncrement,
}

/// A position: X as a diameter (mm), Y and Z in mm, C in degrees.
#[derive(Clone, Copy, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Point {
    /// X, diameter mm.
    pub x: Option<f64>,
    /// Y, mm.
    pub y: Option<f64>,
    /// Z, mm.
    pub z: Option<f64>,
    /// C, degrees.
    pub c: Option<f64>,
}

/// The axes' tables; Y and C exist when their table is given.
#[derive(Clone, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Axes {
    /// Cross slide.
    pub x: Option<AxisFile>,
    /// Y axis.
    pub y: Option<AxisFile>,
    /// Carriage.
    pub z: Option<AxisFile>,
    /// Spindle as a rotary axis.
    pub c: Option<AxisFile>,
}

/// One axis: soft limits in machine coordinates (X as a diameter), rates of the
/// slide (X not doubled), C in degrees.
#[derive(Clone, Copy, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct AxisFile {
    /// Negative soft limit.
    pub min: Option<f64>,
    /// Positive soft limit.
    pub max: Option<f64>,
    /// Rapid rate, mm/min (C: deg/min).
    pub rapid: Option<f64>,
    /// Maximum cutting feed, mm/min.
    pub max_feed: Option<f64>,
    /// Acceleration, mm/s².
    pub accel: Option<f64>,
    /// Largest speed jump at a blended corner, mm/min.
    pub max_jump: Option<f64>,
    /// Motor steps for `steps_travel` of slide travel: an exact ratio.
    pub steps: Option<i64>,
    /// Slide travel of `steps` steps, mm (X: of the slide, a radius; C: degrees).
    pub steps_travel: Option<f64>,
    /// Shortest step pulse of the driver, µs.
    pub pulse_us: Option<f64>,
    /// Direction set-up time before a step, µs.
    pub dir_setup_us: Option<f64>,
    /// Highest step rate of the driver, steps per second.
    pub max_step_rate: Option<u32>,
}

/// Work offsets: machine coordinates of each work zero.
#[derive(Clone, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct WorkOffsets {
    /// G54.
    pub g54: Option<Point>,
    /// G55.
    pub g55: Option<Point>,
    /// G56.
    pub g56: Option<Point>,
    /// G57.
    pub g57: Option<Point>,
    /// G58.
    pub g58: Option<Point>,
    /// G59.
    pub g59: Option<Point>,
    /// Added to all six.
    pub external: Option<Point>,
    /// A mill's G54.1 P1–P48, each with its `p`.
    pub g54_1: Option<Vec<ExtraOffset>>,
}

/// One of a mill's G54.1 work offsets.
#[derive(Clone, Copy, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ExtraOffset {
    /// P: 1–48.
    pub p: u8,
    /// X, mm.
    pub x: Option<f64>,
    /// Y, mm.
    pub y: Option<f64>,
    /// Z, mm.
    pub z: Option<f64>,
}

/// One row of the tool offset page: a lathe's X/Z geometry and wear, nose radius
/// and tip; a mill's tool length (H) and cutter radius (D), geometry and wear.
#[derive(Clone, Copy, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Offset {
    /// Offset number.
    pub number: u16,
    /// Mill: tool length (H), geometry, mm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub length: Option<f64>,
    /// Mill: tool length (H), wear, mm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub length_wear: Option<f64>,
    /// Mill: cutter radius (D), wear, mm (`radius` is its geometry).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub radius_wear: Option<f64>,
    /// X geometry, diameter mm.
    pub x: Option<f64>,
    /// Z geometry, mm.
    pub z: Option<f64>,
    /// X wear, diameter mm.
    pub x_wear: Option<f64>,
    /// Z wear, mm.
    pub z_wear: Option<f64>,
    /// Nose radius, mm.
    pub radius: Option<f64>,
    /// Imaginary tip direction 0–9.
    pub tip: Option<u8>,
    /// Clearance angle of the edge, degrees 0–90 (SINUMERIK P24; 0 = no check).
    pub clearance: Option<f64>,
}

/// Spindle limits.
#[derive(Clone, Copy, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Spindle {
    /// Speed at full output, rev/min.
    pub max_rpm: Option<u32>,
    /// G96 speed before any surface speed was given, rev/min.
    pub css_min_rpm: Option<u32>,
    /// Top speed of gears M41–M44, rev/min (0 = no limit).
    pub gear_max_rpm: Option<[u32; 4]>,
    /// Encoder counts per revolution (four per line).
    pub encoder_counts: Option<u32>,
    /// Acceleration of the spindle drive, rev/min per second.
    pub accel: Option<u32>,
}

/// A user M code.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct UserM {
    /// The M number.
    pub m: u16,
    /// `before` or `after` the block's motion.
    pub timing: TimingName,
}

/// When a user M code acts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum TimingName {
    /// Before the motion.
    Before,
    /// After the motion.
    After,
}

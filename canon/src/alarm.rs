//! Alarms: the one error type the interpreter reports to the operator.
//!
//! An alarm carries a code, the program line and what is wrong. Codes follow the
//! manual where it numbers an alarm (3576, 3577, 3605, 3607), FANUC's PS/OT numbers
//! where the manual only says "alarm" and FANUC has an equivalent, and 4000–4999 for
//! alarms of this controller with no FANUC counterpart. [`CATALOG`] is the one table
//! of every code; `lathe alarms` prints it and docs/ALARMS.md is generated from it.

use core::fmt;

use crate::text::{Text, text_table};

/// A program alarm: what went wrong, where. The block that raised it changed nothing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Alarm {
    /// O number of the program the block is in (0 = the main program as loaded,
    /// or MDI).
    pub program: u32,
    /// 1-based source line of the block that raised the alarm (0 when unknown or MDI).
    pub line: u32,
    /// What is wrong.
    pub kind: AlarmKind,
}

impl Alarm {
    /// An alarm of `kind` raised by the block on `line`.
    pub const fn new(line: u32, kind: AlarmKind) -> Self {
        Alarm { program: 0, line, kind }
    }

    /// An alarm of `kind` raised by the block on `line` of program O`program`.
    pub const fn in_program(program: u32, line: u32, kind: AlarmKind) -> Self {
        Alarm { program, line, kind }
    }

    /// The alarm number shown to the operator.
    pub fn code(&self) -> u16 {
        self.kind.code()
    }
}

impl fmt::Display for Alarm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.program != 0 {
            write!(f, "O{:04} ", self.program)?;
        }
        write!(f, "line {}: alarm {:04}: {}", self.line, self.code(), self.kind)
    }
}

/// An axis or address letter as written in the program (`b'X'`, `b'U'` …).
pub type Letter = u8;

pub use crate::text::GNum;

/// Everything that can be wrong with a block, one variant per alarm code.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum AlarmKind {
    /// 0003: a number has more digits than a word may hold.
    TooManyDigits { letter: Letter },
    /// 0004: a number, sign or symbol stands where an address letter was expected.
    AddressNotFound { found: u8 },
    /// 0005: an address letter is not followed by a value.
    NoDataAfterAddress { letter: Letter },
    /// 0006: a minus sign where the word takes no sign.
    IllegalMinusSign { letter: Letter },
    /// 0007: a decimal point where the word takes none (N, G04 P, T, M …).
    IllegalDecimalPoint { letter: Letter },
    /// 0009: an address letter this controller does not use.
    ImproperAddress { letter: Letter },
    /// 0009: an axis word for an axis this machine does not have.
    AxisNotConfigured { letter: Letter },
    /// 0010: a G code that does not exist in the selected G-code system.
    ImproperGCode { code: GNum },
    /// 0011: a cutting feed with F zero or never set.
    FeedZero,
    /// 0020: arc end point not on the circle (I/K form) or R shorter than half the chord.
    ArcRadiusTolerance { excess_nm: i64 },
    /// 0020: the end point of an ellipse or parabola is off every curve of the given
    /// size (2.4, 2.5).
    CurveEndOff { excess_nm: i64 },
    /// 0021: an axis outside the selected plane in an arc block (2.3 note 7, 2.13 note 5).
    ArcAxisOutsidePlane { letter: Letter },
    /// 0022: arc with neither R nor I/J/K (2.3 note 2, parameter 3403 = alarm).
    ArcCenterMissing,
    /// 0023: arc radius R of zero.
    ArcRadiusZero,
    /// 0030: offset number not in the tool offset table.
    IllegalOffsetNumber { number: u16 },
    /// 0030: tool number not on the turret.
    IllegalToolNumber { number: u16 },
    /// 0030: a mill's T above its tool count (`max`): the same alarm in the words
    /// of a machining centre, which has no turret.
    MillToolNumber { number: u16, max: u16 },
    /// 0032: a G10 offset value (or a work offset of G10 L20) outside the range
    /// the table holds (FANUC 0i-M PS0032).
    OffsetValueOutOfRange,
    /// 0044: G28, G29 or G30 while a hole cycle is in force (FANUC 0i-M PS0044).
    ReferenceInCycle,
    /// 0045: G73/G83 without a peck depth Q (FANUC 0i-M PS0045).
    PeckDepthMissing,
    /// 0046: G30 with P other than 1–4.
    IllegalReferenceNumber,
    /// 0076: M98 names a program that is not in program memory (3.1.6 note 1).
    ProgramNotFound { program: u32 },
    /// 0076: M98, G65 or G66 without P (3.1.6 note 4; FANUC 0i alarm 076).
    SubprogramNumberMissing,
    /// 0077: a subprogram or macro call deeper than 12 levels (3.1.6).
    CallNestingTooDeep,
    /// 0077: a macro call (G65, G66, a G or M code) deeper than 4 macro levels
    /// (FANUC 0i: 4 levels of macro calls within the 12 levels of calls).
    MacroNestingTooDeep,
    /// 0078: GOTO, M99 P or M91/M92 P names a sequence number the program lacks.
    JumpTargetNotFound { seq: u32 },
    /// 0111: a macro calculation overflowed the number range.
    MacroOverflow,
    /// 0112: division by zero in a macro expression (`/`, MOD, TAN of 90°).
    DivideByZero,
    /// 0114: a malformed macro expression or statement.
    MacroFormat { what: &'static str },
    /// 0115: a variable number outside 0–999.
    VariableNumberOutOfRange { number: i32 },
    /// 0116: assignment to #0, which is always null (2.24.1).
    WriteProtectedVariable { number: u16 },
    /// 0118: brackets nested deeper than 5 levels.
    TooManyBrackets,
    /// 0119: a function argument outside its domain (ASIN/ACOS, SQRT, EXP …).
    ArgumentOutOfRange { function: &'static str },
    /// 0122: a fourth G66 while three modal calls are in force (FANUC 0i alarm 122).
    ModalCallsTooDeep,
    /// 0123: GOTO, WHILE, DO or END in MDI.
    ControlInMdi,
    /// 0124: WHILE/DO without a matching END (2.24.2).
    MissingEnd { label: u8 },
    /// 0124: END without a DO of the same number open.
    EndWithoutDo { label: u8 },
    /// 0124: DO ranges that overlap (note 4) or the same number nested.
    LoopsCrossed { label: u8 },
    /// 0126: a DO/END number other than 1, 2, 3 (note 3).
    IllegalLoopNumber { label: u32 },
    /// 0127: a macro statement and NC words in one block (note 7).
    MacroAndNcInOneBlock,
    /// 0128: a GOTO target that is not a whole number 1–99999 (note 1).
    SequenceOutOfRange,
    /// 0129: an address that cannot be an argument of a macro call (G, N, O; P
    /// of a call by G or M code; an eleventh I/J/K group; FANUC 0i alarm 129).
    IllegalArgumentAddress { letter: Letter },
    /// 0142: a G51 scale factor outside 0.001–999.999 (P) or ±0.001–±9.999 (I/J/K),
    /// or zero (FANUC 0i-M PS0142; seed 004 @4506, @4740).
    IllegalScale { letter: Letter },
    /// 0212: a plane change, or an arc outside the rotation plane, while G68 rotates
    /// the coordinates (FANUC 0i-M PS0212).
    RotationPlaneChange,
    /// 0224: G28/G30 before the axis has been referenced (2.11.2 note 2).
    ReferenceNotEstablished { letter: Letter },
    /// 0500: the move would pass the positive soft limit.
    OvertravelPositive { letter: Letter },
    /// 0501: the move would pass the negative soft limit.
    OvertravelNegative { letter: Letter },
    /// 0502/0503: a move would enter the forbidden area of stored stroke check 2 (G22, 2.10).
    StrokeLimit2 { letter: Letter, plus: bool },
    /// 5010: the program text ended without M02, M30 or M99.
    EndOfRecord,
    /// 4001: G20/G21 must stand alone in its block (2.9 note 2).
    UnitsNotAlone,
    /// 4002: G20/G21 after the program started moving (2.9 note 2).
    UnitsNotAtStart,
    /// 4003: two G codes of one modal group in a block.
    DuplicateGroup { first: GNum, second: GNum },
    /// 4004: an address given twice in one block.
    DuplicateAddress { letter: Letter },
    /// 4005: a word that the block's codes do not use.
    WordNotAllowed { letter: Letter, context: &'static str },
    /// 4006: a word the block's code requires is missing.
    MissingWord { letter: Letter, context: &'static str },
    /// 4007: a code this controller recognises but does not implement yet.
    NotSupportedYet { what: &'static str },
    /// 4007: a language or machine kind this firmware was built without (a cargo
    /// feature of the board's build, docs/FIRMWARE-SIZES.md).
    NotInThisBuild { what: &'static str },
    /// 4008: an M code neither in the manual's tables nor configured as a user output.
    UnknownMCode { m: u16 },
    /// 4009: two M codes of a block contradict each other (M03 with M04 …).
    ConflictingMCodes { first: u16, second: u16 },
    /// 4010: more M codes in a block than the controller executes at once (3).
    TooManyMCodes,
    /// 4011: a value outside the range the word accepts.
    ValueOutOfRange { letter: Letter },
    /// 4012: G50 coordinate setting is disabled by parameter 5152.
    CoordinateSettingDisabled,
    /// 4013: feed per revolution (G99) commanded while the spindle is stopped.
    FeedPerRevSpindleStopped,
    /// 4014: a comment `(` without its closing `)`.
    CommentNotClosed,
    /// 4015: G53 takes absolute X/Z only.
    MachineCoordinatesIncremental,
    /// 4015: G52 under G91 on a mill: its words are the local origin's position in
    /// the work frame (seed 004 @2362), never a distance.
    LocalFrameIncremental,
    /// 4016: a G code that must be alone in its block shares it (G04 with motion …).
    CodeMustBeAlone { code: GNum },
    /// 4017: a value or position that does not fit the controller's number range.
    Overflow,
    /// 4018: a `/` block skip in the middle of a block.
    MisplacedBlockSkip,
    /// 4019: a character that cannot start a word (`?`, `@`, `$` …).
    IllegalCharacter { found: u8 },
    /// 4020: an axis given both absolute and incremental (X with U, Z with W).
    AxisTwice { absolute: Letter, incremental: Letter },
    /// 4040: M98 calls the program it is in (3.1.6 note 3).
    SelfCall { program: u32 },
    /// 4041: M98/M99/M91/M92 in MDI (3.1.6 note 2).
    FlowInMdi { m: u16 },
    /// 4042: M99 shares its block with other codes (3.1.7 note 1).
    M99NotAlone,
    /// 4043: the external input M91/M92 test does not exist on this machine.
    InputNotAvailable { input: u16 },
    /// 4050: more of the variables #34–#400 and #601–#999 would hold a value at
    /// once than the controller keeps (they are stored only while not null).
    VariablesFull,
    /// 0014: thread lead zero or out of range, G34 K out of range, or a G34 lead that
    /// would become zero, negative or exceed the maximum (2.17.2).
    IllegalLead,
    /// 0061: a G70–G73 block without P or Q (2.16.7 note 1).
    CycleAddressMissing { letter: Letter },
    /// 0062: an illegal value in a G71–G76 block (depth, count, angle, relief …).
    CycleValueIllegal { what: &'static str },
    /// 0063: the sequence number named by P or Q of G70–G73 is not in the program.
    SequenceNotFound { n: u32 },
    /// 0064: the finishing shape of G71/G72 is not monotone along the cutting axis.
    ProfileNotMonotone,
    /// 0065: the ns block of G71–G73 lacks G00/G01, or moves the wrong axis (2.16.7 note 2).
    ProfileFirstBlock,
    /// 0066: a code not allowed between ns and nf of G71–G73 (2.16.7 note 3).
    ProfileForbiddenCode { what: &'static str },
    /// 0200: rigid tapping without a spindle speed S in the M29 block (2.22.1).
    RigidTapSpeed,
    /// 0203: S between M29 and G84/G88, or M29 repeated (2.22.1).
    RigidTapSequence,
    /// 0204: axis motion between M29 and G84/G88 (2.22.1).
    RigidTapAxisMove,
    /// 0329: the type I finishing shape of G71/G72 is not monotone along the infeed axis.
    ProfileNotMonotoneInfeed,
    /// 4030: single cycle taper |R| larger than |U/2| (G90/G92) or |W| (G94) with opposite signs (2.15).
    CycleTaperTooLarge,
    /// 4031: G70–G76, G90/G92/G94 outside the ZX plane (2.13 note 4).
    CycleNotInZxPlane,
    /// 4032: a cycle block moves an axis other than X/Z (2.15 note 1).
    CycleOtherAxis { letter: Letter },
    /// 4033: thread start angle Q outside 0–360° (2.17.1).
    ThreadStartAngle,
    /// 4034: thread pull-out longer than the thread along its long axis (2.17.3 note 5, 2.17.4 note 8).
    ThreadPulloutTooLong,
    /// 4035: the finishing shape of G70–G73 has more segments than the controller holds.
    ProfileTooLong,
    /// 4036: a type II finishing shape with more than 10 pockets (2.16.1).
    TooManyPockets,
    /// 4037: a cycle that would plan more than a million moves.
    CycleTooLong,
    /// 4501: lead × spindle speed is faster than the thread axis may move.
    ThreadTooFast { letter: Letter },
    /// 4502: the thread's acceleration or deceleration ramp is longer than the thread block.
    ThreadRampTooLong,
    /// 4503: a spindle-synchronised move or feed per revolution with the spindle not turning.
    SpindleNotTurning,
    /// 4504: the spindle did not reach its commanded speed in time.
    SpindleNotAtSpeed,
    /// 4505: lead × spindle speed or acceleration is more than the tapping axis can follow.
    TapTooFast { letter: Letter },
    /// 4506: no spindle index pulse where a thread pass must synchronise.
    SpindleIndexMissing,
    /// 4507: a continuing thread or tap block whose locked predecessor is missing or has
    /// ended, or a tap that does not return to where it started.
    SyncSequenceBroken,
    /// 4508: the machine's motion configuration is unusable (a zero step ratio …).
    MotionConfigInvalid { what: &'static str },
    /// 4509: emergency stop.
    EmergencyStop,
    /// 4510: a G34 lead change K × spindle speed² (the constant acceleration of a
    /// variable-lead thread) takes more than half the long axis's acceleration.
    ThreadLeadChangeTooFast { letter: Letter },
    /// 4511: a machining centre's automatic tool changer did not answer "done"
    /// within `seconds` (`$313`) of the board's request for tool `tool` (M06).
    ToolChangeTimeout { tool: u16, seconds: u16 },
    /// 4601: a streamed job starved: open, its text and motion run out, and no byte
    /// came over the link for `seconds` (the link was lost mid-stream).
    StreamStarved { seconds: u32 },
    /// 0050: `,C`/`,R` in a thread block (2.23 note 8).
    ChamferInThread,
    /// 0051: the block after a `,C`/`,R` block is not a G01/G02/G03 move (2.23 notes 2, 7).
    ChamferNoMove { what: &'static str },
    /// 0055: a chamfer or corner R longer than the moves it joins (2.23 note 3).
    ChamferTooLarge,
    /// 0212: plane selection after a `,C`/`,R` block, or a move leaving the plane (2.23 note 4).
    ChamferPlaneChange,
    /// 4045: a G code polar interpolation does not allow (2.7 note 4).
    PolarCodeNotAllowed { code: GNum },
    /// 4046: an arc in the polar plane without R, or with I/J/K (2.7 note 6).
    PolarArcNeedsR,
    /// 4047: G51.2 polygon turning on a machine without a synchronised tool spindle (2.8 note 6).
    PolygonNoToolSpindle,
    /// 0220: a C (tool-spindle) move programmed in polygon turning (2.8 note 11).
    PolygonAxisCommanded,
    /// 0221: a function that needs the C axis or the spindle in position control
    /// while polygon turning runs, or G51.2 during it (2.8 notes 6, 9).
    PolygonModeConflict {
        /// What conflicts.
        what: &'static str,
    },
    /// 4044: more actions wait behind a held move than the look-ahead holds.
    ContourBufferFull,
    /// 4048: G29 without a G28 intermediate point for an axis it moves.
    NoIntermediatePoint { letter: Letter },
    /// 4049: G15/G16, G50/G51, G50.1/G51.1 or G68/G69 while cutter compensation is
    /// in force.
    FrameInCutterComp,
    /// 4051: G51.1/G50.1 while scaling or rotation is in force, or G51/G50 while
    /// rotation is (FANUC's order: mirror, scaling, rotation; cancel the other way).
    FrameOrder,
    /// 0034: nose compensation starting up or cancelling in an arc block (2.18.3).
    NoseCompArc,
    /// 0037: plane selection while nose compensation is active.
    NoseCompPlaneChange,
    /// 3576: reversing G41/G42 directly while compensating (2.18.4).
    NoseCompReversed,
    /// 3577: T code while nose compensation is active (2.18.4).
    ToolChangeInNoseComp,
    /// 3605: nose compensation would gouge the part (2.18.4).
    NoseCompGouge,
    /// 3607: nose compensation corner angle under 0.1° (2.18.4).
    NoseCompCornerAngle,
    /// A SINUMERIK alarm ([`SiemensAlarm`]).
    Siemens(SiemensAlarm),
    /// A SINUMERIK cycle alarm, 61000–61999 ([`CycleAlarm`]).
    SiemensCycle(CycleAlarm),
}

impl AlarmKind {
    /// Whether the alarm may only mean that program text has not arrived yet: the
    /// end of the text, a jump target, END, shape block, label or PROC further on.
    /// A stream waits for more text and reads the block again before it calls
    /// it an alarm.
    pub fn waits_for_text(&self) -> bool {
        matches!(
            self,
            AlarmKind::EndOfRecord
                | AlarmKind::JumpTargetNotFound { .. }
                | AlarmKind::MissingEnd { .. }
                | AlarmKind::SequenceNotFound { .. }
                | AlarmKind::Siemens(SiemensAlarm::LabelNotFound | SiemensAlarm::SubprogramNotFound)
        )
    }

    /// The alarm number.
    pub fn code(&self) -> u16 {
        use AlarmKind::*;
        match self {
            TooManyDigits { .. } => 3,
            AddressNotFound { .. } => 4,
            NoDataAfterAddress { .. } => 5,
            IllegalMinusSign { .. } => 6,
            IllegalDecimalPoint { .. } => 7,
            ImproperAddress { .. } | AxisNotConfigured { .. } => 9,
            ImproperGCode { .. } => 10,
            FeedZero => 11,
            ArcRadiusTolerance { .. } | CurveEndOff { .. } => 20,
            ArcAxisOutsidePlane { .. } => 21,
            ArcCenterMissing => 22,
            ArcRadiusZero => 23,
            IllegalOffsetNumber { .. } | IllegalToolNumber { .. } | MillToolNumber { .. } => 30,
            IllegalReferenceNumber => 46,
            ProgramNotFound { .. } | SubprogramNumberMissing => 76,
            CallNestingTooDeep | MacroNestingTooDeep => 77,
            JumpTargetNotFound { .. } => 78,
            MacroOverflow => 111,
            DivideByZero => 112,
            MacroFormat { .. } => 114,
            VariableNumberOutOfRange { .. } => 115,
            WriteProtectedVariable { .. } => 116,
            TooManyBrackets => 118,
            ArgumentOutOfRange { .. } => 119,
            ModalCallsTooDeep => 122,
            ControlInMdi => 123,
            MissingEnd { .. } | EndWithoutDo { .. } | LoopsCrossed { .. } => 124,
            IllegalLoopNumber { .. } => 126,
            MacroAndNcInOneBlock => 127,
            SequenceOutOfRange => 128,
            IllegalArgumentAddress { .. } => 129,
            ReferenceNotEstablished { .. } => 224,
            OvertravelPositive { .. } => 500,
            OvertravelNegative { .. } => 501,
            StrokeLimit2 { plus: true, .. } => 502,
            StrokeLimit2 { plus: false, .. } => 503,
            EndOfRecord => 5010,
            UnitsNotAlone => 4001,
            UnitsNotAtStart => 4002,
            DuplicateGroup { .. } => 4003,
            DuplicateAddress { .. } => 4004,
            WordNotAllowed { .. } => 4005,
            MissingWord { .. } => 4006,
            NotSupportedYet { .. } | NotInThisBuild { .. } => 4007,
            UnknownMCode { .. } => 4008,
            ConflictingMCodes { .. } => 4009,
            TooManyMCodes => 4010,
            ValueOutOfRange { .. } => 4011,
            CoordinateSettingDisabled => 4012,
            FeedPerRevSpindleStopped => 4013,
            CommentNotClosed => 4014,
            MachineCoordinatesIncremental | LocalFrameIncremental => 4015,
            CodeMustBeAlone { .. } => 4016,
            Overflow => 4017,
            MisplacedBlockSkip => 4018,
            IllegalCharacter { .. } => 4019,
            AxisTwice { .. } => 4020,
            SelfCall { .. } => 4040,
            FlowInMdi { .. } => 4041,
            M99NotAlone => 4042,
            InputNotAvailable { .. } => 4043,
            VariablesFull => 4050,
            IllegalLead => 14,
            CycleAddressMissing { .. } => 61,
            CycleValueIllegal { .. } => 62,
            SequenceNotFound { .. } => 63,
            ProfileNotMonotone => 64,
            ProfileFirstBlock => 65,
            ProfileForbiddenCode { .. } => 66,
            RigidTapSpeed => 200,
            RigidTapSequence => 203,
            RigidTapAxisMove => 204,
            ProfileNotMonotoneInfeed => 329,
            CycleTaperTooLarge => 4030,
            CycleNotInZxPlane => 4031,
            CycleOtherAxis { .. } => 4032,
            ThreadStartAngle => 4033,
            ThreadPulloutTooLong => 4034,
            ProfileTooLong => 4035,
            TooManyPockets => 4036,
            CycleTooLong => 4037,
            ThreadTooFast { .. } => 4501,
            ThreadRampTooLong => 4502,
            SpindleNotTurning => 4503,
            SpindleNotAtSpeed => 4504,
            TapTooFast { .. } => 4505,
            SpindleIndexMissing => 4506,
            SyncSequenceBroken => 4507,
            MotionConfigInvalid { .. } => 4508,
            EmergencyStop => 4509,
            ThreadLeadChangeTooFast { .. } => 4510,
            ToolChangeTimeout { .. } => 4511,
            StreamStarved { .. } => 4601,
            ChamferInThread => 50,
            ChamferNoMove { .. } => 51,
            ChamferTooLarge => 55,
            ChamferPlaneChange | RotationPlaneChange => 212,
            NoIntermediatePoint { .. } => 4048,
            FrameInCutterComp => 4049,
            FrameOrder => 4051,
            OffsetValueOutOfRange => 32,
            ReferenceInCycle => 44,
            PeckDepthMissing => 45,
            IllegalScale { .. } => 142,
            ContourBufferFull => 4044,
            PolarCodeNotAllowed { .. } => 4045,
            PolarArcNeedsR => 4046,
            PolygonNoToolSpindle => 4047,
            PolygonAxisCommanded => 220,
            PolygonModeConflict { .. } => 221,
            NoseCompArc => 34,
            NoseCompPlaneChange => 37,
            NoseCompReversed => 3576,
            ToolChangeInNoseComp => 3577,
            NoseCompGouge => 3605,
            NoseCompCornerAngle => 3607,
            Siemens(k) => k.code(),
            SiemensCycle(k) => k.code(),
        }
    }
}

text_table! {
    /// The texts of the alarms every build raises (`{}`: the arguments that follow).
    AlarmKind, fn fanuc_text, static FANUC {
        TooManyDigits { letter } => "too many digits in {} word", Ch(letter);
        AddressNotFound { found } => "'{}' where an address letter was expected", Ch(found);
        NoDataAfterAddress { letter } => "no value after address {}", Ch(letter);
        IllegalMinusSign { letter } => "address {} takes no minus sign", Ch(letter);
        IllegalDecimalPoint { letter } => "address {} takes no decimal point", Ch(letter);
        ImproperAddress { letter } => "address {} is not used by this controller", Ch(letter);
        AxisNotConfigured { letter } => "axis {} is not configured on this machine", Ch(letter);
        ImproperGCode { code } => "{} is not a G code of the selected G-code system", G(code);
        FeedZero {} => "cutting feed F is zero or was never given";
        ArcRadiusTolerance { excess_nm } => "arc end point is {} mm off the circle (R too small or I/J/K inconsistent)", Mm(excess_nm);
        CurveEndOff { excess_nm } => "end point is {} mm off every ellipse/parabola of the given A, B or P", Mm(excess_nm);
        ArcAxisOutsidePlane { letter } => "axis {} is outside the arc's plane", Ch(letter);
        ArcCenterMissing {} => "arc needs R or I/J/K";
        ArcRadiusZero {} => "arc radius R is zero";
        IllegalOffsetNumber { number } => "tool offset number {} is not in the offset table", Num(number);
        IllegalToolNumber { number } => "tool number {} is not on the turret", Num(number);
        IllegalReferenceNumber {} => "G30 P must be 1, 2, 3 or 4";
        ProgramNotFound { program } => "program O{} not found", Z4(program);
        SubprogramNumberMissing {} => "M98, G65 and G66 need P with the program number";
        CallNestingTooDeep {} => "subprograms and macros nested deeper than 12 levels";
        MacroNestingTooDeep {} => "macro calls (G65, G66, G or M code) nested deeper than 4 levels";
        JumpTargetNotFound { seq } => "sequence number N{} not found", Num(seq);
        MacroOverflow {} => "macro calculation out of the number range";
        DivideByZero {} => "division by zero (/, MOD or TAN of 90 degrees)";
        MacroFormat { what } => "macro format error: {}", Str(what);
        VariableNumberOutOfRange { number } => "variable #{} does not exist (0-999)", Num(number);
        WriteProtectedVariable { number } => "variable #{} cannot be assigned", Num(number);
        TooManyBrackets {} => "brackets nested deeper than 5 levels";
        ArgumentOutOfRange { function } => "argument of {} out of range", Str(function);
        ModalCallsTooDeep {} => "a fourth modal call G66 while three are in force";
        ControlInMdi {} => "GOTO, WHILE, DO and END cannot be used in MDI";
        MissingEnd { label } => "DO{} has no matching END{}", Num(label), Num(label);
        EndWithoutDo { label } => "END{} without DO{}", Num(label), Num(label);
        LoopsCrossed { label } => "loop {} overlaps another DO-END range", Num(label);
        IllegalLoopNumber { label } => "loop number {} is not 1, 2 or 3", Num(label);
        MacroAndNcInOneBlock {} => "macro statement and NC words in one block";
        SequenceOutOfRange {} => "jump target is not a sequence number 1-99999";
        IllegalArgumentAddress { letter } => "address {} cannot be a macro call argument", Ch(letter);
        ReferenceNotEstablished { letter } => "axis {} has not been referenced (home it before G28/G30)", Ch(letter);
        OvertravelPositive { letter } => "move exceeds the + soft limit of axis {}", Ch(letter);
        OvertravelNegative { letter } => "move exceeds the - soft limit of axis {}", Ch(letter);
        StrokeLimit2 { letter, plus } => "move enters the forbidden area of stored stroke check 2 (G22) in {} {}", Str(if plus { "+" } else { "-" }), Ch(letter);
        EndOfRecord {} => "program ended without M02, M30 or M99";
        UnitsNotAlone {} => "G20/G21 must be alone in its block";
        UnitsNotAtStart {} => "G20/G21 only at the start of the program, before any move";
        DuplicateGroup { first, second } => "{} and {} are of the same modal group", G(first), G(second);
        DuplicateAddress { letter } => "address {} given twice", Ch(letter);
        WordNotAllowed { letter, context } => "address {} is not used by {}", Ch(letter), Str(context);
        MissingWord { letter, context } => "{} needs address {}", Str(context), Ch(letter);
        NotSupportedYet { what } => "{} is not supported yet", Str(what);
        NotInThisBuild { what } => "{} not in this build", Str(what);
        UnknownMCode { m } => "M{} is not a known M code", Z2(m);
        ConflictingMCodes { first, second } => "M{} and M{} contradict each other", Z2(first), Z2(second);
        TooManyMCodes {} => "more than 3 M codes in one block";
        ValueOutOfRange { letter } => "value of {} out of range", Ch(letter);
        CoordinateSettingDisabled {} => "G50 coordinate setting is disabled (parameter 5152)";
        FeedPerRevSpindleStopped {} => "feed per revolution or tapping with the spindle stopped";
        CommentNotClosed {} => "comment '(' is not closed";
        MachineCoordinatesIncremental {} => "G53 takes absolute coordinates only";
        CodeMustBeAlone { code } => "{} must not share its block with other G codes or moves", G(code);
        Overflow {} => "value out of the controller's range";
        MisplacedBlockSkip {} => "block skip '/' only at the start of a block";
        IllegalCharacter { found } => "illegal character '{}'", Ch(found);
        AxisTwice { absolute, incremental } => "{} and {} address the same axis in one block", Ch(absolute), Ch(incremental);
        SelfCall { program } => "O{} calls itself with M98", Z4(program);
        FlowInMdi { m } => "M{} cannot be used in MDI", Z2(m);
        M99NotAlone {} => "M99 must be alone in its block (N and P only)";
        InputNotAvailable { input } => "external input {} for M91/M92 does not exist", Num(input);
        VariablesFull {} => "more than 128 of the variables #34-#400 and #601-#999 hold values";
        IllegalLead {} => "thread lead zero, out of range or becoming negative (G34 K)";
        CycleAddressMissing { letter } => "G70-G73 needs address {}", Ch(letter);
        CycleValueIllegal { what } => "illegal value in cycle: {}", Str(what);
        SequenceNotFound { n } => "sequence number N{} of the cycle not found in the program", Num(n);
        ProfileNotMonotone {} => "finishing shape is not monotone along the cutting axis";
        ProfileFirstBlock {} => "first block of the finishing shape must be G00/G01 moving the infeed axis";
        ProfileForbiddenCode { what } => "{} is not allowed in the finishing shape (ns-nf)", Str(what);
        RigidTapSpeed {} => "rigid tapping needs S in the M29 block";
        RigidTapSequence {} => "S or a repeated M29 between M29 and G84/G88";
        RigidTapAxisMove {} => "axis motion between M29 and G84/G88";
        ProfileNotMonotoneInfeed {} => "type I finishing shape is not monotone along the infeed axis (use X and Z in ns for type II)";
        CycleTaperTooLarge {} => "taper R larger than the cut depth with opposite sign";
        CycleNotInZxPlane {} => "turning and threading cycles work in the ZX plane (G18) only";
        CycleOtherAxis { letter } => "axis {} cannot move in a turning cycle block", Ch(letter);
        ThreadStartAngle {} => "thread start angle Q must be 0 to 360 degrees";
        ThreadPulloutTooLong {} => "thread pull-out is longer than the thread";
        ProfileTooLong {} => "finishing shape has too many segments";
        TooManyPockets {} => "finishing shape has more than 10 pockets";
        CycleTooLong {} => "cycle would make more than a million moves (P/Q without a point are least increments)";
        ThreadTooFast { letter } => "thread lead x spindle speed exceeds the speed limit of axis {}", Ch(letter);
        ThreadRampTooLong {} => "thread acceleration ramp does not fit in the thread (lengthen lead-in/run-out)";
        SpindleNotTurning {} => "spindle is not turning (thread, tap or feed per revolution)";
        SpindleNotAtSpeed {} => "spindle did not reach the commanded speed";
        TapTooFast { letter } => "tap lead x spindle speed or acceleration exceeds the limits of axis {}", Ch(letter);
        SpindleIndexMissing {} => "no spindle index pulse to synchronise the thread";
        SyncSequenceBroken {} => "spindle-locked sequence broken (continuing thread or tap without its start)";
        MotionConfigInvalid { what } => "motion configuration invalid: {}", Str(what);
        EmergencyStop {} => "emergency stop";
        ThreadLeadChangeTooFast { letter } => "G34 lead change K x spindle speed squared exceeds half the acceleration of axis {}", Ch(letter);
        StreamStarved { seconds } => "stream starved: the job is open and nothing came over the link for {} s (link lost?)", Num(seconds);
        ChamferInThread {} => "chamfer or corner R (,C/,R) cannot be given in a thread block";
        ChamferNoMove { what } => "no G01/G02/G03 move after chamfer/corner R: {}", Str(what);
        ChamferTooLarge {} => "chamfer or corner R is larger than the moves it joins";
        ChamferPlaneChange {} => "plane selection or a move out of the plane after chamfer/corner R";
        ContourBufferFull {} => "too many actions between a held move and the next move";
        PolarCodeNotAllowed { code } => "{} is not allowed in polar interpolation (G12.1)", G(code);
        PolarArcNeedsR {} => "arcs in polar interpolation take R, not I/J/K";
        PolygonNoToolSpindle {} => "polygon turning (G51.2) needs a tool spindle synchronised to the work spindle";
        PolygonAxisCommanded {} => "the tool spindle (C) cannot be moved in polygon turning (G51.2)";
        PolygonModeConflict { what } => "{} in polygon turning (G51.2)", Str(what);
        NoseCompArc {} => "radius compensation cannot start up or cancel in an arc block";
        NoseCompPlaneChange {} => "plane selection while radius compensation is active";
        NoseCompReversed {} => "G41/G42 reversed while radius compensation is active";
        ToolChangeInNoseComp {} => "tool change (lathe T, mill M06) while radius compensation is active";
        NoseCompGouge {} => "radius compensation would gouge the part";
        NoseCompCornerAngle {} => "radius compensation corner angle below 0.1 degrees";
    }
}

#[cfg(feature = "mill")]
text_table! {
    /// The texts of the alarms only the machining-centre profile raises.
    AlarmKind, fn mill_text, static MILL {
        RotationPlaneChange {} => "plane change or an arc outside the plane of G68 rotation";
        NoIntermediatePoint { letter } => "G29 moves axis {} but no G28 gave it an intermediate point", Ch(letter);
        FrameInCutterComp {} => "G15/G16, G50/G51, G50.1/G51.1 and G68/G69 only with cutter compensation cancelled (G40)";
        FrameOrder {} => "G51.1 before G51 before G68, cancelled the other way round (G69, then G50, then G50.1)";
        OffsetValueOutOfRange {} => "G10 offset value out of range";
        LocalFrameIncremental {} => "G52 takes absolute coordinates only (G90): the local origin in the work frame";
        MillToolNumber { number, max } => "tool number T{} is not on this machine (T1-T{})", Num(number), Num(max);
        ReferenceInCycle {} => "G28/G29/G30 while a hole cycle is in force (G80 first)";
        PeckDepthMissing {} => "G73/G83 need a peck depth Q greater than zero";
        IllegalScale { letter } => "scale factor {} out of range (P 0.001-999.999, I/J/K +-0.001-9.999)", Ch(letter);
        ToolChangeTimeout { tool, seconds } => "tool changer did not report done within {} s of the request for T{} ($313; ATC done input)", Num(seconds), Z2(tool);
    }
}

/// The text tables of this build (the tests prove each text unpacks to its row).
#[cfg(test)]
pub(crate) static TABLES: &[&crate::text::Table] = &[
    &FANUC,
    #[cfg(feature = "mill")]
    &MILL,
    #[cfg(feature = "siemens")]
    &SIEMENS,
    #[cfg(feature = "siemens")]
    &CYCLE,
];

impl AlarmKind {
    /// What the alarm says: its packed text and the values in it.
    pub fn text(&self) -> Text {
        #[allow(unused_imports)]
        use AlarmKind::*;
        match *self {
            #[cfg(feature = "siemens")]
            Siemens(k) => k.text(),
            #[cfg(feature = "siemens")]
            SiemensCycle(k) => k.text(),
            #[cfg(feature = "mill")]
            RotationPlaneChange
            | NoIntermediatePoint { .. }
            | FrameInCutterComp
            | FrameOrder
            | OffsetValueOutOfRange
            | ReferenceInCycle
            | PeckDepthMissing
            | MillToolNumber { .. }
            | LocalFrameIncremental
            | IllegalScale { .. }
            | ToolChangeTimeout { .. } => self.mill_text(),
            _ => self.fanuc_text(),
        }
    }
}

impl fmt::Display for AlarmKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        #[allow(unused_imports)]
        use AlarmKind::*;
        match *self {
            // A build without SINUMERIK mode never raises these: their texts stay out
            // of its flash.
            #[cfg(not(feature = "siemens"))]
            Siemens(_) | SiemensCycle(_) => f.write_str("SINUMERIK alarm (SINUMERIK mode is not in this build)"),
            // Without the machining-centre profile (feature `mill`) nothing raises
            // these: their texts stay out of the image (the code still names them).
            #[cfg(not(feature = "mill"))]
            RotationPlaneChange
            | NoIntermediatePoint { .. }
            | FrameInCutterComp
            | FrameOrder
            | OffsetValueOutOfRange
            | ReferenceInCycle
            | PeckDepthMissing
            | MillToolNumber { .. }
            | LocalFrameIncremental
            | IllegalScale { .. }
            | ToolChangeTimeout { .. } => f.write_str("machining-centre alarm"),
            _ => self.text().write(f),
        }
    }
}

/// The alarms of the SINUMERIK front end and cycles, with the 840D's numbers
/// (12xxx–17xxx of the NC, 61xxx/62xxx of the cycles; 4xxx where the 840D has no
/// equivalent). Nested in [`AlarmKind::Siemens`]: [`AlarmKind`] stays under 128
/// variants — past 128 every FANUC block costs 3 more Cortex-M4 instructions
/// (measured with `m4-tests/bench.sh bench_interp`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum SiemensAlarm {
    /// 12080: a SINUMERIK block that cannot be read (the 840D's "syntax error").
    SyntaxError { what: &'static str },
    /// 12150: an operation or assignment the value's data type does not allow
    /// (a string in arithmetic, a number for a STRING).
    TypeMismatch,
    /// 12160: a value outside the range of its type or use (INT beyond 32 bits, a
    /// CHAR beyond 255, a number of passes beyond 9999).
    ValueRange,
    /// 12160: a string longer than its STRING variable or the call's argument space.
    StringTooLong,
    /// 12170: a name defined twice in one program level.
    NameDefinedTwice,
    /// 12330: a cycle or subprogram argument whose type does not convert to its
    /// parameter's (seed 001 line 649); `index` counts from 1.
    ParameterType { index: u8 },
    /// 12340: more arguments than the cycle or subprogram has parameters (seed 001 line 596).
    TooManyParameters,
    /// 12460: more DEF variables (or names) than the controller holds.
    TooManySymbols,
    /// 12470: a G function the SINUMERIK table does not hold.
    UnknownGFunction { code: u16 },
    /// 12550: a name that is neither a variable, a keyword nor a program.
    NameNotDefined,
    /// 14011: a subprogram or contour program that is not in program memory.
    SubprogramNotFound,
    /// 14012: subprograms (and REPEAT sections) nested deeper than the controller holds.
    SubprogramLevels,
    /// 14080: a GOTOF/GOTOB/GOTO or REPEAT label (or contour label) not in the program.
    LabelNotFound,
    /// 14500: DEF after the program's first NC block, or PROC not at its start.
    DefNotAtStart,
    /// 14510: a subprogram called with arguments has no PROC statement with parameters.
    ProcMissing,
    /// 16420: an axis programmed twice in one block.
    AxisProgrammedTwice { letter: Letter },
    /// 17020: an array index (R[n], _ZSD[n], $TC_DP…[t,d]) outside the array.
    IndexOutOfRange,
    /// 17180: a D number (cutting edge) with no offset row.
    IllegalDNumber { number: u16 },
    /// 4052: MCALL inside a modally called subprogram (seed 001 line 3027: modal
    /// calls do not nest).
    ModalCallNested,
}

impl From<SiemensAlarm> for AlarmKind {
    fn from(k: SiemensAlarm) -> Self {
        AlarmKind::Siemens(k)
    }
}

impl SiemensAlarm {
    /// The alarm number.
    pub fn code(&self) -> u16 {
        use SiemensAlarm::*;
        match self {
            SyntaxError { .. } => 12080,
            TypeMismatch => 12150,
            ValueRange | StringTooLong => 12160,
            NameDefinedTwice => 12170,
            ParameterType { .. } => 12330,
            TooManyParameters => 12340,
            TooManySymbols => 12460,
            UnknownGFunction { .. } => 12470,
            NameNotDefined => 12550,
            SubprogramNotFound => 14011,
            SubprogramLevels => 14012,
            LabelNotFound => 14080,
            DefNotAtStart => 14500,
            ProcMissing => 14510,
            AxisProgrammedTwice { .. } => 16420,
            IndexOutOfRange => 17020,
            IllegalDNumber { .. } => 17180,
            ModalCallNested => 4052,
        }
    }
}

/// The alarms of the SINUMERIK standard cycles (seed 001 table 5.3, 61000–61999:
/// cleared by NC reset, the block interrupted), with the document's texts.
/// Nested in [`AlarmKind::SiemensCycle`]: [`AlarmKind`] stays under 128 variants
/// (more cost every FANUC block Cortex-M4 instructions).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum CycleAlarm {
    /// 61000: SINUMERIK cycle alarm (seed 001 table 5.3): no tool offset active.
    NoToolOffset,
    /// 61001: SINUMERIK cycle alarm (seed 001 table 5.3): thread pitch wrong.
    ThreadPitchWrong,
    /// 61002: SINUMERIK cycle alarm (seed 001 table 5.3): machining type wrong.
    MachiningTypeWrong,
    /// 61003: SINUMERIK cycle alarm (seed 001 table 5.3): no feed programmed in the cycle.
    NoFeed,
    /// 61005: SINUMERIK cycle alarm (seed 001 table 5.3): 3rd geometry axis not present.
    NoThirdAxis,
    /// 61009: SINUMERIK cycle alarm (seed 001 table 5.3): active tool number = 0.
    ToolNumberZero,
    /// 61011: SINUMERIK cycle alarm (seed 001 table 5.3): scaling not allowed (CYCLE71).
    ScaleNotAllowed,
    /// 61012: SINUMERIK cycle alarm (seed 001 table 5.3): different scaling in the plane
    /// (CYCLE76, CYCLE77).
    ScaleDiffers,
    /// 61019: SINUMERIK cycle alarm (seed 001 table 5.3): parameter programmed incorrectly.
    ParameterWrong,
    /// 61101: SINUMERIK cycle alarm (seed 001 table 5.3): reference plane defined incorrectly.
    ReferencePlaneWrong,
    /// 61102: SINUMERIK cycle alarm (seed 001 table 5.3): no spindle direction programmed.
    NoSpindleDirection,
    /// 61103: SINUMERIK cycle alarm (seed 001 line 3107, table 5.3): number of holes is zero.
    HoleCountZero,
    /// 61104: SINUMERIK cycle alarm (seed 001 table 5.3): contour violation of slots/elongated holes.
    SlotContourViolated,
    /// 61105: SINUMERIK cycle alarm (seed 001 table 5.3): milling cutter radius too large.
    CutterRadiusTooLarge,
    /// 61106: SINUMERIK cycle alarm (seed 001 table 5.3): number or spacing of circle elements.
    CircleElements,
    /// 61107: SINUMERIK cycle alarm (seed 001 line 1803): first drilling depth defined incorrectly.
    FirstDepthWrong,
    /// 61108: SINUMERIK cycle alarm (seed 001 table 5.3): values of _RAD1/_DP1 not allowed.
    InsertionWrong,
    /// 61109: SINUMERIK cycle alarm (seed 001 table 5.3): _CDIR defined incorrectly.
    CdirWrong,
    /// 61110: SINUMERIK cycle alarm (seed 001 table 5.3): floor allowance > depth infeed.
    FloorAllowanceTooLarge,
    /// 61111: SINUMERIK cycle alarm (seed 001 table 5.3): infeed width > tool diameter.
    InfeedWidthTooLarge,
    /// 61112: SINUMERIK cycle alarm (seed 001 table 5.3): tool radius negative.
    ToolRadiusNegative,
    /// 61113: SINUMERIK cycle alarm (seed 001 table 5.3): corner radius _CRAD too large.
    CornerRadiusTooLarge,
    /// 61116: SINUMERIK cycle alarm (seed 001 line 12231): approach or departure path = 0 (CYCLE72 _LP1/_LP2).
    ApproachPathZero,
    /// 61117: SINUMERIK cycle alarm (seed 001 table 5.3): active tool radius <= 0.
    ToolRadiusNotPositive,
    /// 61118: SINUMERIK cycle alarm (seed 001 table 5.3): length or width = 0 (CYCLE71).
    LengthOrWidthZero,
    /// 61124: SINUMERIK cycle alarm (seed 001 table 5.3): infeed width not programmed
    /// (CYCLE71 `_MIDA` 0 with no tool to take it from).
    InfeedWidthMissing,
    /// 61128: SINUMERIK cycle alarm (seed 001 table 5.3): insertion angle = 0 for oscillating insertion.
    InsertionAngleZero,
    /// 61125: SINUMERIK cycle alarm (seed 001 table 5.3): _TECHNO defined incorrectly.
    TechnologyWrong,
    /// 61180: SINUMERIK cycle alarm (seed 001 lines 9197, 12241): no name assigned to
    /// the swivel data record (CYCLE800 on a machine without swivel data records).
    SwivelDataNoName,
    /// 61176: SINUMERIK cycle alarm (seed 001 line 9934): text length _DF programmed
    /// too small (CYCLE60: the characters do not fit the total width, the opening
    /// angle or the circle).
    TextLengthTooSmall,
    /// 61178: SINUMERIK cycle alarm (seed 001 line 9964): no code page (CYCLE60
    /// `_CODEP` other than 0 or 1252).
    NoCodePage,
    /// 61179: SINUMERIK cycle alarm (seed 001 line 9882): character does not exist
    /// (CYCLE60 `_TEXT` with a character its stroke font lacks).
    CharacterMissing,
    /// 61213: SINUMERIK cycle alarm (seed 001 table 5.3): circle radius too small (CYCLE77).
    CircleRadiusTooSmall,
    /// 61215: SINUMERIK cycle alarm (seed 001 table 5.3): blank dimension programmed
    /// incorrectly (CYCLE76, CYCLE77).
    BlankWrong,
    /// 61191: SINUMERIK cycle alarm (seed 001 lines 9794, 12252): 5-axis transformation not
    /// set up (CYCLE832 with TRAORI: this board has no 5-axis transformation).
    FiveAxisNotSetUp,
    /// 61192: SINUMERIK cycle alarm (seed 001 lines 9795, 12253): second 5-axis
    /// transformation not set up (CYCLE832 with TRAORI(2)).
    SecondFiveAxisNotSetUp,
    /// 61194: SINUMERIK cycle alarm (seed 001 lines 9797, 12255): option spline
    /// interpolation not set (CYCLE832 with B splines).
    SplineNotSetUp,
    /// 61601: SINUMERIK cycle alarm (seed 001 table 5.3): finished diameter too small.
    FinishedDiameterTooSmall,
    /// 61602: SINUMERIK cycle alarm (seed 001 table 5.3): tool width wrong.
    ToolWidthWrong,
    /// 61603: SINUMERIK cycle alarm (seed 001 table 5.3): groove form wrong.
    GrooveFormWrong,
    /// 61604: SINUMERIK cycle alarm (seed 001 table 5.3): tool violates contour.
    ToolViolatesContour,
    /// 61605: SINUMERIK cycle alarm (seed 001 table 5.3): contour wrong.
    ContourWrong,
    /// 61606: SINUMERIK cycle alarm (seed 001 table 5.3): contour preparation error.
    ContourPreparation { cause: u16 },
    /// 61607: SINUMERIK cycle alarm (seed 001 table 5.3): start point wrong.
    StartPointWrong,
    /// 61608: SINUMERIK cycle alarm (seed 001 table 5.3): wrong edge position.
    WrongEdgePosition,
    /// 61609: SINUMERIK cycle alarm (seed 001 table 5.3): form wrong.
    FormWrong,
    /// 61610: SINUMERIK cycle alarm (seed 001 table 5.3): no infeed depth programmed
    /// (CYCLE76, CYCLE77 `_MID`).
    NoInfeedDepth,
    /// 61612: SINUMERIK cycle alarm (seed 001 table 5.3): re-cutting impossible.
    RecutImpossible,
    /// 61613: SINUMERIK cycle alarm (seed 001 table 5.3): undercut position wrong.
    UndercutPositionWrong,
    /// 61701: SINUMERIK cycle alarm (seed 001 table 5.3): finished contour wrong.
    FinishedContourWrong,
    /// 61702: SINUMERIK cycle alarm (seed 001 table 5.3): blank contour wrong.
    BlankContourWrong,
    /// 61720: SINUMERIK cycle alarm (seed 001 table 5.3): illegal input.
    IllegalInput,
    /// 61721: SINUMERIK cycle alarm (seed 001 table 5.3): contour direction.
    ContourDirection,
    /// 61905: SINUMERIK cycle alarm (seed 001 table 5.3): milling cutter radius too small (SLOT2).
    CutterRadiusTooSmall,
    /// 61900–61989 but 61905: the alarms of CYCLE73–CYCLE75, pocket milling with
    /// islands (seed 001 lines 7357-7392), `code` the alarm number. One variant
    /// for the table: their texts ([`island_text`]) are only in a build with the
    /// cycle (canon's feature `mill-island`).
    IslandPocket { code: u16 },
    /// 61803: SINUMERIK cycle alarm (seed 001 table 5.3): programmed axis not present.
    AxisNotPresent,
    /// 61807: SINUMERIK cycle alarm (seed 001 table 5.3): spindle direction programmed incorrectly.
    WrongSpindleDirection,
}

impl From<CycleAlarm> for AlarmKind {
    fn from(k: CycleAlarm) -> Self {
        AlarmKind::SiemensCycle(k)
    }
}

impl CycleAlarm {
    /// The alarm number.
    pub fn code(&self) -> u16 {
        match self {
            CycleAlarm::IslandPocket { code } => *code,
            _ => self.fixed_code(),
        }
    }

    /// The number of a variant that has one of its own (not CYCLE73's, which
    /// carry theirs): one table lookup, kept apart from [`CycleAlarm::code`] so
    /// that the compiler does not fold the two into a jump table (+336 B).
    #[inline(never)]
    fn fixed_code(&self) -> u16 {
        use CycleAlarm::*;
        match self {
            NoToolOffset => 61000,
            ThreadPitchWrong => 61001,
            MachiningTypeWrong => 61002,
            NoFeed => 61003,
            NoThirdAxis => 61005,
            ToolNumberZero => 61009,
            ScaleNotAllowed => 61011,
            ScaleDiffers => 61012,
            ParameterWrong => 61019,
            ReferencePlaneWrong => 61101,
            NoSpindleDirection => 61102,
            HoleCountZero => 61103,
            SlotContourViolated => 61104,
            CutterRadiusTooLarge => 61105,
            CircleElements => 61106,
            FirstDepthWrong => 61107,
            InsertionWrong => 61108,
            CdirWrong => 61109,
            FloorAllowanceTooLarge => 61110,
            InfeedWidthTooLarge => 61111,
            ToolRadiusNegative => 61112,
            CornerRadiusTooLarge => 61113,
            ApproachPathZero => 61116,
            ToolRadiusNotPositive => 61117,
            LengthOrWidthZero => 61118,
            InfeedWidthMissing => 61124,
            TechnologyWrong => 61125,
            InsertionAngleZero => 61128,
            SwivelDataNoName => 61180,
            TextLengthTooSmall => 61176,
            NoCodePage => 61178,
            CharacterMissing => 61179,
            CircleRadiusTooSmall => 61213,
            BlankWrong => 61215,
            FiveAxisNotSetUp => 61191,
            SecondFiveAxisNotSetUp => 61192,
            SplineNotSetUp => 61194,
            FinishedDiameterTooSmall => 61601,
            ToolWidthWrong => 61602,
            GrooveFormWrong => 61603,
            ToolViolatesContour => 61604,
            ContourWrong => 61605,
            ContourPreparation { .. } => 61606,
            StartPointWrong => 61607,
            WrongEdgePosition => 61608,
            FormWrong => 61609,
            NoInfeedDepth => 61610,
            RecutImpossible => 61612,
            UndercutPositionWrong => 61613,
            FinishedContourWrong => 61701,
            BlankContourWrong => 61702,
            IllegalInput => 61720,
            ContourDirection => 61721,
            AxisNotPresent => 61803,
            CutterRadiusTooSmall => 61905,
            IslandPocket { .. } => 0,
            WrongSpindleDirection => 61807,
        }
    }
}

#[cfg(feature = "siemens")]
text_table! {
    /// The texts of the SINUMERIK front end's alarms.
    SiemensAlarm, fn text, static SIEMENS {
        SyntaxError { what } => "syntax error: {}", Str(what);
        TypeMismatch {} => "value of the wrong data type for this operation or variable";
        ValueRange {} => "value out of the range of its type or use";
        StringTooLong {} => "string longer than its variable or the argument space";
        NameDefinedTwice {} => "name defined twice in this program";
        ParameterType { index } => "type of parameter {} incorrect", Num(index);
        TooManyParameters {} => "too many parameters";
        TooManySymbols {} => "too many variables defined (DEF)";
        UnknownGFunction { code } => "G{} is not a SINUMERIK G function of this controller", Num(code);
        NameNotDefined {} => "name not defined (not a variable, keyword, cycle or program)";
        SubprogramNotFound {} => "subprogram not in program memory";
        SubprogramLevels {} => "subprograms or REPEAT sections nested too deep";
        LabelNotFound {} => "jump or section label not found";
        DefNotAtStart {} => "DEF only before the first NC block, PROC only at the start of a program";
        ProcMissing {} => "subprogram called with arguments has no PROC statement with parameters";
        AxisProgrammedTwice { letter } => "axis {} programmed twice in the block", Ch(letter);
        IndexOutOfRange {} => "array index out of range";
        IllegalDNumber { number } => "D{} has no tool offset row", Num(number);
        ModalCallNested {} => "MCALL inside a modally called subprogram";
    }
}

#[cfg(feature = "siemens")]
text_table! {
    /// The texts of the SINUMERIK cycles' alarms (seed 001 table 5.3).
    CycleAlarm, fn text, static CYCLE {
        NoToolOffset {} => "no tool offset active (program D before the cycle)";
        ThreadPitchWrong {} => "thread pitch defined incorrectly (PIT/MPIT contradict, or not a DIN 76 / ISO coarse size)";
        MachiningTypeWrong {} => "type of machining (VARI) defined incorrectly";
        NoFeed {} => "no feed programmed in the cycle (FFP1/FFD/FFR zero)";
        NoThirdAxis {} => "3rd geometry axis not present (the drilling axis of the plane)";
        ToolNumberZero {} => "active tool number = 0 (program T before the cycle)";
        ScaleNotAllowed {} => "scaling not allowed";
        ScaleDiffers {} => "different scaling in the plane";
        ParameterWrong {} => "parameter programmed incorrectly (DAM, ENC, _TOL, _TOLM)";
        ReferencePlaneWrong {} => "reference plane defined incorrectly (RTP, RFP, DP/DPR)";
        NoSpindleDirection {} => "no spindle direction programmed (SDIR/SDR 3 or 4, M3/M4 before CYCLE840)";
        HoleCountZero {} => "number of holes is zero (NUM of HOLES1/HOLES2)";
        SlotContourViolated {} => "contour violation of slots/elongated holes";
        CutterRadiusTooLarge {} => "milling cutter radius too large for the contour to be machined";
        CircleElements {} => "number or spacing of circle elements (NUM and INDA do not fit on a full circle)";
        FirstDepthWrong {} => "first drilling depth defined incorrectly (FDEP/FDPR against the total depth)";
        InsertionWrong {} => "values of _RAD1 and _DP1 not allowed (helix or oscillating insertion)";
        CdirWrong {} => "parameter _CDIR defined incorrectly";
        FloorAllowanceTooLarge {} => "floor finishing allowance > depth infeed (_FALD, _MID)";
        InfeedWidthTooLarge {} => "infeed width greater than the tool diameter (_MIDA)";
        ToolRadiusNegative {} => "tool radius negative";
        CornerRadiusTooLarge {} => "corner radius parameter _CRAD too large";
        ApproachPathZero {} => "approach or departure path = 0";
        ToolRadiusNotPositive {} => "active tool radius <= 0";
        LengthOrWidthZero {} => "length or width = 0 (_LENG, _WID)";
        InfeedWidthMissing {} => "infeed width not programmed (_MIDA)";
        TechnologyWrong {} => "technology selection in parameter _TECHNO defined incorrectly";
        InsertionAngleZero {} => "insertion angle = 0 for oscillating insertion";
        SwivelDataNoName {} => "no name assigned to the swivel data record";
        TextLengthTooSmall {} => "text length _DF programmed too small";
        NoCodePage {} => "engraving cycle: no code page (_CODEP)";
        CharacterMissing {} => "character does not exist (not in the engraving font)";
        CircleRadiusTooSmall {} => "circle radius too small (_PRAD)";
        BlankWrong {} => "blank dimension programmed incorrectly (_AP1/_AP2 not larger than the spigot)";
        FiveAxisNotSetUp {} => "5-axis transformation not set up (TRAORI)";
        SecondFiveAxisNotSetUp {} => "second 5-axis transformation not set up (TRAORI(2))";
        SplineNotSetUp {} => "option spline interpolation not set (B spline)";
        FinishedDiameterTooSmall {} => "finished part diameter too small (under 3 mm)";
        ToolWidthWrong {} => "tool width defined incorrectly (grooving tool wider than the groove, or no width)";
        GrooveFormWrong {} => "groove form defined incorrectly";
        ToolViolatesContour {} => "active tool violates the programmed contour (clearance angle too small for an undercut)";
        ContourWrong {} => "contour programmed incorrectly";
        StartPointWrong {} => "starting point programmed incorrectly (inside the rectangle of the contour)";
        WrongEdgePosition {} => "wrong tool point direction programmed (cutting edge position 1-4 needed)";
        FormWrong {} => "form defined incorrectly (CYCLE94: E or F, CYCLE96: A-D)";
        NoInfeedDepth {} => "no infeed depth programmed (_MID)";
        RecutImpossible {} => "thread re-cutting not possible";
        UndercutPositionWrong {} => "undercut position (_VARI) defined incorrectly";
        FinishedContourWrong {} => "finished part contour description wrong (_NP1-_NP3)";
        BlankContourWrong {} => "blank contour description wrong (_NP5-_NP7, _APZ/_APX)";
        IllegalInput {} => "illegal input (a _VARI digit of CYCLE950 out of its range)";
        ContourDirection {} => "wrong contour direction, cannot be computed";
        AxisNotPresent {} => "programmed axis does not exist (_AXN)";
        CutterRadiusTooSmall {} => "milling cutter radius too small";
        WrongSpindleDirection {} => "spindle direction programmed incorrectly (SDR/SDAC of CYCLE840)";
        ContourPreparation { cause } => "error during contour preparation ({})", Str(preparation_error(cause));
        IslandPocket { code } => "{}", Str(island_text(code));
    }
}

/// The text of a SINUMERIK cycle message (62000–62999, seed 001 table 5.3: shown,
/// cleared by the clear key, the program goes on), `None` for a number that is
/// not one of this controller's messages.
pub fn cycle_message(code: u16) -> Option<&'static str> {
    Some(match code {
        62100 => "no drilling cycle active (program MCALL CYCLE81-89/840 before the pattern)",
        62101 => "wrong milling direction, G3 generated (CDIR not 2 or 3)",
        62105 => "number of columns or rows is zero (_NUM1/_NUM2 of CYCLE801)",
        _ => return None,
    })
}

/// What CONTPRON's error `cause` of alarm 61606 says.
#[cfg(feature = "siemens")]
fn preparation_error(cause: u16) -> &'static str {
    match cause {
        10930 => "10930: illegal interpolation type in the stock removal contour",
        10931 => "10931: incorrect stock removal contour",
        10933 => "10933: the contour contains too few contour blocks",
        10934 => "10934: contour table overflow",
        15800 => "15800: incorrect start conditions for CONTPRON",
        _ => "the contour",
    }
}

/// The text of CYCLE73–CYCLE75 alarm `code` (seed 001 lines 7357-7392, the
/// document's texts).
#[cfg(feature = "siemens")]
fn island_text(code: u16) -> &'static str {
    #[cfg(feature = "mill-island")]
    return match code {
        61900 => "no contour (CYCLE74 not called before CYCLE73)",
        61901 => "contour not closed",
        61903 => "too many contour elements",
        61904 => "too many intersections (a contour crosses itself or another)",
        61906 => "too many contours (islands)",
        61907 => "circle without centre",
        61908 => "start point wrong",
        61909 => "helix radius too small",
        61910 => "helix violates the contour",
        61911 => "more insertion points required",
        61912 => "no path generated",
        61913 => "no rest material generated",
        61914 => "programmed helix violates the contour",
        61915 => "approach or departure violates the contour",
        61916 => "ramp too short",
        61917 => "with less than 50 % overlap residual corners may remain",
        61918 => "cutter radius for rest material too large",
        61980 => "island contour wrong",
        61981 => "edge contour wrong",
        61982 => "infeed width in the plane too large",
        61983 => "pocket edge contour wrong",
        61984 => "tool parameter _TN not defined",
        61985 => "name of the drilling positions program wrong",
        61988 => "name of the pocket milling program wrong",
        61989 => "D1 not programmed as the active tool edge",
        _ => "pocket milling with islands",
    };
    #[cfg(not(feature = "mill-island"))]
    {
        let _ = code;
        "pocket milling with islands (CYCLE73-CYCLE75, not in this build)"
    }
}

impl fmt::Display for SiemensAlarm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        #[cfg(feature = "siemens")]
        return self.text().write(f);
        #[cfg(not(feature = "siemens"))]
        f.write_str("SINUMERIK alarm (SINUMERIK mode is not in this build)")
    }
}

impl fmt::Display for CycleAlarm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        #[cfg(feature = "siemens")]
        return self.text().write(f);
        #[cfg(not(feature = "siemens"))]
        f.write_str("SINUMERIK alarm (SINUMERIK mode is not in this build)")
    }
}

/// One row of the alarm table: code, short title, when it is raised.
#[derive(Clone, Copy, Debug)]
pub struct CatalogEntry {
    /// Alarm number.
    pub code: u16,
    /// Short name.
    pub title: &'static str,
    /// When the controller raises it, with the manual section where there is one.
    pub when: &'static str,
}

/// Every alarm code, in numeric order. Tests keep it in step with [`AlarmKind::code`].
pub const CATALOG: &[CatalogEntry] = &[
    CatalogEntry {
        code: 3,
        title: "too many digits",
        when: "a word's number has more than 9 digits before or after the point",
    },
    CatalogEntry {
        code: 4,
        title: "address not found",
        when: "a value or symbol stands where an address letter belongs",
    },
    CatalogEntry { code: 5, title: "no data after address", when: "a letter with no number after it" },
    CatalogEntry {
        code: 6,
        title: "illegal minus sign",
        when: "minus sign on N, O, G, M, S, T, F, L, G04 P/X/U, a ,C/,R corner, a cycle's count or depth word",
    },
    CatalogEntry {
        code: 7,
        title: "illegal decimal point",
        when: "decimal point on N, O, M, S, T, L, G04 P (2.6), cycle P/Q",
    },
    CatalogEntry { code: 9, title: "improper address", when: "unknown letter, or an axis the machine does not have" },
    CatalogEntry {
        code: 10,
        title: "improper G code",
        when: "G code not in table 1.1 for the configured system A/B/C",
    },
    CatalogEntry { code: 11, title: "feed zero", when: "G01/G02/G03 with F zero or never commanded" },
    CatalogEntry {
        code: 14,
        title: "illegal lead",
        when: "thread lead F/E zero or beyond 500 mm; G34 K beyond +-499.99 or a lead that becomes zero, negative or too large (2.17.2)",
    },
    CatalogEntry {
        code: 20,
        title: "arc radius out of tolerance",
        when: "R shorter than half the chord, or I/K (mill: I/J/K) end point off the circle by more than parameter 3410; an ellipse (G02.1/G03.1) or parabola (G02.2/G03.2) whose end point no curve of the given A/B or P reaches (2.4, 2.5)",
    },
    CatalogEntry {
        code: 21,
        title: "axis outside arc plane",
        when: "arc block moves an axis outside the G17/G18/G19 plane (2.3 note 7, 2.13 note 5)",
    },
    CatalogEntry {
        code: 22,
        title: "arc centre missing",
        when: "G02/G03 without R or I/J/K and parameter 3403 = 0 (2.3 note 2)",
    },
    CatalogEntry { code: 23, title: "arc radius zero", when: "G02/G03 with R0" },
    CatalogEntry {
        code: 30,
        title: "illegal offset or tool number",
        when: "T word selects a tool or offset outside the tool table; on a mill T above tool_count, H or D beyond the offset rows",
    },
    CatalogEntry {
        code: 32,
        title: "G10 offset value out of range",
        when: "G10 L10-L13 value beyond +-999.999 mm, or G10 L20 work offset beyond +-2,147 mm (mill)",
    },
    CatalogEntry {
        code: 34,
        title: "arc in compensation start-up or cancel",
        when: "the first move after G41/G42 or the G40 move is an arc (2.18.3; nose radius on a lathe, cutter radius on a mill)",
    },
    CatalogEntry { code: 37, title: "plane change in compensation", when: "G17/G18/G19 while G41/G42 is in force" },
    CatalogEntry {
        code: 44,
        title: "reference return in a hole cycle",
        when: "G28, G29 or G30 while G73-G89 is in force on a mill (FANUC 0i-M PS0044)",
    },
    CatalogEntry {
        code: 45,
        title: "peck depth missing",
        when: "G73/G83 on a mill without Q, or Q0 (FANUC 0i-M PS0045)",
    },
    CatalogEntry { code: 46, title: "illegal reference number", when: "G30 P other than 1-4 (2.11.2)" },
    CatalogEntry {
        code: 50,
        title: "chamfer in thread block",
        when: ",C or ,R in a G32/G34/G92/G76 block (2.23 note 8)",
    },
    CatalogEntry {
        code: 51,
        title: "no move after chamfer/corner R",
        when: "the block after a ,C/,R block is not a G01/G02/G03 move (one G04 block may stand between), or a group 00 code shares or follows it (2.23 notes 2, 7)",
    },
    CatalogEntry {
        code: 55,
        title: "chamfer/corner R too large",
        when: "the chamfer or corner R does not fit on the moves it joins (2.23 note 3)",
    },
    CatalogEntry {
        code: 61,
        title: "P/Q missing in G70-G73",
        when: "G70 without P and Q, G71-G73 P without Q (2.16.7 note 1)",
    },
    CatalogEntry {
        code: 62,
        title: "illegal cycle value",
        when: "G71/G72 depth or retract, G73 count, G74/G75 step, G76 height, first depth, minimum depth, allowance, angle, finish count (2.16, 2.17.4 notes 6-7)",
    },
    CatalogEntry {
        code: 63,
        title: "sequence number not found",
        when: "ns or nf of G70-G73 not in the current program",
    },
    CatalogEntry {
        code: 64,
        title: "shape not monotone",
        when: "G71/G72 finishing shape goes back along the cutting axis (Z for G71; 2.16.1 note 4)",
    },
    CatalogEntry {
        code: 65,
        title: "bad first block of shape",
        when: "ns block of G71-G73 without G00/G01, or a type I G71 ns block that moves Z (2.16.7 note 2)",
    },
    CatalogEntry {
        code: 66,
        title: "code not allowed in shape",
        when: "group 00 code other than G04, group 01 other than G00-G03, G20/G21, M98/M99, M00/M01/M02/M30 between ns and nf (2.16.7 note 3)",
    },
    CatalogEntry {
        code: 76,
        title: "program not found",
        when: "M98, G65 or G66 P names a program not in memory (3.1.6 note 1), a G, M or T code calls a program not in memory, or M98/G65/G66 has no P (note 4)",
    },
    CatalogEntry {
        code: 77,
        title: "subprogram nesting too deep",
        when: "a 13th nested call (3.1.6: 12 levels, macro calls included), or a 5th nested macro call (G65, G66, G or M code; FANUC 0i: 4 levels)",
    },
    CatalogEntry {
        code: 78,
        title: "sequence number not found",
        when: "GOTO n, M99 P n (3.1.7 note 2) or M91/M92 P n names an N the program lacks",
    },
    CatalogEntry { code: 111, title: "macro overflow", when: "a macro calculation leaves the f64 number range" },
    CatalogEntry {
        code: 112,
        title: "division by zero",
        when: "divisor 0 in / or MOD, or TAN of an odd multiple of 90 degrees (2.24.2)",
    },
    CatalogEntry {
        code: 114,
        title: "macro format error",
        when: "malformed expression or statement: missing ']' or operand, unknown function, IF without a comparison",
    },
    CatalogEntry { code: 115, title: "variable number out of range", when: "#i with i outside 0-999 (2.24.1)" },
    CatalogEntry { code: 116, title: "write-protected variable", when: "assignment to #0 (2.24.1)" },
    CatalogEntry {
        code: 118,
        title: "too many brackets",
        when: "more than 5 nested bracket levels, function brackets included",
    },
    CatalogEntry {
        code: 119,
        title: "argument out of range",
        when: "ASIN/ACOS outside -1..1, SQRT < 0, EXP beyond +-80, ATAN[0]/[0], AND/OR/XOR not on 0..2^32-1 integers",
    },
    CatalogEntry {
        code: 122,
        title: "four-fold macro modal call",
        when: "a G66 while three modal calls are in force (FANUC 0i)",
    },
    CatalogEntry { code: 123, title: "control statement in MDI", when: "GOTO, WHILE, DO or END entered in MDI" },
    CatalogEntry {
        code: 124,
        title: "DO-END mismatch",
        when: "WHILE/DO without END, END without DO, overlapping ranges (2.24.2 note 4)",
    },
    CatalogEntry { code: 126, title: "illegal loop number", when: "DO/END number other than 1, 2, 3 (2.24.2 note 3)" },
    CatalogEntry {
        code: 127,
        title: "macro and NC statement in one block",
        when: "a macro statement shares its block with NC words (2.24.2 note 7)",
    },
    CatalogEntry {
        code: 128,
        title: "illegal sequence number",
        when: "GOTO target not a whole number 1-99999 (2.24.2 note 1)",
    },
    CatalogEntry {
        code: 129,
        title: "illegal argument address",
        when: "G, N or O among the arguments of a macro call, P in a call by G or M code, more than 10 I/J/K groups (FANUC 0i)",
    },
    CatalogEntry {
        code: 142,
        title: "illegal scale factor",
        when: "G51 P outside 0.001-999.999, I/J/K outside +-0.001-+-9.999 or zero (seed 004 @4506, @4740)",
    },
    CatalogEntry { code: 200, title: "rigid tap S missing", when: "M29 without S or with S0 (2.22.1)" },
    CatalogEntry {
        code: 203,
        title: "rigid tap sequence",
        when: "S between M29 and G84/G88, or M29 repeated in rigid tapping (2.22.1)",
    },
    CatalogEntry { code: 204, title: "axis move in rigid tap", when: "axis motion between M29 and G84/G88 (2.22.1)" },
    CatalogEntry {
        code: 212,
        title: "illegal plane selection",
        when: "G17/G18/G19 in the block after a ,C/,R block, or a chamfered move leaving the plane (2.23 note 4); \
               on a mill a plane change, or an arc in another plane, while G68 rotation is in force",
    },
    CatalogEntry {
        code: 220,
        title: "tool spindle moved in polygon turning",
        when: "a block moves C (the tool spindle) between G51.2 and G50.2 (2.8 note 11)",
    },
    CatalogEntry {
        code: 221,
        title: "illegal command in polygon turning",
        when: "G12.1, M29 rigid tapping or another use of the spindle or C in position control between G51.2 and G50.2, or G51.2 in G12.1 (2.8 notes 6, 9)",
    },
    CatalogEntry {
        code: 224,
        title: "reference not established",
        when: "G28/G30 on an axis that has not been homed (2.11.2 note 2)",
    },
    CatalogEntry {
        code: 329,
        title: "shape not monotone (infeed axis)",
        when: "type I G71/G72 finishing shape goes back along the infeed axis (2.16.1)",
    },
    CatalogEntry {
        code: 500,
        title: "+ overtravel (soft)",
        when: "a move's end point or arc passes the axis's + travel limit",
    },
    CatalogEntry {
        code: 501,
        title: "- overtravel (soft)",
        when: "a move's end point or arc passes the axis's - travel limit",
    },
    CatalogEntry {
        code: 502,
        title: "+ overtravel (stroke check 2)",
        when: "G22 in force: a move would enter the forbidden area moving in + (2.10), or the tool is outside an outside-forbidden box when G22 is given (note 7)",
    },
    CatalogEntry { code: 503, title: "- overtravel (stroke check 2)", when: "as 0502, moving in - or below the box" },
    CatalogEntry {
        code: 3576,
        title: "radius compensation reversed",
        when: "G41 to G42 or back directly while compensating (2.18.4)",
    },
    CatalogEntry {
        code: 3577,
        title: "tool change in radius compensation",
        when: "T code in G41/G42 on a lathe (2.18.4); M06 in G41/G42 on a mill",
    },
    CatalogEntry {
        code: 3605,
        title: "radius compensation gouge",
        when: "interference check finds overcutting (2.18.4; a mill's cutter compensation the same way): a move \
               whose offset runs against it (named by the alarm; the machine stops before it), an inside arc \
               smaller than the nose or cutter, a G90/G94 cut shorter than the nose",
    },
    CatalogEntry {
        code: 3607,
        title: "compensation corner angle",
        when: "corner between two paths under 0.1 degrees (2.18.4)",
    },
    CatalogEntry {
        code: 4001,
        title: "G20/G21 not alone",
        when: "G20/G21 shares its block with other words (2.9 note 2)",
    },
    CatalogEntry {
        code: 4002,
        title: "G20/G21 not at start",
        when: "G20/G21 after the program has moved an axis (2.9 note 2)",
    },
    CatalogEntry { code: 4003, title: "modal group conflict", when: "two G codes of one modal group in one block" },
    CatalogEntry { code: 4004, title: "duplicate address", when: "the same address twice in one block" },
    CatalogEntry {
        code: 4005,
        title: "word not allowed",
        when: "a word the block's codes do not use (I/K in G01, P in G00 ...)",
    },
    CatalogEntry {
        code: 4006,
        title: "word missing",
        when: "a word the block's code requires (G04 time, G52 axes, the axis of a mill's G51.1 ...)",
    },
    CatalogEntry {
        code: 4007,
        title: "not supported yet",
        when: "a code of the manual this build does not implement yet; SINUMERIK mode (G290, $310=1) on a board built without it (the F446: SINUMERIK mode not in this build)",
    },
    CatalogEntry {
        code: 4008,
        title: "unknown M code",
        when: "M code not in tables 1.2/3.1 nor configured as a user output",
    },
    CatalogEntry { code: 4009, title: "conflicting M codes", when: "M03 with M04, M08 with M09 ... in one block" },
    CatalogEntry { code: 4010, title: "too many M codes", when: "more than 3 M codes in one block" },
    CatalogEntry {
        code: 4011,
        title: "value out of range",
        when: "a word's value outside its range (T digits, S negative, G30 P ...)",
    },
    CatalogEntry {
        code: 4012,
        title: "G50 disabled",
        when: "G50 coordinate setting while parameter 5152 = 1 (2.12.1 note 3)",
    },
    CatalogEntry {
        code: 4013,
        title: "feed per rev without spindle",
        when: "feed per revolution (lathe G99, mill G95) cutting move, or a mill's floating tap G84/G74, while the spindle is stopped",
    },
    CatalogEntry { code: 4014, title: "comment not closed", when: "'(' without ')' in the block" },
    CatalogEntry {
        code: 4015,
        title: "G53 or G52 incremental",
        when: "G53 with U/W instead of X/Z (mill: G53 under G91); on a mill also G52 under G91 (its words are the local origin, seed 004 @2362)",
    },
    CatalogEntry {
        code: 4016,
        title: "code must be alone",
        when: "G04, G28, G30, G50, G52, G53 with a motion G code in the same block",
    },
    CatalogEntry { code: 4017, title: "overflow", when: "a value or computed position beyond the controller's range" },
    CatalogEntry { code: 4018, title: "misplaced block skip", when: "'/' inside a block outside an expression" },
    CatalogEntry { code: 4019, title: "illegal character", when: "a character that cannot start a word" },
    CatalogEntry {
        code: 4020,
        title: "axis given twice",
        when: "absolute and incremental address of one axis in a block (X with U, Z with W; 2.17.1 note 7)",
    },
    CatalogEntry {
        code: 4030,
        title: "taper too large",
        when: "G90/G92 |R| > |U/2| or G94 |R| > |W| with R and U/W of opposite sign (2.15, figures 2.24/2.28)",
    },
    CatalogEntry {
        code: 4031,
        title: "cycle outside ZX plane",
        when: "G70-G76, G90, G92, G94 in G17/G19 (2.13 note 4)",
    },
    CatalogEntry {
        code: 4032,
        title: "other axis in cycle",
        when: "a G70-G76/G90/G92/G94 block moves Y or C (2.15 note 1)",
    },
    CatalogEntry { code: 4033, title: "thread start angle", when: "G32/G34 Q outside 0-360 degrees (2.17.1)" },
    CatalogEntry {
        code: 4034,
        title: "pull-out too long",
        when: "G92/G76 pull-out (NO.5130 x 0.1 lead) longer than the thread (2.17.3 note 5, 2.17.4 note 8)",
    },
    CatalogEntry {
        code: 4035,
        title: "shape too long",
        when: "finishing shape ns-nf with more segments than the controller holds (48)",
    },
    CatalogEntry {
        code: 4036,
        title: "too many pockets",
        when: "type II G71/G72 shape with more than 10 pockets (2.16.1)",
    },
    CatalogEntry {
        code: 4037,
        title: "cycle too long",
        when: "a cycle would plan more than 1,000,000 moves (G74/G75 P3 is 0.003 mm; 2.16.5)",
    },
    CatalogEntry { code: 4040, title: "subprogram calls itself", when: "M98 P names its own program (3.1.6 note 3)" },
    CatalogEntry {
        code: 4041,
        title: "M98/M99/M91/M92 in MDI",
        when: "subprogram call or jump entered in MDI (3.1.6 note 2)",
    },
    CatalogEntry {
        code: 4042,
        title: "M99 not alone",
        when: "M99 shares its block with G, M or other words besides N and P (3.1.7 note 1)",
    },
    CatalogEntry {
        code: 4043,
        title: "jump input missing",
        when: "M91/M92 test an external input the machine does not have (3.1.5)",
    },
    CatalogEntry {
        code: 4044,
        title: "look-ahead full",
        when: "too many actions (M codes, dwells, blocks without motion) between a held move and the next move",
    },
    CatalogEntry {
        code: 4045,
        title: "code not allowed in polar interpolation",
        when: "in G12.1 a G code other than G01, G02, G03, G04, G40-G42, G98/G99, G13.1 (2.7 note 4)",
    },
    CatalogEntry {
        code: 4046,
        title: "polar arc without R",
        when: "G02/G03 in G12.1 with I/J/K or without R (2.7 note 6)",
    },
    CatalogEntry {
        code: 4047,
        title: "no tool spindle for polygon turning",
        when: "G51.2 (its P/Q/R/S valid) on a machine without a C axis: the C axis drive is the tool spindle that 2.8 note 6 requires",
    },
    CatalogEntry {
        code: 4048,
        title: "G29 without G28",
        when: "G29 moves an axis that no G28 since power-on or reset has given an intermediate point",
    },
    CatalogEntry {
        code: 4049,
        title: "transformation in cutter compensation",
        when: "G15/G16, G50/G51, G50.1/G51.1 or G68/G69 while G41/G42 is in force (cancel with G40 first)",
    },
    CatalogEntry {
        code: 4050,
        title: "variables full",
        when: "a 129th variable of #34-#400 and #601-#999 would hold a value at once (setting one to null frees its place)",
    },
    CatalogEntry {
        code: 4051,
        title: "transformations out of order",
        when: "G51.1/G50.1 while G51 or G68 is in force, or G51/G50 while G68 is (FANUC: mirror, scaling, \
               rotation, cancelled in the reverse order)",
    },
    CatalogEntry {
        code: 4052,
        title: "MCALL nested",
        when: "SINUMERIK: MCALL in a subprogram that MCALL called (modal calls do not nest, seed 001 line 3027; \
               4048/4049/4051 are the mill profile's)",
    },
    CatalogEntry {
        code: 4501,
        title: "thread too fast",
        when: "lead x spindle speed (with the ripple margin) above an axis's cutting feed or step-rate limit, \
               for G34 with the largest lead of the pass (at its end when K > 0); raised before the pass moves (2.17)",
    },
    CatalogEntry {
        code: 4502,
        title: "thread ramp too long",
        when: "the acceleration/deceleration ramp at the measured speed is longer than the thread block (2.17.1)",
    },
    CatalogEntry {
        code: 4503,
        title: "spindle not turning",
        when: "thread, rigid tap or G99 feed started while the encoder shows no rotation",
    },
    CatalogEntry {
        code: 4504,
        title: "spindle not at speed",
        when: "the spindle stayed outside the at-speed band longer than the configured timeout",
    },
    CatalogEntry {
        code: 4505,
        title: "tap too fast",
        when: "rigid tap lead x spindle speed or acceleration above the tapping axis's limits (2.22.2)",
    },
    CatalogEntry {
        code: 4506,
        title: "spindle index missing",
        when: "no encoder index pulse within two revolutions when a thread pass synchronises (2.17.1)",
    },
    CatalogEntry {
        code: 4507,
        title: "spindle-locked sequence broken",
        when: "a continuing thread block after its predecessor ended, or a tap that does not return to its start",
    },
    CatalogEntry {
        code: 4508,
        title: "motion configuration invalid",
        when: "zero step ratio, driver timing that cannot be met, zero encoder counts ...",
    },
    CatalogEntry {
        code: 4509,
        title: "emergency stop",
        when: "e-stop input: axes decelerate, spindle stops, queue dropped",
    },
    CatalogEntry {
        code: 4510,
        title: "G34 lead change too fast",
        when: "G34 K x spindle speed squared (with the ripple margin), the constant acceleration of a \
               variable-lead thread, above half the long axis's acceleration; raised before the pass moves (2.17.2)",
    },
    CatalogEntry {
        code: 4511,
        title: "tool change timeout",
        when: "a mill's M06 with the automatic tool changer ($312=1, machine file tool_changer = \"automatic\"): \
               the changer's done input did not come within $313 seconds (default 30) of the board's \
               request; the job stops, the spindle stays stopped, the request outputs drop",
    },
    CatalogEntry {
        code: 4601,
        title: "stream starved (link lost)",
        when: "a streamed job is open (it ran a block and did not reach M02/M30, nor its tape's closing %), \
               its text and motion have run out, and no byte, not even a status poll, came over the link \
               for $304 seconds since before it ran out (default 10 s; $304=0 off)",
    },
    CatalogEntry { code: 5010, title: "end of record", when: "program text ends without M02, M30 or M99" },
    CatalogEntry {
        code: 12080,
        title: "syntax error",
        when: "SINUMERIK: a block that cannot be read (unknown word, unbalanced brackets or quotes, a keyword in the wrong place)",
    },
    CatalogEntry {
        code: 12150,
        title: "data type",
        when: "SINUMERIK: a string in arithmetic or a comparison with a number, a number for a STRING variable",
    },
    CatalogEntry {
        code: 12160,
        title: "value range",
        when: "SINUMERIK: INT beyond 32 bits, CHAR beyond 255, a string longer than its STRING[n] or a call's arguments beyond the 256 bytes they are kept in",
    },
    CatalogEntry { code: 12170, title: "name defined twice", when: "SINUMERIK: DEF of a name the program level has" },
    CatalogEntry {
        code: 12330,
        title: "parameter type",
        when: "SINUMERIK: an argument of a cycle or subprogram call whose type does not convert to its parameter's (a string for REAL/INT, a number for STRING/CHAR; seed 001 line 649)",
    },
    CatalogEntry {
        code: 12340,
        title: "too many parameters",
        when: "SINUMERIK: more arguments than the cycle or subprogram has parameters (seed 001 line 596)",
    },
    CatalogEntry {
        code: 12460,
        title: "too many variables",
        when: "SINUMERIK: more than 32 DEF variables and PROC parameters, 192 bytes of their names or 96 bytes of STRING contents in all program levels",
    },
    CatalogEntry {
        code: 12470,
        title: "unknown G function",
        when: "SINUMERIK: a G number the SINUMERIK table of this controller does not hold",
    },
    CatalogEntry {
        code: 12550,
        title: "name not defined",
        when: "SINUMERIK: a word that is no variable, keyword, cycle or stored program",
    },
    CatalogEntry {
        code: 14011,
        title: "program not found",
        when: "SINUMERIK: a subprogram call or a cycle's contour names a program that is not in program memory",
    },
    CatalogEntry {
        code: 14012,
        title: "subprogram levels",
        when: "SINUMERIK: calls and REPEAT sections nested deeper than 12 levels",
    },
    CatalogEntry {
        code: 14080,
        title: "label not found",
        when: "SINUMERIK: the label of GOTOF/GOTOB/GOTO, REPEAT or a contour range is not in the program (GOTOF searches forward, GOTOB backward)",
    },
    CatalogEntry {
        code: 14500,
        title: "DEF or PROC misplaced",
        when: "SINUMERIK: DEF after the program's first NC block, PROC other than at a program's start",
    },
    CatalogEntry {
        code: 14510,
        title: "PROC missing",
        when: "SINUMERIK: a subprogram is called with arguments but has no PROC statement with parameters",
    },
    CatalogEntry { code: 16420, title: "axis programmed twice", when: "SINUMERIK: one axis twice in a block" },
    CatalogEntry {
        code: 17020,
        title: "array index",
        when: "SINUMERIK: R[n] beyond R99, _ZSD[n] beyond 9, $TC_DP…[t,d] beyond the tool table",
    },
    CatalogEntry {
        code: 17180,
        title: "illegal D number",
        when: "SINUMERIK: T t D d selects offset row t + (d-1) x tool count, which the offset table does not have",
    },
    CatalogEntry {
        code: 61000,
        title: "no tool offset active",
        when: "SINUMERIK CYCLE93-CYCLE96 called without a D offset in force (seed 001 lines 10353, 10537, 11045: 没有刀具补偿有效)",
    },
    CatalogEntry {
        code: 61001,
        title: "thread pitch wrong",
        when: "CYCLE97 PIT and MPIT contradict or neither gives a pitch; MPIT or CYCLE96 DIATH not an ISO coarse size M3-M60/M68 (lines 11136-11142, 11009: 螺距定义错误)",
    },
    CatalogEntry {
        code: 61002,
        title: "machining type wrong",
        when: "VARI outside the values of CYCLE93 (1-8, 11-18), CYCLE95 (1-12, hundreds 0/2), CYCLE97/CYCLE98 (1-4), POCKET1/POCKET2 (0-2), POCKET3 (1, 2, 11, 12, 21, 22, 31, 32), POCKET4 (the same without 3x) (lines 10311, 10799, 11195, 11397: 加工方式错误定义)",
    },
    CatalogEntry {
        code: 61003,
        title: "no feed in the cycle",
        when: "SINUMERIK CYCLE71/CYCLE72 (and the milling cycles' feeds) called with a feed of zero and none in force (table: 在循环中没有编程进给)",
    },
    CatalogEntry {
        code: 61005,
        title: "3rd geometry axis not present",
        when: "a SINUMERIK drilling cycle (CYCLE81-89, CYCLE840 without _AXN) whose drilling axis, the applicate of the plane, the machine lacks: a lathe in G18 drills along Y (line 2721: 3. 几何轴没有出现); use G17 or _AXN=1",
    },
    CatalogEntry {
        code: 61009,
        title: "active tool number 0",
        when: "SINUMERIK milling cycle (CYCLE71, CYCLE72) called with no tool selected, T0; CYCLE76/CYCLE77 with no tool or no offset active (lines 5921, 6083) (table: 有效的刀具号=0)",
    },
    CatalogEntry {
        code: 61011,
        title: "scaling not allowed",
        when: "SINUMERIK CYCLE71 called with a scaling in force (table: 比例缩放不允许)",
    },
    CatalogEntry {
        code: 61012,
        title: "different scaling in the plane",
        when: "SINUMERIK CYCLE76/CYCLE77 called with unequal scale factors on the plane's two axes (table: 平面中比例缩放不同)",
    },
    CatalogEntry {
        code: 61019,
        title: "parameter wrong",
        when: "CYCLE83 DAM under -1 (line 1824), CYCLE840 ENC other than 0, 1, 11, 20 (table 12213: 参数错误编程); CYCLE832 _TOL negative or above 10 mm, a _TOLM digit outside its values (the document names no alarm; see docs/SIEMENS-MILL.md)",
    },
    CatalogEntry {
        code: 61101,
        title: "reference plane wrong",
        when: "a SINUMERIK drilling cycle with a relative depth DPR and RTP = RFP, a depth on the retract plane's side of RFP, or no depth (lines 1583-1589: 基准面错误定义)",
    },
    CatalogEntry {
        code: 61102,
        title: "no spindle direction",
        when: "CYCLE86/87/88 SDIR other than 3/4, CYCLE84 SDAC other than 0/3/4/5, CYCLE840 with the spindle stopped at the call or SDR = 0 without an encoder (ENC 1/11), POCKET3/POCKET4 climb/conventional milling (_CDIR 0/1) with the spindle stopped (lines 2689, 2814, 2896, table 12217: 没有编程主轴方向)",
    },
    CatalogEntry {
        code: 61103,
        title: "number of holes zero",
        when: "HOLES1/HOLES2 NUM zero, negative or left out (line 3107, table 12216: 孔数为零)",
    },
    CatalogEntry {
        code: 61104,
        title: "slot contour violation",
        when: "LONGHOLE/SLOT1/SLOT2 whose slots touch or cut each other on the circle (neighbours closer than the width at their inner ends, SLOT2's gap between slots no wider than WID) or a SLOT2 over the circle's centre (table: 键槽轮廓损伤; lines 3905, 4194, 4376, table 12217)",
    },
    CatalogEntry {
        code: 61105,
        title: "cutter radius too large",
        when: "SINUMERIK milling cycle whose cutter does not fit the slot, pocket, elongated hole or thread (table: 铣刀半径太大; lines 3743, 3862, 4054, 4519)",
    },
    CatalogEntry {
        code: 61106,
        title: "circle elements",
        when: "HOLES2 NUM holes, LONGHOLE/SLOT1/SLOT2 NUM slots at INDA apart do not fit on a full circle: (NUM−1)·|INDA| ≥ 360°; slots also for NUM ≤ 0 (table 12221: 圆弧单元个数或者间距)",
    },
    CatalogEntry {
        code: 61107,
        title: "first depth wrong",
        when: "CYCLE83 first depth FDEP/FDPR deeper than the final depth or not into the hole (lines 1803, 1823: 第一次钻深错误定义)",
    },
    CatalogEntry {
        code: 61108,
        title: "_RAD1/_DP1 not allowed",
        when: "SINUMERIK POCKET3/POCKET4 helical insertion (_VARI 2x) with _RAD1 or _DP1 zero or a helix that does not fit the pocket, POCKET3 oscillating insertion (3x) with an angle _RAD1 outside 0-90 degrees (table: 不允许的值用于参数_RAD1和_DP1)",
    },
    CatalogEntry {
        code: 61109,
        title: "_CDIR wrong",
        when: "SINUMERIK POCKET3/POCKET4 _CDIR other than 0-3 (table: 参数_CDIR错误定义)",
    },
    CatalogEntry {
        code: 61110,
        title: "floor allowance > depth infeed",
        when: "SINUMERIK POCKET3/POCKET4 floor allowance _FALD larger than the depth infeed _MID (table: 底部的精加工余量>深度进刀)",
    },
    CatalogEntry {
        code: 61111,
        title: "infeed width > tool diameter",
        when: "SINUMERIK CYCLE71/POCKET3/POCKET4 _MIDA larger than the cutter diameter (table: 进刀宽度>刀具直径)",
    },
    CatalogEntry {
        code: 61112,
        title: "tool radius negative",
        when: "SINUMERIK CYCLE72/76/77/90 with a negative radius in the active D offset (table: 刀具半径为负)",
    },
    CatalogEntry {
        code: 61113,
        title: "_CRAD too large",
        when: "SINUMERIK POCKET3 corner radius _CRAD above half the pocket's length or width (table: 拐角半径参数_CRAD太大)",
    },
    CatalogEntry {
        code: 61116,
        title: "approach or departure path = 0",
        when: "SINUMERIK CYCLE72 with _LP1 or _LP2 zero (table: 返回运行位移或者开始运行位移=0)",
    },
    CatalogEntry {
        code: 61117,
        title: "active tool radius <= 0",
        when: "SINUMERIK CYCLE71/POCKET3/POCKET4 with a radius of zero or less in the active D offset (table: 有效的刀具半径<=0)",
    },
    CatalogEntry {
        code: 61118,
        title: "length or width 0",
        when: "SINUMERIK CYCLE71 with _LENG or _WID zero (table: 长度或者宽度=0)",
    },
    CatalogEntry {
        code: 61124,
        title: "infeed width not programmed",
        when: "SINUMERIK CYCLE71 with _MIDA zero and no tool selected (T0) to take 80 % of its diameter from (table: 进刀宽度没有编程)",
    },
    CatalogEntry {
        code: 61125,
        title: "_TECHNO wrong",
        when: "CYCLE84/CYCLE840 _TECHNO with a digit outside its values (table: 参数_TECHNO中工艺选择错误定义)",
    },
    CatalogEntry {
        code: 61128,
        title: "insertion angle 0",
        when: "SLOT1 with oscillating insertion (VARI tens 3) and _STA2 = 0 (table: 在以摆动或者螺旋插入时再入角=0)",
    },
    CatalogEntry {
        code: 61176,
        title: "text length _DF too small",
        when: "SINUMERIK CYCLE60 whose characters do not fit the total width _DF, the opening angle _DF or the circle (line 9934: 文字长度_DF编程太小)",
    },
    CatalogEntry {
        code: 61178,
        title: "no code page",
        when: "SINUMERIK CYCLE60 with _CODEP other than 0 or 1252 (line 9964: 没有代码页)",
    },
    CatalogEntry {
        code: 61179,
        title: "character does not exist",
        when: "SINUMERIK CYCLE60 _TEXT with a character outside printable ASCII, which the engraving font does not cover (line 9882: 字符不存在)",
    },
    CatalogEntry {
        code: 61180,
        title: "no swivel data record",
        when: "SINUMERIK CYCLE800 that would swivel: this board has no swivel kinematics, so no swivel data records (lines 9197, 12241: 没有给回转数据组分配名称); CYCLE800() and _TC=\"0\" deselect and are accepted",
    },
    CatalogEntry {
        code: 61191,
        title: "5-axis transformation not set up",
        when: "SINUMERIK CYCLE832 _TOLM tens digit 1 (TRAORI): this board has no 5-axis transformation (lines 9794, 12252: 5轴转换没有设置)",
    },
    CatalogEntry {
        code: 61192,
        title: "second 5-axis transformation not set up",
        when: "SINUMERIK CYCLE832 _TOLM tens digit 2 (TRAORI(2)) (lines 9795, 12253: 第二个5轴转换没有设置)",
    },
    CatalogEntry {
        code: 61194,
        title: "option spline interpolation not set",
        when: "SINUMERIK CYCLE832 _TOLM hundreds digit 3 (B spline): this board has no spline interpolation (lines 9797, 12255: 选项样条插补没有设置)",
    },
    CatalogEntry {
        code: 61213,
        title: "circle radius too small",
        when: "SINUMERIK CYCLE77 with a spigot diameter _PRAD of zero (table: 圆弧半径太小)",
    },
    CatalogEntry {
        code: 61215,
        title: "blank dimension wrong",
        when: "SINUMERIK CYCLE76/CYCLE77 with a blank _AP1 (_AP2) not larger than the spigot's length (width, diameter) (table: 毛坯尺寸错误编程)",
    },
    CatalogEntry {
        code: 61601,
        title: "finished diameter too small",
        when: "CYCLE94 SPD or CYCLE96 DIATH gives a finished diameter under 3 mm (lines 10504, 11003: 成品直径太小)",
    },
    CatalogEntry {
        code: 61602,
        title: "tool width wrong",
        when: "CYCLE93 groove narrower than the two-edge tool (offsets D and D+1), or a tool width of zero (line 10268: 刀具宽度错误定义)",
    },
    CatalogEntry {
        code: 61603,
        title: "groove form wrong",
        when: "CYCLE93 radii/chamfers that touch or cut each other at the bottom, or a face groove on a line parallel to the longitudinal axis (line 10313: 错误定义切槽形状)",
    },
    CatalogEntry {
        code: 61604,
        title: "tool violates contour",
        when: "CYCLE95 undercut steeper than the tool's clearance angle (offset parameter P24, 0 = no check) allows (line 10870: 激活的刀具损坏编程的轮廓)",
    },
    CatalogEntry {
        code: 61605,
        title: "contour wrong",
        when: "CYCLE95 contour with an element the cycle cannot machine (an undercut against the machining direction); CYCLE76 spigot with _LENG or _WID zero or a corner radius _CRAD above half its width (table 12260: 轮廓错误编程)",
    },
    CatalogEntry {
        code: 61606,
        title: "contour preparation error",
        when: "CYCLE95 contour that cannot be prepared, with the NCK alarm that caused it: 10930 a motion other than G0-G3, 10931 an arc of more than 180 degrees / G41/G42 / a plane change, 10933 fewer than 3 blocks, 10934 more elements than the cycle holds, 15800 a first block without G0-G3 (lines 10820-10858: 轮廓预处理时出错)",
    },
    CatalogEntry {
        code: 61607,
        title: "start point wrong",
        when: "CYCLE95 called from a point inside the rectangle the contour spans (table 12267: 起始点错误编程)",
    },
    CatalogEntry {
        code: 61608,
        title: "wrong edge position",
        when: "CYCLE94/CYCLE96 with _VARI=0 and an active cutting edge position other than 1-4 (line 10527: 编程了错误的刀沿位置)",
    },
    CatalogEntry {
        code: 61609,
        title: "form wrong",
        when: "CYCLE94 FORM not E/F, CYCLE96 FORM not A-D (lines 10513, 11024: 形状错误定义); LONGHOLE LENG 0, SLOT1 WID 0 or LENG < WID (table 12269)",
    },
    CatalogEntry {
        code: 61610,
        title: "no infeed depth",
        when: "SINUMERIK CYCLE76/CYCLE77 with _MID zero (table: 没有编程进刀深度)",
    },
    CatalogEntry {
        code: 61612,
        title: "re-cutting impossible",
        when: "CYCLE97/CYCLE98 with thread re-cutting (4.9) set up but the thread is a multi-start one or the synchronised angle is missing (table 12272: 不可能进行螺纹精整)",
    },
    CatalogEntry {
        code: 61613,
        title: "undercut position wrong",
        when: "CYCLE94/CYCLE96 _VARI outside 0-4 (table 12273: 退刀槽位置错误定义)",
    },
    CatalogEntry {
        code: 61701,
        title: "finished contour wrong",
        when: "CYCLE950 without a finished contour (_NP1, or _NP2/_NP3 not found), or one that cannot be prepared (table 12112: 成品轮廓描述错误)",
    },
    CatalogEntry {
        code: 61702,
        title: "blank contour wrong",
        when: "CYCLE950 blank given wrongly: _APZA/_APXA other than 90/91, or a blank cylinder inside the finished contour (table 12113: 坯件轮廓描述错误)",
    },
    CatalogEntry {
        code: 61720,
        title: "illegal input",
        when: "CYCLE950 _VARI with a digit outside its values, or a machining or infeed direction that does not fit the machining type (table 12124: 非法输入)",
    },
    CatalogEntry {
        code: 61721,
        title: "contour direction",
        when: "CYCLE950 machining direction (_VARI hundred-thousands) against the direction the contour can be cut in (table 12125: 错误轮廓方向不可计算)",
    },
    CatalogEntry {
        code: 61803,
        title: "axis not present",
        when: "CYCLE83/84/840 _AXN choosing a drilling axis the machine lacks (table: 编程的轴不存在)",
    },
    CatalogEntry {
        code: 61807,
        title: "spindle direction wrong",
        when: "CYCLE840 SDR the direction the spindle turns into the hole (it must reverse), or SDAC other than 0/3/4/5 (table: 编程错误的主轴方向)",
    },
    CatalogEntry {
        code: 61900,
        title: "no contour",
        when: "CYCLE73 without a CYCLE74 before it in the run, or CYCLE75 before CYCLE74 (table: 没有轮廓出现)",
    },
    CatalogEntry {
        code: 61901,
        title: "contour not closed",
        when: "a CYCLE74/CYCLE75 contour whose last point is not its first (line 6249; table: 轮廓不闭合)",
    },
    CatalogEntry {
        code: 61903,
        title: "too many contour elements",
        when: "a CYCLE74/CYCLE75 contour of more than the 48 elements the contour store holds (table: 太多轮廓单元)",
    },
    CatalogEntry {
        code: 61904,
        title: "too many intersections",
        when: "a CYCLE73 pocket beyond what the offsetting computes: coordinates beyond ±5 m, or more rings than it lays (table: 太多交叉点)",
    },
    CatalogEntry {
        code: 61905,
        title: "cutter radius too small",
        when: "SLOT2 (not VARI x3) with a cutter diameter below half the slot width: material would stay in the slot; CYCLE73 with a cutter radius of 0 or less (line 6257) or below 10 µm (table: 铣刀半径太小)",
    },
    CatalogEntry {
        code: 61906,
        title: "too many contours",
        when: "a 16th island transferred by CYCLE75 (the edge and 15 islands are kept; table: 太多轮廓)",
    },
    CatalogEntry {
        code: 61908,
        title: "start point wrong",
        when: "CYCLE73 with a manual start point (_VARI 2xxx) where the cutter's centre may not be: in an island or closer than radius + _FAL to a wall (line 6831; table: 起始点说明出错)",
    },
    CatalogEntry {
        code: 61909,
        title: "helix radius too small",
        when: "CYCLE73 helical insertion (_VARI x2x) with _RAD 0, or a helix too small for the cutter (its diameter below the cutter radius: a core would stay; table: 螺旋线半径太小)",
    },
    CatalogEntry {
        code: 61910,
        title: "helix violates the contour",
        when: "CYCLE73 helical insertion at an automatic start point where the helix does not fit the pocket (table: 螺旋线破坏轮廓)",
    },
    CatalogEntry {
        code: 61911,
        title: "more insertion points required",
        when: "CYCLE73 pre-drilling of a pocket divided into more than the 32 parts a drilling pattern lists, or material the clearing cannot reach in 200 rounds of extra insertions (table: 要求更多的插入点)",
    },
    CatalogEntry {
        code: 61912,
        title: "no path generated",
        when: "a CYCLE73 pocket too narrow anywhere for the cutter's centre (radius + _FAL; table: 不要产生轨迹)",
    },
    CatalogEntry {
        code: 61913,
        title: "no rest material",
        when: "CYCLE73 rest material (_VARI xxx2) where the larger cutter of _TN left nothing this one can reach (table: 没有产生剩余材料)",
    },
    CatalogEntry {
        code: 61914,
        title: "programmed helix violates the contour",
        when: "CYCLE73 helical insertion at the manual start point (_PA/_PO) where the helix does not fit (table: 编程的螺旋线破坏轮廓)",
    },
    CatalogEntry {
        code: 61915,
        title: "approach/departure violates the contour",
        when: "CYCLE73 edge finish (_VARI xxx3) where no tangential approach arc fits beside a contour (table: 返回运行/离开运行破坏轮廓)",
    },
    CatalogEntry {
        code: 61916,
        title: "ramp too short",
        when: "CYCLE73 oscillating insertion (_VARI x3x) where the pocket leaves the ramp shorter than the cutter radius (table: 斜坡太短)",
    },
    CatalogEntry {
        code: 61918,
        title: "rest cutter radius too large",
        when: "CYCLE73 rest material (_VARI xxx2) with a cutter not smaller than tool _TN's, whose rest it clears (table: 剩余材料的铣刀半径太大)",
    },
    CatalogEntry {
        code: 61980,
        title: "island contour wrong",
        when: "CYCLE75 naming no contour, or an island that cannot be read, crosses itself, has no area, lies outside the edge or crosses it (table: 中心岛轮廓出错)",
    },
    CatalogEntry {
        code: 61982,
        title: "infeed width too large",
        when: "CYCLE73 _MIDA above 80 % of the cutter diameter (line 6808; table: 平面中进刀宽度太大)",
    },
    CatalogEntry {
        code: 61983,
        title: "pocket edge contour wrong",
        when: "CYCLE74 naming no contour, or an edge that cannot be read, crosses itself or has no area (table: 凹槽边缘轮廓出错)",
    },
    CatalogEntry {
        code: 61984,
        title: "_TN not defined",
        when: "CYCLE73 with _TN empty or not a tool number of the table (line 6736; table: 刀具参数_TN没有定义)",
    },
    CatalogEntry {
        code: 61985,
        title: "drilling positions program name wrong",
        when: "CYCLE73 pre-drilling (_VARI xxx5) with _BNAME empty (table: 钻孔位置程序名称出错)",
    },
    CatalogEntry {
        code: 61988,
        title: "pocket milling program name wrong",
        when: "CYCLE73 with _PNAME empty (table: 凹槽铣削程序名称出错)",
    },
    CatalogEntry {
        code: 61989,
        title: "D1 not the active tool edge",
        when: "CYCLE73 with a cutting edge other than D1 active (line 6760; table: 没有编程D1作为有效的刀具边沿)",
    },
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn catalog_is_sorted_and_unique() {
        for w in CATALOG.windows(2) {
            assert!(w[0].code < w[1].code, "{} before {}", w[0].code, w[1].code);
        }
    }

    /// One of every kind (a new variant must be added here and to CATALOG).
    const EVERY_KIND: &[AlarmKind] = {
        use AlarmKind::*;
        &[
            TooManyDigits { letter: b'X' },
            AddressNotFound { found: b'1' },
            NoDataAfterAddress { letter: b'X' },
            IllegalMinusSign { letter: b'M' },
            IllegalDecimalPoint { letter: b'N' },
            ImproperAddress { letter: b'D' },
            AxisNotConfigured { letter: b'Y' },
            ImproperGCode { code: GNum(910) },
            FeedZero,
            ArcRadiusTolerance { excess_nm: 1 },
            CurveEndOff { excess_nm: 1 },
            CurveEndOff { excess_nm: 1 },
            ArcAxisOutsidePlane { letter: b'Y' },
            ArcCenterMissing,
            ArcRadiusZero,
            IllegalOffsetNumber { number: 99 },
            IllegalToolNumber { number: 99 },
            MillToolNumber { number: 99, max: 24 },
            LocalFrameIncremental,
            IllegalReferenceNumber,
            ProgramNotFound { program: 12 },
            SubprogramNumberMissing,
            CallNestingTooDeep,
            MacroNestingTooDeep,
            ModalCallsTooDeep,
            IllegalArgumentAddress { letter: b'G' },
            VariablesFull,
            JumpTargetNotFound { seq: 10 },
            MacroOverflow,
            DivideByZero,
            MacroFormat { what: "x" },
            VariableNumberOutOfRange { number: 1000 },
            WriteProtectedVariable { number: 0 },
            TooManyBrackets,
            ArgumentOutOfRange { function: "SQRT" },
            ControlInMdi,
            MissingEnd { label: 1 },
            EndWithoutDo { label: 1 },
            LoopsCrossed { label: 1 },
            IllegalLoopNumber { label: 4 },
            MacroAndNcInOneBlock,
            SequenceOutOfRange,
            ReferenceNotEstablished { letter: b'X' },
            OvertravelPositive { letter: b'X' },
            OvertravelNegative { letter: b'X' },
            EndOfRecord,
            StrokeLimit2 { letter: b'X', plus: true },
            StrokeLimit2 { letter: b'X', plus: false },
            UnitsNotAlone,
            UnitsNotAtStart,
            DuplicateGroup { first: GNum(0), second: GNum(10) },
            DuplicateAddress { letter: b'X' },
            WordNotAllowed { letter: b'P', context: "G00" },
            MissingWord { letter: b'X', context: "G28" },
            NotSupportedYet { what: "x" },
            UnknownMCode { m: 77 },
            ConflictingMCodes { first: 3, second: 4 },
            TooManyMCodes,
            ValueOutOfRange { letter: b'S' },
            CoordinateSettingDisabled,
            FeedPerRevSpindleStopped,
            CommentNotClosed,
            MachineCoordinatesIncremental,
            CodeMustBeAlone { code: GNum(40) },
            Overflow,
            MisplacedBlockSkip,
            IllegalCharacter { found: b'?' },
            AxisTwice { absolute: b'X', incremental: b'U' },
            IllegalLead,
            CycleAddressMissing { letter: b'P' },
            CycleValueIllegal { what: "x" },
            SequenceNotFound { n: 10 },
            ProfileNotMonotone,
            ProfileFirstBlock,
            ProfileForbiddenCode { what: "x" },
            RigidTapSpeed,
            RigidTapSequence,
            RigidTapAxisMove,
            ProfileNotMonotoneInfeed,
            CycleTaperTooLarge,
            CycleNotInZxPlane,
            CycleOtherAxis { letter: b'Y' },
            ThreadStartAngle,
            ThreadPulloutTooLong,
            ProfileTooLong,
            TooManyPockets,
            CycleTooLong,
            SelfCall { program: 12 },
            FlowInMdi { m: 98 },
            M99NotAlone,
            InputNotAvailable { input: 40 },
            ThreadTooFast { letter: b'Z' },
            ThreadRampTooLong,
            SpindleNotTurning,
            SpindleNotAtSpeed,
            TapTooFast { letter: b'Z' },
            SpindleIndexMissing,
            SyncSequenceBroken,
            MotionConfigInvalid { what: "x" },
            EmergencyStop,
            ThreadLeadChangeTooFast { letter: b'Z' },
            ToolChangeTimeout { tool: 2, seconds: 30 },
            StreamStarved { seconds: 10 },
            ChamferInThread,
            ChamferNoMove { what: "x" },
            ChamferTooLarge,
            ChamferPlaneChange,
            ContourBufferFull,
            NoIntermediatePoint { letter: b'X' },
            FrameInCutterComp,
            FrameOrder,
            OffsetValueOutOfRange,
            ReferenceInCycle,
            PeckDepthMissing,
            IllegalScale { letter: b'P' },
            RotationPlaneChange,
            PolarCodeNotAllowed { code: GNum(0) },
            PolarArcNeedsR,
            PolygonNoToolSpindle,
            PolygonAxisCommanded,
            PolygonModeConflict { what: "x" },
            NoseCompArc,
            NoseCompPlaneChange,
            NoseCompReversed,
            ToolChangeInNoseComp,
            NoseCompGouge,
            NoseCompCornerAngle,
            Siemens(SiemensAlarm::SyntaxError { what: "x" }),
            Siemens(SiemensAlarm::TypeMismatch),
            Siemens(SiemensAlarm::ValueRange),
            Siemens(SiemensAlarm::StringTooLong),
            Siemens(SiemensAlarm::NameDefinedTwice),
            Siemens(SiemensAlarm::ParameterType { index: 1 }),
            Siemens(SiemensAlarm::TooManyParameters),
            Siemens(SiemensAlarm::TooManySymbols),
            Siemens(SiemensAlarm::UnknownGFunction { code: 5 }),
            Siemens(SiemensAlarm::NameNotDefined),
            Siemens(SiemensAlarm::SubprogramNotFound),
            Siemens(SiemensAlarm::SubprogramLevels),
            Siemens(SiemensAlarm::LabelNotFound),
            Siemens(SiemensAlarm::DefNotAtStart),
            Siemens(SiemensAlarm::ProcMissing),
            Siemens(SiemensAlarm::AxisProgrammedTwice { letter: b'X' }),
            Siemens(SiemensAlarm::IndexOutOfRange),
            Siemens(SiemensAlarm::IllegalDNumber { number: 99 }),
            Siemens(SiemensAlarm::ModalCallNested),
            SiemensCycle(CycleAlarm::NoToolOffset),
            SiemensCycle(CycleAlarm::ThreadPitchWrong),
            SiemensCycle(CycleAlarm::MachiningTypeWrong),
            SiemensCycle(CycleAlarm::NoFeed),
            SiemensCycle(CycleAlarm::NoThirdAxis),
            SiemensCycle(CycleAlarm::ToolNumberZero),
            SiemensCycle(CycleAlarm::ScaleNotAllowed),
            SiemensCycle(CycleAlarm::ScaleDiffers),
            SiemensCycle(CycleAlarm::ParameterWrong),
            SiemensCycle(CycleAlarm::ReferencePlaneWrong),
            SiemensCycle(CycleAlarm::NoSpindleDirection),
            SiemensCycle(CycleAlarm::HoleCountZero),
            SiemensCycle(CycleAlarm::CutterRadiusTooLarge),
            SiemensCycle(CycleAlarm::CircleElements),
            SiemensCycle(CycleAlarm::FirstDepthWrong),
            SiemensCycle(CycleAlarm::InsertionWrong),
            SiemensCycle(CycleAlarm::CdirWrong),
            SiemensCycle(CycleAlarm::FloorAllowanceTooLarge),
            SiemensCycle(CycleAlarm::InfeedWidthTooLarge),
            SiemensCycle(CycleAlarm::ToolRadiusNegative),
            SiemensCycle(CycleAlarm::CornerRadiusTooLarge),
            SiemensCycle(CycleAlarm::ApproachPathZero),
            SiemensCycle(CycleAlarm::ToolRadiusNotPositive),
            SiemensCycle(CycleAlarm::LengthOrWidthZero),
            SiemensCycle(CycleAlarm::InfeedWidthMissing),
            SiemensCycle(CycleAlarm::TechnologyWrong),
            SiemensCycle(CycleAlarm::SwivelDataNoName),
            SiemensCycle(CycleAlarm::TextLengthTooSmall),
            SiemensCycle(CycleAlarm::NoCodePage),
            SiemensCycle(CycleAlarm::CharacterMissing),
            SiemensCycle(CycleAlarm::CircleRadiusTooSmall),
            SiemensCycle(CycleAlarm::BlankWrong),
            SiemensCycle(CycleAlarm::FiveAxisNotSetUp),
            SiemensCycle(CycleAlarm::SecondFiveAxisNotSetUp),
            SiemensCycle(CycleAlarm::SplineNotSetUp),
            SiemensCycle(CycleAlarm::FinishedDiameterTooSmall),
            SiemensCycle(CycleAlarm::ToolWidthWrong),
            SiemensCycle(CycleAlarm::GrooveFormWrong),
            SiemensCycle(CycleAlarm::ToolViolatesContour),
            SiemensCycle(CycleAlarm::ContourWrong),
            SiemensCycle(CycleAlarm::ContourPreparation { cause: 10933 }),
            SiemensCycle(CycleAlarm::StartPointWrong),
            SiemensCycle(CycleAlarm::WrongEdgePosition),
            SiemensCycle(CycleAlarm::FormWrong),
            SiemensCycle(CycleAlarm::NoInfeedDepth),
            SiemensCycle(CycleAlarm::RecutImpossible),
            SiemensCycle(CycleAlarm::UndercutPositionWrong),
            SiemensCycle(CycleAlarm::FinishedContourWrong),
            SiemensCycle(CycleAlarm::BlankContourWrong),
            SiemensCycle(CycleAlarm::IllegalInput),
            SiemensCycle(CycleAlarm::ContourDirection),
            SiemensCycle(CycleAlarm::AxisNotPresent),
            SiemensCycle(CycleAlarm::WrongSpindleDirection),
            SiemensCycle(CycleAlarm::SlotContourViolated),
            SiemensCycle(CycleAlarm::InsertionAngleZero),
            SiemensCycle(CycleAlarm::CutterRadiusTooSmall),
            SiemensCycle(CycleAlarm::IslandPocket { code: 61900 }),
            SiemensCycle(CycleAlarm::IslandPocket { code: 61901 }),
            SiemensCycle(CycleAlarm::IslandPocket { code: 61903 }),
            SiemensCycle(CycleAlarm::IslandPocket { code: 61904 }),
            SiemensCycle(CycleAlarm::IslandPocket { code: 61906 }),
            SiemensCycle(CycleAlarm::IslandPocket { code: 61908 }),
            SiemensCycle(CycleAlarm::IslandPocket { code: 61909 }),
            SiemensCycle(CycleAlarm::IslandPocket { code: 61910 }),
            SiemensCycle(CycleAlarm::IslandPocket { code: 61911 }),
            SiemensCycle(CycleAlarm::IslandPocket { code: 61912 }),
            SiemensCycle(CycleAlarm::IslandPocket { code: 61913 }),
            SiemensCycle(CycleAlarm::IslandPocket { code: 61914 }),
            SiemensCycle(CycleAlarm::IslandPocket { code: 61915 }),
            SiemensCycle(CycleAlarm::IslandPocket { code: 61916 }),
            SiemensCycle(CycleAlarm::IslandPocket { code: 61918 }),
            SiemensCycle(CycleAlarm::IslandPocket { code: 61980 }),
            SiemensCycle(CycleAlarm::IslandPocket { code: 61982 }),
            SiemensCycle(CycleAlarm::IslandPocket { code: 61983 }),
            SiemensCycle(CycleAlarm::IslandPocket { code: 61984 }),
            SiemensCycle(CycleAlarm::IslandPocket { code: 61985 }),
            SiemensCycle(CycleAlarm::IslandPocket { code: 61988 }),
            SiemensCycle(CycleAlarm::IslandPocket { code: 61989 }),
        ]
    };

    #[test]
    fn every_kind_is_in_the_catalog() {
        for k in EVERY_KIND {
            assert!(CATALOG.iter().any(|e| e.code == k.code()), "{k:?} ({}) missing from CATALOG", k.code());
        }
        for e in CATALOG {
            assert!(EVERY_KIND.iter().any(|k| k.code() == e.code), "CATALOG row {} has no kind", e.code);
        }
    }

    /// Kinds whose text has a branch or a number format `EVERY_KIND` does not reach.
    #[cfg(all(feature = "siemens", feature = "mill"))]
    const MORE_TEXTS: &[AlarmKind] = {
        use AlarmKind::*;
        &[
            TooManyDigits { letter: 0x01 },
            AddressNotFound { found: 0xC3 },
            ImproperGCode { code: GNum(121) },
            ArcRadiusTolerance { excess_nm: 12_345_678_901 },
            ArcRadiusTolerance { excess_nm: -2_004_000 },
            CurveEndOff { excess_nm: 999_999 },
            ProgramNotFound { program: 123_456 },
            UnknownMCode { m: 5 },
            UnknownMCode { m: 198 },
            ConflictingMCodes { first: 103, second: 8 },
            VariableNumberOutOfRange { number: -7 },
            MillToolNumber { number: 0, max: 1 },
            ToolChangeTimeout { tool: 123, seconds: 0 },
            FlowInMdi { m: 1 },
            SelfCall { program: 99_999 },
            DuplicateGroup { first: GNum(21), second: GNum(1000) },
            Siemens(SiemensAlarm::UnknownGFunction { code: 65_535 }),
            Siemens(SiemensAlarm::ParameterType { index: 255 }),
            SiemensCycle(CycleAlarm::ContourPreparation { cause: 10930 }),
            SiemensCycle(CycleAlarm::ContourPreparation { cause: 10931 }),
            SiemensCycle(CycleAlarm::ContourPreparation { cause: 10934 }),
            SiemensCycle(CycleAlarm::ContourPreparation { cause: 15800 }),
            SiemensCycle(CycleAlarm::ContourPreparation { cause: 1 }),
        ]
    };

    /// Every alarm text exactly as the board sends it (`alarm_texts.txt`, made from
    /// the texts before they were packed: `ALARM_TEXTS_BLESS=1` writes it anew).
    #[cfg(all(feature = "siemens", feature = "mill"))]
    #[test]
    fn every_text_is_the_same_byte_for_byte() {
        use std::{format, string::String};
        let mut all = String::new();
        for k in EVERY_KIND.iter().chain(MORE_TEXTS) {
            all += &format!("{:04} {}\n", k.code(), k);
        }
        all += &format!("{}\n", Alarm::in_program(7, 12, AlarmKind::EndOfRecord));
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/src/alarm_texts.txt");
        if std::env::var_os("ALARM_TEXTS_BLESS").is_some() {
            std::fs::write(path, &all).unwrap();
        }
        let want = std::fs::read_to_string(path).unwrap();
        for (got, want) in all.lines().zip(want.lines()) {
            assert_eq!(got, want);
        }
        assert_eq!(all, want);
    }

    #[test]
    fn alarms_in_subprograms_name_the_program() {
        use core::fmt::Write;
        let mut s = heapless::String::<96>::new();
        write!(s, "{}", Alarm::in_program(12, 3, AlarmKind::JumpTargetNotFound { seq: 40 })).unwrap();
        assert_eq!(s.as_str(), "O0012 line 3: alarm 0078: sequence number N40 not found");
        s.clear();
        write!(s, "{}", Alarm::new(3, AlarmKind::TooManyBrackets)).unwrap();
        assert_eq!(s.as_str(), "line 3: alarm 0118: brackets nested deeper than 5 levels");
    }

    #[test]
    fn gnum_formats_like_the_manual() {
        use core::fmt::Write;
        let mut s = heapless::String::<16>::new();
        write!(s, "{} {} {}", GNum(10), GNum(21), GNum(121)).unwrap();
        assert_eq!(s.as_str(), "G01 G02.1 G12.1");
    }
}

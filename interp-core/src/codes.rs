//! The language tables: G codes of table 1.1 in systems A/B/C with their modal
//! groups, and the M codes of tables 1.2 and 3.1 with their timing.

use crate::config::{CodeTable, ConfigError, GCodeSystem, Language, MTiming, MachineConfig};

/// A G code by meaning, independent of the G-code system it was written in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum GCode {
    Rapid,
    Linear,
    ArcCw,
    ArcCcw,
    EllipseCw,
    EllipseCcw,
    ParabolaCw,
    ParabolaCcw,
    Dwell,
    ExactStopOnce,
    PolarOn,
    PolarOff,
    PlaneXy,
    PlaneZx,
    PlaneYz,
    TurningCycle,
    ThreadCycle,
    FacingCycle,
    ReferenceReturn,
    ReferenceReturnN,
    Thread,
    VariableLeadThread,
    NoseCompOff,
    NoseCompLeft,
    NoseCompRight,
    PolygonOn,
    PolygonOff,
    LocalFrame,
    MachineCoordinates,
    /// G54–G59: work frame 0–5.
    WorkFrame(u8),
    Inch,
    Metric,
    /// A SINUMERIK standard cycle call (`CYCLE95("KONTUR_1", …)` in a block of its
    /// own): no G number; to the engine one of the multiple cycles (next to them,
    /// so that testing for them stays one range compare). The bound call reaches
    /// the engine in the block's stage ([`crate::cycles::CycleStage::call`],
    /// [`crate::lang::siemens::call`]).
    CycleCall,
    FinishCycle,
    RoughTurnCycle,
    RoughFaceCycle,
    PatternCycle,
    FacePeckCycle,
    GroovePeckCycle,
    MultiThreadCycle,
    DrillCancel,
    FaceDrill,
    FaceTap,
    FaceBore,
    SideDrill,
    SideTap,
    SideBore,
    /// G50 (A) / G92 (B, C): coordinate setting and spindle clamp.
    SetCoordinates,
    FeedPerMin,
    FeedPerRev,
    CssOn,
    CssOff,
    StrokeCheckOn,
    StrokeCheckOff,
    ExactStopMode,
    ContinuousMode,
    /// G90 of systems B/C.
    Absolute,
    /// G91 of systems B/C.
    Incremental,
    /// G98 of systems B/C: drilling cycles return to the initial level.
    ReturnInitial,
    /// G99 of systems B/C: drilling cycles return to the R level.
    ReturnR,
    /// G290 (to SINUMERIK mode) / G291 (to the FANUC-style ISO dialect): the
    /// language the following blocks are read in, in a block of its own.
    Language(Language),
    // The M series of a machining centre (seed 004): meanings no lathe code has.
    /// G10: programmable data input (work offsets L2/L20, offset pages L10–L13).
    DataSetting,
    /// G15: polar coordinate command off.
    PolarCoordOff,
    /// G16: polar coordinate command (radius and angle in the plane).
    PolarCoordOn,
    /// G29: return from the reference position through G28's intermediate point.
    ReturnFromReference,
    /// G43: tool length compensation + (H).
    LengthPlus,
    /// G44: tool length compensation − (H).
    LengthMinus,
    /// G49: tool length compensation cancelled.
    LengthOff,
    /// G50: scaling off.
    ScalingOff,
    /// G51: scaling (P, or I/J/K per axis) about X/Y/Z.
    ScalingOn,
    /// G50.1: programmable mirror image off.
    MirrorOff,
    /// G51.1: programmable mirror image about the X/Y/Z given.
    MirrorOn,
    /// G54.1 P1–P48: an additional work frame.
    ExtraWorkFrame,
    /// G68: coordinate rotation by R about X/Y in the plane.
    RotationOn,
    /// G69: coordinate rotation off.
    RotationOff,
    /// G73: high-speed peck drilling (back by d after each peck).
    HighSpeedPeck,
    /// G74: left-hand (counter) tapping.
    LeftTap,
    /// G76: fine boring (oriented stop and shift Q at the bottom).
    FineBore,
    /// G81: drilling (feed in, rapid out).
    Drill,
    /// G82: drilling with a dwell at the bottom (counter boring).
    DrillDwell,
    /// G83: deep-hole peck drilling (back to R after each peck).
    PeckDrill,
    /// G84: right-hand tapping.
    Tap,
    /// G85: boring (feed in, feed out).
    Bore,
    /// G86: boring (spindle stop at the bottom, rapid out).
    BoreSpindleStop,
    /// G87: back boring.
    BackBore,
    /// G88: boring with a dwell, a stop for the operator and a rapid out.
    BoreManual,
    /// G89: boring with a dwell at the bottom, feed out.
    BoreDwell,
}

/// Modal groups (FANUC numbering in the comments). Group 00 codes act in their block only.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Group {
    /// 00: one-shot codes.
    NonModal,
    /// 01: motion and single cycles.
    Motion,
    /// 02: G96/G97.
    SpindleMode,
    /// 03: G90/G91 (systems B/C).
    Distance,
    /// 04: G22/G23.
    StrokeCheck,
    /// 05: G98/G99 (A), G94/G95 (B/C).
    FeedMode,
    /// 06: G20/G21.
    Units,
    /// 07: G40/G41/G42.
    NoseComp,
    /// 10: drilling cycles and G80.
    Drilling,
    /// 11: G98/G99 return level (B/C).
    ReturnLevel,
    /// 14: G54–G59.
    WorkFrame,
    /// 15: G61/G64.
    PathMode,
    /// 16: G17/G18/G19.
    Plane,
    /// 20: G50.2/G51.2.
    Polygon,
    /// 21: G12.1/G13.1.
    Polar,
    /// Mill 08: G43/G44/G49.
    LengthComp,
    /// Mill 11: G50/G51.
    Scaling,
    /// Mill 22: G50.1/G51.1.
    Mirror,
    /// Mill 16: G68/G69.
    Rotation,
    /// Mill 17: G15/G16.
    PolarCoord,
}

impl GCode {
    /// The G code written as `G<tenths/10>` in `table`, if it exists there.
    #[inline]
    pub fn from_tenths(table: CodeTable, tenths: u16) -> Option<GCode> {
        match table {
            CodeTable::Lathe(system) => Self::lathe(system, tenths),
            CodeTable::Mill if crate::MILL => Self::mill(tenths),
            CodeTable::Mill => None,
        }
    }

    /// The lathe's table 1.1 in `system`.
    fn lathe(system: GCodeSystem, tenths: u16) -> Option<GCode> {
        use GCode::*;
        let common = match tenths {
            0 => Rapid,
            10 => Linear,
            20 => ArcCw,
            30 => ArcCcw,
            21 => EllipseCw,
            31 => EllipseCcw,
            22 => ParabolaCw,
            32 => ParabolaCcw,
            40 => Dwell,
            90 => ExactStopOnce,
            121 => PolarOn,
            131 => PolarOff,
            170 => PlaneXy,
            180 => PlaneZx,
            190 => PlaneYz,
            220 => StrokeCheckOn,
            230 => StrokeCheckOff,
            280 => ReferenceReturn,
            300 => ReferenceReturnN,
            340 => VariableLeadThread,
            400 => NoseCompOff,
            410 => NoseCompLeft,
            420 => NoseCompRight,
            502 => PolygonOff,
            512 => PolygonOn,
            520 => LocalFrame,
            530 => MachineCoordinates,
            540..=590 if tenths.is_multiple_of(10) => WorkFrame(((tenths - 540) / 10) as u8),
            610 => ExactStopMode,
            640 => ContinuousMode,
            800 => DrillCancel,
            830 => FaceDrill,
            840 => FaceTap,
            850 => FaceBore,
            870 => SideDrill,
            880 => SideTap,
            890 => SideBore,
            960 => CssOn,
            970 => CssOff,
            2900 => Language(crate::config::Language::Siemens),
            2910 => Language(crate::config::Language::Fanuc),
            _ => return Self::system_specific(system, tenths),
        };
        Some(common)
    }

    /// The M series of a machining centre (FANUC 0i-M, seed 004). A number the
    /// table does not hold is alarm 0010, so a lathe code never silently means
    /// something on a mill (G71, G76, G96, G32, G12.1, G50.2/G51.2 …).
    fn mill(tenths: u16) -> Option<GCode> {
        use GCode::*;
        Some(match tenths {
            0 => Rapid,
            10 => Linear,
            20 => ArcCw,
            30 => ArcCcw,
            40 => Dwell,
            90 => ExactStopOnce,
            100 => DataSetting,
            150 => PolarCoordOff,
            160 => PolarCoordOn,
            170 => PlaneXy,
            180 => PlaneZx,
            190 => PlaneYz,
            200 => Inch,
            210 => Metric,
            220 => StrokeCheckOn,
            230 => StrokeCheckOff,
            280 => ReferenceReturn,
            290 => ReturnFromReference,
            300 => ReferenceReturnN,
            400 => NoseCompOff,
            410 => NoseCompLeft,
            420 => NoseCompRight,
            430 => LengthPlus,
            440 => LengthMinus,
            490 => LengthOff,
            500 => ScalingOff,
            501 => MirrorOff,
            510 => ScalingOn,
            511 => MirrorOn,
            520 => LocalFrame,
            530 => MachineCoordinates,
            540..=590 if tenths.is_multiple_of(10) => WorkFrame(((tenths - 540) / 10) as u8),
            541 => ExtraWorkFrame,
            610 => ExactStopMode,
            640 => ContinuousMode,
            680 => RotationOn,
            690 => RotationOff,
            730 => HighSpeedPeck,
            740 => LeftTap,
            760 => FineBore,
            800 => DrillCancel,
            810 => Drill,
            820 => DrillDwell,
            830 => PeckDrill,
            840 => Tap,
            850 => Bore,
            860 => BoreSpindleStop,
            870 => BackBore,
            880 => BoreManual,
            890 => BoreDwell,
            900 => Absolute,
            910 => Incremental,
            920 => SetCoordinates,
            940 => FeedPerMin,
            950 => FeedPerRev,
            980 => ReturnInitial,
            990 => ReturnR,
            2900 => Language(crate::config::Language::Siemens),
            2910 => Language(crate::config::Language::Fanuc),
            _ => return None,
        })
    }

    /// Codes whose number differs between systems (table 1.1 columns).
    fn system_specific(system: GCodeSystem, tenths: u16) -> Option<GCode> {
        use GCode::*;
        use GCodeSystem::*;
        Some(match (system, tenths) {
            (A, 200) | (B, 200) | (C, 700) => Inch,
            (A, 210) | (B, 210) | (C, 710) => Metric,
            (A, 320) | (B, 330) | (C, 330) => Thread,
            (A, 500) | (B, 920) | (C, 920) => SetCoordinates,
            (A, 700) | (B, 700) | (C, 720) => FinishCycle,
            (A, 710) | (B, 710) | (C, 730) => RoughTurnCycle,
            (A, 720) | (B, 720) | (C, 740) => RoughFaceCycle,
            (A, 730) | (B, 730) | (C, 750) => PatternCycle,
            (A, 740) | (B, 740) | (C, 760) => FacePeckCycle,
            (A, 750) | (B, 750) | (C, 770) => GroovePeckCycle,
            (A, 760) | (B, 760) | (C, 780) => MultiThreadCycle,
            (A, 900) | (B, 770) | (C, 200) => TurningCycle,
            (A, 920) | (B, 780) | (C, 210) => ThreadCycle,
            (A, 940) | (B, 790) | (C, 240) => FacingCycle,
            (A, 980) | (B, 940) | (C, 940) => FeedPerMin,
            (A, 990) | (B, 950) | (C, 950) => FeedPerRev,
            (B, 900) | (C, 900) => Absolute,
            (B, 910) | (C, 910) => Incremental,
            (B, 980) | (C, 980) => ReturnInitial,
            (B, 990) | (C, 990) => ReturnR,
            _ => return None,
        })
    }

    /// The modal group of the code.
    #[inline(always)]
    pub fn group(self) -> Group {
        use GCode::*;
        match self {
            Rapid | Linear | ArcCw | ArcCcw | EllipseCw | EllipseCcw | ParabolaCw | ParabolaCcw | Thread
            | VariableLeadThread | TurningCycle | ThreadCycle | FacingCycle => Group::Motion,
            Dwell | ExactStopOnce | ReferenceReturn | ReferenceReturnN | LocalFrame | MachineCoordinates
            | SetCoordinates | FinishCycle | RoughTurnCycle | RoughFaceCycle | PatternCycle | FacePeckCycle
            | GroovePeckCycle | MultiThreadCycle | Language(_) | CycleCall | DataSetting | ReturnFromReference => {
                Group::NonModal
            }
            CssOn | CssOff => Group::SpindleMode,
            Absolute | Incremental => Group::Distance,
            StrokeCheckOn | StrokeCheckOff => Group::StrokeCheck,
            FeedPerMin | FeedPerRev => Group::FeedMode,
            Inch | Metric => Group::Units,
            NoseCompOff | NoseCompLeft | NoseCompRight => Group::NoseComp,
            DrillCancel | FaceDrill | FaceTap | FaceBore | SideDrill | SideTap | SideBore | HighSpeedPeck | LeftTap
            | FineBore | Drill | DrillDwell | PeckDrill | Tap | Bore | BoreSpindleStop | BackBore | BoreManual
            | BoreDwell => Group::Drilling,
            ReturnInitial | ReturnR => Group::ReturnLevel,
            WorkFrame(_) | ExtraWorkFrame => Group::WorkFrame,
            ExactStopMode | ContinuousMode => Group::PathMode,
            PlaneXy | PlaneZx | PlaneYz => Group::Plane,
            PolygonOn | PolygonOff => Group::Polygon,
            PolarOn | PolarOff => Group::Polar,
            LengthPlus | LengthMinus | LengthOff => Group::LengthComp,
            ScalingOn | ScalingOff => Group::Scaling,
            MirrorOn | MirrorOff => Group::Mirror,
            RotationOn | RotationOff => Group::Rotation,
            PolarCoordOn | PolarCoordOff => Group::PolarCoord,
        }
    }
}

/// What an M code does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum MFunction {
    /// M00: program stop.
    Stop,
    /// M01: optional stop (only with the optional-stop switch on).
    OptionalStop,
    /// M02: end of program.
    End,
    /// M30: end of program and rewind.
    EndRewind,
    /// M03: spindle clockwise.
    SpindleCw,
    /// M04: spindle counter-clockwise.
    SpindleCcw,
    /// M05: spindle stop.
    SpindleStop,
    /// M98: call a subprogram (3.1.6).
    Call,
    /// M99: return from a subprogram, or restart the main program (3.1.7).
    Return,
    /// M91: jump when the external input is 0 (3.1.5).
    JumpIfLow,
    /// M92: jump when the external input is 1 (3.1.5).
    JumpIfHigh,
    /// M06 of a machining centre: the tool selected by T goes into the spindle
    /// (seed 004 @813, @10392).
    ToolChange,
    /// Any other M code: a machine output switched before or after the motion.
    Aux(MTiming),
}

impl MFunction {
    /// Whether the code changes where the program goes on (M98, M99, M91, M92).
    pub fn is_flow(self) -> bool {
        matches!(self, MFunction::Call | MFunction::Return | MFunction::JumpIfLow | MFunction::JumpIfHigh)
    }
}

/// Conflict class of an M code: two codes of one class in a block contradict
/// each other (M07 and M08 may be on together, so coolant-on codes have none).
fn m_class(m: u16) -> Option<u8> {
    Some(match m {
        // Stops, ends, calls, returns and jumps: at most one per block.
        0 | 1 | 2 | 30 | 91 | 92 | 98 | 99 => 0,
        // M06 and M29 start things that exclude each other and the stops.
        6 => 0,
        3..=5 => 1,
        9 => 2,
        10 | 11 => 3,
        12 | 13 => 4,
        19 | 20 => 5,
        31..=33 => 6,
        41..=44 => 7,
        45..=48 => 8,
        63..=65 => 9,
        _ => return None,
    })
}

/// Whether M codes `a` and `b` in one block contradict each other.
pub fn m_codes_conflict(a: u16, b: u16) -> bool {
    if a == b {
        return true;
    }
    let coolant = |m| matches!(m, 7..=9);
    if coolant(a) && coolant(b) {
        return a == 9 || b == 9;
    }
    matches!((m_class(a), m_class(b)), (Some(x), Some(y)) if x == y)
}

/// The function of M code `m` on this machine, `None` if unknown.
///
/// Timing follows the usual ladder (seed 003 2.2.2: "前置 G00 M03, 后置 G00 M02"):
/// codes that switch something on act before the motion, codes that switch off or
/// stop act after it.
pub fn m_function(m: u16, cfg: &MachineConfig) -> Option<MFunction> {
    use MTiming::{After, Before};
    Some(match m {
        0 => MFunction::Stop,
        1 => MFunction::OptionalStop,
        2 => MFunction::End,
        30 => MFunction::EndRewind,
        91 => MFunction::JumpIfLow,
        92 => MFunction::JumpIfHigh,
        98 => MFunction::Call,
        99 => MFunction::Return,
        3 => MFunction::SpindleCw,
        4 => MFunction::SpindleCcw,
        5 => MFunction::SpindleStop,
        6 if crate::is_mill(cfg) => MFunction::ToolChange,
        7 | 8 | 10 | 12 | 19 | 20 | 29 | 31 | 32 | 41..=48 | 63 | 64 => MFunction::Aux(Before),
        9 | 11 | 13 | 33 | 65 => MFunction::Aux(After),
        _ => return cfg.user_m(m).map(|u| MFunction::Aux(u.timing)),
    })
}

/// Checks the machine's user M codes (after [`MachineConfig::validate`]): none of
/// them a code the manual's tables already define, none listed twice.
pub fn check_user_m_codes(cfg: &MachineConfig) -> Result<(), ConfigError> {
    let standard = MachineConfig { kind: cfg.kind, ..MachineConfig::default() };
    for (i, u) in cfg.user_m_codes.iter().enumerate() {
        if m_function(u.m, &standard).is_some() {
            return Err(ConfigError::UserMStandard { m: u.m });
        }
        if cfg.user_m_codes[..i].iter().any(|o| o.m == u.m) {
            return Err(ConfigError::UserMTwice { m: u.m });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn systems_map_the_cycles_of_table_1_1() {
        let (a, b, c) =
            (CodeTable::Lathe(GCodeSystem::A), CodeTable::Lathe(GCodeSystem::B), CodeTable::Lathe(GCodeSystem::C));
        assert_eq!(GCode::from_tenths(a, 900), Some(GCode::TurningCycle));
        assert_eq!(GCode::from_tenths(b, 770), Some(GCode::TurningCycle));
        assert_eq!(GCode::from_tenths(c, 200), Some(GCode::TurningCycle));
        assert_eq!(GCode::from_tenths(c, 700), Some(GCode::Inch));
        assert_eq!(GCode::from_tenths(a, 200), Some(GCode::Inch));
        assert_eq!(GCode::from_tenths(b, 900), Some(GCode::Absolute));
        assert_eq!(GCode::from_tenths(a, 910), None);
        assert_eq!(GCode::from_tenths(a, 990), Some(GCode::FeedPerRev));
        assert_eq!(GCode::from_tenths(b, 950), Some(GCode::FeedPerRev));
        assert_eq!(GCode::from_tenths(a, 570), Some(GCode::WorkFrame(3)));
        assert_eq!(GCode::from_tenths(a, 545), None);
        assert_eq!(GCode::from_tenths(a, 500), Some(GCode::SetCoordinates));
        assert_eq!(GCode::from_tenths(b, 920), Some(GCode::SetCoordinates));
        assert_eq!(GCode::from_tenths(a, 70), None);
    }

    /// A build without the `mill` feature has no M-series table: a machine of
    /// kind mill (refused by the board's `$311`) would read no G code (alarm 0010).
    #[cfg(not(feature = "mill"))]
    #[test]
    fn without_the_mill_feature_the_mill_table_is_empty() {
        for tenths in [0, 10, 170, 430, 810, 900] {
            assert_eq!(GCode::from_tenths(CodeTable::Mill, tenths), None);
        }
        assert!(!crate::MILL);
    }

    /// The mill's table holds no lathe-only code: the same number never silently
    /// means the lathe's cycle on a mill (alarm 0010 instead), and the numbers the
    /// M series uses for something else mean its own code.
    #[cfg(feature = "mill")]
    #[test]
    fn the_mill_table_refuses_lathe_codes() {
        let m = CodeTable::Mill;
        let a = CodeTable::Lathe(GCodeSystem::A);
        for lathe_only in [121, 131, 320, 340, 502, 512, 700, 710, 720, 750, 960, 970, 21, 22, 31, 32] {
            assert_eq!(GCode::from_tenths(m, lathe_only), None, "G{}", lathe_only / 10);
        }
        for (tenths, mill) in [
            (500, GCode::ScalingOff),
            (510, GCode::ScalingOn),
            (730, GCode::HighSpeedPeck),
            (740, GCode::LeftTap),
            (760, GCode::FineBore),
            (830, GCode::PeckDrill),
            (840, GCode::Tap),
            (850, GCode::Bore),
            (870, GCode::BackBore),
            (880, GCode::BoreManual),
            (890, GCode::BoreDwell),
            (900, GCode::Absolute),
            (920, GCode::SetCoordinates),
            (980, GCode::ReturnInitial),
            (990, GCode::ReturnR),
        ] {
            assert_eq!(GCode::from_tenths(m, tenths), Some(mill), "G{}", tenths / 10);
            assert_ne!(GCode::from_tenths(a, tenths), Some(mill), "G{} means the same on a lathe", tenths / 10);
        }
        assert_eq!(GCode::from_tenths(m, 940), Some(GCode::FeedPerMin));
        assert_eq!(GCode::from_tenths(m, 170), Some(GCode::PlaneXy));
        assert_eq!(GCode::from_tenths(m, 541), Some(GCode::ExtraWorkFrame));
        assert_eq!(GCode::from_tenths(m, 511), Some(GCode::MirrorOn));
        for (t, g) in [(810, GCode::Drill), (820, GCode::DrillDwell), (860, GCode::BoreSpindleStop)] {
            assert_eq!(GCode::from_tenths(m, t), Some(g));
            assert_eq!(GCode::from_tenths(a, t), None, "G{} is no lathe code", t / 10);
        }
        for t in [CodeTable::Mill, CodeTable::Lathe(GCodeSystem::A), CodeTable::Lathe(GCodeSystem::C)] {
            assert_eq!(GCode::from_tenths(t, 2900), Some(GCode::Language(Language::Siemens)));
            assert_eq!(GCode::from_tenths(t, 2910), Some(GCode::Language(Language::Fanuc)));
        }
    }

    #[test]
    fn conflicting_m_codes() {
        assert!(m_codes_conflict(3, 4));
        assert!(m_codes_conflict(8, 9));
        assert!(!m_codes_conflict(7, 8));
        assert!(!m_codes_conflict(3, 8));
        assert!(m_codes_conflict(41, 42));
        assert!(m_codes_conflict(0, 30));
        assert!(m_codes_conflict(98, 30));
        assert!(m_codes_conflict(91, 99));
        assert!(!m_codes_conflict(98, 8));
    }

    #[test]
    fn user_m_codes_must_be_new_and_unique() {
        use crate::config::UserMCode;
        assert_eq!(check_user_m_codes(&MachineConfig::default()), Ok(()));
        let mut c = MachineConfig::default();
        c.user_m_codes.push(UserMCode { m: 8, timing: MTiming::After }).unwrap();
        assert_eq!(check_user_m_codes(&c), Err(ConfigError::UserMStandard { m: 8 }));
        let mut c = MachineConfig::default();
        c.user_m_codes.push(UserMCode { m: 50, timing: MTiming::After }).unwrap();
        c.user_m_codes.push(UserMCode { m: 50, timing: MTiming::Before }).unwrap();
        assert_eq!(check_user_m_codes(&c), Err(ConfigError::UserMTwice { m: 50 }));
    }
}

//! The numbered parameter set: every parameter the manual refers to by number, with
//! its meaning, unit and default. This is the one place parameters are defined;
//! machine files set them by number, programs may update some (G71 U(Δd) writes 5147).

/// How a parameter's value is written in a machine file and stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ParamUnit {
    /// 0 or 1.
    Bool,
    /// A whole number (a count, a code, digits).
    Count,
    /// Millimetres in the file, nanometres stored.
    Mm,
    /// Millimetres per minute in the file, nanometres per minute stored.
    MmPerMin,
    /// Milliseconds.
    Ms,
    /// Whole degrees.
    Deg,
    /// Tenths of the thread lead (parameter 5130).
    TenthLead,
}

/// A parameter: what the manual calls "参数 NO.n".
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(u8)]
pub enum Param {
    /// No.10: inch input at power-on (2.9 note 1).
    InchAtPowerOn,
    /// No.405: F at power-up for both G98 and G99 memories (2.20 note 5).
    InitialFeed,
    /// No.1002: stored stroke check 2 forbids 0 = the inside, 1 = the outside of its box (2.10 note 3).
    Stroke2Outside,
    /// No.1360: stored stroke check 2, + limit of X (machine, diameter).
    Stroke2PlusX,
    /// No.1361: + limit of Y.
    Stroke2PlusY,
    /// No.1362: + limit of Z.
    Stroke2PlusZ,
    /// No.1370: stored stroke check 2, - limit of X (machine, diameter).
    Stroke2MinusX,
    /// No.1371: - limit of Y.
    Stroke2MinusY,
    /// No.1372: - limit of Z.
    Stroke2MinusZ,
    /// No.3401#0 (DPI, seed 004): 1 = calculator-type input, 0 = least increment.
    CalculatorInput,
    /// No.3403: G02/G03 without R/I/J/K: 1 = straight line, 0 = alarm 0022 (2.3 note 2).
    ArcWithoutCenterIsLine,
    /// No.3410: tolerance of the arc end-point radius (2.3, 2.16.1 note 5).
    ArcRadiusTolerance,
    /// No.5002: digits of the offset number at the end of a T word (1 or 2).
    OffsetDigits,
    /// No.5101: G83/G87 with Q: 0 = high-speed peck, 1 = deep peck (2.21.1).
    DeepPeckDrilling,
    /// No.5102: G84/G88 with Q: 0 = high-speed peck, 1 = deep peck tapping (2.22.2).
    DeepPeckTapping,
    /// No.5113: return / clearance d of peck drilling (2.21.1).
    PeckDrillClearance,
    /// No.5114: return / clearance d of peck tapping (2.22.2).
    PeckTapClearance,
    /// No.5130: thread pull-out (chamfer) in 0.1 × lead (2.17.3, 2.17.4).
    ThreadChamfer,
    /// No.5131: thread pull-out angle of G92 and G76, degrees; 0 = 45° (2.17.3). The
    /// manual's G76 table says P(a) writes 5131; its note 4 and FANUC say 5143.
    ThreadChamferAngle,
    /// No.5139: retract e of G74/G75 (2.16.5).
    GrooveRetract,
    /// No.5140: minimum depth Δdmin of G76 (2.17.4).
    ThreadMinDepth,
    /// No.5141: finishing allowance d of G76 (2.17.4).
    ThreadFinishAllowance,
    /// No.5142: finishing repetitions m of G76 (2.17.4).
    ThreadFinishCount,
    /// No.5143: tool angle a of G76 (2.17.4).
    ThreadToolAngle,
    /// No.5144: relief Δi of G73 in X (radius) (2.16.3).
    PatternReliefX,
    /// No.5145: relief Δk of G73 in Z (2.16.3).
    PatternReliefZ,
    /// No.5146: number of divisions d of G73 (2.16.3).
    PatternDivisions,
    /// No.5147: depth of cut Δd of G71/G72 (2.16.1).
    RoughingDepth,
    /// No.5148: retract e of G71/G72 (2.16.1).
    RoughingRetract,
    /// No.5149: where a machining centre's G76/G87 shift the tool after the
    /// oriented stop: 1 = +X, 2 = −X, 3 = +Y, 4 = −Y (FANUC 0i-M: 5101 #4/#5).
    BoreShiftDirection,
    /// No.5152: 1 = G50 coordinate setting disabled (2.12.1 note 3).
    DisableCoordinateSetting,
    /// No.5153: motion mode at power-on: 0 = G00, 1 = G01 (2.1 note 2).
    InitialLinear,
    /// No.5154: feed mode at power-on: 0 = G98 per minute, 1 = G99 per revolution (2.20 note 1).
    InitialPerRev,
    /// No.5160: 1 = reset cancels the G52 local frame (2.12.3 note 5).
    ResetCancelsLocal,
    /// No.5170: 1 = reverse-thread rigid tapping option (2.22.2).
    ReverseTapping,
    /// No.6001#5 (TCS, FANUC 0i): 1 = a T code calls subprogram O9000, the T value in #149.
    TCodeCall,
    /// No.6023: maximum cutting feed along the path (2.2 note 3).
    MaxCuttingFeed,
    /// No.6050 (FANUC 0i): the G code that calls macro O9010 (0 = none).
    CallG9010,
    /// No.6051 (FANUC 0i): the G code that calls macro O9011 (0 = none).
    CallG9011,
    /// No.6052 (FANUC 0i): the G code that calls macro O9012 (0 = none).
    CallG9012,
    /// No.6053 (FANUC 0i): the G code that calls macro O9013 (0 = none).
    CallG9013,
    /// No.6054 (FANUC 0i): the G code that calls macro O9014 (0 = none).
    CallG9014,
    /// No.6055 (FANUC 0i): the G code that calls macro O9015 (0 = none).
    CallG9015,
    /// No.6056 (FANUC 0i): the G code that calls macro O9016 (0 = none).
    CallG9016,
    /// No.6057 (FANUC 0i): the G code that calls macro O9017 (0 = none).
    CallG9017,
    /// No.6058 (FANUC 0i): the G code that calls macro O9018 (0 = none).
    CallG9018,
    /// No.6059 (FANUC 0i): the G code that calls macro O9019 (0 = none).
    CallG9019,
    /// No.6071 (FANUC 0i): the M code that calls subprogram O9001 (0 = none).
    SubM9001,
    /// No.6072 (FANUC 0i): the M code that calls subprogram O9002 (0 = none).
    SubM9002,
    /// No.6073 (FANUC 0i): the M code that calls subprogram O9003 (0 = none).
    SubM9003,
    /// No.6074 (FANUC 0i): the M code that calls subprogram O9004 (0 = none).
    SubM9004,
    /// No.6075 (FANUC 0i): the M code that calls subprogram O9005 (0 = none).
    SubM9005,
    /// No.6076 (FANUC 0i): the M code that calls subprogram O9006 (0 = none).
    SubM9006,
    /// No.6077 (FANUC 0i): the M code that calls subprogram O9007 (0 = none).
    SubM9007,
    /// No.6078 (FANUC 0i): the M code that calls subprogram O9008 (0 = none).
    SubM9008,
    /// No.6079 (FANUC 0i): the M code that calls subprogram O9009 (0 = none).
    SubM9009,
    /// No.6080 (FANUC 0i): the M code that calls macro O9020 (0 = none).
    CallM9020,
    /// No.6081 (FANUC 0i): the M code that calls macro O9021 (0 = none).
    CallM9021,
    /// No.6082 (FANUC 0i): the M code that calls macro O9022 (0 = none).
    CallM9022,
    /// No.6083 (FANUC 0i): the M code that calls macro O9023 (0 = none).
    CallM9023,
    /// No.6084 (FANUC 0i): the M code that calls macro O9024 (0 = none).
    CallM9024,
    /// No.6085 (FANUC 0i): the M code that calls macro O9025 (0 = none).
    CallM9025,
    /// No.6086 (FANUC 0i): the M code that calls macro O9026 (0 = none).
    CallM9026,
    /// No.6087 (FANUC 0i): the M code that calls macro O9027 (0 = none).
    CallM9027,
    /// No.6088 (FANUC 0i): the M code that calls macro O9028 (0 = none).
    CallM9028,
    /// No.6089 (FANUC 0i): the M code that calls macro O9029 (0 = none).
    CallM9029,
    /// No.7013: dwell at R point in rigid tapping (2.22.2).
    TapDwellAtR,
}

/// Definition of a parameter: number, unit, default (in file units) and meaning.
#[derive(Clone, Copy, Debug)]
pub struct ParamDef {
    /// The parameter.
    pub id: Param,
    /// The manual's number ("NO.n").
    pub number: u16,
    /// Unit of the value in machine files.
    pub unit: ParamUnit,
    /// Default, in file units.
    pub default: f64,
}

impl ParamDef {
    /// What it does (for `lathe params` and docs/PARAMETERS.md). The texts are a
    /// table of their own, apart from [`PARAMS`]: the board looks parameters up by
    /// number and never shows a meaning, so 5 KB of text stay out of its flash.
    pub fn meaning(&self) -> &'static str {
        MEANINGS[self.id as usize]
    }
}

macro_rules! defs {
    ($($id:ident $num:literal $unit:ident $def:literal $text:literal;)*) => {
        /// Every parameter, in the order of [`Param`].
        pub const PARAMS: &[ParamDef] = &[
            $(ParamDef { id: Param::$id, number: $num, unit: ParamUnit::$unit, default: $def },)*
        ];
        /// What each parameter of [`PARAMS`] does, in the same order.
        const MEANINGS: &[&str] = &[$($text,)*];
    };
}

defs! {
    InchAtPowerOn 10 Bool 0.0 "1 = G20 (inch) at power-on, 0 = G21 (2.9 note 1)";
    InitialFeed 405 Count 0.0 "F value of both G98 and G99 memories at power-on (2.20 note 5)";
    Stroke2Outside 1002 Bool 0.0 "stored stroke check 2 (G22): 0 = the inside of the box is forbidden, 1 = the outside (2.10 note 3)";
    Stroke2PlusX 1360 Mm 0.0 "G22 box without words: + limit of X, machine coordinates, diameter (2.10)";
    Stroke2PlusY 1361 Mm 0.0 "G22 box: + limit of Y, machine coordinates (2.10)";
    Stroke2PlusZ 1362 Mm 0.0 "G22 box: + limit of Z, machine coordinates (2.10)";
    Stroke2MinusX 1370 Mm 0.0 "G22 box: - limit of X, machine coordinates, diameter; above 1360 switches the check off (2.10 note 8)";
    Stroke2MinusY 1371 Mm 0.0 "G22 box: - limit of Y, machine coordinates (2.10)";
    Stroke2MinusZ 1372 Mm 0.0 "G22 box: - limit of Z, machine coordinates (2.10)";
    CalculatorInput 3401 Bool 1.0 "1 = calculator-type input (X60 = 60 mm), 0 = least increment (X60 = 0.060 mm)";
    ArcWithoutCenterIsLine 3403 Bool 0.0 "G02/G03 without R and I/J/K: 1 = straight line, 0 = alarm 0022 (2.3 note 2)";
    ArcRadiusTolerance 3410 Mm 0.01 "allowed difference of start and end radius of an arc (2.3)";
    OffsetDigits 5002 Count 2.0 "digits of the offset number at the end of T (T0101: 2)";
    DeepPeckDrilling 5101 Bool 0.0 "G83/G87 with Q: 0 = high-speed peck (back d of 5113), 1 = deep peck (back to R each peck) (2.21.1)";
    DeepPeckTapping 5102 Bool 0.0 "rigid G84/G88 with Q: 0 = high-speed peck (back d of 5114), 1 = deep peck (back to R) (2.22.2)";
    PeckDrillClearance 5113 Mm 0.5 "G83/G87 peck (mill: G73, G83): return d (high-speed) or clearance above the last depth (deep), mm (2.21.1)";
    PeckTapClearance 5114 Mm 0.5 "rigid tapping peck: return d of the high-speed peck, mm (2.22.2)";
    ThreadChamfer 5130 TenthLead 10.0 "G92/G76 pull-out along the long axis in 0.1 x lead (10 = one lead); G76 P(r) sets it (2.17.3 note 1, 2.17.4)";
    ThreadChamferAngle 5131 Deg 0.0 "G92/G76 pull-out angle from the long axis, degrees; 0 = 45 (2.17.3 note 1)";
    GrooveRetract 5139 Mm 0.1 "G74/G75 retract e after each peck, mm; G74/G75 R(e) sets it (2.16.5, 2.16.6)";
    ThreadMinDepth 5140 Mm 0.1 "G76 minimum depth of cut dmin, mm radius; G76 Q(dmin) sets it (2.17.4)";
    ThreadFinishAllowance 5141 Mm 0.05 "G76 finishing allowance d, mm radius; G76 R(d) sets it (2.17.4)";
    ThreadFinishCount 5142 Count 1.0 "G76 finishing passes m (1-99); G76 P(m) sets it (2.17.4)";
    ThreadToolAngle 5143 Deg 60.0 "G76 tool angle a, degrees (0-99); G76 P(a) sets it (2.17.4 note 4)";
    PatternReliefX 5144 Mm 0.0 "G73 relief di in X, mm radius, signed; G73 U(di) sets it (2.16.3)";
    PatternReliefZ 5145 Mm 0.0 "G73 relief dk in Z, mm, signed; G73 W(dk) sets it (2.16.3)";
    PatternDivisions 5146 Count 1.0 "G73 number of passes d; G73 R(d) sets it (2.16.3)";
    RoughingDepth 5147 Mm 1.0 "depth of cut dd of G71/G72, mm (G71: radius); G71 U(dd) / G72 W(dd) set it (2.16.1, 2.16.2)";
    RoughingRetract 5148 Mm 0.5 "G71/G72 retract e (45 degrees), mm; G71/G72 R(e) sets it (2.16.1, 2.16.2)";
    BoreShiftDirection 5149 Count 1.0 "mill G76/G87: direction of the shift Q after the oriented spindle stop, 1 = +X, 2 = -X, 3 = +Y, 4 = -Y (FANUC 0i-M 5101 #4/#5)";
    DisableCoordinateSetting 5152 Bool 0.0 "1 = G50 X/Z coordinate setting disabled (2.12.1 note 3)";
    InitialLinear 5153 Bool 0.0 "motion mode at power-on: 0 = G00, 1 = G01 (2.1 note 2)";
    InitialPerRev 5154 Bool 0.0 "feed mode at power-on: 0 = G98 per minute, 1 = G99 per revolution (2.20 note 1)";
    ResetCancelsLocal 5160 Bool 0.0 "1 = reset cancels the G52 local coordinate system (2.12.3 note 5)";
    ReverseTapping 5170 Bool 0.0 "rigid tapping spindle direction: 0 = M03 in, M04 out; 1 = M04 in, M03 out (2.22.2 note 7)";
    TCodeCall 6001 Bool 0.0 "(bit 5, TCS) 1 = a T code calls subprogram O9000 with the T value in #149, instead of indexing the turret (FANUC 0i)";
    MaxCuttingFeed 6023 MmPerMin 5000.0 "maximum cutting feed along the path (2.2 note 3)";
    CallG9010 6050 Count 0.0 "G code that calls macro O9010 with its arguments, as G65 P9010 would; 0 = none (FANUC 0i)";
    CallG9011 6051 Count 0.0 "G code that calls macro O9011 with its arguments, as G65 P9011 would; 0 = none (FANUC 0i)";
    CallG9012 6052 Count 0.0 "G code that calls macro O9012 with its arguments, as G65 P9012 would; 0 = none (FANUC 0i)";
    CallG9013 6053 Count 0.0 "G code that calls macro O9013 with its arguments, as G65 P9013 would; 0 = none (FANUC 0i)";
    CallG9014 6054 Count 0.0 "G code that calls macro O9014 with its arguments, as G65 P9014 would; 0 = none (FANUC 0i)";
    CallG9015 6055 Count 0.0 "G code that calls macro O9015 with its arguments, as G65 P9015 would; 0 = none (FANUC 0i)";
    CallG9016 6056 Count 0.0 "G code that calls macro O9016 with its arguments, as G65 P9016 would; 0 = none (FANUC 0i)";
    CallG9017 6057 Count 0.0 "G code that calls macro O9017 with its arguments, as G65 P9017 would; 0 = none (FANUC 0i)";
    CallG9018 6058 Count 0.0 "G code that calls macro O9018 with its arguments, as G65 P9018 would; 0 = none (FANUC 0i)";
    CallG9019 6059 Count 0.0 "G code that calls macro O9019 with its arguments, as G65 P9019 would; 0 = none (FANUC 0i)";
    SubM9001 6071 Count 0.0 "M code that calls subprogram O9001, as M98 P9001 would; 0 = none (FANUC 0i)";
    SubM9002 6072 Count 0.0 "M code that calls subprogram O9002, as M98 P9002 would; 0 = none (FANUC 0i)";
    SubM9003 6073 Count 0.0 "M code that calls subprogram O9003, as M98 P9003 would; 0 = none (FANUC 0i)";
    SubM9004 6074 Count 0.0 "M code that calls subprogram O9004, as M98 P9004 would; 0 = none (FANUC 0i)";
    SubM9005 6075 Count 0.0 "M code that calls subprogram O9005, as M98 P9005 would; 0 = none (FANUC 0i)";
    SubM9006 6076 Count 0.0 "M code that calls subprogram O9006, as M98 P9006 would; 0 = none (FANUC 0i)";
    SubM9007 6077 Count 0.0 "M code that calls subprogram O9007, as M98 P9007 would; 0 = none (FANUC 0i)";
    SubM9008 6078 Count 0.0 "M code that calls subprogram O9008, as M98 P9008 would; 0 = none (FANUC 0i)";
    SubM9009 6079 Count 0.0 "M code that calls subprogram O9009, as M98 P9009 would; 0 = none (FANUC 0i)";
    CallM9020 6080 Count 0.0 "M code that calls macro O9020 with its arguments, as G65 P9020 would; 0 = none (FANUC 0i)";
    CallM9021 6081 Count 0.0 "M code that calls macro O9021 with its arguments, as G65 P9021 would; 0 = none (FANUC 0i)";
    CallM9022 6082 Count 0.0 "M code that calls macro O9022 with its arguments, as G65 P9022 would; 0 = none (FANUC 0i)";
    CallM9023 6083 Count 0.0 "M code that calls macro O9023 with its arguments, as G65 P9023 would; 0 = none (FANUC 0i)";
    CallM9024 6084 Count 0.0 "M code that calls macro O9024 with its arguments, as G65 P9024 would; 0 = none (FANUC 0i)";
    CallM9025 6085 Count 0.0 "M code that calls macro O9025 with its arguments, as G65 P9025 would; 0 = none (FANUC 0i)";
    CallM9026 6086 Count 0.0 "M code that calls macro O9026 with its arguments, as G65 P9026 would; 0 = none (FANUC 0i)";
    CallM9027 6087 Count 0.0 "M code that calls macro O9027 with its arguments, as G65 P9027 would; 0 = none (FANUC 0i)";
    CallM9028 6088 Count 0.0 "M code that calls macro O9028 with its arguments, as G65 P9028 would; 0 = none (FANUC 0i)";
    CallM9029 6089 Count 0.0 "M code that calls macro O9029 with its arguments, as G65 P9029 would; 0 = none (FANUC 0i)";
    TapDwellAtR 7013 Ms 0.0 "rigid tapping dwell at the R level after tapping, ms (2.22.2 step 6, default 0 ms)";
}

/// Number of parameters.
pub const PARAM_COUNT: usize = PARAMS.len();

impl Param {
    /// The definition row.
    #[inline]
    pub fn def(self) -> &'static ParamDef {
        &PARAMS[self as usize]
    }

    /// The parameter with the manual's number `n`.
    pub fn by_number(n: u16) -> Option<Param> {
        PARAMS.iter().find(|d| d.number == n).map(|d| d.id)
    }
}

/// Stored parameter values in internal units (nm, nm/min, ms, counts).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Parameters {
    values: [i64; PARAM_COUNT],
}

impl Default for Parameters {
    fn default() -> Self {
        let mut p = Parameters { values: [0; PARAM_COUNT] };
        for d in PARAMS {
            p.values[d.id as usize] = to_internal(d.unit, d.default);
        }
        p
    }
}

/// A file-unit value in internal units.
fn to_internal(unit: ParamUnit, v: f64) -> i64 {
    let scale = match unit {
        ParamUnit::Mm | ParamUnit::MmPerMin => 1e6,
        _ => 1.0,
    };
    libm::round(v * scale) as i64
}

impl Parameters {
    /// The value in internal units.
    #[inline]
    pub fn get(&self, p: Param) -> i64 {
        self.values[p as usize]
    }

    /// Whether a Bool parameter is 1.
    #[inline]
    pub fn flag(&self, p: Param) -> bool {
        self.get(p) != 0
    }

    /// Sets a value in internal units (what a program's G71 U(Δd) does to 5147).
    #[inline]
    pub fn set(&mut self, p: Param, internal: i64) {
        self.values[p as usize] = internal;
    }

    /// Sets parameter number `n` from a machine-file value in file units, after
    /// checking that the value suits the parameter's unit.
    pub fn set_from_file(&mut self, n: u16, value: f64) -> Result<(), ParamError> {
        let p = Param::by_number(n).ok_or(ParamError::Unknown { number: n })?;
        let def = p.def();
        let bad = |problem| Err(ParamError::BadValue { number: n, problem });
        if !value.is_finite() || value.abs() > 9.0e12 {
            return bad("is out of range");
        }
        match def.unit {
            ParamUnit::Bool if value != 0.0 && value != 1.0 => return bad("must be 0 or 1"),
            ParamUnit::Count | ParamUnit::Ms | ParamUnit::Deg | ParamUnit::TenthLead
                if value < 0.0 || value != libm::trunc(value) =>
            {
                return bad("must be a whole number, 0 or more");
            }
            _ => {}
        }
        if let Some(problem) = call_code_problem(p, value) {
            return bad(problem);
        }
        self.set(p, to_internal(def.unit, value));
        Ok(())
    }
}

/// Parameters 6050–6059: the G codes that call macros O9010–O9019.
pub const CALL_G: [Param; 10] = [
    Param::CallG9010,
    Param::CallG9011,
    Param::CallG9012,
    Param::CallG9013,
    Param::CallG9014,
    Param::CallG9015,
    Param::CallG9016,
    Param::CallG9017,
    Param::CallG9018,
    Param::CallG9019,
];
/// Parameters 6071–6079: the M codes that call subprograms O9001–O9009.
pub const SUB_M: [Param; 9] = [
    Param::SubM9001,
    Param::SubM9002,
    Param::SubM9003,
    Param::SubM9004,
    Param::SubM9005,
    Param::SubM9006,
    Param::SubM9007,
    Param::SubM9008,
    Param::SubM9009,
];
/// Parameters 6080–6089: the M codes that call macros O9020–O9029.
pub const CALL_M: [Param; 10] = [
    Param::CallM9020,
    Param::CallM9021,
    Param::CallM9022,
    Param::CallM9023,
    Param::CallM9024,
    Param::CallM9025,
    Param::CallM9026,
    Param::CallM9027,
    Param::CallM9028,
    Param::CallM9029,
];

/// M codes no parameter may turn into a call: the program-flow codes.
const FLOW_M: [f64; 7] = [1.0, 2.0, 30.0, 91.0, 92.0, 98.0, 99.0];

/// What is wrong with `value` (a whole number, 0 or more) for a parameter of
/// 6050–6089: a G code 1–9999 other than G65–G67, an M code 1–999 other than
/// the program-flow codes (0 = none).
fn call_code_problem(p: Param, value: f64) -> Option<&'static str> {
    if CALL_G.contains(&p) {
        if value > 9_999.0 {
            return Some("must be a G code 1-9999, or 0 for none");
        }
        if (65.0..=67.0).contains(&value) {
            return Some("cannot be G65, G66 or G67");
        }
    }
    if SUB_M.contains(&p) || CALL_M.contains(&p) {
        if value > 999.0 {
            return Some("must be an M code 1-999, or 0 for none");
        }
        if FLOW_M.contains(&value) {
            return Some("cannot be M01, M02, M30, M91, M92, M98 or M99");
        }
    }
    None
}

impl ParamUnit {
    /// How the unit is written in tables and machine files.
    pub const fn name(self) -> &'static str {
        match self {
            ParamUnit::Bool => "0/1",
            ParamUnit::Count => "count",
            ParamUnit::Mm => "mm",
            ParamUnit::MmPerMin => "mm/min",
            ParamUnit::Ms => "ms",
            ParamUnit::Deg => "degrees",
            ParamUnit::TenthLead => "0.1 x lead",
        }
    }
}

/// A parameter that cannot be set from a machine file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ParamError {
    /// No parameter has this number.
    Unknown {
        /// The number given.
        number: u16,
    },
    /// The value does not suit the parameter.
    BadValue {
        /// The parameter.
        number: u16,
        /// What is wrong with the value.
        problem: &'static str,
    },
}

impl core::fmt::Display for ParamError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            ParamError::Unknown { number } => write!(f, "there is no parameter {number}"),
            ParamError::BadValue { number, problem } => write!(f, "parameter {number} {problem}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_order_matches_the_enum() {
        for (i, d) in PARAMS.iter().enumerate() {
            assert_eq!(d.id as usize, i, "parameter {} out of order", d.number);
        }
    }

    #[test]
    fn defaults_and_file_values_convert_to_internal_units() {
        let mut p = Parameters::default();
        assert_eq!(p.get(Param::ArcRadiusTolerance), 10_000);
        assert_eq!(p.set_from_file(5147, 2.5), Ok(()));
        assert_eq!(p.get(Param::RoughingDepth), 2_500_000);
        assert_eq!(p.set_from_file(9999, 1.0), Err(ParamError::Unknown { number: 9999 }));
        assert!(p.set_from_file(5152, 2.0).is_err());
        assert!(p.set_from_file(5142, 1.5).is_err());
        assert!(p.set_from_file(5142, -1.0).is_err());
        assert!(p.set_from_file(5147, f64::NAN).is_err());
        assert_eq!(p.get(Param::RoughingDepth), 2_500_000, "rejected values change nothing");
        assert_eq!(Param::by_number(5152), Some(Param::DisableCoordinateSetting));
    }

    #[test]
    fn call_code_parameters_take_only_codes_that_can_call() {
        let mut p = Parameters::default();
        assert_eq!(p.set_from_file(6050, 100.0), Ok(()));
        assert_eq!(p.get(Param::CallG9010), 100);
        assert_eq!(p.set_from_file(6059, 9999.0), Ok(()));
        assert!(p.set_from_file(6051, 10_000.0).is_err());
        assert!(p.set_from_file(6052, 65.0).is_err());
        assert!(p.set_from_file(6053, 100.5).is_err());
        assert_eq!(p.set_from_file(6071, 6.0), Ok(()));
        assert_eq!(p.set_from_file(6089, 999.0), Ok(()));
        for m in [1.0, 2.0, 30.0, 98.0, 99.0, 1000.0] {
            assert!(p.set_from_file(6080, m).is_err(), "M{m}");
        }
        assert_eq!(p.set_from_file(6001, 1.0), Ok(()));
        assert!(p.flag(Param::TCodeCall));
        assert_eq!([CALL_G[0], SUB_M[8], CALL_M[9]].map(|q| q.def().number), [6050, 6079, 6089]);
    }
}

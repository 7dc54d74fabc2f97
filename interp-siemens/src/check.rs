//! Checking a SINUMERIK block: its [`Words`] become a [`Command`] for the engine —
//! the G functions of the SINUMERIK table by meaning (G70/G71 are inch/metric
//! here, G96 is constant cutting speed *and* feed per revolution, as in the
//! 840D's group 15), coordinates in internal units (nm, X as a radius: halved
//! under DIAMON), `AC()`/`IC()` per coordinate, `ANG=` lines with one end
//! coordinate, `CR=` arcs, `RND=`/`CHF=`/`CHR=` corners, `T`/`D` tool edges.
//!
//! What the command has no room for and the driver sets on the state before the
//! block runs (undone with it if it fails) comes back in [`Extras`]: `LIMS=`
//! (the G96 speed limit) and DIAMON/DIAMOF.

use super::read::{Addr, Words, mask};
use interp_core::alarm::{AlarmKind, GNum, SiemensAlarm as S};
use interp_core::axis::Axis;
use interp_core::canon::{FeedMode, Plane};
use interp_core::codes::{GCode, MFunction, m_codes_conflict, m_function};
use interp_core::command::{AxisWord, Command, CycleArgs, FlowWord};
use interp_core::config::MachineConfig;
use interp_core::modal::{Corner, State};
use interp_core::units::{InputMode, Number, NumberFormat, Units};

/// What the block sets on the state that the [`Command`] does not carry.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Extras {
    /// `LIMS=`: the spindle speed limit of G96, rev/min.
    pub lims: Option<u32>,
    /// DIAMON (true) / DIAMOF (false).
    pub diam: Option<bool>,
}

/// DIAMON/DIAMOF and LIMS= on the state, before the block runs (undone with it).
pub fn apply(extras: Extras, st: &mut State) {
    if let Some(d) = extras.diam {
        st.modal.diameter = d;
    }
    if let Some(l) = extras.lims {
        st.spindle.clamp = Some(l);
    }
}

/// What a SINUMERIK G function means to the engine.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Meaning {
    /// A code of the engine.
    Code(GCode),
    /// G94 (false) / G95 (true): feed per minute / revolution, constant cutting speed off.
    Feed(bool),
    /// G96: constant cutting speed, feed per revolution.
    CssOn,
    /// G97: constant cutting speed off.
    CssOff,
    /// Accepted with nothing to do on this machine (G601–G603 exact-stop windows,
    /// G450/G451 corner behaviour of compensation).
    Nothing,
}

/// The group of G290/G291 (the 840D's 47), numbered below 32 here: the groups
/// of a block are a 32-bit mask.
const LANGUAGE_GROUP: u8 = 31;

/// The SINUMERIK G functions: meaning and the 840D's group (two of one group in a
/// block is an error).
fn g_function(n: u16) -> Option<(Meaning, u8)> {
    use GCode::*;
    use Meaning::Code;
    Some(match n {
        0 => (Code(Rapid), 1),
        1 => (Code(Linear), 1),
        2 => (Code(ArcCw), 1),
        3 => (Code(ArcCcw), 1),
        33 => (Code(Thread), 1),
        4 => (Code(Dwell), 2),
        9 => (Code(ExactStopOnce), 11),
        17 => (Code(PlaneXy), 6),
        18 => (Code(PlaneZx), 6),
        19 => (Code(PlaneYz), 6),
        40 => (Code(NoseCompOff), 7),
        41 => (Code(NoseCompLeft), 7),
        42 => (Code(NoseCompRight), 7),
        53 => (Code(MachineCoordinates), 9),
        54..=57 => (Code(WorkFrame((n - 54) as u8)), 8),
        505 | 506 => (Code(WorkFrame((n - 501) as u8)), 8),
        60 => (Code(ExactStopMode), 10),
        64 | 641 | 642 => (Code(ContinuousMode), 10),
        601..=603 => (Meaning::Nothing, 12),
        70 | 700 => (Code(Inch), 13),
        71 | 710 => (Code(Metric), 13),
        90 => (Code(Absolute), 14),
        91 => (Code(Incremental), 14),
        94 => (Meaning::Feed(false), 15),
        95 => (Meaning::Feed(true), 15),
        96 => (Meaning::CssOn, 15),
        97 => (Meaning::CssOff, 15),
        290 => (Code(GCode::Language(interp_core::config::Language::Siemens)), LANGUAGE_GROUP),
        291 => (Code(GCode::Language(interp_core::config::Language::Fanuc)), LANGUAGE_GROUP),
        450 | 451 => (Meaning::Nothing, 18),
        _ => return None,
    })
}

/// The number format of SINUMERIK words: a number without a point is whole
/// units (no least-increment input), in the units in force.
pub fn number_format(units: Units, cfg: &MachineConfig) -> NumberFormat {
    NumberFormat { units, input: InputMode::Calculator, increments: cfg.increments }
}

/// The M functions of the SINUMERIK language. M17 ends a subprogram (a return,
/// like RET), M6 (tool change) needs nothing on a turret that indexes on T; on
/// the machining centre it changes to the tool T selected (as FANUC's M06).
fn m_of(m: u16, cfg: &MachineConfig) -> Result<Option<MFunction>, AlarmKind> {
    Ok(Some(match m {
        6 if cfg.kind != interp_core::config::MachineKind::Mill => return Ok(None),
        17 => MFunction::Return,
        29 | 91 | 92 | 98 | 99 => return Err(AlarmKind::UnknownMCode { m }),
        19 => return Err(AlarmKind::NotSupportedYet { what: "M19 (spindle positioning)" }),
        _ => m_function(m, cfg).ok_or(AlarmKind::UnknownMCode { m })?,
    }))
}

/// Checks `w` against the machine and the state into `cmd`.
pub fn check_into(w: &Words, st: &State, cfg: &MachineConfig, cmd: &mut Command) -> Result<Extras, AlarmKind> {
    *cmd = Command::EMPTY;
    cmd.line = w.line;
    cmd.seq = w.seq;
    let mut extras = Extras { lims: None, diam: w.diam };
    let (mut groups, mut css) = (0u32, None::<bool>);
    for &n in &w.g {
        let (meaning, group) = g_function(n).ok_or(AlarmKind::from(S::UnknownGFunction { code: n }))?;
        if groups & (1 << group) != 0 {
            let first = w.g.iter().copied().find(|&o| g_function(o).is_some_and(|(_, g)| g == group)).unwrap_or(0);
            return Err(AlarmKind::DuplicateGroup { first: GNum(first * 10), second: GNum(n * 10) });
        }
        groups |= 1 << group;
        match meaning {
            Meaning::Code(c) => cmd.g.assign(c),
            Meaning::Feed(rev) => {
                cmd.g.feed_mode = Some(if rev { FeedMode::PerRev } else { FeedMode::PerMin });
                css = Some(false);
            }
            Meaning::CssOn => {
                cmd.g.feed_mode = Some(FeedMode::PerRev);
                css = Some(true);
            }
            Meaning::CssOff => css = Some(false),
            Meaning::Nothing => {}
        }
    }
    if css.is_some_and(|on| on != st.modal.css) || css == Some(true) {
        cmd.g.css = css;
    }
    if let Some(GCode::Language(_)) = cmd.g.one_shot
        && (w.g.len() > 1 || !w.m.is_empty() || w.any(u32::MAX) || w.diam.is_some())
    {
        // G290/G291 stand in a block of their own, as on the 840D.
        return Err(AlarmKind::CodeMustBeAlone {
            code: GNum(w.g.iter().copied().find(|&g| g >= 290).unwrap_or(0) * 10),
        });
    }
    let units = cmd.g.units.unwrap_or(st.modal.units);
    let fmt = number_format(units, cfg);
    m_words(w, cfg, cmd)?;
    let dwell = cmd.g.one_shot == Some(GCode::Dwell);
    let diameter = w.diam.unwrap_or(st.modal.diameter);
    axes(w, st, cfg, &fmt, diameter, cmd)?;
    arc_words(w, st, cfg, &fmt, diameter, cmd)?;
    if dwell {
        cmd.dwell_ms = Some(dwell_ms(w, st, &fmt)?);
    } else {
        if let Some(f) = w.get(Addr::F) {
            if f.is_negative() {
                return Err(AlarmKind::IllegalMinusSign { letter: b'F' });
            }
            cmd.feed = Some(fmt.feed_nm(&f).ok_or(AlarmKind::Overflow)?);
        }
        if let Some(s) = w.get(Addr::S) {
            cmd.speed = Some(whole_u32(&s, b'S')?);
        }
    }
    tool(w, st, cfg, cmd)?;
    cmd.corner = corner(w, &fmt)?;
    if let Some(l) = w.get(Addr::Lims) {
        extras.lims = Some(whole_u32(&l, b'L')?);
    }
    if w.get(Addr::Spos).is_some() {
        return Err(AlarmKind::NotSupportedYet { what: "SPOS (spindle positioning)" });
    }
    if w.get(Addr::H).is_some() {
        return Err(AlarmKind::NotSupportedYet { what: "H auxiliary functions" });
    }
    // On the machining centre a block with M6 takes the mill's way (the tool
    // change), as one with T or D does.
    if cfg.kind == interp_core::config::MachineKind::Mill && cmd.m.iter().any(|&(_, f)| f == MFunction::ToolChange) {
        cmd.g.mill = true;
    }
    Ok(extras)
}

/// A whole non-negative number (S, LIMS), rounded.
fn whole_u32(n: &Number, letter: u8) -> Result<u32, AlarmKind> {
    if n.is_negative() {
        return Err(AlarmKind::IllegalMinusSign { letter });
    }
    let v = n.scaled(0).ok_or(AlarmKind::Overflow)?;
    u32::try_from(v).ok().filter(|v| *v <= 99_999).ok_or(AlarmKind::ValueOutOfRange { letter })
}

/// The block's M functions; M17 also asks for the return.
fn m_words(w: &Words, cfg: &MachineConfig, cmd: &mut Command) -> Result<(), AlarmKind> {
    for (i, &m) in w.m.iter().enumerate() {
        let Some(f) = m_of(m, cfg)? else { continue };
        if let Some(&other) = w.m[..i].iter().find(|&&o| m_codes_conflict(o, m) || (o == 17 && m_codes_conflict(99, m)))
        {
            return Err(AlarmKind::ConflictingMCodes { first: other, second: m });
        }
        cmd.m.push((m, f)).map_err(|_| AlarmKind::TooManyMCodes)?;
        if m == 17 {
            cmd.flow = Some(FlowWord::Return { seq: None });
        }
    }
    Ok(())
}

/// The plane's abscissa and ordinate (G17 X/Y, G18 Z/X, G19 Y/Z).
fn plane_axes(p: Plane) -> (Axis, Axis) {
    match p {
        Plane::Xy => (Axis::X, Axis::Y),
        Plane::Zx => (Axis::Z, Axis::X),
        Plane::Yz => (Axis::Y, Axis::Z),
    }
}

/// An axis (or centre) value in nm: a length, X halved under DIAMON; C in µdeg.
fn axis_nm(a: Axis, n: &Number, fmt: &NumberFormat, diameter: bool) -> Result<i64, AlarmKind> {
    if a.is_rotary() {
        return fmt.angle_udeg(n).ok_or(AlarmKind::Overflow);
    }
    let v = fmt.length_nm(n).ok_or(AlarmKind::Overflow)?;
    Ok(if a == Axis::X && diameter { v / 2 } else { v })
}

/// X/Y/Z/C, with AC()/IC(), G90/G91 and ANG=.
fn axes(
    w: &Words,
    st: &State,
    cfg: &MachineConfig,
    fmt: &NumberFormat,
    diameter: bool,
    cmd: &mut Command,
) -> Result<(), AlarmKind> {
    for letter in [Addr::A, Addr::B] {
        if w.get(letter).is_some() {
            return Err(AlarmKind::AxisNotConfigured { letter: letter.letter() });
        }
    }
    let g91 = cmd.g.incremental.unwrap_or(st.modal.incremental);
    for (addr, axis) in [(Addr::X, Axis::X), (Addr::Y, Axis::Y), (Addr::Z, Axis::Z), (Addr::C, Axis::C)] {
        let Some(n) = w.get(addr) else { continue };
        if !cfg.axis(axis).present {
            return Err(AlarmKind::AxisNotConfigured { letter: axis.letter() });
        }
        let incremental = w.explicit(addr).unwrap_or(g91);
        cmd.axes[axis.index()] = Some(AxisWord { value: axis_nm(axis, &n, fmt, diameter)?, incremental });
    }
    if let Some(ang) = w.get(Addr::Ang) {
        angle_line(ang, st, cfg, cmd)?;
    }
    Ok(())
}

/// `ANG=`: a straight line at that angle to the plane's abscissa, with one end
/// coordinate given; the other is where the line reaches it.
fn angle_line(ang: Number, st: &State, cfg: &MachineConfig, cmd: &mut Command) -> Result<(), AlarmKind> {
    let motion = cmd.g.motion.unwrap_or(st.modal.motion);
    if !matches!(motion, GCode::Linear | GCode::Rapid) {
        return Err(syntax_err("ANG= with G0/G1 only"));
    }
    let (ab, or) = plane_axes(cmd.g.plane.unwrap_or(st.modal.plane));
    let here = st.work_pos(cfg);
    let end =
        |a: Axis, cmd: &Command| cmd.axes[a.index()].map(|w| if w.incremental { here[a] + w.value } else { w.value });
    let deg = ang.to_f64();
    let (s, c) = (interp_core::geom::deg::sin_deg(deg), interp_core::geom::deg::cos_deg(deg));
    let (d_ab, d_or) = match (end(ab, cmd), end(or, cmd)) {
        (Some(_), Some(_)) => return Err(syntax_err("ANG= with both coordinates of the plane")),
        (None, None) => {
            return Err(AlarmKind::NotSupportedYet { what: "ANG= without an end coordinate (two-block contours)" });
        }
        (Some(e), None) => {
            let d = (e - here[ab]) as f64;
            if c.abs() < 1e-9 || d * c < 0.0 && d != 0.0 {
                return Err(syntax_err("ANG= does not reach the programmed coordinate"));
            }
            (d, d * s / c)
        }
        (None, Some(e)) => {
            let d = (e - here[or]) as f64;
            if s.abs() < 1e-9 || d * s < 0.0 && d != 0.0 {
                return Err(syntax_err("ANG= does not reach the programmed coordinate"));
            }
            (d * c / s, d)
        }
    };
    let _ = d_ab;
    for (a, d) in [(ab, d_ab), (or, d_or)] {
        if cmd.axes[a.index()].is_none() {
            let v = libm::round(here[a] as f64 + d);
            if !v.is_finite() || v.abs() > 1e15 {
                return Err(AlarmKind::Overflow);
            }
            cmd.axes[a.index()] = Some(AxisWord { value: v as i64, incremental: false });
        }
    }
    Ok(())
}

fn syntax_err(what: &'static str) -> AlarmKind {
    S::SyntaxError { what }.into()
}

/// I/J/K (radius values, from the start point; `=AC()` an absolute centre), CR=,
/// and G33's lead K/I.
fn arc_words(
    w: &Words,
    st: &State,
    cfg: &MachineConfig,
    fmt: &NumberFormat,
    diameter: bool,
    cmd: &mut Command,
) -> Result<(), AlarmKind> {
    if !w.any(mask::CENTRE | (1 << Addr::Cr as u32)) {
        return Ok(());
    }
    let motion = cmd.g.motion.unwrap_or(st.modal.motion);
    if motion == GCode::Thread {
        // G33: K is the lead along Z, I along X (mm/rev).
        let lead = match (w.get(Addr::K), w.get(Addr::I)) {
            (Some(k), None) | (None, Some(k)) => fmt.length_nm(&k).ok_or(AlarmKind::Overflow)?.abs(),
            _ => return Err(AlarmKind::MissingWord { letter: b'K', context: "G33 (one lead, K or I)" }),
        };
        interp_core::command::cycle::check_lead(lead, fmt.units)?;
        cmd.cycle = CycleArgs::Thread { lead: Some(lead), start_udeg: None, delta: 0 };
        return Ok(());
    }
    if !matches!(motion, GCode::ArcCw | GCode::ArcCcw) {
        return Err(AlarmKind::WordNotAllowed {
            letter: if w.get(Addr::Cr).is_some() { b'C' } else { b'I' },
            context: "a block without G2/G3",
        });
    }
    let here = st.work_pos(cfg);
    for (addr, axis) in [(Addr::I, Axis::X), (Addr::J, Axis::Y), (Addr::K, Axis::Z)] {
        let Some(n) = w.get(addr) else { continue };
        let v = match w.explicit(addr) {
            Some(false) => axis_nm(axis, &n, fmt, diameter)? - here[axis],
            _ => fmt.length_nm(&n).ok_or(AlarmKind::Overflow)?,
        };
        cmd.center[axis.index()] = Some(v);
    }
    if let Some(r) = w.get(Addr::Cr) {
        let r = fmt.length_nm(&r).ok_or(AlarmKind::Overflow)?;
        if r == 0 {
            return Err(AlarmKind::ArcRadiusZero);
        }
        cmd.radius = Some(r);
    }
    Ok(())
}

/// G4: F seconds, or S spindle revolutions at the speed in force.
fn dwell_ms(w: &Words, st: &State, fmt: &NumberFormat) -> Result<u32, AlarmKind> {
    if w.any(mask::AXES) {
        return Err(AlarmKind::CodeMustBeAlone { code: GNum(40) });
    }
    let ms = match (w.get(Addr::F), w.get(Addr::S)) {
        (Some(_), Some(_)) => return Err(AlarmKind::WordNotAllowed { letter: b'S', context: "G4 with F" }),
        (Some(f), None) => {
            if f.is_negative() {
                return Err(AlarmKind::IllegalMinusSign { letter: b'F' });
            }
            fmt.seconds_ms(&f).ok_or(AlarmKind::Overflow)?
        }
        (None, Some(s)) => {
            if s.is_negative() {
                return Err(AlarmKind::IllegalMinusSign { letter: b'S' });
            }
            let rpm = st.spindle.rpm;
            if rpm == 0 || st.spindle.dir == interp_core::canon::SpindleDir::Stop {
                return Err(AlarmKind::SpindleNotTurning);
            }
            interp_core::geom::round_i64(s.to_f64() * 60_000.0 / f64::from(rpm))
        }
        (None, None) => {
            return Err(AlarmKind::MissingWord { letter: b'F', context: "G4 (F seconds or S revolutions)" });
        }
    };
    u32::try_from(ms).map_err(|_| AlarmKind::ValueOutOfRange { letter: b'F' })
}

/// T (turret station) and D (cutting edge): offset row t + (d − 1) × tool count;
/// T alone selects its edge D1 (the 840D's default), D0 no offset.
fn tool(w: &Words, st: &State, cfg: &MachineConfig, cmd: &mut Command) -> Result<(), AlarmKind> {
    let t = w.get(Addr::T).map(|n| whole_u32(&n, b'T')).transpose()?;
    let d = w.get(Addr::D).map(|n| whole_u32(&n, b'D')).transpose()?;
    if t.is_none() && d.is_none() {
        return Ok(());
    }
    if let Some(t) = t
        && (t == 0 || t > u32::from(cfg.tool_count))
    {
        return Err(AlarmKind::IllegalToolNumber { number: t.min(u32::from(u16::MAX)) as u16 });
    }
    let station = t.map_or(u32::from(st.tool.tool), |t| t);
    let edge = d.unwrap_or(1);
    let row = if edge == 0 {
        0
    } else {
        super::read::tool_row(cfg, i64::from(station), i64::from(edge))
            .ok_or(AlarmKind::from(S::IllegalDNumber { number: edge.min(u32::from(u16::MAX)) as u16 }))?
    };
    cmd.tool = Some((t.map_or(0, |t| t as u16), row));
    if cfg.kind == interp_core::config::MachineKind::Mill {
        // A machining centre takes the cutter radius from D (`cmd.d`, as its
        // FANUC D, on the mill's block path): the milling cycles and G41/G42
        // read it; T selects and M6 changes, as on the FANUC mill.
        cmd.d = Some(row);
        cmd.g.mill = true;
    }
    Ok(())
}

/// RND= (round), CHR= (chamfer leg), CHF= (chamfer length): one per block.
fn corner(w: &Words, fmt: &NumberFormat) -> Result<Option<Corner>, AlarmKind> {
    let mut out = None;
    for (a, make) in [
        (Addr::Rnd, Corner::Round as fn(i64) -> Corner),
        (Addr::Chr, Corner::Chamfer),
        (Addr::Chf, Corner::ChamferLength),
    ] {
        let Some(n) = w.get(a) else { continue };
        if out.is_some() {
            return Err(syntax_err("RND=, CHF= and CHR= exclude each other"));
        }
        if n.is_negative() {
            return Err(AlarmKind::IllegalMinusSign { letter: a.letter() });
        }
        let v = fmt.length_nm(&n).ok_or(AlarmKind::Overflow)?;
        out = Some((v > 0).then(|| make(v)));
    }
    Ok(out.flatten())
}

/// One block of a cycle's contour (CYCLE95 `NPP` …) read and checked: its words
/// may use the calling level's variables `vars`; its blocks are NC blocks only (a
/// label, a comment, DIAMON/DIAMOF are fine; DEF, a jump, a call or an assignment
/// is alarm 61606 with the NCK cause 10930). `None` for a block without words.
/// Not inlined: the reader's scratch (words, pending assignments, call
/// arguments: ~1.5 KB) stays out of the frame that runs the contour's blocks.
#[inline(never)]
pub fn contour_command(
    raw: &interp_core::program::RawBlock<'_>,
    vars: &interp_core::lang::siemens::vars::Vars,
    st: &State,
    cfg: &MachineConfig,
) -> Result<Option<Command>, AlarmKind> {
    use crate::read::{Pending, Scope, Stmt, Words, read};
    use interp_core::alarm::CycleAlarm;
    use interp_core::lang::siemens::call::CallArgs;
    let scope = Scope { vars, state: st, cfg };
    let (mut words, mut pending, mut args) = (Words::EMPTY, Pending::new(), CallArgs::new());
    match read(raw.text, raw.line, &scope, &mut words, &mut pending, &mut args)? {
        Stmt::Nc { jump: None } if pending.is_empty() => {}
        _ => return Err(AlarmKind::SiemensCycle(CycleAlarm::ContourPreparation { cause: 10930 })),
    }
    if words.is_empty() {
        return Ok(None);
    }
    let mut cmd = Command::EMPTY;
    check_into(&words, st, cfg, &mut cmd)?;
    Ok(Some(cmd))
}

/// Every axis the command moves, for tests.
#[cfg(test)]
fn moved(cmd: &Command) -> [Option<i64>; interp_core::axis::AXIS_COUNT] {
    let mut o = [None; interp_core::axis::AXIS_COUNT];
    for (i, w) in cmd.axes.iter().enumerate() {
        o[i] = w.map(|w| w.value);
    }
    o
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::read::{Pending, Scope, read};
    use interp_core::axis::Pos;
    use interp_core::lang::siemens::call::CallArgs;
    use interp_core::lang::siemens::vars::Vars;

    const MM: i64 = 1_000_000;

    fn check(text: &str, st: &State) -> Result<(Command, Extras), AlarmKind> {
        let cfg = MachineConfig::default();
        let vars = Vars::new();
        let scope = Scope { vars: &vars, state: st, cfg: &cfg };
        let mut w = Words::default();
        let (mut p, mut a) = (Pending::new(), CallArgs::new());
        read(text.as_bytes(), 1, &scope, &mut w, &mut p, &mut a)?;
        let mut cmd = Command::EMPTY;
        let e = check_into(&w, st, &cfg, &mut cmd)?;
        Ok((cmd, e))
    }

    fn state() -> State {
        State::power_on(&MachineConfig::default(), Pos::ZERO)
    }

    #[test]
    fn g_functions_by_meaning() {
        let st = state();
        let (c, _) = check("G1 G90 X40 Z-2", &st).unwrap();
        assert_eq!(c.g.motion, Some(GCode::Linear));
        assert_eq!(moved(&c)[0], Some(20 * MM), "X40 under DIAMON is radius 20");
        assert_eq!(moved(&c)[2], Some(-2 * MM));
        let (c, _) = check("G70", &st).unwrap();
        assert_eq!(c.g.units, Some(Units::Inch), "SINUMERIK G70 is inch");
        let (c, _) = check("G96 S200 LIMS=3000", &st).unwrap();
        assert_eq!((c.g.css, c.g.feed_mode, c.speed), (Some(true), Some(FeedMode::PerRev), Some(200)));
        assert_eq!(
            check("G95 G97", &st).unwrap_err(),
            AlarmKind::DuplicateGroup { first: GNum(950), second: GNum(970) }
        );
        assert_eq!(check("G96 LIMS=3000", &st).unwrap().1.lims, Some(3000));
        assert_eq!(check("G55", &st).unwrap().0.g.work_frame, Some(1));
        assert_eq!(check("G12", &st).unwrap_err(), S::UnknownGFunction { code: 12 }.into());
        assert_eq!(check("G290 X1", &st).unwrap_err(), AlarmKind::CodeMustBeAlone { code: GNum(2900) });
    }

    #[test]
    fn diamof_ac_ic_and_angles() {
        let mut st = state();
        let (c, e) = check("DIAMOF G1 X10 Z100", &st).unwrap();
        assert_eq!((e.diam, moved(&c)[0]), (Some(false), Some(10 * MM)));
        st.modal.diameter = false;
        st.pos = Pos::xz(10 * MM, 90 * MM);
        // CYCLE95 example 2 (line 10948): Z=AC(70) ANG=150 from X10 Z90 (radius).
        let (c, _) = check("G1 Z=AC(70) ANG=150", &st).unwrap();
        let x = moved(&c)[0].unwrap();
        assert_eq!(moved(&c)[2], Some(70 * MM));
        assert!((x - (10 * MM + 11_547_005)).abs() <= 1, "{x}");
        let (c, _) = check("G1 X=IC(4) Z=AC(50)", &st).unwrap();
        assert_eq!(c.axes[0], Some(AxisWord { value: 4 * MM, incremental: true }));
        assert_eq!(c.axes[2], Some(AxisWord { value: 50 * MM, incremental: false }));
        assert!(check("G1 X1 Z2 ANG=30", &st).is_err());
        assert!(check("G2 X1 Z2 ANG=30", &st).is_err());
    }

    #[test]
    fn arcs_corners_tools_and_dwell() {
        let mut st = state();
        let (c, _) = check("G3 X20 Z-10 CR=-25", &st).unwrap();
        assert_eq!(c.radius, Some(-25 * MM));
        let (c, _) = check("G2 X20 Z-10 I5 K=AC(-3)", &st).unwrap();
        assert_eq!((c.center[0], c.center[2]), (Some(5 * MM), Some(-3 * MM)));
        assert_eq!(
            check("G1 X1 CR=3", &st).unwrap_err(),
            AlarmKind::WordNotAllowed { letter: b'C', context: "a block without G2/G3" }
        );
        assert_eq!(check("G1 X65 Z95 RND=5", &st).unwrap().0.corner, Some(Corner::Round(5 * MM)));
        assert_eq!(check("G1 X65 CHF=10", &st).unwrap().0.corner, Some(Corner::ChamferLength(10 * MM)));
        assert_eq!(check("G1 X65 CHR=2", &st).unwrap().0.corner, Some(Corner::Chamfer(2 * MM)));
        assert!(check("G1 X65 CHR=2 RND=1", &st).is_err());
        assert_eq!(check("T3 D1", &st).unwrap().0.tool, Some((3, 3)));
        assert_eq!(check("T3", &st).unwrap().0.tool, Some((3, 3)));
        assert_eq!(check("T3 D2", &st).unwrap().0.tool, Some((3, 15)), "3 + 1 x 12 tools");
        assert_eq!(check("T3 D0", &st).unwrap().0.tool, Some((3, 0)));
        assert_eq!(check("T3 D4", &st).unwrap_err(), S::IllegalDNumber { number: 4 }.into());
        assert_eq!(check("T13", &st).unwrap_err(), AlarmKind::IllegalToolNumber { number: 13 });
        st.tool.tool = 5;
        assert_eq!(check("D2", &st).unwrap().0.tool, Some((0, 17)));
        assert_eq!(check("G4 F2", &st).unwrap().0.dwell_ms, Some(2000));
        assert_eq!(check("G4 S10", &st).unwrap_err(), AlarmKind::SpindleNotTurning);
        st.spindle.rpm = 300;
        st.spindle.dir = interp_core::canon::SpindleDir::Cw;
        assert_eq!(check("G4 S10", &st).unwrap().0.dwell_ms, Some(2000), "10 rev at 300 rev/min");
        let (c, _) = check("M17", &st).unwrap();
        assert_eq!(c.flow, Some(FlowWord::Return { seq: None }));
        assert_eq!(check("M6", &st).unwrap().0.m.len(), 0);
        assert_eq!(check("M98", &st).unwrap_err(), AlarmKind::UnknownMCode { m: 98 });
        let (c, _) = check("G33 Z-35 K2", &st).unwrap();
        assert_eq!(c.cycle, CycleArgs::Thread { lead: Some(2 * MM), start_udeg: None, delta: 0 });
    }
}

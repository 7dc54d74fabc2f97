//! The words of a machining centre's block (the M series of FANUC 0i-M, seed
//! 004): X, Y, Z (and C if configured) in radius, absolute under G90 and
//! incremental under G91 — no U/V/W incremental addresses —, H and D offset
//! numbers, T a tool number, the words of G10, G51 (P, I/J/K), G51.1, G68 (R),
//! G54.1 (P) and of the hole cycles (R level, Q with a decimal point, P, K), and
//! radius and angle under G16.

use super::words::{ALWAYS, Letters, axis_value, convert_arc_words, corner_word, dwell_ms, length_nm, required_words};
use crate::alarm::AlarmKind;
use crate::axis::Axis;
use crate::codes::{GCode, MFunction};
use crate::command::cycle::{CycleArgs, is_hole};
use crate::command::{AxisWord, Command, EXTRA_FRAME};
use crate::config::{EXTRA_FRAMES, MAX_OFFSETS, MachineConfig};
use crate::lang::fanuc::parse::{Block, whole};
use crate::modal::State;
use crate::modal::mill::on;
use crate::units::{Number, NumberFormat};

/// Axis addresses of a machining centre.
const AXES: Letters = Letters::of(b"XYZC");
/// Letters of additional axes this board does not drive (FANUC M's U, V, W).
const UNUSED: Letters = Letters::of(b"UVW");
/// Offset numbers a move may carry (H with G43/G44, D with G41/G42, or alone).
const OFFSETS: Letters = Letters::of(b"HD");

/// The words `code` takes besides F, S, T, and its name for messages.
fn words_of(code: GCode) -> (Letters, &'static str) {
    use GCode::*;
    // A row number by code, then one table: the compiler's switch tables by
    // code (one per field, ~350 B each) were three times this.
    const ROWS: [(Letters, &str); 16] = [
        (AXES.with(OFFSETS), "G00"),
        (AXES.with(OFFSETS), "G01"),
        (AXES.with(OFFSETS).with(Letters::of(b"IJKR")), "G02/G03"),
        (Letters::of(b"PX"), "G04"),
        (AXES.with(Letters::of(b"LPR")), "G10"),
        (Letters::of(b"XYZIJK"), "G22"),
        (AXES, "G28"),
        (AXES, "G29"),
        (AXES.with(Letters::of(b"P")), "G30"),
        (AXES.with(Letters::of(b"PIJK")), "G51"),
        (AXES, "G50.1/G51.1"),
        (AXES, "G52"),
        (AXES, "G53"),
        (AXES.with(Letters::of(b"R")), "G68"),
        (AXES, "G92"),
        (AXES.with(Letters::of(b"RQPK")), "G73-G89"),
    ];
    let row = match code {
        Rapid => 0,
        Linear => 1,
        ArcCw | ArcCcw => 2,
        Dwell => 3,
        DataSetting => 4,
        StrokeCheckOn => 5,
        ReferenceReturn => 6,
        ReturnFromReference => 7,
        ReferenceReturnN => 8,
        ScalingOn => 9,
        MirrorOn | MirrorOff => 10,
        LocalFrame => 11,
        MachineCoordinates => 12,
        RotationOn => 13,
        SetCoordinates => 14,
        c if is_hole(c) => 15,
        _ => return (Letters(0), "this block"),
    };
    ROWS[row]
}

/// Checks the block's words against the M series and converts them into `cmd`;
/// marks the blocks that need the machining centre's execution paths. Out of
/// line and cold: the lathe's way through the checker keeps its registers.
#[cold]
#[inline(never)]
pub(super) fn check<const GENERAL: bool>(
    block: &Block,
    user: GCode,
    flow: Option<MFunction>,
    state: &State,
    cfg: &MachineConfig,
    fmt: &NumberFormat,
    cmd: &mut Command,
) -> Result<(), AlarmKind> {
    // `GENERAL` (tests only): every block the general way, to compare.
    if !GENERAL && plain_move(block, user, flow, state, cfg, cmd) {
        return plain(block, state, fmt, cmd);
    }
    alone(block, cmd)?;
    check_letters(block, user, flow, cmd, cfg)?;
    cmd.h = None;
    cmd.d = None;
    convert(block, user, state, cfg, fmt, cmd)?;
    cmd.g.mill = needs_mill_paths(cmd, state, user);
    Ok(())
}

/// The words of a plain move (and of [`ALWAYS`] but T and a call).
const PLAIN: Letters = Letters::of(b"XYZFS");

/// Whether the block is a plain G00/G01 (X, Y, Z, F, S at most, on configured
/// axes; no frame, offset, polar, length, one-shot code, M98/M99 family, chamfer
/// or corner; no transformation in force): [`plain`] checks it as the general
/// way would, without its per-code tests (most blocks of a mill program).
#[inline(always)]
fn plain_move(
    block: &Block,
    user: GCode,
    flow: Option<MFunction>,
    state: &State,
    cfg: &MachineConfig,
    cmd: &Command,
) -> bool {
    let present = block.present();
    let absent = |a: Axis| if cfg.axis(a).present { 0 } else { 1u32 << (a.letter() - b'A') };
    matches!(user, GCode::Linear | GCode::Rapid)
        && present & !PLAIN.0 == 0
        && present & (absent(Axis::X) | absent(Axis::Y) | absent(Axis::Z)) == 0
        && flow.is_none()
        && state.mill.frame.active == 0
        && cmd.g.frame.is_none()
        && cmd.g.one_shot.is_none()
        && cmd.g.length.is_none()
        && cmd.g.work_frame.is_none()
        && cmd.g.polar_coord.is_none()
        && block.chamfer.is_none()
        && block.corner.is_none()
}

/// A [`plain_move`] block's words into `cmd`: what [`check_letters`], [`convert`]
/// and [`needs_mill_paths`] do with it, in the same order (the same alarm first).
#[inline(always)]
fn plain(block: &Block, state: &State, fmt: &NumberFormat, cmd: &mut Command) -> Result<(), AlarmKind> {
    let incremental = cmd.g.incremental.unwrap_or(state.modal.incremental);
    linear_word(Axis::X, block, incremental, fmt, cmd)?;
    linear_word(Axis::Y, block, incremental, fmt, cmd)?;
    linear_word(Axis::Z, block, incremental, fmt, cmd)?;
    feed_and_speed(block, fmt, cmd)?;
    cmd.h = None;
    cmd.d = None;
    cmd.g.mill = cmd.m.iter().any(|&(_, f)| f == MFunction::ToolChange);
    Ok(())
}

/// G50/G51, G50.1/G51.1 and G68/G69 take the block's axis words: no motion, no
/// group 00 code, no hole cycle and no second one of them in the block.
#[inline(never)]
fn alone(block: &Block, cmd: &Command) -> Result<(), AlarmKind> {
    use crate::alarm::GNum;
    if cmd.g.frame.is_none() {
        return Ok(());
    }
    let frames = block.g.iter().filter(|t| matches!(**t, 500 | 501 | 510 | 511 | 680 | 690)).count();
    if frames > 1 || cmd.g.motion.is_some() || cmd.g.one_shot.is_some() || cmd.g.drilling.is_some() {
        let t = block.g.iter().copied().find(|t| matches!(*t, 500 | 501 | 510 | 511 | 680 | 690)).unwrap_or(0);
        return Err(AlarmKind::CodeMustBeAlone { code: GNum(t) });
    }
    Ok(())
}

/// Every letter must belong to the block's code (or its M98/M99/M91/M92, G54.1's
/// P, G43/G44's H, G41/G42's D); U, V, W are no addresses of this machine (0009);
/// an axis word must name an axis the machine has.
#[inline(never)]
fn check_letters(
    block: &Block,
    user: GCode,
    flow: Option<MFunction>,
    cmd: &Command,
    cfg: &MachineConfig,
) -> Result<(), AlarmKind> {
    let (mut allowed, name) = words_of(user);
    if cmd.g.length.is_some() {
        allowed = allowed.with(Letters::of(b"H"));
    }
    if cmd.g.nose_comp.is_some() {
        allowed = allowed.with(Letters::of(b"D"));
    }
    if cmd.g.work_frame == Some(EXTRA_FRAME) {
        if allowed.contains(b'P') {
            return Err(AlarmKind::WordNotAllowed { letter: b'P', context: "G54.1 with a code that takes P" });
        }
        allowed = allowed.with(Letters::of(b"P"));
    }
    if let Some(f) = flow {
        if allowed.contains(b'P') && block.has(b'P') {
            return Err(AlarmKind::WordNotAllowed {
                letter: b'P',
                context: "a code with P together with M98/M99/M91/M92",
            });
        }
        allowed = allowed.with(if f == MFunction::Call { Letters::of(b"PL") } else { Letters::of(b"P") });
    }
    let present = block.present();
    // Most blocks: every letter allowed, every axis word on an axis the machine
    // has (the per-letter loop below names the first fault otherwise).
    let absent =
        Axis::ALL.into_iter().filter(|a| !cfg.axis(*a).present).fold(0, |m, a| m | 1u32 << (a.letter() - b'A'));
    let axes_absent = if user == GCode::Dwell { 0 } else { absent };
    if present & (UNUSED.0 | !allowed.with(ALWAYS).0 | axes_absent) == 0 {
        return Ok(());
    }
    for letter in block.letters() {
        if UNUSED.contains(letter) {
            return Err(AlarmKind::ImproperAddress { letter });
        }
        if !allowed.with(ALWAYS).contains(letter) {
            return Err(AlarmKind::WordNotAllowed { letter, context: name });
        }
        if user != GCode::Dwell
            && AXES.contains(letter)
            && let Some(axis) = Axis::ALL.into_iter().find(|a| a.letter() == letter)
            && !cfg.axis(axis).present
        {
            return Err(AlarmKind::AxisNotConfigured { letter });
        }
    }
    Ok(())
}

/// Converts the block's values into `cmd`.
fn convert(
    block: &Block,
    user: GCode,
    state: &State,
    cfg: &MachineConfig,
    fmt: &NumberFormat,
    cmd: &mut Command,
) -> Result<(), AlarmKind> {
    use GCode::*;
    if user == Dwell {
        cmd.dwell_ms = Some(dwell_ms(block, fmt)?);
    } else if block.present() & AXES.0 != 0 {
        convert_axes(block, user, state, cfg, fmt, cmd)?;
    }
    match user {
        ArcCw | ArcCcw | StrokeCheckOn => convert_arc_words(block, fmt, cmd)?,
        c if is_hole(c) => cmd.cycle = super::cycle_args::read(c, block, fmt, false)?,
        ReferenceReturnN => {
            cmd.reference = match block.get(b'P') {
                None => 2,
                Some(p) => match p.as_integer() {
                    Some(n @ 1..=4) if !p.has_point => n as u8,
                    _ => return Err(AlarmKind::IllegalReferenceNumber),
                },
            };
        }
        DataSetting => cmd.cycle = data(block, fmt)?,
        ScalingOn => cmd.cycle = scale(block)?,
        RotationOn => {
            let r = block.get(b'R').map(|r| fmt.angle_udeg(&r).ok_or(AlarmKind::Overflow)).transpose()?;
            cmd.cycle = CycleArgs::Rotate { r_udeg: r };
        }
        _ => {}
    }
    if cmd.g.work_frame == Some(EXTRA_FRAME) {
        let p = block.get(b'P').ok_or(AlarmKind::MissingWord { letter: b'P', context: "G54.1" })?;
        let p = whole(b'P', &p, EXTRA_FRAMES as u32)?;
        if p == 0 {
            return Err(AlarmKind::ValueOutOfRange { letter: b'P' });
        }
        cmd.g.work_frame = Some(5 + p as u8);
    }
    if block.present() & Letters::of(b"FSTHD").0 != 0 {
        other_words(block, cfg, fmt, cmd)?;
    }
    if block.chamfer.is_some() || block.corner.is_some() {
        cmd.corner = corner_word(block, fmt)?;
    }
    if user == ReturnFromReference && !cmd.has_axes() {
        return Err(AlarmKind::MissingWord { letter: b'X', context: "G29" });
    }
    required_words(user, cmd)
}

/// F (never negative) and S (a whole number up to 99999) into `cmd`: the plain
/// move's short way and [`other_words`] alike.
#[inline(always)]
fn feed_and_speed(block: &Block, fmt: &NumberFormat, cmd: &mut Command) -> Result<(), AlarmKind> {
    if let Some(f) = block.get(b'F') {
        if f.is_negative() {
            return Err(AlarmKind::IllegalMinusSign { letter: b'F' });
        }
        cmd.feed = Some(fmt.feed_nm(&f).ok_or(AlarmKind::Overflow)?);
    }
    if let Some(s) = block.get(b'S') {
        cmd.speed = Some(whole(b'S', &s, 99_999)?);
    }
    Ok(())
}

/// F, S, T, H, D.
fn other_words(block: &Block, cfg: &MachineConfig, fmt: &NumberFormat, cmd: &mut Command) -> Result<(), AlarmKind> {
    feed_and_speed(block, fmt, cmd)?;
    if let Some(t) = block.get(b'T') {
        let t = whole(b'T', &t, 99_999_999)?;
        if t > u32::from(cfg.tool_count) {
            let number = t.min(u32::from(u16::MAX)) as u16;
            return Err(AlarmKind::MillToolNumber { number, max: cfg.tool_count });
        }
        cmd.tool = Some((t as u16, 0));
    }
    cmd.h = offset_number(block, b'H')?;
    cmd.d = offset_number(block, b'D')?;
    Ok(())
}

/// H or D: an offset row number, 0 (none) to the table's last.
#[inline(never)]
fn offset_number(block: &Block, letter: u8) -> Result<Option<u16>, AlarmKind> {
    let Some(n) = block.get(letter) else { return Ok(None) };
    let v = whole(letter, &n, 99_999_999)?;
    if v as usize > MAX_OFFSETS {
        return Err(AlarmKind::IllegalOffsetNumber { number: v.min(u32::from(u16::MAX)) as u16 });
    }
    Ok(Some(v as u16))
}

/// Whether G16 reads the block's plane words as radius and angle.
fn polar(user: GCode, state: &State, cmd: &Command) -> bool {
    let on = cmd.g.polar_coord.unwrap_or(state.mill.frame.active & on::POLAR != 0);
    on && matches!(user, GCode::Rapid | GCode::Linear | GCode::ArcCw | GCode::ArcCcw) | is_hole(user)
}

/// X, Y, Z, C: absolute under G90, incremental under G91 — except the centres of
/// G51, G51.1 and G68, always absolute (seed 004 @4506). Under G16 the plane's
/// second axis word is an angle in degrees.
fn convert_axes(
    block: &Block,
    user: GCode,
    state: &State,
    cfg: &MachineConfig,
    fmt: &NumberFormat,
    cmd: &mut Command,
) -> Result<(), AlarmKind> {
    let g91 = cmd.g.incremental.unwrap_or(state.modal.incremental);
    let absolute = matches!(user, GCode::ScalingOn | GCode::MirrorOn | GCode::MirrorOff | GCode::RotationOn);
    let incremental = g91 && !absolute;
    if state.mill.frame.active & on::POLAR != 0 || cmd.g.polar_coord.is_some() {
        return polar_axes(block, user, incremental, state, cfg, fmt, cmd);
    }
    // One call per axis with constant letters (as the lathe's checker reads them).
    linear_word(Axis::X, block, incremental, fmt, cmd)?;
    linear_word(Axis::Y, block, incremental, fmt, cmd)?;
    linear_word(Axis::Z, block, incremental, fmt, cmd)?;
    if let Some(n) = block.get(b'C') {
        cmd.axes[Axis::C.index()] = Some(AxisWord { value: axis_value(Axis::C, &n, cfg, fmt)?, incremental });
    }
    Ok(())
}

/// [`convert_axes`] under G15/G16 in force or in the block: the plane's second
/// axis word an angle when G16 reads radius and angle. Out of line: rare.
#[inline(never)]
fn polar_axes(
    block: &Block,
    user: GCode,
    incremental: bool,
    state: &State,
    cfg: &MachineConfig,
    fmt: &NumberFormat,
    cmd: &mut Command,
) -> Result<(), AlarmKind> {
    let angle_axis = polar(user, state, cmd).then(|| cmd.g.plane.unwrap_or(state.modal.plane).axes().1);
    for axis in Axis::ALL {
        let Some(n) = block.get(axis.letter()) else { continue };
        let value = if Some(axis) == angle_axis {
            fmt.angle_udeg(&n).ok_or(AlarmKind::Overflow)?
        } else {
            axis_value(axis, &n, cfg, fmt)?
        };
        cmd.axes[axis.index()] = Some(AxisWord { value, incremental });
    }
    Ok(())
}

/// The word of linear `axis` (radius, no diameter on a mill), if given.
#[inline(always)]
fn linear_word(
    axis: Axis,
    block: &Block,
    incremental: bool,
    fmt: &NumberFormat,
    cmd: &mut Command,
) -> Result<(), AlarmKind> {
    if block.present() & (1 << (axis.letter() - b'A')) == 0 {
        return Ok(());
    }
    let value = length_nm(fmt, &block.value(axis.letter())).ok_or(AlarmKind::Overflow)?;
    cmd.axes[axis.index()] = Some(AxisWord { value, incremental });
    Ok(())
}

/// G10 L P R: L2 (work offsets, P0 the external one, P1–P6 = G54–G59), L20
/// (G54.1 P1–P48), L10–L13 (offset pages, P the row, R the value).
#[inline(never)]
fn data(block: &Block, fmt: &NumberFormat) -> Result<CycleArgs, AlarmKind> {
    let l = block.get(b'L').ok_or(AlarmKind::MissingWord { letter: b'L', context: "G10" })?;
    let l = whole(b'L', &l, 99)? as u8;
    let p = block.get(b'P').ok_or(AlarmKind::MissingWord { letter: b'P', context: "G10" })?;
    let p = whole(b'P', &p, 9_999)? as u16;
    let r = block.get(b'R').map(|r| length_nm(fmt, &r).ok_or(AlarmKind::Overflow)).transpose()?;
    match l {
        2 if p > 6 => Err(AlarmKind::ValueOutOfRange { letter: b'P' }),
        20 if p == 0 || usize::from(p) > EXTRA_FRAMES => Err(AlarmKind::ValueOutOfRange { letter: b'P' }),
        10..=13 if p == 0 || usize::from(p) > MAX_OFFSETS => Err(AlarmKind::IllegalOffsetNumber { number: p }),
        10..=13 if r.is_none() => Err(AlarmKind::MissingWord { letter: b'R', context: "G10 L10-L13" }),
        2 | 20 if r.is_some() => Err(AlarmKind::WordNotAllowed { letter: b'R', context: "G10 L2/L20" }),
        2 | 20 | 10..=13 => Ok(CycleArgs::Data { l, p, r }),
        _ => Err(AlarmKind::ValueOutOfRange { letter: b'L' }),
    }
}

/// G51 P or I/J/K (seed 004 @4506, @4740): thousandths without a decimal point
/// (P1500 and I1500 are 1.5), P also in units with one (P1.5); P 0.001–999.999,
/// I/J/K ±0.001–±9.999 and without a decimal point ("比例系数I、J、K不用小数点").
/// An axis I/J/K leaves out keeps the factor 1.
#[inline(never)]
fn scale(block: &Block) -> Result<CycleArgs, AlarmKind> {
    let thousandths = |letter: u8, n: &Number, max: i64| -> Result<i32, AlarmKind> {
        let v = if n.has_point { n.scaled(3) } else { n.as_integer() }.ok_or(AlarmKind::IllegalScale { letter })?;
        if v == 0 || v.abs() > max {
            return Err(AlarmKind::IllegalScale { letter });
        }
        Ok(v as i32)
    };
    let p = match block.get(b'P') {
        Some(n) if n.is_negative() => return Err(AlarmKind::IllegalScale { letter: b'P' }),
        Some(n) => Some(thousandths(b'P', &n, 999_999)?),
        None => None,
    };
    let mut ijk = [None; 3];
    for (slot, letter) in ijk.iter_mut().zip([b'I', b'J', b'K']) {
        if let Some(n) = block.get(letter) {
            if n.has_point {
                return Err(AlarmKind::IllegalDecimalPoint { letter });
            }
            *slot = Some(thousandths(letter, &n, 9_999)?);
        }
    }
    match (p, ijk.iter().any(Option::is_some)) {
        (Some(_), true) => Err(AlarmKind::WordNotAllowed { letter: b'I', context: "G51 with P" }),
        (None, false) => Err(AlarmKind::MissingWord { letter: b'P', context: "G51" }),
        _ => Ok(CycleArgs::Scale { p, ijk }),
    }
}

/// Whether the block needs more than the plain way (see `GSet::mill`).
fn needs_mill_paths(cmd: &Command, state: &State, user: GCode) -> bool {
    cmd.h.is_some()
        || cmd.d.is_some()
        || cmd.tool.is_some()
        || cmd.g.one_shot.is_some()
        || cmd.g.length.is_some()
        || cmd.g.frame.is_some()
        || cmd.g.polar_coord.is_some()
        || cmd.g.work_frame.is_some()
        || state.mill.frame.active != 0
        || is_hole(user)
        || cmd.m.iter().any(|&(_, f)| f == MFunction::ToolChange)
}

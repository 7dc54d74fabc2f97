//! Which words a block may hold, and their conversion into internal units.

use super::axis_of;
use crate::alarm::AlarmKind;
use crate::axis::Axis;
use crate::codes::{GCode, MFunction};
use crate::command::{AxisWord, Command};
use crate::config::{MAX_OFFSETS, MachineConfig, Param};
use crate::lang::fanuc::parse::{Block, whole};
use crate::modal::State;
use crate::units::{InputMode, Number, NumberFormat, Units};

/// A set of address letters, one bit per letter A–Z.
#[derive(Clone, Copy)]
pub(super) struct Letters(pub(super) u32);

impl Letters {
    pub(super) const fn of(letters: &[u8]) -> Letters {
        let mut bits = 0;
        let mut i = 0;
        while i < letters.len() {
            bits |= 1 << (letters[i] - b'A');
            i += 1;
        }
        Letters(bits)
    }

    pub(super) const fn with(self, o: Letters) -> Letters {
        Letters(self.0 | o.0)
    }

    pub(super) const fn contains(self, l: u8) -> bool {
        self.0 & (1 << (l - b'A')) != 0
    }
}

/// Axis addresses, absolute and incremental.
const AXES: Letters = Letters::of(b"XYZCUVWH");
/// Words every block may hold (and a subprogram call by an M or T code, which is
/// not a word).
pub(super) const ALWAYS: Letters = Letters::of(b"FST").with(Letters(crate::lang::fanuc::parse::SUB_CALL));
/// Letters no function of this controller uses.
const UNUSED: Letters = Letters::of(b"D");

/// The words `code` takes besides [`ALWAYS`], and its name for messages.
fn words_of(code: GCode) -> (Letters, &'static str) {
    use GCode::*;
    match code {
        Rapid => (AXES, "G00"),
        Linear => (AXES, "G01"),
        ArcCw | ArcCcw => (AXES.with(Letters::of(b"IJKR")), "G02/G03"),
        Dwell => (Letters::of(b"PXU"), "G04"),
        ReferenceReturn => (AXES, "G28"),
        ReferenceReturnN => (AXES.with(Letters::of(b"P")), "G30"),
        SetCoordinates => (AXES, "G50"),
        LocalFrame => (AXES, "G52"),
        MachineCoordinates => (AXES, "G53"),
        StrokeCheckOn => (Letters::of(b"XYZIJK"), "G22"),
        PolygonOn => (Letters::of(b"PQR"), "G51.2"),
        EllipseCw | EllipseCcw => (Letters::of(b"XZUWABQ"), "G02.1/G03.1"),
        ParabolaCw | ParabolaCcw => (Letters::of(b"XZUWPQ"), "G02.2/G03.2"),
        _ => (Letters(0), "this block"),
    }
}

/// Every letter of the block must belong to the code that uses the axis words (or
/// to the block's M98/M99/M91/M92: P, and L for M98), and every axis word must name
/// an axis the machine has.
pub(super) fn check_letters(
    block: &Block,
    user: GCode,
    flow: Option<MFunction>,
    cfg: &MachineConfig,
) -> Result<(), AlarmKind> {
    let (mut allowed, name) = match crate::lang::fanuc::check::cycle_args::letters_of(user) {
        Some((l, name)) => (Letters::of(l), name),
        None => words_of(user),
    };
    // A subprogram call by an M or T code stands as an M98 but takes no P or L.
    if let Some(f) = flow.filter(|_| block.sub_call().is_none()) {
        if allowed.contains(b'P') && block.has(b'P') {
            return Err(AlarmKind::WordNotAllowed {
                letter: b'P',
                context: "a code with P together with M98/M99/M91/M92",
            });
        }
        allowed = allowed.with(if f == MFunction::Call { Letters::of(b"PL") } else { Letters::of(b"P") });
    }
    if !any_letter_refused(block.present(), allowed, user, cfg) {
        return Ok(());
    }
    // Some letter is refused: the first in alphabetical order names the alarm.
    for letter in block.letters() {
        if UNUSED.contains(letter) {
            return Err(AlarmKind::ImproperAddress { letter });
        }
        if !allowed.with(ALWAYS).contains(letter) {
            return Err(AlarmKind::WordNotAllowed { letter, context: name });
        }
        if user != GCode::Dwell
            && !(user == GCode::ThreadCycle && letter == b'H')
            && crate::command::cycle::axes_are_points(user)
            && let Some((axis, _)) = axis_of(letter)
            && !cfg.axis(axis).present
        {
            return Err(AlarmKind::AxisNotConfigured { letter });
        }
    }
    Ok(())
}

/// Whether the per-letter rules of [`check_letters`] refuse any of the letters
/// `present`, tested on all letters at once.
#[inline(always)]
fn any_letter_refused(present: u32, allowed: Letters, user: GCode, cfg: &MachineConfig) -> bool {
    if present & (UNUSED.0 | !allowed.with(ALWAYS).0) != 0 {
        return true;
    }
    if user == GCode::Dwell || !crate::command::cycle::axes_are_points(user) {
        return false;
    }
    // G92 H is the number of starts, not the C axis.
    let h = if user == GCode::ThreadCycle { Letters::of(b"H").0 } else { 0 };
    Axis::ALL.into_iter().any(|axis| {
        let letters = axis_letters(axis) & !h;
        present & letters != 0 && !cfg.axis(axis).present
    })
}

/// The absolute and incremental letters of `axis`.
#[inline(always)]
fn axis_letters(axis: Axis) -> u32 {
    (1 << (axis.letter() - b'A')) | (1 << (axis.incremental_letter() - b'A'))
}

/// Converts the block's values into `cmd`.
pub(super) fn convert(
    block: &Block,
    user: GCode,
    state: &State,
    cfg: &MachineConfig,
    fmt: &NumberFormat,
    cmd: &mut Command,
) -> Result<(), AlarmKind> {
    use crate::command::cycle as args;
    if user == GCode::Dwell {
        cmd.dwell_ms = Some(dwell_ms(block, fmt)?);
    } else if args::axes_are_points(user) {
        convert_axes(block, state, cfg, fmt, cmd, user == GCode::ThreadCycle)?;
    }
    if args::is_cycle(user) {
        cmd.cycle = super::cycle_args::read(user, block, fmt, cfg.diameter_x)?;
    }
    if user == GCode::PolygonOn {
        cmd.cycle = polygon(block, fmt, cfg)?;
    }
    if matches!(user, GCode::EllipseCw | GCode::EllipseCcw | GCode::ParabolaCw | GCode::ParabolaCcw) {
        cmd.cycle = super::cycle_args::read_curve(block, fmt)?;
    }
    if matches!(user, GCode::ArcCw | GCode::ArcCcw | GCode::StrokeCheckOn) {
        convert_arc_words(block, fmt, cmd)?;
    }
    if user == GCode::ReferenceReturnN {
        cmd.reference = match block.get(b'P') {
            None => 2,
            Some(p) => match p.as_integer() {
                Some(n @ 1..=4) if !p.has_point => n as u8,
                _ => return Err(AlarmKind::IllegalReferenceNumber),
            },
        };
    }
    if let Some(f) = block.get(b'F').filter(|_| !args::f_is_lead(user)) {
        if f.is_negative() {
            return Err(AlarmKind::IllegalMinusSign { letter: b'F' });
        }
        cmd.feed = Some(fmt.feed_nm(&f).ok_or(AlarmKind::Overflow)?);
    }
    if let Some(s) = block.get(b'S') {
        cmd.speed = Some(whole(b'S', &s, 99_999)?);
    }
    if let Some(t) = block.get(b'T') {
        cmd.tool = Some(tool_word(&t, cfg)?);
    }
    cmd.corner = corner_word(block, fmt)?;
    required_words(user, cmd)
}

/// Axis words into nm (X diameter halved), noting absolute or incremental.
fn convert_axes(
    block: &Block,
    state: &State,
    cfg: &MachineConfig,
    fmt: &NumberFormat,
    cmd: &mut Command,
    h_is_count: bool,
) -> Result<(), AlarmKind> {
    let present = block.present();
    if present & AXES.0 == 0 {
        return Ok(());
    }
    let g91 = cmd.g.incremental.unwrap_or(state.modal.incremental);
    // One call per axis, in axis order (the first bad axis names the alarm), each
    // with constant letters.
    axis_word(Axis::X, block, g91, state, cfg, fmt, cmd)?;
    axis_word(Axis::Y, block, g91, state, cfg, fmt, cmd)?;
    axis_word(Axis::Z, block, g91, state, cfg, fmt, cmd)?;
    if !h_is_count {
        // G92 H is the number of starts, not the C axis.
        axis_word(Axis::C, block, g91, state, cfg, fmt, cmd)?;
    }
    Ok(())
}

/// The word of `axis` (absolute or incremental), if given, into `cmd.axes`.
#[inline(always)]
fn axis_word(
    axis: Axis,
    block: &Block,
    g91: bool,
    state: &State,
    cfg: &MachineConfig,
    fmt: &NumberFormat,
    cmd: &mut Command,
) -> Result<(), AlarmKind> {
    let (abs, inc) = (axis.letter(), axis.incremental_letter());
    let (abs_bit, inc_bit) = (1u32 << (abs - b'A'), 1u32 << (inc - b'A'));
    let given = block.present() & (abs_bit | inc_bit);
    if given == 0 {
        return Ok(());
    }
    if given == abs_bit | inc_bit {
        return Err(AlarmKind::AxisTwice { absolute: abs, incremental: inc });
    }
    let (letter, incremental) = if given == abs_bit { (abs, g91) } else { (inc, true) };
    let n = block.value(letter);
    let value = if axis == Axis::C && state.polar.is_some() {
        // 2.7: in polar interpolation C is the plane's second axis, a length.
        length_nm(fmt, &n).ok_or(AlarmKind::Overflow)?
    } else {
        axis_value(axis, &n, cfg, fmt)?
    };
    cmd.axes[axis.index()] = Some(AxisWord { value, incremental });
    Ok(())
}

/// One axis value in internal units.
#[inline(always)]
pub(super) fn axis_value(axis: Axis, n: &Number, cfg: &MachineConfig, fmt: &NumberFormat) -> Result<i64, AlarmKind> {
    let v = if axis.is_rotary() { fmt.angle_udeg(n) } else { length_nm(fmt, n) };
    let v = v.ok_or(AlarmKind::Overflow)?;
    Ok(if axis == Axis::X && cfg.diameter_x { v / 2 } else { v })
}

/// [`NumberFormat::length_nm`], with the usual word (metric, read as written, no
/// more fraction digits than the least increment: nothing to round) as one
/// multiply.
#[inline(always)]
pub(super) fn length_nm(fmt: &NumberFormat, n: &Number) -> Option<i64> {
    /// `10^(6 - f)`: millimetres with `f` fraction digits to nanometres.
    const NM_PER_DIGIT: [i32; 4] = [1_000_000, 100_000, 10_000, 1_000];
    if fmt.units == Units::Metric
        && (n.has_point || fmt.input == InputMode::Calculator)
        && let (Some(&scale), Ok(m)) = (NM_PER_DIGIT.get(usize::from(n.frac_digits)), i32::try_from(n.mantissa))
    {
        // IS-B and IS-C metric keep at least 3 fraction digits: exact, and an i32
        // times at most 10^6 fits an i64.
        return Some(i64::from(m) * i64::from(scale));
    }
    length_nm_general(fmt, n)
}

/// [`NumberFormat::length_nm`] out of line: the checkers convert axis words at
/// a dozen sites, each would inline its own copy (two 64-bit divisions).
#[inline(never)]
pub(super) fn length_nm_general(fmt: &NumberFormat, n: &Number) -> Option<i64> {
    fmt.length_nm(n)
}

/// I/J/K (radius values) and R of an arc.
pub(super) fn convert_arc_words(block: &Block, fmt: &NumberFormat, cmd: &mut Command) -> Result<(), AlarmKind> {
    // Written out per axis (constant letters), in axis order: X, Y, Z (C has none).
    let mut center = |axis: Axis, letter: u8| -> Result<(), AlarmKind> {
        if let Some(n) = block.get(letter) {
            cmd.center[axis.index()] = Some(length_nm(fmt, &n).ok_or(AlarmKind::Overflow)?);
        }
        Ok(())
    };
    center(Axis::X, b'I')?;
    center(Axis::Y, b'J')?;
    center(Axis::Z, b'K')?;
    if let Some(r) = block.get(b'R') {
        let r = length_nm(fmt, &r).ok_or(AlarmKind::Overflow)?;
        if r == 0 {
            return Err(AlarmKind::ArcRadiusZero);
        }
        cmd.radius = Some(r);
    }
    Ok(())
}

/// G04: P in ms without decimal point, or X/U in seconds; none = exact stop.
pub(super) fn dwell_ms(block: &Block, fmt: &NumberFormat) -> Result<u32, AlarmKind> {
    let secs = match (block.get(b'X'), block.get(b'U')) {
        (Some(_), Some(_)) => return Err(AlarmKind::AxisTwice { absolute: b'X', incremental: b'U' }),
        (x, u) => x.map(|n| (b'X', n)).or(u.map(|n| (b'U', n))),
    };
    match (block.get(b'P'), secs) {
        (Some(_), Some((l, _))) => Err(AlarmKind::WordNotAllowed { letter: l, context: "G04 with P" }),
        (Some(p), None) => whole(b'P', &p, 99_999_999),
        (None, Some((l, n))) => {
            if n.is_negative() {
                return Err(AlarmKind::IllegalMinusSign { letter: l });
            }
            let ms = fmt.seconds_ms(&n).ok_or(AlarmKind::Overflow)?;
            u32::try_from(ms).map_err(|_| AlarmKind::ValueOutOfRange { letter: l })
        }
        (None, None) => Ok(0),
    }
}

/// Words a code cannot do without.
#[inline]
pub(super) fn required_words(user: GCode, cmd: &Command) -> Result<(), AlarmKind> {
    use GCode::*;
    let (context, needs_axis) = match user {
        ReferenceReturn => ("G28", true),
        ReferenceReturnN => ("G30", true),
        LocalFrame => ("G52", true),
        SetCoordinates => ("G50", cmd.speed.is_none()),
        _ => ("", false),
    };
    if needs_axis && !cmd.has_axes() {
        return Err(AlarmKind::MissingWord { letter: b'X', context });
    }
    if user == MachineCoordinates && cmd.axes.iter().flatten().any(|w| w.incremental) {
        return Err(AlarmKind::MachineCoordinatesIncremental);
    }
    Ok(())
}

/// T: turret station and offset number (the last 1 or 2 digits, parameter 5002).
fn tool_word(t: &Number, cfg: &MachineConfig) -> Result<(u16, u16), AlarmKind> {
    let v = whole(b'T', t, 99_999_999)?;
    let split = if cfg.params.get(Param::OffsetDigits) == 1 { 10 } else { 100 };
    let (tool, offset) = (v / split, v % split);
    if tool > u32::from(cfg.tool_count) {
        return Err(AlarmKind::IllegalToolNumber { number: tool.min(u32::from(u16::MAX)) as u16 });
    }
    if offset as usize > MAX_OFFSETS {
        return Err(AlarmKind::IllegalOffsetNumber { number: offset as u16 });
    }
    Ok((tool as u16, offset as u16))
}

/// `,C` / `,R` (2.23): a length, never negative; zero asks for nothing.
pub(super) fn corner_word(block: &Block, fmt: &NumberFormat) -> Result<Option<crate::command::Corner>, AlarmKind> {
    use crate::command::Corner;
    let (n, letter, make): (_, u8, fn(i64) -> Corner) = match (&block.chamfer, &block.corner) {
        (_, Some(r)) if block.corner_last => (r, b'R', Corner::Round),
        (Some(c), _) => (c, b'C', Corner::Chamfer),
        (None, Some(r)) => (r, b'R', Corner::Round),
        (None, None) => return Ok(None),
    };
    if n.is_negative() {
        return Err(AlarmKind::IllegalMinusSign { letter });
    }
    let v = length_nm_general(fmt, n).ok_or(AlarmKind::Overflow)?;
    Ok((v > 0).then(|| make(v)))
}

/// G51.2 P Q R S (2.8): P and Q whole 1–999 (1 when omitted), R 0–359.999°, S
/// 1–9999 rev/min. Polygon turning needs a tool spindle in position control
/// synchronised to the work spindle (note 6, "否则报警"): the C axis drive is it, so
/// a machine without a C axis raises alarm 4047.
fn polygon(
    block: &Block,
    fmt: &NumberFormat,
    cfg: &MachineConfig,
) -> Result<crate::command::cycle::CycleArgs, AlarmKind> {
    let mut pq = [1u16; 2];
    for (i, l) in [b'P', b'Q'].into_iter().enumerate() {
        if let Some(n) = block.get(l) {
            let v = whole(l, &n, 999)?;
            if v == 0 {
                return Err(AlarmKind::ValueOutOfRange { letter: l });
            }
            pq[i] = u16::try_from(v).map_err(|_| AlarmKind::ValueOutOfRange { letter: l })?;
        }
    }
    let mut phase_udeg = 0;
    if let Some(r) = block.get(b'R') {
        let u = fmt.angle_udeg(&r).ok_or(AlarmKind::Overflow)?;
        if !(0..360_000_000).contains(&u) {
            return Err(AlarmKind::ValueOutOfRange { letter: b'R' });
        }
        phase_udeg = u;
    }
    if let Some(s) = block.get(b'S')
        && !(1..=9_999).contains(&whole(b'S', &s, 99_999)?)
    {
        return Err(AlarmKind::ValueOutOfRange { letter: b'S' });
    }
    if !cfg.axis(crate::axis::Axis::C).present {
        return Err(AlarmKind::PolygonNoToolSpindle);
    }
    Ok(crate::command::cycle::CycleArgs::Polygon { p: pq[0], q: pq[1], phase_udeg })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::units::IncrementSystem;

    /// The one-multiply length agrees with `NumberFormat::length_nm` everywhere:
    /// both units, both input modes, both increment systems, with and without a
    /// point, every fraction length, values at the edges of an i32.
    #[test]
    fn short_length_conversion_matches_the_general_one() {
        let mantissas =
            [0, 1, -1, 5, 40_824, -100, 999_999_999, -999_999_999, 2_147_483_647, -2_147_483_648, 2_147_483_648];
        for units in [Units::Metric, Units::Inch] {
            for input in [InputMode::Calculator, InputMode::LeastIncrement] {
                for increments in [IncrementSystem::IsB, IncrementSystem::IsC] {
                    let fmt = NumberFormat { units, input, increments };
                    for mantissa in mantissas {
                        for frac_digits in 0..=9 {
                            for has_point in [false, true] {
                                let n = Number { mantissa, frac_digits, has_point };
                                assert_eq!(length_nm(&fmt, &n), fmt.length_nm(&n), "{fmt:?} {n:?}");
                            }
                        }
                    }
                }
            }
        }
        let metric =
            NumberFormat { units: Units::Metric, input: InputMode::Calculator, increments: IncrementSystem::IsB };
        assert_eq!(length_nm(&metric, &Number { mantissa: 40_824, frac_digits: 3, has_point: true }), Some(40_824_000));
        assert_eq!(length_nm(&metric, &Number { mantissa: -1, frac_digits: 1, has_point: true }), Some(-100_000));
    }
}

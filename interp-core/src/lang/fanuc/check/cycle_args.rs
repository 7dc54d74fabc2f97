//! The words of cycle blocks, checked and converted into internal units. Called by
//! the check layer; no state changes here. What a letter means depends on the cycle
//! and on which of its two blocks it is (G71 U is Δd in the first block and Δu in
//! the second), so each cycle family reads its own words.

use crate::alarm::AlarmKind;
use crate::codes::GCode;
use crate::command::cycle::{CycleArgs, check_lead};
use crate::lang::fanuc::parse::Block;
use crate::units::{InputMode, NM_PER_INCH, Number, NumberFormat, UDEG_PER_DEG, Units, pow10};

/// Reads the cycle words of `block` for `code`.
pub fn read(code: GCode, block: &Block, fmt: &NumberFormat, diameter_x: bool) -> Result<CycleArgs, AlarmKind> {
    use GCode::*;
    let r = Reader { block, fmt, diameter_x };
    Ok(match code {
        TurningCycle => CycleArgs::Single { taper: r.taper()? },
        FacingCycle => CycleArgs::Single { taper: r.length(b'R')? },
        ThreadCycle => CycleArgs::ThreadCycle { taper: r.taper()?, lead: r.lead()?, starts: r.starts()? },
        Thread | VariableLeadThread => CycleArgs::Thread {
            lead: r.lead()?,
            start_udeg: r.start_angle()?,
            delta: if code == VariableLeadThread { r.lead_delta()? } else { 0 },
        },
        RoughTurnCycle | RoughFaceCycle if !r.has_shape() => CycleArgs::RoughSetup {
            depth: r.unsigned(if code == RoughTurnCycle { b'U' } else { b'W' }, "depth of cut")?,
            retract: r.unsigned(b'R', "retract")?,
        },
        PatternCycle if !r.has_shape() => {
            CycleArgs::PatternSetup { di: r.length(b'U')?, dk: r.length(b'W')?, count: r.count(b'R')? }
        }
        RoughTurnCycle | RoughFaceCycle | PatternCycle => r.shape()?,
        FinishCycle => {
            let (ns, nf) = r.sequence_pair()?;
            CycleArgs::Finish { ns, nf }
        }
        FacePeckCycle | GroovePeckCycle if !r.has_point() => {
            CycleArgs::GrooveSetup { retract: r.unsigned(b'R', "retract")? }
        }
        FacePeckCycle | GroovePeckCycle => CycleArgs::Groove {
            p: r.increment(b'P')?.unwrap_or(0),
            q: r.increment(b'Q')?.unwrap_or(0),
            relief: r.unsigned(b'R', "relief")?.unwrap_or(0),
        },
        MultiThreadCycle if !r.has_point() => CycleArgs::ThreadSetup {
            packed: r.packed()?,
            min_depth: r.increment(b'Q')?,
            allowance: r.unsigned(b'R', "finishing allowance")?,
        },
        MultiThreadCycle => CycleArgs::MultiThread {
            taper: r.length(b'R')?.unwrap_or(0),
            height: r.increment(b'P')?,
            first: r.increment(b'Q')?,
            lead: r.lead()?,
        },
        FaceDrill | FaceTap | FaceBore | SideDrill | SideTap | SideBore | HighSpeedPeck | LeftTap | FineBore
        | Drill | DrillDwell | PeckDrill | Tap | Bore | BoreSpindleStop | BackBore | BoreManual | BoreDwell => {
            CycleArgs::Hole {
                r: r.length(b'R')?,
                dwell_ms: r.count(b'P')?,
                q: r.unsigned(b'Q', "peck depth")?,
                repeat: r.count(b'K')?,
            }
        }
        _ => CycleArgs::None,
    })
}

/// Word access with the conversions cycles need.
struct Reader<'a> {
    block: &'a Block,
    fmt: &'a NumberFormat,
    diameter_x: bool,
}

impl Reader<'_> {
    /// A length word (R, U, W …) in nm, radius value as written.
    fn length(&self, l: u8) -> Result<Option<i64>, AlarmKind> {
        self.block.get(l).map(|n| super::words::length_nm_general(self.fmt, &n).ok_or(AlarmKind::Overflow)).transpose()
    }

    /// A length that the manual declares unsigned.
    fn unsigned(&self, l: u8, what: &'static str) -> Result<Option<i64>, AlarmKind> {
        let v = self.length(l)?;
        if v.is_some_and(|v| v < 0) {
            return Err(AlarmKind::CycleValueIllegal { what });
        }
        Ok(v)
    }

    /// G90/G92 taper: R, or seed 003's I (FANUC 0T); not both.
    fn taper(&self) -> Result<Option<i64>, AlarmKind> {
        match (self.length(b'R')?, self.length(b'I')?) {
            (Some(_), Some(_)) => Err(AlarmKind::WordNotAllowed { letter: b'I', context: "a cycle with R" }),
            (r, i) => Ok(r.or(i)),
        }
    }

    /// A whole number without decimal point or sign.
    fn count(&self, l: u8) -> Result<Option<u32>, AlarmKind> {
        let Some(n) = self.block.get(l) else { return Ok(None) };
        if n.is_negative() {
            return Err(AlarmKind::IllegalMinusSign { letter: l });
        }
        match n.as_integer() {
            Some(v) if !n.has_point || n.frac_digits == 0 => {
                u32::try_from(v).map(Some).map_err(|_| AlarmKind::ValueOutOfRange { letter: l })
            }
            _ => Err(AlarmKind::IllegalDecimalPoint { letter: l }),
        }
    }

    /// P/Q of G74–G76: least input increments without a decimal point (P6000 = 6 mm
    /// in IS-B metric), millimetres with one (P3.68); never negative.
    fn increment(&self, l: u8) -> Result<Option<i64>, AlarmKind> {
        let Some(n) = self.block.get(l) else { return Ok(None) };
        if n.is_negative() {
            return Err(AlarmKind::IllegalMinusSign { letter: l });
        }
        let fmt = NumberFormat { input: InputMode::LeastIncrement, ..*self.fmt };
        super::words::length_nm_general(&fmt, &n).map(Some).ok_or(AlarmKind::Overflow)
    }

    /// Whether the block names an end point (second block of G74–G76).
    fn has_point(&self) -> bool {
        [b'X', b'Z', b'U', b'W'].iter().any(|l| self.block.has(*l))
    }

    /// Whether the block is the shape block of G71–G73 (it has P and Q).
    fn has_shape(&self) -> bool {
        self.block.has(b'P') || self.block.has(b'Q')
    }

    /// P(ns) and Q(nf), both required (alarm 0061).
    fn sequence_pair(&self) -> Result<(u32, u32), AlarmKind> {
        let seq = |l: u8| -> Result<u32, AlarmKind> {
            let n = self.block.get(l).ok_or(AlarmKind::CycleAddressMissing { letter: l })?;
            if n.has_point {
                return Err(AlarmKind::IllegalDecimalPoint { letter: l });
            }
            match n.as_integer() {
                Some(v @ 1..=99_999) => Ok(v as u32),
                _ => Err(AlarmKind::ValueOutOfRange { letter: l }),
            }
        };
        Ok((seq(b'P')?, seq(b'Q')?))
    }

    /// The second block of G71–G73: P, Q, U(Δu, diameter), W(Δw).
    fn shape(&self) -> Result<CycleArgs, AlarmKind> {
        let (ns, nf) = self.sequence_pair()?;
        let du = self.length(b'U')?.unwrap_or(0);
        let du = if self.diameter_x { du / 2 } else { du };
        Ok(CycleArgs::Shape { ns, nf, du, dw: self.length(b'W')?.unwrap_or(0) })
    }

    /// Lead from F (mm or inch per revolution) or E (threads per inch).
    fn lead(&self) -> Result<Option<i64>, AlarmKind> {
        let lead = match (self.block.get(b'F'), self.block.get(b'E')) {
            (Some(_), Some(_)) => return Err(AlarmKind::WordNotAllowed { letter: b'E', context: "a thread with F" }),
            (Some(f), None) => self.fmt.feed_nm(&f).ok_or(AlarmKind::IllegalLead)?,
            (None, Some(e)) => threads_per_inch(&e)?,
            (None, None) => return Ok(None),
        };
        check_lead(lead, self.fmt.units)?;
        Ok(Some(lead))
    }

    /// G32/G34 Q: start angle in degrees, 0–360 (2.17.1 Q rule 3).
    fn start_angle(&self) -> Result<Option<u32>, AlarmKind> {
        let Some(q) = self.block.get(b'Q') else { return Ok(None) };
        let u = self.fmt.angle_udeg(&q).ok_or(AlarmKind::ThreadStartAngle)?;
        if !(0..=360 * UDEG_PER_DEG).contains(&u) {
            return Err(AlarmKind::ThreadStartAngle);
        }
        Ok(Some(u as u32))
    }

    /// G34 K: lead change per revolution, within ±499.99 mm (±9.98 in) (2.17.2).
    fn lead_delta(&self) -> Result<i64, AlarmKind> {
        let Some(k) = self.block.get(b'K') else { return Ok(0) };
        let v = self.fmt.feed_nm(&k).ok_or(AlarmKind::IllegalLead)?;
        let max = match self.fmt.units {
            Units::Metric => 499_990_000,
            Units::Inch => 9_980 * NM_PER_INCH / 1_000,
        };
        if v.abs() > max {
            return Err(AlarmKind::IllegalLead);
        }
        Ok(v)
    }

    /// G92 H: number of starts 1–99.
    fn starts(&self) -> Result<u8, AlarmKind> {
        match self.count(b'H')? {
            None => Ok(1),
            Some(h @ 1..=99) => Ok(h as u8),
            Some(_) => Err(AlarmKind::ValueOutOfRange { letter: b'H' }),
        }
    }

    /// G76 P(m)(r)(a): the last two digits are a, the two before them r, the rest m
    /// (2.17.4 note 4, which also covers values with fewer or more digits).
    fn packed(&self) -> Result<Option<(u32, u32, u32)>, AlarmKind> {
        let Some(p) = self.count(b'P')? else { return Ok(None) };
        let (m, r, a) = (p / 10_000, (p / 100) % 100, p % 100);
        if !(1..=99).contains(&m) {
            return Err(AlarmKind::CycleValueIllegal { what: "G76 finishing count m must be 01-99" });
        }
        Ok(Some((m, r, a)))
    }
}

/// E threads per inch as a lead in nm/rev: 25.4 mm / E.
fn threads_per_inch(e: &Number) -> Result<i64, AlarmKind> {
    if e.mantissa <= 0 {
        return Err(AlarmKind::IllegalLead);
    }
    let scale = pow10(e.frac_digits).ok_or(AlarmKind::IllegalLead)?;
    let num = i128::from(NM_PER_INCH) * i128::from(scale);
    let den = i128::from(e.mantissa);
    i64::try_from((2 * num + den) / (2 * den)).map_err(|_| AlarmKind::IllegalLead)
}

/// Words a cycle code takes besides F, S, T, and its name for messages.
pub fn letters_of(code: GCode) -> Option<(&'static [u8], &'static str)> {
    use GCode::*;
    Some(match code {
        TurningCycle => (b"XZUWYVCHRI", "G90"),
        FacingCycle => (b"XZUWYVCHR", "G94"),
        ThreadCycle => (b"XZUWYVCRIEH", "G92"),
        Thread => (b"XZUWYVCHEQ", "G32"),
        VariableLeadThread => (b"XZUWYVCHEQK", "G34"),
        FinishCycle => (b"PQ", "G70"),
        RoughTurnCycle => (b"UWRPQ", "G71"),
        RoughFaceCycle => (b"UWRPQ", "G72"),
        PatternCycle => (b"UWRPQ", "G73"),
        FacePeckCycle => (b"XZUWYVCHPQR", "G74"),
        GroovePeckCycle => (b"XZUWYVCHPQR", "G75"),
        MultiThreadCycle => (b"XZUWYVCHPQR", "G76"),
        FaceDrill | SideDrill | FaceTap | SideTap => (b"XZUWYVCHRPQK", "G83/G84/G87/G88"),
        FaceBore | SideBore => (b"XZUWYVCHRPK", "G85/G89"),
        _ => return None,
    })
}

/// The words of an ellipse or parabola block (2.4, 2.5): A, B, P lengths; Q an
/// angle in 0.001° without a decimal point, in degrees with one.
pub fn read_curve(block: &Block, fmt: &NumberFormat) -> Result<CycleArgs, AlarmKind> {
    let r = Reader { block, fmt, diameter_x: false };
    let q_udeg = match block.get(b'Q') {
        None => 0,
        Some(q) if q.has_point => fmt.angle_udeg(&q).ok_or(AlarmKind::Overflow)?,
        Some(q) => q.as_integer().and_then(|v| v.checked_mul(1_000)).ok_or(AlarmKind::Overflow)?,
    };
    Ok(CycleArgs::Curve { a: r.length(b'A')?, b: r.length(b'B')?, p: r.length(b'P')?, q_udeg })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lang::fanuc::parse::read_block;
    use crate::units::IncrementSystem;

    const FMT: NumberFormat =
        NumberFormat { units: Units::Metric, input: InputMode::Calculator, increments: IncrementSystem::IsB };

    fn read_of(code: GCode, text: &str) -> Result<CycleArgs, AlarmKind> {
        read(code, &read_block(text.as_bytes(), 1).unwrap(), &FMT, true)
    }

    #[test]
    fn g76_packed_p_and_increment_words() {
        assert_eq!(
            read_of(GCode::MultiThreadCycle, "G76 P020560 Q0.15 R0.1"),
            Ok(CycleArgs::ThreadSetup { packed: Some((2, 5, 60)), min_depth: Some(150_000), allowance: Some(100_000) })
        );
        // Irregular P: last two digits a, the two before r, the rest m.
        assert_eq!(
            read_of(GCode::MultiThreadCycle, "G76 P21060"),
            Ok(CycleArgs::ThreadSetup { packed: Some((2, 10, 60)), min_depth: None, allowance: None })
        );
        assert!(matches!(read_of(GCode::MultiThreadCycle, "G76 P1231060"), Err(AlarmKind::CycleValueIllegal { .. })));
        assert_eq!(
            read_of(GCode::MultiThreadCycle, "G76 X60.64 Z-62 P3680 Q1800 F6"),
            Ok(CycleArgs::MultiThread {
                taper: 0,
                height: Some(3_680_000),
                first: Some(1_800_000),
                lead: Some(6_000_000)
            })
        );
    }

    #[test]
    fn g75_p_q_are_least_increments_without_point() {
        assert_eq!(
            read_of(GCode::GroovePeckCycle, "G75 X40 Z-50 P6000 Q3000"),
            Ok(CycleArgs::Groove { p: 6_000_000, q: 3_000_000, relief: 0 })
        );
        assert_eq!(read_of(GCode::GroovePeckCycle, "G75 R0.5"), Ok(CycleArgs::GrooveSetup { retract: Some(500_000) }));
    }

    #[test]
    fn thread_words() {
        assert_eq!(
            read_of(GCode::Thread, "G32 W-10 E10 Q180"),
            Ok(CycleArgs::Thread { lead: Some(2_540_000), start_udeg: Some(180_000_000), delta: 0 })
        );
        assert_eq!(read_of(GCode::Thread, "G32 W-10 F2 Q361"), Err(AlarmKind::ThreadStartAngle));
        assert_eq!(read_of(GCode::Thread, "G32 W-10 F0"), Err(AlarmKind::IllegalLead));
        assert_eq!(read_of(GCode::VariableLeadThread, "G34 W-10 F4 K500"), Err(AlarmKind::IllegalLead));
    }
}

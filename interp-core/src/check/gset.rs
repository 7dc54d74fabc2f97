//! Resolving a block's G codes: table lookup, one code per modal group, and the
//! rules about codes that must stand alone.

use crate::alarm::{AlarmKind, GNum};
use crate::canon::{FeedMode, Plane};
use crate::codes::{GCode, Group};
use crate::config::MachineConfig;
use crate::modal::State;
use crate::parse::Block;
use crate::units::Units;

/// The G codes of one block, one slot per modal group.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct GSet {
    /// Group 01.
    pub motion: Option<GCode>,
    /// Group 00 (G04, G09, G28, G30, G50, G52, G53, G70–G76).
    pub one_shot: Option<GCode>,
    /// Group 16.
    pub plane: Option<Plane>,
    /// Group 06.
    pub units: Option<Units>,
    /// Group 03 (B/C): Some(true) = G91.
    pub incremental: Option<bool>,
    /// Group 05.
    pub feed_mode: Option<FeedMode>,
    /// Group 02: Some(true) = G96.
    pub css: Option<bool>,
    /// Group 07.
    pub nose_comp: Option<GCode>,
    /// Group 14: frame 0–5.
    pub work_frame: Option<u8>,
    /// Group 15: Some(true) = G61.
    pub exact_stop_mode: Option<bool>,
    /// Group 10.
    pub drilling: Option<GCode>,
    /// Group 11 (B/C): Some(true) = G99.
    pub return_to_r: Option<bool>,
    /// Group 04: Some(true) = G22, Some(false) = G23.
    pub stroke: Option<bool>,
    /// Group 21: Some(true) = G12.1, Some(false) = G13.1.
    pub polar: Option<bool>,
    /// Group 20: Some(true) = G51.2, Some(false) = G50.2.
    pub polygon: Option<bool>,
}

/// Whether a group-00 code takes the block's axis words for itself.
pub(crate) fn uses_axes(c: GCode) -> bool {
    use GCode::*;
    matches!(c, Dwell | ReferenceReturn | ReferenceReturnN | SetCoordinates | LocalFrame | MachineCoordinates)
        || crate::check::cycle_args::is_multiple(c)
}

impl GSet {
    /// No G code at all.
    pub const NONE: GSet = GSet {
        motion: None,
        one_shot: None,
        plane: None,
        units: None,
        incremental: None,
        feed_mode: None,
        css: None,
        nose_comp: None,
        work_frame: None,
        exact_stop_mode: None,
        drilling: None,
        return_to_r: None,
        stroke: None,
        polar: None,
        polygon: None,
    };

    /// Looks up every G code of `block` and sorts it into its group.
    pub fn resolve(block: &Block, state: &State, cfg: &MachineConfig) -> Result<GSet, AlarmKind> {
        let mut set = GSet::NONE;
        set.resolve_into(block, state, cfg)?;
        Ok(set)
    }

    /// [`GSet::resolve`] in place (the command's set, reused block after block:
    /// nothing is copied). On an alarm the set holds a partial result.
    #[inline]
    pub(crate) fn resolve_into(&mut self, block: &Block, state: &State, cfg: &MachineConfig) -> Result<(), AlarmKind> {
        *self = GSet::NONE;
        let set = self;
        // Groups seen so far, a bit each; the codes themselves are looked up again
        // only for an alarm.
        let mut seen = 0u32;
        let first = |group: Group| {
            let of = |t: &&u16| GCode::from_tenths(cfg.gcode_system, **t).is_some_and(|c| c.group() == group);
            block.g.iter().find(of).copied().unwrap_or(0)
        };
        for &tenths in &block.g {
            let code =
                GCode::from_tenths(cfg.gcode_system, tenths).ok_or(AlarmKind::ImproperGCode { code: GNum(tenths) })?;
            let bit = 1u32 << (code.group() as u32);
            if seen & bit != 0 {
                return Err(AlarmKind::DuplicateGroup { first: GNum(first(code.group())), second: GNum(tenths) });
            }
            seen |= bit;
            supported(code)?;
            set.assign(code);
        }
        set.check_units_alone(block, state)?;
        // 2.10 note 6: G22/G23 take no other G code in their block; 2.7: G12.1/G13.1
        // are given in a block of their own.
        // 2.8 note 1: G50.2/G51.2 too, without M codes.
        let polygon_not_alone = set.polygon.is_some() && !block.m.is_empty();
        for (on, group) in [
            (set.stroke.is_some(), Group::StrokeCheck),
            (set.polar.is_some(), Group::Polar),
            (set.polygon.is_some(), Group::Polygon),
        ] {
            if on && (block.g.len() > 1 || (group == Group::Polygon && polygon_not_alone)) {
                return Err(AlarmKind::CodeMustBeAlone { code: GNum(first(group)) });
            }
        }
        if let (Some(one), Some(_)) = (set.one_shot, set.motion)
            && uses_axes(one)
        {
            return Err(AlarmKind::CodeMustBeAlone { code: GNum(first(Group::NonModal)) });
        }
        Ok(())
    }

    fn assign(&mut self, code: GCode) {
        use GCode::*;
        match code {
            PlaneXy => self.plane = Some(Plane::Xy),
            PlaneZx => self.plane = Some(Plane::Zx),
            PlaneYz => self.plane = Some(Plane::Yz),
            Inch => self.units = Some(Units::Inch),
            Metric => self.units = Some(Units::Metric),
            Absolute => self.incremental = Some(false),
            Incremental => self.incremental = Some(true),
            FeedPerMin => self.feed_mode = Some(FeedMode::PerMin),
            FeedPerRev => self.feed_mode = Some(FeedMode::PerRev),
            CssOn => self.css = Some(true),
            CssOff => self.css = Some(false),
            WorkFrame(n) => self.work_frame = Some(n),
            ExactStopMode => self.exact_stop_mode = Some(true),
            ContinuousMode => self.exact_stop_mode = Some(false),
            ReturnInitial => self.return_to_r = Some(false),
            ReturnR => self.return_to_r = Some(true),
            StrokeCheckOn => self.stroke = Some(true),
            StrokeCheckOff => self.stroke = Some(false),
            PolarOn => self.polar = Some(true),
            PolarOff => self.polar = Some(false),
            PolygonOn => self.polygon = Some(true),
            PolygonOff => self.polygon = Some(false),
            _ => match code.group() {
                Group::Motion => self.motion = Some(code),
                Group::NonModal => self.one_shot = Some(code),
                Group::NoseComp => self.nose_comp = Some(code),
                Group::Drilling => self.drilling = Some(code),
                // Polar, polygon and stroke-check codes that reach here are the
                // cancel codes of modes that are never on: nothing to record.
                _ => {}
            },
        }
    }

    /// G20/G21 that switches units must be alone and before any move (2.9 note 2);
    /// repeating the units already in force is harmless anywhere.
    fn check_units_alone(&self, block: &Block, state: &State) -> Result<(), AlarmKind> {
        if self.units.is_some_and(|u| u != state.modal.units) {
            let alone = block.g.len() == 1 && block.m.is_empty() && block.letters().next().is_none();
            if !alone {
                return Err(AlarmKind::UnitsNotAlone);
            }
            if state.moved {
                return Err(AlarmKind::UnitsNotAtStart);
            }
        }
        Ok(())
    }
}

/// Every code of the manual is implemented: nothing to reject here any more. Kept
/// as the one place a future code's "not supported yet" (4007) would go.
fn supported(_code: GCode) -> Result<(), AlarmKind> {
    Ok(())
}

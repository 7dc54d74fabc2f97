//! Resolving a block's G codes: table lookup, one code per modal group, and the
//! rules about codes that must stand alone.

use crate::alarm::{AlarmKind, GNum};
use crate::codes::{GCode, Group};
use crate::command::{GSet, uses_axes};
use crate::config::MachineConfig;
use crate::lang::fanuc::parse::Block;
use crate::modal::State;

impl GSet {
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
        let table = cfg.code_table();
        let first = |group: Group| {
            let of = |t: &&u16| GCode::from_tenths(table, **t).is_some_and(|c| c.group() == group);
            block.g.iter().find(of).copied().unwrap_or(0)
        };
        for &tenths in &block.g {
            let code = GCode::from_tenths(table, tenths).ok_or(AlarmKind::ImproperGCode { code: GNum(tenths) })?;
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
        // G290/G291 stand in a block of their own, as on the 840D.
        if let Some(GCode::Language(_)) = set.one_shot {
            let alone = block.g.len() == 1 && block.m.is_empty() && block.letters().next().is_none();
            if !alone {
                return Err(AlarmKind::CodeMustBeAlone { code: GNum(first(Group::NonModal)) });
            }
        }
        if let (Some(one), Some(_)) = (set.one_shot, set.motion)
            && uses_axes(one)
        {
            return Err(AlarmKind::CodeMustBeAlone { code: GNum(first(Group::NonModal)) });
        }
        Ok(())
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

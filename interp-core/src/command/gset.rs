//! The G codes of one checked block, one slot per modal group.

use crate::canon::{FeedMode, Plane};
use crate::codes::{GCode, Group};
use crate::units::Units;

/// The G codes of one block, one slot per modal group.
///
/// Word-aligned: the set is cleared for every block ([`GSet::NONE`]), and a
/// byte-aligned copy of its 26 bytes is a byte loop on the Cortex-M4 (~180
/// instructions) where an aligned one is a few word stores.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(align(4))]
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
    /// Mill group 08: G43, G44 or G49.
    pub length: Option<GCode>,
    /// Mill group 17: Some(true) = G16, Some(false) = G15.
    pub polar_coord: Option<bool>,
    /// Mill groups 11, 22, 16: G50/G51, G50.1/G51.1 or G68/G69 (one per block: they
    /// take the block's axis words).
    pub frame: Option<GCode>,
    /// A machining centre's block that needs more than a lathe's plain way: H, D,
    /// T, M06, G10, G28–G30, G43/G44/G49, G54.1, G15/G16, G50/G51, G50.1/G51.1,
    /// G68/G69, a hole cycle, or any block while a transformation is in force. Set
    /// by the mill's checker; execution then takes the full way and the block's
    /// undo saves the mill's data.
    pub mill: bool,
}

/// `work_frame` of a block with G54.1 until its P is read (the checker then puts
/// frame 5 + P there: 6–53).
pub const EXTRA_FRAME: u8 = u8::MAX;

/// Whether a group-00 code takes the block's axis words for itself.
pub fn uses_axes(c: GCode) -> bool {
    use GCode::*;
    matches!(
        c,
        Dwell
            | ReferenceReturn
            | ReferenceReturnN
            | SetCoordinates
            | LocalFrame
            | MachineCoordinates
            | DataSetting
            | ReturnFromReference
    ) || super::cycle::is_multiple(c)
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
        length: None,
        polar_coord: None,
        frame: None,
        mill: false,
    };

    /// Puts `code` into its group's slot (the front end has checked that the
    /// group is not given twice).
    pub fn assign(&mut self, code: GCode) {
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
            PolarCoordOn => self.polar_coord = Some(true),
            PolarCoordOff => self.polar_coord = Some(false),
            ExtraWorkFrame => self.work_frame = Some(EXTRA_FRAME),
            _ => match code.group() {
                Group::Motion => self.motion = Some(code),
                Group::NonModal => self.one_shot = Some(code),
                Group::NoseComp => self.nose_comp = Some(code),
                Group::Drilling => self.drilling = Some(code),
                Group::LengthComp => self.length = Some(code),
                Group::Scaling | Group::Mirror | Group::Rotation => self.frame = Some(code),
                // Polar, polygon and stroke-check codes that reach here are the
                // cancel codes of modes that are never on: nothing to record.
                _ => {}
            },
        }
    }
}

//! SINUMERIK milling cycles (seed 001 chapter 3, lines 3399-10068) on the mill
//! profile: each cycle's parameters read and checked here (its 61xxx alarms),
//! its tool path laid out by a generator of the crate `mill_paths` and run by
//! the engine ([`Engine::mill`]) in the active plane — emitted, dry-run and
//! limit-checked like every other cycle. One file per family: this module holds
//! what every milling cycle shares.
//!
//! Shared rules (lines 3476-3536):
//! - **Plane** (3486-3494): the cycle works in the active plane G17/G18/G19; the
//!   infeed is along its third axis (the applicate). The plane's three axes must
//!   exist, else 61005 "3rd geometry axis not present" (as the drilling cycles).
//! - **Tool** (3478): a tool offset must be active before the call: D0 is 61000.
//!   Cycles that check the radius say which alarm a bad one raises (61112
//!   "tool radius negative": CYCLE72/76/77/90; 61117 "active tool radius <= 0":
//!   CYCLE71/POCKET3/POCKET4); T0 is 61009 where the cycle names it (CYCLE71/72).
//! - **Levels**: RTP retract plane, RFP reference plane, SDIS safety distance
//!   (no sign, towards RTP), DP final depth absolute or DPR relative to RFP (DPR
//!   wins); the same checks as the drilling cycles (61101). The depth infeeds
//!   start at RFP + SDIS, or at RFP with `_ZSD[1]` = 1 (lines 3522-3536), and are
//!   divided by [`mill_paths::infeed`].
//! - **Feeds** in the feed unit in force (FFD depth, FFP1 surface, FFP2 finish);
//!   a feed of 0 is the feed in force (F before the call, line 3480).

// A board build that leaves out the cycles behind the features below leaves some
// shared checks without a caller (`here`, `tool_selected`, `width_infeed`, …).
#![cfg_attr(
    not(all(
        feature = "mill-face",
        feature = "mill-slots",
        feature = "mill-pockets",
        feature = "mill-engrave",
        feature = "mill-contour",
        feature = "mill-island"
    )),
    allow(dead_code)
)]

mod settings;

#[cfg(feature = "mill-contour")]
pub(super) mod contour;
#[cfg(feature = "mill-engrave")]
pub(super) mod engrave;
#[cfg(feature = "mill-face")]
pub(super) mod face;
#[cfg(feature = "mill-island")]
pub(crate) mod island;
pub(super) use settings::{cycle800, cycle832};
pub(super) mod pocket;
#[cfg(feature = "mill-slots")]
pub(super) mod slot;
pub(super) mod thread;

use super::Params;
use interp_core::MachineConfig;
use interp_core::alarm::CycleAlarm;
use interp_core::axis::Axis;
use interp_core::cycles::mill::plane_axes;
use interp_core::modal::State;
use mill_paths::P3;

/// The levels of a milling call along the applicate, work nm.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Levels {
    /// Retract plane (RTP).
    pub rtp: i64,
    /// Reference plane (RFP).
    pub rfp: i64,
    /// RFP advanced by the safety distance towards RTP (RFP + SDIS).
    pub safe: i64,
    /// Where the depth infeeds start: `safe`, or RFP with `_ZSD[1]` = 1.
    pub start: i64,
    /// Final depth (DP, or RFP − DPR into the material).
    pub bottom: i64,
    /// Into the material: −1 (down the applicate) or +1.
    pub dir: i64,
}

/// RTP, RFP, SDIS, DP of the call at `[rtp, rfp, sdis, dp]`, DPR at `dpr` when
/// the cycle has it: the levels, or 61101 "reference plane defined incorrectly"
/// (a relative depth with RTP = RFP, a depth on the retract plane's side, no
/// depth). The rule of the drilling cycles (lines 1559-1591).
pub(super) fn levels(p: &Params<'_, '_>, st: &State, at: [usize; 4], dpr: Option<usize>) -> Result<Levels, CycleAlarm> {
    let (rtp, rfp, sdis, dp) = (p.len(at[0]), p.len(at[1]), p.unsigned(at[2]), p.len(at[3]));
    let dpr = dpr.map_or(0, |i| p.unsigned(i));
    let dir = if rtp != rfp {
        (rfp - rtp).signum()
    } else if dpr != 0 {
        return Err(CycleAlarm::ReferencePlaneWrong);
    } else {
        (dp - rfp).signum()
    };
    let bottom = if dpr != 0 { rfp + dir * dpr } else { dp };
    if dir == 0 || (bottom - rfp) * dir <= 0 {
        return Err(CycleAlarm::ReferencePlaneWrong);
    }
    let safe = rfp - dir * sdis;
    let start = if st.cycle.zsd[1] == 1 { rfp } else { safe };
    Ok(Levels { rtp, rfp, safe, start, bottom, dir })
}

/// The plane's three axes (abscissa, ordinate, applicate), or 61005 when the
/// machine lacks one (a lathe's G18 without Y).
pub(super) fn plane(st: &State, cfg: &MachineConfig) -> Result<[Axis; 3], CycleAlarm> {
    let axes = plane_axes(st.modal.plane);
    if axes.iter().any(|a| !cfg.axes[a.index()].present) {
        return Err(CycleAlarm::NoThirdAxis);
    }
    Ok(axes)
}

/// Where the tool is at the call, in the plane's coordinates.
pub(super) fn here(st: &State, cfg: &MachineConfig) -> P3 {
    let w = st.work_pos(cfg);
    let [a, o, d] = plane_axes(st.modal.plane);
    P3::new(w[a], w[o], w[d])
}

/// How a cycle checks the cutter radius of the active offset.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Radius {
    /// Negative is 61112 "tool radius negative" (CYCLE72, CYCLE76, CYCLE77, CYCLE90).
    NotNegative,
    /// Zero or negative is 61117 "active tool radius <= 0" (CYCLE71, POCKET3, POCKET4).
    Positive,
}

/// The cutter radius of the active D offset, nm: D0 is 61000 "no tool offset
/// active" (line 3478), a radius the cycle cannot use its `rule`'s alarm.
pub(super) fn cutter(st: &State, rule: Radius) -> Result<i64, CycleAlarm> {
    // A lathe's offset is T's row, a machining centre's D (`st.mill.d`).
    if st.tool.offset_number == 0 && st.mill.d == 0 {
        return Err(CycleAlarm::NoToolOffset);
    }
    let r = st.tool.nose_radius;
    match rule {
        Radius::NotNegative if r < 0 => Err(CycleAlarm::ToolRadiusNegative),
        Radius::Positive if r <= 0 => Err(CycleAlarm::ToolRadiusNotPositive),
        _ => Ok(r),
    }
}

/// 61009 "active tool number = 0" unless a tool is selected (CYCLE71, CYCLE72).
pub(super) fn tool_selected(st: &State) -> Result<(), CycleAlarm> {
    if st.tool.tool == 0 { Err(CycleAlarm::ToolNumberZero) } else { Ok(()) }
}

/// Feed parameter `i` in nm per minute (or per revolution): 0 or left out is
/// the feed in force; 61003 "no feed programmed in the cycle" when that is 0 too.
pub(super) fn feed(p: &Params<'_, '_>, i: usize, st: &State) -> Result<i64, CycleAlarm> {
    match p.unsigned(i) {
        0 => match st.feed.get(st.modal.feed_mode) {
            0 => Err(CycleAlarm::NoFeed),
            f => Ok(f),
        },
        f => Ok(f),
    }
}

/// The largest width infeed in the plane from `_MIDA` (0: 80 % of the cutter
/// diameter, line 4960): wider than the cutter diameter is 61111 "infeed width >
/// tool diameter".
pub(super) fn width_infeed(mida: i64, radius: i64) -> Result<i64, CycleAlarm> {
    if mida > 2 * radius {
        return Err(CycleAlarm::InfeedWidthTooLarge);
    }
    Ok(mill_paths::infeed::max_width(mida, radius))
}

/// 61105 "milling cutter radius too large" unless a cutter of `radius` fits a
/// width of `space` (a slot's width, a pocket's side, an elongated hole's
/// length: the cutter diameter must not exceed it, lines 3862, 4054, 4519).
pub(super) fn fits(space: i64, radius: i64) -> Result<(), CycleAlarm> {
    if 2 * radius > space { Err(CycleAlarm::CutterRadiusTooLarge) } else { Ok(()) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cycles::Arg;
    use interp_core::axis::Pos;

    fn mill_state(d: u16, radius: i64) -> State {
        let cfg = MachineConfig::default();
        let mut st = State::power_on(&cfg, Pos::default());
        st.tool.tool = 1;
        st.tool.offset_number = d;
        st.tool.nose_radius = radius;
        st
    }

    fn reals(v: &[f64]) -> std::vec::Vec<Arg<'static>> {
        v.iter().map(|&x| Arg::Real(x)).collect()
    }

    /// Levels as the drilling cycles read them, and where the infeeds start.
    #[test]
    fn levels_and_the_reference_plane_alarm() {
        let mut st = mill_state(1, 5_000_000);
        let args = reals(&[10.0, 0.0, 2.0, -23.0, 0.0]);
        let p = Params::new(&args, &st);
        let l = levels(&p, &st, [0, 1, 2, 3], Some(4)).unwrap();
        assert_eq!(
            (l.rtp, l.rfp, l.safe, l.start, l.bottom, l.dir),
            (10_000_000, 0, 2_000_000, 2_000_000, -23_000_000, -1)
        );
        // DPR wins over DP; _ZSD[1] = 1 starts the infeeds at RFP.
        st.cycle.zsd[1] = 1;
        let args = reals(&[10.0, 0.0, 2.0, -23.0, 5.0]);
        let p = Params::new(&args, &st);
        let l = levels(&p, &st, [0, 1, 2, 3], Some(4)).unwrap();
        assert_eq!((l.start, l.bottom), (0, -5_000_000));
        // DPR with RTP = RFP, a depth on the retract side, no depth: 61101.
        for v in [[0.0, 0.0, 2.0, 0.0, 5.0], [10.0, 0.0, 2.0, 5.0, 0.0], [10.0, 0.0, 2.0, 0.0, 0.0]] {
            let args = reals(&v);
            let p = Params::new(&args, &st);
            assert_eq!(levels(&p, &st, [0, 1, 2, 3], Some(4)), Err(CycleAlarm::ReferencePlaneWrong), "{v:?}");
        }
    }

    /// The tool checks of the milling cycles (61000, 61009, 61112, 61117), the
    /// feed (61003) and the width infeed (61111).
    #[test]
    fn tool_feed_and_width_alarms() {
        assert_eq!(cutter(&mill_state(0, 5), Radius::NotNegative), Err(CycleAlarm::NoToolOffset));
        assert_eq!(cutter(&mill_state(1, -5), Radius::NotNegative), Err(CycleAlarm::ToolRadiusNegative));
        assert_eq!(cutter(&mill_state(1, 0), Radius::NotNegative), Ok(0));
        assert_eq!(cutter(&mill_state(1, 0), Radius::Positive), Err(CycleAlarm::ToolRadiusNotPositive));
        assert_eq!(cutter(&mill_state(2, 4_000_000), Radius::Positive), Ok(4_000_000));
        let mut st = mill_state(1, 5);
        st.tool.tool = 0;
        assert_eq!(tool_selected(&st), Err(CycleAlarm::ToolNumberZero));
        (st.feed.per_min, st.feed.per_rev) = (0, 0);
        let args = reals(&[0.0, 120.0]);
        let p = Params::new(&args, &st);
        assert_eq!(feed(&p, 0, &st), Err(CycleAlarm::NoFeed));
        assert_eq!(feed(&p, 1, &st), Ok(120_000_000));
        assert_eq!(width_infeed(0, 5_000_000), Ok(8_000_000));
        assert_eq!(width_infeed(10_000_001, 5_000_000), Err(CycleAlarm::InfeedWidthTooLarge));
        assert_eq!(fits(10_000_000, 5_000_000), Ok(()));
        assert_eq!(fits(9_999_999, 5_000_000), Err(CycleAlarm::CutterRadiusTooLarge));
    }
}

//! Blocks of the modal cycles: G90/G94 turning and facing (2.15), G92 threading
//! (2.17.3), G32/G34 thread blocks (2.17.1–2) and the hole cycles G83–G89 (2.21–2.22),
//! with the values these blocks keep for the next ones.

use super::emit::{Emitter, Pt, Step};
use super::hole::{HoleGen, HoleSpec, HoleWork};
use super::thread::{Pullout, ThreadCycleGen, check_variable_lead, long_axis};
use super::{Ctx, CycleArgs, Gen, args};
use crate::alarm::AlarmKind;
use crate::axis::{Axis, Pos};
use crate::canon::{FeedMode, Plane, SpindleDir};
use crate::codes::GCode;
use crate::command::Command;
use crate::config::{MachineConfig, Param};
use crate::contour::cycle::{Nose, single};
use crate::modal::{RigidTap, SingleMemory, State};
use crate::moves::motion;

/// G90/G94/G92: the end point and taper, completed from the retained values when
/// the block does not repeat the cycle code (2.15 note 2); `None` without axis words.
fn end_and_taper(
    cmd: &Command,
    st: &mut State,
    cfg: &MachineConfig,
    taper: Option<i64>,
) -> Result<Option<(Pt, i64)>, AlarmKind> {
    if !cmd.has_axes() {
        return Ok(None);
    }
    let w = motion::target(cmd, st, cfg)?;
    let mut end = Pt::new(w[Axis::X], w[Axis::Z]);
    let mut r = taper.unwrap_or(0);
    if cmd.g.motion.is_none()
        && let Some(m) = st.cycle.single
    {
        if cmd.axes[Axis::X.index()].is_none() {
            end.x = m.x;
        }
        if cmd.axes[Axis::Z.index()].is_none() {
            end.z = m.z;
        }
        r = taper.unwrap_or(m.r);
    }
    st.cycle.single = Some(SingleMemory { x: end.x, z: end.z, r });
    Ok(Some((end, r)))
}

/// |R| ≤ |U/2| (|W| for G94) when R and U (W) have opposite signs (figures 2.24, 2.28).
#[inline(never)]
fn check_taper(r: i64, travel: i64) -> Result<(), AlarmKind> {
    if r != 0 && travel != 0 && super::sign(r) != super::sign(travel) && r.abs() > travel.abs() {
        return Err(AlarmKind::CycleTaperTooLarge);
    }
    Ok(())
}

/// The nose a G90/G94 cycle is compensated for: G41/G42 in force (and not
/// suppressed in a G71–G73 shape), with the radius and tip the offset started up
/// with, or the offset row's when it starts in this block.
fn cycle_nose(st: &State) -> Option<Nose> {
    if st.contour.no_comp || !matches!(st.modal.nose_comp, GCode::NoseCompLeft | GCode::NoseCompRight) {
        return None;
    }
    let c = st.contour.comp;
    let (radius, tip) = if c.side.is_some() { (c.radius, c.tip) } else { (st.tool.nose_radius, st.tool.tip) };
    Some(Nose { radius, tip })
}

/// G90, G94, G92 blocks.
pub fn single_block(code: GCode, cmd: &Command, st: &mut State, cfg: &MachineConfig) -> Result<Option<Gen>, AlarmKind> {
    let here = Emitter::for_block(st, cmd.line).here(cfg);
    let (taper, lead, starts) = match cmd.cycle {
        CycleArgs::Single { taper } => (taper, None, 1),
        CycleArgs::ThreadCycle { taper, lead, starts } => (taper, lead, starts),
        _ => (None, None, 1),
    };
    if code == GCode::ThreadCycle
        && let Some(l) = lead
    {
        st.cycle.lead = l;
    }
    let Some((c, r)) = end_and_taper(cmd, st, cfg, taper)? else { return Ok(None) };
    let a = here;
    let mut plan = heapless::Vec::new();
    let mut add = |s| plan.push(s).map_err(|_| AlarmKind::Overflow);
    match code {
        GCode::TurningCycle | GCode::FacingCycle => {
            // G90: ① X rapid to B, ② cut to C, ③ X feed back to D, ④ Z rapid to A.
            // G94: ① Z rapid to B, ② cut to C, ③ Z feed back to D, ④ X rapid to A.
            let turning = code == GCode::TurningCycle;
            let (b, d) = if turning {
                check_taper(r, c.x - a.x)?;
                (Pt::new(c.x + r, a.z), Pt::new(a.x, c.z))
            } else {
                check_taper(r, c.z - a.z)?;
                (Pt::new(a.x, c.z + r), Pt::new(c.x, a.z))
            };
            let [b, c, d] = match cycle_nose(st) {
                Some(nose) => {
                    let xz = |p: Pt| (p.x, p.z);
                    single(xz(a), xz(b), xz(c), xz(d), turning, nose)?.map(|(x, z)| Pt::new(x, z))
                }
                None => [b, c, d],
            };
            add(Step::Rapid(b))?;
            add(Step::Feed(c))?;
            add(Step::Feed(d))?;
            add(Step::Rapid(a))?;
        }
        _ => {
            check_taper(r, c.x - a.x)?;
            let pitch = st.cycle.lead;
            args::check_lead(pitch, st.modal.units)?;
            let pull = Pullout {
                tenths: cfg.params.get(Param::ThreadChamfer),
                angle_deg: cfg.params.get(Param::ThreadChamferAngle),
            };
            return Ok(Some(Gen::ThreadCycle(ThreadCycleGen::new(a, c, r, pitch, starts, pull)?)));
        }
    }
    Ok(Some(Gen::Plan(plan)))
}

/// G32/G34: one thread move, emitted with the block. Q counts only on the first of
/// consecutive thread blocks; the others continue without the index (note 2).
pub fn thread_block(cmd: &Command, st: &mut State, ctx: &mut Ctx<'_, '_>, chained: bool) -> Result<(), AlarmKind> {
    let CycleArgs::Thread { lead, start_udeg, delta } = cmd.cycle else { return Ok(()) };
    if let Some(l) = lead {
        st.cycle.lead = l;
    }
    if !cmd.has_axes() {
        return Ok(());
    }
    let lead = st.cycle.lead;
    args::check_lead(lead, st.modal.units)?;
    let mut em = Emitter::for_block(st, cmd.line);
    let from = em.here(ctx.cfg);
    let w = motion::target(cmd, st, ctx.cfg)?;
    let to = Pt::new(w[Axis::X], w[Axis::Z]);
    let long = long_axis(from, to);
    if delta != 0 {
        let max = match st.modal.units {
            crate::units::Units::Metric => 500_000_000,
            crate::units::Units::Inch => 19_685 * crate::units::NM_PER_INCH / 1_000,
        };
        check_variable_lead(lead, delta, to.get(long) - from.get(long), max)?;
    }
    let angle = if chained { 0 } else { start_udeg.unwrap_or(0) };
    em.emit(super::thread::single(to, lead, delta, angle, chained), ctx.cfg, &mut ctx.out.staged)?;
    *st = State { cycle: st.cycle, ..em.st };
    st.cycle.thread_chain = true;
    Ok(())
}

/// G83–G89 blocks: hole data completed from the retained values, rigid or floating
/// tapping, the lead of tapping. `None` when the block drills nothing (no hole
/// position and not the cycle's own block, or K0).
pub fn hole_block(
    code: GCode,
    cmd: &Command,
    st: &mut State,
    cfg: &MachineConfig,
) -> Result<Option<HoleGen>, AlarmKind> {
    use GCode::*;
    let axis = hole_axis(code, st.modal.plane);
    if !cfg.axis(axis).present {
        return Err(AlarmKind::AxisNotConfigured { letter: axis.letter() });
    }
    let CycleArgs::Hole { r, dwell_ms, q, repeat } = cmd.cycle else { return Ok(None) };
    let mem = &mut st.cycle.hole;
    if let Some(r) = r {
        mem.r = r;
    }
    if let Some(q) = q {
        mem.q = q;
    }
    if let Some(p) = dwell_ms {
        mem.dwell_ms = p;
    }
    if cmd.g.drilling.is_none() && !cmd.has_axes() {
        return Ok(None);
    }
    // The holes are positioned in the plane normal to the drilling axis (on a
    // lathe C stands in for the plane's second axis).
    let plane = match axis {
        Axis::Z => Plane::Xy,
        Axis::X => Plane::Yz,
        _ => Plane::Zx,
    };
    let here = super::emit::work_pos(st, cfg);
    let mut position = here;
    let mut step = Pos::ZERO;
    for a in Axis::ALL {
        if a == axis {
            continue;
        }
        if let Some(w) = cmd.axes[a.index()] {
            if w.incremental {
                position[a] = position[a].saturating_add(w.value);
                step[a] = w.value;
            } else {
                position[a] = w.value;
            }
        }
    }
    let r_level = here[axis] + st.cycle.hole.r;
    let bottom = match cmd.axes[axis.index()] {
        Some(w) if w.incremental => r_level + w.value,
        Some(w) => w.value,
        None => st.cycle.hole.bottom.ok_or(AlarmKind::MissingWord { letter: axis.letter(), context: "hole cycle" })?,
    };
    st.cycle.hole.bottom = Some(bottom);
    let mem = st.cycle.hole;
    let work = match code {
        FaceDrill | SideDrill => HoleWork::Drill {
            q: mem.q,
            deep: cfg.params.flag(Param::DeepPeckDrilling),
            d: cfg.params.get(Param::PeckDrillClearance),
        },
        FaceBore | SideBore => HoleWork::Bore,
        _ => tap_work(st, cfg, mem.q)?,
    };
    let spec = HoleSpec {
        work,
        axis,
        plane,
        position,
        step,
        // A lathe's initial level is where each hole block starts (2.21).
        initial: here[axis],
        r_level,
        bottom,
        dwell_ms: mem.dwell_ms,
        stay_at_r: st.modal.return_to_r,
        repeat: repeat.unwrap_or(1),
    };
    Ok(Some(HoleGen::new(spec)))
}

/// The axis a hole cycle works along. Drilling and boring: Z for the face codes
/// (G83, G85), X for the side codes (G87, G89), whatever the plane (2.13 note 4 keeps
/// only G70–G76 and G90/G92/G94 to the ZX plane). Tapping follows the plane (2.22.2
/// and 2.22.3 note 6): G84 in G17/G18/G19 taps along X/Z/Y, G88 along Y/X/Z.
fn hole_axis(code: GCode, plane: Plane) -> Axis {
    use GCode::*;
    match (code, plane) {
        (FaceTap, Plane::Xy) | (SideTap, Plane::Zx) => Axis::X,
        (FaceTap, Plane::Yz) | (SideTap, Plane::Xy) => Axis::Y,
        (FaceTap, Plane::Zx) | (SideTap, Plane::Yz) => Axis::Z,
        (FaceDrill | FaceBore, _) => Axis::Z,
        _ => Axis::X,
    }
}

/// The lead of tapping at `rpm`: F/S under feed per minute (seed 004 @8614: "螺距
/// T=F/S"), F under feed per revolution; alarms for F0 and a stopped spindle.
#[inline(never)]
pub(super) fn tap_lead(st: &State, rpm: u32) -> Result<i64, AlarmKind> {
    let mode = st.modal.feed_mode;
    let f = st.feed.get(mode);
    if f <= 0 {
        return Err(AlarmKind::FeedZero);
    }
    match mode {
        FeedMode::PerRev => Ok(f),
        FeedMode::PerMin if rpm > 0 => Ok(crate::units::div_round(f, i64::from(rpm))),
        FeedMode::PerMin => Err(AlarmKind::FeedPerRevSpindleStopped),
    }
}

/// Rigid (after M29) or floating tapping, with the lead F/S (G98) or F (G99).
fn tap_work(st: &mut State, cfg: &MachineConfig, q: i64) -> Result<HoleWork, AlarmKind> {
    if st.feed.get(st.modal.feed_mode) <= 0 {
        return Err(AlarmKind::FeedZero);
    }
    match st.cycle.rigid {
        RigidTap::Pending { rpm, before } | RigidTap::Active { rpm, before } => {
            st.cycle.rigid = RigidTap::Active { rpm, before };
            let dir = if cfg.params.flag(Param::ReverseTapping) { SpindleDir::Ccw } else { SpindleDir::Cw };
            Ok(HoleWork::RigidTap {
                lead: tap_lead(st, rpm)?,
                q,
                deep: cfg.params.flag(Param::DeepPeckTapping),
                d: cfg.params.get(Param::PeckTapClearance),
                dir,
                dwell_r_ms: u32::try_from(cfg.params.get(Param::TapDwellAtR)).unwrap_or(0),
                restore: if before == SpindleDir::Stop { SpindleDir::Cw } else { before },
            })
        }
        RigidTap::Off => {
            // The direction before the first tapping block, else the one remembered,
            // else M03 (2.22.3 note 2).
            let dir = match (st.spindle.dir, st.cycle.tap_dir) {
                (SpindleDir::Stop, SpindleDir::Stop) => SpindleDir::Cw,
                (SpindleDir::Stop, d) => d,
                (d, _) => d,
            };
            let turning = st.spindle.dir == dir;
            st.cycle.tap_dir = dir;
            // 2.22.3: M05 at the bottom and at R, M03/M04 again for the next hole.
            Ok(HoleWork::FloatTap {
                lead: tap_lead(st, st.spindle.rpm)?,
                dir,
                turning,
                after: SpindleDir::Stop,
                stop_at_bottom: true,
            })
        }
    }
}

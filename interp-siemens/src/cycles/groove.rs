//! CYCLE93 grooving (seed 001 4.3, lines 10192–10451): the groove's contour from
//! its parameters — on a surface at STA1 to the longitudinal axis, width WIDG and
//! depth DIAG from the start point SPD/SPL, flanks at ANG1/ANG2, radii (> 0) or
//! chamfers (< 0) at the outer (RCO) and bottom (RCI) corners, the chamfer as CHF
//! (VARI 1–8) or CHR (11–18) — handed to the grooving generator (`interp_core::cycles`,
//! G74/G75's pecking columns): plunges with IDEP pecks and _VRT chip breaking, DTB
//! at the bottom, the flanks along their slope, then each side finished along the
//! contour with its own cutting edge (D and D + 1, line 10342).
//!
//! VARI's units digit (line 10298): 1/5 longitudinal outside, start point left/right
//! of the groove; 3/7 longitudinal inside; 6/8 face outside, start point above/below;
//! 2/4 face inside. Alarms: 61000 no D, 61002 VARI, 61602 a groove narrower than the
//! tool (the two edges' offsets) or no tool width, 61603 a groove whose flanks or
//! corners do not fit it, or a face groove on a surface parallel to Z.
//!
//! Choices (docs/SIEMENS.md): STA1 turns the groove's surface counter-clockwise
//! from +Z in the (Z, X) plane (a face groove on a plain face has STA1 = 90); under
//! DIAMON the values along X — DIAG and IDEP of a longitudinal groove, WIDG of a
//! face groove — are diameters (the document's example, SPD 35 with DIAG 25, only
//! fits so); radii, chamfers, allowances and _VRT are lengths.

use super::stock::seconds_ms;
use super::{Engine, Params, need_zx};
use interp_core::alarm::{AlarmKind, CycleAlarm};
use interp_core::axis::Axis;
use interp_core::command::Command;
use interp_core::command::job::GrooveSpec;
use interp_core::geom::path::V2;
use interp_core::geom::{Pt, Seg, SegKind, sin_cos};
use interp_core::modal::State;

/// Most pieces a groove's contours take: the rough outline (lead-in, four corners
/// and the lines after them: 9), the two flank lines, each finishing half (lead-in,
/// two corners, two lines: 5 each) — 21.
const SEGS: usize = 24;

/// A corner of the groove: a radius (> 0), a chamfer (< 0) or none.
#[derive(Clone, Copy, Debug)]
struct CornerSpec {
    value: f64,
    /// Chamfers are CHR (leg length) rather than CHF (chamfer length).
    chr: bool,
}

/// The groove in its own frame: `p` across (from the start side's edge), `q` deep.
struct Frame {
    origin: V2,
    p: V2,
    q: V2,
}

impl Frame {
    fn at(&self, p: f64, q: f64) -> V2 {
        self.origin.plus(self.p.scale(p)).plus(self.q.scale(q))
    }
}

/// CYCLE93 (SPD, SPL, WIDG, DIAG, STA1, ANG1, ANG2, RCO1, RCO2, RCI1, RCI2, FAL1,
/// FAL2, IDEP, DTB, VARI, _VRT).
pub(super) fn cycle93(
    p: &Params<'_, '_>,
    cmd: &Command,
    st: &mut State,
    ctx: &mut dyn Engine,
) -> Result<(), AlarmKind> {
    need_zx(st)?;
    // A negative VARI (or one beyond u32) reads as 0, whose units are wrong.
    let vari = u32::try_from(p.int(15)).unwrap_or(0);
    let (units, tens) = (vari % 10, vari / 10);
    if !(1..=8).contains(&units) || !(0..=1).contains(&tens) {
        return Err(AlarmKind::SiemensCycle(CycleAlarm::MachiningTypeWrong));
    }
    let d = st.tool.offset_number;
    if d == 0 {
        return Err(AlarmKind::SiemensCycle(CycleAlarm::NoToolOffset));
    }
    let face = units % 2 == 0;
    let inside = matches!(units, 2 | 3 | 4 | 7);
    // Longitudinal: the groove runs to +Z from a start point on its left (1, 3);
    // face: to -X from a start point above it (6, 2).
    let towards_plus = matches!(units, 1 | 3 | 8 | 4);
    let half = |v: i64| if p.diameter { v / 2 } else { v };
    let width = p.unsigned(2);
    let depth = p.unsigned(3);
    let (width, depth, peck) =
        if face { (half(width), depth, p.unsigned(13)) } else { (width, half(depth), half(p.unsigned(13))) };
    let sta = p.real(4).to_radians();
    let (a1, a2) = (p.real(5).to_radians(), p.real(6).to_radians());
    let corner = |i: usize| CornerSpec { value: p.real(i), chr: tens == 1 };
    let (rco1, rco2, rci1, rci2) = (corner(7), corner(8), corner(9), corner(10));
    let (fal1, fal2) = (p.unsigned(11) as f64, p.unsigned(12) as f64);
    let safety = p.or_1mm(16);
    if peck <= 0 {
        return Err(AlarmKind::CycleValueIllegal { what: "CYCLE93 needs the infeed depth IDEP" });
    }
    // The groove's frame (line 10244: STA1 from the longitudinal axis).
    let surface = {
        let (s, c) = sin_cos(sta);
        V2::new(c, s)
    };
    let (along, deep) = if face { (surface.b, Axis::Z) } else { (surface.a, Axis::X) };
    if libm::fabs(along) < 1e-9 {
        return Err(AlarmKind::SiemensCycle(CycleAlarm::GrooveFormWrong));
    }
    let mut pdir = surface;
    if ((if face { pdir.b } else { pdir.a }) > 0.0) != towards_plus {
        pdir = pdir.scale(-1.0);
    }
    let left = pdir.left();
    let comp = |v: V2| if deep == Axis::X { v.b } else { v.a };
    // Deeper: -X (-Z for a face groove) outside, + inside.
    let want = if inside { 1.0 } else { -1.0 };
    if libm::fabs(comp(left)) < 1e-9 {
        return Err(AlarmKind::SiemensCycle(CycleAlarm::GrooveFormWrong));
    }
    let qdir = if comp(left) * want > 0.0 { left } else { left.scale(-1.0) };
    let origin = V2::new(p.len(1) as f64, p.x(0).abs() as f64);
    let fr = Frame { origin, p: pdir, q: qdir };
    let (w, dp) = (width as f64, depth as f64);
    // The final contour and the rough one (the flanks FAL2 and the bottom FAL1 in).
    let lead = 1e6 + safety as f64 + [rco1, rco2].iter().map(|c| c.value.abs() * 2e6).fold(0.0, f64::max);
    let fin = outline(&fr, w, dp, a1, a2, 0.0, 0.0, lead);
    let rough = outline(&fr, w, dp, a1, a2, fal2, fal1, lead);
    let corners = [rco1, rci1, rci2, rco2];
    let mut segs: heapless::Vec<Seg, SEGS> = heapless::Vec::new();
    // The rough contour without its lead-in and lead-out on the surface.
    let (r0, r1) = contour(&rough, &corners, None, &mut segs)?;
    let rough_range = (r0 + 1, r1 - 1);
    // The flanks' rough lines, from off the surface down to their feet.
    let flanks_from = segs.len() as u16;
    for (edge, foot, a) in [(rough[1], rough[2], a1), (rough[4], rough[3], a2)] {
        let down = foot.minus(edge).dot(qdir).max(1.0);
        let top = if a > 0.0 { edge.minus(foot.minus(edge).scale(safety as f64 / down)) } else { foot };
        push(&mut segs, line(top, if a > 0.0 { foot } else { top }))?;
    }
    let flanks = (flanks_from, segs.len() as u16);
    let h1 = contour(&fin, &corners, Some(0), &mut segs)?;
    let h2 = contour(&fin, &corners, Some(1), &mut segs)?;
    // The tool: edges D and D + 1 (line 10342) of the tool in force; edge D + 1's
    // offset row is a tool count further (`T t D d` is row t + (d − 1) × count).
    let cfg = ctx.cfg();
    let (Some(e1), Some(e2)) = (cfg.tools.get(d), cfg.tools.get(d.saturating_add(cfg.tool_count))) else {
        return Err(AlarmKind::SiemensCycle(CycleAlarm::ToolWidthWrong));
    };
    let span = Pt::new(e1.total_x() - e2.total_x(), e1.total_z() - e2.total_z());
    let step_axis = if face { Axis::X } else { Axis::Z };
    let opening = (pt(fin[4]).get(step_axis) - pt(fin[1]).get(step_axis)).abs();
    let tool = span.get(step_axis).abs();
    if tool == 0 || opening < tool {
        return Err(AlarmKind::SiemensCycle(CycleAlarm::ToolWidthWrong));
    }
    let spec = GrooveSpec {
        face,
        inward: if inside { 1 } else { -1 },
        edges: [pt(fin[1]), pt(fin[4])],
        safety,
        peck,
        dwell_ms: seconds_ms(p.real(14)),
        retract_feed: st.cycle.zsd[4] != 1,
        span,
        noses: [(e1.radius, e1.tip), (e2.radius, e2.tip)],
        rough: rough_range,
        flanks,
        halves: [h1, h2],
        half1_left: left.dot(qdir.scale(-1.0)) > 0.0,
    };
    p.ok()?;
    ctx.grooving(&spec, &segs, cmd, st)
}

/// The groove's outline V0…V5 (lead-in on the surface, edge, foot, foot, edge,
/// lead-out), its flanks moved in by `fal2` and its bottom up by `fal1`.
#[allow(clippy::too_many_arguments)]
fn outline(fr: &Frame, w: f64, d: f64, a1: f64, a2: f64, fal2: f64, fal1: f64, lead: f64) -> [V2; 6] {
    let (e1, e2) = (fal2 / sin_cos(a1).1, fal2 / sin_cos(a2).1);
    let dd = d - fal1;
    let (t1, t2) = (libm::tan(a1), libm::tan(a2));
    [
        fr.at(-lead, 0.0),
        fr.at(e1, 0.0),
        fr.at(e1 + dd * t1, dd),
        fr.at(w - e2 - dd * t2, dd),
        fr.at(w - e2, 0.0),
        fr.at(w + lead, 0.0),
    ]
}

/// Appends the outline with its corners (at V1–V4) to `segs`: all of it
/// (`half` None), or the start side (0) or the far side (1) from its lead-in to the
/// middle of the bottom. Returns the range. 61603 when corners do not fit their
/// lines or the bottom has no width.
fn contour(
    v: &[V2; 6],
    corners: &[CornerSpec; 4],
    half: Option<u8>,
    segs: &mut heapless::Vec<Seg, SEGS>,
) -> Result<(u16, u16), AlarmKind> {
    let from = segs.len() as u16;
    // Each corner: where it starts and ends on its two lines, and its piece.
    let mut cuts: [(V2, V2, Option<Seg>); 4] = [(V2::new(0.0, 0.0), V2::new(0.0, 0.0), None); 4];
    for i in 0..4 {
        cuts[i] = corner(v[i], v[i + 1], v[i + 2], corners[i])?;
    }
    // The straight pieces must keep a length ≥ 0 between their corners.
    let fits = |a: V2, b: V2, from: V2, to: V2| b.minus(a).dot(to.minus(from)) >= -1.0;
    if !fits(cuts[0].1, cuts[1].0, v[1], v[2])
        || !fits(cuts[1].1, cuts[2].0, v[2], v[3])
        || !fits(cuts[2].1, cuts[3].0, v[3], v[4])
    {
        return Err(AlarmKind::SiemensCycle(CycleAlarm::GrooveFormWrong));
    }
    let bottom_mid = cuts[1].1.plus(cuts[2].0.minus(cuts[1].1).scale(0.5));
    // The walk along the outline: the lead-in, each corner's start and end, the
    // lead-out, with the corners' pieces between; from the far side for half 1,
    // to the middle of the bottom for a half.
    let mut pts = [v[0], cuts[0].0, cuts[0].1, cuts[1].0, cuts[1].1, cuts[2].0, cuts[2].1, cuts[3].0, cuts[3].1, v[5]];
    let mut pieces = [cuts[0].2, cuts[1].2, cuts[2].2, cuts[3].2];
    if half.is_some_and(|h| h != 0) {
        pts.reverse();
        pieces.reverse();
        for c in pieces.iter_mut().flatten() {
            *c = reversed(*c);
        }
    }
    let n = if half.is_some() { 2 } else { 4 };
    if half.is_some() {
        pts[2 * n + 1] = bottom_mid;
    }
    // Pieces of no length (a flank of no depth, a corner of 0) are left out.
    let mut keep = |s: Seg| if s.a == s.b { Ok(()) } else { push(segs, s) };
    for i in 0..n {
        keep(line(pts[2 * i], pts[2 * i + 1]))?;
        if let Some(c) = pieces[i] {
            keep(c)?;
        }
    }
    keep(line(pts[2 * n], pts[2 * n + 1]))?;
    Ok((from, segs.len() as u16))
}

/// The corner at `b` between the lines `a`→`b` and `b`→`c`: where it starts on the
/// first, ends on the second, and its piece (arc or chamfer line).
fn corner(a: V2, b: V2, c: V2, spec: CornerSpec) -> Result<(V2, V2, Option<Seg>), CycleAlarm> {
    let (t1, t2) = (b.minus(a).unit(), c.minus(b).unit());
    let turn = libm::atan2(t1.cross(t2), t1.dot(t2));
    let v = spec.value * 1e6;
    if v == 0.0 || libm::fabs(turn) < 1e-9 {
        return Ok((b, b, None));
    }
    let half = libm::fabs(turn) / 2.0;
    let leg = if v > 0.0 {
        v * libm::tan(half)
    } else if spec.chr {
        -v
    } else {
        -v / (2.0 * sin_cos(half).1)
    };
    if leg > b.minus(a).len() + 1.0 || leg > c.minus(b).len() + 1.0 {
        return Err(CycleAlarm::GrooveFormWrong);
    }
    let (s, e) = (b.minus(t1.scale(leg)), b.plus(t2.scale(leg)));
    let piece = if v > 0.0 {
        // The centre: a radius off the first line towards the turn.
        let n = if turn > 0.0 { t1.left() } else { t1.left().scale(-1.0) };
        let center = s.plus(n.scale(v));
        Seg { kind: SegKind::Arc { center: pt(center), cw: turn < 0.0 }, a: pt(s), b: pt(e) }
    } else {
        line(s, e)
    };
    Ok((s, e, Some(piece)))
}

fn pt(v: V2) -> Pt {
    let (z, x) = v.round();
    Pt::new(x, z)
}

fn line(a: V2, b: V2) -> Seg {
    Seg { kind: SegKind::Line, a: pt(a), b: pt(b) }
}

fn reversed(s: Seg) -> Seg {
    let kind = match s.kind {
        SegKind::Arc { center, cw } => SegKind::Arc { center, cw: !cw },
        k => k,
    };
    Seg { kind, a: s.b, b: s.a }
}

fn push(segs: &mut heapless::Vec<Seg, SEGS>, s: Seg) -> Result<(), AlarmKind> {
    segs.push(s).map_err(|_| AlarmKind::ProfileTooLong)
}

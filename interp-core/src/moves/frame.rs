//! A machining centre's programmable transformations (seed 004, FANUC 0i-M): G16
//! polar coordinates, G51.1 mirror image, G51 scaling and G68 rotation, applied
//! to a programmed point in that order (@5212, @5293: scaling before rotation,
//! rotation before cutter and tool length compensation, which follow in the
//! contour layer and the work frame). Their data is [`crate::modal::mill::Frame`].
//!
//! A block's move is turned into absolute work coordinates here before the move
//! helpers see it ([`adapt`]), so soft limits, stroke check 2, chamfers and
//! cutter compensation all work on the transformed path. Incremental words add
//! to the programmed position ([`Frame::prog`]), as FANUC's G91 does under
//! scaling and rotation. Nothing here runs while no transformation is in force:
//! the checker sends only blocks of a machining centre with one in force (or
//! switching one) this way.

use crate::alarm::AlarmKind;
use crate::axis::{Axis, Pos};
use crate::canon::Plane;
use crate::codes::GCode;
use crate::command::{AxisWord, Command, CycleArgs};
use crate::modal::State;
use crate::modal::mill::{FRAME_AXES, Frame, narrow, narrow3, on, turn, xyz};

/// µdeg per radian.
const UDEG_PER_RAD: f64 = 180e6 / core::f64::consts::PI;

impl Frame {
    /// A programmed point (X, Y, Z) in work coordinates: mirror, scaling, rotation.
    pub fn forward(&self, p: [i64; 3]) -> [i64; 3] {
        let mut v = p.map(|c| c as f64);
        self.forward_f(&mut v, true);
        v.map(crate::geom::round_i64)
    }

    /// A programmed vector (I/J/K, a K-repeat step) in work coordinates: the
    /// linear part of [`Frame::forward`].
    pub fn vector(&self, d: [i64; 3]) -> [i64; 3] {
        let mut v = d.map(|c| c as f64);
        self.forward_f(&mut v, false);
        v.map(crate::geom::round_i64)
    }

    fn forward_f(&self, v: &mut [f64; 3], point: bool) {
        let origin = |c: i32| if point { f64::from(c) } else { 0.0 };
        if self.active & on::MIRROR != 0 {
            for (i, (v, at)) in v.iter_mut().zip(self.mirror_at).enumerate() {
                if self.mirror & (1 << i) != 0 {
                    *v = 2.0 * origin(at) - *v;
                }
            }
        }
        if self.active & on::SCALE != 0 {
            for ((v, at), k) in v.iter_mut().zip(self.scale_at).zip(self.scale) {
                let c = origin(at);
                *v = c + (*v - c) * f64::from(k) / 1e3;
            }
        }
        if self.active & on::ROTATE != 0 {
            let (a, b) = plane_index(self.rot_plane);
            let (ca, cb) = (origin(self.rot_at[0]), origin(self.rot_at[1]));
            let (s, c) = libm::sincos(f64::from(self.rot_udeg) / UDEG_PER_RAD);
            let (x, y) = (v[a] - ca, v[b] - cb);
            v[a] = ca + x * c - y * s;
            v[b] = cb + x * s + y * c;
        }
    }

    /// The programmed point of work point `w`: the inverse of [`Frame::forward`].
    pub fn inverse(&self, w: [i64; 3]) -> [i64; 3] {
        let mut v = w.map(|c| c as f64);
        if self.active & on::ROTATE != 0 {
            let (a, b) = plane_index(self.rot_plane);
            let (ca, cb) = (f64::from(self.rot_at[0]), f64::from(self.rot_at[1]));
            let (s, c) = libm::sincos(-f64::from(self.rot_udeg) / UDEG_PER_RAD);
            let (x, y) = (v[a] - ca, v[b] - cb);
            v[a] = ca + x * c - y * s;
            v[b] = cb + x * s + y * c;
        }
        if self.active & on::SCALE != 0 {
            for ((v, at), k) in v.iter_mut().zip(self.scale_at).zip(self.scale) {
                let c = f64::from(at);
                *v = c + (*v - c) * 1e3 / f64::from(k);
            }
        }
        if self.active & on::MIRROR != 0 {
            for (i, (v, at)) in v.iter_mut().zip(self.mirror_at).enumerate() {
                if self.mirror & (1 << i) != 0 {
                    *v = 2.0 * f64::from(at) - *v;
                }
            }
        }
        v.map(crate::geom::round_i64)
    }

    /// Whether mirror, scaling or rotation (not only G16) is in force.
    pub fn moves_points(&self) -> bool {
        self.active & (on::MIRROR | on::SCALE | on::ROTATE) != 0
    }

    /// The scale of an arc radius R in `plane`: FANUC takes the larger factor of
    /// the plane's two axes when they differ.
    fn radius_scale(&self, plane: Plane) -> f64 {
        if self.active & on::SCALE == 0 {
            return 1.0;
        }
        let (a, b) = plane_index(plane);
        f64::from(self.scale[a].unsigned_abs().max(self.scale[b].unsigned_abs())) / 1e3
    }
}

/// Indices (0–2 of X, Y, Z) of the plane's two axes.
fn plane_index(p: Plane) -> (usize, usize) {
    let (a, b) = p.axes();
    (a.index(), b.index())
}

/// The programmed position while a transformation is in force.
fn prog(st: &State) -> [i64; 3] {
    st.mill.frame.prog()
}

/// G15/G16, G50/G51, G50.1/G51.1 and G68/G69 of the block put in force (after the
/// block's modal codes: the plane and G90/G91 it gives count). FANUC's order:
/// G51.1 before G51 before G68, cancelled the other way round; none of them while
/// cutter compensation is in force.
pub fn switch(cmd: &Command, st: &mut State, cfg: &crate::config::MachineConfig) -> Result<(), AlarmKind> {
    if cmd.g.frame.is_none() && cmd.g.polar_coord.is_none() {
        return Ok(());
    }
    if st.contour.comp.side.is_some() || st.modal.nose_comp != GCode::NoseCompOff {
        return Err(AlarmKind::FrameInCutterComp);
    }
    let was = st.mill.frame.active;
    if was == 0 {
        // From here on G91 adds to the programmed position: where the tool is.
        let here = xyz(&st.work_pos(cfg));
        st.mill.frame.set_prog(here)?;
    }
    let f = &mut st.mill.frame;
    match cmd.g.polar_coord {
        Some(true) if f.active & on::POLAR == 0 => {
            f.active |= on::POLAR;
            // Radius and angle of where the tool is, for words left out.
            let (a, b) = plane_index(st.modal.plane);
            let (x, y) = (f64::from(f.prog[a]), f64::from(f.prog[b]));
            f.polar_r = narrow(crate::geom::round_i64(libm::hypot(x, y)))?;
            f.polar_udeg = turn(crate::geom::round_i64(libm::atan2(y, x) * UDEG_PER_RAD));
        }
        Some(false) => f.active &= !on::POLAR,
        _ => {}
    }
    let later = |bits: u8| f.active & bits != 0;
    match cmd.g.frame {
        Some(GCode::MirrorOn) => {
            if later(on::SCALE | on::ROTATE) {
                return Err(AlarmKind::FrameOrder);
            }
            // G51.1 names the axes it mirrors: without X, Y or Z it would mirror
            // nothing where the programmer expects a mirror.
            if FRAME_AXES.iter().all(|a| cmd.axes[a.index()].is_none()) {
                return Err(AlarmKind::MissingWord { letter: b'X', context: "G51.1" });
            }
            for (i, a) in FRAME_AXES.into_iter().enumerate() {
                if let Some(w) = cmd.axes[a.index()] {
                    f.mirror |= 1 << i;
                    f.mirror_at[i] = narrow(w.value)?;
                }
            }
            if f.mirror != 0 {
                f.active |= on::MIRROR;
            }
        }
        Some(GCode::MirrorOff) => {
            if later(on::SCALE | on::ROTATE) {
                return Err(AlarmKind::FrameOrder);
            }
            let all = !cmd.has_axes();
            for (i, a) in FRAME_AXES.into_iter().enumerate() {
                if all || cmd.axes[a.index()].is_some() {
                    f.mirror &= !(1 << i);
                }
            }
            if f.mirror == 0 {
                f.active &= !on::MIRROR;
            }
        }
        Some(GCode::ScalingOn) => {
            if later(on::ROTATE) {
                return Err(AlarmKind::FrameOrder);
            }
            let CycleArgs::Scale { p, ijk } = cmd.cycle else { return Ok(()) };
            // The centre: the X/Y/Z given, the programmed position for the others
            // (FANUC), mirrored as the points will be.
            let mut center = f.prog();
            for (i, a) in FRAME_AXES.into_iter().enumerate() {
                if let Some(w) = cmd.axes[a.index()] {
                    center[i] = w.value;
                }
            }
            let mirror_only = Frame { active: f.active & on::MIRROR, ..*f };
            f.scale_at = narrow3(mirror_only.forward(center))?;
            f.scale = match p {
                Some(k) => [k; 3],
                None => ijk.map(|k| k.unwrap_or(1_000)),
            };
            f.active |= on::SCALE;
        }
        Some(GCode::ScalingOff) => {
            if later(on::ROTATE) {
                return Err(AlarmKind::FrameOrder);
            }
            f.active &= !on::SCALE;
        }
        Some(GCode::RotationOn) => {
            let CycleArgs::Rotate { r_udeg } = cmd.cycle else { return Ok(()) };
            let r = r_udeg.ok_or(AlarmKind::MissingWord { letter: b'R', context: "G68" })?;
            let plane = st.modal.plane;
            let incremental = cmd.g.incremental.unwrap_or(st.modal.incremental);
            let before = f.active & on::ROTATE != 0;
            // G91: the angle adds to the rotation in force (FANUC).
            f.rot_udeg = turn(if incremental && before { i64::from(f.rot_udeg) + r } else { r });
            let (a, b) = plane_index(plane);
            let mut center = f.prog();
            for (i, axis) in FRAME_AXES.into_iter().enumerate() {
                if let Some(w) = cmd.axes[axis.index()] {
                    center[i] = w.value;
                }
            }
            // The centre is mirrored and scaled like the points (FANUC: scaling
            // scales the rotation centre, not the angle).
            let before_rotation = Frame { active: f.active & (on::MIRROR | on::SCALE), ..*f };
            let c = before_rotation.forward(center);
            f.rot_at = [narrow(c[a])?, narrow(c[b])?];
            f.rot_plane = plane;
            f.active |= on::ROTATE;
        }
        Some(GCode::RotationOff) => f.active &= !on::ROTATE,
        _ => {}
    }
    Ok(())
}

/// The programmed target of a move block (G00–G03, a hole position) in
/// programmed coordinates: its words added to or replacing the programmed
/// position, G16's radius and angle turned into the plane's two coordinates.
/// Also updates G16's remembered radius and angle.
pub fn programmed_target(cmd: &Command, st: &mut State) -> Result<[i64; 3], AlarmKind> {
    let mut t = prog(st);
    let polar = st.mill.frame.active & on::POLAR != 0;
    let (pa, pb) = st.modal.plane.axes();
    for (i, a) in FRAME_AXES.into_iter().enumerate() {
        if polar && (a == pa || a == pb) {
            continue;
        }
        if let Some(w) = cmd.axes[a.index()] {
            t[i] = if w.incremental { t[i].checked_add(w.value).ok_or(AlarmKind::Overflow)? } else { w.value };
        }
    }
    if polar && (cmd.axes[pa.index()].is_some() || cmd.axes[pb.index()].is_some()) {
        let (ia, ib) = (pa.index(), pb.index());
        let f = &mut st.mill.frame;
        let (r_word, a_word) = (cmd.axes[ia], cmd.axes[ib]);
        // Seed 004 @4336: an absolute radius is measured from the local origin, an
        // incremental one from the current point.
        let p = f.prog();
        let (pole, r) = match r_word {
            Some(AxisWord { incremental: true, value }) => ((p[ia], p[ib]), value),
            Some(w) => ((0, 0), w.value),
            None => ((0, 0), i64::from(f.polar_r)),
        };
        let angle = match a_word {
            Some(AxisWord { incremental: true, value }) => {
                i64::from(f.polar_udeg).checked_add(value).ok_or(AlarmKind::Overflow)?
            }
            Some(w) => w.value,
            None => i64::from(f.polar_udeg),
        };
        let (s, c) = libm::sincos(angle as f64 / UDEG_PER_RAD);
        t[ia] = pole.0 + crate::geom::round_i64(r as f64 * c);
        t[ib] = pole.1 + crate::geom::round_i64(r as f64 * s);
        f.polar_r = narrow(r)?;
        f.polar_udeg = turn(angle);
    }
    Ok(t)
}

/// A move block (G00–G03) under a transformation: `adapted` gets the block's
/// target as absolute work coordinates of X, Y and Z, an arc's I/J/K as the
/// transformed vector and its R scaled; returns the programmed target, which
/// becomes the programmed position once the block has succeeded. G16 arcs take R
/// only (as G12.1's, alarm 4046); a G68 rotation admits arcs in its plane only.
pub fn adapt(cmd: &Command, st: &mut State, arc: bool, adapted: &mut Command) -> Result<[i64; 3], AlarmKind> {
    let plane = st.modal.plane;
    let f = st.mill.frame;
    if f.active & on::ROTATE != 0 && plane != f.rot_plane {
        return Err(AlarmKind::RotationPlaneChange);
    }
    if arc && f.active & on::POLAR != 0 && cmd.center.iter().any(Option::is_some) {
        return Err(AlarmKind::PolarArcNeedsR);
    }
    let target = programmed_target(cmd, st)?;
    let f = st.mill.frame;
    let work = f.forward(target);
    narrow3(target)?;
    // Every axis of the frame, given or not: a rotation moves an axis the block
    // leaves out, and one left out stays where the programmed position is.
    for (i, a) in FRAME_AXES.into_iter().enumerate() {
        adapted.axes[a.index()] = Some(AxisWord { value: work[i], incremental: false });
    }
    if arc {
        let mut v = [0i64; 3];
        let mut any = false;
        for (i, a) in FRAME_AXES.into_iter().enumerate() {
            if let Some(c) = cmd.center[a.index()] {
                v[i] = c;
                any = true;
            }
        }
        if any {
            let t = f.vector(v);
            let (pa, pb) = plane.axes();
            for a in [pa, pb] {
                adapted.center[a.index()] = Some(t[a.index()]);
            }
        }
        if let Some(r) = cmd.radius {
            adapted.radius = Some(crate::geom::round_i64(r as f64 * f.radius_scale(plane)));
        }
    }
    Ok(target)
}

/// The programmed position again from where the tool is (after a block the
/// transformations did not plan: G28, G53, a hole cycle …).
pub fn resync(st: &mut State, cfg: &crate::config::MachineConfig) {
    let w = xyz(&st.work_pos(cfg));
    let p = st.mill.frame.inverse(w);
    // Beyond ±2,147 mm only after a move the limits refused: keep the old one.
    let _ = st.mill.frame.set_prog(p);
}

/// The work position of programmed point `p` with the other axes from `base`.
pub fn work_point(f: &Frame, p: [i64; 3], base: Pos) -> Pos {
    let w = f.forward(p);
    let mut out = base;
    for (i, a) in FRAME_AXES.into_iter().enumerate() {
        out[a] = w[i];
    }
    out
}

/// Whether `axis` is one of the frame's axes (X, Y, Z).
pub fn is_frame_axis(axis: Axis) -> bool {
    FRAME_AXES.contains(&axis)
}

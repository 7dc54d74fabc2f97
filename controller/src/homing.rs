//! `$J=` jogging and `$H` homing: moves the controller makes itself, straight to
//! the motion port (the interpreter is not involved; it takes the position from
//! the motion core when they end).
//!
//! Homing: with `$22=0` (no home switches, the default) `$H` declares the axes to
//! be at reference position 1 (G28) where they stand. With `$22=1` it runs a
//! sequence per axis, X first: seek toward the home switch at `$25` (toward
//! plus unless `$23` has the axis's bit), brake when the switch input is seen,
//! redefine the axis so that the point where the switch tripped is the
//! reference position, then move to `$27` short of that point at `$24`.

use interp_core::axis::{Axis, Pos};
use interp_core::canon::{Action, Canon, Endpoint, Feed, FeedMode, Move, SpindleSpeed};
use interp_core::units::Units;

use crate::controller::{Controller, Mode};
use crate::lines::Handled;
use crate::port::MotionPort;

/// Where a homing sequence is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Homing {
    /// 0: X, 1: Z.
    axis: usize,
    phase: Phase,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Phase {
    /// Waiting for the motion core to be at rest.
    Start,
    /// Moving toward the switch.
    Seek,
    /// The switch tripped at this position; braking.
    Braking { trip: Pos },
    /// Moving off the switch.
    PullOff,
}

const AXES: [Axis; 2] = [Axis::X, Axis::Z];

/// A parsed jog line.
#[derive(Clone, Copy, Debug, Default)]
struct Jog {
    x: Option<f64>,
    z: Option<f64>,
    f: Option<f64>,
    incremental: bool,
    machine: bool,
    inch: bool,
}

fn parse_jog(text: &[u8]) -> Option<Jog> {
    let mut j = Jog::default();
    let mut i = 0;
    while i < text.len() {
        let c = text[i].to_ascii_uppercase();
        i += 1;
        if c == b' ' {
            continue;
        }
        let start = i;
        while i < text.len() && matches!(text[i], b'0'..=b'9' | b'.' | b'-' | b'+') {
            i += 1;
        }
        let v = crate::decimal::decimal(&text[start..i])?;
        match (c, v as i32) {
            (b'G', 20) => j.inch = true,
            (b'G', 21) => j.inch = false,
            (b'G', 90) => j.incremental = false,
            (b'G', 91) => j.incremental = true,
            (b'G', 53) => j.machine = true,
            (b'X', _) => j.x = Some(v),
            (b'Z', _) => j.z = Some(v),
            (b'F', _) if v > 0.0 => j.f = Some(v),
            _ => return None,
        }
    }
    Some(j)
}

/// A straight feed move to machine position `to` at `feed` nm/min.
pub(crate) fn feed_move(to: Pos, work: Pos, feed: i64, max_rpm: u32) -> Canon {
    let spindle = SpindleSpeed { rpm: None, css: None, max_rpm };
    let m = Move {
        to: Endpoint { machine: to, work },
        feed: Feed { mode: FeedMode::PerMin, value: feed },
        spindle,
        exact_stop: true,
        independent: false,
    };
    Canon { line: 0, action: Action::Linear(m) }
}

impl<const W: usize, const T: usize, const P: usize, const S: usize> Controller<W, T, P, S> {
    /// `$J=…`: a jog move (Idle or while jogging).
    pub(crate) fn jog_line<M: MotionPort + ?Sized>(&mut self, text: &[u8], port: &mut M) -> Handled {
        if self.alarm.is_some() {
            self.refuse(9, "Alarm: $X or reset first");
            return Handled::Done;
        }
        if port.status().state == motion_core::motion::State::Stopping {
            // Braking after a reset or unlock: the jog waits (in the buffer).
            return Handled::Wait;
        }
        if !matches!(self.mode(port), Mode::Idle | Mode::Jog) || self.check {
            self.refuse(8, "Jog only when idle");
            return Handled::Done;
        }
        let Some(j) = parse_jog(text).filter(|j| j.f.is_some() && (j.x.is_some() || j.z.is_some())) else {
            self.refuse(16, "Jog: G20/G21/G53/G90/G91 X Z and F only, F required");
            return Handled::Done;
        };
        let cfg = self.interp.config();
        let w2m = self.interp.state().work_to_machine(cfg);
        let base = if self.jog { self.jog_target } else { self.interp.state().pos };
        let inch = j.inch || (self.interp.state().modal.units == Units::Inch && !text.windows(3).any(|w| w == b"G21"));
        let scale = if inch { 25.4e6 } else { 1e6 };
        let mut to = base;
        for (axis, v) in [(Axis::X, j.x), (Axis::Z, j.z)] {
            let Some(v) = v else { continue };
            let radius = if axis == Axis::X && cfg.diameter_x { 0.5 } else { 1.0 };
            let nm = libm::round(v * scale * radius) as i64;
            to[axis] = if j.incremental {
                base[axis].saturating_add(nm)
            } else if j.machine {
                nm
            } else {
                nm.saturating_add(w2m[axis])
            };
            let a = cfg.axis(axis);
            if self.settings.soft_limits && !(a.min..=a.max).contains(&to[axis]) {
                self.refuse(15, "Jog target beyond the soft limits");
                return Handled::Done;
            }
        }
        let feed = libm::round(j.f.unwrap_or(0.0) * scale) as i64;
        let c = feed_move(to, to - w2m, feed.max(1), cfg.spindle.max_rpm);
        if port.push(c).is_err() {
            return Handled::Wait;
        }
        self.jog = true;
        self.jog_target = to;
        self.ok();
        Handled::Done
    }

    /// `$H`.
    pub(crate) fn home<M: MotionPort + ?Sized>(&mut self, port: &mut M) -> Handled {
        if self.prev_inputs.estop {
            self.refuse(9, "E-stop is active");
            return Handled::Done;
        }
        if !port.status().idle || self.job != crate::controller::Job::None {
            self.refuse(8, "Homing only at rest");
            return Handled::Done;
        }
        if self.alarm.take().is_some() {
            // Clears the core's alarm; the sequence starts once it is at rest.
            port.reset();
        }
        if !self.settings.homing {
            let r = self.interp.config().reference[0];
            if !port.set_position(r) {
                self.refuse(8, "Homing only at rest");
                return Handled::Done;
            }
            self.interp.set_machine_position(r);
            self.homed = true;
            self.msg(format_args!("No home switches ($22=0): reference position set where the axes stand"));
            self.ok();
            return Handled::Done;
        }
        self.homing = Some(Homing { axis: 0, phase: Phase::Start });
        self.ok();
        Handled::Done
    }

    /// Starts the seek of axis `i` toward its switch.
    fn seek<M: MotionPort + ?Sized>(&mut self, i: usize, port: &mut M) {
        let a = AXES[i];
        let cfg = self.interp.config();
        let ax = cfg.axis(a);
        let travel = (ax.max - ax.min).saturating_mul(3) / 2;
        let from = port.status().position;
        let mut to = from;
        to[a] = from[a].saturating_add(travel * self.home_dir(i));
        let feed = i64::from(self.settings.homing_seek) * 1_000_000;
        let _ = port.push(feed_move(to, to, feed, cfg.spindle.max_rpm));
    }

    /// +1 or -1: the direction toward axis `i`'s home switch.
    fn home_dir(&self, i: usize) -> i64 {
        let bit = AXES[i].index();
        if self.settings.homing_dir_mask & (1 << bit) != 0 { -1 } else { 1 }
    }

    /// One poll of the homing sequence.
    pub(crate) fn homing_step<M: MotionPort + ?Sized>(&mut self, port: &mut M) {
        let Some(h) = self.homing else { return };
        let st = port.status();
        let switch = if h.axis == 0 { self.prev_inputs.home_x } else { self.prev_inputs.home_z };
        match h.phase {
            Phase::Start if st.idle => {
                self.homing = Some(Homing { phase: Phase::Seek, ..h });
                self.seek(h.axis, port);
            }
            Phase::Seek if switch => {
                port.reset();
                self.homing = Some(Homing { phase: Phase::Braking { trip: st.position }, ..h });
            }
            Phase::Seek if st.idle => {
                self.homing = None;
                self.msg(format_args!("Homing failed: no home switch found"));
                self.enter_alarm(9, port);
            }
            Phase::Braking { trip } if st.idle => {
                let a = AXES[h.axis];
                let mut pos = st.position;
                pos[a] = self.interp.config().reference[0][a] + (st.position[a] - trip[a]);
                port.set_position(pos);
                // Pull off from the switch point (the axis braked beyond it).
                let mut to = pos;
                to[a] = self.interp.config().reference[0][a]
                    - i64::from(self.settings.homing_pulloff_um) * 1_000 * self.home_dir(h.axis);
                let feed = i64::from(self.settings.homing_feed) * 1_000_000;
                let _ = port.push(feed_move(to, to, feed, self.interp.config().spindle.max_rpm));
                self.homing = Some(Homing { phase: Phase::PullOff, ..h });
            }
            Phase::PullOff if st.idle => {
                if h.axis + 1 < AXES.len() {
                    self.homing = Some(Homing { axis: h.axis + 1, phase: Phase::Start });
                } else {
                    self.homing = None;
                    self.homed = true;
                    self.interp.set_machine_position(st.position);
                    self.msg(format_args!("Homed"));
                }
            }
            _ => {}
        }
    }
}

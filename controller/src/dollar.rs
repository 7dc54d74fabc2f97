//! `$` commands (PROTOCOL.md): settings, offsets, modal state, unlock, homing,
//! check mode, jogging, startup blocks, programs in memory, variables.

use interp_core::axis::Axis;
use interp_core::canon::{FeedMode, Plane, SpindleDir};
use interp_core::codes::GCode;
use interp_core::config::{MachineKind, PARAMS, Param};
use interp_core::units::Units;

use crate::controller::{Controller, Handled, Job, Mode};
use crate::framing::LinkSeq;
use crate::homing::Homing;
use crate::jog::{JogFrom, jog_move};
use crate::outq::Class;
use crate::port::MotionPort;
use crate::report::{Value, Xyz};
use crate::settings::{self, NUMBERS, SettingError};

const HELP: &str =
    "[HLP:$$ $# $G $I $N $x=val $Nx=line $J=line $SLP $C $X $H $RST= $P $Pn=val $PL $PR=n $PD=n $V $LN=n ~ ! ? ctrl-x]";

/// The name of a machine kind on the link (`$I`, `$311`'s message).
fn kind_name(k: MachineKind) -> &'static str {
    match k {
        MachineKind::Lathe => "lathe",
        MachineKind::Mill => "mill",
    }
}

/// Whether a `$` command only reads (allowed in any state).
fn read_only(cmd: &[u8]) -> bool {
    matches!(cmd, b"" | b"$" | b"#" | b"G" | b"I" | b"N" | b"P" | b"PL" | b"V") || cmd.starts_with(b"LN=")
}

/// A decimal number.
fn number(s: &[u8]) -> Option<f64> {
    crate::decimal::decimal(s)
}

/// A whole number; ASCII blanks around it are ignored (the link is ASCII: no
/// Unicode whitespace table in the image).
fn whole(s: &[u8]) -> Option<u32> {
    core::str::from_utf8(s.trim_ascii()).ok()?.parse().ok()
}

impl<const W: usize, const T: usize, const P: usize, const S: usize> Controller<W, T, P, S> {
    /// A `$` line; `cmd` is what follows the `$`.
    pub(crate) fn dollar<M: MotionPort + ?Sized>(&mut self, cmd: &[u8], port: &mut M) -> Handled {
        let mut upper: heapless::Vec<u8, 128> = heapless::Vec::new();
        for &b in cmd {
            let _ = upper.push(if b.is_ascii_lowercase() && upper.len() < 4 { b.to_ascii_uppercase() } else { b });
        }
        let cmd = &upper[..];
        if !read_only(cmd) && !matches!(cmd, b"X" | b"SLP") && !cmd.starts_with(b"J=") {
            if self.alarm.is_some() && !cmd.starts_with(b"RST=") && cmd != b"H" {
                self.refuse(9, "Alarm: $X or reset first");
                return Handled::Done;
            }
            if matches!(self.job, Job::Memory(_)) || !matches!(self.mode(port), Mode::Idle | Mode::Check) {
                self.refuse(8, "Only when idle");
                return Handled::Done;
            }
        }
        match cmd {
            b"" => self.out.line(Class::Info, HELP),
            b"$" => self.list_settings(),
            b"#" => self.list_offsets(),
            b"G" => self.list_modal(),
            b"I" => {
                let kind = kind_name(self.interp.config().kind);
                self.out.fmt(Class::Info, format_args!("[VER:1.1h.{kind}:]"));
                self.out.fmt(Class::Info, format_args!("[OPT:,{},{}]", port.status().capacity, crate::controller::RX));
                let language = match self.interp.language() {
                    interp_core::config::Language::Fanuc => "FANUC",
                    interp_core::config::Language::Siemens => "SINUMERIK",
                };
                self.msg(format_args!("lathe controller {} ({language} {kind} language)", env!("CARGO_PKG_VERSION")));
            }
            b"N" => {
                for i in 0..2 {
                    let s = self.startup[i].clone();
                    self.out.fmt(Class::Info, format_args!("$N{i}={s}"));
                }
            }
            b"P" => self.list_params(),
            b"PL" => self.list_programs(),
            b"V" => self.list_variables(),
            b"X" => return self.unlock(port),
            b"C" => self.toggle_check(),
            b"TAPE" => {
                // Tape mode asked for by name (`lathe upload`, `lathe send --tape`):
                // whatever grbl traffic came before.
                self.start_tape();
                return Handled::Done;
            }
            b"H" => return self.home(port),
            b"SLP" => {
                port.reset();
                self.close_job();
                self.sleep = true;
                self.msg(format_args!("Sleeping"));
            }
            _ => return self.dollar_assign(cmd, port),
        }
        self.ok();
        Handled::Done
    }

    /// `$x=…` forms.
    fn dollar_assign<M: MotionPort + ?Sized>(&mut self, cmd: &[u8], port: &mut M) -> Handled {
        let (key, value) = match cmd.iter().position(|&b| b == b'=') {
            Some(i) => (&cmd[..i], &cmd[i + 1..]),
            None => {
                self.refuse(3, "Unknown $ command");
                return Handled::Done;
            }
        };
        let r: Result<(), (u8, &'static str)> = match key {
            b"J" => return self.jog_line(value, port),
            b"N0" | b"N1" => self.set_startup(usize::from(key[1] - b'0'), value),
            b"RST" => self.restore(value, port),
            b"PR" => self.run_program(value),
            b"PD" => self.delete_program(value),
            b"LN" => match whole(value) {
                Some(n) => {
                    self.link = LinkSeq { active: n > 0, expected: n.max(1) };
                    self.out.crc = n > 0;
                    // Says which number it took: line noise may have changed it.
                    self.out.fmt(Class::Info, format_args!("[LN:{n}]"));
                    Ok(())
                }
                None => Err((2, "Bad number")),
            },
            [b'P', digits @ ..] => self.set_param(digits, value),
            digits => self.set_setting(digits, value, port),
        };
        if r.is_ok() {
            match key {
                b"N0" | b"N1" => self.dirty.startup = true,
                b"PD" => self.dirty.programs = true,
                b"RST" => (self.dirty.settings, self.dirty.startup, self.dirty.programs) = (true, true, true),
                b"J" | b"PR" | b"LN" => {}
                _ => self.dirty.settings = true,
            }
        }
        match r {
            Ok(()) => self.ok(),
            Err((n, why)) => self.refuse(n, why),
        }
        Handled::Done
    }

    fn set_setting<M: MotionPort + ?Sized>(
        &mut self,
        key: &[u8],
        value: &[u8],
        port: &mut M,
    ) -> Result<(), (u8, &'static str)> {
        let n = whole(key).and_then(|n| u16::try_from(n).ok()).ok_or((3, "Unknown $ command"))?;
        let v = number(value).ok_or((2, "Bad number"))?;
        let mut cfg = self.interp.config().clone();
        let mut s = self.settings;
        settings::set(n, v, &mut cfg, &mut s).map_err(|e| match e {
            SettingError::Unknown => (3, "Unknown setting"),
            SettingError::BadValue(why) => (2, why),
        })?;
        if cfg != *self.interp.config() {
            port.reconfigure(&cfg).map_err(|_| (2, "The motion core cannot run with this value"))?;
            let kind_changed = cfg.kind != self.interp.config().kind;
            *self.interp.config_mut() = cfg;
            if kind_changed {
                // Another G-code table and power-on modes (G17 on a mill, G18 on
                // a lathe): the modal state starts again as after a reset.
                self.interp.reset();
                self.msg(format_args!("Machine kind: {}", kind_name(self.interp.config().kind)));
            }
        }
        self.settings = s;
        Ok(())
    }

    fn set_param(&mut self, digits: &[u8], value: &[u8]) -> Result<(), (u8, &'static str)> {
        let n = whole(digits).and_then(|n| u16::try_from(n).ok()).ok_or((3, "Unknown $ command"))?;
        let v = number(value).ok_or((2, "Bad number"))?;
        self.interp.config_mut().params.set_from_file(n, v).map_err(|e| match e {
            interp_core::config::ParamError::Unknown { .. } => (3, "Unknown parameter"),
            _ => (2, "Bad value for this parameter"),
        })
    }

    fn set_startup(&mut self, i: usize, value: &[u8]) -> Result<(), (u8, &'static str)> {
        let text = core::str::from_utf8(value).map_err(|_| (1, "Not text"))?;
        let mut s = heapless::String::new();
        s.push_str(text).map_err(|_| (11, "Startup block longer than 80 characters"))?;
        if let Some(slot) = self.startup.get_mut(i) {
            *slot = s;
        }
        Ok(())
    }

    /// `$RST=$` settings, `$RST=#` offsets, `$RST=*` everything.
    fn restore<M: MotionPort + ?Sized>(&mut self, what: &[u8], port: &mut M) -> Result<(), (u8, &'static str)> {
        // One machine description in this frame, which is on the stack while the
        // motion core is rebuilt; `restored` changes it in place.
        let mut cfg = self.interp.config().clone();
        self.restored(what, &mut cfg)?;
        port.reconfigure(&cfg).map_err(|_| (2, "The motion core cannot run with the defaults"))?;
        *self.interp.config_mut() = cfg;
        Ok(())
    }

    /// Turns `cfg` into the machine description `$RST=` `what` leads to (the
    /// settings, startup blocks and programs it clears are cleared here). Never
    /// inlined, and in place: the defaults it starts from stay out of `restore`'s
    /// frame, and no third description (3.5 KB with a mill's tables) is built.
    #[inline(never)]
    fn restored(&mut self, what: &[u8], cfg: &mut interp_core::MachineConfig) -> Result<(), (u8, &'static str)> {
        match what {
            b"$" => {
                // The settings go back to their defaults; the offsets and the
                // reference positions stay (G54.1's too).
                *cfg = interp_core::MachineConfig {
                    work_offsets: cfg.work_offsets,
                    extra_offsets: cfg.extra_offsets,
                    tools: cfg.tools,
                    reference: cfg.reference,
                    ..Default::default()
                };
                self.settings = settings::Settings::default();
            }
            b"#" => {
                // The offsets: G54-G59, the external offset, G54.1 P1-P48, the tools.
                cfg.work_offsets = Default::default();
                cfg.external_offset = interp_core::axis::Pos::ZERO;
                cfg.extra_offsets = Default::default();
                cfg.tools = Default::default();
            }
            b"*" => {
                *cfg = interp_core::MachineConfig::default();
                self.settings = settings::Settings::default();
                self.startup = Default::default();
                self.memory.clear();
            }
            _ => return Err((3, "$RST= takes $, # or *")),
        }
        Ok(())
    }

    /// `$PR=n`: runs O`n` from memory.
    fn run_program(&mut self, value: &[u8]) -> Result<(), (u8, &'static str)> {
        let n = whole(value).ok_or((2, "Bad number"))?;
        if n == 0 || !self.memory.numbers().any(|p| p == n) {
            return Err((20, "No such program in memory ($PL lists them)"));
        }
        self.interp.select_main(n);
        self.job = Job::Memory(n);
        Ok(())
    }

    /// `$PD=n`: deletes O`n`.
    fn delete_program(&mut self, value: &[u8]) -> Result<(), (u8, &'static str)> {
        let n = whole(value).ok_or((2, "Bad number"))?;
        if self.memory.remove(n) { Ok(()) } else { Err((20, "No such program in memory")) }
    }

    fn unlock<M: MotionPort + ?Sized>(&mut self, port: &mut M) -> Handled {
        if self.prev_inputs.estop {
            self.refuse(9, "E-stop is active");
            return Handled::Done;
        }
        if self.alarm.take().is_some() {
            port.reset();
            self.need_sync = true;
            self.msg(format_args!("Caution: Unlocked"));
        }
        self.sleep = false;
        self.ok();
        Handled::Done
    }

    fn toggle_check(&mut self) {
        self.check = !self.check;
        self.close_job();
        self.msg(format_args!("{}", if self.check { "Enabled" } else { "Disabled" }));
    }

    fn list_settings(&mut self) {
        for &n in NUMBERS {
            if let Some(v) = settings::get(n, self.interp.config(), &self.settings) {
                self.out.fmt(Class::Info, format_args!("${n}={}", Value(v)));
            }
        }
    }

    fn list_params(&mut self) {
        for d in PARAMS {
            let v = settings::param_value(d.id, self.interp.config());
            self.out.fmt(Class::Info, format_args!("$P{}={}", d.number, Value(v)));
        }
    }

    fn list_offsets(&mut self) {
        let cfg = self.interp.config().clone();
        for (i, o) in cfg.work_offsets.iter().enumerate() {
            self.out.fmt(Class::Info, format_args!("[G{}:{}]", 54 + i, Xyz::of(o, &cfg)));
        }
        self.out.fmt(Class::Info, format_args!("[G28:{}]", Xyz::of(&cfg.reference[0], &cfg)));
        self.out.fmt(Class::Info, format_args!("[G30:{}]", Xyz::of(&cfg.reference[1], &cfg)));
        let shift = self.interp.state().frames.shift;
        self.out.fmt(Class::Info, format_args!("[G92:{}]", Xyz::of(&shift, &cfg)));
        let tlo = self.interp.state().tool.offset[Axis::Z];
        self.out.fmt(Class::Info, format_args!("[TLO:{}]", Self::mm(tlo)));
    }

    fn list_modal(&mut self) {
        let st = *self.interp.state();
        let m = &st.modal;
        let motion = match m.motion {
            GCode::Rapid => "0",
            GCode::Linear => "1",
            GCode::ArcCw => "2",
            GCode::ArcCcw => "3",
            GCode::Thread => "32",
            GCode::VariableLeadThread => "34",
            GCode::TurningCycle => "90",
            GCode::ThreadCycle => "92",
            GCode::FacingCycle => "94",
            _ => "80",
        };
        let plane = match m.plane {
            Plane::Xy => 17,
            Plane::Zx => 18,
            Plane::Yz => 19,
        };
        let units = if m.units == Units::Inch { 20 } else { 21 };
        let css = if m.css { 96 } else { 97 };
        let feed_mode = if m.feed_mode == FeedMode::PerRev { 99 } else { 98 };
        let spindle = match st.spindle.dir {
            SpindleDir::Cw => 3,
            SpindleDir::Ccw => 4,
            SpindleDir::Stop => 5,
        };
        let coolant = if self.flood {
            8
        } else if self.mist {
            7
        } else {
            9
        };
        let f = Value(st.feed.get(m.feed_mode) as f64 / 1e6);
        let s = if m.css { st.spindle.css.unwrap_or(0) / 1000 } else { st.spindle.rpm };
        self.out.fmt(
            Class::Info,
            format_args!(
                "[GC:G{motion} G{} G{plane} G{units} G{css} G{feed_mode} M{spindle} M{coolant} T{:02}{:02} F{f} S{s}]",
                54 + u16::from(m.work_frame),
                st.tool.tool,
                st.tool.offset_number,
            ),
        );
    }

    fn list_programs(&mut self) {
        let mut numbers: heapless::Vec<u32, 64> = heapless::Vec::new();
        for n in self.memory.numbers() {
            let _ = numbers.push(n);
        }
        for n in numbers {
            let len = interp_core::ProgramStore::text(&self.memory, n).map_or(0, <[u8]>::len);
            self.out.fmt(Class::Info, format_args!("[PRG:O{n:04},{len}]"));
        }
    }

    fn list_variables(&mut self) {
        let mut vars: heapless::Vec<(u16, f64), 200> = heapless::Vec::new();
        for (n, v) in self.interp.variables().defined() {
            if interp_core::lang::fanuc::macros::Variables::is_common(n) {
                let _ = vars.push((n, v));
            }
        }
        for (n, v) in vars {
            self.out.fmt(Class::Info, format_args!("[VAR:#{n}={}]", Value(v)));
        }
    }

    /// A parameter by number, for tests and tools.
    pub fn param(&self, n: u16) -> Option<f64> {
        Param::by_number(n).map(|p| settings::param_value(p, self.interp.config()))
    }
}

// ----- `$J=` and `$H`: moves the controller makes itself (the interpreter takes
// the position from the motion core when they end) -----

impl<const W: usize, const T: usize, const P: usize, const S: usize> Controller<W, T, P, S> {
    /// `$J=…`: a jog move (Idle or while jogging).
    fn jog_line<M: MotionPort + ?Sized>(&mut self, text: &[u8], port: &mut M) -> Handled {
        // The operator is at the machine (`$306`).
        self.attendance.action(self.now);
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
        let cfg = self.interp.config();
        let st = self.interp.state();
        let from = JogFrom {
            base: if self.jog { self.jog_target } else { st.pos },
            work_to_machine: st.work_to_machine(cfg),
            inch_mode: st.modal.units == Units::Inch,
            soft_limits: self.settings.soft_limits,
        };
        let (c, to) = match jog_move(text, &from, cfg) {
            Ok(m) => m,
            Err((n, why)) => {
                self.refuse(n, why);
                return Handled::Done;
            }
        };
        if port.push(c).is_err() {
            return Handled::Wait;
        }
        self.jog = true;
        self.jog_target = to;
        self.ok();
        Handled::Done
    }

    /// `$H`: with `$22=0` (no home switches, the default) the axes are declared to
    /// be at reference position 1 (G28) where they stand; with `$22=1` the homing
    /// sequence runs ([`Homing`]).
    fn home<M: MotionPort + ?Sized>(&mut self, port: &mut M) -> Handled {
        if self.prev_inputs.estop {
            self.refuse(9, "E-stop is active");
            return Handled::Done;
        }
        if !port.status().idle || self.job != Job::None {
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
        self.homing = Some(Homing::new());
        self.ok();
        Handled::Done
    }
}

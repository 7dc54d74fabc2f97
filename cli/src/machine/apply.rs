//! A machine file laid over a [`MachineConfig`]: each given field replaces the
//! built-in value, converted to internal units (nm, X as a radius, µdeg).

use std::collections::BTreeMap;

use interp_core::config::{
    AxisConfig, GCodeSystem, Language, MAX_OFFSETS, MAX_USER_M, MTiming, MachineKind, MillPage, MotionConfig, Param,
    ParamError, Parameters, ToolChanger, UserMCode,
};
use interp_core::units::IncrementSystem;
use interp_core::{Axis, MachineConfig, Pos};

use super::file::{
    AxisFile, GCodeSystemName, IncrementName, InputName, KindName, LanguageName, MachineFile, MotionFile, Offset,
    ParamKey, Point, Spindle, TimingName, ToolChangerName, UserM, WorkOffsets,
};

/// Largest magnitude of an internal value from a file: 10⁹ mm, far beyond any machine.
const MAX_INTERNAL: f64 = 1e15;
/// Internal units per file unit of rates and accelerations (mm → nm, deg → µdeg).
const RATE_SCALE: f64 = 1e6;

/// Internal units per file unit of positions of axis `a` on `cfg`: X diameter mm
/// → radius nm on a lathe with diameter programming, mm → nm otherwise.
pub(super) fn position_scale(a: Axis, cfg: &MachineConfig) -> f64 {
    if a == Axis::X && cfg.diameter_x { 5e5 } else { 1e6 }
}

/// The file's name of axis `a` (`x`, `y`, `z`, `c`).
pub(super) fn axis_name(a: Axis) -> char {
    char::from(a.letter()).to_ascii_lowercase()
}

/// Applies every field of `file` to `cfg`; the error names the field.
pub(super) fn apply(file: &MachineFile, cfg: &mut MachineConfig) -> Result<(), String> {
    apply_modes(file, cfg);
    if let Some(axes) = &file.axes {
        for (a, f) in [(Axis::X, &axes.x), (Axis::Y, &axes.y), (Axis::Z, &axes.z), (Axis::C, &axes.c)] {
            if let Some(f) = f {
                let scale = position_scale(a, cfg);
                apply_axis(a, f, scale, &mut cfg.axes[a.index()])?;
            }
        }
    }
    if let Some(r) = &file.reference {
        cfg.reference = references(r, cfg)?;
    }
    if let Some(w) = &file.work_offsets {
        apply_work_offsets(w, cfg)?;
    }
    if let Some(rows) = &file.offsets {
        apply_offsets(rows, cfg)?;
    }
    if let Some(s) = &file.spindle {
        apply_spindle(s, cfg);
    }
    if let Some(m) = &file.user_m_codes {
        apply_user_m_codes(m, cfg)?;
    }
    if let Some(p) = &file.parameters {
        apply_parameters(p, &mut cfg.params)?;
    }
    if let Some(m) = &file.motion {
        apply_motion(m, &mut cfg.motion)?;
    }
    apply_input(file, &mut cfg.params)?;
    if let Some(t) = file.tool_change_timeout
        && !cfg.tool_change_timeout.set(t)
    {
        return Err(format!("tool_change_timeout = {t} is out of range (1 to 3600 s)"));
    }
    cfg.validate()
        .and_then(|()| motion_core::planner::machine::check_config(cfg))
        .and_then(|()| interp_core::codes::check_user_m_codes(cfg))
        .map_err(|e| e.to_string())
}

/// Kind, language, G-code system, increments, diameter programming, rapid mode, tool count.
fn apply_modes(file: &MachineFile, cfg: &mut MachineConfig) {
    if let Some(k) = file.kind {
        cfg.kind = match k {
            KindName::Lathe => MachineKind::Lathe,
            KindName::Mill => MachineKind::Mill,
        };
    }
    if let Some(l) = file.language {
        cfg.language = match l {
            LanguageName::Fanuc => Language::Fanuc,
            LanguageName::Siemens => Language::Siemens,
        };
    }
    if let Some(s) = file.gcode_system {
        cfg.gcode_system = match s {
            GCodeSystemName::A => GCodeSystem::A,
            GCodeSystemName::B => GCodeSystem::B,
            GCodeSystemName::C => GCodeSystem::C,
        };
    }
    if let Some(i) = file.increment_system {
        cfg.increments = match i {
            IncrementName::IsB => IncrementSystem::IsB,
            IncrementName::IsC => IncrementSystem::IsC,
        };
    }
    if let Some(d) = file.diameter_programming {
        cfg.diameter_x = d;
    }
    if let Some(r) = file.rapid_independent {
        cfg.rapid_independent = r;
    }
    if let Some(t) = file.tool_count {
        cfg.tool_count = t;
    }
    if let Some(i) = file.jump_input {
        cfg.jump_input = i;
    }
    if let Some(t) = file.tool_changer {
        cfg.tool_changer = match t {
            ToolChangerName::Manual => ToolChanger::Manual,
            ToolChangerName::Automatic => ToolChanger::Automatic,
        };
    }
}

/// `input` sets parameter 3401; giving both would leave one of them ignored.
fn apply_input(file: &MachineFile, params: &mut Parameters) -> Result<(), String> {
    let Some(input) = file.input else { return Ok(()) };
    let number = Param::CalculatorInput.def().number;
    if file.parameters.as_ref().is_some_and(|p| p.contains_key(&ParamKey(number.to_string()))) {
        return Err(format!("`input` and parameter {number} set the same thing; give one of them"));
    }
    params.set(Param::CalculatorInput, i64::from(input == InputName::Calculator));
    Ok(())
}

/// A file value times `scale`, rounded; an error naming `field` if it is not a sensible number.
fn internal(v: f64, scale: f64, field: &str) -> Result<i64, String> {
    let r = (v * scale).round();
    if r.is_finite() && r.abs() <= MAX_INTERNAL {
        Ok(r as i64)
    } else {
        Err(format!("{field} = {v:?} is out of range"))
    }
}

/// Sets `target` from an optional file value.
fn set(target: &mut i64, v: Option<f64>, scale: f64, field: &str) -> Result<(), String> {
    if let Some(v) = v {
        *target = internal(v, scale, field)?;
    }
    Ok(())
}

/// One axis table: the axis exists, the given values replace the built-in ones.
fn apply_axis(a: Axis, f: &AxisFile, scale: f64, ax: &mut AxisConfig) -> Result<(), String> {
    let field = |k: &str| format!("axes.{}.{k}", axis_name(a));
    ax.present = true;
    set(&mut ax.min, f.min, scale, &field("min"))?;
    set(&mut ax.max, f.max, scale, &field("max"))?;
    set(&mut ax.rapid_per_min, f.rapid, RATE_SCALE, &field("rapid"))?;
    set(&mut ax.max_feed_per_min, f.max_feed, RATE_SCALE, &field("max_feed"))?;
    set(&mut ax.accel_per_s2, f.accel, RATE_SCALE, &field("accel"))?;
    set(&mut ax.max_jump_per_min, f.max_jump, RATE_SCALE, &field("max_jump"))?;
    let d = &mut ax.drive;
    d.steps = f.steps.unwrap_or(d.steps);
    set(&mut d.per_nm, f.steps_travel, RATE_SCALE, &field("steps_travel"))?;
    set_u32(&mut d.pulse_ns, f.pulse_us, 1e3, &field("pulse_us"))?;
    set_u32(&mut d.dir_setup_ns, f.dir_setup_us, 1e3, &field("dir_setup_us"))?;
    d.max_step_hz = f.max_step_rate.unwrap_or(d.max_step_hz);
    Ok(())
}

/// Sets a `u32` target from an optional file value times `scale`.
fn set_u32(target: &mut u32, v: Option<f64>, scale: f64, field: &str) -> Result<(), String> {
    if let Some(v) = v {
        let i = internal(v, scale, field)?;
        *target = u32::try_from(i).map_err(|_| format!("{field} = {v:?} is out of range"))?;
    }
    Ok(())
}

/// The `[motion]` table.
fn apply_motion(f: &MotionFile, m: &mut MotionConfig) -> Result<(), String> {
    if let Some(p) = f.period_us {
        m.tick_ns = p.checked_mul(1_000).ok_or_else(|| format!("motion.period_us = {p} is out of range"))?;
    }
    set(&mut m.junction_deviation, f.junction_deviation, 1e6, "motion.junction_deviation")?;
    set(&mut m.chord_tolerance, f.chord_tolerance, 1e6, "motion.chord_tolerance")?;
    m.speed_window_ticks = f.speed_window.unwrap_or(m.speed_window_ticks);
    m.at_speed_pct = f.at_speed.unwrap_or(m.at_speed_pct);
    set_u32(&mut m.at_speed_timeout_ms, f.at_speed_timeout, 1e3, "motion.at_speed_timeout")?;
    m.thread_margin_pct = f.thread_margin.unwrap_or(m.thread_margin_pct);
    Ok(())
}

/// `base` with the coordinates given in `p` replaced.
fn point(base: Pos, p: &Point, cfg: &MachineConfig, field: &str) -> Result<Pos, String> {
    let mut out = base;
    for (a, v) in [(Axis::X, p.x), (Axis::Y, p.y), (Axis::Z, p.z), (Axis::C, p.c)] {
        set(&mut out[a], v, position_scale(a, cfg), &format!("{field}.{}", axis_name(a)))?;
    }
    Ok(out)
}

/// One to four reference positions; the ones not given equal the first.
fn references(points: &[Point], cfg: &MachineConfig) -> Result<[Pos; 4], String> {
    let base = &cfg.reference;
    if points.is_empty() || points.len() > base.len() {
        return Err(format!("reference: give 1 to 4 positions, not {}", points.len()));
    }
    let mut out = *base;
    for (i, p) in points.iter().enumerate() {
        out[i] = point(base[i], p, cfg, &format!("reference[{}]", i + 1))?;
    }
    for i in points.len()..out.len() {
        out[i] = out[0];
    }
    Ok(out)
}

fn apply_work_offsets(w: &WorkOffsets, cfg: &mut MachineConfig) -> Result<(), String> {
    let frames = [&w.g54, &w.g55, &w.g56, &w.g57, &w.g58, &w.g59];
    for (i, p) in frames.into_iter().enumerate() {
        if let Some(p) = p {
            cfg.work_offsets[i] = point(cfg.work_offsets[i], p, cfg, &format!("work_offsets.g{}", 54 + i))?;
        }
    }
    if let Some(p) = &w.external {
        cfg.external_offset = point(cfg.external_offset, p, cfg, "work_offsets.external")?;
    }
    if let Some(rows) = &w.g54_1 {
        if cfg.kind != MachineKind::Mill {
            return Err("work_offsets.g54_1: G54.1 is a mill's (kind = \"mill\")".into());
        }
        let mut seen = Vec::new();
        for r in rows {
            let field = |k: &str| format!("work_offsets.g54_1 p = {}: {k}", r.p);
            if seen.contains(&r.p) {
                return Err(field("given twice"));
            }
            seen.push(r.p);
            let mut pos = cfg.extra_offsets.get(r.p).ok_or_else(|| field("p must be 1 to 48"))?;
            let xyz = Point { x: r.x, y: r.y, z: r.z, c: None };
            pos = point(pos, &xyz, cfg, field("").trim_end_matches(": "))?;
            if !cfg.extra_offsets.set(r.p, pos) {
                return Err(field("coordinates must be within +-2147 mm"));
            }
        }
    }
    Ok(())
}

/// Tool offset rows, each number once: a lathe's X/Z/nose radius/tip, a mill's
/// length and radius (H and D pages).
fn apply_offsets(rows: &[Offset], cfg: &mut MachineConfig) -> Result<(), String> {
    let mut seen = Vec::new();
    let mill = cfg.kind == MachineKind::Mill;
    let x_scale = position_scale(Axis::X, cfg);
    for r in rows {
        let field = |k: &str| format!("offsets number {}: {k}", r.number);
        if seen.contains(&r.number) {
            return Err(field("given twice"));
        }
        seen.push(r.number);
        let row = cfg.tools.get_mut(r.number).ok_or_else(|| field(&format!("must be 1 to {MAX_OFFSETS}")))?;
        if mill {
            if r.x.is_some() || r.z.is_some() || r.x_wear.is_some() || r.z_wear.is_some() || r.tip.is_some() {
                return Err(field("a mill's row has length, length_wear, radius and radius_wear"));
            }
            for (page, v, name) in [
                (MillPage::Length, r.length, "length"),
                (MillPage::LengthWear, r.length_wear, "length_wear"),
                (MillPage::Radius, r.radius, "radius"),
                (MillPage::RadiusWear, r.radius_wear, "radius_wear"),
            ] {
                if let Some(v) = v {
                    row.set_mill(page, internal(v, 1e6, &field(name))?);
                }
            }
            continue;
        }
        if r.length.is_some() || r.length_wear.is_some() || r.radius_wear.is_some() {
            return Err(field("length, length_wear and radius_wear are a mill's (kind = \"mill\")"));
        }
        set(&mut row.x, r.x, x_scale, &field("x"))?;
        set(&mut row.z, r.z, 1e6, &field("z"))?;
        set(&mut row.x_wear, r.x_wear, x_scale, &field("x_wear"))?;
        set(&mut row.z_wear, r.z_wear, 1e6, &field("z_wear"))?;
        set(&mut row.radius, r.radius, 1e6, &field("radius"))?;
        match r.tip {
            Some(t) if t > 9 => return Err(field("tip must be 0 to 9")),
            Some(t) => row.tip = t,
            None => {}
        }
        match r.clearance {
            Some(c) if !(0.0..=90.0).contains(&c) => return Err(field("clearance must be 0 to 90 degrees")),
            Some(c) => row.clearance_udeg = (c * 1e6).round() as u32,
            None => {}
        }
    }
    Ok(())
}

fn apply_spindle(s: &Spindle, cfg: &mut MachineConfig) {
    let sp = &mut cfg.spindle;
    sp.max_rpm = s.max_rpm.unwrap_or(sp.max_rpm);
    sp.css_min_rpm = s.css_min_rpm.unwrap_or(sp.css_min_rpm);
    sp.gear_max_rpm = s.gear_max_rpm.unwrap_or(sp.gear_max_rpm);
    sp.encoder_cpr = s.encoder_counts.unwrap_or(sp.encoder_cpr);
    sp.accel_rpm_per_s = s.accel.unwrap_or(sp.accel_rpm_per_s);
}

/// User M codes (checked with the whole machine by `codes::check_user_m_codes`).
fn apply_user_m_codes(list: &[UserM], cfg: &mut MachineConfig) -> Result<(), String> {
    cfg.user_m_codes.clear();
    for u in list {
        let timing = match u.timing {
            TimingName::Before => MTiming::Before,
            TimingName::After => MTiming::After,
        };
        cfg.user_m_codes
            .push(UserMCode { m: u.m, timing })
            .map_err(|_| format!("user_m_codes: at most {MAX_USER_M} entries"))?;
    }
    Ok(())
}

/// `[parameters]` by number; all unknown numbers are named in one error.
fn apply_parameters(map: &BTreeMap<ParamKey, f64>, params: &mut Parameters) -> Result<(), String> {
    let mut unknown = Vec::new();
    for (key, &v) in map {
        match key.0.parse::<u16>().ok().filter(|n| Param::by_number(*n).is_some()) {
            Some(n) => params.set_from_file(n, v).map_err(|e| match e {
                ParamError::BadValue { problem, .. } => format!("parameters.{n} = {v} {problem}"),
                ParamError::Unknown { .. } => e.to_string(),
            })?,
            None => unknown.push(key.0.as_str()),
        }
    }
    if unknown.is_empty() {
        Ok(())
    } else {
        Err(format!("unknown parameter number(s) {} (docs/PARAMETERS.md lists them all)", unknown.join(", ")))
    }
}

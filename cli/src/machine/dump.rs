//! A [`MachineConfig`] as a machine file: the inverse of [`super::apply`], for
//! `lathe machine` (show the machine in force) and the round-trip tests.

use std::collections::BTreeMap;

use interp_core::config::{
    AxisConfig, EXTRA_FRAMES, GCodeSystem, Language, MTiming, MachineKind, MillPage, MotionConfig, PARAMS, Param,
    ParamUnit, ToolChanger, ToolOffset,
};
use interp_core::units::IncrementSystem;
use interp_core::{Axis, MachineConfig, Pos};

use super::apply::position_scale;
use super::file::{
    Axes, AxisFile, ExtraOffset, GCodeSystemName, IncrementName, InputName, KindName, LanguageName, MachineFile,
    MotionFile, Offset, ParamKey, Point, Spindle, TimingName, ToolChangerName, UserM, WorkOffsets,
};

/// Every setting of `cfg` as a machine file (offset rows that are all zero left out).
pub(super) fn file_of(cfg: &MachineConfig) -> MachineFile {
    MachineFile {
        kind: Some(match cfg.kind {
            MachineKind::Lathe => KindName::Lathe,
            MachineKind::Mill => KindName::Mill,
        }),
        language: Some(match cfg.language {
            Language::Fanuc => LanguageName::Fanuc,
            Language::Siemens => LanguageName::Siemens,
        }),
        gcode_system: Some(match cfg.gcode_system {
            GCodeSystem::A => GCodeSystemName::A,
            GCodeSystem::B => GCodeSystemName::B,
            GCodeSystem::C => GCodeSystemName::C,
        }),
        increment_system: Some(match cfg.increments {
            IncrementSystem::IsB => IncrementName::IsB,
            IncrementSystem::IsC => IncrementName::IsC,
        }),
        input: Some(if cfg.params.flag(Param::CalculatorInput) {
            InputName::Calculator
        } else {
            InputName::LeastIncrement
        }),
        diameter_programming: Some(cfg.diameter_x),
        rapid_independent: Some(cfg.rapid_independent),
        tool_count: Some(cfg.tool_count),
        tool_changer: (cfg.kind == MachineKind::Mill).then_some(match cfg.tool_changer {
            ToolChanger::Manual => ToolChangerName::Manual,
            ToolChanger::Automatic => ToolChangerName::Automatic,
        }),
        tool_change_timeout: (cfg.kind == MachineKind::Mill).then_some(cfg.tool_change_timeout.seconds()),
        reference: Some(cfg.reference.iter().map(|p| point(cfg, *p)).collect()),
        axes: Some(axes(cfg)),
        work_offsets: Some(work_offsets(cfg)),
        offsets: Some(offsets(cfg)),
        spindle: Some(Spindle {
            max_rpm: Some(cfg.spindle.max_rpm),
            css_min_rpm: Some(cfg.spindle.css_min_rpm),
            gear_max_rpm: Some(cfg.spindle.gear_max_rpm),
            encoder_counts: Some(cfg.spindle.encoder_cpr),
            accel: Some(cfg.spindle.accel_rpm_per_s),
        }),
        user_m_codes: Some(cfg.user_m_codes.iter().map(|u| UserM { m: u.m, timing: timing(u.timing) }).collect()),
        jump_input: Some(cfg.jump_input),
        parameters: Some(parameters(cfg)),
        motion: Some(motion(&cfg.motion)),
    }
}

fn motion(m: &MotionConfig) -> MotionFile {
    MotionFile {
        period_us: Some(m.tick_ns / 1_000),
        junction_deviation: Some(external(m.junction_deviation, 1e6)),
        chord_tolerance: Some(external(m.chord_tolerance, 1e6)),
        speed_window: Some(m.speed_window_ticks),
        at_speed: Some(m.at_speed_pct),
        at_speed_timeout: Some(f64::from(m.at_speed_timeout_ms) / 1e3),
        thread_margin: Some(m.thread_margin_pct),
    }
}

/// A file value from internal units.
fn external(v: i64, scale: f64) -> f64 {
    v as f64 / scale
}

/// A position with the machine's axes (Y and C only if present).
fn point(cfg: &MachineConfig, p: Pos) -> Point {
    let coord = |a: Axis| cfg.axis(a).present.then(|| external(p[a], position_scale(a, cfg)));
    Point { x: coord(Axis::X), y: coord(Axis::Y), z: coord(Axis::Z), c: coord(Axis::C) }
}

fn axes(cfg: &MachineConfig) -> Axes {
    let axis = |a: Axis| {
        let ax: &AxisConfig = cfg.axis(a);
        ax.present.then(|| AxisFile {
            min: Some(external(ax.min, position_scale(a, cfg))),
            max: Some(external(ax.max, position_scale(a, cfg))),
            rapid: Some(external(ax.rapid_per_min, 1e6)),
            max_feed: Some(external(ax.max_feed_per_min, 1e6)),
            accel: Some(external(ax.accel_per_s2, 1e6)),
            max_jump: Some(external(ax.max_jump_per_min, 1e6)),
            steps: Some(ax.drive.steps),
            steps_travel: Some(external(ax.drive.per_nm, 1e6)),
            pulse_us: Some(f64::from(ax.drive.pulse_ns) / 1e3),
            dir_setup_us: Some(f64::from(ax.drive.dir_setup_ns) / 1e3),
            max_step_rate: Some(ax.drive.max_step_hz),
        })
    };
    Axes { x: axis(Axis::X), y: axis(Axis::Y), z: axis(Axis::Z), c: axis(Axis::C) }
}

fn work_offsets(cfg: &MachineConfig) -> WorkOffsets {
    let w = |i: usize| Some(point(cfg, cfg.work_offsets[i]));
    WorkOffsets {
        g54: w(0),
        g55: w(1),
        g56: w(2),
        g57: w(3),
        g58: w(4),
        g59: w(5),
        external: Some(point(cfg, cfg.external_offset)),
        g54_1: (cfg.kind == MachineKind::Mill).then(|| {
            (1..=EXTRA_FRAMES as u8)
                .filter_map(|p| cfg.extra_offsets.get(p).filter(|o| *o != Pos::ZERO).map(|o| (p, o)))
                .map(|(p, o)| ExtraOffset {
                    p,
                    x: Some(external(o[Axis::X], 1e6)),
                    y: Some(external(o[Axis::Y], 1e6)),
                    z: Some(external(o[Axis::Z], 1e6)),
                })
                .collect()
        }),
    }
}

/// The offset rows that are not all zero: a lathe's X/Z rows, a mill's H/D rows.
fn offsets(cfg: &MachineConfig) -> Vec<Offset> {
    let mill = cfg.kind == MachineKind::Mill;
    (1..=interp_core::config::MAX_OFFSETS as u16)
        .filter_map(|n| cfg.tools.get(n).filter(|r| **r != ToolOffset::default()).map(|r| (n, r)))
        .map(|(number, r)| {
            if mill {
                let v = |page| Some(external(r.mill_value(page), 1e6));
                return Offset {
                    number,
                    length: v(MillPage::Length),
                    length_wear: v(MillPage::LengthWear),
                    radius: v(MillPage::Radius),
                    radius_wear: v(MillPage::RadiusWear),
                    ..Offset::default()
                };
            }
            Offset {
                number,
                x: Some(external(r.x, position_scale(Axis::X, cfg))),
                z: Some(external(r.z, 1e6)),
                x_wear: Some(external(r.x_wear, position_scale(Axis::X, cfg))),
                z_wear: Some(external(r.z_wear, 1e6)),
                radius: Some(external(r.radius, 1e6)),
                tip: Some(r.tip),
                clearance: (r.clearance_udeg != 0).then(|| external(i64::from(r.clearance_udeg), 1e6)),
                ..Offset::default()
            }
        })
        .collect()
}

fn timing(t: MTiming) -> TimingName {
    match t {
        MTiming::Before => TimingName::Before,
        MTiming::After => TimingName::After,
    }
}

/// Every parameter in file units, except 3401, which `input` carries.
fn parameters(cfg: &MachineConfig) -> BTreeMap<ParamKey, f64> {
    PARAMS
        .iter()
        .filter(|d| d.id != Param::CalculatorInput)
        .map(|d| {
            let v = cfg.params.get(d.id);
            let scale = if matches!(d.unit, ParamUnit::Mm | ParamUnit::MmPerMin) { 1e6 } else { 1.0 };
            (ParamKey(d.number.to_string()), external(v, scale))
        })
        .collect()
}

//! Spindle speed: S, G96/G97, G50 S clamp and gears (2.19), and the spindle
//! actions of M03/M04/M05.

use crate::alarm::AlarmKind;
use crate::axis::Axis;
use crate::canon::{Action, SpindleCommand, SpindleDir, SpindleSpeed, css_rpm};
use crate::codes::{GCode, MFunction};
use crate::command::Command;
use crate::config::MachineConfig;
use crate::modal::State;
use crate::stage::Staged;
use crate::units::{Units, div_round};

/// The speed the control commands with the tool at work X radius `x` (nm):
/// G97 S, or under G96 the surface speed over π·|X| (2.19), capped by the
/// spindle's maximum, the gear's maximum and (G96 only) the G50 S clamp.
pub fn spindle_speed(st: &State, cfg: &MachineConfig, x: i64) -> SpindleSpeed {
    let sp = &st.spindle;
    let gear_cap = match sp.gear {
        g @ 1..=4 => cfg.spindle.gear_max_rpm[usize::from(g - 1)],
        _ => 0,
    };
    let cap = if gear_cap > 0 { cfg.spindle.max_rpm.min(gear_cap) } else { cfg.spindle.max_rpm };
    if !st.modal.css {
        let rpm = (sp.dir != SpindleDir::Stop).then(|| sp.rpm.min(cap));
        return SpindleSpeed { rpm, css: None, max_rpm: cap };
    }
    let cap = sp.clamp.map_or(cap, |c| c.min(cap));
    let rpm = match sp.css {
        Some(v) => css_rpm(v, x).min(cap),
        None => cfg.spindle.css_min_rpm.min(cap),
    };
    SpindleSpeed { rpm: (sp.dir != SpindleDir::Stop).then_some(rpm), css: sp.css, max_rpm: cap }
}

/// S, G96/G97, G50 S, gears and M03/M04 before the block's motion.
#[inline]
pub(crate) fn before_motion(
    cmd: &Command,
    st: &mut State,
    cfg: &MachineConfig,
    out: &mut Staged<'_>,
) -> Result<(), AlarmKind> {
    if cmd.g.css.is_none() && cmd.speed.is_none() && cmd.m.is_empty() {
        // Nothing here can change the spindle (most motion blocks).
        return Ok(());
    }
    spindle_words(cmd, st, cfg, out)
}

/// [`before_motion`] for a block with G96/G97, S or M words.
#[inline(never)]
fn spindle_words(cmd: &Command, st: &mut State, cfg: &MachineConfig, out: &mut Staged<'_>) -> Result<(), AlarmKind> {
    let x = st.work_axis(cfg, Axis::X);
    let before = spindle_speed(st, cfg, x);
    if let Some(css) = cmd.g.css {
        if st.modal.css && !css && cmd.speed.is_none() {
            // 2.19 note 3: G97 without S keeps the last G96 speed.
            st.spindle.rpm = before.rpm.unwrap_or(0);
        }
        st.modal.css = css;
    }
    if let Some(s) = cmd.speed {
        if cmd.g.one_shot == Some(GCode::SetCoordinates) {
            st.spindle.clamp = Some(s);
        } else if st.modal.css {
            st.spindle.css = Some(surface_speed_mm_min(s, st.modal.units));
        } else {
            st.spindle.rpm = s;
        }
    }
    for &(m, _) in &cmd.m {
        if let 41..=44 = m {
            st.spindle.gear = (m - 40) as u8;
        }
    }
    let turn = cmd.m.iter().find_map(|&(_, f)| spindle_dir(f)).filter(|d| *d != SpindleDir::Stop);
    if let Some(d) = turn {
        st.spindle.dir = d;
    }
    let now = spindle_speed(st, cfg, x);
    if turn.is_some() || (st.spindle.dir != SpindleDir::Stop && now != before) {
        out.emit(Action::Spindle(SpindleCommand { dir: st.spindle.dir, rpm: now.rpm, css: now.css }))?;
    }
    Ok(())
}

/// M05 after the block's motion.
pub(crate) fn after_motion(cmd: &Command, st: &mut State, out: &mut Staged<'_>) -> Result<(), AlarmKind> {
    if cmd.m.iter().any(|&(_, f)| spindle_dir(f) == Some(SpindleDir::Stop)) {
        st.spindle.dir = SpindleDir::Stop;
        let css = if st.modal.css { st.spindle.css } else { None };
        out.emit(Action::Spindle(SpindleCommand { dir: SpindleDir::Stop, rpm: None, css }))?;
    }
    Ok(())
}

/// S of G96 as mm/min: m/min in metric, ft/min in inch.
fn surface_speed_mm_min(s: u32, units: Units) -> u32 {
    let mm = match units {
        Units::Metric => i64::from(s) * 1000,
        Units::Inch => div_round(i64::from(s) * 3048, 10),
    };
    u32::try_from(mm).unwrap_or(u32::MAX)
}

/// Direction a spindle M code commands, if it is one.
pub(crate) fn spindle_dir(f: MFunction) -> Option<SpindleDir> {
    match f {
        MFunction::SpindleCw => Some(SpindleDir::Cw),
        MFunction::SpindleCcw => Some(SpindleDir::Ccw),
        MFunction::SpindleStop => Some(SpindleDir::Stop),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn surface_speed_to_rpm_matches_figure_2_73() {
        // 300 m/min at X100, X50, X80 (diameters): 955, 1910, 1194 r/min.
        assert_eq!(css_rpm(300_000, 50_000_000), 955);
        assert_eq!(css_rpm(300_000, 25_000_000), 1910);
        assert_eq!(css_rpm(300_000, 40_000_000), 1194);
        assert_eq!(css_rpm(300_000, 0), u32::MAX);
        // Seed 003: 150 m/min at diameters 40, 60, 70: 1193, 795, 682.
        assert_eq!(css_rpm(150_000, 20_000_000), 1194); // 1193.7, the textbook truncates
        assert_eq!(css_rpm(150_000, 30_000_000), 796); // 795.8
        assert_eq!(css_rpm(150_000, 35_000_000), 682);
    }

    #[test]
    fn inch_surface_speed_is_feet_per_minute() {
        assert_eq!(surface_speed_mm_min(100, Units::Inch), 30_480);
        assert_eq!(surface_speed_mm_min(300, Units::Metric), 300_000);
    }
}

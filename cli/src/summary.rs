//! `lathe sim --format summary`: what a run did, in a few aligned lines: blocks,
//! moves, path lengths, extents, tools, stops, alarms and an estimated cycle time.

use std::fmt;

use interp_core::canon::Action;
use interp_core::{Alarm, MachineConfig};

use crate::motion::Motion;
use crate::path::{Bounds, Motion as PathMotion, Segment, segments};
use crate::program::Run;
use crate::timing;
use crate::units::{dia, fixed3, mm};

/// Counts, lengths and times of a run.
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    /// Program name as given.
    pub program: String,
    /// Blocks executed.
    pub blocks: usize,
    /// Moves of each kind.
    pub moves: MoveCounts,
    /// Cutting path length (linear, arc, thread, tap), mm.
    pub cutting_mm: f64,
    /// Rapid path length, mm.
    pub rapid_mm: f64,
    /// Box of the path in work coordinates: X diameter and Z, mm; `None` without motion.
    pub extents: Option<Extents>,
    /// Tool changes: turret station and offset number.
    pub tools: Vec<(u16, u16)>,
    /// Program stops (M00/M01) answered with cycle start.
    pub stops: usize,
    /// Alarms as reported (`PROGRAM:LINE: alarm CODE: message`).
    pub alarms: Vec<String>,
    /// How the program ended: `M30`, `M02`, or `None` if it did not reach its end.
    pub end: Option<&'static str>,
    /// Estimated cycle time.
    pub time: Times,
    /// What the simulated machine did (cycle time with acceleration, path deviation).
    pub motion: Option<Motion>,
}

/// Moves by kind.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MoveCounts {
    /// G00.
    pub rapid: usize,
    /// G01.
    pub linear: usize,
    /// G02/G03.
    pub arc: usize,
    /// Thread moves.
    pub thread: usize,
    /// Tapping moves.
    pub tap: usize,
}

/// A box of the path, mm, X as a diameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Extents {
    /// Least and greatest X diameter.
    pub x: (f64, f64),
    /// Least and greatest Z.
    pub z: (f64, f64),
}

/// Estimated time without acceleration, seconds.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Times {
    /// Rapids.
    pub rapid: f64,
    /// Cutting moves.
    pub cutting: f64,
    /// Dwells.
    pub dwell: f64,
}

impl Times {
    /// The whole cycle.
    pub fn total(&self) -> f64 {
        self.rapid + self.cutting + self.dwell
    }
}

impl Summary {
    /// The summary of `run` of `program` on machine `cfg`.
    pub fn new(program: &str, run: &Run, cfg: &MachineConfig) -> Self {
        let segs = segments(run.start, &run.actions);
        let mut s = Summary {
            program: program.to_owned(),
            blocks: run.blocks,
            moves: MoveCounts::default(),
            cutting_mm: 0.0,
            rapid_mm: 0.0,
            extents: Bounds::of(&segs).map(|b| Extents { x: (dia(b.x.0), dia(b.x.1)), z: (mm(b.z.0), mm(b.z.1)) }),
            tools: Vec::new(),
            stops: 0,
            alarms: run.alarms.iter().map(|a: &Alarm| run.alarm_line(program, a)).collect(),
            end: None,
            time: Times::default(),
            motion: None,
        };
        segs.iter().for_each(|seg| s.add_motion(seg, cfg));
        run.actions.iter().for_each(|c| s.add_other(&c.action));
        s
    }

    /// Adds the simulated machine's results.
    pub fn with_motion(mut self, m: Option<Motion>) -> Self {
        self.motion = m;
        self
    }

    /// Counts a move, its length and its time.
    fn add_motion(&mut self, seg: &Segment, cfg: &MachineConfig) {
        let len = seg.length(cfg) / 1e6;
        let t = timing::seconds(seg, cfg);
        let counter = match seg.motion {
            PathMotion::Rapid(_) => &mut self.moves.rapid,
            PathMotion::Linear(_) => &mut self.moves.linear,
            PathMotion::Arc(_) => &mut self.moves.arc,
            PathMotion::Thread(_) => &mut self.moves.thread,
            PathMotion::Tap(_) => &mut self.moves.tap,
        };
        *counter += 1;
        if let PathMotion::Rapid(_) = seg.motion {
            self.rapid_mm += len;
            self.time.rapid += t;
        } else {
            self.cutting_mm += len;
            self.time.cutting += t;
        }
    }

    /// Counts tool changes, stops, dwells and the end.
    fn add_other(&mut self, action: &Action) {
        match *action {
            Action::Tool { tool, offset } => self.tools.push((tool, offset)),
            Action::Stop { .. } => self.stops += 1,
            Action::Dwell { ms } => self.time.dwell += f64::from(ms) / 1e3,
            Action::End { rewind } => self.end = Some(if rewind { "M30" } else { "M02" }),
            _ => {}
        }
    }
}

/// Width of the label column.
const LABEL: usize = 12;

impl fmt::Display for Summary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let row = |f: &mut fmt::Formatter<'_>, label: &str, value: &str| writeln!(f, "{label:<LABEL$}{value}");
        row(f, "program", &self.program)?;
        row(f, "blocks", &format!("{} executed", self.blocks))?;
        row(f, "moves", &self.moves.to_string())?;
        row(f, "path", &format!("{} mm cutting, {} mm rapid", fixed3(self.cutting_mm), fixed3(self.rapid_mm)))?;
        row(f, "extents", &self.extents.map_or("no motion".into(), |e| e.to_string()))?;
        row(f, "tools", &tools(&self.tools))?;
        let stops = match self.stops {
            0 => "none".to_owned(),
            n => format!("{n} (M00/M01, answered with cycle start)"),
        };
        row(f, "stops", &stops)?;
        row(f, "alarms", if self.alarms.is_empty() { "none" } else { &self.alarms[0] })?;
        for a in self.alarms.iter().skip(1) {
            row(f, "", a)?;
        }
        row(f, "end", self.end.unwrap_or("not reached"))?;
        let t = &self.time;
        let estimate = format!(
            "{} ({} s rapid, {} s cutting, {} s dwell; no acceleration)",
            clock(t.total()),
            tenths(t.rapid),
            tenths(t.cutting),
            tenths(t.dwell)
        );
        let Some(m) = &self.motion else { return row(f, "cycle time", &estimate) };
        row(f, "cycle time", &format!("{} simulated (acceleration, spindle starts, dwells)", clock(m.cycle_s)))?;
        row(f, "estimate", &estimate)?;
        let deviation = format!(
            "{:.4} mm = {:.2} steps at most from the programmed path (line {})",
            m.deviation_mm, m.deviation_steps, m.deviation_line
        );
        row(f, "deviation", &deviation)?;
        row(f, "steps", &format!("{} step events", m.steps))
    }
}

impl fmt::Display for MoveCounts {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} rapid, {} linear, {} arc", self.rapid, self.linear, self.arc)?;
        if self.thread > 0 {
            write!(f, ", {} thread", self.thread)?;
        }
        if self.tap > 0 {
            write!(f, ", {} tap", self.tap)?;
        }
        Ok(())
    }
}

impl fmt::Display for Extents {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "X {} .. {} (diameter), Z {} .. {}",
            fixed3(self.x.0),
            fixed3(self.x.1),
            fixed3(self.z.0),
            fixed3(self.z.1)
        )
    }
}

/// Tool changes as `N: T0101, T0202`.
fn tools(t: &[(u16, u16)]) -> String {
    if t.is_empty() {
        return "none".into();
    }
    let list: Vec<String> = t.iter().map(|(tool, offset)| format!("T{tool:02}{offset:02}")).collect();
    let noun = if t.len() == 1 { "change" } else { "changes" };
    format!("{} {noun}: {}", t.len(), list.join(", "))
}

/// Seconds as `m:ss.s`.
fn clock(s: f64) -> String {
    let tenths = (s * 10.0).round() as u64;
    format!("{}:{:02}.{}", tenths / 600, tenths / 10 % 60, tenths % 10)
}

/// Seconds with one decimal.
fn tenths(s: f64) -> String {
    format!("{s:.1}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn times_read_as_minutes_and_seconds() {
        assert_eq!(clock(0.0), "0:00.0");
        assert_eq!(clock(83.44), "1:23.4");
        assert_eq!(clock(3599.96), "60:00.0");
        assert_eq!(tools(&[(1, 1), (12, 0)]), "2 changes: T0101, T1200");
        assert_eq!(tools(&[(3, 3)]), "1 change: T0303");
    }
}

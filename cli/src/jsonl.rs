//! `lathe sim --format jsonl`: one JSON object per canonical action, in order.
//!
//! Every object starts with `line` (1-based source line), then `program` for an
//! action of a subprogram (its O number; `line` is then a line of the file it came
//! from; absent for the main program), and `kind`; positions are
//! work coordinates in mm with X as a diameter on a lathe (a plain coordinate on
//! a mill), `y` and `c` only on machines with those axes; `mx`, `my` (machines
//! with a Y axis) and `mz` are the machine coordinates of a move's end; feeds in
//! mm/min or mm/rev, surface speeds in m/min, angles in degrees. Key order is the
//! field order of the record types below and never changes.

use std::io::{self, Write};

use interp_core::canon::{
    Action, ArcMove, Canon, Endpoint, FeedMode, Move, Plane, SpindleCommand, SpindleDir, SpindleSpeed, TapMove,
    ThreadMove, ThreadSync,
};
use interp_core::{Axis, MachineConfig};
use serde::Serialize;

use crate::program::Run;
use crate::units::{deg, dia, m_per_min, mm};

/// One line of output.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Record {
    /// Source line.
    pub line: u32,
    /// O number of the subprogram the action comes from; `None` for the main program.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub program: Option<u32>,
    /// `kind` and the fields of that kind.
    #[serde(flatten)]
    pub body: Body,
}

/// The fields of each kind of action.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Body {
    /// G00 positioning.
    Rapid(MoveRecord),
    /// G01 cutting.
    Linear(MoveRecord),
    /// G02/G03.
    Arc(ArcRecord),
    /// Thread cutting.
    Thread(ThreadRecord),
    /// Rigid tapping.
    Tap(TapRecord),
    /// G04.
    Dwell {
        /// Duration, s.
        seconds: f64,
    },
    /// M03/M04/M05 or a speed change.
    Spindle {
        /// `cw`, `ccw` or `stop`.
        dir: &'static str,
        /// Commanded rev/min, null when stopped.
        rpm: Option<u32>,
        /// G96 surface speed, m/min.
        css: Option<f64>,
    },
    /// T word.
    Tool {
        /// Turret station.
        tool: u16,
        /// Offset number (0 = cancelled).
        offset: u16,
    },
    /// M06 of a machining centre: the tool selected goes into the spindle.
    ToolChange {
        /// The tool put in.
        tool: u16,
        /// The tool taken out (0 = none).
        previous: u16,
        /// By hand (the machine stops for the operator) or by the tool changer.
        manual: bool,
    },
    /// A machine output switched by an M code.
    Aux {
        /// The M number.
        m: u16,
    },
    /// M00, or M01 with the optional-stop switch on.
    Stop {
        /// True for M01.
        optional: bool,
    },
    /// M02/M30.
    End {
        /// True for M30.
        rewind: bool,
    },
    /// G51.2 (P, Q) or G50.2 (both null): polygon turning.
    Polygon {
        /// Work-spindle turns P.
        p: Option<u16>,
        /// Tool-spindle turns Q.
        q: Option<u16>,
    },
    /// SINUMERIK CYCLE832: the path tolerance of the blocks after it.
    Tolerance {
        /// mm; null: the machine's own.
        mm: Option<f64>,
    },
}

/// Where a move ends: work X (diameter on a lathe), Y, Z, C (the machine
/// coordinates `mx`, `my`, `mz` follow in each move record).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Point {
    /// Work X, diameter mm.
    pub x: f64,
    /// Work Y, mm (machines with a Y axis).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub y: Option<f64>,
    /// Work Z, mm.
    pub z: f64,
    /// Work C, degrees (machines with a C axis).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub c: Option<f64>,
}

/// A rapid or linear move.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MoveRecord {
    /// End point.
    #[serde(flatten)]
    pub to: Point,
    /// Feed in mm/min or mm/rev; null for rapids.
    pub f: Option<f64>,
    /// `per_min` (G98) or `per_rev` (G99); for rapids the modal mode.
    pub feed_mode: &'static str,
    /// Commanded spindle speed at the end point, null when stopped.
    pub rpm: Option<u32>,
    /// G96 surface speed, m/min, null under G97.
    pub css: Option<f64>,
    /// Exact stop at the end.
    pub exact_stop: bool,
    /// Rapids only: axes at their own rates (dog-leg path).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub independent: Option<bool>,
    /// Machine X, diameter mm.
    pub mx: f64,
    /// Machine Y, mm (machines with a Y axis).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub my: Option<f64>,
    /// Machine Z, mm.
    pub mz: f64,
}

/// A G02/G03 move.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ArcRecord {
    /// End point.
    #[serde(flatten)]
    pub to: Point,
    /// Centre X, diameter mm.
    pub cx: f64,
    /// Centre Y, mm (G17/G19 arcs on machines with a Y axis).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cy: Option<f64>,
    /// Centre Z, mm.
    pub cz: f64,
    /// G02.
    pub cw: bool,
    /// Feed in mm/min or mm/rev.
    pub f: f64,
    /// `per_min` or `per_rev`.
    pub feed_mode: &'static str,
    /// Commanded spindle speed at the end point.
    pub rpm: Option<u32>,
    /// G96 surface speed, m/min.
    pub css: Option<f64>,
    /// Exact stop at the end.
    pub exact_stop: bool,
    /// A full circle.
    pub full_circle: bool,
    /// `xy`, `zx` or `yz`.
    pub plane: &'static str,
    /// Machine X, diameter mm.
    pub mx: f64,
    /// Machine Y, mm (machines with a Y axis).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub my: Option<f64>,
    /// Machine Z, mm.
    pub mz: f64,
}

/// A thread move.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ThreadRecord {
    /// End point.
    #[serde(flatten)]
    pub to: Point,
    /// Lead, mm/rev.
    pub lead: f64,
    /// Spindle angle after the index where the pass starts, degrees.
    pub start_deg: f64,
    /// `index` or `continue`.
    pub sync: &'static str,
    /// Lead change per revolution (G34), mm/rev per rev.
    pub lead_delta: f64,
    /// Spindle speed.
    pub rpm: Option<u32>,
    /// Machine X, diameter mm.
    pub mx: f64,
    /// Machine Y, mm (machines with a Y axis).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub my: Option<f64>,
    /// Machine Z, mm.
    pub mz: f64,
}

/// A rigid-tapping move.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TapRecord {
    /// End point.
    #[serde(flatten)]
    pub to: Point,
    /// Lead, mm/rev.
    pub lead: f64,
    /// Spindle direction during the move.
    pub dir: &'static str,
    /// Spindle speed.
    pub rpm: Option<u32>,
    /// Machine X, diameter mm.
    pub mx: f64,
    /// Machine Y, mm (machines with a Y axis).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub my: Option<f64>,
    /// Machine Z, mm.
    pub mz: f64,
}

/// The record of one action on machine `cfg` (which says whether Y and C exist).
pub fn record(c: &Canon, cfg: &MachineConfig) -> Record {
    let body = match &c.action {
        Action::Rapid(m) => Body::Rapid(move_record(m, cfg, true)),
        Action::Linear(m) => Body::Linear(move_record(m, cfg, false)),
        Action::Arc(a) => Body::Arc(arc_record(a, cfg)),
        Action::Thread(t) => Body::Thread(thread_record(t, cfg)),
        Action::Tap(t) => Body::Tap(tap_record(t, cfg)),
        Action::Dwell { ms } => Body::Dwell { seconds: f64::from(*ms) / 1e3 },
        Action::Spindle(s) => spindle_record(s),
        Action::Tool { tool, offset } => Body::Tool { tool: *tool, offset: *offset },
        Action::ToolChange(t) => Body::ToolChange { tool: t.tool, previous: t.previous, manual: t.manual },
        Action::Aux { m } => Body::Aux { m: *m },
        Action::Stop { optional } => Body::Stop { optional: *optional },
        Action::End { rewind } => Body::End { rewind: *rewind },
        Action::Polygon(p) => Body::Polygon { p: p.map(|s| s.p), q: p.map(|s| s.q) },
        Action::Tolerance { nm } => Body::Tolerance { mm: (*nm > 0).then(|| f64::from(*nm) / 1e6) },
    };
    Record { line: c.line, program: None, body }
}

/// Writes one line per action of the run.
pub fn write(run: &Run, cfg: &MachineConfig, out: &mut dyn Write) -> io::Result<()> {
    for (i, c) in run.actions.iter().enumerate() {
        let mut r = record(c, cfg);
        r.program = run.origins.get(i).copied().filter(|p| *p != run.main);
        serde_json::to_writer(&mut *out, &r)?;
        out.write_all(b"\n")?;
    }
    Ok(())
}

/// X for output: a diameter on a lathe that programs diameters, the coordinate
/// itself on a mill.
fn x_of(radius_nm: i64, cfg: &MachineConfig) -> f64 {
    if cfg.diameter_x { dia(radius_nm) } else { mm(radius_nm) }
}

/// Work coordinates of `ep` for output; Y and C only on machines that have them.
fn point(ep: &Endpoint, cfg: &MachineConfig) -> Point {
    let w = &ep.work;
    Point {
        x: x_of(w[Axis::X], cfg),
        y: cfg.axis(Axis::Y).present.then(|| mm(w[Axis::Y])),
        z: mm(w[Axis::Z]),
        c: cfg.axis(Axis::C).present.then(|| deg(w[Axis::C])),
    }
}

/// Machine Y of `ep` for output, on machines that have a Y axis.
fn machine_y(ep: &Endpoint, cfg: &MachineConfig) -> Option<f64> {
    cfg.axis(Axis::Y).present.then(|| mm(ep.machine[Axis::Y]))
}

fn move_record(m: &Move, cfg: &MachineConfig, rapid: bool) -> MoveRecord {
    MoveRecord {
        to: point(&m.to, cfg),
        f: (!rapid).then(|| mm(m.feed.value)),
        feed_mode: feed_mode(m.feed.mode),
        rpm: m.spindle.rpm,
        css: css(&m.spindle),
        exact_stop: m.exact_stop,
        independent: rapid.then_some(m.independent),
        mx: x_of(m.to.machine[Axis::X], cfg),
        my: machine_y(&m.to, cfg),
        mz: mm(m.to.machine[Axis::Z]),
    }
}

fn arc_record(a: &ArcMove, cfg: &MachineConfig) -> ArcRecord {
    let c = &a.center.work;
    let y_arc = a.plane != Plane::Zx && cfg.axis(Axis::Y).present;
    ArcRecord {
        to: point(&a.to, cfg),
        cx: x_of(c[Axis::X], cfg),
        cy: y_arc.then(|| mm(c[Axis::Y])),
        cz: mm(c[Axis::Z]),
        cw: a.cw,
        f: mm(a.feed.value),
        feed_mode: feed_mode(a.feed.mode),
        rpm: a.spindle.rpm,
        css: css(&a.spindle),
        exact_stop: a.exact_stop,
        full_circle: a.full_circle,
        plane: match a.plane {
            Plane::Xy => "xy",
            Plane::Zx => "zx",
            Plane::Yz => "yz",
        },
        mx: x_of(a.to.machine[Axis::X], cfg),
        my: machine_y(&a.to, cfg),
        mz: mm(a.to.machine[Axis::Z]),
    }
}

fn thread_record(t: &ThreadMove, cfg: &MachineConfig) -> ThreadRecord {
    ThreadRecord {
        to: point(&t.to, cfg),
        lead: mm(t.lead),
        start_deg: deg(i64::from(t.start_udeg)),
        sync: match t.sync {
            ThreadSync::Index => "index",
            ThreadSync::Continue => "continue",
        },
        lead_delta: mm(t.lead_delta),
        rpm: t.spindle.rpm,
        mx: x_of(t.to.machine[Axis::X], cfg),
        my: machine_y(&t.to, cfg),
        mz: mm(t.to.machine[Axis::Z]),
    }
}

fn tap_record(t: &TapMove, cfg: &MachineConfig) -> TapRecord {
    TapRecord {
        to: point(&t.to, cfg),
        lead: mm(t.lead),
        dir: spindle_dir(t.dir),
        rpm: t.spindle.rpm,
        mx: x_of(t.to.machine[Axis::X], cfg),
        my: machine_y(&t.to, cfg),
        mz: mm(t.to.machine[Axis::Z]),
    }
}

fn spindle_record(s: &SpindleCommand) -> Body {
    Body::Spindle { dir: spindle_dir(s.dir), rpm: s.rpm, css: s.css.map(m_per_min) }
}

/// G96 surface speed of a move in m/min.
fn css(s: &SpindleSpeed) -> Option<f64> {
    s.css.map(m_per_min)
}

/// The JSON name of a feed mode.
fn feed_mode(mode: FeedMode) -> &'static str {
    match mode {
        FeedMode::PerMin => "per_min",
        FeedMode::PerRev => "per_rev",
    }
}

/// The JSON name of a spindle direction.
fn spindle_dir(d: SpindleDir) -> &'static str {
    match d {
        SpindleDir::Cw => "cw",
        SpindleDir::Ccw => "ccw",
        SpindleDir::Stop => "stop",
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::program::{OnAlarm, run};

    /// A mill's X is a coordinate, not a diameter; Y is carried.
    #[test]
    fn a_mill_record_carries_x_as_it_is_and_y() {
        let cfg = crate::machine::parse(include_str!("../../examples/machines/mill.toml")).unwrap();
        let r =
            run(b"G90 G54 G00 X40. Y-25.5 Z10.\nM30\n", &cfg, &interp_core::Panel::default(), OnAlarm::Stop).unwrap();
        let mut out = Vec::new();
        write(&r, &cfg, &mut out).unwrap();
        let first = String::from_utf8(out).unwrap().lines().next().unwrap().to_string();
        assert!(first.contains("\"x\":40.0,\"y\":-25.5,\"z\":10.0"), "{first}");
        // G54 is X-300 Y-200 Z-250 in mill.toml: machine X -260, Y -225.5.
        assert!(first.contains("\"mx\":-260.0,\"my\":-225.5,\"mz\":-240.0"), "{first}");
    }
}

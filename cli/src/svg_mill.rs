//! `lathe sim --format svg` of a mill program (`kind = "mill"`): the plan view
//! (X to the right, Y up) beside the side view (X to the right, Z up), one scale,
//! machine coordinates (so G52/G54.1/G68 frames changing within the program do
//! not tear the picture apart). Rapids are red and dashed, cutting moves blue; every hole (a
//! feed or tap move along Z alone, downward) is marked with a circle in the plan
//! view at its X Y; a dot marks the start. Arcs in any plane are drawn through
//! points along them, so a helix shows as a circle in plan and a ramp from the side.

use std::fmt::Write;

use interp_core::{Axis, MachineConfig, Pos};

use crate::path::{ArcPath, Motion, Segment, segments};
use crate::program::Run;

/// Width of the picture, px.
const WIDTH_PX: f64 = 1000.0;
/// Points an arc is drawn with.
const ARC_POINTS: u32 = 48;

/// A drawn point: (X, Y, Z) mm, work coordinates.
type P3 = [f64; 3];

fn mm(p: Pos) -> P3 {
    [p[Axis::X] as f64 / 1e6, p[Axis::Y] as f64 / 1e6, p[Axis::Z] as f64 / 1e6]
}

/// Machine minus work coordinates of a segment (its frame).
fn frame(seg: &Segment) -> Pos {
    let e = seg.motion.to();
    e.machine - e.work
}

/// The points a segment is drawn through, machine coordinates.
fn points(seg: &Segment, cfg: &MachineConfig) -> Vec<P3> {
    let f = frame(seg);
    match &seg.motion {
        Motion::Arc(a) => {
            let arc = ArcPath::new(seg.from, a);
            (0..=ARC_POINTS).map(|i| mm(arc.point(f64::from(i) / f64::from(ARC_POINTS)) + f)).collect()
        }
        _ => seg.vertices(cfg).into_iter().map(|p| mm(p + f)).collect(),
    }
}

/// Where a hole is (machine X Y): a feed or tap move along Z alone, downward.
fn hole(seg: &Segment) -> Option<(f64, f64)> {
    let f = frame(seg);
    let (a, b) = (mm(seg.from + f), mm(seg.to() + f));
    let plunge = a[0] == b[0] && a[1] == b[1] && b[2] < a[2];
    (plunge && matches!(seg.motion, Motion::Linear(_) | Motion::Tap(_))).then_some((a[0], a[1]))
}

/// A number for SVG: at most 3 decimals, no trailing zeros.
fn n(v: f64) -> String {
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

/// One view: which coordinates go right and up, and where its box is drawn.
struct Panel {
    /// Indices into a [`P3`]: horizontal, vertical.
    axes: (usize, usize),
    /// Left edge of the panel on the page, mm.
    left: f64,
    /// The lowest horizontal and highest vertical value shown, mm.
    h0: f64,
    v1: f64,
}

impl Panel {
    /// Page coordinates of `p` (SVG y grows downward).
    fn at(&self, p: &P3) -> (f64, f64) {
        (self.left + p[self.axes.0] - self.h0, self.v1 - p[self.axes.1])
    }

    fn polyline(&self, pts: &[P3]) -> String {
        let mut d = String::new();
        for (i, p) in pts.iter().enumerate() {
            let (x, y) = self.at(p);
            let _ = write!(d, "{}{} {}", if i == 0 { "M" } else { " L" }, n(x), n(y));
        }
        d
    }
}

/// The drawing of `run` of `program` on machine `cfg` as an SVG document.
pub fn render(program: &str, run: &Run, cfg: &MachineConfig) -> String {
    let segs = segments(run.start, &run.actions);
    let drawn: Vec<(&Segment, Vec<P3>)> = segs.iter().map(|s| (s, points(s, cfg))).collect();
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in drawn.iter().flat_map(|(_, pts)| pts) {
        for i in 0..3 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    let span = (0..3).map(|i| hi[i] - lo[i]).fold(1.0, f64::max);
    let margin = 0.06 * span;
    let (lo, hi) = (lo.map(|v| v - margin), hi.map(|v| v + margin));
    let (w, gap) = (hi[0] - lo[0], 0.08 * span);
    let caption = 0.07 * span;
    let plan = Panel { axes: (0, 1), left: 0.0, h0: lo[0], v1: hi[1] + caption };
    let side = Panel { axes: (0, 2), left: w + gap, h0: lo[0], v1: hi[2] + caption };
    let width = 2.0 * w + gap;
    let height = caption + (hi[1] - lo[1]).max(hi[2] - lo[2]);
    let px = width / WIDTH_PX;
    let mut s = String::new();
    let _ = writeln!(s, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>");
    let _ = writeln!(
        s,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {} {}\" width=\"{}\" height=\"{}\">",
        n(width),
        n(height),
        WIDTH_PX.round(),
        (height / px).round()
    );
    let _ = writeln!(s, "<title>{}: mill tool path, plan X-Y and side X-Z</title>", escape(program));
    let _ = writeln!(
        s,
        "<style>\npath {{ fill: none; stroke-linecap: round; stroke-linejoin: round; }}\n\
         .frame {{ fill: #fff; stroke: #ccc; stroke-width: {w1}px; }}\n\
         .rapid {{ stroke: #d62728; stroke-width: {w15}px; stroke-dasharray: {d6}px {d4}px; }}\n\
         .feed {{ stroke: #1f4fb4; stroke-width: {w2}px; }}\n\
         .hole {{ fill: none; stroke: #000; stroke-width: {w15}px; }}\n\
         .start {{ fill: #2ca02c; }}\n\
         text {{ font-family: sans-serif; font-size: {f13}px; fill: #000; }}\n</style>",
        w1 = n(px),
        w15 = n(1.5 * px),
        w2 = n(2.0 * px),
        d4 = n(4.0 * px),
        d6 = n(6.0 * px),
        f13 = n(13.0 * px),
    );
    for (panel, title, (v0, v1)) in
        [(&plan, "plan (X right, Y up)", (lo[1], hi[1])), (&side, "side (X right, Z up)", (lo[2], hi[2]))]
    {
        let (x0, y0) = panel.at(&[lo[0], v1, v1]);
        let _ = writeln!(
            s,
            "<rect class=\"frame\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/>",
            n(x0),
            n(panel.v1 - v1),
            n(w),
            n(v1 - v0)
        );
        let _ = writeln!(s, "<text x=\"{}\" y=\"{}\">{title}</text>", n(panel.left), n(y0 - 0.4 * caption));
    }
    for (panel, id) in [(&plan, "plan"), (&side, "side")] {
        let _ = writeln!(s, "<g id=\"{id}\">");
        for (seg, pts) in &drawn {
            let class = if matches!(seg.motion, Motion::Rapid(_)) { "rapid" } else { "feed" };
            let _ = writeln!(s, "<path class=\"{class}\" data-line=\"{}\" d=\"{}\"/>", seg.line, panel.polyline(pts));
        }
        s.push_str("</g>\n");
    }
    let mut holes: Vec<(f64, f64)> = Vec::new();
    for h in segs.iter().filter_map(hole) {
        if !holes.iter().any(|o| (o.0 - h.0).abs() < 1e-6 && (o.1 - h.1).abs() < 1e-6) {
            holes.push(h);
        }
    }
    s.push_str("<g id=\"holes\">\n");
    for (x, y) in &holes {
        let (cx, cy) = plan.at(&[*x, *y, 0.0]);
        let _ = writeln!(
            s,
            "<circle class=\"hole\" cx=\"{}\" cy=\"{}\" r=\"{}\"><title>hole X{} Y{}</title></circle>",
            n(cx),
            n(cy),
            n(6.0 * px),
            n(*x),
            n(*y)
        );
    }
    s.push_str("</g>\n");
    if let Some((_, pts)) = drawn.first() {
        for panel in [&plan, &side] {
            let (x, y) = panel.at(&pts[0]);
            let _ = writeln!(s, "<circle class=\"start\" cx=\"{}\" cy=\"{}\" r=\"{}\"/>", n(x), n(y), n(4.0 * px));
        }
    }
    let _ = writeln!(
        s,
        "<text x=\"0\" y=\"{}\">{}: {} holes; rapid red dashed, feed blue, circle = hole, green dot = start; machine coordinates, mm</text>",
        n(0.35 * caption),
        escape(program),
        holes.len()
    );
    s.push_str("</svg>\n");
    s
}

/// Text with XML's special characters escaped.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::program::{OnAlarm, run};
    use interp_core::Panel as Switches;

    #[test]
    fn a_bolt_circle_shows_six_holes_in_plan_and_side_views() {
        let cfg = crate::machine::parse(include_str!("../../examples/machines/mill.toml")).unwrap();
        let text = include_bytes!("../../examples/mill/bolt_circle_g16.nc");
        let r = run(text, &cfg, &Switches::default(), OnAlarm::Stop).unwrap();
        assert!(r.alarms.is_empty(), "{:?}", r.alarms);
        let svg = render("bolt_circle_g16.nc", &r, &cfg);
        assert_eq!(svg.matches("class=\"hole\"").count(), 6, "{svg}");
        assert!(svg.contains("<g id=\"plan\">") && svg.contains("<g id=\"side\">"));
        assert!(svg.contains("class=\"rapid\"") && svg.contains("class=\"feed\""));
        // The holes lie on R40 about X100 Y60 (G52 + G16) of G54 (machine X-300
        // Y-200): the first at X140 Y60, machine X-160 Y-140; the third X80 Y94.641.
        assert!(svg.contains("<title>hole X-160 Y-140</title>"), "{svg}");
        assert!(svg.contains("<title>hole X-220 Y-105.359</title>"), "{svg}");
    }
}

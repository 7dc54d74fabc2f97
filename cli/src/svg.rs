//! `lathe sim --format svg`: the tool path in the X–Z plane, work coordinates.
//!
//! Z runs to the right and X up, with X drawn as a *radius* so arcs are true
//! circles (grid labels give the programmed diameter). Rapids are dashed, cutting
//! moves solid, threads and taps in their own colours; the spindle centreline is
//! dash-dot and a dot marks the start. Line widths and text sizes are computed from
//! the drawing's size, so they look the same for a watch part and a shaft.
//!
//! With tool-nose radius compensation (G41/G42) two more layers are drawn: the
//! programmed contour (grey) and the path of the nose centre (green, what the
//! compensation computed); the blue path is the imaginary tip the machine moves.
//!
//! SVG's y axis points down, so a point (Z, X) is drawn at (Z, −X). The picture is
//! the program's view (X up), where G02 turns clockwise: that is sweep-flag 1.

use std::fmt::Write;

use interp_core::canon::{Canon, Plane};
use interp_core::{Axis, MachineConfig, Pos};

use crate::path::{ArcPath, Bounds, Motion, Segment, segments};
use crate::program::Run;

/// Largest side of the picture, px.
const SIZE_PX: f64 = 800.0;
/// Height of the caption band above the drawing, px.
const CAPTION_PX: f64 = 36.0;
/// Points a G17/G19 arc is drawn with (it projects to a line or curve in X–Z).
const PROJECTED_ARC_POINTS: u32 = 32;

/// The paths drawn besides the machine's when nose compensation was used.
#[derive(Debug, Clone, Default)]
pub struct Overlay {
    /// The run with every nose radius 0: the programmed contour.
    pub contour: Vec<Canon>,
    /// The run with every tip direction 0: the nose centre's path.
    pub centre: Vec<Canon>,
}

/// The drawing of `run` of `program` on machine `cfg` as an SVG document, with the
/// compensation layers of `overlay`.
pub fn render(program: &str, run: &Run, cfg: &MachineConfig, overlay: Option<&Overlay>) -> String {
    let segs = segments(run.start, &run.actions);
    // With compensation the interest is the cut: the view fits the cutting moves
    // (a 0.8 mm offset would vanish beside the rapid from the reference position).
    let cuts: Vec<Segment> = segs.iter().filter(|g| !matches!(g.motion, Motion::Rapid(_))).copied().collect();
    let view = View::fit(Bounds::of(if overlay.is_some() && !cuts.is_empty() { &cuts } else { &segs }));
    let mut s = String::new();
    view.open(&mut s, program);
    view.grid(&mut s);
    view.centreline(&mut s);
    if let Some(o) = overlay {
        group(&mut s, "contour", Some("contour"), &segments(run.start, &o.contour), cfg);
    }
    group(&mut s, "path", None, &segs, cfg);
    if let Some(o) = overlay {
        group(&mut s, "centre", Some("centre"), &segments(run.start, &o.centre), cfg);
    }
    if let Some(first) = segs.first() {
        let (x, y) = screen(first.from);
        let _ = writeln!(
            s,
            "<circle class=\"start\" cx=\"{}\" cy=\"{}\" r=\"{}\"><title>start</title></circle>",
            n(x),
            n(y),
            n(4.0 * view.px)
        );
    }
    view.caption(&mut s, program, overlay.is_some());
    s.push_str("</svg>\n");
    s
}

/// A `<g>` of path elements; `class` replaces the feed/rapid classes of the
/// cutting moves (rapids keep theirs).
fn group(s: &mut String, id: &str, class: Option<&str>, segs: &[Segment], cfg: &MachineConfig) {
    let _ = writeln!(s, "<g id=\"{id}\">");
    for seg in segs {
        path_element(s, seg, cfg, class);
    }
    s.push_str("</g>\n");
}

/// A work position as drawn: (Z, −X radius) in mm.
fn screen(p: Pos) -> (f64, f64) {
    (p[Axis::Z] as f64 / 1e6, -(p[Axis::X] as f64) / 1e6)
}

/// A number for SVG: at most 4 decimals, no trailing zeros.
fn n(v: f64) -> String {
    let s = format!("{v:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

/// Text with XML's special characters escaped.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// The visible area and the sizes derived from it.
struct View {
    /// Left edge, mm (screen coordinates: Z).
    min_x: f64,
    /// Top edge, mm (screen coordinates: −X radius).
    min_y: f64,
    /// Width, mm.
    width: f64,
    /// Height, mm, caption included.
    height: f64,
    /// mm per output pixel.
    px: f64,
    /// Grid spacing, mm.
    step: f64,
}

impl View {
    /// A view of the path's box and the spindle centreline, with a margin and room for the caption.
    fn fit(bounds: Option<Bounds>) -> View {
        let b = bounds.unwrap_or(Bounds::point(Pos::ZERO));
        let (z0, z1) = (b.z.0 as f64 / 1e6, b.z.1 as f64 / 1e6);
        let (x0, x1) = (b.x.0.min(0) as f64 / 1e6, b.x.1.max(0) as f64 / 1e6);
        let span = (z1 - z0).max(x1 - x0).max(1.0);
        let margin = 0.08 * span;
        let (width, body) = (z1 - z0 + 2.0 * margin, x1 - x0 + 2.0 * margin);
        let px = width.max(body) / SIZE_PX;
        let caption = CAPTION_PX * px;
        View {
            min_x: z0 - margin,
            min_y: -x1 - margin - caption,
            width,
            height: body + caption,
            px,
            step: nice_step(span / 8.0),
        }
    }

    /// The document start: size, title and styles.
    fn open(&self, s: &mut String, program: &str) {
        let scale = SIZE_PX / self.width.max(self.height);
        let _ = writeln!(s, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>");
        let _ = writeln!(
            s,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"{} {} {} {}\" width=\"{}\" height=\"{}\">",
            n(self.min_x),
            n(self.min_y),
            n(self.width),
            n(self.height),
            (self.width * scale).round(),
            (self.height * scale).round()
        );
        let _ = writeln!(s, "<title>{}: tool path in X-Z (X drawn as radius)</title>", escape(program));
        let p = |k: f64| n(k * self.px);
        let _ = writeln!(
            s,
            "<style>\n\
             path, line {{ fill: none; stroke-linecap: round; stroke-linejoin: round; }}\n\
             .grid {{ stroke: #e4e4e4; stroke-width: {w1}px; }}\n\
             .centreline {{ stroke: #555; stroke-width: {w1}px; stroke-dasharray: {d12}px {d3}px {d2}px {d3}px; }}\n\
             .rapid {{ stroke: #d62728; stroke-width: {w15}px; stroke-dasharray: {d6}px {d4}px; }}\n\
             .feed {{ stroke: #1f4fb4; stroke-width: {w2}px; }}\n\
             .thread {{ stroke: #9c27b0; stroke-width: {w2}px; }}\n\
             .tap {{ stroke: #8c564b; stroke-width: {w2}px; }}\n\
             .contour {{ stroke: #888; stroke-width: {w3}px; }}\n\
             .centre {{ stroke: #2ca02c; stroke-width: {w1}px; }}\n\
             .start {{ fill: #2ca02c; }}\n\
             .scale {{ stroke: #000; stroke-width: {w15}px; }}\n\
             text {{ font-family: sans-serif; font-size: {f11}px; fill: #555; }}\n\
             .caption {{ font-size: {f13}px; fill: #000; }}\n\
             </style>",
            w1 = p(1.0),
            w15 = p(1.5),
            w2 = p(2.0),
            w3 = p(3.0),
            d2 = p(2.0),
            d3 = p(3.0),
            d4 = p(4.0),
            d6 = p(6.0),
            d12 = p(12.0),
            f11 = p(11.0),
            f13 = p(13.0),
        );
        let _ = writeln!(
            s,
            "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"#fff\"/>",
            n(self.min_x),
            n(self.min_y),
            n(self.width),
            n(self.height)
        );
    }

    /// Grid lines every `step` mm, labelled with Z and the X diameter.
    fn grid(&self, s: &mut String) {
        let (left, right) = (self.min_x, self.min_x + self.width);
        let (top, bottom) = (self.min_y + CAPTION_PX * self.px, self.min_y + self.height);
        s.push_str("<g class=\"grid\">\n");
        for z in multiples(left, right, self.step) {
            let _ = writeln!(s, "<line x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{2}\"/>", n(z), n(top), n(bottom));
        }
        for y in multiples(top, bottom, self.step) {
            let _ = writeln!(s, "<line x1=\"{1}\" y1=\"{0}\" x2=\"{2}\" y2=\"{0}\"/>", n(y), n(left), n(right));
        }
        s.push_str("</g>\n<g class=\"labels\">\n");
        let pad = 3.0 * self.px;
        for z in multiples(left, right, self.step) {
            let _ = writeln!(s, "<text x=\"{}\" y=\"{}\">Z{}</text>", n(z + pad), n(bottom - pad), n(z));
        }
        for y in multiples(top, bottom, self.step) {
            let _ = writeln!(s, "<text x=\"{}\" y=\"{}\">X{}</text>", n(left + pad), n(y - pad), n(-2.0 * y));
        }
        s.push_str("</g>\n");
    }

    /// The spindle axis (X = 0), dash-dot.
    fn centreline(&self, s: &mut String) {
        let _ = writeln!(
            s,
            "<line class=\"centreline\" x1=\"{}\" y1=\"0\" x2=\"{}\" y2=\"0\"><title>spindle centreline</title></line>",
            n(self.min_x),
            n(self.min_x + self.width)
        );
    }

    /// Title line, legend and a scale bar one grid step long.
    fn caption(&self, s: &mut String, program: &str, comp: bool) {
        let x = self.min_x + 6.0 * self.px;
        let (y1, y2) = (self.min_y + 15.0 * self.px, self.min_y + 31.0 * self.px);
        let _ = writeln!(
            s,
            "<text class=\"caption\" x=\"{}\" y=\"{}\">{}: Z to the right, X up drawn as radius (labels give the diameter), work coordinates</text>",
            n(x),
            n(y1),
            escape(program)
        );
        let _ = writeln!(
            s,
            "<text x=\"{}\" y=\"{}\">rapid: red dashed; feed: blue; thread: purple; tap: brown; green dot: start; {}grid {} mm</text>",
            n(x),
            n(y2),
            if comp { "grey: programmed contour; green line: nose centre (G41/G42); " } else { "" },
            n(self.step)
        );
        let right = self.min_x + self.width - 10.0 * self.px;
        let y = self.min_y + self.height - 18.0 * self.px;
        let _ = writeln!(
            s,
            "<g><line class=\"scale\" x1=\"{x0}\" y1=\"{y}\" x2=\"{x1}\" y2=\"{y}\"/><text x=\"{x0}\" y=\"{ty}\">{len} mm</text></g>",
            x0 = n(right - self.step),
            x1 = n(right),
            y = n(y),
            ty = n(y - 4.0 * self.px),
            len = n(self.step)
        );
    }
}

/// The multiples of `step` from `lo` to `hi`.
fn multiples(lo: f64, hi: f64, step: f64) -> impl Iterator<Item = f64> {
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last).map(move |k| k as f64 * step)
}

/// The 1, 2 or 5 × 10ⁿ nearest above `raw`.
fn nice_step(raw: f64) -> f64 {
    let pow = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0].into_iter().map(|m| m * pow).find(|&s| s >= raw).unwrap_or(10.0 * pow)
}

/// One `<path>` for a move, with its class and source line.
fn path_element(s: &mut String, seg: &Segment, cfg: &MachineConfig, layer: Option<&str>) {
    let (class, d) = match &seg.motion {
        Motion::Rapid(_) => ("rapid", polyline(&seg.vertices(cfg))),
        Motion::Linear(_) => ("feed", polyline(&seg.vertices(cfg))),
        Motion::Arc(a) => ("feed", arc_data(&ArcPath::new(seg.from, a), a.cw, seg.to())),
        Motion::Thread(_) => ("thread", polyline(&seg.vertices(cfg))),
        Motion::Tap(_) => ("tap", polyline(&seg.vertices(cfg))),
    };
    let class = match layer {
        Some(l) if class != "rapid" => l,
        Some(_) => return,
        None => class,
    };
    let _ = writeln!(s, "<path class=\"{class}\" data-line=\"{}\" d=\"{d}\"/>", seg.line);
}

/// Path data through `points`.
fn polyline(points: &[Pos]) -> String {
    let mut d = String::new();
    for (i, p) in points.iter().enumerate() {
        let (x, y) = screen(*p);
        let _ = write!(d, "{}{} {}", if i == 0 { "M" } else { " L" }, n(x), n(y));
    }
    d
}

/// Path data of an arc ending at `to`: SVG arc commands in the Z–X plane (a full
/// circle as two halves, since an arc command cannot start and end at one point);
/// arcs in other planes as their projection, through points along the arc.
fn arc_data(arc: &ArcPath, cw: bool, to: Pos) -> String {
    if arc.plane != Plane::Zx {
        let pts: Vec<Pos> =
            (0..=PROJECTED_ARC_POINTS).map(|i| arc.point(f64::from(i) / f64::from(PROJECTED_ARC_POINTS))).collect();
        return polyline(&pts);
    }
    let (x0, y0) = screen(arc.from);
    let r = n(arc.radius / 1e6);
    let sweep = u8::from(cw);
    let mut d = format!("M{} {}", n(x0), n(y0));
    let ends = if arc.sweep.abs() >= std::f64::consts::TAU {
        vec![(arc.point(0.5), false), (to, false)]
    } else {
        vec![(to, arc.large())]
    };
    for (p, large) in ends {
        let (x, y) = screen(p);
        let _ = write!(d, " A{r} {r} 0 {} {sweep} {} {}", u8::from(large), n(x), n(y));
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short_and_steps_are_round() {
        assert_eq!(n(-0.00001), "0");
        assert_eq!(n(12.5), "12.5");
        assert_eq!(n(-30.0), "-30");
        assert_eq!(nice_step(7.0), 10.0);
        assert_eq!(nice_step(1.2), 2.0);
        assert_eq!(nice_step(0.3), 0.5);
        assert_eq!(multiples(-25.0, 12.0, 10.0).collect::<Vec<_>>(), vec![-20.0, -10.0, 0.0, 10.0]);
        assert_eq!(escape("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
    }
}

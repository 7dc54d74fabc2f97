//! `lathe sim --format svg`: well-formed XML, arcs turning the right way.

use super::{lathe, scratch, status, stdout};

/// The SVG of `program` on the built-in machine.
fn svg(name: &str, program: &str) -> String {
    let o = lathe(&["sim", &scratch(name, program), "--format", "svg"]);
    assert_eq!(status(&o), 0);
    stdout(&o)
}

/// `d` of every path of class `class`.
fn paths(doc: &roxmltree::Document<'_>, class: &str) -> Vec<String> {
    doc.descendants()
        .filter(|n| n.has_tag_name("path") && n.attribute("class") == Some(class))
        .map(|n| n.attribute("d").unwrap().to_owned())
        .collect()
}

/// An SVG arc: start, radius, flags, end.
#[derive(Debug)]
struct SvgArc {
    from: (f64, f64),
    r: f64,
    large: bool,
    sweep: bool,
    to: (f64, f64),
}

/// The arcs of path data `M x y A r r 0 large sweep x y [A ...]`.
fn arcs(d: &str) -> Vec<SvgArc> {
    let t: Vec<&str> = d.split(|c: char| c.is_whitespace() || c == 'M' || c == 'A').filter(|s| !s.is_empty()).collect();
    let num = |i: usize| t[i].parse::<f64>().unwrap();
    let mut from = (num(0), num(1));
    let mut out = Vec::new();
    for k in (2..t.len()).step_by(7) {
        let to = (num(k + 5), num(k + 6));
        out.push(SvgArc { from, r: num(k), large: t[k + 3] == "1", sweep: t[k + 4] == "1", to });
        from = to;
    }
    out
}

/// The centre an SVG viewer draws an arc around (SVG 1.1 appendix F.6.5, rx = ry, no rotation).
fn centre(a: &SvgArc) -> (f64, f64) {
    let (x1p, y1p) = ((a.from.0 - a.to.0) / 2.0, (a.from.1 - a.to.1) / 2.0);
    let r2 = a.r * a.r;
    let d2 = x1p * x1p + y1p * y1p;
    let sign = if a.large != a.sweep { 1.0 } else { -1.0 };
    let coef = sign * ((r2 - d2) / d2).max(0.0).sqrt();
    (coef * y1p + (a.from.0 + a.to.0) / 2.0, -coef * x1p + (a.from.1 + a.to.1) / 2.0)
}

fn close(p: (f64, f64), q: (f64, f64)) -> bool {
    (p.0 - q.0).abs() < 1e-3 && (p.1 - q.1).abs() < 1e-3
}

#[test]
fn the_drawing_is_well_formed_xml_with_a_caption() {
    let s = svg("svg-xml.nc", "%\nO0001 (A & B <test>)\nG00 X20 Z25\nG01 X60 Z7 F500\nG02 X50 Z-30 R25\nM30\n%\n");
    let doc = roxmltree::Document::parse(&s).expect("well-formed XML");
    let root = doc.root_element();
    assert!(root.has_tag_name(("http://www.w3.org/2000/svg", "svg")));
    assert_eq!(root.attribute("viewBox").unwrap().split(' ').count(), 4);
    let title = root.children().find(|n| n.has_tag_name("title")).unwrap().text().unwrap();
    assert!(title.contains("X drawn as radius"), "{title}");
    assert_eq!(paths(&doc, "rapid").len(), 1);
    assert_eq!(paths(&doc, "feed").len(), 2);
    assert!(doc.descendants().any(|n| n.attribute("class") == Some("centreline")));
    assert!(doc.descendants().any(|n| n.attribute("class") == Some("start")));
}

#[test]
fn g02_and_g03_sweep_the_way_the_program_turns() {
    // G02 from (X0 Z0) to (X20 Z-10) R10: centre X radius 10, Z 0, drawn at (0, -10).
    // G03 on to (X40 Z-20) R10: centre X radius 10, Z -20, drawn at (-20, -10).
    let s = svg("svg-sweep.nc", "G00 X0 Z0\nG02 X20 Z-10 R10 F100\nG03 X40 Z-20 R10\nM30\n");
    let doc = roxmltree::Document::parse(&s).unwrap();
    let feeds = paths(&doc, "feed");
    let (g02, g03) = (&arcs(&feeds[0])[0], &arcs(&feeds[1])[0]);
    assert!(g02.sweep && !g02.large, "{g02:?}");
    assert!(close(centre(g02), (0.0, -10.0)), "{:?}", centre(g02));
    assert!(!g03.sweep && !g03.large, "{g03:?}");
    assert!(close(centre(g03), (-20.0, -10.0)), "{:?}", centre(g03));
}

#[test]
fn a_full_circle_is_drawn_as_two_halves() {
    let s = svg("svg-circle.nc", "G00 X20 Z0\nG02 X20 Z0 K-10 F100\nM30\n");
    let doc = roxmltree::Document::parse(&s).unwrap();
    let halves = arcs(&paths(&doc, "feed")[0]);
    assert_eq!(halves.len(), 2);
    for h in &halves {
        assert!(h.sweep);
        assert!(close(centre(h), (-10.0, -10.0)), "{:?}", centre(h));
    }
    assert!(close(halves[1].to, halves[0].from));
}

/// Stroke width of the cutting moves over the drawing's width.
fn relative_stroke(s: &str) -> f64 {
    let doc = roxmltree::Document::parse(s).unwrap();
    let width: f64 = doc.root_element().attribute("viewBox").unwrap().split(' ').nth(2).unwrap().parse().unwrap();
    let style = doc.descendants().find(|n| n.has_tag_name("style")).unwrap().text().unwrap().to_owned();
    let feed = style.lines().find(|l| l.starts_with(".feed")).unwrap();
    let w = feed.split("stroke-width: ").nth(1).unwrap().split("px").next().unwrap();
    w.parse::<f64>().unwrap() / width
}

#[test]
fn line_widths_do_not_grow_with_the_part() {
    let small = svg("svg-small.nc", "G00 X1 Z1\nG01 X2 Z0 F10\nM30\n");
    let large = svg("svg-large.nc", "G00 X10 Z-500\nG01 X300 Z200 F1000\nM30\n");
    let (a, b) = (relative_stroke(&small), relative_stroke(&large));
    assert!((a - b).abs() < 1e-3 * a, "{a} vs {b}");
}

/// With nose radius compensation the drawing adds the programmed contour and the
/// nose-centre path; without it, neither.
#[test]
fn compensation_draws_the_contour_and_the_nose_centre() {
    let machine = scratch("r08.toml", "[[offsets]]\nnumber = 1\nradius = 0.8\ntip = 3\n");
    let prog = scratch("g42.nc", "T0101\nG00 X20 Z3\nG42 G01 Z0 F100\nZ-10\nX30 Z-20\nG40 G00 X50\nM30\n");
    let o = lathe(&["sim", &prog, "--machine", &machine, "--format", "svg"]);
    assert_eq!(status(&o), 0);
    let text = stdout(&o);
    let doc = roxmltree::Document::parse(&text).unwrap();
    let contour = paths(&doc, "contour");
    let centre = paths(&doc, "centre");
    // The taper (line 5) as programmed: (Z-10, r10) to (Z-20, r15), drawn at (Z, -r).
    assert!(contour.iter().any(|d| d == "M-10 -10 L-20 -15"), "{contour:?}");
    // The nose centre on the taper lies 0.8 mm off it: check both ends' distance.
    let taper_centre = doc
        .descendants()
        .find(|n| n.attribute("class") == Some("centre") && n.attribute("data-line") == Some("5"))
        .and_then(|n| n.attribute("d"))
        .unwrap();
    let v: Vec<f64> = taper_centre
        .split(|c: char| c == 'M' || c == 'L' || c.is_whitespace())
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().unwrap())
        .collect();
    for p in [(v[0], -v[1]), (v[2], -v[3])] {
        // Line through (-10, 10) and (-20, 15): distance |(p - a) × (b - a)| / |b - a|.
        let (dx, dy) = (-10.0, 5.0);
        let d = ((p.0 + 10.0) * dy - (p.1 - 10.0) * dx).abs() / f64::hypot(dx, dy);
        assert!((d - 0.8).abs() < 2e-4, "{p:?}: {d}");
    }
    assert!(!centre.is_empty());
    let plain = svg("plain.nc", "G00 X20 Z3\nG01 Z-10 F100\nM30\n");
    assert!(!plain.contains("class=\"contour\"") && !plain.contains("class=\"centre\""));
}

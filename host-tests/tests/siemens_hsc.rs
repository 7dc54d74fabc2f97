//! SINUMERIK CYCLE832 high-speed settings on the mill (seed 001 lines 9261-9797):
//! `_TOL` becomes the path tolerance the motion core plans the following blocks
//! with (junction deviation of G64 corners, chord tolerance of arcs), `_TOLM`'s
//! machining type the blending mode (deselect: exact stop G60). The corner and
//! arc speeds are computed here from the look-ahead's formulas
//! (`motion_core::planner::lookahead`, `block::arc`) and measured on the
//! simulated machine, period by period.

mod mill_common;

use mill_common::plane::siemens;

use host_tests::Run;
use interp_core::MachineConfig;
use interp_core::canon::{Action, Canon};
use interp_core::config::Language;
use motion_core::fixed::STEP_ONE;
use sim::{Sim, SimOptions};

const HEAD: &str = "G17 G0 G90 X0 Y0 Z20 F200 S500 M3 T1 D1\n";

/// The tolerances (nm) the run hands the motion core, in order.
fn tolerances(r: &Run) -> Vec<u32> {
    r.actions
        .iter()
        .filter_map(|c| match c.action {
            Action::Tolerance { nm } => Some(nm),
            _ => None,
        })
        .collect()
}

/// Whether each cutting move of the run ends with an exact stop, in order.
fn exact_stops(r: &Run) -> Vec<bool> {
    r.actions
        .iter()
        .filter_map(|c| match c.action {
            Action::Linear(m) => Some(m.exact_stop),
            Action::Arc(a) => Some(a.exact_stop),
            _ => None,
        })
        .collect()
}

/// The document's example (lines 9344-9374): roughing at 0.2 mm, finishing at
/// 0.01 mm with technology adaptation and G641, deselect. Roughing and
/// finishing blend (continuous path), deselect stops exactly at every block;
/// deselect hands the machine's own tolerance back (0).
#[test]
fn the_documents_calls_set_tolerance_and_blending() {
    let r = siemens(&format!(
        "{HEAD}CYCLE832(0.2, 1003)\nG1 X10\nY10\nCYCLE832(0.01, 102001)\nX20\nY20\nCYCLE832(0.1, 0)\nX30\nY30\nM30\n"
    ));
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    assert_eq!(tolerances(&r), vec![200_000, 10_000, 0]);
    assert_eq!(exact_stops(&r), vec![false, false, false, false, true, true]);
    // Each tolerance goes out on its cycle's line, before the moves after it.
    let lines: Vec<u32> =
        r.actions.iter().filter(|c| matches!(c.action, Action::Tolerance { .. })).map(|c| c.line).collect();
    assert_eq!(lines, vec![2, 5, 8]);
}

/// `CYCLE832()` deselects (line 9390); `CYCLE832(_TOL)` sets the tolerance
/// alone and leaves the G functions as they are (line 9395); a `_TOL` of 0
/// takes the machining type's preset (lines 9434-9439: finishing 0.01,
/// semi-finishing 0.05, roughing 0.1 mm); inch programs give it in inches.
#[test]
fn short_calls_presets_and_inches() {
    let r = siemens(&format!("{HEAD}CYCLE832(0.1, 3)\nCYCLE832()\nG1 X10\nM30\n"));
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    assert_eq!(tolerances(&r), vec![100_000, 0]);
    assert_eq!(exact_stops(&r), vec![true]);

    // G60 stays in force under CYCLE832(_TOL); G64 too.
    let r = siemens(&format!("{HEAD}G60\nCYCLE832(0.05)\nG1 X10\nG64\nCYCLE832(0.02)\nX20\nM30\n"));
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    assert_eq!(tolerances(&r), vec![50_000, 20_000]);
    assert_eq!(exact_stops(&r), vec![true, false]);

    for (tolm, nm) in [(1, 10_000), (2, 50_000), (3, 100_000)] {
        let r = siemens(&format!("{HEAD}CYCLE832(0, {tolm})\nCYCLE832(, {tolm})\nM30\n"));
        assert!(r.alarms.is_empty(), "{:?}", r.alarms);
        assert_eq!(tolerances(&r), vec![nm, nm], "_TOLM {tolm}");
    }
    let r = siemens(&format!("{HEAD}G70\nCYCLE832(0.001, 1)\nM30\n"));
    assert_eq!(tolerances(&r), vec![25_400]);
}

/// The digits this board has no use for (compressor COMPCAD/COMPCURV,
/// feedforward, jerk, adaptation, path control G64/G641/G642) are accepted and
/// change nothing but what the machining type sets.
#[test]
fn settings_without_meaning_here_are_accepted() {
    let plain = siemens(&format!("{HEAD}CYCLE832(0.1, 3)\nG1 X10\nY10\nM30\n"));
    for tolm in [1003, 103, 203, 3, 2003, 11_003, 21_003, 101_003, 122_203] {
        let r = siemens(&format!("{HEAD}CYCLE832(0.1, {tolm})\nG1 X10\nY10\nM30\n"));
        assert!(r.alarms.is_empty(), "{tolm}: {:?}", r.alarms);
        assert_eq!(r.kinds(), plain.kinds(), "_TOLM {tolm}");
    }
}

/// Alarms (lines 9785-9797 and our choices, docs/SIEMENS-MILL.md): TRAORI and
/// TRAORI(2) are 61191/61192 (no 5-axis transformation), B spline 61194 (no
/// spline interpolation); a negative or too wide tolerance and a `_TOLM` digit
/// outside its values are 61019. The call's line, nothing emitted.
#[test]
fn alarms_on_the_cycles_line_and_nothing_changes() {
    let before = siemens(&format!("{HEAD}G1 X10\nY10\nM30\n"));
    assert!(before.alarms.is_empty(), "{:?}", before.alarms);
    for (call, code) in [
        ("CYCLE832(0.1, 1013)", 61191),
        ("CYCLE832(0.1, 11)", 61191),
        ("CYCLE832(0.1, 1023)", 61192),
        ("CYCLE832(0.1, 1303)", 61194),
        ("CYCLE832(-0.1, 1)", 61019),
        ("CYCLE832(-0.01)", 61019),
        ("CYCLE832(10.5, 1)", 61019),
        ("CYCLE832(0.1, 4)", 61019),
        ("CYCLE832(0.1, 33)", 61019),
        ("CYCLE832(0.1, 403)", 61019),
        ("CYCLE832(0.1, 3003)", 61019),
        ("CYCLE832(0.1, 31003)", 61019),
        ("CYCLE832(0.1, 201003)", 61019),
        ("CYCLE832(0.1, 1000003)", 61019),
        ("CYCLE832(0.1, -3)", 61019),
        ("CYCLE832(20000, 1)", 61019),
    ] {
        let r = siemens(&format!("{HEAD}{call}\nG1 X10\nY10\nM30\n"));
        assert_eq!(r.alarm_codes(), vec![(2, code)], "{call}");
        assert!(tolerances(&r).is_empty(), "{call}");
        assert_eq!(r.kinds(), before.kinds(), "{call}");
    }
}

/// A machining centre whose axes may change speed by 3000 mm/min at a junction
/// (the board's default is 300): the tolerance, not the axes' jump, rules the
/// corners below.
fn corner_machine() -> MachineConfig {
    let mut c = MachineConfig { language: Language::Siemens, ..MachineConfig::mill() };
    for ax in &mut c.axes[..3] {
        ax.max_jump_per_min = 3_000_000_000;
    }
    c
}

/// nm a period from a program on `cfg`, sampled: the commanded positions (Q16
/// steps of 2.5 µm) as nm in X, Y.
fn xy_samples(s: &Sim) -> Vec<(u32, [f64; 2])> {
    let nm = |q: i64| q as f64 / STEP_ONE as f64 * 2_500.0;
    s.samples.iter().map(|t| (t.line, [nm(t.commanded[0]), nm(t.commanded[1])])).collect()
}

/// The path speed (nm a period) where the program passes from block `line`
/// to the next at `corner` (nm): the slowest period among the four around the
/// crossing, the crossing one measured along the path through the corner.
fn corner_speed(s: &Sim, line: u32, corner: [f64; 2]) -> f64 {
    let p = xy_samples(s);
    let cross = p.iter().position(|(l, _)| *l == line + 1).expect("the next block ran");
    let dist = |a: [f64; 2], b: [f64; 2]| (b[0] - a[0]).hypot(b[1] - a[1]);
    let d = |k: usize| {
        if k == cross { dist(p[k - 1].1, corner) + dist(corner, p[k].1) } else { dist(p[k - 1].1, p[k].1) }
    };
    (cross - 2..=cross + 1).map(d).fold(f64::MAX, f64::min)
}

/// The junction speed of the look-ahead (nm a period) for a turn by `phi`
/// (rad) between long blocks at feed `feed` (nm a period): the smaller of the
/// deviation circle `√(a·δ·cos(φ/2) / (1 − cos(φ/2)))` and the chord limit
/// `2·tol / sin(φ/2)` (junction deviation δ, chord tolerance `tol`, nm; `a`
/// nm/period²).
fn junction(phi: f64, delta: f64, tol: f64, a: f64, feed: f64) -> f64 {
    let (c, s) = ((phi / 2.0).cos(), (phi / 2.0).sin());
    (a * delta * c / (1.0 - c)).sqrt().min(2.0 * tol / s).min(feed)
}

/// Whether `speed`, measured at a junction, is the planned junction speed
/// `want`: the period that crosses the junction runs at most at it, and at
/// least one period's acceleration `a` below it.
fn at_junction(speed: f64, want: f64, a: f64) -> bool {
    speed <= want * 1.001 && speed >= want - a * 1.01
}

/// A 20° corner between two 50 mm lines at F5000 (83,333 nm a period of 1 ms;
/// axes at 500 mm/s², 500 nm/period²). The machine's own tolerances
/// (junction deviation 10 µm, chord 1 µm) take it at the chord limit
/// 2·1 µm / sin 10° = 11.5 µm a period (691 mm/min); after CYCLE832(0.05, 1)
/// the 50 µm deviation circle allows 40.3 µm a period (2415 mm/min); after
/// deselect the path stops at the corner. After M30 and after reset the next
/// program has the machine's own tolerance again.
#[test]
fn a_corner_after_cycle832_is_as_fast_as_its_tolerance_allows() {
    let phi = 20f64.to_radians();
    let (x2, y2) = (-150.0 + 50.0 * phi.cos(), -200.0 + 50.0 * phi.sin());
    let program =
        |call: &str| format!("G17 G90 G94 G0 X-200 Y-200 Z-10\n{call}\nG1 X-150 F5000\nX{x2:.4} Y{y2:.4}\nM30\n");
    // The direction actually programmed (rounded to 0.1 µm).
    let phi = ((format!("{y2:.4}").parse::<f64>().unwrap() + 200.0)
        / (format!("{x2:.4}").parse::<f64>().unwrap() + 150.0))
        .atan();
    let feed = 5000.0 * 1e6 / 60_000.0;
    let a = 500.0;
    let opts = SimOptions { samples: true, ..SimOptions::default() };
    let mut s = Sim::new(corner_machine(), opts).unwrap();
    let run = |s: &mut Sim, call: &str| {
        s.samples.clear();
        let r = s.run_program(&program(call));
        assert!(r.alarms.is_empty() && r.ended, "{call}: {r:?}");
        corner_speed(s, 3, [-150e6, -200e6])
    };

    let own = run(&mut s, "");
    let want = junction(phi, 10_000.0, 1_000.0, a, feed);
    assert!(at_junction(own, want, a), "machine's tolerance: {own} nm/period, computed {want}");
    assert!((want - 2.0 * 1_000.0 / (phi / 2.0).sin()).abs() < 1e-6, "the chord limit rules");

    let hsc = run(&mut s, "CYCLE832(0.05, 1)");
    let want = junction(phi, 50_000.0, 50_000.0, a, feed);
    assert!(at_junction(hsc, want, a), "CYCLE832(0.05): {hsc} nm/period, computed {want}");
    assert!(want > 3.4 * own && want < feed, "the deviation circle rules: {want}");

    let deselect = run(&mut s, "CYCLE832(0.05, 0)");
    assert!(deselect <= a, "exact stop at the corner: {deselect} nm/period");

    // M30 of the CYCLE832 program put the machine's tolerance back.
    run(&mut s, "CYCLE832(0.2, 3)");
    let again = run(&mut s, "");
    assert!((again - own).abs() <= 0.01 * own, "after M30: {again} vs {own}");

    // A tolerance stays in force until M30 or reset (here one handed over
    // alone, with no M30 after it), and reset puts the machine's back.
    let tol = [Canon { line: 1, action: Action::Tolerance { nm: 50_000 } }];
    s.run_actions(&tol);
    let kept = run(&mut s, "");
    assert!((kept - hsc).abs() <= 0.01 * hsc, "kept: {kept} vs {hsc}");
    s.run_actions(&tol);
    s.core.reset();
    let reset = run(&mut s, "");
    assert!((reset - own).abs() <= 0.01 * own, "after reset: {reset} vs {own}");
}

/// A full circle of radius 0.5 mm at F5000 on axes of 20,000 mm/s² (20,000
/// nm/period²; an arc plans with half for the path): its speed is capped by the
/// centripetal limit √(a/2·r) = 70.7 µm a period and by the chord limit
/// √(8·r·tol), which with the machine's 1 µm is 63.2 µm — the chord of each
/// period then strays exactly 1 µm from the arc. After CYCLE832(0.1, 3) the
/// chord limit is 632 µm: the centripetal limit rules, and every period's
/// chord stays within 0.1 mm of the arc (1.25 µm here).
#[test]
fn an_arc_after_cycle832_is_chorded_within_its_tolerance() {
    let mut cfg = corner_machine();
    for ax in &mut cfg.axes[..2] {
        ax.accel_per_s2 = 20_000_000_000;
    }
    let (r, feed, half_a) = (500_000.0f64, 5000.0 * 1e6 / 60_000.0, 10_000.0);
    let opts = SimOptions { samples: true, ..SimOptions::default() };
    for (call, tol) in [("", 1_000.0), ("CYCLE832(0.1, 3)", 100_000.0)] {
        let mut s = Sim::new(cfg.clone(), opts).unwrap();
        let rep =
            s.run_program(&format!("G17 G90 G94 G0 X-200 Y-200 Z-10\n{call}\nG2 X-200 Y-200 I0.5 J0 F5000\nM30\n"));
        assert!(rep.alarms.is_empty() && rep.ended, "{call}: {rep:?}");
        let cap = (half_a * r).sqrt().min((8.0 * r * tol).sqrt()).min(feed);
        let p: Vec<[f64; 2]> = xy_samples(&s).into_iter().filter(|(l, _)| *l == 3).map(|(_, p)| p).collect();
        assert!(p.len() > 40, "{} periods", p.len());
        let centre = [-199.5e6, -200e6];
        let (mut fastest, mut sag) = (0.0f64, 0.0f64);
        for w in p.windows(2) {
            let chord = (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]);
            fastest = fastest.max(chord);
            // Sagitta of the chord: the arc's radius minus the distance of the
            // chord's midpoint from the centre.
            let mid = [(w[0][0] + w[1][0]) / 2.0 - centre[0], (w[0][1] + w[1][1]) / 2.0 - centre[1]];
            sag = sag.max(r - mid[0].hypot(mid[1]));
        }
        // The chord of a period at the cap: 2r·sin(s / 2r).
        let want = 2.0 * r * (cap / (2.0 * r)).sin();
        assert!((fastest - want).abs() <= 0.01 * want, "{call}: {fastest} nm a period, computed {want}");
        assert!(sag <= tol + 50.0, "{call}: a chord strays {sag} nm from the arc (tolerance {tol})");
        if tol == 1_000.0 {
            assert!(sag >= 0.9 * tol, "the chord limit rules: {sag}");
        }
    }
}

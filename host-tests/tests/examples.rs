//! Every program in `examples/` runs on the default machine without an alarm (with
//! the subprograms of `examples/lib` in program memory), and the macro part-family
//! programs cut what they say.

use std::fs;
use std::path::PathBuf;

use host_tests::{Run, kind_names, run_lib};
use interp_core::canon::Action;

/// The repository's `examples/` directory.
fn dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../examples")
}

/// A file of `examples/`.
fn example(name: &str) -> String {
    let p = dir().join(name);
    fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// The texts of the `.nc` files in `examples/<sub>`.
fn programs_in(sub: &str) -> Vec<(PathBuf, String)> {
    let mut v: Vec<(PathBuf, String)> = fs::read_dir(dir().join(sub))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "nc"))
        .map(|p| {
            let text = fs::read_to_string(&p).unwrap();
            (p, text)
        })
        .collect();
    v.sort();
    v
}

/// Runs `main` with every subprogram of `examples/lib`.
fn with_library(main: &str) -> Run {
    let lib: Vec<String> = programs_in("lib").into_iter().map(|(_, t)| t).collect();
    let refs: Vec<&str> = lib.iter().map(String::as_str).collect();
    run_lib(main, &refs)
}

#[test]
fn example_programs_run_without_alarms() {
    let mut count = 0;
    for (path, text) in programs_in("") {
        let r = with_library(&text);
        assert!(r.alarms.is_empty(), "{}: {:?}", path.display(), r.alarms);
        assert_eq!(kind_names(&r).last().map(String::as_str), Some("end true"), "{}", path.display());
        count += 1;
    }
    assert!(count >= 7, "found {count} examples");
}

/// Runs an example with the subprograms of `examples/lib`.
fn run_example(name: &str) -> Run {
    let r = with_library(&example(name));
    assert!(r.alarms.is_empty(), "{name}: {:?}", r.alarms);
    assert!(matches!(r.actions.last().map(|c| c.action), Some(Action::End { rewind: true })), "{name} ends with M30");
    r
}

/// (X diameter, Z) of every cutting move.
fn cuts(r: &Run) -> Vec<(f64, f64)> {
    r.actions.iter().filter(|c| matches!(c.action, Action::Linear(_))).filter_map(host_tests::xz).collect()
}

#[test]
fn parabola_points_lie_on_z_equals_minus_x_squared_over_40() {
    let r = run_example("parabola_while.nc");
    let pts = cuts(&r);
    assert_eq!(pts.len(), 81, "Z0 approach plus 80 steps of 0.5 mm");
    for &(x, z) in &pts[1..] {
        let expect = -(x * x) / 40.0;
        assert!((z - expect).abs() <= 0.0005, "({x}, {z}) vs {expect}");
    }
    assert_eq!(pts[1], (0.5, -0.006), "-0.00625 rounds to the least increment");
    assert_eq!(*pts.last().unwrap(), (40.0, -40.0));
}

#[test]
fn groove_series_pitch_grows_by_one_and_a_half() {
    let r = run_example("groove_series.nc");
    let plunges: Vec<(f64, f64)> = cuts(&r);
    let z: Vec<f64> = plunges.iter().map(|p| p.1).collect();
    assert_eq!(z, vec![-5.0, -9.0, -14.5, -21.5, -30.0, -40.0]);
    assert!(plunges.iter().all(|p| p.0 == 24.0));
    let dwells = r.actions.iter().filter(|c| c.action == Action::Dwell { ms: 500 }).count();
    assert_eq!(dwells, 6);
}

#[test]
fn stepped_shaft_family_defaults_when_the_commons_are_empty() {
    let r = run_example("stepped_shaft_family.nc");
    assert_eq!(
        cuts(&r),
        vec![(18.0, 0.0), (20.0, 0.0), (20.0, -10.0), (30.0, -10.0), (30.0, -25.0), (40.0, -25.0), (40.0, -45.0)]
    );
    assert_eq!(r.interp.variables().get(503), Ok(Some(40.0)));
}

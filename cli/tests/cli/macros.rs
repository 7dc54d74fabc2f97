//! Macro programs and subprograms on the command line: `--lib`, `--vars`,
//! `--input`, and alarms named after the file they happen in.

use super::{lathe, scratch, status, stderr, stdout};

/// `examples/` of the repository.
const EXAMPLES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples");

/// A scratch directory `name` holding `files`.
fn scratch_dir(name: &str, files: &[(&str, &str)]) -> String {
    let dir = std::path::Path::new(&scratch(&format!("{name}.keep"), "")).with_file_name(name);
    std::fs::create_dir_all(&dir).unwrap();
    for (file, text) in files {
        std::fs::write(dir.join(file), text).unwrap();
    }
    dir.display().to_string()
}

#[test]
fn sim_jsonl_shows_the_expanded_moves_of_a_subprogram_loop() {
    let main = format!("{EXAMPLES}/groove_series.nc");
    let o = lathe(&["sim", &main, "--lib", &format!("{EXAMPLES}/lib"), "--format", "jsonl"]);
    assert_eq!(status(&o), 0, "{}", stderr(&o));
    let lines: Vec<serde_json::Value> = stdout(&o).lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    let plunges: Vec<(u64, f64)> = lines
        .iter()
        .filter(|v| v["kind"] == "linear")
        .map(|v| (v["program"].as_u64().unwrap(), v["z"].as_f64().unwrap()))
        .collect();
    assert_eq!(plunges, [(201, -5.0), (201, -9.0), (201, -14.5), (201, -21.5), (201, -30.0), (201, -40.0)]);
    // Lines of the subprogram's file; the main program's actions carry no "program".
    assert!(lines.iter().filter(|v| v["kind"] == "linear").all(|v| v["line"] == 4));
    assert!(lines.iter().filter(|v| v["kind"] == "spindle").all(|v| v.get("program").is_none()));
    let o = lathe(&["sim", &main]);
    assert_eq!(status(&o), 1);
    assert_eq!(stderr(&o), format!("{main}:15: alarm 0076: program O0201 not found\n"));
}

#[test]
fn check_reports_macro_alarms_with_the_file_and_line_they_happen_in() {
    let lib = scratch_dir("check-lib", &[("o0050.nc", "%\nO0050\n#1=SQRT[-1]\nG00 X[1/#0]\nM99\n%\n")]);
    let main = scratch("check-macro.nc", "#1=1\nIF [#1 EQ 1] GOTO 99\nM98 P50\nWHILE [#1 LT 3] DO4\nM30\n");
    let o = lathe(&["check", &main, "--lib", &lib]);
    assert_eq!(status(&o), 1);
    assert_eq!(
        stdout(&o),
        format!(
            "{main}:2: alarm 0078: sequence number N99 not found\n\
             {lib}/o0050.nc:3: alarm 0119: argument of SQRT out of range\n\
             {lib}/o0050.nc:4: alarm 0112: division by zero (/, MOD or TAN of 90 degrees)\n\
             {main}:4: alarm 0126: loop number 4 is not 1, 2 or 3\n\
             {main}: 3 blocks, 4 alarms\n"
        )
    );
}

#[test]
fn vars_file_keeps_the_common_variables_between_runs() {
    let vars = scratch("sim-vars.txt", "");
    std::fs::remove_file(&vars).unwrap();
    let p = scratch("sim-vars.nc", "#500=#500+1\n#1=7\nG00 X[#500*10] Z0\nM30\n");
    for expect in [10.0, 20.0] {
        let o = lathe(&["sim", &p, "--vars", &vars, "--format", "jsonl"]);
        assert_eq!(status(&o), 0, "{}", stderr(&o));
        let v: serde_json::Value = serde_json::from_str(stdout(&o).lines().next().unwrap()).unwrap();
        assert_eq!(v["x"].as_f64(), Some(expect));
    }
    let kept = std::fs::read_to_string(&vars).unwrap();
    assert!(kept.ends_with("\n#500 = 2.0\n"), "only the commons are kept: {kept}");
    // check reads the file but leaves it alone.
    assert_eq!(status(&lathe(&["check", &p, "--vars", &vars])), 0);
    assert_eq!(std::fs::read_to_string(&vars).unwrap(), kept);
    let bad = scratch("bad-vars.txt", "#500 = 1\n#5 = 2\n");
    let o = lathe(&["sim", &p, "--vars", &bad]);
    assert_eq!(status(&o), 2);
    assert_eq!(stderr(&o), format!("lathe: {bad}:2: only common variables #401-#600 are kept\n"));
}

#[test]
fn inputs_decide_m91_and_m92() {
    let p = scratch("sim-m92.nc", "N50 M92 P100\nN60 G0 X10 Z10\nN100 G0 X20 Z30\nM30\n");
    let xs = |args: &[&str]| -> Vec<f64> {
        let o = lathe(&[&["sim", &p, "--format", "jsonl"][..], args].concat());
        assert_eq!(status(&o), 0, "{}", stderr(&o));
        stdout(&o).lines().filter_map(|l| serde_json::from_str::<serde_json::Value>(l).unwrap()["x"].as_f64()).collect()
    };
    assert_eq!(xs(&[]), [10.0, 20.0]);
    assert_eq!(xs(&["--input", "0=1"]), [20.0]);
    assert_eq!(xs(&["--input", "0=1", "--input", "0=0"]), [10.0, 20.0]);
    assert_eq!(status(&lathe(&["sim", &p, "--input", "32=1"])), 2);
    assert_eq!(status(&lathe(&["sim", &p, "--input", "1=2"])), 2);
}

#[test]
fn library_problems_are_errors_naming_the_file() {
    let lib = scratch_dir("dup-lib", &[("a.nc", "O0007\nM99\n"), ("b.nc", "O0007\nM99\n")]);
    let p = scratch("lib-user.nc", "M98 P7\nM30\n");
    let o = lathe(&["sim", &p, "--lib", &lib]);
    assert_eq!(status(&o), 2);
    assert_eq!(stderr(&o), format!("lathe: {lib}/b.nc: program O0007 is already in memory\n"));
    let lib = scratch_dir("nameless-lib", &[("c.nc", "G00 X1\nM99\n")]);
    let o = lathe(&["check", &p, "--lib", &lib]);
    assert_eq!(status(&o), 2);
    assert_eq!(stderr(&o), format!("lathe: {lib}/c.nc: line 1: blocks before the first O number\n"));
    // A main program inside its own library directory is read once.
    let dir = scratch_dir("self-lib", &[("main.nc", "O0001\nM98 P2\nM30\n"), ("sub.nc", "O0002\nG00 X4 Z4\nM99\n")]);
    let o = lathe(&["check", &format!("{dir}/main.nc"), "--lib", &dir]);
    assert_eq!(status(&o), 0, "{}{}", stdout(&o), stderr(&o));
}

/// The macro examples of `examples/macros/` (docs/MACROS.md): each checks without an
/// alarm, simulates to M30, and renders exactly as the SVG committed beside it.
#[test]
fn every_macro_example_checks_simulates_and_matches_its_render() {
    let dir = format!("{EXAMPLES}/macros");
    let (lib, machine) = (format!("{dir}/lib"), format!("{dir}/machine.toml"));
    let mut programs: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "nc"))
        .collect();
    programs.sort();
    assert_eq!(programs.len(), 3);
    for p in &programs {
        let p = p.to_str().unwrap();
        let with = |args: &[&str]| lathe(&[args, &["--lib", &lib, "--machine", &machine]].concat());
        let o = with(&["check", p]);
        assert_eq!(status(&o), 0, "{p}: {}{}", stdout(&o), stderr(&o));
        assert!(stdout(&o).ends_with("no alarms\n"), "{p}: {}", stdout(&o));
        let summary = stdout(&with(&["sim", p]));
        assert!(summary.contains("alarms      none\n") && summary.contains("end         M30\n"), "{p}: {summary}");
        // The render names the file as given: as from the repository's root.
        let name = p.rsplit('/').next().unwrap();
        let svg = stdout(&with(&["sim", p, "--format", "svg"])).replace(p, &format!("examples/macros/{name}"));
        let committed = std::fs::read_to_string(p.replace(".nc", ".svg")).unwrap();
        assert!(svg == committed, "{p}: the render differs; regenerate it as docs/MACROS.md says");
    }
}

#[test]
fn the_macro_examples_make_the_moves_they_promise() {
    let dir = format!("{EXAMPLES}/macros");
    let (lib, machine) = (format!("{dir}/lib"), format!("{dir}/machine.toml"));
    let moves = |name: &str| -> Vec<serde_json::Value> {
        let o = lathe(&["sim", &format!("{dir}/{name}"), "--lib", &lib, "--machine", &machine, "--format", "jsonl"]);
        assert_eq!(status(&o), 0, "{}", stderr(&o));
        stdout(&o)
            .lines()
            .map(|l| serde_json::from_str(l).unwrap())
            .filter(|v: &serde_json::Value| v["kind"] == "linear")
            .collect()
    };
    // G66: a plunge to X26 after each of the four moves, at its Z, from O9110.
    let grooves: Vec<(f64, f64, u64)> = moves("grooves_g66.nc")
        .iter()
        .map(|v| (v["x"].as_f64().unwrap(), v["z"].as_f64().unwrap(), v["program"].as_u64().unwrap()))
        .collect();
    assert_eq!(grooves, [(26.0, -10.0, 9110), (26.0, -20.0, 9110), (26.0, -30.0, 9110), (26.0, -42.0, 9110)]);
    // G100 (6050 = 100 calls O9010): 4 plunges across 12 mm, 3 across 8 mm.
    let plunges: Vec<(f64, f64)> = moves("g100_wide_grooves.nc")
        .iter()
        .map(|v| (v["x"].as_f64().unwrap(), (v["z"].as_f64().unwrap() * 1000.0).round() / 1000.0))
        .collect();
    assert_eq!(
        plunges,
        [(30.0, -10.0), (30.0, -12.667), (30.0, -15.333), (30.0, -18.0), (34.0, -35.0), (34.0, -37.0), (34.0, -39.0)]
    );
    // G65 bolt circles: the feeds of the holes go down to Z-12 (six) and Z-8 (four).
    let bottoms: Vec<f64> = moves("bolt_circle_g65.nc")
        .iter()
        .map(|v| v["z"].as_f64().unwrap())
        .filter(|z| *z == -12.0 || *z == -8.0)
        .collect();
    assert_eq!(bottoms, [-12.0; 6].into_iter().chain([-8.0; 4]).collect::<Vec<_>>());
}

//! `lathe sim`: stopping at the first alarm, the summary, the operator switches.

use interp_core::{MachineConfig, Panel};
use lathe::program::{OnAlarm, run};
use lathe::summary::Summary;

use super::{lathe, scratch, status, stderr, stdout};

#[test]
fn stops_at_the_first_alarm_after_writing_what_ran() {
    let p = scratch("sim-stop.nc", "G00 X20 Z25\nG07 X10\nG01 X30 F0\nM30\n");
    let o = lathe(&["sim", &p, "--format", "jsonl"]);
    assert_eq!(status(&o), 1);
    let out = stdout(&o);
    assert_eq!(out.lines().count(), 1);
    assert!(out.starts_with(r#"{"line":1,"kind":"rapid""#));
    assert_eq!(stderr(&o), format!("{p}:2: alarm 0010: G07 is not a G code of the selected G-code system\n"));
}

#[test]
fn out_file_gets_the_output_even_after_an_alarm() {
    let p = scratch("sim-out.nc", "G00 X20 Z25\nG01 X30 F0\nM30\n");
    let out = scratch("sim-out.txt", "");
    let o = lathe(&["sim", &p, "--out", &out]);
    assert_eq!(status(&o), 1);
    assert_eq!(stdout(&o), "");
    let summary = std::fs::read_to_string(&out).unwrap();
    assert!(summary.contains(&format!("alarms      {p}:2: alarm 0011:")), "{summary}");
    assert!(summary.contains("end         not reached"), "{summary}");
}

#[test]
fn summary_counts_lengths_extents_and_time() {
    // From reference position 1 (X300 Z250): a rapid of X 100 mm (radius) at 6 m/min
    // and Z 150 mm at 8 m/min takes 1.125 s; 100 mm at 600 mm/min 10 s; dwell 2 s.
    // Simulated, with acceleration (500 mm/s²) and the straight rapid slowed to the
    // axes' rates along it: 13.4 s; the stepped path is within 0.58 steps.
    let p = scratch("sim-summary.nc", "T0101\nG00 X100 Z100\nG01 Z0 F600\nG04 X2\nM00\nM30\n");
    let o = lathe(&["sim", &p]);
    assert_eq!(status(&o), 0);
    let expected = format!(
        "program     {p}\n\
         blocks      6 executed\n\
         moves       1 rapid, 1 linear, 0 arc\n\
         path        100.000 mm cutting, 180.278 mm rapid\n\
         extents     X 100.000 .. 300.000 (diameter), Z 0.000 .. 250.000\n\
         tools       1 change: T0101\n\
         stops       1 (M00/M01, answered with cycle start)\n\
         alarms      none\n\
         end         M30\n\
         cycle time  0:13.4 simulated (acceleration, spindle starts, dwells)\n\
         estimate    0:13.1 (1.1 s rapid, 10.0 s cutting, 2.0 s dwell; no acceleration)\n\
         deviation   0.0017 mm = 0.58 steps at most from the programmed path (line 2)\n\
         steps       120000 step events\n"
    );
    assert_eq!(stdout(&o), expected);
}

/// Cutting time of `program` on the built-in machine, seconds.
fn cutting_seconds(program: &str) -> f64 {
    let cfg = MachineConfig::default();
    let r = run(program.as_bytes(), &cfg, &Panel::default(), OnAlarm::Stop).unwrap();
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    Summary::new("t", &r, &cfg).time.cutting
}

#[test]
fn feed_per_revolution_under_css_follows_the_diameter() {
    // G96 300 m/min, 0.2 mm/rev. Turning at X100: n = 300000 / (pi 100), so
    // 50 mm take 50 pi 100 / (0.2 * 300000) min. The control commands whole
    // rev/min (955, not 954.93), which moves the time by less than 0.1 %.
    let close = |t: f64, exact: f64| (t - exact).abs() < 1e-3 * exact;
    let t = cutting_seconds("M3 G96 S300 G99\nG0 X100 Z100\nG1 Z50 F0.2\nM30\n");
    assert!(close(t, 50.0 * std::f64::consts::PI * 100.0 / 60_000.0 * 60.0), "{t}");
    // Facing from radius 50 to 30: dt = 2 pi r dr / (f css), t = pi (50² - 30²) / (f css).
    let t = cutting_seconds("M3 G96 S300 G99\nG0 X100 Z0\nG1 X60 F0.2\nM30\n");
    let exact = std::f64::consts::PI * (2500.0 - 900.0) / 60_000.0 * 60.0;
    assert!(close(t, exact), "{t} vs {exact}");
}

#[test]
fn feeds_are_capped_by_parameter_6023() {
    let t = cutting_seconds("G0 X100 Z100\nG1 Z0 F10000\nM30\n");
    assert!((t - 100.0 / 5000.0 * 60.0).abs() < 1e-9, "{t}");
}

#[test]
fn optional_stop_and_block_skip_switches() {
    let p = scratch("sim-switches.nc", "G00 X20 Z25\n/G00 X30\n/2 G00 X40\nM01\nM30\n");
    let kinds = |args: &[&str]| {
        let mut all = vec!["sim", p.as_str(), "--format", "jsonl"];
        all.extend_from_slice(args);
        let o = lathe(&all);
        assert_eq!(status(&o), 0, "{}", stderr(&o));
        stdout(&o).lines().map(|l| l.split(',').take(2).collect::<Vec<_>>().join(",")).collect::<Vec<_>>()
    };
    let r = r#"{"line":1,"kind":"rapid""#;
    assert_eq!(
        kinds(&[]),
        [r, r#"{"line":2,"kind":"rapid""#, r#"{"line":3,"kind":"rapid""#, r#"{"line":5,"kind":"end""#]
    );
    assert_eq!(
        kinds(&["--block-skip", "--optional-stop"]),
        [r, r#"{"line":3,"kind":"rapid""#, r#"{"line":4,"kind":"stop""#, r#"{"line":5,"kind":"end""#]
    );
    assert_eq!(kinds(&["--block-skip=1,2"]), [r, r#"{"line":5,"kind":"end""#]);
    assert_eq!(status(&lathe(&["sim", &p, "--block-skip=10"])), 2);
}

#[test]
fn every_example_program_simulates_in_every_format() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples");
    let mut programs: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "nc"))
        .collect();
    programs.sort();
    assert!(!programs.is_empty());
    let lib = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/lib");
    for p in &programs {
        let p = p.to_str().unwrap();
        let jsonl = lathe(&["sim", p, "--format", "jsonl", "--lib", lib]);
        assert_eq!(status(&jsonl), 0, "{p}: {}", stderr(&jsonl));
        for line in stdout(&jsonl).lines() {
            let v: serde_json::Value = serde_json::from_str(line).unwrap();
            assert!(v["line"].as_u64().is_some() && v["kind"].is_string(), "{p}: {line}");
        }
        let svg = lathe(&["sim", p, "--format", "svg", "--lib", lib]);
        assert!(roxmltree::Document::parse(&stdout(&svg)).is_ok(), "{p}");
        let summary = stdout(&lathe(&["sim", p, "--lib", lib]));
        assert!(summary.contains("alarms      none\n") && summary.contains("end         M30\n"), "{p}: {summary}");
    }
}

#[test]
fn trace_writes_one_row_per_step_event() {
    // 10 mm of Z at 320 steps/mm and 5 mm of X diameter (2.5 mm radius at 400 steps/mm).
    let p = scratch("sim-trace.nc", "G00 X295 Z240\nM3 S600\nG99 G01 W-10 F0.2\nM30\n");
    let csv = scratch("sim-trace.csv", "");
    let o = lathe(&["sim", &p, "--format", "jsonl", "--trace", &csv]);
    assert_eq!(status(&o), 0, "{}", stderr(&o));
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("t_s,x_mm,z_mm,spindle_deg"));
    let rows: Vec<Vec<f64>> = lines.map(|l| l.split(',').map(|v| v.parse().unwrap()).collect()).collect();
    // The rapid: 1000 X and 3200 Z steps; the cut: 3200 Z steps.
    assert_eq!(rows.len(), 1_000 + 3_200 + 3_200);
    assert!(rows.windows(2).all(|w| w[1][0] >= w[0][0]), "time goes forward");
    let last = rows.last().unwrap();
    assert_eq!((last[1], last[2]), (295.0, 230.0));
    // 10 mm at 0.2 mm/rev: the spindle turned 50 revolutions during the cut.
    let cut: Vec<_> = rows.iter().filter(|r| r[2] < 240.0).collect();
    let turns = (cut[cut.len() - 1][3] - cut[0][3]) / 360.0;
    assert!((turns - 50.0).abs() < 0.2, "{turns} revolutions");
}

#[test]
fn a_motion_alarm_stops_the_run_with_its_line() {
    // 10 mm lead at 2000 rev/min: 20 m/min is more than Z may cut.
    let p = scratch("sim-motion-alarm.nc", "M3 S2000\nG0 X40 Z5\nG32 W-40 F10\nM30\n");
    let o = lathe(&["sim", &p]);
    assert_eq!(status(&o), 1);
    assert_eq!(
        stderr(&o),
        format!("{p}:3: alarm 4501: thread lead x spindle speed exceeds the speed limit of axis Z\n")
    );
}

#[test]
fn a_g34_program_runs_end_to_end() {
    // Fig. 2.54: lead 4 at the start growing by K 0.2 per revolution over 78 mm,
    // two passes at 500 rev/min.
    let p = scratch(
        "sim-g34.nc",
        "G00 X60 Z4 M03 S500\nG00 U-10\nG00 U-0.7\nG34 W-78 F4 K0.2\nG00 U10\nZ4\n\
         G00 X50\nG00 U-1.0\nG34 W-78 F4 K0.2\nG00 U10\nZ4\nM30\n",
    );
    let csv = scratch("sim-g34.csv", "");
    let o = lathe(&["sim", &p, "--trace", &csv]);
    assert_eq!(status(&o), 0, "{}", stderr(&o));
    let out = stdout(&o);
    for expected in [
        "moves       9 rapid, 0 linear, 0 arc, 2 thread\n",
        "extents     X 49.000 .. 300.000 (diameter), Z -74.000 .. 250.000\n",
        "alarms      none\n",
        "end         M30\n",
        // 4θ + 0.1θ² = 78: 14.35 revolutions, 1.72 s per pass.
        "3.4 s cutting",
    ] {
        assert!(out.contains(expected), "{expected:?} in\n{out}");
    }
    // The spindle turns θ(s) = (√(F² + 2·K·s) − F)/K revolutions over the first s mm:
    // from 10 mm (Z-6) to 70 mm (Z-66) into the first pass, 10.805 revolutions.
    let text = std::fs::read_to_string(&csv).unwrap();
    let rows: Vec<Vec<f64>> =
        text.lines().skip(1).map(|l| l.split(',').map(|v| v.parse().unwrap()).collect()).collect();
    let pass: Vec<_> = rows.iter().filter(|r| r[1] == 49.3).collect();
    let deg_at = |z: f64| pass.iter().find(|r| r[2] <= z).unwrap()[3];
    let theta = |s: f64| ((16.0 + 0.4 * s).sqrt() - 4.0) / 0.2;
    let turns = (deg_at(-66.0) - deg_at(-6.0)) / 360.0;
    assert!((turns - (theta(70.0) - theta(10.0))).abs() < 0.002, "{turns} revolutions");
    assert_eq!(pass.last().map(|r| r[2]), Some(-74.0));
}

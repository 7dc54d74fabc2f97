//! Machine files: the example equals the built-in machine, values convert to
//! internal units, a file written back reads the same, and mistakes are named.

use std::collections::BTreeSet;

use interp_core::config::{GCodeSystem, MTiming, Param};
use interp_core::units::IncrementSystem;
use interp_core::{Axis, MachineConfig, Pos};
use lathe::machine::{parse, to_toml};

use super::{lathe, scratch, status, stderr, stdout};

fn example() -> String {
    std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/machines/default.toml")).unwrap()
}

#[test]
fn the_example_file_is_the_built_in_machine() {
    assert_eq!(parse(&example()), Ok(MachineConfig::default()));
}

/// Every key path of a TOML document (`axes.x.min`, `reference[].x`, …).
fn keys(v: &toml::Value, prefix: &str, out: &mut BTreeSet<String>) {
    match v {
        toml::Value::Table(t) => {
            for (k, v) in t {
                let path = if prefix.is_empty() { k.clone() } else { format!("{prefix}.{k}") };
                out.insert(path.clone());
                keys(v, &path, out);
            }
        }
        toml::Value::Array(a) => a.iter().for_each(|e| keys(e, &format!("{prefix}[]"), out)),
        _ => {}
    }
}

#[test]
fn the_example_file_shows_every_field_and_parameter() {
    let (mut written, mut documented) = (BTreeSet::new(), BTreeSet::new());
    keys(&toml::from_str(&to_toml(&MachineConfig::default()).unwrap()).unwrap(), "", &mut written);
    keys(&toml::from_str(&example()).unwrap(), "", &mut documented);
    let missing: Vec<_> = written.difference(&documented).collect();
    assert!(missing.is_empty(), "examples/machines/default.toml lacks {missing:?}");
    for p in interp_core::config::PARAMS.iter().filter(|p| p.number != 3401) {
        assert!(documented.contains(&format!("parameters.{}", p.number)), "parameter {}", p.number);
    }
}

/// The brief's machine: every kind of field set away from the defaults.
const SHOP: &str = r#"
gcode_system = "B"
increment_system = "IS-C"
input = "least_increment"
diameter_programming = true
rapid_independent = true
tool_count = 8
reference = [{ x = 300, z = 250 }, { x = 200.5, z = 100 }]
user_m_codes = [{ m = 50, timing = "after" }, { m = 51, timing = "before" }]

[axes.x]
min = -10.0
max = 320.0
rapid = 6000
max_feed = 4000
accel = 400

[axes.z]
min = -600
max = 300
rapid = 8000

[axes.c]
min = 0
max = 360
rapid = 36000
max_feed = 7200
accel = 1000

[work_offsets]
g54 = { x = 0, z = -150.0 }
g59 = { z = -99.5 }
external = { x = 0.2, z = 0.1 }

[[offsets]]
number = 1
x = -120.5
z = 30.2
x_wear = 0.02
z_wear = 0
radius = 0.4
tip = 3

[spindle]
max_rpm = 4000
css_min_rpm = 60
gear_max_rpm = [800, 1600, 3000, 0]

[parameters]
5147 = 2.0
5130 = 10
6023 = 4500
"#;

#[test]
fn values_are_converted_to_internal_units() {
    let cfg = parse(SHOP).unwrap();
    assert_eq!(cfg.gcode_system, GCodeSystem::B);
    assert_eq!(cfg.increments, IncrementSystem::IsC);
    assert!(!cfg.params.flag(Param::CalculatorInput));
    assert!(cfg.rapid_independent);
    assert_eq!(cfg.tool_count, 8);
    // X in the file is a diameter, inside a radius; rates are not halved.
    let x = cfg.axis(Axis::X);
    assert_eq!(
        (x.min, x.max, x.rapid_per_min, x.max_feed_per_min),
        (-5_000_000, 160_000_000, 6_000_000_000, 4_000_000_000)
    );
    assert_eq!(x.accel_per_s2, 400_000_000);
    // Z keeps the built-in values not given; C exists now.
    assert_eq!(cfg.axis(Axis::Z).max_feed_per_min, MachineConfig::default().axis(Axis::Z).max_feed_per_min);
    assert!(cfg.axis(Axis::C).present && !cfg.axis(Axis::Y).present);
    assert_eq!(cfg.axis(Axis::C).max, 360_000_000);
    // Two reference positions given: 3 and 4 equal the first.
    let r1 = Pos::xz(150_000_000, 250_000_000);
    assert_eq!(cfg.reference, [r1, Pos::xz(100_250_000, 100_000_000), r1, r1]);
    assert_eq!(cfg.work_offsets[0], Pos::xz(0, -150_000_000));
    assert_eq!(cfg.work_offsets[5], Pos::xz(0, -99_500_000));
    assert_eq!(cfg.external_offset, Pos::xz(100_000, 100_000));
    let t = cfg.tools.get(1).unwrap();
    assert_eq!((t.x, t.z, t.x_wear, t.z_wear, t.radius, t.tip), (-60_250_000, 30_200_000, 10_000, 0, 400_000, 3));
    assert_eq!(
        (cfg.spindle.max_rpm, cfg.spindle.css_min_rpm, cfg.spindle.gear_max_rpm),
        (4000, 60, [800, 1600, 3000, 0])
    );
    assert_eq!(cfg.user_m(50).map(|u| u.timing), Some(MTiming::After));
    assert_eq!(cfg.user_m(51).map(|u| u.timing), Some(MTiming::Before));
    assert_eq!(cfg.params.get(Param::RoughingDepth), 2_000_000);
    assert_eq!(cfg.params.get(Param::MaxCuttingFeed), 4_500_000_000);
}

#[test]
fn a_machine_written_back_reads_the_same() {
    let cfg = parse(SHOP).unwrap();
    let text = to_toml(&cfg).unwrap();
    assert_eq!(parse(&text), Ok(cfg));
    let default = MachineConfig::default();
    assert_eq!(parse(&to_toml(&default).unwrap()), Ok(default));
}

#[test]
fn lathe_machine_prints_the_machine_in_force() {
    let m = scratch("machine-print.toml", SHOP);
    let o = lathe(&["machine", "--machine", &m]);
    assert_eq!(status(&o), 0);
    assert_eq!(parse(&stdout(&o)), parse(SHOP));
}

/// The error `parse` gives for `text`.
fn error(text: &str) -> String {
    parse(text).unwrap_err()
}

#[test]
fn mistakes_are_named() {
    assert!(error("[axes.x]\nrapdi = 5\n").contains("unknown field `rapdi`"));
    assert!(error("gcode_system = \"D\"\n").contains("unknown variant `D`"));
    assert_eq!(
        error("[parameters]\n9999 = 1\n5147 = 2\n12 = 0\n"),
        "unknown parameter number(s) 12, 9999 (docs/PARAMETERS.md lists them all)"
    );
    assert_eq!(error("[parameters]\n5152 = 2\n"), "parameters.5152 = 2 must be 0 or 1");
    assert_eq!(error("[parameters]\n5142 = 1.5\n"), "parameters.5142 = 1.5 must be a whole number, 0 or more");
    assert_eq!(
        error("input = \"calculator\"\n[parameters]\n3401 = 1\n"),
        "`input` and parameter 3401 set the same thing; give one of them"
    );
    assert_eq!(error("[axes.y]\nmin = -50\nmax = 50\n"), "axes.y: rapid, max_feed and accel must be positive");
    assert_eq!(error("[axes.x]\nmin = 400\n"), "axes.x: min must be below max");
    assert_eq!(error("[axes.z]\nmax = 1e300\n"), "axes.z.max = 1e300 is out of range");
    assert_eq!(error("reference = []\n"), "reference: give 1 to 4 positions, not 0");
    assert_eq!(error("[[offsets]]\nnumber = 33\n"), "offsets number 33: must be 1 to 32");
    assert_eq!(error("[[offsets]]\nnumber = 2\ntip = 10\n"), "offsets number 2: tip must be 0 to 9");
    assert_eq!(error("[[offsets]]\nnumber = 2\n[[offsets]]\nnumber = 2\n"), "offsets number 2: given twice");
    assert_eq!(error("user_m_codes = [{ m = 8, timing = \"before\" }]\n"), "user_m_codes: M08 is a standard M code");
    let mill = "kind = \"mill\"\ndiameter_programming = false\ntool_changer = \"automatic\"\n";
    assert_eq!(
        error(&format!("{mill}tool_count = 40\n")),
        "tool_count = 40: the automatic tool changer's outputs name tools 1 to 31"
    );
    assert!(parse(&format!("{mill}tool_count = 31\n")).is_ok());
}

#[test]
fn a_missing_or_broken_machine_file_exits_2_naming_it() {
    let p = scratch("machine-prog.nc", "M30\n");
    let o = lathe(&["sim", &p, "--machine", "/nonexistent/machine.toml"]);
    assert_eq!(status(&o), 2);
    assert!(stderr(&o).starts_with("lathe: cannot read /nonexistent/machine.toml: "));
    let m = scratch("machine-broken.toml", "[axes.x\n");
    let o = lathe(&["sim", &p, "--machine", &m]);
    assert_eq!(status(&o), 2);
    assert!(stderr(&o).starts_with(&format!("lathe: machine file {m}: TOML parse error at line 1")), "{}", stderr(&o));
}

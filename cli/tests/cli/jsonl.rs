//! `lathe sim --format jsonl`: exact records of small programs.

use interp_core::canon::{Action, Canon, Endpoint, SpindleDir, SpindleSpeed, TapMove, ThreadMove, ThreadSync};
use interp_core::{MachineConfig, Pos};
use serde_json::Value;

use super::{lathe, scratch, status, stdout};

const PROGRAM: &str = "%\nO0001\nG00 X20 Z25\nG01 X60 Z7 F500\nG02 X50 Z-30 R25\nG04 X0.5\nM03 S800\n\
                       G99 G01 Z-40 F0.15\nT0202\nG00 X100 Z50\nM30\n%\n";

/// Work zero at machine Z-150; offset 2 shifts X by 1 mm on the diameter and Z by 2 mm.
const MACHINE: &str = "[work_offsets]\ng54 = { z = -150.0 }\n[[offsets]]\nnumber = 2\nx = 1.0\nz = 2.0\n";

#[test]
fn every_action_is_one_line_with_exact_values() {
    let o = lathe(&[
        "sim",
        &scratch("jsonl.nc", PROGRAM),
        "--format",
        "jsonl",
        "--machine",
        &scratch("jsonl.toml", MACHINE),
    ]);
    assert_eq!(status(&o), 0);
    let expected = [
        r#"{"line":3,"kind":"rapid","x":20.0,"z":25.0,"f":null,"feed_mode":"per_min","rpm":null,"css":null,"exact_stop":true,"independent":false,"mx":20.0,"mz":-125.0}"#,
        r#"{"line":4,"kind":"linear","x":60.0,"z":7.0,"f":500.0,"feed_mode":"per_min","rpm":null,"css":null,"exact_stop":false,"mx":60.0,"mz":-143.0}"#,
        r#"{"line":5,"kind":"arc","x":50.0,"z":-30.0,"cx":87.957018,"cz":-13.726825,"cw":true,"f":500.0,"feed_mode":"per_min","rpm":null,"css":null,"exact_stop":false,"full_circle":false,"plane":"zx","mx":50.0,"mz":-180.0}"#,
        r#"{"line":6,"kind":"dwell","seconds":0.5}"#,
        r#"{"line":7,"kind":"spindle","dir":"cw","rpm":800,"css":null}"#,
        r#"{"line":8,"kind":"linear","x":50.0,"z":-40.0,"f":0.15,"feed_mode":"per_rev","rpm":800,"css":null,"exact_stop":false,"mx":50.0,"mz":-190.0}"#,
        r#"{"line":9,"kind":"tool","tool":2,"offset":2}"#,
        r#"{"line":10,"kind":"rapid","x":100.0,"z":50.0,"f":null,"feed_mode":"per_rev","rpm":800,"css":null,"exact_stop":true,"independent":false,"mx":101.0,"mz":-98.0}"#,
        r#"{"line":11,"kind":"end","rewind":true}"#,
    ];
    assert_eq!(stdout(&o).lines().collect::<Vec<_>>(), expected);
}

#[test]
fn the_arc_centre_is_25_mm_from_both_ends() {
    let o = lathe(&["sim", &scratch("centre.nc", PROGRAM), "--format", "jsonl"]);
    let arc: Value =
        stdout(&o).lines().map(|l| serde_json::from_str(l).unwrap()).find(|v: &Value| v["kind"] == "arc").unwrap();
    let (cx, cz) = (arc["cx"].as_f64().unwrap() / 2.0, arc["cz"].as_f64().unwrap());
    // From (X60, Z7) to (X50, Z-30): radii 30 and 25.
    for (x, z) in [(30.0, 7.0), (25.0, -30.0)] {
        let r = ((x - cx) * (x - cx) + (z - cz) * (z - cz)).sqrt();
        assert!((r - 25.0).abs() < 2e-6, "radius {r}");
    }
    // G02 going to -Z runs under its centre (clockwise with Z right, X up).
    assert!(cx > 30.0);
}

#[test]
fn surface_speed_follows_the_diameter_as_in_figure_2_73() {
    let program = "M3 G96 S300; G0 X100 Z100; G0 X50 Z0; G1 W-30 F200; X80 W-20 F150; G0 X100 Z100; M30;\n";
    let o = lathe(&["sim", &scratch("fig273.nc", program), "--format", "jsonl"]);
    assert_eq!(status(&o), 0);
    let moves: Vec<Value> = stdout(&o)
        .lines()
        .map(|l| serde_json::from_str::<Value>(l).unwrap())
        .filter(|v| v["kind"] == "rapid" || v["kind"] == "linear")
        .collect();
    let rpm: Vec<u64> = moves.iter().map(|v| v["rpm"].as_u64().unwrap()).collect();
    assert_eq!(rpm, [955, 1910, 1910, 1194, 955]);
    assert!(moves.iter().all(|v| v["css"] == 300.0));
}

fn speed() -> SpindleSpeed {
    SpindleSpeed { rpm: Some(500), css: None, max_rpm: 3000 }
}

fn endpoint(x_radius_nm: i64, z_nm: i64) -> Endpoint {
    Endpoint { machine: Pos::xz(x_radius_nm, z_nm), work: Pos::xz(x_radius_nm, z_nm) }
}

#[test]
fn thread_and_tap_records_carry_lead_and_synchronisation() {
    let cfg = MachineConfig::default();
    let thread = Action::Thread(ThreadMove {
        to: endpoint(14_350_000, -30_000_000),
        lead: 1_500_000,
        lead_delta: 0,
        start_udeg: 180_000_000,
        sync: ThreadSync::Index,
        spindle: speed(),
    });
    let tap =
        Action::Tap(TapMove { to: endpoint(0, -20_000_000), lead: 1_250_000, dir: SpindleDir::Cw, spindle: speed() });
    let json = |action| serde_json::to_string(&lathe::jsonl::record(&Canon { line: 7, action }, &cfg)).unwrap();
    assert_eq!(
        json(thread),
        r#"{"line":7,"kind":"thread","x":28.7,"z":-30.0,"lead":1.5,"start_deg":180.0,"sync":"index","lead_delta":0.0,"rpm":500,"mx":28.7,"mz":-30.0}"#
    );
    assert_eq!(
        json(tap),
        r#"{"line":7,"kind":"tap","x":0.0,"z":-20.0,"lead":1.25,"dir":"cw","rpm":500,"mx":0.0,"mz":-20.0}"#
    );
}

/// On a mill every move record carries work `y` and machine `my` (G54 of
/// examples/machines/mill.toml is X-300 Y-200 Z-250): rapids, lines, arcs and
/// the rigid tap of a hole cycle alike.
#[test]
fn a_mill_move_carries_machine_y() {
    let program = "O0001\nG90 G54 G17 G00 X10. Y-20. Z5.\nG01 Y-30. F200\nG02 X20. Y-40. R10.\n\
                   M29 S500\nG99 G84 X30. Y-50. Z-10. R2. F500\nG80\nM30\n";
    let o = lathe(&[
        "sim",
        &scratch("jsonl_mill.nc", program),
        "--format",
        "jsonl",
        "--machine",
        concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/machines/mill.toml"),
    ]);
    assert_eq!(status(&o), 0, "{}", stdout(&o));
    let out = stdout(&o);
    let moves: Vec<Value> = out
        .lines()
        .map(|l| serde_json::from_str::<Value>(l).unwrap())
        .filter(|v| ["rapid", "linear", "arc", "tap"].contains(&v["kind"].as_str().unwrap()))
        .collect();
    for kind in ["rapid", "linear", "arc", "tap"] {
        assert!(moves.iter().any(|v| v["kind"] == kind), "no {kind} in {out}");
    }
    for v in &moves {
        let (y, my) = (v["y"].as_f64().unwrap(), v["my"].as_f64().unwrap());
        assert!((my - (y - 200.0)).abs() < 1e-9, "my is not y + G54's Y: {v}");
        assert!((v["mx"].as_f64().unwrap() - (v["x"].as_f64().unwrap() - 300.0)).abs() < 1e-9, "{v}");
    }
    // Key order: the machine coordinates end the record, Y between X and Z.
    let first = out.lines().find(|l| l.contains("\"rapid\"")).unwrap();
    assert!(first.ends_with(r#""mx":-290.0,"my":-220.0,"mz":-245.0}"#), "{first}");
    let arc = out.lines().find(|l| l.contains("\"arc\"")).unwrap();
    assert!(arc.contains(r#""mx":-280.0,"my":-240.0,"mz":-245.0"#), "{arc}");
}

//! docs/ALARMS.md and docs/PARAMETERS.md are exactly what `lathe alarms` and
//! `lathe params` print, so they cannot drift from the interpreter's tables.

use super::{lathe, status, stdout};

/// Compares a committed file with the command's output.
fn assert_generated(file: &str, command: &str) {
    let path = format!("{}/../docs/{file}", env!("CARGO_MANIFEST_DIR"));
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    let o = lathe(&[command]);
    assert_eq!(status(&o), 0);
    assert!(
        committed == stdout(&o),
        "docs/{file} differs from `lathe {command}`; regenerate it: cargo run -p lathe -- {command} > docs/{file}"
    );
}

#[test]
fn alarms_md_is_generated_from_the_catalog() {
    assert_generated("ALARMS.md", "alarms");
}

#[test]
fn parameters_md_is_generated_from_the_table() {
    assert_generated("PARAMETERS.md", "params");
}

#[test]
fn every_alarm_code_and_parameter_has_a_row() {
    let alarms = stdout(&lathe(&["alarms"]));
    for e in interp_core::alarm::CATALOG {
        assert!(alarms.contains(&format!("\n| {:04} | {} |", e.code, e.title)), "{}", e.code);
    }
    let params = stdout(&lathe(&["params"]));
    for p in interp_core::config::PARAMS {
        assert!(params.contains(&format!("\n| {} | ", p.number)), "{}", p.number);
    }
}

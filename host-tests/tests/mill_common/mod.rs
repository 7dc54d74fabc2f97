//! The machining centre every mill test runs on (`examples/machines/mill.toml`) and
//! two runners: a program that must run without an alarm, and the alarms of one.
//! Each test file uses what it needs.
#![allow(dead_code)]

use host_tests::{Run, run_with};
use interp_core::{MachineConfig, Panel};

pub mod plane;

/// examples/machines/mill.toml: G54 at X-300 Y-200 Z-250, H1 100 mm, D1 5 mm …
pub fn mill() -> MachineConfig {
    lathe::machine::parse(include_str!("../../../examples/machines/mill.toml")).expect("mill.toml parses")
}

/// Runs `text` on the mill and asserts it raised no alarm.
pub fn go(text: &str) -> Run {
    let r = run_with(text, mill(), Panel::default());
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    r
}

/// The alarms of `text` on the mill, as (line, code).
pub fn alarms(text: &str) -> Vec<(u32, u16)> {
    run_with(text, mill(), Panel::default()).alarm_codes()
}

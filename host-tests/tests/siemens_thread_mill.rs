//! SINUMERIK thread milling and the setting cycles on the mill (seed 001
//! chapter 3): CYCLE90 (lines 3538-3772), CYCLE800 (7391-7790, 9188-9260).
//! Geometry is computed here from the document's formulas and compared with the
//! actions the interpreter emits.

mod mill_common;

use host_tests::{Run, run_with};
use interp_core::config::Language;
use interp_core::{MachineConfig, Panel};

fn cfg() -> MachineConfig {
    MachineConfig { language: Language::Siemens, ..mill_common::mill() }
}

fn siemens(text: &str) -> Run {
    run_with(text, cfg(), Panel::default())
}

const HEAD: &str = "G17 G0 G90 X0 Y0 Z20 F200 S500 M3 T1 D1\n";

/// CYCLE800 on a board without swivel kinematics (lines 9197, 12241): every call
/// that would swivel raises 61180 on its line and moves nothing; `CYCLE800()`
/// and `_TC="0"` deselect (lines 7517, 7633) and are accepted.
#[test]
fn cycle800_swivels_raise_61180_and_deselect_is_accepted() {
    let before = siemens(&format!("{HEAD}M30\n"));
    assert!(before.alarms.is_empty(), "{:?}", before.alarms);
    for call in [
        "CYCLE800(1, \"\", 0, 57, 0, 0, 0, 0, 0, 0, 0, 0, -1)",
        "CYCLE800(1,\"\",0,57,0,40,0,-45,0,0,0,0,-1)",
        "CYCLE800(0, \"HEAD1\", 0, 27, 0, 0, 0, 0, 30, 0, 0, 0, 0, 0)",
        "CYCLE800(2, \"\", 1, 0, 10, 0, 0, 0, 0, 90, 0, 0, 0, 1)",
    ] {
        let r = siemens(&format!("{HEAD}{call}\nM30\n"));
        assert_eq!(r.alarm_codes(), vec![(2, 61180)], "{call}");
        assert_eq!(r.actions.len(), before.actions.len(), "{call} moved");
    }
    for call in ["CYCLE800()", "CYCLE800(1, \"0\", 0, 57, 0, 0, 0, 0, 0, 0, 0, 0, -1)", "CYCLE800(, \"0\")"] {
        let r = siemens(&format!("{HEAD}{call}\nG1 X5\nM30\n"));
        assert!(r.alarms.is_empty(), "{call}: {:?}", r.alarms);
        let moved = siemens(&format!("{HEAD}G1 X5\nM30\n"));
        assert_eq!(r.kinds(), moved.kinds(), "{call} changed the actions");
    }
}

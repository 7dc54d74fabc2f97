//! Bad input on a machining centre (issue 20): what FANUC 0i-M refuses gets its
//! alarm with the line and no motion from the block, in words true on a mill (no
//! turret, no tool nose, no G99 feed per revolution); what FANUC 0i-M accepts
//! (G43 without H, G43 with D) is accepted and does what FANUC does. Machine
//! positions are computed here from mill.toml: G54 at X-300 Y-200 Z-250, H1
//! 100 mm, H2 119.95 mm, D2 3.98 mm.

mod mill_common;

use host_tests::{Run, run_with};
use interp_core::canon::Canon;
use interp_core::{Alarm, MachineConfig, Panel};
use mill_common::{go, mill};

/// The first alarm of `text` on the mill, and the run (which goes on after it).
fn first_alarm(text: &str) -> (Alarm, Run) {
    let r = run_with(text, mill(), Panel::default());
    let a = *r.alarms.first().unwrap_or_else(|| panic!("no alarm from {text:?}"));
    (a, r)
}

/// Asserts `text` raises `code` on `line` and that no action came from that line.
fn refused(text: &str, line: u32, code: u16) -> (Alarm, Run) {
    let (a, r) = first_alarm(text);
    assert_eq!((a.line, a.code()), (line, code), "{a}");
    assert!(r.actions.iter().all(|c| c.line != line), "line {line} moved: {:?}", r.actions);
    (a, r)
}

/// Machine (X, Y, Z) mm at the end of the last move of `line`.
fn machine_at(r: &Run, line: u32) -> [f64; 3] {
    let c: &Canon = r.actions.iter().rev().find(|c| c.line == line && c.action.endpoint().is_some()).unwrap();
    let m = c.action.endpoint().unwrap().machine;
    [0, 1, 2].map(|i| m.0[i] as f64 / 1e6)
}

fn near(a: [f64; 3], b: [f64; 3]) {
    assert!(a.iter().zip(b).all(|(p, q)| (p - q).abs() < 1e-6), "{a:?} vs {b:?}");
}

/// The texts of alarms the lathe and the mill share speak of the mill's things
/// when a mill raises them: its tools (T above `tool_count`, not a turret), its
/// cutter radius compensation, its feed per revolution (G95; G99 is the R-level
/// return on a mill) and its taps.
#[test]
fn shared_alarms_speak_a_mills_words() {
    let cases: [(&str, u32, u16, &str); 7] = [
        ("G00 X-10. Y-10.\nT30 M06\nM30\n", 2, 30, "tool number T30 is not on this machine (T1-T24)"),
        (
            "G00 X-10. Y-10. Z10.\nG41 D1 G02 X-20. Y-20. R10. F100\nM30\n",
            2,
            34,
            "radius compensation cannot start up or cancel in an arc block",
        ),
        (
            "G00 X-10. Y-10. Z10.\nG41 D1 G01 X-20. Y-20. F100\nG18\nM30\n",
            3,
            37,
            "plane selection while radius compensation is active",
        ),
        (
            "G00 X-10. Y-10. Z10.\nG41 D1 G01 X-20. Y-20. F100\nG42 X-30.\nM30\n",
            3,
            3576,
            "G41/G42 reversed while radius compensation is active",
        ),
        (
            "G00 X-10. Y-10. Z10.\nG95 G01 X-20. F0.1\nM30\n",
            2,
            4013,
            "feed per revolution or tapping with the spindle stopped",
        ),
        (
            "G00 X-10. Y-10. Z10.\nG84 X-20. Y-20. Z-5. R2. F1.\nM30\n",
            2,
            4013,
            "feed per revolution or tapping with the spindle stopped",
        ),
        (
            "G00 X0 Y100.\nG51 X0 Y0 I2000 J1000\nG02 X100. Y0 I0 J-100. F500\nM30\n",
            3,
            20,
            "(R too small or I/J/K inconsistent)",
        ),
    ];
    for (text, line, code, words) in cases {
        let (a, _) = refused(text, line, code);
        let shown = a.to_string();
        assert!(shown.contains(words), "{shown}");
        for lathe_word in ["turret", "nose", "G99", "I/K"] {
            assert!(!shown.contains(lathe_word), "{shown}");
        }
    }
    // The lathe keeps its turret.
    let r = run_with("T9900\nM30\n", MachineConfig::default(), Panel::default());
    assert_eq!(r.alarms[0].to_string(), "line 1: alarm 0030: tool number 99 is not on the turret");
}

/// G51.1 names the axes it mirrors (FANUC's format `G51.1 IP_`); a bare G51.1
/// would mirror nothing while the programmer expects a mirror: 4006, and the
/// moves after it are not mirrored.
#[test]
fn g51_1_without_an_axis_is_refused() {
    let (a, r) = refused("G90 G00 X-10. Y-10. Z-10.\nG51.1\nG01 X-20. F100\nM30\n", 2, 4006);
    assert_eq!(a.to_string(), "line 2: alarm 4006: G51.1 needs address X");
    near(machine_at(&r, 3), [-320.0, -210.0, -260.0]);
    // With an axis it mirrors: X-20 about X0 is X20.
    let r = go("G90 G00 X-10. Y-10. Z-10.\nG51.1 X0\nG01 X-20. F100\nG50.1 X0\nM30\n");
    near(machine_at(&r, 3), [-280.0, -210.0, -260.0]);
    // Other frame codes are unchanged: G50.1 alone cancels every mirrored axis.
    let r = go("G51.1 X0 Y0\nG50.1\nG00 X-5. Y-5. Z0\nM30\n");
    near(machine_at(&r, 3), [-305.0, -205.0, -250.0]);
}

/// G52's words are the local origin's position in the work frame (seed 004
/// @2362 "IP-指令局部坐標系原點在工件坐標系中的位置"); under G91 there is no
/// such position: 4015 as for G53, with G91 in the block or in force, and the
/// local frame stays as it was.
#[test]
fn g52_under_g91_is_refused() {
    let (a, r) = refused("G90 G52 X5. Y5.\nG91 G52 X10. Y5.\nG90 G00 X0 Y0 Z0\nM30\n", 2, 4015);
    assert_eq!(
        a.to_string(),
        "line 2: alarm 4015: G52 takes absolute coordinates only (G90): the local origin in the work frame"
    );
    near(machine_at(&r, 3), [-295.0, -195.0, -250.0]);
    refused("G91 G00 X-1.\nG52 X10.\nM30\n", 2, 4015);
    // Under G90 it sets, and G52 X0 Y0 cancels, whatever was in force.
    let r = go("G90 G52 X5. Y5.\nG52 X10. Y-5.\nG00 X0 Y0 Z0\nG52 X0 Y0\nG00 X0 Y0\nM30\n");
    near(machine_at(&r, 3), [-290.0, -205.0, -250.0]);
    near(machine_at(&r, 5), [-300.0, -200.0, -250.0]);
}

/// FANUC 0i-M: H is a modal offset number. G43 (or G44) without H takes the H
/// in force — through G49 too —, and H0 (power-on) is a length of zero.
#[test]
fn g43_without_h_takes_the_h_in_force() {
    let r = go("G90 G00 X-10. Y-10. Z-10.\nG43 Z-8.\nG43 H1 Z-5.\nG43 Z-8.\nG49 Z-8.\nG43 Z-8.\nM30\n");
    near(machine_at(&r, 1), [-310.0, -210.0, -260.0]);
    near(machine_at(&r, 2), [-310.0, -210.0, -258.0]); // H0: no length
    near(machine_at(&r, 3), [-310.0, -210.0, -155.0]); // H1: 100 mm
    near(machine_at(&r, 4), [-310.0, -210.0, -158.0]); // still H1
    near(machine_at(&r, 5), [-310.0, -210.0, -258.0]); // G49: no length
    near(machine_at(&r, 6), [-310.0, -210.0, -158.0]); // H1 again
}

/// D is the cutter radius row of G41/G42, never a length: `G43 D2` takes the
/// length of the H in force (FANUC 0i-M) and D2 waits for the next G41/G42,
/// which then offsets by row 2's radius as if it carried D2 itself.
#[test]
fn g43_with_d_keeps_h_and_sets_the_radius_row() {
    let r = go("G90 G00 X-10. Y-10. Z-10.\nG43 H1 Z-5.\nG43 D2 Z-6.\nM30\n");
    near(machine_at(&r, 3), [-310.0, -210.0, -156.0]); // H1's 100 mm, not row 2's length
    let contour = "G01 X-40. F200\nY-40.\nG40 X-10. Y-10.\nM30\n";
    let with_d_before = go(&format!("G90 G00 X-10. Y-10. Z-10.\nG43 H1 D2 Z-6.\nG41 G01 X-20. Y-20. F200\n{contour}"));
    let with_d_in_g41 = go(&format!("G90 G00 X-10. Y-10. Z-10.\nG43 H1 Z-6.\nG41 D2 G01 X-20. Y-20. F200\n{contour}"));
    assert_eq!(with_d_before.actions, with_d_in_g41.actions);
    // Row 2's radius is 3.98 mm: the X-40 leg runs 3.98 mm below Y-20 (G41, left
    // of the path going -X) and ends at the inner corner with the Y-40 leg, 3.98 mm
    // right of X-40.
    near(machine_at(&with_d_before, 4), [-300.0 - 40.0 + 3.98, -200.0 - 20.0 - 3.98, -250.0 - 6.0 + 100.0]);
}

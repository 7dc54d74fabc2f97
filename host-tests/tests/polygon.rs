//! Polygon turning G51.2/G50.2 (2.8): the words and alarms of the section, the
//! phase move, and the C axis (the tool spindle) following the simulated spindle
//! encoder at Q/P turns per turn from an index, checked against the counts here.

use host_tests::{kind_names, run_with};
use interp_core::axis::Axis;
use interp_core::{MachineConfig, Panel};
use sim::{Sim, SimOptions};

/// The machine of examples/machines/polygon.toml: C at 10 steps per degree.
fn machine() -> MachineConfig {
    lathe::machine::parse(include_str!("../../examples/machines/polygon.toml")).unwrap()
}

const REV: i64 = 3600;

#[test]
fn g51_2_starts_the_spindle_turns_c_to_the_phase_and_locks() {
    let r = run_with("G00 X50 Z2\nG51.2 P1 Q2 R60 S500\nG01 W-10 F200\nG50.2\nM30\n", machine(), Panel::default());
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    let k = kind_names(&r);
    let i = k.iter().position(|k| k == "polygon 2/1").unwrap();
    assert_eq!(k[i - 2], "spindle Cw Some(500)");
    assert_eq!(k[i - 1], "rapid");
    let phase = r.actions[i - 1].action.endpoint().unwrap().machine[Axis::C];
    assert_eq!(phase, 60_000_000, "C to R60");
    assert!(k.contains(&"polygon off".to_string()));
}

#[test]
fn m30_ends_polygon_turning_and_p_q_default_to_1() {
    let r = run_with("G51.2 S500\nG00 X50\nM30\n", machine(), Panel::default());
    let k = kind_names(&r);
    assert!(k.contains(&"polygon 1/1".to_string()), "{k:?}");
    let off = k.iter().position(|k| k == "polygon off").unwrap();
    assert_eq!(k[off + 1], "end true");
}

#[test]
fn alarms_of_2_8() {
    let cases: &[(&str, u32, u16)] = &[
        ("G51.2 P1 Q2 S300\nG00 C10\nM30\n", 2, 220),
        ("G51.2 P1 Q2 S300\nG12.1\nM30\n", 2, 221),
        ("G51.2 P1 Q2 S300\nM29 S100\nM30\n", 2, 221),
        ("G12.1\nG51.2 P1 Q2\nM30\n", 2, 221),
        ("G51.2 P0 Q2\nM30\n", 1, 4011),
        ("G51.2 P1 Q2 R360\nM30\n", 1, 4011),
        ("G51.2 P1 Q2 M03\nM30\n", 1, 4016),
    ];
    for &(text, line, code) in cases {
        let r = run_with(text, machine(), Panel::default());
        assert_eq!(r.alarm_codes().first(), Some(&(line, code)), "{text}");
    }
    // Without a C axis there is no tool spindle.
    let r = run_with("G51.2 P1 Q2\nM30\n", MachineConfig::default(), Panel::default());
    assert_eq!(r.alarm_codes(), vec![(1, 4047)]);
}

#[test]
fn c_follows_the_spindle_at_q_over_p_from_an_index_and_stops_on_a_whole_turn() {
    let cfg = machine();
    let cpr = i64::from(cfg.spindle.encoder_cpr);
    let mut sim = Sim::new(cfg, SimOptions::default()).unwrap();
    // P2 Q3: 1.5 tool turns per work turn; S600 for 3 s is about 30 work turns.
    let prog = "G51.2 P2 Q3 R60 S600\nG00 X50 Z2\nG04 X3.\nG50.2\nG00 X60\nM30\n";
    let mut checked = 0;
    let mut lock = None;
    let report = sim.run_program_with(prog, |s| {
        let c = Axis::C.index();
        if let Some((origin, base)) = s.core.polygon_lock() {
            lock = Some((origin, base));
            let n = s.spindle_count() - origin;
            if n > 0 && s.core.polygon_steps().is_some_and(|t| t > 0) {
                // Exactly Q/P of the spindle's counts, rounded: within one step
                // (the drive may still owe the step of this very count).
                let expect = base + (2 * n * 3 * REV + 2 * cpr) / (2 * 2 * cpr);
                assert!((s.axes[c].steps - expect).abs() <= 1, "{} vs {expect} after {n} counts", s.axes[c].steps);
                checked += 1;
            }
        }
    });
    assert!(report.alarms.is_empty(), "{:?}", report.alarms);
    assert!(checked > 2000, "{checked} periods checked");
    let (origin, base) = lock.unwrap();
    // Locked at an index, with C on the phase angle R60 there.
    assert_eq!((origin - sim.spindle_index()).rem_euclid(cpr), 0);
    assert_eq!(base.rem_euclid(REV), 600);
    // After G50.2 C stands on a whole turn from the lock: the same angle as before,
    // and the core counts it there again.
    let c = Axis::C.index();
    assert_eq!((sim.axes[c].steps - base).rem_euclid(REV), 0);
    assert!(sim.axes[c].steps - base >= 40 * REV, "{} turns", (sim.axes[c].steps - base) / REV);
    assert_eq!(sim.core.steps()[c], base);
    assert!(sim.core.polygon_steps().is_none());
}

#[test]
fn the_polygon_example_runs_in_the_simulator_with_c_back_on_its_angle() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/c_axis/polygon_g51_2.nc");
    let text = std::fs::read_to_string(path).unwrap();
    let mut sim = Sim::new(machine(), SimOptions::default()).unwrap();
    let report = sim.run_program(&text);
    assert!(report.alarms.is_empty(), "{:?}", report.alarms);
    let c = Axis::C.index();
    // R180 of the second G51.2 was the last phase: C stands on 180° (whole turns on).
    assert_eq!(sim.axes[c].steps.rem_euclid(REV), 1800);
    assert_eq!(sim.core.steps()[c], 1800);
    assert!(sim.axes.iter().all(|a| a.violations == 0));
}

#[test]
fn g51_2_under_g42_ends_the_held_move_first() {
    // The phase move of C is a temporary cancel: the held X50 move ends on its
    // normal before it, and the Z cut after it starts the offset up again.
    let mut cfg = machine();
    let row = cfg.tools.get_mut(1).unwrap();
    row.radius = 800_000;
    row.tip = 3;
    let r = run_with(
        "T0101\nG00 X60 Z2\nG42 G01 X50 F0.2\nG51.2 P1 Q2 R60 S500\nG01 Z-10\nG50.2\nG40 G00 X70\nM30\n",
        cfg,
        Panel::default(),
    );
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    let lines: Vec<u32> = r.actions.iter().map(|c| c.line).collect();
    assert!(lines.windows(2).all(|w| w[0] <= w[1]), "{lines:?}");
}

/// Note 7: in feed hold the work spindle and the tool spindle keep turning (their
/// speeds do not drop to 0): the path stops, C goes on following the encoder at
/// Q/P, and after cycle start the cut goes on.
#[test]
fn feed_hold_stops_the_path_but_not_the_two_spindles() {
    let cfg = machine();
    let cpr = i64::from(cfg.spindle.encoder_cpr);
    let mut sim = Sim::new(cfg, SimOptions::default()).unwrap();
    let prog = "G51.2 P2 Q3 R60 S600\nG00 X50 Z2\nG98 G01 W-20 F300\nG50.2\nM30\n";
    const S: u64 = 1_000_000_000;
    let (c, z) = (Axis::C.index(), Axis::Z.index());
    let mut held_z = None;
    let mut during_hold = 0;
    let mut hold_at = None;
    let report = sim.run_program_with(prog, |s| {
        let now = s.clock.0;
        let locked = s.core.polygon_lock();
        if hold_at.is_none() && locked.is_some() && s.axes[z].steps < 0 {
            hold_at = Some(now);
            s.core.feed_hold();
        }
        let Some(t0) = hold_at else { return };
        // After 0.5 s of braking the path stands; C still follows for 1 s more.
        if (t0 + S / 2..t0 + 3 * S / 2).contains(&now) {
            let z_now = s.axes[z].steps;
            assert_eq!(*held_z.get_or_insert(z_now), z_now, "the path stands in feed hold");
            let (origin, base) = locked.expect("still locked in feed hold");
            let n = s.spindle_count() - origin;
            let expect = base + (2 * n * 3 * REV + 2 * cpr) / (2 * 2 * cpr);
            assert!((s.axes[c].steps - expect).abs() <= 1, "C follows in feed hold");
            assert!(s.spindle.rpm() > 590.0, "the work spindle keeps its speed: {}", s.spindle.rpm());
            during_hold += 1;
        } else if now >= t0 + 3 * S / 2 {
            s.core.cycle_start();
        }
    });
    assert!(report.alarms.is_empty(), "{:?}", report.alarms);
    assert!(during_hold > 500, "{during_hold} periods checked in feed hold");
    // The cut went on after cycle start (W-20 from Z2 ends at Z-18).
    let held_z = held_z.expect("the path stood");
    assert!(sim.axes[z].steps < held_z, "{} after {held_z}", sim.axes[z].steps);
    assert_eq!(sim.machine_pos()[Axis::Z], -18_000_000);
    assert!(sim.core.polygon_steps().is_none());
}

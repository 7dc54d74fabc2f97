//! Program text, units, input modes, G-code systems, all-or-nothing and back-pressure.

use host_tests::{VecSink, kind_names, mm, path, run, run_with};
use interp_core::canon::{Canon, CanonSink, Full};
use interp_core::config::{GCodeSystem, Param};
use interp_core::units::Units;
use interp_core::{Axis, Interpreter, MachineConfig, Panel, Progress, SingleProgram};

#[test]
fn percent_o_number_comments_semicolons_and_lowercase() {
    let r = run("%\nO0001 (SHAFT)\nn10 g00 x20 z5 ; N20 G01 X30 F100 (cut; feed)\n\nN30 M30\n%\nG00 X99\n");
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    assert_eq!(path(&r), vec![(20.0, 5.0), (30.0, 5.0)]);
    assert_eq!(r.actions[1].line, 3, "both blocks of line 3 report line 3");
}

#[test]
fn running_off_the_end_without_m30_is_end_of_record_5010() {
    assert_eq!(run("G00 X10\n").alarm_codes(), vec![(2, 5010)]);
    assert_eq!(run("%\nG00 X10\n%\n").alarm_codes(), vec![(3, 5010)]);
    assert_eq!(run("O1\nG00 X10\nO2\nM30\n").alarm_codes(), vec![(3, 5010)]);
}

#[test]
fn optional_block_skip_follows_its_switch() {
    let text = "G00 X10\n/G00 X20\n/2 G00 X30\nM30\n";
    assert_eq!(path(&run(text)), vec![(10.0, 0.0), (20.0, 0.0), (30.0, 0.0)]);
    let panel = Panel { block_skip: 0b1, ..Panel::default() };
    assert_eq!(path(&run_with(text, MachineConfig::default(), panel)), vec![(10.0, 0.0), (30.0, 0.0)]);
    let panel = Panel { block_skip: 0b10, ..Panel::default() };
    assert_eq!(path(&run_with(text, MachineConfig::default(), panel)), vec![(10.0, 0.0), (20.0, 0.0)]);
}

#[test]
fn least_increment_input_parameter_3401() {
    let mut cfg = MachineConfig::default();
    cfg.params.set(Param::CalculatorInput, 0);
    let r = run_with("G00 X60000 Z-7.5\nG04 X1500\nG04 P200\nM30\n", cfg, Panel::default());
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    assert_eq!(path(&r), vec![(60.0, -7.5)]);
    assert_eq!(kind_names(&r)[1..3], ["dwell 1500", "dwell 200"]);
}

#[test]
fn g20_switches_to_inch_alone_and_before_any_move() {
    let r = run("G20\nG00 X1.0 Z-0.5\nG01 Z-1 F10\nM30\n");
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    assert_eq!(path(&r), vec![(25.4, -12.7), (25.4, -25.4)]);
    let interp_core::Action::Linear(m) = r.actions[1].action else { panic!() };
    assert_eq!(m.feed.value, mm(254.0), "F10 in/min");
    assert_eq!(r.interp.state().modal.units, Units::Inch);
    // Switching not alone, or after a move: alarms 4001 / 4002. Repeating the
    // units in force is harmless anywhere (CAM safety lines).
    let r = run("G20 G00 X1\nG00 X10\nG20\nG21 G40 G18\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(1, 4001), (3, 4002)]);
}

#[test]
fn inch_at_power_on_by_parameter_10() {
    let mut cfg = MachineConfig::default();
    cfg.params.set(Param::InchAtPowerOn, 1);
    let r = run_with("G00 X1\nM30\n", cfg, Panel::default());
    assert_eq!(path(&r), vec![(25.4, 0.0)]);
}

#[test]
fn power_on_modal_states_of_the_notes() {
    let r = run("M30\n");
    let m = r.interp.state().modal;
    assert_eq!(m.motion, interp_core::codes::GCode::Rapid);
    assert_eq!(m.plane, interp_core::canon::Plane::Zx);
    assert_eq!(m.feed_mode, interp_core::canon::FeedMode::PerMin);
    assert!(!m.css && !m.exact_stop_mode && m.work_frame == 0);
    assert_eq!(m.nose_comp, interp_core::codes::GCode::NoseCompOff);
    let mut cfg = MachineConfig::default();
    cfg.params.set(Param::InitialLinear, 1);
    cfg.params.set(Param::InitialPerRev, 1);
    cfg.params.set(Param::InitialFeed, 2);
    let r = run_with("M3 S100\nX10\nM30\n", cfg, Panel::default());
    let interp_core::Action::Linear(l) = r.actions[1].action else { panic!("{:?}", kind_names(&r)) };
    assert_eq!((l.feed.mode, l.feed.value), (interp_core::canon::FeedMode::PerRev, mm(2.0)));
}

#[test]
fn system_b_uses_g90_g91_g94_g95_and_g92_for_coordinates() {
    let cfg = MachineConfig { gcode_system: GCodeSystem::B, ..MachineConfig::default() };
    let r = run_with(
        "G00 X200 Z100\nG92 X100 Z50\nG91 G00 X-20 Z-5\nG90 G95 M3 S500 G01 X60 F0.2\nM30\n",
        cfg,
        Panel::default(),
    );
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
    assert_eq!(path(&r)[1..], [(80.0, 45.0), (60.0, 45.0)]);
    let cfg = MachineConfig { gcode_system: GCodeSystem::C, ..MachineConfig::default() };
    let r = run_with("G70\nG00 X1\nM30\n", cfg, Panel::default());
    assert_eq!(path(&r), vec![(25.4, 0.0)], "G70 is inch input in system C");
}

#[test]
fn g91_does_not_exist_in_system_a() {
    assert_eq!(run("G91 X10\nM30\n").alarm_codes(), vec![(1, 10)]);
}

#[test]
fn an_alarm_changes_nothing() {
    // Every word of the bad block is valid except Q: F, G99, G55, S, T and the
    // move must all be discarded with it.
    let good = run("G00 X10 Z10\nM30\n");
    let bad = run("G00 X10 Z10\nG99 G55 G01 X40 F0.3 S900 T0101 M08 Q5\nM30\n");
    assert_eq!(bad.alarm_codes(), vec![(2, 4005)]);
    assert_eq!(bad.interp.state(), good.interp.state());
    assert_eq!(kind_names(&bad), kind_names(&good));
}

#[test]
fn two_g_codes_of_one_group_duplicate_words_and_foreign_words() {
    let r = run("G00 G01 X10\nG01 X10 X20 F1\nG00 X10 R5\nG01 X1 K2 F1\nG01 X1 U2 F1\nD1\nG07\nM30\n");
    assert_eq!(r.alarm_codes(), vec![(1, 4003), (2, 4004), (3, 4005), (4, 4005), (5, 4020), (6, 9), (7, 10)]);
    let msg = r.alarms[0].to_string();
    assert_eq!(msg, "line 1: alarm 4003: G00 and G01 are of the same modal group");
}

#[test]
fn codes_not_implemented_yet_say_so() {
    // Every code of the manual runs now; a canned cycle typed in MDI still says so.
    let mut interp = interp_core::Interpreter::new(interp_core::MachineConfig::default());
    let mut sink = host_tests::VecSink::default();
    let e = interp.mdi(b"G90 X10 Z-5 F100", &interp_core::Panel::default(), &mut sink).unwrap_err();
    assert_eq!(e.code(), 4007);
    assert!(e.to_string().contains("canned cycles in MDI"), "{e}");
}

/// A sink that takes at most one action per step.
struct OneAtATime {
    got: Vec<Canon>,
    room: bool,
}

impl CanonSink for OneAtATime {
    fn push(&mut self, c: Canon) -> Result<(), Full> {
        if !self.room {
            return Err(Full);
        }
        self.room = false;
        self.got.push(c);
        Ok(())
    }
}

#[test]
fn a_full_sink_applies_back_pressure_and_loses_nothing() {
    let text = "G28 U0 W0\nM3 S500 M8\nG01 X10 Z-5 F100 M5 M9\nM30\n";
    let reference = run(text);
    let mut interp = Interpreter::new(MachineConfig::default());
    let mut sink = OneAtATime { got: Vec::new(), room: true };
    let mut blocked = 0;
    for _ in 0..100 {
        sink.room = true;
        match interp.step(&SingleProgram(text.as_bytes()), &Panel::default(), &mut sink).unwrap() {
            Progress::Ended => break,
            Progress::Blocked => blocked += 1,
            _ => {}
        }
    }
    assert!(blocked > 0);
    assert_eq!(sink.got, reference.actions);
}

#[test]
fn m00_pauses_until_cycle_start() {
    let text = "G00 X10 M00\nG00 X20\nM30\n";
    let mut interp = Interpreter::new(MachineConfig::default());
    let mut sink = VecSink::default();
    let store = SingleProgram(text.as_bytes());
    assert_eq!(interp.step(&store, &Panel::default(), &mut sink), Ok(Progress::Executed { line: 1 }));
    assert_eq!(interp.step(&store, &Panel::default(), &mut sink), Ok(Progress::Paused));
    assert_eq!(interp.step(&store, &Panel::default(), &mut sink), Ok(Progress::Paused));
    interp.cycle_start();
    assert_eq!(interp.step(&store, &Panel::default(), &mut sink), Ok(Progress::Executed { line: 2 }));
    assert_eq!(interp.state().pos[Axis::X], mm(10.0));
}

/// G290 switches the following blocks to SINUMERIK mode, in a block of its own
/// (docs/LANGUAGES.md); G291 is the FANUC-style dialect's own mode and changes
/// nothing there. Not alone: alarm 4016 (a code that must stand alone).
#[test]
fn g290_and_g291_stand_alone_and_switch_the_language() {
    assert!(run("G291\nG00 X10\nM30\n").alarms.is_empty());
    assert_eq!(run("G290 X10\nM30\n").alarm_codes(), vec![(1, 4016)]);
    assert_eq!(run("G00 G291\nM30\n").alarm_codes(), vec![(1, 4016)]);
    // After G290 the blocks are SINUMERIK blocks (siemens_language.rs has more):
    // `;` is a comment there, and the text ends without M30 (alarm 5010).
    let r = run("G00 X10\nN20 G290\nG0 X20 ; SINUMERIK comment\n");
    assert_eq!(path(&r), vec![(10.0, 0.0), (20.0, 0.0)]);
    assert_eq!(r.alarm_codes(), vec![(4, 5010)], "{:?}", r.alarms);
}

/// The mill's table holds no lathe cycle: G71 on a machining centre is alarm 0010,
/// never a lathe roughing cycle.
#[test]
fn a_lathe_code_on_a_mill_is_not_a_g_code() {
    let cfg = MachineConfig { kind: interp_core::config::MachineKind::Mill, ..MachineConfig::default() };
    let r = run_with("G71 U1 R1\nM30\n", cfg, Panel::default());
    assert_eq!(r.alarm_codes(), vec![(1, 10)]);
}

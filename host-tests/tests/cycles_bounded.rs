//! A canned cycle is validated completely before its first action, in bounded
//! chunks: every step returns after a bounded amount of work, even for a cycle of
//! thousands of moves, and an alarm on its last pass leaves no motion at all.

use host_tests::{VecSink, run};
use interp_core::{Action, Interpreter, MachineConfig, Panel, Progress, SingleProgram};

/// G75 grooving X125 → X40 in 0.5 mm pecks, columns every 0.5 mm from Z-20 to `z_end`.
fn groove(z_end: f64) -> String {
    format!("G00 X150 Z50 M3 S500\nG0 X125 Z-20\nG75 R0.2 F150\nG75 X40 Z{z_end} P500 Q500\nG0 X150 Z50\nM30\n")
}

/// Steps the interpreter until it ends; returns (steps that yielded while the
/// G75 block was being validated, the sink, the alarms).
fn drive(text: &str) -> (usize, VecSink, Vec<interp_core::Alarm>) {
    let mut interp = Interpreter::new(MachineConfig::default());
    let mut sink = VecSink::default();
    let mut alarms = vec![];
    let mut yielded = 0;
    for _ in 0..1_000_000 {
        match interp.step(&SingleProgram(text.as_bytes()), &Panel::default(), &mut sink) {
            Ok(Progress::Ended) => break,
            Ok(Progress::Yielded { line: 4 }) => yielded += 1,
            Ok(_) => {}
            Err(a) => alarms.push(a),
        }
    }
    (yielded, sink, alarms)
}

#[test]
fn a_long_cycle_is_validated_over_several_steps_then_delivered_whole() {
    let text = groove(-500.0);
    let (yielded, sink, alarms) = drive(&text);
    assert!(alarms.is_empty(), "{alarms:?}");
    let from_cycle = sink.0.iter().filter(|c| c.line == 4).count();
    assert!(from_cycle > 10_000, "{from_cycle} actions");
    // 128 actions are validated per step at most.
    assert!(yielded >= from_cycle / 128, "{yielded} validating steps for {from_cycle} actions");
    assert_eq!(sink.0, run(&text).actions, "the same actions as an unhurried run");
}

#[test]
fn an_alarm_on_the_last_pass_of_a_long_cycle_leaves_no_motion() {
    // The last columns pass the Z soft limit (-600 mm): alarm 0501 on the G75 block.
    let (yielded, sink, alarms) = drive(&groove(-620.0));
    assert_eq!(alarms.iter().map(|a| (a.line, a.code())).collect::<Vec<_>>(), vec![(4, 501)]);
    assert!(yielded > 10, "validated over {yielded} steps");
    assert!(sink.0.iter().all(|c| c.line != 4), "no action of the G75 block was delivered");
    let last = sink.0.iter().rev().find_map(|c| match c.action {
        Action::Rapid(m) => Some(m.to.work),
        _ => None,
    });
    assert_eq!(last.map(|w| w.0[2]), Some(50_000_000), "the program went on after the alarm from Z50");
}

//! Whatever the input, the interpreter never panics, and a block that raises an
//! alarm leaves the state exactly as it was.

use host_tests::VecSink;
use interp_core::config::{GCodeSystem, Param};
use interp_core::{Interpreter, MachineConfig, Panel, Progress, SingleProgram};
use proptest::prelude::*;

/// Runs a program to its end (bounded), checking the all-or-nothing rule on every alarm.
fn drive(text: &[u8], cfg: MachineConfig) {
    let mut interp = Interpreter::new(cfg);
    let mut sink = VecSink::default();
    let store = SingleProgram(text);
    for _ in 0..2_000 {
        let before = *interp.state();
        match interp.step(&store, &Panel::default(), &mut sink) {
            Ok(Progress::Ended) => return,
            Ok(Progress::Paused) => interp.cycle_start(),
            Ok(_) => {}
            Err(alarm) => {
                assert_eq!(*interp.state(), before, "alarm {alarm} changed the state");
                let _ = alarm.to_string();
            }
        }
    }
}

/// One word: an address letter (sometimes lowercase or a comma word) and a number
/// of any shape, including huge and malformed ones.
fn word() -> impl Strategy<Value = String> {
    let letter = prop::sample::select(b"ABCDEFGHIJKLMNOPQRSTUVWXYZgxzufm,/(%#[=".to_vec());
    let number = prop_oneof![
        (-1_000_000i64..1_000_000).prop_map(|v| v.to_string()),
        (-1e12f64..1e12).prop_map(|v| format!("{v}")),
        (0u32..1000, 0u32..10).prop_map(|(a, b)| format!("{a}.{b}")),
        Just("99999999999999999999".to_string()),
        Just("-.".to_string()),
        Just("".to_string()),
        Just("1.2.3".to_string()),
        Just("--5".to_string()),
    ];
    (letter, number).prop_map(|(l, n)| format!("{}{}", l as char, n))
}

fn machine(system: u8, calculator: bool) -> MachineConfig {
    let mut cfg = MachineConfig {
        gcode_system: [GCodeSystem::A, GCodeSystem::B, GCodeSystem::C][usize::from(system % 3)],
        ..MachineConfig::default()
    };
    cfg.params.set(Param::CalculatorInput, i64::from(calculator));
    cfg
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2_000, ..ProptestConfig::default() })]

    #[test]
    fn random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..400), sys in 0u8..3, calc: bool) {
        drive(&bytes, machine(sys, calc));
    }

    #[test]
    fn word_soup_never_panics(
        blocks in prop::collection::vec(prop::collection::vec(word(), 0..8), 0..30),
        sys in 0u8..3,
        calc: bool,
    ) {
        let text: String = blocks.iter().map(|b| b.join(" ") + "\n").collect();
        drive(text.as_bytes(), machine(sys, calc));
    }

    #[test]
    fn plausible_programs_never_panic(
        blocks in prop::collection::vec(
            (prop::sample::select(vec!["G00", "G01", "G02", "G03", "G04", "G28", "G30", "G50", "G52", "G53",
                "G96", "G97", "G98", "G99", "G20", "G21", "G54", "G59", "G61", "G64", "G09", "G17", "G18", "M03",
                "M05", "M08", "T0101", "T0202", "S", ""]),
             prop::collection::vec((prop::sample::select(b"XZUWIKRFSPT".to_vec()), -500i32..500), 0..4)),
            1..40),
    ) {
        let text: String = blocks
            .iter()
            .map(|(code, words)| {
                let w: Vec<String> = words.iter().map(|(l, v)| format!("{}{}", *l as char, v)).collect();
                format!("{code} {}\n", w.join(" "))
            })
            .collect();
        drive(text.as_bytes(), MachineConfig::default());
    }
}

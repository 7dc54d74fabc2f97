//! On-target tests: run on the emulated Cortex-M4F by
//! `cargo test --target thumbv7em-none-eabihf` in `m4-tests/`.
//!
//! A test is a plain `fn() -> Result<(), &'static str>`; add it to [`TESTS`].
#![no_std]
#![no_main]

use core::hint::black_box;

use cortex_m_rt::entry;
use heapless::Vec;
use interp_core::canon::{Action, Canon, CanonSink, Full, RecordingSink, ThreadSync};
use interp_core::lang::fanuc::macros::{MacroStatement, Variables};
use interp_core::lang::fanuc::parse::{Statement, read_statement};
use interp_core::{Alarm, Axis, Interpreter, MachineConfig, Panel, Progress, SingleProgram};
use m4_tests::{TestFn, run_tests, tests};

/// Every on-target test, run in this order.
const TESTS: &[(&str, TestFn)] = &tests![
    i64_arithmetic,
    f64_software_float_is_exact,
    f32_hardware_float,
    heapless_vec_reports_full,
    interpreter_figure_2_6_arcs,
    interpreter_figure_2_73_surface_speed,
    interpreter_alarm_changes_nothing,
    interpreter_figure_2_60_g76,
    macro_functions_match_the_host_bit_for_bit,
    macro_loop_through_the_interpreter,
    motion_core_runs_a_contour_to_its_exact_end,
    motion_thread_gearbox_counts_exactly,
    motion_g34_gearbox_counts_exactly,
];

#[entry]
fn main() -> ! {
    run_tests(TESTS)
}

/// Fails with `reason` unless `ok` holds.
fn check(ok: bool, reason: &'static str) -> Result<(), &'static str> {
    if ok { Ok(()) } else { Err(reason) }
}

/// 64-bit integers, which the M4 handles in register pairs and library calls
/// (`__aeabi_ldivmod` for division).
fn i64_arithmetic() -> Result<(), &'static str> {
    let a = black_box(-7_000_000_000_123_i64);
    let b = black_box(1_000_i64);
    check(a / b == -7_000_000_000, "division truncates toward zero")?;
    check(a % b == -123, "remainder takes the dividend's sign")?;
    check(a.div_euclid(b) == -7_000_000_001, "euclidean division")?;
    check(black_box(3_037_000_500_i64).checked_mul(3_037_000_500).is_none(), "overflow detected")?;
    check(black_box(u64::MAX) >> black_box(63) == 1, "64-bit shift across the register pair")
}

/// f64 runs in software on the M4; libm must give the same bits as on the host.
fn f64_software_float_is_exact() -> Result<(), &'static str> {
    let two = black_box(2.0_f64);
    check(libm::sqrt(two) == core::f64::consts::SQRT_2, "sqrt is correctly rounded")?;
    check(libm::atan2(black_box(1.0), black_box(1.0)) == core::f64::consts::FRAC_PI_4, "atan2(1, 1) is pi/4")?;
    check(libm::hypot(black_box(3.0), black_box(4.0)) == 5.0, "hypot(3, 4) is 5")?;
    check(black_box(0.1_f64) + black_box(0.2) == 0.300_000_000_000_000_04, "0.1 + 0.2 rounds like IEEE 754")?;
    check(libm::floor(black_box(-2.5)) == -3.0 && libm::round(black_box(2.5)) == 3.0, "floor and round")
}

/// f32 runs on the FPU, which cortex-m-rt enables at reset.
fn f32_hardware_float() -> Result<(), &'static str> {
    check(black_box(1.5_f32) * black_box(2.25) == 3.375, "FPU multiply")?;
    check(libm::sqrtf(black_box(2.0)) == core::f32::consts::SQRT_2, "f32 sqrt")
}

/// A full fixed-capacity vector hands the rejected element back instead of growing.
fn heapless_vec_reports_full() -> Result<(), &'static str> {
    let mut v: Vec<u8, 4> = Vec::new();
    for i in 0..4 {
        v.push(i).map_err(|_| "push below capacity")?;
    }
    check(v.push(4) == Err(4), "push at capacity returns the element")?;
    check(v.len() == 4 && v.is_full(), "length stays at capacity")
}

/// Runs `text` to its end on the default machine; returns the actions and the first alarm.
fn interpret(text: &[u8]) -> (Vec<Canon, 32>, Option<Alarm>, Interpreter) {
    let mut interp = Interpreter::new(MachineConfig::default());
    let mut sink = RecordingSink::<32>::new();
    let mut alarm = None;
    for _ in 0..200 {
        match interp.step(&SingleProgram(text), &Panel::default(), &mut sink) {
            Ok(Progress::Ended) => break,
            Ok(_) => {}
            Err(a) => {
                alarm.get_or_insert(a);
            }
        }
    }
    (sink.actions, alarm, interp)
}

/// Manual figure 2.6 on the M4: end points and the two arc centres (R15 ball end on
/// the axis at Z-15; R5 fillet at X32 Z-27), exact to the nanometre.
fn interpreter_figure_2_6_arcs() -> Result<(), &'static str> {
    let (actions, alarm, _) = interpret(
        b"N001 G0 X40 Z5\nN002 M03 S200\nN003 G01 X0 Z0 F900\nN005 G03 U24 W-24 R15\n\
          N006 G02 X26 Z-31 R5\nN007 G01 Z-40\nN008 X40 Z5\nN009 M30\n",
    );
    check(alarm.is_none(), "no alarm")?;
    let mut centers = actions.iter().filter_map(|c| match c.action {
        Action::Arc(a) => Some((a.center.work[Axis::X], a.center.work[Axis::Z], a.to.work[Axis::Z])),
        _ => None,
    });
    check(centers.next() == Some((0, -15_000_000, -24_000_000)), "R15 centre and end")?;
    check(centers.next() == Some((16_000_000, -27_000_000, -31_000_000)), "R5 centre and end")?;
    check(matches!(actions.last().map(|c| c.action), Some(Action::End { rewind: true })), "ends with M30")
}

/// Manual figure 2.73 on the M4: 955, 1910, 1910, 1194, 955 r/min under G96 S300.
fn interpreter_figure_2_73_surface_speed() -> Result<(), &'static str> {
    let (actions, alarm, _) =
        interpret(b"M3 G96 S300\nG0 X100 Z100\nG0 X50 Z0\nG1 W-30 F200\nX80 W-20 F150\nG0 X100 Z100\nM30\n");
    check(alarm.is_none(), "no alarm")?;
    let rpms: Vec<u32, 8> = actions
        .iter()
        .filter_map(|c| match c.action {
            Action::Rapid(m) | Action::Linear(m) => m.spindle.rpm,
            _ => None,
        })
        .collect();
    check(rpms.as_slice() == [955, 1910, 1910, 1194, 955], "speeds of figure 2.73")
}

/// A block with one wrong word raises its alarm on the M4 and changes nothing.
fn interpreter_alarm_changes_nothing() -> Result<(), &'static str> {
    let (_, _, good) = interpret(b"G00 X10 Z10\nM30\n");
    let (_, alarm, bad) = interpret(b"G00 X10 Z10\nG99 G55 G01 X40 F0.3 S900 Q5\nM30\n");
    check(alarm.map(|a| (a.line, a.code())) == Some((2, 4005)), "alarm 4005 on line 2")?;
    check(good.state() == bad.state(), "state unchanged")
}

/// Records where each index-synchronised thread pass starts (the X of the rapid
/// before it) and counts all actions.
struct Passes {
    last_x: i64,
    starts: Vec<i64, 8>,
    count: u32,
}

impl CanonSink for Passes {
    fn push(&mut self, c: Canon) -> Result<(), Full> {
        self.count += 1;
        match c.action {
            Action::Rapid(m) => self.last_x = m.to.work[Axis::X],
            Action::Thread(t) if t.sync == ThreadSync::Index => self.starts.push(self.last_x).map_err(|_| Full)?,
            _ => {}
        }
        Ok(())
    }
}

/// Manual figure 2.60 (G76 M68x6) on the M4: the cycle refills the outbox step by
/// step; pass depths 1.8, 1.8*sqrt(2), 1.8*sqrt(3), k-d = 3.58, then k = 3.68 twice
/// (radius from the crest X68), to the nanometre as on the host.
fn interpreter_figure_2_60_g76() -> Result<(), &'static str> {
    let text = b"M3 S300\nG00 X80 Z10\nG76 P020560 Q0.15 R0.1\nG76 X60.64 Z-62 P3.68 Q1.8 F6\nM30\n";
    let mut interp = Interpreter::new(MachineConfig::default());
    let mut sink = Passes { last_x: 0, starts: Vec::new(), count: 0 };
    for _ in 0..200 {
        match interp.step(&SingleProgram(text), &Panel::default(), &mut sink) {
            Ok(Progress::Ended) => break,
            Ok(_) => {}
            Err(_) => return Err("alarm"),
        }
    }
    check(
        sink.starts.as_slice() == [32_200_000, 31_454_416, 30_882_309, 30_420_000, 30_320_000, 30_320_000],
        "pass depths",
    )?;
    check(sink.count == 33, "actions: spindle, rapid, 6 passes of 5, end")
}

/// Macro expressions give the same f64 bits on the M4 (software float) as on the
/// host: the values were printed by the host build of the same code.
fn macro_functions_match_the_host_bit_for_bit() -> Result<(), &'static str> {
    const CASES: &[(&str, u64)] = &[
        ("#1=SIN[30]*2+SQRT[16]", 0x4014_0000_0000_0000), // 5.0 exactly
        ("#1=SIN[12.3456]", 0x3fcb_5e0e_d446_7e91),
        ("#1=COS[33.3]", 0x3fea_beef_145a_a617),
        ("#1=TAN[71.5]", 0x4007_e8d3_a968_38bd),
        ("#1=ASIN[0.3]", 0x4031_7525_7a72_ef10),
        ("#1=ATAN[1]/[3]", 0x4032_6f58_ce59_e23c),
        ("#1=EXP[2.5]", 0x4028_5d6f_d931_e0bb),
        ("#1=SQRT[2]*SQRT[3]", 0x4003_988e_1409_212f),
        ("#1=1/3", 0x3fd5_5555_5555_5555),
    ];
    let vars = Variables::new();
    let fmt = Interpreter::new(MachineConfig::default()).number_format();
    for &(text, bits) in CASES {
        let Ok(Statement::Macro(m)) = read_statement(black_box(text.as_bytes()), 1, &vars, &fmt) else {
            return Err("not read as a macro statement");
        };
        let MacroStatement::Assign { value: Some(x), .. } = m.statement else { return Err("not an assignment") };
        check(x.to_bits() == bits, text)?;
    }
    Ok(())
}

/// A WHILE loop run by the interpreter on the M4: the sum of 1..10 becomes a move.
fn macro_loop_through_the_interpreter() -> Result<(), &'static str> {
    let text = b"#1=0\n#2=1\nWHILE [#2 LE 10] DO1\n#1=#1+#2\n#2=#2+1\nEND1\nG00 X#1 Z[SIN[30]]\nM30\n";
    let store = SingleProgram(black_box(text));
    let mut interp = Interpreter::new(MachineConfig::default());
    let mut sink = RecordingSink::<8>::new();
    let panel = Panel::default();
    for _ in 0..100 {
        match interp.step(&store, &panel, &mut sink) {
            Ok(Progress::Ended) => break,
            Ok(_) => {}
            Err(_) => return Err("alarm"),
        }
    }
    check(interp.variables().get(1) == Ok(Some(55.0)), "sum of 1..10")?;
    let to = sink.actions.first().and_then(|c| c.action.endpoint()).ok_or("no move")?;
    check(to.work.0[0] == 27_500_000 && to.work.0[2] == 500_000, "X55 (radius 27.5 mm), Z0.5")
}

/// The motion core on the target: the program of figure 2.6 (lines and arcs)
/// interpreted into the core, every period's steps issued, ends exactly on the
/// programmed point with every step accounted for.
fn motion_core_runs_a_contour_to_its_exact_end() -> Result<(), &'static str> {
    use motion_core::motion::{Feedback, MotionCore, QUEUE};
    let cfg = MachineConfig::default();
    let text = b"G00 X0 Z0\nG01 X20 Z-10 F800\nG02 X40 Z-20 R10\nG03 X60 Z-30 I10 K0\nG01 Z-35\nM30\n";
    let mut interp = Interpreter::new(cfg.clone());
    let mut core: MotionCore<QUEUE> = MotionCore::new(&cfg, interp_core::Pos::ZERO).map_err(|_| "config")?;
    let (mut now, mut steps) = (0u64, [0i64; 4]);
    for _ in 0..200_000 {
        let _ = interp.step(&SingleProgram(text), &Panel::default(), &mut core);
        core.tick(now, Feedback::default());
        now += 1_000_000;
        for (axis, s) in steps.iter_mut().enumerate() {
            while let Some(e) = core.next_step(axis, now) {
                if let motion_core::stepgen::EdgeKind::Step(up) = e.kind {
                    *s += if up { 1 } else { -1 };
                }
            }
        }
        if core.ended() && core.is_idle() {
            break;
        }
    }
    check(core.ended(), "program ended")?;
    // X60 (radius 30 mm at 400 steps/mm), Z-35 (at 320 steps/mm).
    check(steps[0] == 12_000 && steps[2] == -11_200, "steps issued to the end point")?;
    check(core.steps() == steps, "step generator and issued steps agree")
}

/// The thread gearbox on the target: 2 mm lead at 5/32 step per count with a ramp;
/// after it Z is exactly round((count − sync) × 5/32) and the pass ends on its end.
fn motion_thread_gearbox_counts_exactly() -> Result<(), &'static str> {
    use motion_core::sync::{Gear, Leg, Ratio};
    let leg = Leg { start: [0; 4], end: [0, 0, -6_400, 0], long: 2 };
    let mut g = Gear::thread(leg, Ratio { n: 5, d: 32 }, 1_000, 1, 0).map_err(|_| "gear")?;
    let mut pos = [0i64; 4];
    for c in 1..60_000i64 {
        g.on_count(c);
        g.positions(&mut pos);
        if c > 1_000 && -pos[2] < 5_000 && -pos[2] != ((c - 500) * 5 + 16) / 32 {
            return Err("Z off the lead after the ramp");
        }
    }
    check(pos[2] == -6_400, "pass ends exactly on its end point")
}

/// The G34 gearbox on the target: F 2 mm growing by K 0.1 mm per revolution
/// (`Gearing::new` reduces in 128 bits); after the ramp Z is exactly
/// round((n1·c + n2·c²)/den) and the pass ends on its end point.
fn motion_g34_gearbox_counts_exactly() -> Result<(), &'static str> {
    use motion_core::sync::{Gear, Gearing, Leg};
    let g = Gearing::new(2_000_000, 100_000, 1, 3_125, 4_096).map_err(|_| "gearing")?;
    check(g == Gearing { n1: 163_840, n2: 1, den: 1_048_576 }, "F 2 K 0.1 on 3.125 um steps, 4096 counts")?;
    let leg = Leg { start: [0; 4], end: [0, 0, -20_000, 0], long: 2 };
    let mut gear = Gear::thread(leg, g, 1_000, 1, 0).map_err(|_| "gear")?;
    let mut pos = [0i64; 4];
    for m in 1..200_000i64 {
        gear.on_count(m);
        gear.positions(&mut pos);
        let c = m - 500;
        let ideal = (2 * (g.n1 * c + g.n2 * c * c) + g.den).div_euclid(2 * g.den);
        if m > 1_000 && -pos[2] < 18_000 && -pos[2] != ideal {
            return Err("Z off z(c) after the ramp");
        }
    }
    check(pos[2] == -20_000, "pass ends exactly on its end point")
}

//! SINUMERIK drilling patterns on the mill (seed 001 chapter 2.3, lines
//! 3084-3397): HOLES1, HOLES2 and CYCLE801 position with G0 to each hole in the
//! plane and call the modal drilling cycle there. The hole positions are computed
//! here from the document's formulas and compared with where the interpreter
//! drills (the work XY of each feed move down the drilling axis).

mod mill_common;

use host_tests::{Run, run_with};
use interp_core::canon::{Action, Canon};
use interp_core::config::Language;
use interp_core::interpreter::Progress;
use interp_core::{MachineConfig, Panel};

fn cfg() -> MachineConfig {
    MachineConfig { language: Language::Siemens, ..mill_common::mill() }
}

fn siemens(text: &str) -> Run {
    run_with(text, cfg(), Panel::default())
}

/// Where each hole is drilled: the work XY of every feed move (the drilling
/// cycle's infeed), rounded to µm.
fn holes(r: &Run) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = Vec::new();
    for c in &r.actions {
        if let (Action::Linear(_), Some(e)) = (c.action, c.action.endpoint()) {
            let p = (um(e.work.0[0]), um(e.work.0[1]));
            if out.last() != Some(&p) {
                out.push(p);
            }
        }
    }
    out
}

/// The rapid positions in the plane (work XY, rounded to µm), in order, with
/// repeats merged.
fn rapids_xy(actions: &[Canon]) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = Vec::new();
    for c in actions {
        if let (Action::Rapid(_), Some(e)) = (c.action, c.action.endpoint()) {
            let p = (um(e.work.0[0]), um(e.work.0[1]));
            if out.last() != Some(&p) {
                out.push(p);
            }
        }
    }
    out
}

fn um(nm: i64) -> f64 {
    (nm as f64 / 1000.0).round() / 1000.0
}

fn r3(v: f64) -> f64 {
    (v * 1000.0).round() / 1000.0
}

fn clean(r: &Run) {
    assert!(r.alarms.is_empty(), "{:?}", r.alarms);
}

fn alarms(text: &str) -> Vec<(u32, u16)> {
    siemens(text).alarm_codes()
}

/// HOLES1 (lines 3117-3160): hole k at (SPCA, SPCO) + (FDIS + k·DBH)·(cos STA1,
/// sin STA1), from the end nearer the tool.
fn row(spca: f64, spco: f64, sta1: f64, fdis: f64, dbh: f64, num: u32) -> Vec<(f64, f64)> {
    let a = sta1.to_radians();
    (0..num)
        .map(|k| {
            let d = fdis + f64::from(k) * dbh;
            (r3(spca + d * a.cos()), r3(spco + d * a.sin()))
        })
        .collect()
}

/// HOLES2 (lines 3286-3298): hole k at the centre + RAD·(cos, sin)(STA1 + k·INDA),
/// INDA = 360/NUM when 0.
fn circle(cpa: f64, cpo: f64, rad: f64, sta1: f64, inda: f64, num: u32) -> Vec<(f64, f64)> {
    let inda = if inda == 0.0 { 360.0 / f64::from(num) } else { inda };
    (0..num)
        .map(|k| {
            let a = (sta1 + f64::from(k) * inda).to_radians();
            (r3(cpa + rad * a.cos()), r3(cpo + rad * a.sin()))
        })
        .collect()
}

#[test]
fn holes1_row_from_the_first_hole_then_from_the_last() {
    let text = include_str!("../../examples/sinumerik/mill/holes1_row.mpf");
    let r = siemens(text);
    clean(&r);
    let expect = row(30.0, 20.0, 0.0, 10.0, 20.0, 5);
    let got = holes(&r);
    // The CYCLE81 pass: from the first hole (the tool at X30 Y20 is nearer it).
    assert_eq!(got[..5], expect[..]);
    // The CYCLE84 pass (tapping: its infeed is a tap move, not a feed line), the
    // row from the fifth hole: the rapids after N70.
    let n70_line = text.lines().position(|l| l.starts_with("N70")).expect("N70") as u32 + 1;
    let n70 = r.actions.iter().position(|c| c.line == n70_line).expect("N70 moves");
    let after: Vec<_> = rapids_xy(&r.actions[n70..]).into_iter().skip(1).collect();
    let mut rev = expect.clone();
    rev.reverse();
    assert_eq!(after, rev);
}

#[test]
fn holes1_at_an_angle_and_from_the_far_end() {
    let text = "G17 G90 G0 X0 Y0 Z50 S500 M3 F100 D1 T1\nMCALL CYCLE81(10, 0, 2, -5)\n\
                HOLES1(10, 5, 30, 4, 7.5, 4)\nMCALL\nG0 X200 Y200\nMCALL CYCLE81(10, 0, 2, -5)\n\
                HOLES1(10, 5, -150, 4, 7.5, 3)\nMCALL\nM30\n";
    let r = siemens(text);
    clean(&r);
    let mut expect = row(10.0, 5.0, 30.0, 4.0, 7.5, 4);
    // From (200, 200) the far end of the second row (STA1 -150) is nearer? The
    // first hole at distance 4 is nearer than the third at 19: from the first.
    let second = row(10.0, 5.0, -150.0, 4.0, 7.5, 3);
    let (d0, d2) = (dist((200.0, 200.0), second[0]), dist((200.0, 200.0), second[2]));
    if d2 < d0 {
        expect.extend(second.iter().rev());
    } else {
        expect.extend(second.iter());
    }
    assert_eq!(holes(&r), expect);
}

fn dist(a: (f64, f64), b: (f64, f64)) -> f64 {
    ((a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)).sqrt()
}

#[test]
fn holes1_grid_by_label_loop() {
    let r = siemens(include_str!("../../examples/sinumerik/mill/holes1_grid.mpf"));
    clean(&r);
    let mut expect = Vec::new();
    for line in 0..5 {
        expect.extend(row(30.0, 20.0 + 10.0 * f64::from(line), 0.0, 10.0, 10.0, 5));
    }
    // Each row starts where the last ended? The tool ends a row at X80 and the next
    // row's first hole X40 is farther than its last X80: the rows alternate.
    let mut got = holes(&r);
    assert_eq!(got.len(), 25);
    for line in 0..5 {
        let mut want = expect[line * 5..line * 5 + 5].to_vec();
        if line % 2 == 1 {
            want.reverse();
        }
        assert_eq!(got.drain(..5).collect::<Vec<_>>(), want, "row {line}");
    }
}

#[test]
fn holes2_circle_with_inda_left_out_and_given() {
    let r = siemens(include_str!("../../examples/sinumerik/mill/holes2_circle.mpf"));
    clean(&r);
    assert_eq!(holes(&r), circle(70.0, 60.0, 42.0, 45.0, 0.0, 4));
    // The cycle-support program (lines 873-888): nine holes 20° apart, radius 37.
    let text = "N100 G17 G0 G90 Z20 F2000 S500 M3 D1 T1\nN120 G0 G90 X50 Y50\n\
                N130 MCALL CYCLE82(10,0,2,0,30,5)\nN150 HOLES2(50,50,37,20,20,9)\nN170 MCALL\nM30\n";
    let r = siemens(text);
    clean(&r);
    assert_eq!(holes(&r), circle(50.0, 50.0, 37.0, 20.0, 20.0, 9));
    // A negative INDA runs clockwise.
    let text = "G17 G0 G90 X0 Y0 Z20 F200 S500 M3 D1 T1\nMCALL CYCLE81(10, 0, 2, -3)\n\
                HOLES2(0, 0, 25, 180, -45, 5)\nMCALL\nM30\n";
    let r = siemens(text);
    clean(&r);
    assert_eq!(holes(&r), circle(0.0, 0.0, 25.0, 180.0, -45.0, 5));
}

/// CYCLE801 (lines 3359-3397): the grid from the corner nearest the tool, row by
/// row (rows along the smaller spacing), each row back the way the last came.
#[test]
fn cycle801_grid_meanders_from_the_nearest_corner() {
    let r = siemens(include_str!("../../examples/sinumerik/mill/cycle801_grid.mpf"));
    clean(&r);
    // The mill starts at machine zero, work X300 Y200 (G54 at X-300 Y-200):
    // corner (70, 50) is nearest; rows (10 < 15) from there, meandering.
    let mut expect = Vec::new();
    for rr in (0..3).rev() {
        let cols: Vec<u32> = if rr % 2 == 0 { (0..5).rev().collect() } else { (0..5).collect() };
        for c in cols {
            expect.push((r3(30.0 + 10.0 * f64::from(c)), r3(20.0 + 15.0 * f64::from(rr))));
        }
    }
    assert_eq!(holes(&r), expect);
    // From beyond the far corner, with columns closer than rows swapped: spacing
    // 20 between columns, 5 between rows → column by column from (70, 30).
    let text = "G17 G0 G90 X100 Y100 Z20 F200 S500 M3 D1 T1\nMCALL CYCLE81(10, 0, 2, -3)\n\
                CYCLE801(30, 20, 0, 20, 5, 3, 3)\nMCALL\nM30\n";
    let r = siemens(text);
    clean(&r);
    let mut expect = Vec::new();
    for (i, c) in [2u32, 1, 0].iter().enumerate() {
        let rows: Vec<u32> = if i % 2 == 0 { vec![2, 1, 0] } else { vec![0, 1, 2] };
        for rr in rows {
            expect.push((r3(30.0 + 20.0 * f64::from(*c)), r3(20.0 + 5.0 * f64::from(rr))));
        }
    }
    assert_eq!(holes(&r), expect);
}

/// Bad calls stop on their line with the document's alarm and move nothing.
#[test]
fn alarms_of_the_patterns_move_nothing() {
    let head = "G17 G0 G90 X0 Y0 Z20 F200 S500 M3 D1 T1\nMCALL CYCLE81(10, 0, 2, -3)\n";
    for (call, code) in [
        ("HOLES1(0, 0, 0, 5, 5, 0)", 61103),
        ("HOLES1(0, 0, 0, 5, 5, -2)", 61103),
        ("HOLES1(0, 0, 0, 5, 5)", 61103),
        ("HOLES2(0, 0, 10, 0, 0, 0)", 61103),
        ("HOLES2(0, 0, 10, 0, 90, 5)", 61106),
        ("HOLES2(0, 0, 10, 0, -120, 4)", 61106),
        ("HOLES1(0, 0, 200, 5, 5, 3)", 12160),
        ("HOLES1(0, 0, -180, 5, 5, 3)", 12160),
        ("HOLES1(0, 0, 0, -5, 5, 3)", 12160),
        ("HOLES2(0, 0, -10, 0, 0, 3)", 12160),
        ("CYCLE801(0, 0, 0, -1, 5, 3, 3)", 12160),
    ] {
        let text = format!("{head}{call}\nM30\n");
        let r = siemens(&text);
        assert_eq!(r.alarm_codes(), vec![(3, code)], "{call}");
        let before = siemens(&format!("{head}M30\n"));
        assert_eq!(r.actions.len(), before.actions.len(), "{call} moved");
    }
    // A lathe (no Y: no drilling axis for G17's pattern): 61005.
    let lathe = MachineConfig { language: Language::Siemens, ..MachineConfig::default() };
    let r = run_with("G17 G0 X0 Z20\nHOLES1(0, 0, 0, 5, 5, 3)\nM30\n", lathe, Panel::default());
    assert_eq!(r.alarm_codes(), vec![(2, 61005)]);
    let _ = alarms;
}

/// Without a modal drilling cycle (lines 3095-3101): message 62100, the program
/// stops; NC start positions the pattern without drilling. CYCLE801 with no
/// columns: 62105 and nothing moves.
#[test]
fn without_mcall_62100_stops_then_positions_only() {
    let text = "G17 G0 G90 X0 Y0 Z20\nHOLES2(0, 0, 10, 0, 0, 4)\nG0 Z50\nM30\n";
    let mut interp = interp_core::Interpreter::new(cfg());
    interp.plug(&interp_siemens::SINUMERIK);
    let prog = interp_core::SingleProgram(text.as_bytes());
    let mut sink = host_tests::VecSink::default();
    let mut paused = 0;
    for _ in 0..10_000 {
        match interp.step(&prog, &Panel::default(), &mut sink) {
            Ok(Progress::Ended) => break,
            Ok(Progress::Paused) => {
                paused += 1;
                assert_eq!(interp.siemens.notice, Some((62100, 2)));
                interp.cycle_start();
            }
            Ok(_) => {}
            Err(a) => panic!("{a}"),
        }
    }
    assert_eq!(paused, 1);
    assert!(!sink.0.iter().any(|c| matches!(c.action, Action::Linear(_))), "nothing drilled");
    assert_eq!(rapids_xy(&sink.0)[1..], circle(0.0, 0.0, 10.0, 0.0, 0.0, 4)[..]);

    let text = "G17 G0 G90 X0 Y0 Z20\nMCALL CYCLE81(10, 0, 2, -3)\nCYCLE801(0, 0, 0, 5, 5, 0, 3)\nMCALL\nM30\n";
    let mut interp = interp_core::Interpreter::new(cfg());
    interp.plug(&interp_siemens::SINUMERIK);
    let prog = interp_core::SingleProgram(text.as_bytes());
    let mut sink = host_tests::VecSink::default();
    for _ in 0..10_000 {
        match interp.step(&prog, &Panel::default(), &mut sink) {
            Ok(Progress::Ended) => break,
            Ok(Progress::Paused) => {
                assert_eq!(interp.siemens.notice, Some((62105, 3)));
                interp.cycle_start();
            }
            Ok(_) => {}
            Err(a) => panic!("{a}"),
        }
    }
    assert!(!sink.0.iter().any(|c| matches!(c.action, Action::Linear(_))));
}

/// The cycle-support program (lines 873-888): a labelled HOLES2 drilled with
/// CYCLE82, then the same section repeated (REPEAT) under a tapping MCALL — the
/// second pass taps at the same nine positions. (The document's label 孔圆弧1 is
/// LOCH1 here: labels are ASCII names on this board.)
#[test]
fn a_repeated_pattern_section_taps_where_it_drilled() {
    let text = "N100 G17 G0 G90 Z20 F2000 S500 M3 D1 T1\nN120 G0 G90 X50 Y50\n\
                N130 MCALL CYCLE82(10,0,2,0,30,5)\nN140 LOCH1:\nN150 HOLES2(50,50,37,20,20,9)\n\
                N160 ENDLABEL:\nN170 MCALL\nN190 S400 M3\n\
                N200 MCALL CYCLE84(10,0,2,0,30,,3,5,0.8,180,300,500)\nN210 REPEAT LOCH1 ENDLABEL\n\
                N220 MCALL\nM30\n";
    let r = siemens(text);
    clean(&r);
    let expect = circle(50.0, 50.0, 37.0, 20.0, 20.0, 9);
    assert_eq!(holes(&r), expect);
    // After the last drilling feed: the tapping pass's positions.
    let drilled = r.actions.iter().rposition(|c| matches!(c.action, Action::Linear(_))).expect("drilled");
    assert!(r.actions[drilled..].iter().any(|c| matches!(c.action, Action::Tap(_))), "tapped");
    let tapped: Vec<_> = rapids_xy(&r.actions[drilled..]).into_iter().skip(1).collect();
    assert_eq!(tapped, expect);
}

/// MCALL of a subprogram (lines 3095-3099: the pattern calls whatever was called
/// modally): the subprogram runs whole at each hole before the next is approached.
#[test]
fn a_modally_called_subprogram_runs_at_each_hole() {
    let main = "G17 G0 G90 X0 Y0 Z20 F100 S500 M3 D1 T1\nMCALL SPOT\nHOLES1(10, 0, 0, 0, 10, 3)\nMCALL\nM30\n";
    let sub = "PROC SPOT\nG1 G91 Z-5\nG0 Z5\nG90\nRET\n";
    let mut m = Box::new(host_tests::Memory::new());
    let id = m.load_named(main.as_bytes(), Some(0)).expect("main program loads");
    m.load_named(sub.as_bytes(), None).expect("subprogram loads");
    let mut interp = interp_core::Interpreter::new(cfg());
    interp.select_main(id);
    let r = host_tests::run_interp(interp, &*m, &Panel::default(), 100_000);
    clean(&r);
    assert_eq!(holes(&r), row(10.0, 0.0, 0.0, 0.0, 10.0, 3));
    // Each hole: a rapid to it, the feed down, the rapid up — in that order.
    let kinds: Vec<char> = r
        .actions
        .iter()
        .filter_map(|c| match c.action {
            Action::Rapid(_) => Some('r'),
            Action::Linear(_) => Some('l'),
            _ => None,
        })
        .collect();
    assert_eq!(kinds.iter().collect::<String>(), "rrlrrlrrlr");
}

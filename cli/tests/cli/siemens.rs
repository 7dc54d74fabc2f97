//! SINUMERIK programs on the command line (issue 19): `.mpf`/`.spf` files and
//! `--lang`, subprograms from `--lib`, and the examples of `examples/sinumerik`
//! run to the positions their numbers give.

use super::{lathe, scratch, status, stderr, stdout};

/// `examples/sinumerik` of the repository.
const SINUMERIK: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/sinumerik");

/// `lathe sim … --format jsonl` as (kind initial, x, z) of every move, and the actions.
fn moves(args: &[&str]) -> (Vec<(char, f64, f64)>, Vec<serde_json::Value>) {
    let mut all = vec!["sim"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["--format", "jsonl"]);
    let o = lathe(&all);
    assert_eq!(status(&o), 0, "{}", stderr(&o));
    let actions: Vec<serde_json::Value> = stdout(&o).lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    let m = actions
        .iter()
        .filter(|v| ["rapid", "linear", "arc"].contains(&v["kind"].as_str().unwrap_or("")))
        .map(|v| {
            let k = v["kind"].as_str().unwrap().chars().next().unwrap();
            (k, v["x"].as_f64().unwrap(), v["z"].as_f64().unwrap())
        })
        .collect();
    (m, actions)
}

#[test]
fn the_language_tour_runs_its_loop_jumps_calls_and_cycle() {
    let main = format!("{SINUMERIK}/language_tour.mpf");
    let lib = format!("{SINUMERIK}/lib");
    let (m, actions) = moves(&[&main, "--lib", &lib]);
    let mut want = vec![('r', 50.0, 2.0)];
    // PASSES loop: PASS 0, 1, 2 -> Z = -PASS*STEP, X from DM+10 to R1-20.
    for pass in 0..3 {
        let z = -2.0 * f64::from(pass);
        want.extend([('l', 50.0, z), ('l', 20.0, z), ('r', 20.0, 2.0), ('r', 50.0, 2.0)]);
    }
    // GOTOF TURN skips X999; IC(-20); G2 CR=5; G3 I0 K-5 to AC(60).
    want.extend([('l', 40.0, 0.0), ('l', 40.0, -20.0), ('a', 50.0, -25.0), ('a', 60.0, -30.0)]);
    // SHOULDER(DM+20): Z-40, X=XEND+10; FASE (lib): G91 X2 Z-1.
    want.extend([('l', 60.0, -40.0), ('l', 70.0, -40.0), ('l', 72.0, -41.0)]);
    // CYCLE82(RTP 10, RFP 0, SDIS 2, DP -15, , DTB 1) on the centre line.
    want.extend([('r', 0.0, 10.0), ('r', 0.0, 2.0), ('l', 0.0, -15.0), ('r', 0.0, 2.0), ('r', 0.0, 10.0)]);
    assert_eq!(m, want);
    let arcs: Vec<(f64, f64)> = actions
        .iter()
        .filter(|v| v["kind"] == "arc")
        .map(|v| (v["cx"].as_f64().unwrap(), v["cz"].as_f64().unwrap()))
        .collect();
    assert_eq!(arcs, [(50.0, -20.0), (50.0, -30.0)], "CR=5 and I0 K-5 centres");
    let dwell: Vec<f64> =
        actions.iter().filter(|v| v["kind"] == "dwell").map(|v| v["seconds"].as_f64().unwrap()).collect();
    assert_eq!(dwell, [1.0]);
    assert!(actions.iter().all(|v| v["x"].as_f64() != Some(999.0)), "N100 is jumped over");
    // Without the library FASE is not in program memory: 14011 on its line, and
    // nothing of that block moved.
    let o = lathe(&["check", &main]);
    assert_eq!(status(&o), 1);
    assert!(stdout(&o).starts_with(&format!("{main}:26: alarm 14011: ")), "{}", stdout(&o));
}

#[test]
fn lang_selects_the_language_whatever_the_file_is_called() {
    let nc = scratch("siemens_lang.nc", "R1=5 ; an R parameter\nG0 X=R1*2 Z1\nM30\n");
    let (m, _) = moves(&[&nc, "--lang", "siemens"]);
    assert_eq!(m, [('r', 10.0, 1.0)]);
    // Read as FANUC, `R1=5` is no FANUC block.
    let o = lathe(&["check", &nc]);
    assert_eq!(status(&o), 1, "{}", stdout(&o));
    assert!(stdout(&o).starts_with(&format!("{nc}:1: alarm ")), "{}", stdout(&o));
    // A .mpf file read as FANUC with --lang fanuc.
    let mpf = scratch("fanuc_lang.mpf", "G00 X20 Z1\nG01 U-2 F100\nM30\n");
    let (m, _) = moves(&[&mpf, "--lang", "fanuc"]);
    assert_eq!(m, [('r', 20.0, 1.0), ('l', 18.0, 1.0)]);
    let o = lathe(&["check", &mpf]);
    assert_eq!(status(&o), 1, "U is no SINUMERIK address: {}", stdout(&o));
    assert!(stdout(&o).contains(":2: alarm 12550"), "{}", stdout(&o));
}

#[test]
fn cycle95_example_1_finishes_on_the_contour_of_its_subprogram() {
    // Seed 001 lines 10891-10922: KONTUR_1's points, finished at FF3 = 0.2 mm/rev.
    let (m, actions) = moves(&[&format!("{SINUMERIK}/turn_cycle95_kontur.mpf")]);
    let contour = [(37.0, 120.0), (40.0, 117.0), (40.0, 112.0)];
    let at = m.iter().rposition(|p| (p.1, p.2) == contour[0]).expect("the finishing pass reaches X37 Z120");
    let tail: Vec<(f64, f64)> = m[at..].iter().filter(|p| p.0 == 'l').map(|p| (p.1, p.2)).collect();
    assert_eq!(&tail[..3], &contour);
    let end = [
        (65.0, 87.0),
        (29.0, 77.0),
        (29.0, 62.0),
        (44.0, 58.0),
        (44.0, 52.0),
        (37.0, 41.0),
        (37.0, 35.0),
        (76.0, 35.0),
    ];
    assert_eq!(&tail[tail.len() - end.len()..], &end);
    let finish_feed: Vec<f64> =
        actions.iter().filter(|v| v["kind"] == "linear" && v["line"] == 7).filter_map(|v| v["f"].as_f64()).collect();
    assert_eq!(finish_feed.last(), Some(&0.2));
    // The tool ends where N30/N40 send it.
    assert_eq!(m.last(), Some(&('r', 81.0, 125.0)));
}

#[test]
fn cycle95_example_2_reads_its_contour_after_m02() {
    // Seed 001 lines 10929-10953: "ANFANG:ENDE" after N170 M02; DIAMOF, so X is a radius.
    let (m, _) = moves(&[&format!("{SINUMERIK}/turn_cycle95_labels.mpf")]);
    assert!(!m.is_empty());
    // Roughing only (VARI 1): nothing below the contour plus the allowances.
    let xmin = m.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
    assert!((xmin - 21.6).abs() < 1e-9, "X10 radius + FALX 0.8 = 10.8 radius = 21.6 diameter, got {xmin}");
    let o = lathe(&["check", &format!("{SINUMERIK}/turn_cycle95_labels.mpf")]);
    assert_eq!(status(&o), 0, "{}", stdout(&o));
}

#[test]
fn the_sinumerik_examples_check_clean() {
    for name in [
        "language_tour.mpf",
        "drill_cycle81.mpf",
        "drill_cycle82.mpf",
        "drill_cycle84.mpf",
        "drill_cycle840.mpf",
        "drill_cycle85.mpf",
        "drill_cycle86.mpf",
        "drill_cycle87.mpf",
        "drill_cycle88.mpf",
        "drill_cycle89.mpf",
        "drill_mcall_row.mpf",
        "turn_cycle95_kontur.mpf",
        "turn_cycle95_labels.mpf",
        "turn_cycle97.mpf",
        "turn_cycle98.mpf",
    ] {
        let path = format!("{SINUMERIK}/{name}");
        let o = lathe(&["check", &path, "--lib", &format!("{SINUMERIK}/lib")]);
        assert_eq!(status(&o), 0, "{name}: {}", stdout(&o));
        assert!(stdout(&o).ends_with("no alarms\n"), "{name}: {}", stdout(&o));
    }
    // The ones whose tools and cutting edges the built-in turret lacks (T4, T5 D3,
    // T1 D2 and D3) run on examples/machines/sinumerik_tools.toml.
    let machine = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/machines/sinumerik_tools.toml");
    for name in
        ["drill_cycle83.mpf", "drill_cycle83_g18_axn.mpf", "turn_cycle93.mpf", "turn_cycle94.mpf", "turn_cycle96.mpf"]
    {
        let path = format!("{SINUMERIK}/{name}");
        let o = lathe(&["check", &path, "--machine", machine]);
        assert_eq!(status(&o), 0, "{name}: {}", stdout(&o));
        assert!(stdout(&o).ends_with("no alarms\n"), "{name}: {}", stdout(&o));
    }
}

/// The drilling-pattern examples (HOLES1, HOLES2, CYCLE801, seed 001 chapter 2.3) and
/// the pockets (POCKET1 to POCKET4), thread milling (CYCLE90) and slots (LONGHOLE,
/// SLOT1, SLOT2, chapter 3)
/// run clean on the machining centre and draw exactly their committed plan-view
/// renders.
#[test]
fn the_sinumerik_mill_examples_run_and_match_their_renders() {
    let machine = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/machines/mill.toml");
    for name in [
        "holes1_row",
        "holes1_grid",
        "holes2_circle",
        "cycle801_grid",
        "pocket1",
        "pocket2",
        "pocket3",
        "pocket4",
        "cycle90",
        "cycle90_up",
        "longhole",
        "slot1",
        "slot2",
    ] {
        let path = format!("{SINUMERIK}/mill/{name}.mpf");
        let o = lathe(&["check", &path, "--machine", machine]);
        assert_eq!(status(&o), 0, "{name}: {}", stdout(&o));
        assert!(stdout(&o).ends_with("no alarms\n"), "{name}: {}", stdout(&o));
        let svg = scratch(&format!("{name}.svg"), "");
        let rel = format!("examples/sinumerik/mill/{name}.mpf");
        let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_lathe"))
            .current_dir(root)
            .args(["sim", &rel, "--machine", "examples/machines/mill.toml", "--format", "svg", "--out", &svg])
            .output()
            .expect("lathe runs");
        assert_eq!(status(&o), 0, "{name}: {}", stderr(&o));
        let drawn = std::fs::read_to_string(&svg).expect("render written");
        let committed = std::fs::read_to_string(format!("{SINUMERIK}/mill/{name}.svg")).expect("committed render");
        assert_eq!(drawn, committed, "{name}: render differs (tools/render-examples.sh)");
    }
}

#[test]
fn lathe_machine_shows_the_power_on_language() {
    let o = lathe(&["machine"]);
    assert!(stdout(&o).lines().any(|l| l == "language = \"fanuc\""), "{}", stdout(&o));
    let m = scratch("siemens_machine.toml", "language = \"siemens\"\n");
    let o = lathe(&["machine", "--machine", &m]);
    assert!(stdout(&o).lines().any(|l| l == "language = \"siemens\""), "{}", stdout(&o));
    // The machine's language reads a .nc file as SINUMERIK.
    let nc = scratch("siemens_machine.nc", "R2=3\nG0 X=R2 Z=R2\nM30\n");
    let (m2, _) = moves(&[&nc, "--machine", &m]);
    assert_eq!(m2, [('r', 3.0, 3.0)]);
}

/// A cycle message (62xxx) is shown and the program goes on: HOLES1 without a
/// modal drilling cycle only positions (62100, seed 001 lines 3095-3101) and
/// `lathe sim`/`lathe check` say so with the message's number, line and text.
#[test]
fn cycle_messages_are_shown_with_their_line() {
    let machine = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/machines/mill.toml");
    let p = scratch("holes_no_mcall.mpf", "G17 G90 G0 X0 Y0 Z10\nHOLES1(10, 20, 0, 5, 10, 3)\nM30\n");
    let o = lathe(&["sim", &p, "--machine", machine, "--format", "jsonl"]);
    assert_eq!(status(&o), 0, "{}", stderr(&o));
    let want = "line 2: message 62100: no drilling cycle active (program MCALL CYCLE81-89/840 before the pattern)";
    assert!(stderr(&o).lines().any(|l| l.ends_with(want)), "{}", stderr(&o));
    let o = lathe(&["check", &p, "--machine", machine]);
    assert!(stdout(&o).contains(want), "{}", stdout(&o));
    assert!(stdout(&o).ends_with("no alarms\n"), "{}", stdout(&o));
}

/// SLOT2 with a CDIR other than 2/3 (seed 001 table 12278): message 62101 "wrong
/// milling direction, G3 generated" on the call's line, and the rings run G3 (the
/// end caps counterclockwise; the sides about the circle's centre go both ways).
#[test]
fn slot2_cdir_other_than_2_or_3_is_message_62101() {
    let machine = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/machines/mill.toml");
    let p = scratch(
        "slot2_cdir.mpf",
        "G17 G90 G0 X60 Y60 Z5 S600 M3\nT1 D1\nSLOT2(2, 0, 2, -5, , 3, 30, 15, 60, 60, 42, , 120, 100, 300, 6, 7, 0.5)\nM30\n",
    );
    let o = lathe(&["sim", &p, "--machine", machine, "--format", "jsonl"]);
    assert_eq!(status(&o), 0, "{}", stderr(&o));
    let want = "line 3: message 62101: wrong milling direction, G3 generated (CDIR not 2 or 3)";
    assert!(stderr(&o).lines().any(|l| l.ends_with(want)), "{}", stderr(&o));
    let out = stdout(&o);
    let caps = |l: &&str| l.contains(r#""kind":"arc""#) && !l.contains(r#""cx":60.0,"cy":60.0"#);
    let arcs: Vec<&str> = out.lines().filter(caps).collect();
    assert!(!arcs.is_empty() && arcs.iter().all(|l| l.contains(r#""cw":false"#)), "{out}");
}

/// On the machining centre in SINUMERIK mode T selects the tool and M6 changes
/// it (as FANUC's M06): the change is an action of the M6 block.
#[test]
fn m6_changes_the_tool_on_the_machining_centre() {
    let machine = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/machines/mill.toml");
    let p = scratch("m6_mill.mpf", "G17 G90\nT2 D1\nM6\nG0 X10 Y10 Z5\nM30\n");
    let o = lathe(&["sim", &p, "--machine", machine, "--format", "jsonl"]);
    assert_eq!(status(&o), 0, "{}", stderr(&o));
    let first = stdout(&o).lines().next().unwrap_or_default().to_owned();
    assert!(first.starts_with(r#"{"line":3,"kind":"tool_change","tool":2"#), "{}", stdout(&o));
}

//! SINUMERIK CYCLE73 pocket milling with islands on the mill (seed 001 lines
//! 6150-7392): CYCLE74/CYCLE75 transfer the pocket's edge and islands, CYCLE73
//! clears, finishes or pre-drills the pocket minus its islands. The document's
//! example 1 is built here from its program text (the RND fillets computed in
//! the test), the cutter's swept area rasterised and measured against it.

mod mill_common;

use mill_common::plane::*;

/// T5 radius 4 (the document's second listing), T2 radius 5, T3 radius 6.
const HEAD: &str = "$TC_DP1[5,1]=120 $TC_DP6[5,1]=4\n$TC_DP1[2,1]=120 $TC_DP6[2,1]=5\n\
    $TC_DP1[3,1]=120 $TC_DP6[3,1]=6\nT5 D1\nM6\nS500 M3 F2000\nG17 G0 G90 G94 X0 Y0 Z20\n";

/// Example 1's edge and islands (lines 6886-6901) as label sections after M02.
const CONTOURS: &str = "M02\n\
    N510 _RAND:G0 G64 X25 Y30\nN520 G1 X118 RND=5\nN530 Y96 RND=5\nN540 X40 RND=5\n\
    N545 X20 Y75 RND=5\nN550 Y35\nN560 _ENDRAND:G3 X25 Y30 CR=5\n\
    N570 _INSEL1:G0 X34 Y58\nN580 G1 X64\nN590 _ENDINSEL1:G2 X34 Y58 CR=15\n\
    N600 _INSEL2:G0 X79 Y73\nN610 G1 X99\nN620 _ENDINSEL2:G3 X79 Y73 CR=10\n";

/// The transfer of example 1's contours.
const TRANSFER: &str = "CYCLE74 (\"\", \"_RAND\", \"_ENDRAND\")\nCYCLE75 (\"\", \"_INSEL1\", \"_ENDINSEL1\")\n\
    CYCLE75 (\"\", \"_INSEL2\", \"_ENDINSEL2\")\n";

/// Example 1's clearing call (line 6913): VARI 1021, RTP 10, RFP 0, SDIS 1,
/// DP −17.5, MIDA 2, FAL 0.5, FFP1 9000, FFD 3000, CDIR 0, RAD 4, DP1 3.
const ROUGH: &str = "1021, \"\", \"BEISPIEL1_MILL1\", \"5\", 10, 0, 1, -17.5, 0, , 2, 0.5, , 9000, 3000, 0, , , 4, 3";

/// `HEAD`, then `body`, then the contours; the line of the first line of `body`.
fn program(body: &str) -> (String, u32) {
    (format!("{HEAD}{body}{CONTOURS}"), HEAD.lines().count() as u32 + 1)
}

/// The alarm of `body`'s line `k` (0: its first), and nothing moved on that line.
fn alarm_at(body: &str, k: u32) -> u16 {
    let (text, first) = program(body);
    let r = siemens(&text);
    let line = first + k;
    let codes = r.alarm_codes();
    assert_eq!(codes.len(), 1, "{body}: {codes:?}");
    assert_eq!(codes[0].0, line, "{body}: {codes:?}");
    assert!(!r.actions.iter().any(|c| c.line == line && c.action.endpoint().is_some()), "{body} moved");
    codes[0].1
}

/// The transfer's alarms, on the transferring call's line.
#[test]
fn transfer_alarms_move_nothing() {
    // CYCLE73 or CYCLE75 with no CYCLE74 before: no contour.
    assert_eq!(alarm_at(&format!("CYCLE73({ROUGH})\n"), 0), 61900);
    assert_eq!(alarm_at("CYCLE75 (\"\", \"_INSEL1\", \"_ENDINSEL1\")\n", 0), 61900);
    // Nothing named: the edge's or the island's contour wrong.
    assert_eq!(alarm_at("CYCLE74 (\"\", \"\", \"\")\n", 0), 61983);
    assert_eq!(alarm_at("CYCLE74 (\"\", \"_RAND\", \"_ENDRAND\")\nCYCLE75 (\"\", \"\", \"\")\n", 1), 61980);
    // A label that is not there (the labels' own alarm).
    let code = alarm_at("CYCLE74 (\"\", \"_RAND\", \"_NOWHERE\")\n", 0);
    assert_eq!(code, alarm_at("GOTOF _NOWHERE\n", 0));
    // The edge and 15 islands fit; a 16th island is 61906.
    let mut body = String::from("CYCLE74 (\"\", \"_RAND\", \"_ENDRAND\")\n");
    for _ in 0..15 {
        body.push_str("CYCLE75 (\"\", \"_INSEL1\", \"_ENDINSEL1\")\n");
    }
    body.push_str("CYCLE75 (\"\", \"_INSEL2\", \"_ENDINSEL2\")\n");
    assert_eq!(alarm_at(&body, 16), 61906);
}

/// CYCLE73's own checks, on its line, before anything moves.
#[test]
fn cycle73_alarms_move_nothing() {
    let call = |args: &str| format!("{TRANSFER}CYCLE73({args})\n");
    let with = |i: usize, v: &str| {
        let mut a: Vec<String> = ROUGH.split(", ").map(str::to_string).collect();
        a[i] = v.to_string();
        call(&a.join(", "))
    };
    for (body, code) in [
        (with(3, "\"\""), 61984),
        (with(2, "\"\""), 61988),
        (with(0, "1015"), 61985),
        (with(10, "7"), 61982),
        (with(0, "1023"), 61002),
        (with(0, "1041"), 61002),
        (with(0, "3021"), 61002),
        (with(0, "1026"), 61002),
        (with(18, "0"), 61909),
        (with(19, "0"), 61108),
        (with(15, "5"), 61109),
        (with(7, "5"), 61101),
        // Rest material with tool 5 (radius 4) after tool 2 (radius 5) is fine; after
        // itself it has nothing smaller to follow.
        (with(0, "1012"), 61918),
    ] {
        assert_eq!(alarm_at(&body, 3), code, "{body}");
    }
    // D2 is not D1.
    let (text, first) = program(&call(ROUGH));
    let r = siemens(&text.replace("T5 D1", "T5 D2"));
    assert_eq!(r.alarm_codes(), vec![(first + 3, 61989)]);
}

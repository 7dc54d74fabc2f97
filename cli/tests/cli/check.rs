//! `lathe check`: every alarm as PROGRAM:LINE: alarm CODE: message, exit statuses.

use super::{lathe, scratch, status, stderr, stdout};

/// Line 4: G07 does not exist; line 5: F0. The blocks around them are fine.
const TWO_BAD_BLOCKS: &str = "%\nO0002\nG00 X20 Z25\nG07 X10\nG01 X30 F0\nG01 X40 Z-5 F100\nM30\n%\n";

#[test]
fn reports_every_alarm_with_its_line_and_exits_1() {
    let p = scratch("two-bad.nc", TWO_BAD_BLOCKS);
    let o = lathe(&["check", &p]);
    assert_eq!(status(&o), 1);
    assert_eq!(
        stdout(&o),
        format!(
            "{p}:4: alarm 0010: G07 is not a G code of the selected G-code system\n\
             {p}:5: alarm 0011: cutting feed F is zero or was never given\n\
             {p}: 3 blocks, 2 alarms\n"
        )
    );
    assert_eq!(stderr(&o), "");
}

#[test]
fn a_clean_program_gets_one_line_and_exit_0() {
    let p = scratch("clean.nc", "%\nO0003\nG00 X20 Z25\nG01 X60 Z7 F500\nM30\n%\n");
    let o = lathe(&["check", &p]);
    assert_eq!(status(&o), 0);
    assert_eq!(stdout(&o), format!("{p}: 3 blocks, no alarms\n"));
}

#[test]
fn several_programs_are_checked_in_turn() {
    let good = scratch("several-good.nc", "G00 X20 Z25\nM30\n");
    let bad = scratch("several-bad.nc", TWO_BAD_BLOCKS);
    let o = lathe(&["check", &bad, &good]);
    assert_eq!(status(&o), 1);
    let out = stdout(&o);
    assert_eq!(out.lines().count(), 4);
    assert!(out.ends_with(&format!("{good}: 2 blocks, no alarms\n")));
}

#[test]
fn a_program_without_an_end_raises_end_of_record() {
    let p = scratch("no-end.nc", "G00 X20 Z25\n");
    let o = lathe(&["check", &p]);
    assert_eq!(status(&o), 1);
    assert!(stdout(&o).starts_with(&format!("{p}:2: alarm 5010: program ended without M02, M30 or M99\n")));
}

#[test]
fn a_missing_file_is_an_error_and_the_others_are_still_checked() {
    let good = scratch("missing-good.nc", "G00 X20 Z25\nM30\n");
    let o = lathe(&["check", "/nonexistent/part.nc", &good]);
    assert_eq!(status(&o), 2);
    assert!(stderr(&o).starts_with("lathe: cannot read /nonexistent/part.nc: "));
    assert_eq!(stdout(&o), format!("{good}: 2 blocks, no alarms\n"));
}

#[test]
fn a_program_that_is_not_utf8_is_an_error_naming_the_place() {
    let p = scratch("latin1.nc", b"G00 X20 Z25\nG01 X30 (D\xc9BUT)\nM30\n");
    let o = lathe(&["check", &p]);
    assert_eq!(status(&o), 2);
    assert_eq!(
        stderr(&o),
        format!("lathe: {p}:2: byte 0xC9 at column 11 is not UTF-8 text; save the program as ASCII or UTF-8\n")
    );
}

#[test]
fn garbage_gives_alarms_not_a_crash() {
    let p = scratch("garbage.nc", "@@\n((\nX\n%%%\n;;;\nG1.2.3\n\u{e9}\n");
    let o = lathe(&["check", &p]);
    assert_eq!(status(&o), 1);
    assert!(stdout(&o).contains("alarm"));
}

#[test]
fn a_bad_machine_file_is_an_error() {
    let p = scratch("bad-machine.nc", "M30\n");
    let m = scratch("typo.toml", "tool_cont = 8\n");
    let o = lathe(&["check", &p, "--machine", &m]);
    assert_eq!(status(&o), 2);
    let err = stderr(&o);
    assert!(err.starts_with(&format!("lathe: machine file {m}: ")), "{err}");
    assert!(err.contains("unknown field `tool_cont`"), "{err}");
}

#[test]
fn usage_errors_exit_2() {
    assert_eq!(status(&lathe(&["check"])), 2);
    assert_eq!(status(&lathe(&["frobnicate"])), 2);
    let help = lathe(&["--help"]);
    assert_eq!(status(&help), 0);
    assert!(stdout(&help).contains("Usage: lathe <COMMAND>"));
}

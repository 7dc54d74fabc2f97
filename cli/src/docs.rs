//! `lathe alarms` and `lathe params`: the alarm catalog and the parameter table of
//! `interp-core` as Markdown. docs/ALARMS.md and docs/PARAMETERS.md are exactly
//! this output, and a test keeps them so.

use std::fmt::Write;

use interp_core::alarm::CATALOG;
use interp_core::config::PARAMS;

/// docs/ALARMS.md: a header and one row per alarm code.
pub fn alarms_markdown() -> String {
    let mut s = String::from(
        "# Alarms\n\n\
         Every alarm the lathe interpreter raises. A block that raises an alarm changes nothing: \
         the control stops there, `lathe sim` stops there too, and `lathe check` reports it as \
         `PROGRAM:LINE: alarm CODE: message` and goes on with the next block. Codes follow the \
         manual where it numbers an alarm, FANUC's numbers where it has an equivalent, and \
         4000-4999 for alarms of this controller alone. This file is generated from \
         `interp_core::alarm::CATALOG` by `lathe alarms > docs/ALARMS.md`; a test fails when \
         the two differ.\n\n\
         | Code | Alarm | Raised when |\n\
         | ---: | --- | --- |\n",
    );
    for e in CATALOG {
        let _ = writeln!(s, "| {:04} | {} | {} |", e.code, cell(e.title), cell(e.when));
    }
    s
}

/// docs/PARAMETERS.md: a header and one row per parameter.
pub fn params_markdown() -> String {
    let mut s = String::from(
        "# Parameters\n\n\
         The numbered parameters of the lathe interpreter, with the manual's numbers. Set them in \
         the `[parameters]` table of a machine file (`lathe sim --machine FILE`) by number, in the \
         unit shown, for example `5147 = 2.0`; a number not listed here is an error. Programs may \
         change some of them while they run (G71 U writes 5147). This file is generated from \
         `interp_core::config::PARAMS` by `lathe params > docs/PARAMETERS.md`; a test fails when \
         the two differ.\n\n\
         | No. | Unit | Default | Meaning |\n\
         | ---: | --- | ---: | --- |\n",
    );
    for p in PARAMS {
        let _ = writeln!(s, "| {} | {} | {} | {} |", p.number, p.unit.name(), p.default, cell(p.meaning));
    }
    s
}

/// Text safe inside a Markdown table cell.
fn cell(text: &str) -> String {
    text.replace('|', "\\|")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_have_a_row_per_entry() {
        let a = alarms_markdown();
        // Header and separator rows, then one row per entry.
        assert_eq!(a.lines().filter(|l| l.starts_with("| ")).count(), CATALOG.len() + 2);
        assert!(a.contains("| 0010 | improper G code |"));
        let p = params_markdown();
        assert_eq!(p.lines().filter(|l| l.starts_with("| ")).count(), PARAMS.len() + 2);
        assert!(p.contains("| 5147 | mm | 1 | depth of cut"));
        assert!(p.contains("| 6023 | mm/min | 5000 |"));
        assert_eq!(cell("a|b"), "a\\|b");
    }
}

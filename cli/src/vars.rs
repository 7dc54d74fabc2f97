//! The variables file of `--vars`: the common variables #401–#600, which a control
//! keeps through power-off (2.24.1), as `#n = value` lines. `lathe sim` reads it
//! before the run and writes it back after (creating it); `lathe check` only reads.

use std::path::Path;

use interp_core::lang::fanuc::macros::{Variables, parse_common_line, write_commons};

use crate::error::Error;

/// The common variables kept in `path`; all null if the file does not exist yet.
pub fn read(path: &Path) -> Result<Variables, Error> {
    let mut vars = Variables::new();
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(vars),
        Err(source) => return Err(Error::Read { path: path.to_owned(), source }),
    };
    for (i, line) in text.lines().enumerate() {
        let bad = |message| Error::Vars { path: path.to_owned(), line: i + 1, message };
        if let Some((n, v)) = parse_common_line(line).map_err(bad)? {
            vars.set(n, Some(v)).map_err(|_| bad("not a common variable"))?;
        }
    }
    Ok(vars)
}

/// Writes the common variables of `vars` that are not null to `path`.
pub fn write(path: &Path, vars: &Variables) -> Result<(), Error> {
    let mut text = String::from("; common variables #401-#600, kept by lathe sim (null ones are not listed)\n");
    // Writing to a String cannot fail.
    let _ = write_commons(vars, &mut text);
    std::fs::write(path, text).map_err(|source| Error::Write { target: path.display().to_string(), source })
}

//! Errors that keep a command from doing its work: unreadable files, programs that
//! are not text, bad machine files, output that cannot be written. All of them make
//! `lathe` exit with status 2 (alarms, status 1, are results, not errors), and so
//! do a failed link to the board and program lines that cannot be sent.

use std::fmt;
use std::io;
use std::path::PathBuf;

/// Why a command failed.
#[derive(Debug)]
pub enum Error {
    /// A file could not be read.
    Read {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        source: io::Error,
    },
    /// A program holds bytes that are not UTF-8 text.
    NotUtf8 {
        /// The program.
        path: PathBuf,
        /// 1-based line of the first bad byte.
        line: usize,
        /// 1-based byte column of the first bad byte.
        column: usize,
        /// The first bad byte.
        byte: u8,
    },
    /// A machine file is not TOML or does not describe a machine.
    Machine {
        /// The machine file.
        path: PathBuf,
        /// What is wrong, naming the field.
        message: String,
    },
    /// Output could not be written.
    Write {
        /// The file, or "standard output".
        target: String,
        /// What the operating system said.
        source: io::Error,
    },
    /// A program file or library file cannot be put into program memory (a
    /// program number twice, blocks before the first O of a library file …).
    Library {
        /// The file.
        path: String,
        /// What is wrong.
        message: String,
    },
    /// A variables file (`--vars`) is not `#n = value` lines of common variables.
    Vars {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// What is wrong.
        message: &'static str,
    },
    /// A program line cannot go over the link (`lathe send`, `upload`).
    Unsendable {
        /// The program.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// The link to the board failed (port, timeout, no welcome).
    Link(crate::link::LinkError),
    /// A program was still running after [`crate::program::MAX_STEPS`] steps.
    Runaway {
        /// The program.
        path: PathBuf,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Read { path, source } => write!(f, "cannot read {}: {source}", path.display()),
            Error::NotUtf8 { path, line, column, byte } => write!(
                f,
                "{}:{line}: byte 0x{byte:02X} at column {column} is not UTF-8 text; save the program as ASCII or UTF-8",
                path.display()
            ),
            Error::Machine { path, message } => write!(f, "machine file {}: {message}", path.display()),
            Error::Write { target, source } => write!(f, "cannot write {target}: {source}"),
            Error::Library { path, message } => write!(f, "{path}: {message}"),
            Error::Vars { path, line, message } => write!(f, "{}:{line}: {message}", path.display()),
            Error::Unsendable { path, line, message } => write!(f, "{}:{line}: {message}", path.display()),
            Error::Link(e) => write!(f, "{e}"),
            Error::Runaway { path } => write!(
                f,
                "{}: still running after {} steps; the program loops",
                path.display(),
                crate::program::MAX_STEPS
            ),
        }
    }
}

impl std::error::Error for Error {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Error::Read { source, .. } | Error::Write { source, .. } => Some(source),
            _ => None,
        }
    }
}

impl From<crate::link::LinkError> for Error {
    fn from(e: crate::link::LinkError) -> Self {
        Error::Link(e)
    }
}

//! The host side of the board's serial link (docs/PROTOCOL.md): `lathe send`,
//! `upload`, `run`, `status` and `settings`.
//!
//! - [`wire`]: opening a port (a pty path works), response lines and flow-control
//!   bytes out of the byte stream, waiting with deadlines.
//! - [`stream`]: the character-counting streamer of grbl mode with checksums and
//!   resends, and [`tape`]: FANUC tape mode with XON/XOFF — both state machines that
//!   never touch a port, so they are tested by feeding them answers.
//! - [`session`]: the loop that drives one of them over a [`wire::Link`] while
//!   polling the status, reading keys and showing progress ([`ui`], [`keys`]).
//! - [`commands`]: the subcommands built from these.
//!
//! Nothing here is global: a command opens its link, runs, and drops it.

pub mod commands;
pub mod crc;
pub mod keys;
pub mod response;
pub mod session;
pub mod source;
pub mod stream;
pub mod tape;
pub mod ui;
pub mod wire;

use std::fmt;

/// Why talking to the board failed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LinkError {
    /// The port could not be opened.
    Open {
        /// The port.
        port: String,
        /// What the operating system said.
        message: String,
    },
    /// Reading or writing the port failed.
    Io {
        /// The port.
        port: String,
        /// What the operating system said.
        message: String,
    },
    /// The board did not send what was awaited in time.
    Timeout {
        /// The port.
        port: String,
        /// What was awaited.
        what: String,
    },
    /// The board refused a command with `error:N`.
    Refused {
        /// The command.
        command: String,
        /// The error number.
        code: u16,
        /// The `[MSG:…]` before it, or the meaning of the number.
        message: String,
    },
    /// The board is not in a state to do it.
    NotReady {
        /// The state it reported.
        state: String,
        /// What to do about it.
        hint: &'static str,
    },
}

impl fmt::Display for LinkError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LinkError::Open { port, message } => write!(f, "cannot open {port}: {message}"),
            LinkError::Io { port, message } => write!(f, "{port}: {message}"),
            LinkError::Timeout { port, what } => write!(f, "{port}: no answer from the board: waited for {what}"),
            LinkError::Refused { command, code, message } => {
                write!(f, "board refused {command}: error:{code}: {message}")
            }
            LinkError::NotReady { state, hint } => write!(f, "the board is in state {state}; {hint}"),
        }
    }
}

impl std::error::Error for LinkError {}

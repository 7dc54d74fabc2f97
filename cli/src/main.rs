//! The `lathe` command: parses the arguments and runs the library's [`lathe::app`].

use std::io::{stderr, stdout};
use std::process::ExitCode;

fn main() -> ExitCode {
    let status = lathe::app::main(std::env::args_os(), &mut stdout().lock(), &mut stderr().lock());
    ExitCode::from(status)
}

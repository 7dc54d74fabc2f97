//! Tests of the `lathe` command: the binary run as a user runs it, and the library
//! where a test needs values rather than text.

mod board;
mod check;
mod docs;
#[cfg(unix)]
mod fake_board;
mod jsonl;
#[cfg(unix)]
mod link;
mod machine;
mod macros;
mod siemens;
mod sim;
mod svg;
mod tape_flow;

use std::path::PathBuf;
use std::process::{Command, Output};

/// Runs `lathe` with `args`.
fn lathe(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lathe")).args(args).output().expect("the lathe binary runs")
}

/// Writes `content` to a scratch file `name` (unique per test) and returns its path as text.
fn scratch(name: &str, content: impl AsRef<[u8]>) -> String {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("lathe-cli-tests");
    std::fs::create_dir_all(&dir).expect("scratch directory");
    let path = dir.join(name);
    std::fs::write(&path, content).expect("scratch file");
    path.display().to_string()
}

/// Standard output as text.
fn stdout(o: &Output) -> String {
    String::from_utf8(o.stdout.clone()).expect("UTF-8 output")
}

/// Standard error as text.
fn stderr(o: &Output) -> String {
    String::from_utf8(o.stderr.clone()).expect("UTF-8 errors")
}

/// The exit status.
fn status(o: &Output) -> i32 {
    o.status.code().expect("exited")
}

//! What a user sees while the board works: a progress bar with a live status line
//! on a terminal ([`Bar`]), or plain log lines for logs and tests ([`Plain`]).

use std::io::Write;

use indicatif::{MultiProgress, ProgressBar, ProgressDrawTarget, ProgressStyle};

use super::response::Status;

/// Where a session reports.
pub trait Ui {
    /// A line worth keeping: a board message, an error, an event.
    fn note(&mut self, text: &str);
    /// Lines written, accepted, and the total.
    fn progress(&mut self, sent: usize, accepted: usize, total: usize);
    /// A status report.
    fn status(&mut self, status: &Status);
    /// The session is over: leave the display as it is.
    fn finish(&mut self);
}

/// Plain lines to a writer: notes as they come, state changes as `state Run`;
/// no progress output.
pub struct Plain<'a> {
    out: &'a mut dyn Write,
    state: String,
}

impl<'a> Plain<'a> {
    /// Log lines to `out`.
    pub fn new(out: &'a mut dyn Write) -> Self {
        Plain { out, state: String::new() }
    }
}

impl Ui for Plain<'_> {
    fn note(&mut self, text: &str) {
        let _ = writeln!(self.out, "{text}");
    }

    fn progress(&mut self, _sent: usize, _accepted: usize, _total: usize) {}

    fn status(&mut self, status: &Status) {
        if status.state != self.state {
            self.state.clone_from(&status.state);
            let _ = writeln!(self.out, "state {}", status.state);
        }
    }

    fn finish(&mut self) {
        let _ = self.out.flush();
    }
}

/// A progress bar (lines acknowledged, lines sent, percent, elapsed, ETA) and a
/// status line under it, drawn on standard error.
pub struct Bar {
    multi: MultiProgress,
    bar: ProgressBar,
    line: ProgressBar,
}

impl Bar {
    /// A bar for `total` lines, with `help` shown until the first status report.
    pub fn new(total: usize, help: &str) -> Self {
        let multi = MultiProgress::with_draw_target(ProgressDrawTarget::stderr_with_hz(10));
        let style = ProgressStyle::with_template(
            "{bar:32} {pos}/{len} acknowledged, {msg} sent  {percent:>3}%  {elapsed_precise}  ETA {eta}",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar());
        let bar = multi.add(ProgressBar::new(total as u64).with_style(style).with_message("0"));
        let line_style = ProgressStyle::with_template("{msg}").unwrap_or_else(|_| ProgressStyle::default_spinner());
        let line = multi.add(ProgressBar::new_spinner().with_style(line_style).with_message(help.to_owned()));
        Bar { multi, bar, line }
    }
}

impl Ui for Bar {
    fn note(&mut self, text: &str) {
        let _ = self.multi.println(text);
    }

    fn progress(&mut self, sent: usize, accepted: usize, total: usize) {
        self.bar.set_length(total as u64);
        self.bar.set_position(accepted as u64);
        self.bar.set_message(sent.to_string());
    }

    fn status(&mut self, status: &Status) {
        self.line.set_message(status.summary());
    }

    fn finish(&mut self) {
        self.bar.abandon();
        self.line.abandon();
    }
}

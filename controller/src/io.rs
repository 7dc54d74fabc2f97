//! The machine's side of the controller, apart from motion: switch inputs read
//! every poll, and the outputs the motion events switch.

use interp_core::canon::SpindleDir;

/// Switch inputs as the shell read them for this poll (true = active: pressed,
/// tripped, open). The shell debounces and inverts normally-closed contacts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Inputs {
    /// Emergency stop.
    pub estop: bool,
    /// X limit switch (either end).
    pub limit_x: bool,
    /// Y limit switch (either end; a mill's).
    pub limit_y: bool,
    /// Z limit switch (either end).
    pub limit_z: bool,
    /// X home switch.
    pub home_x: bool,
    /// Y home switch (a mill's).
    pub home_y: bool,
    /// Z home switch.
    pub home_z: bool,
    /// Feed hold button.
    pub feed_hold: bool,
    /// Cycle start button.
    pub cycle_start: bool,
    /// Safety door open.
    pub door: bool,
    /// The automatic tool changer's "done" line (a mill's ATC).
    pub tool_change_done: bool,
    /// External inputs 0–31 that M91/M92 test (bit n).
    pub user: u32,
}

/// Outputs that follow the program: the motion core emits M codes, tool changes
/// and spindle commands as events in stream order (when the motion before them
/// has finished) and the controller hands them on here. Every method defaults to
/// doing nothing.
pub trait MachineIo {
    /// An M code with an output (coolant, chuck, tailstock, lube, gears, user M
    /// codes) reached its place in the motion; `line` is its program line.
    fn m_code(&mut self, m: u16, line: u32) {
        let _ = (m, line);
    }
    /// Index the turret to `tool`, offset number `offset`.
    fn tool(&mut self, tool: u16, offset: u16) {
        let _ = (tool, offset);
    }
    /// The automatic tool changer's request (a mill's M06 with `$312=1`):
    /// `Some(tool)` puts the tool number and the request on its outputs
    /// ([`hal::ToolChangeRequest::request_tool`]), `None` drops them
    /// ([`hal::ToolChangeRequest::clear_request`]).
    fn tool_change_request(&mut self, tool: Option<u16>) {
        let _ = tool;
    }
    /// Spindle direction and commanded speed changed (the drive itself follows the
    /// motion core's spindle output every period).
    fn spindle(&mut self, dir: SpindleDir, rpm: u32) {
        let _ = (dir, rpm);
    }
}

/// No outputs.
impl MachineIo for () {}

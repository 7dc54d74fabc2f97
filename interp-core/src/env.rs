//! What the interpreter reads from the machine while it runs: operator switches,
//! homing status, inputs. Passed in on every step, never fetched from globals.

use crate::axis::Axis;

/// The machine's side of the interpreter.
pub trait Environment {
    /// Optional block skip switch `level` (1 for `/`, 2–9 for `/2`…`/9`).
    fn block_skip(&self, level: u8) -> bool;
    /// Optional-stop switch: M01 stops only when on (3.1.2).
    fn optional_stop(&self) -> bool;
    /// Whether `axis` has been referenced since power-on (G28/G30 need it).
    fn referenced(&self, axis: Axis) -> bool;
    /// External input `n` (M91/M92), `None` if the machine has no such input.
    fn input(&self, n: u16) -> Option<bool>;
}

impl<E: Environment + ?Sized> Environment for &E {
    fn block_skip(&self, level: u8) -> bool {
        (**self).block_skip(level)
    }
    fn optional_stop(&self) -> bool {
        (**self).optional_stop()
    }
    fn referenced(&self, axis: Axis) -> bool {
        (**self).referenced(axis)
    }
    fn input(&self, n: u16) -> Option<bool> {
        (**self).input(n)
    }
}

/// Switch and input settings held in plain fields (simulator, tests, MDI).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Panel {
    /// Block skip switches 1–9 (bit n-1).
    pub block_skip: u16,
    /// Optional-stop switch.
    pub optional_stop: bool,
    /// Axes referenced (bit per [`Axis`] index).
    pub referenced: u8,
    /// External inputs 0–31 (bit n).
    pub inputs: u32,
}

impl Default for Panel {
    /// Switches off, all axes referenced, inputs low.
    fn default() -> Self {
        Panel { block_skip: 0, optional_stop: false, referenced: 0xff, inputs: 0 }
    }
}

impl Environment for Panel {
    fn block_skip(&self, level: u8) -> bool {
        level >= 1 && self.block_skip & (1 << (level - 1)) != 0
    }

    fn optional_stop(&self) -> bool {
        self.optional_stop
    }

    fn referenced(&self, axis: Axis) -> bool {
        self.referenced & (1 << axis.index()) != 0
    }

    fn input(&self, n: u16) -> Option<bool> {
        (n < 32).then(|| self.inputs & (1 << n) != 0)
    }
}

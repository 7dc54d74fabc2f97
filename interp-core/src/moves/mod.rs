//! The move helpers the execution layers share: a block's target and soft limits
//! (`motion`), polar interpolation's virtual moves ([`polar`]), stored stroke
//! check 2 ([`stroke`]) and the spindle speed a move runs at ([`spindle_speed`]). Below
//! the contour look-ahead and the cycles, which use them, and `exec`, which
//! dispatches to all three.

pub mod frame;
pub(crate) mod motion;
pub mod polar;
pub(crate) mod spindle;
pub mod stroke;

pub use spindle::spindle_speed;

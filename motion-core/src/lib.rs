//! Lathe motion core: canonical actions in, timed step events and spindle commands
//! out. `no_std`, no allocation, no unsafe code: the firmware's interrupts and the
//! host simulator run exactly this code. It knows nothing of the program language;
//! it depends only on the shared vocabulary of the [`canon`] crate.
//!
//! Layers, one module each, each using only the ones below it:
//! - [`fixed`]: fixed-point helpers (Q formats, division by multiplication, gcd);
//! - [`cordic`]: integer angle, cosine and sine (arcs);
//! - [`planner`]: canonical actions into planned blocks with look-ahead speeds, in
//!   the motion units of [`planner::MotionParams`];
//! - [`interpolator`]: the head block into axis targets per interpolation period;
//! - [`stepgen`]: axis targets into exactly timed step edges;
//! - [`sync`]: the axes geared to the spindle encoder (threads, rigid taps);
//! - [`motion`]: [`MotionCore`], the sink the interpreter feeds and the clock drives.
//!
//! The shared vocabulary is imported at the root, so the modules name it as before
//! the split: `crate::canon` (the actions), `crate::axis`, `crate::alarm`,
//! `crate::config`.
#![no_std]
#![forbid(unsafe_code)]

#[cfg(test)]
extern crate std;

pub use ::canon;
use ::canon::{alarm, axis, config};

pub mod cordic;
pub mod fixed;
pub mod interpolator;
pub mod motion;
pub mod planner;
pub mod stepgen;
pub mod sync;

pub use motion::{MotionCore, QUEUE};

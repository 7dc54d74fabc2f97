//! The firmware's interrupt-level motion logic without any hardware: what the step
//! interrupt and the motion interrupt do, as plain functions on plain state, so the
//! host tests it and the Cortex-M4 benchmarks (m4-tests `bench_isr`) count its
//! instructions. The firmware only adds the register reads and writes around it.
//!
//! - [`ring`]: per-axis lock-free edge queues from the motion interrupt to the step
//!   interrupt.
//! - [`playback`]: the step interrupt: due edges → one GPIO BSRR word, pulse ends,
//!   driver timing kept, no STEP rise while e-stop is active.
//! - [`engine`]: the motion interrupt: e-stop, encoder reading, `MotionCore::tick`
//!   one period ahead, step events → timed edges; the spindle-sync path at the
//!   counts where a step falls due, and the encoder compares that name them.
//! - [`timebase`]: ns ↔ timer ticks by multiplication.
//! - [`encoder`]: 32- or 16-bit hardware count → the core's 64-bit count, index on
//!   the same scale; due counts → compare values.
//! - [`io`]: switch debouncing, M-code outputs, spindle PWM duty.
//! - [`board`]: the board's types and its interrupt bodies and planner push as
//!   non-generic functions, compiled at this crate's opt-level.
#![no_std]

#[cfg(test)]
extern crate std;

pub mod board;
pub mod encoder;
pub mod engine;
pub mod io;
pub mod playback;
pub mod ring;
pub mod timebase;

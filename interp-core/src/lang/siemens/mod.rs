//! The SINUMERIK 840D front end (seed 001): the language's cycle calls and the
//! standard turning and drilling cycles' parameters.
//!
//! - [`call`]: an evaluated cycle call (its arguments, the cycles' signatures, where
//!   a cycle's contour is) — the seam between the reader and the cycles;
//! - [`cycles`]: the standard cycles (CYCLE93–CYCLE98, CYCLE950 …): their parameter
//!   lists, their checks and alarms (61xxx), mapped onto the engine's generators.

pub mod call;
pub mod cycles;

//! The SINUMERIK 840D language (seed 001, the cycles manual, and the 840D's
//! programming rules the cycles rely on): blocks of one line, `;` comments, R
//! parameters and DEF variables, labels and GOTOF/GOTOB, IF, REPEAT, PROC
//! subprograms called by name with parameters, MCALL, and the standard cycles.
//!
//! - [`call`]: argument lists of cycle and subprogram calls ([`call::Arg`],
//!   [`call::Ty`], [`call::Signature`]) and how they bind (12330/12340);
//! - [`vars`]: R parameters, DEF variables, the cycle setting data `_ZSD`;
//! - [`cycles`]: the standard cycles' parameter lists and their start on the
//!   engine's generators.

pub mod call;
pub mod check;
pub mod cycles;
pub mod expr;
pub mod lex;
pub mod read;
pub mod vars;

//! What the engine keeps of the SINUMERIK 840D language (seed 001): the state
//! the interpreter holds for it between steps and the plain data a cycle call
//! hands the engine. The language itself — reader, checker, expressions, the
//! standard cycles' parameter lists and alarms, the statements' flow — is the
//! `interp-siemens` crate, plugged in as a [`crate::lang::Front`].
//!
//! - [`call`]: argument lists of cycle and subprogram calls ([`call::Arg`],
//!   [`call::Ty`], [`call::Signature`]) and how they bind (12330/12340), the
//!   bound call and its contour as the engine gets them;
//! - [`vars`]: R parameters, DEF variables, the cycle setting data `_ZSD`.

pub mod call;
pub mod vars;

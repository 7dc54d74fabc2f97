//! The FANUC-style language: the ELESY-E3TA lathe dialect (manual 000, G-code
//! systems A/B/C) with the FANUC-0T conventions of seed 003, custom macro B.
//!
//! - [`parse`]: one block of text into words, or an evaluated macro statement;
//! - [`macros`]: variables #n, expressions, GOTO/IF/WHILE;
//! - [`check`]: the words into a [`crate::command::Command`] (meaning, units);
//! - [`calls`]: G65/G66/G67 and the calls by G, M and T codes (FANUC 0i).

pub mod calls;
pub mod check;
pub mod macros;
pub mod parse;

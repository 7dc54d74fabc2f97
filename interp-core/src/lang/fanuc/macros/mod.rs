//! The macro language of 2.24: variables, expressions and control statements.
//!
//! Expressions are evaluated while a block is read (as LinuxCNC does), against the
//! variable table as it stands: a block of NC words comes out of the reader holding
//! plain numbers, so checking and execution know nothing of macros. A macro
//! statement comes out evaluated too ([`MacroStatement`]); the interpreter stores
//! its value or moves its cursor.

mod expr;
mod func;
mod statement;
mod vars;

pub use expr::MAX_BRACKET_DEPTH;
pub use statement::{MAX_SEQUENCE, MacroStatement};
pub use vars::{
    COMMON_COUNT, CommonStore, FIRST_COMMON, LAST_COMMON, LOCAL_COUNT, Locals, MAX_MACRO_LEVEL, MAX_VARIABLE,
    POOL_SIZE, Value, Variables, parse_common_line, write_commons,
};

pub(crate) use expr::{Eval, Rounding, format, nullable};
pub use statement::find_loop_end;
pub(crate) use statement::{starts_statement, statement};

#[cfg(test)]
mod tests;

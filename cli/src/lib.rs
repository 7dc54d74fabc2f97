//! The `lathe` host command as a library: checking and simulating part programs
//! with the interpreter of `interp-core`, reading machine files, generating
//! the alarm and parameter documentation, and talking to the board ([`link`]). The binary (`src/main.rs`) only calls
//! [`app::main`]; `host-tests` uses the modules directly for golden tests.
//!
//! Internal units come from `interp-core` (nanometres, micro-degrees, X as a
//! radius); everything shown to users is in millimetres and degrees with X as a
//! diameter (see [`units`]).

pub mod app;
pub mod board;
pub mod docs;
pub mod error;
pub mod jsonl;
pub mod link;
pub mod machine;
pub mod motion;
pub mod path;
pub mod program;
pub mod summary;
pub mod svg;
pub mod svg_mill;
pub mod timing;
pub mod units;
pub mod vars;

pub use error::Error;
pub use program::{OnAlarm, Run};

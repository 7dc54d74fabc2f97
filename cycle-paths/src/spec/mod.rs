//! What a front end asks a generator to do, in the generators' own terms.

pub mod hole;
pub mod job;

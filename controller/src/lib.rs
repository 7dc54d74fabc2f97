//! The board's controller: everything between the serial link and the motion core
//! that is the same on the real board and on the host's virtual board — the link
//! protocols (grbl 1.1 line protocol, FANUC tape mode), job control, the stream
//! window and program store, settings and persistence. `no_std`, no allocation,
//! no unsafe code; bytes in, bytes out, time and hardware readings as arguments.
//! See `docs/PROTOCOL.md` for the wire contract.
#![no_std]
#![forbid(unsafe_code)]

#[cfg(test)]
extern crate std;

pub mod persist;

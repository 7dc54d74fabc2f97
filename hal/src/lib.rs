//! Hardware capability traits: one small trait per capability (step/dir output,
//! spindle encoder, spindle output, digital I/O, monotonic time). The firmware
//! implements them on the STM32 board; the host simulator models them.
#![no_std]
#![forbid(unsafe_code)]

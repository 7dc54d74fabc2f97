//! Fuzz target `program`: see [`lathe_fuzz::program`].
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| lathe_fuzz::program(data));

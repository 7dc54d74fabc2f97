//! Fuzz target `cycles`: see [`lathe_fuzz::cycles`].
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| lathe_fuzz::cycles(data));

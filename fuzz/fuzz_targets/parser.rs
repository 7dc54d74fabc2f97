//! Fuzz target `parser`: see [`lathe_fuzz::parser`].
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| lathe_fuzz::parser(data));

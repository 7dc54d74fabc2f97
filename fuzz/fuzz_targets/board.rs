//! Fuzz target `board`: see [`lathe_fuzz::board`].
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| lathe_fuzz::board(data));

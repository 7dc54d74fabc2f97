//! Link setup for the firmware: cortex-m-rt's `link.x` (which includes `memory.x`:
//! the workspace root's for the STM32F405, `memory-f446/` for the F446RE), defmt's
//! `defmt.x`, and `--nmagic` so sections need no page alignment in flash; and the
//! cfg `persist` where settings and programs persist on flash (the STM32F405 board
//! build: the F446RE's 256 KB below its store sectors is too small for the program,
//! QEMU's flash cannot be programmed).

use std::env;
use std::path::PathBuf;

fn main() {
    let manifest_dir = PathBuf::from(env::var_os("CARGO_MANIFEST_DIR").expect("set by cargo"));
    let root = manifest_dir.parent().expect("firmware/ sits in the workspace root");
    let memory_dir =
        if env::var_os("CARGO_FEATURE_F446").is_some() { manifest_dir.join("memory-f446") } else { root.to_path_buf() };
    println!("cargo:rustc-link-search={}", memory_dir.display());
    println!("cargo:rustc-check-cfg=cfg(persist)");
    if env::var_os("CARGO_FEATURE_HW").is_some() && env::var_os("CARGO_FEATURE_F405").is_some() {
        println!("cargo:rustc-cfg=persist");
    }
    println!("cargo:rerun-if-changed=../memory.x");
    println!("cargo:rerun-if-changed=memory-f446/memory.x");
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rustc-link-arg-bins=--nmagic");
    println!("cargo:rustc-link-arg-bins=-Tlink.x");
    println!("cargo:rustc-link-arg-bins=-Tdefmt.x");
}

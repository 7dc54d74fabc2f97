//! Link setup for the firmware: cortex-m-rt's `link.x` (which includes `memory.x`:
//! `memory-f405/`'s for the STM32F405, `memory-f446/`'s for the F446RE; no
//! memory.x may lie in the workspace root, which the linker searches first), defmt's
//! `defmt.x`, and `--nmagic` so sections need no page alignment in flash; and the
//! cfg `persist` where settings and programs persist on flash (the board builds,
//! STM32F405 and F446RE; QEMU's flash cannot be programmed).

use std::env;
use std::path::PathBuf;

fn main() {
    let manifest_dir = PathBuf::from(env::var_os("CARGO_MANIFEST_DIR").expect("set by cargo"));
    let memory_dir =
        manifest_dir.join(if env::var_os("CARGO_FEATURE_F446").is_some() { "memory-f446" } else { "memory-f405" });
    println!("cargo:rustc-link-search={}", memory_dir.display());
    println!("cargo:rustc-check-cfg=cfg(persist)");
    if env::var_os("CARGO_FEATURE_HW").is_some() {
        println!("cargo:rustc-cfg=persist");
    }
    println!("cargo:rerun-if-changed=memory-f405/memory.x");
    println!("cargo:rerun-if-changed=memory-f446/memory.x");
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rustc-link-arg-bins=--nmagic");
    println!("cargo:rustc-link-arg-bins=-Tlink.x");
    println!("cargo:rustc-link-arg-bins=-Tdefmt.x");
}

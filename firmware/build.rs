//! Link setup for the STM32F405 firmware: cortex-m-rt's `link.x` (which includes the
//! workspace-root `memory.x`), defmt's `defmt.x`, and `--nmagic` so sections need no
//! page alignment in flash.

use std::env;
use std::path::PathBuf;

fn main() {
    let manifest_dir = PathBuf::from(env::var_os("CARGO_MANIFEST_DIR").expect("set by cargo"));
    let root = manifest_dir.parent().expect("firmware/ sits in the workspace root");
    println!("cargo:rustc-link-search={}", root.display());
    println!("cargo:rerun-if-changed=../memory.x");
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rustc-link-arg-bins=--nmagic");
    println!("cargo:rustc-link-arg-bins=-Tlink.x");
    println!("cargo:rustc-link-arg-bins=-Tdefmt.x");
}

#!/usr/bin/env bash
# Per-function instruction profile of the measured regions of a benchmark binary on
# the emulated Cortex-M4F. Usage: m4-tests/profile.sh BIN [TOP]
set -euo pipefail
cd "$(dirname "$0")"
bin=$1
target_dir=${CARGO_TARGET_DIR:-target}
mkdir -p "$target_dir"
plugin=$(realpath "$target_dir")/icount.so
gcc -O2 -Wall -shared -fPIC -o "$plugin" qemu-plugin/icount.c
cargo build -q --release --bin "$bin"
prof=$(realpath "$target_dir")/$bin.profile
cargo run -q --release --bin "$bin" -- -plugin "$plugin,profile=$prof" -d plugin >/dev/null 2>&1
python3 profile.py "$target_dir/thumbv7em-none-eabihf/release/$bin" "$prof" "${2:-25}"

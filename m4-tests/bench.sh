#!/usr/bin/env bash
# Instruction counts on the emulated Cortex-M4F: builds the icount QEMU plugin and a
# benchmark binary (release), runs it twice under QEMU with the plugin loaded, prints
# the output (`instructions: N` for each `m4_tests::measure` call) and fails unless
# both runs print exactly the same.
#
# Usage: m4-tests/bench.sh [BIN]    (BIN defaults to bench_example; see src/bin/)
set -euo pipefail
cd "$(dirname "$0")"

bin=${1:-bench_example}
target_dir=${CARGO_TARGET_DIR:-target}
mkdir -p "$target_dir"
plugin=$(realpath "$target_dir")/icount.so

gcc -O2 -Wall -shared -fPIC -o "$plugin" qemu-plugin/icount.c
cargo build --release --bin "$bin"

# The runner in .cargo/config.toml starts QEMU; the plugin options follow the ELF.
run() { cargo run -q --release --bin "$bin" -- -plugin "$plugin" -d plugin 2>&1; }
first=$(run)
second=$(run)
echo "$first"
if [ "$first" != "$second" ]; then
    echo "bench.sh: the two runs differ:" >&2
    diff <(echo "$first") <(echo "$second") >&2
    exit 1
fi
echo "bench.sh: repeatable (a second run printed the same counts)"

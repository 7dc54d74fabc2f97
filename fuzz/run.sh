#!/usr/bin/env bash
# Runs every fuzz target for SECONDS (default 20) each, from its committed corpus
# (fuzz/corpus/<target>; new inputs go to fuzz/work/<target>, not committed: merge
# the useful ones with `cargo fuzz cmin`). CI runs a short
# bounded pass; a finding leaves its input in fuzz/artifacts/<target>/ and fails.
# Stable Rust takes cargo-fuzz's nightly flags with RUSTC_BOOTSTRAP=1.
#   fuzz/run.sh 20            # 20 s per target
#   fuzz/run.sh 600 board     # one target
set -euo pipefail
cd "$(dirname "$0")"
secs="${1:-20}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(program cycles board)
export RUSTC_BOOTSTRAP=1
command -v cargo-fuzz >/dev/null || cargo install cargo-fuzz --locked
for t in "${targets[@]}"; do
    echo "== $t: ${secs} s"
    # -max_len: programs up to 4 KiB; rss limit keeps a runaway input a finding.
    mkdir -p "work/$t"
    cargo fuzz run "$t" "work/$t" "corpus/$t" -- -max_total_time="$secs" -max_len=4096 \
        -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 2>&1 | \
        grep -E '^(stat::number_of_executed_units|stat::average_exec_per_sec|#[0-9]+ +DONE)|ERROR|panicked|SUMMARY|Test unit written' || true
    # cargo fuzz run's status is lost in the pipe: a finding leaves an artifact.
    if compgen -G "artifacts/$t/*" >/dev/null; then
        echo "finding(s) in fuzz/artifacts/$t" >&2
        exit 1
    fi
done

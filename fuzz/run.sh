#!/usr/bin/env bash
# Runs every fuzz target for SECONDS (default 20) each, from its committed corpus
# (fuzz/corpus/<target>; new inputs go to fuzz/work/<target>, not committed: merge
# the useful ones with `cargo fuzz cmin`). CI runs a short
# bounded pass; a finding leaves its input in fuzz/artifacts/<target>/ and fails.
# Stable Rust takes cargo-fuzz's nightly flags with RUSTC_BOOTSTRAP=1.
# Built without AddressSanitizer (every crate under test forbids unsafe code) and
# without libFuzzer's compare tracing (2× faster per input): the dictionaries in
# fuzz/dict give the mutator the G-code, macro and link tokens instead, and the
# board harness frames checked lines itself. Override with FUZZ_BUILD="...".
# Runs at nice 19, one fuzz process at a time; every run appends a line to
# fuzz/runs.log (date, target, executions, seconds, exec/s, findings).
#   fuzz/run.sh 20            # 20 s per target
#   fuzz/run.sh 600 board     # one target
# With FUZZ_RUNS=n each target runs n inputs from seed FUZZ_SEED (default 1) instead,
# SECONDS only a limit: the same inputs every time, so a run passes or fails the same
# way (CI). A timed run (the default) draws a fresh seed and explores.
set -euo pipefail
cd "$(dirname "$0")"
secs="${1:-20}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(parser program cycles board)
read -r -a build <<<"${FUZZ_BUILD:--s none --no-trace-compares}"
bound=(-max_total_time="$secs")
if [ -n "${FUZZ_RUNS:-}" ]; then
    bound=(-runs="$FUZZ_RUNS" -seed="${FUZZ_SEED:-1}" -max_total_time="$secs")
fi
export RUSTC_BOOTSTRAP=1
command -v cargo-fuzz >/dev/null || cargo install cargo-fuzz --locked
for t in "${targets[@]}"; do
    echo "== $t: ${secs} s"
    # -max_len: programs up to 4 KiB; rss limit keeps a runaway input a finding.
    mkdir -p "work/$t"
    dict=()
    case "$t" in
        parser | program) dict=(-dict=dict/gcode.dict) ;;
        board) dict=(-dict=dict/board.dict) ;;
    esac
    log="work/$t.log"
    nice -n 19 cargo fuzz run "${build[@]}" "$t" "work/$t" "corpus/$t" -- "${bound[@]}" -max_len=4096 \
        -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 "${dict[@]}" >"$log" 2>&1 || true
    grep -E '^(stat::number_of_executed_units|stat::average_exec_per_sec|#[0-9]+ +DONE)|ERROR|panicked|SUMMARY|Test unit written' "$log" || true
    execs=$(grep -oP '^stat::number_of_executed_units: *\K[0-9]+' "$log" || echo 0)
    found=$(find "artifacts/$t" -type f 2>/dev/null | wc -l)
    secs_run=$(grep -oP '^Done [0-9]+ runs in \K[0-9]+' "$log" || echo 0)
    printf '%s %s execs=%s secs=%s exec/s=%s findings=%s\n' "$(date -u +%FT%TZ)" "$t" "$execs" "$secs_run" \
        "$(( execs / (secs_run > 0 ? secs_run : 1) ))" "$found" >>runs.log
    # cargo fuzz run's status is lost in the pipe: a finding leaves an artifact.
    if compgen -G "artifacts/$t/*" >/dev/null; then
        echo "finding(s) in fuzz/artifacts/$t" >&2
        exit 1
    fi
done

#!/usr/bin/env bash
# CNCjs (a real third-party grbl sender) streams programs to `lathe board` (our
# controller on the simulated machine) over a pty; what the board's motion core
# accepted must be what `lathe sim` interprets for the same file.
#
#   tools/third-party-sender/board-test.sh LATHE_BINARY [--machine FILE] PROGRAM...
#
# With --machine the board and `lathe sim` both run that machine file (a mill:
# examples/machines/mill.toml).
#
# CNCjs strips comments, blank and `%` lines before sending (so line numbers differ)
# and appends `G4 P0.5` (the board runs it as a 0.5 s dwell, setting $303): the
# comparison ignores line numbers and allows that one trailing dwell.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
lathe="$1"; shift
machine=()
if [ "${1:-}" = "--machine" ]; then machine=(--machine "$2"); shift 2; fi
work="$(mktemp -d)"
trap 'kill "${board_pid:-0}" 2>/dev/null || true; rm -rf "$work"' EXIT
failed=0
for program in "$@"; do
    name="$(basename "$program")"
    pty="$work/board.pty"
    "$lathe" board "${machine[@]}" --pty "$pty" --speed 20 --record "$work/$name.board.jsonl" --exit-after 900 > "$work/board.log" 2>&1 &
    board_pid=$!
    for _ in $(seq 100); do [ -e "$pty" ] && break; sleep 0.1; done
    "$lathe" sim "${machine[@]}" "$program" --format jsonl > "$work/$name.sim.jsonl"
    if "$here/run.sh" "$pty" "$program" --timeout 300 > "$work/run.log" 2>&1; then
        sleep 0.5
        if python3 - "$work/$name.sim.jsonl" "$work/$name.board.jsonl" <<'PY'
import json, sys
def load(p):
    out = []
    for l in open(p):
        r = json.loads(l); r.pop("line", None); r.pop("program", None); out.append(r)
    return out
want, got = load(sys.argv[1]), load(sys.argv[2])
if got and got[-1] == {"kind": "dwell", "seconds": 0.5}:
    got = got[:-1]
if got != want:
    n = next((i for i, (a, b) in enumerate(zip(got, want)) if a != b), min(len(got), len(want)))
    print(f"  {len(got)} actions on the board, {len(want)} from lathe sim; first difference at {n}:")
    print("  board:", got[n] if n < len(got) else None)
    print("  sim:  ", want[n] if n < len(want) else None)
    sys.exit(1)
print(f"  {len(got)} actions, identical to lathe sim")
PY
        then echo "ok   $name"; else echo "FAIL $name (actions differ)"; failed=1; fi
    else
        echo "FAIL $name (CNCjs did not complete the job)"; sed 's/^/  /' "$work/run.log" | tail -5; failed=1
    fi
    kill "$board_pid" 2>/dev/null || true; wait "$board_pid" 2>/dev/null || true
done
exit $failed

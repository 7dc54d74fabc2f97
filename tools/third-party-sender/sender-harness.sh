#!/usr/bin/env bash
# The harness of the third-party sender tests: for one program, starts `lathe board`
# on a pty with `--record`, runs a sender's stream command against it, waits until
# the board's motion core has accepted as many actions as `lathe sim` interprets for
# the file, and compares the two.
#
#   sender-harness.sh [options] LATHE_BINARY PROGRAM -- COMMAND [ARG...]
#
# In COMMAND's arguments `@PTY@` becomes the board's pty and `@PROGRAM@` the program;
# it gets a newline on stdin (stream.py waits for Enter when it is done) and runs
# under `timeout`. It passes when it exits 0 and its output matches --ok-if and does
# not match --fail-if.
#
#   --name NAME        the sender's name in messages (default: COMMAND)
#   --compare exact    the records must be byte for byte equal, line numbers included
#   --compare actions  line and program numbers ignored, one trailing `G4 P0.5`
#                      dwell of the board allowed (CNCjs strips comment, blank and `%`
#                      lines and appends that dwell)
#   --ok-if REGEX / --fail-if REGEX   (grep -E) on the sender's output
#   --timeout S        the sender's time limit (default 300)
#   --exit-after S     the board's (default 600)
#   --machine FILE     the board and `lathe sim` run that machine file (a mill:
#                      examples/machines/mill.toml)
#
# Prints `ok   <program>: …` or `FAIL <program>: …` with the sender's and the board's
# last lines; exit status 0 or 1. Used by board-test.sh (CNCjs), stream-py-test.sh
# and grbl-streamer-test.sh.
set -euo pipefail
name="" compare=exact ok_if="" fail_if="" timeout=300 exit_after=600
machine=()
while [ $# -gt 0 ]; do
    case "$1" in
        --name) name="$2"; shift 2 ;;
        --compare) compare="$2"; shift 2 ;;
        --ok-if) ok_if="$2"; shift 2 ;;
        --fail-if) fail_if="$2"; shift 2 ;;
        --timeout) timeout="$2"; shift 2 ;;
        --exit-after) exit_after="$2"; shift 2 ;;
        --machine) machine=(--machine "$2"); shift 2 ;;
        *) break ;;
    esac
done
if [ $# -lt 4 ] || [ "$3" != "--" ]; then
    echo "usage: $0 [options] LATHE_BINARY PROGRAM -- COMMAND [ARG...]" >&2
    exit 2
fi
lathe="$1" program="$2"; shift 3
name="${name:-$1}"
base="$(basename "$program")"
work="$(mktemp -d)"
trap 'kill "${board_pid:-0}" 2>/dev/null || true; wait "${board_pid:-0}" 2>/dev/null || true; rm -rf "$work"' EXIT
pty="$work/board.pty" sim="$work/sim.jsonl" record="$work/board.jsonl"

"$lathe" board "${machine[@]}" --pty "$pty" --speed 20 --record "$record" --exit-after "$exit_after" > "$work/board.log" 2>&1 &
board_pid=$!
for _ in $(seq 100); do [ -e "$pty" ] && break; sleep 0.1; done
"$lathe" sim "${machine[@]}" "$program" --format jsonl > "$sim"
want=$(wc -l < "$sim")

cmd=()
for a in "$@"; do a="${a//@PTY@/$pty}"; cmd+=("${a//@PROGRAM@/$program}"); done

tails() {
    grep -v '^> ' "$work/sender.log" | tail -6 | sed 's/^/  sender: /' || true
    tail -4 "$work/board.log" | sed 's/^/  board: /' || true
}

if ! echo | timeout "$timeout" "${cmd[@]}" > "$work/sender.log" 2>&1 \
    || { [ -n "$ok_if" ] && ! grep -qE "$ok_if" "$work/sender.log"; } \
    || { [ -n "$fail_if" ] && grep -qE "$fail_if" "$work/sender.log"; }; then
    echo "FAIL $base: $name did not complete the job"
    tails
    exit 1
fi

# The record is written as the motion core accepts actions: wait for them all.
for _ in $(seq 600); do
    [ "$(wc -l < "$record" 2>/dev/null || echo 0)" -ge "$want" ] && break
    sleep 0.1
done
sleep 0.5
if result=$(python3 - "$compare" "$sim" "$record" <<'PY'
import json, sys
mode, sim, board = sys.argv[1:4]
if mode == "exact":
    want, got = open(sim).read().splitlines(), open(board).read().splitlines()
    how = "line numbers included"
else:
    def load(p):
        out = []
        for l in open(p):
            r = json.loads(l); r.pop("line", None); r.pop("program", None); out.append(r)
        return out
    want, got = load(sim), load(board)
    if got and got[-1] == {"kind": "dwell", "seconds": 0.5}:
        got = got[:-1]
    how = "line numbers ignored"
if got != want:
    n = next((i for i, (a, b) in enumerate(zip(got, want)) if a != b), min(len(got), len(want)))
    print(f"{len(got)} actions on the board, {len(want)} from lathe sim; first difference at {n}:")
    print("  board:", got[n] if n < len(got) else None)
    print("  sim:  ", want[n] if n < len(want) else None)
    sys.exit(1)
print(f"{len(got)} actions, identical to lathe sim ({how})")
PY
); then
    echo "ok   $base: $result"
else
    echo "FAIL $base: the board's actions differ from lathe sim's: $result"
    tails
    exit 1
fi

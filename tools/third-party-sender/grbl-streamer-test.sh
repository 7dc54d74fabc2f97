#!/usr/bin/env bash
# grbl-streamer 2.0.2 (PyPI) in its raw mode (grbl-streamer/run_grbl_streamer.py)
# streams programs to `lathe board` over a pty; what the board's motion core
# accepted must equal `lathe sim` of the same file, line numbers included (raw mode
# sends every line; comment-only lines go as empty lines). Macro programs cannot
# pass: grbl-streamer empties every line with a `#` it did not define itself
# (docs/SENDERS.md).
#
#   tools/third-party-sender/grbl-streamer-test.sh LATHE_BINARY PROGRAM...
#
# Needs a Python with grbl-streamer 2.0.2 (GRBL_STREAMER_PYTHON, default python3):
#   python3 -m venv /tmp/gs && /tmp/gs/bin/pip install grbl-streamer==2.0.2
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
lathe="$1"; shift
python="${GRBL_STREAMER_PYTHON:-python3}"
work="$(mktemp -d)"
trap 'kill "${board_pid:-0}" 2>/dev/null || true; rm -rf "$work"' EXIT
failed=0
for program in "$@"; do
    name="$(basename "$program")"
    pty="$work/board.pty"
    rm -f "$pty"
    "$lathe" board --pty "$pty" --speed 20 --record "$work/$name.board.jsonl" --exit-after 600 > "$work/board.log" 2>&1 &
    board_pid=$!
    for _ in $(seq 100); do [ -e "$pty" ] && break; sleep 0.1; done
    "$lathe" sim "$program" --format jsonl > "$work/$name.sim.jsonl"
    want=$(wc -l < "$work/$name.sim.jsonl")
    if timeout 300 "$python" "$here/grbl-streamer/run_grbl_streamer.py" "$program" "$pty" 240 > "$work/stream.log" 2>&1; then
        for _ in $(seq 600); do
            [ "$(wc -l < "$work/$name.board.jsonl")" -ge "$want" ] && break
            sleep 0.1
        done
        sleep 0.5
        if cmp -s "$work/$name.sim.jsonl" "$work/$name.board.jsonl"; then
            echo "ok   $name: $want actions, identical to lathe sim (line numbers included)"
        else
            echo "FAIL $name: the board's actions differ from lathe sim's"
            diff "$work/$name.sim.jsonl" "$work/$name.board.jsonl" | head -6 | sed 's/^/  /' || true
            grep -v '^> ' "$work/stream.log" | tail -6 | sed 's/^/  sender: /' || true
            tail -6 "$work/board.log" | sed 's/^/  board: /'
            failed=1
        fi
    else
        echo "FAIL $name: grbl-streamer did not stream the file without errors"
        tail -8 "$work/stream.log" | sed 's/^/  /'
        failed=1
    fi
    kill "$board_pid" 2>/dev/null || true; wait "$board_pid" 2>/dev/null || true
done
exit $failed

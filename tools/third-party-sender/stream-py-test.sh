#!/usr/bin/env bash
# gnea/grbl's stream.py (a real third-party grbl sender, its aggressive
# character-counting mode) streams programs to `lathe board` over a pty; what the
# board's motion core accepted must equal `lathe sim` of the same file, line
# numbers included: stream.py sends every line of the file (blank and comment lines
# as empty lines, the `%` lines too) after its wake-up `\r\n\r\n`, which must not
# shift them. It strips every blank and comment and upper-cases the text.
#
#   tools/third-party-sender/stream-py-test.sh LATHE_BINARY PROGRAM...
#
# Needs Python 3 with lib2to3 and pyserial (Debian: python3-lib2to3 python3-serial;
# stream.py is Python 2, see stream-py/run_stream_py.py).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
lathe="$1"; shift
python="${STREAM_PY_PYTHON:-python3}"
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
    # stream.py waits for Enter when it has sent everything (then closes the port).
    if echo | timeout 300 "$python" "$here/stream-py/run_stream_py.py" "$program" "$pty" > "$work/stream.log" 2>&1 \
        && grep -q "G-code streaming finished" "$work/stream.log" && ! grep -q "error" "$work/stream.log"; then
        for _ in $(seq 600); do
            [ "$(wc -l < "$work/$name.board.jsonl")" -ge "$want" ] && break
            sleep 0.1
        done
        sleep 0.5
        if cmp -s "$work/$name.sim.jsonl" "$work/$name.board.jsonl"; then
            echo "ok   $name: $want actions, identical to lathe sim (line numbers included)"
        else
            echo "FAIL $name: the board's actions differ from lathe sim's"
            diff "$work/$name.sim.jsonl" "$work/$name.board.jsonl" | head -6 | sed 's/^/  /'
            failed=1
        fi
    else
        echo "FAIL $name: stream.py did not stream the file without errors"
        tail -8 "$work/stream.log" | sed 's/^/  /'
        failed=1
    fi
    kill "$board_pid" 2>/dev/null || true; wait "$board_pid" 2>/dev/null || true
done
exit $failed

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
failed=0
for program in "$@"; do
    # stream.py waits for Enter when it has sent everything (the harness gives it one).
    "$here/sender-harness.sh" --name stream.py --compare exact --ok-if "G-code streaming finished" --fail-if error \
        "$lathe" "$program" -- "$python" "$here/stream-py/run_stream_py.py" @PROGRAM@ @PTY@ || failed=1
done
exit $failed

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
failed=0
for program in "$@"; do
    "$here/sender-harness.sh" --name grbl-streamer --compare exact "$lathe" "$program" \
        -- "$python" "$here/grbl-streamer/run_grbl_streamer.py" @PROGRAM@ @PTY@ 240 || failed=1
done
exit $failed

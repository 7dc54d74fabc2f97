#!/usr/bin/env bash
# CNCjs (a real third-party grbl sender) streams programs to `lathe board` (our
# controller on the simulated machine) over a pty; what the board's motion core
# accepted must be what `lathe sim` interprets for the same file.
#
#   tools/third-party-sender/board-test.sh LATHE_BINARY PROGRAM...
#
# CNCjs strips comments, blank and `%` lines before sending (so line numbers differ)
# and appends `G4 P0.5` (the board runs it as a 0.5 s dwell, setting $303): the
# comparison ignores line numbers and allows that one trailing dwell
# (sender-harness.sh --compare actions).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
lathe="$1"; shift
failed=0
for program in "$@"; do
    "$here/sender-harness.sh" --name CNCjs --compare actions --timeout 330 --exit-after 900 "$lathe" "$program" \
        -- "$here/run.sh" @PTY@ @PROGRAM@ --timeout 300 || failed=1
done
exit $failed

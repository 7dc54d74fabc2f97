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
# comparison ignores line numbers and allows that one trailing dwell
# (sender-harness.sh --compare actions).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
lathe="$1"; shift
machine=()
if [ "${1:-}" = "--machine" ]; then machine=(--machine "$2"); shift 2; fi
failed=0
for program in "$@"; do
    "$here/sender-harness.sh" --name CNCjs --compare actions "${machine[@]}" --timeout 330 --exit-after 900 "$lathe" "$program" \
        -- "$here/run.sh" @PTY@ @PROGRAM@ --timeout 300 || failed=1
done
exit $failed

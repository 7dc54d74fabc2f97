#!/usr/bin/env bash
# Streams a G-code file to a grbl serial device with CNCjs (a real third-party
# sender), headless, at 115200 baud. Exit 0 only when CNCjs reports the job complete
# with every line acknowledged; 1 error/alarm, 2 usage, 3 timeout, 4 CNCjs could not
# start or open the device. Installs nothing: run setup.sh once first.
#   run.sh <device> <gcode-file> [--timeout SECONDS] [--verbose]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
if [ $# -lt 2 ]; then
  echo "usage: $0 <device> <gcode-file> [--timeout SECONDS] [--verbose]" >&2
  exit 2
fi
if [ ! -d "$here/node_modules/cncjs" ]; then
  echo "run.sh: CNCjs is not installed; run $here/setup.sh first" >&2
  exit 4
fi
exec node "$here/drive.js" "$@"

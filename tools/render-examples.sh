#!/usr/bin/env bash
# Regenerates the render (examples/X.svg, `lathe sim --format svg`) of every example
# program the manual shows, checking each on the way. Commit the changed .svg files;
# CI (tools/check-examples.sh) fails while a render differs from its program.
#
# Usage: tools/render-examples.sh [LATHE]
exec "$(dirname "$0")/check-examples.sh" --render "$@"

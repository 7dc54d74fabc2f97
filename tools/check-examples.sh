#!/usr/bin/env bash
# Every example program the manual shows runs as the manual says: each examples/**/*.nc
# (and *.mpf, SINUMERIK main programs) goes through `lathe check` (no alarm) and
# `lathe sim --format svg`, whose drawing must equal the committed render next to it
# (examples/X.nc -> examples/X.svg). With --render the renders are written instead:
# that is the one command that regenerates them (tools/render-examples.sh calls it).
#
# Usage: tools/check-examples.sh [--render] [LATHE]
#   LATHE: the lathe binary (default: target/debug/lathe, built by `cargo build -p lathe`)
#
# Per program, from a comment in its first 10 lines:
#   --machine examples/DIR/NAME.toml        run it on that machine (e.g. a C axis)
#   CHECK ONLY                              `lathe check` only, no `lathe sim`
# Files in a directory named lib/ are subprograms: they are given to every program
# with --lib, not run alone. The mill examples (examples/mill/) are a machine of their
# own: they run on examples/machines/mill.toml with examples/mill/lib only (its O0100
# and O0200 are not the lathe examples' programs of those numbers), and the lathe
# examples never see that lib. A fresh common-variable file (--vars) per program keeps
# the runs independent of each other.
set -euo pipefail
cd "$(dirname "$0")/.."

render=false
if [ "${1:-}" = "--render" ]; then render=true; shift; fi
lathe=${1:-${CARGO_TARGET_DIR:-target}/debug/lathe}
if [ ! -x "$lathe" ]; then
    cargo build -q -p lathe
fi

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

libs=()
while IFS= read -r d; do libs+=(--lib "$d"); done < <(find examples -type d -name lib -not -path 'examples/mill/*' | sort)
mill_libs=(--lib examples/mill/lib)

failed=0
count=0
while IFS= read -r prog; do
    count=$((count + 1))
    head=$(head -n 10 "$prog")
    opts=("${libs[@]}")
    case "$prog" in
        examples/mill/*) opts=("${mill_libs[@]}" --machine examples/machines/mill.toml) ;;
        # SINUMERIK on the machining centre (HOLES1/HOLES2/CYCLE801 …): the mill, no libraries.
        examples/sinumerik/mill/*) opts=(--machine examples/machines/mill.toml) ;;
    esac
    machine=$(grep -oiE -- '--machine +examples/[A-Za-z0-9_/.-]+\.toml' <<<"$head" | head -n 1 | sed -E 's/^--machine +//I' || true)
    if [ -n "$machine" ]; then
        # The comment may be upper case (FANUC programs are): find the file whatever its case.
        real=$(find examples -ipath "$machine" -name '*.toml' | head -n 1)
        opts+=(--machine "${real:-$machine}")
    fi
    rm -f "$tmp/vars"
    if ! "$lathe" check "$prog" "${opts[@]}" --vars "$tmp/vars" >"$tmp/out" 2>&1; then
        echo "check-examples: $prog: lathe check ${opts[*]} failed:"; cat "$tmp/out"
        failed=$((failed + 1)); continue
    fi
    if grep -qi 'CHECK ONLY' <<<"$head"; then
        echo "check-examples: $prog: checked (check only)"; continue
    fi
    svg="${prog%.*}.svg"
    rm -f "$tmp/vars"
    if ! "$lathe" sim "$prog" "${opts[@]}" --vars "$tmp/vars" --format svg --out "$tmp/render.svg" >"$tmp/out" 2>&1; then
        echo "check-examples: $prog: lathe sim ${opts[*]} failed:"; cat "$tmp/out"
        failed=$((failed + 1)); continue
    fi
    if $render; then
        cp "$tmp/render.svg" "$svg"
        echo "check-examples: $prog: checked, rendered to $svg"
    elif [ ! -f "$svg" ]; then
        echo "check-examples: $prog: no render $svg (run tools/render-examples.sh and commit it)"
        failed=$((failed + 1))
    elif ! cmp -s "$tmp/render.svg" "$svg"; then
        echo "check-examples: $prog: $svg differs from lathe sim's drawing (run tools/render-examples.sh and commit it)"
        diff "$svg" "$tmp/render.svg" | head -n 10 || true
        failed=$((failed + 1))
    else
        echo "check-examples: $prog: checked, simulated, render up to date"
    fi
done < <(find examples \( -name '*.nc' -o -name '*.mpf' \) -not -path '*/lib/*' | sort)

if [ "$count" -eq 0 ]; then echo "check-examples: no example programs found"; exit 1; fi
if [ "$failed" -ne 0 ]; then echo "check-examples: $failed of $count example programs failed"; exit 1; fi
echo "check-examples: all $count example programs pass"

#!/usr/bin/env bash
# Builds the manual: `mdbook build docs` into target/book/docs/ (docs/book.toml), then
# copies examples/ beside it, so the pages' links and images ../examples/… (the
# example programs and their renders) resolve in the built book as they do on GitHub.
# Open target/book/docs/index.html.
#
# Usage: tools/build-book.sh [MDBOOK]   (default: mdbook on the PATH)
set -euo pipefail
cd "$(dirname "$0")/.."
mdbook=${1:-mdbook}
"$mdbook" build docs
rm -rf target/book/examples
cp -r examples target/book/examples
echo "build-book: target/book/docs/index.html"

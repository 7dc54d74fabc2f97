#!/usr/bin/env bash
# Installs mdBook (the manual's builder, `mdbook build docs`) for CI, quickly: the
# prebuilt release binary from GitHub (a few seconds), or, when that cannot be fetched,
# `cargo install mdbook --locked` (several minutes on 2 cores: it compiles ~200 crates).
# Does nothing when the pinned version is already on the PATH.
#
# Usage: tools/install-mdbook.sh [DIR]   (DIR defaults to ~/.cargo/bin, on the PATH)
set -euo pipefail
version=0.5.4
dir=${1:-${CARGO_HOME:-$HOME/.cargo}/bin}

if command -v mdbook >/dev/null && [ "$(mdbook --version)" = "mdbook v$version" ]; then
    echo "install-mdbook: mdbook v$version already installed"
    exit 0
fi
mkdir -p "$dir"
url="https://github.com/rust-lang/mdBook/releases/download/v$version/mdbook-v$version-x86_64-unknown-linux-gnu.tar.gz"
start=$SECONDS
if [ "$(uname -m)" = x86_64 ] && curl -sSfL --retry 3 --connect-timeout 10 "$url" | tar -xz -C "$dir" mdbook; then
    echo "install-mdbook: release binary v$version in $((SECONDS - start)) s"
else
    echo "install-mdbook: no release binary; building it (cargo install, several minutes)"
    cargo install mdbook --locked --version "$version" --root "$(dirname "$dir")"
    echo "install-mdbook: built v$version in $((SECONDS - start)) s"
fi
"$dir/mdbook" --version

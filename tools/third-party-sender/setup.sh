#!/usr/bin/env bash
# Installs CNCjs (the third-party grbl sender run.sh drives) and its socket.io client
# into tools/third-party-sender/node_modules, exactly as pinned in package-lock.json.
# Idempotent: when node_modules already matches the lock (stamp file) and loads, it
# does nothing and needs no network. Also installs socat (apt) for selftest.sh when
# missing and we are root. Needs Node.js >= 18 with npm (the machine has Node 20).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$here"

command -v node >/dev/null || { echo "setup.sh: node is not installed" >&2; exit 1; }
major="$(node -p 'process.versions.node.split(".")[0]')"
[ "$major" -ge 18 ] || { echo "setup.sh: CNCjs needs Node.js >= 18, found $(node --version)" >&2; exit 1; }

# True when the installed tree loads: the server, the socket.io client, the JWT
# library, and serialport's native binding (a prebuilt .node inside the npm tarball).
loads() {
  node -e '
    require("./node_modules/socket.io-client");
    require("./node_modules/jsonwebtoken");
    require("./node_modules/@serialport/bindings-cpp");
    require("fs").accessSync("./node_modules/cncjs/bin/cncjs");
  ' 2>/dev/null
}

stamp="node_modules/.setup-stamp"
want="$(sha256sum package-lock.json | cut -d' ' -f1) node-$major"
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$want" ] && loads; then
  echo "setup.sh: CNCjs already installed (node_modules matches package-lock.json)"
else
  start=$SECONDS
  # npm ci: exactly the lock; --prefer-offline reuses npm's cache when it has the files.
  npm ci --no-audit --no-fund --prefer-offline --loglevel=error
  loads || { echo "setup.sh: installed, but CNCjs or serialport's binding does not load" >&2; exit 1; }
  echo "$want" > "$stamp"
  echo "setup.sh: CNCjs installed in $((SECONDS - start)) s"
fi

if ! command -v socat >/dev/null; then
  if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
    echo "setup.sh: installing socat (selftest.sh needs it)"
    apt-get update -qq >/dev/null && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq socat >/dev/null
  else
    echo "setup.sh: socat missing (selftest.sh needs it): apt-get install socat" >&2
  fi
fi

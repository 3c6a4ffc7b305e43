#!/usr/bin/env bash
# Installs the npm packages the tests use (tests/npm/: the official MCAP reader @mcap/core, its zstd
# and lz4 decompressors, Foxglove's omgidl parser and CDR decoder, the ws-protocol client and `ws`,
# its WebSocket in node), exactly as pinned by tests/npm/package-lock.json, with `npm ci`. Does
# nothing when tests/npm/node_modules exists and is newer than the lock file. Needs node and npm
# (scripts/setup.sh installs them).
set -euo pipefail
DIR="$(cd "$(dirname "$0")/.." && pwd)/tests/npm"
if [[ -d $DIR/node_modules && ! $DIR/package-lock.json -nt $DIR/node_modules ]]; then
  echo "npm_setup: tests/npm/node_modules is up to date"
  exit 0
fi
if ! command -v npm >/dev/null; then
  echo "npm_setup: npm not found (scripts/setup.sh installs Debian's nodejs and npm)" >&2
  exit 1
fi
echo "npm_setup: npm ci in tests/npm (versions of package-lock.json)"
(cd "$DIR" && npm ci --no-audit --no-fund)
touch "$DIR/node_modules"  # newer than the lock file from now on

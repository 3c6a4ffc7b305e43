#!/usr/bin/env bash
# Installs what is missing, builds, and runs the whole ctest suite (unit, integration, system).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
"$ROOT/scripts/setup.sh"
"$ROOT/scripts/npm_setup.sh"  # the official MCAP reader and Foxglove decoders (tests/npm/)
"$ROOT/scripts/build.sh"
cd "$ROOT/build"
ctest --output-on-failure -j "$(nproc)" --timeout 600

#!/usr/bin/env bash
# Configures and builds robodds into build/ (Release, warnings as errors).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
cmake -S "$ROOT" -B "$ROOT/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DROBODDS_WERROR=ON ${ROBODDS_CMAKE_ARGS:-}
cmake --build "$ROOT/build" -j "$(nproc)"

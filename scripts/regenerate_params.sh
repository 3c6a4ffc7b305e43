#!/usr/bin/env bash
# Rewrites every component's config/<name>.params.yaml from its parameter table (the one source
# of keys, defaults, units, ranges and descriptions). Run after editing a table; the unit test
# robodds_params_files_test fails until the checked-in files match.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="${ROBODDS_BUILD_DIR:-$ROOT/build}"
[[ -f "$BUILD/CMakeCache.txt" ]] || { echo "regenerate_params.sh: no build in $BUILD; run scripts/build.sh first" >&2; exit 1; }
cmake --build "$BUILD" --target robodds_regenerate_params
"$BUILD/tools/regenerate/robodds_regenerate_params" "$ROOT"
# A new component's defaults file is installed only if it existed when CMake configured: configure again.
cmake "$BUILD" >/dev/null

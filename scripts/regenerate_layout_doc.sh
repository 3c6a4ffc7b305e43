#!/usr/bin/env bash
# Rewrites the generated rows of README.md's Layout (every component folder: robodds_component();
# every metrics module of the evaluator: robodds_metrics_module()) from their registration (run it
# after adding, moving or describing one; layout_doc_test fails until you do). Builds the
# generator into build/.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="${ROBODDS_BUILD_DIR:-$ROOT/build}"
[[ -f "$BUILD/CMakeCache.txt" ]] || { echo "regenerate_layout_doc.sh: no build in $BUILD; run scripts/build.sh first" >&2; exit 1; }
cmake --build "$BUILD" --target robodds_regenerate_layout_doc
"$BUILD/tools/regenerate/robodds_regenerate_layout_doc" "$ROOT/README.md"

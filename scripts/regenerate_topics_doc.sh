#!/usr/bin/env bash
# Rewrites the topic table of docs/topics.md from the topic catalog (runtime/topics/topic_catalog.cpp:
# the runtime's own topics; system/topics.cpp: the robot system's) (run it after changing
# the catalog; runtime_topic_table_test fails until you do). Builds the generator into build/.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="${ROBODDS_BUILD_DIR:-$ROOT/build}"
[[ -f "$BUILD/CMakeCache.txt" ]] || { echo "regenerate_topics_doc.sh: no build in $BUILD; run scripts/build.sh first" >&2; exit 1; }
cmake --build "$BUILD" --target robodds_regenerate_topics_doc
"$BUILD/tools/regenerate/robodds_regenerate_topics_doc" "$ROOT/docs/topics.md"

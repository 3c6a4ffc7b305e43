#!/usr/bin/env bash
# Installs what is missing, builds, runs the main scenario and says where the results are.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
"$ROOT/scripts/setup.sh"
"$ROOT/scripts/build.sh"
SCENARIO="${1:-$ROOT/sim/scenarios/paper1_waypoints.yaml}"  # paper 1 with the particle filter in the loop
cd "$ROOT"
"$ROOT/build/tools/robodds/robodds" run "$SCENARIO"

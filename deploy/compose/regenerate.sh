#!/usr/bin/env bash
# Regenerates every shipped file of deploy/compose/ from the scenarios.
# Run it after changing a scenario's groups or components:
#   deploy/compose/regenerate.sh [ROBODDS_BINARY [OUT_DIR]]
# tests/integration/compose_test.sh regenerates into a scratch directory and requires the
# shipped files to be byte-identical, so they cannot drift.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
ROBODDS="${1:-$ROOT/build/tools/robodds/robodds}"
OUT="${2:-$ROOT/deploy/compose}"
SCENARIOS=(paper1_ideal paper1_waypoints plant_smoke)  # the shipped closed-loop scenarios
mkdir -p "$OUT"

# stdout output is written for a file in deploy/compose/ (build context and mounts "../.."),
# so the text is the same whatever OUT is.
cd "$ROOT"
for s in "${SCENARIOS[@]}"; do
  "$ROBODDS" deploy compose "sim/scenarios/$s.yaml" >"$OUT/$s.yml"
  "$ROBODDS" deploy compose "sim/scenarios/$s.yaml" --discovery server >"$OUT/$s.discovery-server.yml"
  "$ROBODDS" deploy compose "sim/scenarios/$s.yaml" --network host >"$OUT/$s.host-network.yml"
done
echo "regenerated ${#SCENARIOS[@]} scenarios x 3 variants in $OUT"

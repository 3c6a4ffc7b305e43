#!/bin/bash
# Issue 28, "straight legs": the paper's law against the path-following law
# (controller.path_lookahead_m, components/waypoint_controller/path_law.hpp) on the 500 m leg and
# on five 300 m legs, the particle filter in the loop, seeds 1-N: way-points reached, time to the
# last one, the true track's cross-track error after the first 10 m of each leg (RMS and max,
# the evaluator's cross_track_rms_m / cross_track_max_m), the estimate's RMSE.
# usage: scripts/paper1_straight_legs.sh ROBODDS OUT_DIR [SEEDS (1-10)] [LOOKAHEAD_M (3)] [DOMAIN (226)]
set -euo pipefail
R=$1 OUT=$2 SEEDS=${3:-1-10} L=${4:-3} DOMAIN=${5:-226}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$OUT"
for scenario in paper1_long_leg paper1_straight_legs; do
  for lookahead in 0 "$L"; do
    timeout 3600 "$R" --log warn sweep "$ROOT/sim/scenarios/$scenario.yaml" --seeds "$SEEDS" --jobs 1 --domain "$DOMAIN" \
      --out "$OUT/${scenario}_$lookahead" --set "controller.path_lookahead_m=$lookahead" >"$OUT/${scenario}_$lookahead.log" 2>&1
  done
done
python3 - "$OUT" "$L" <<'PY'
import csv, sys
out, lookahead = sys.argv[1], sys.argv[2]
print("| scenario | law | runs | way-points | time to final (s) | cross-track RMS (m) | cross-track max (m) | estimate RMSE (m) |")
print("|---|---|---|---|---|---|---|---|")
def span(values, fmt):
    return (fmt % min(values)) + "-" + (fmt % max(values)) if values else "-"
for scenario in ("paper1_long_leg", "paper1_straight_legs"):
    for law, key in (("paper, eq. (10)", "0"), (f"path, lookahead {lookahead} m", lookahead)):
        rows = list(csv.DictReader(open(f"{out}/{scenario}_{key}/runs.csv")))
        complete = sum(1 for r in rows if r["waypoints_reached"] == r["waypoints_total"])
        num = lambda k: [float(r[k]) for r in rows if r.get(k) not in (None, "")]
        print(f"| {scenario} | {law} | {len(rows)} | all on {complete} | {span(num('time_to_final_s'), '%.1f')} | "
              f"{span(num('cross_track_rms_m'), '%.3f')} | {span(num('cross_track_max_m'), '%.2f')} | {span(num('pf_rmse_m'), '%.3f')} |")
PY

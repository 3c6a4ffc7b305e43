#!/usr/bin/env bash
# Regenerates the "Robustness" table of docs/results/paper1.md: issue 12's cases (biased odometry,
# wrong starts, outliers, kidnapping, standstill) on paper1_waypoints over 10 seeds, two runs at a
# time, and checks issue 12's acceptance figures. Needs a build (scripts/build.sh). Extra arguments
# go to scripts/paper1_robustness.py (e.g. --seeds 3, --cases wheel_2pct,outliers_100m, --out DIR,
# --domains 5,6).
set -euo pipefail
cd "$(dirname "$0")/.."
exec python3 scripts/paper1_robustness.py --check "$@"

#!/usr/bin/env bash
# Issue 12's acceptance figures for the robust particle filter: scripts/paper1_robustness.py --check
# runs every case (one wheel 2 % fast, 1 deg/s turn-rate bias, start heading off by pi, start 20 m
# off with unknown heading, 5 % outliers at +30 m and +100 m, a 10 m and a 90-degree kidnap, 600 s
# standstill, and the nominal mission) on paper1_waypoints with the realistic actuator, over
# $SEEDS seeds (default 5 here, to keep the suite within its 30 minutes; the issue's 10-seed figures in
# docs/results/paper1.md come from `scripts/paper1_robustness.py --seeds 10`), two runs at a time (domains $DOMAIN and $DOMAIN+1),
# and fails naming every figure that misses its bound.
source "$(dirname "$0")/../integration/lib.sh"
SEEDS="${4:-5}"
# The bound on the script is the ctest TIMEOUT less a minute (as paper3_results): 128-141 s on an
# idle 2-core machine, more than 600 s beside eight CPU hogs.
limit_s=2300
rc=0
ROBODDS="$ROBODDS" timeout -k 5 "$limit_s" python3 "$SRC/scripts/paper1_robustness.py" --out "$WORK/results" --seeds "$SEEDS" \
  --domains "$DOMAIN,$((DOMAIN + 1))" --check >"$WORK/table.md" 2>"$WORK/errors.txt" || rc=$?
cat "$WORK/table.md"
[[ $rc -ne 124 ]] || fail "scripts/paper1_robustness.py did not finish within $limit_s s"
[[ $rc -eq 0 ]] || fail "paper-1 robustness figures missed: $(cat "$WORK/errors.txt")"
grep -q "^| kidnap_10m" "$WORK/table.md" || fail "no table printed"
echo "ok: every issue-12 robustness figure holds over $SEEDS seeds"

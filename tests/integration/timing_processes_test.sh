#!/usr/bin/env bash
# Compute times end to end (issue 11): the particle filter (paper1_waypoints' pf_estimator,
# stage "pf") records its step times; co-located and across processes (where they travel from
# the estimation host on run/health), in lockstep and in real time, they reach summary.json
# run.timing.pf, and the determinism comparison (same_outputs, which leaves out "run") still finds
# the co-located and multi-process lockstep runs identical.
source "$(dirname "$0")/lib.sh"
SCENARIO="$SRC/sim/scenarios/paper1_waypoints.yaml"
check_timing() {  # check_timing DIR
  python3 - "$1/summary.json" <<'PY' || fail "$(basename "$1"): summary.json lacks run.timing.pf of the estimator"
import json, sys
run = json.load(open(sys.argv[1]))["run"]
pf = run["timing"]["pf"]
assert pf["component"] == "estimator" and pf["components"] == 1, pf
# 2 s at 100 Hz: steps 0..200 in lockstep; in real time the steps the estimator's host ran
assert pf["cycles"] == 201 if run["mode"] == "lockstep" else 0 < pf["cycles"] <= 201, pf
assert 0 < pf["cycle_ms_median"] <= pf["cycle_ms_p99"] <= pf["cycle_ms_max"] < 1000, pf
print("ok (%s, %s): run.timing.pf %s" % (run["deploy"], run["mode"], pf))
PY
}
for deploy in colocated processes; do
  timeout -k 5 120 "$ROBODDS" run "$SCENARIO" --duration 2 --deploy "$deploy" --out "$WORK/$deploy" --domain "$DOMAIN" \
    --no-plots >"$WORK/$deploy.log" 2>&1 || fail "$deploy run failed: $(tail -5 "$WORK/$deploy.log")"
  check_timing "$WORK/$deploy"
done
same_outputs "$WORK/colocated" "$WORK/processes"
timeout -k 5 120 "$ROBODDS" run "$SCENARIO" --duration 2 --deploy processes --realtime $(rt_priority_flag) --max-missed-steps 1000000 \
  --out "$WORK/realtime" --domain "$DOMAIN" --no-plots >"$WORK/realtime.log" 2>&1 ||
  fail "real-time processes run failed: $(tail -5 "$WORK/realtime.log")"
check_timing "$WORK/realtime"
echo "ok: run.timing.pf co-located and across processes (lockstep and real time); co-located and processes lockstep runs: $N_CSV CSV files and the metrics identical"

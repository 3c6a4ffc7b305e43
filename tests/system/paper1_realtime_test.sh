#!/usr/bin/env bash
# Paper 1 with the particle filter, in real time (wall-clock timers, latest-sample inputs),
# across processes: 60 s of the mission make real progress (the estimate becomes valid, tracks the
# truth, and the robot reaches a way-point), so the components work outside lockstep too.
#
# How long the filter needs to become valid (heading std < 0.2 rad while the robot creeps at
# 0.3 m/s) is a property of the noise's realisation, not of the machine's load: in lockstep over
# seeds 1-230 (`robodds sweep sim/scenarios/paper1_waypoints.yaml --seeds 1-230 --duration 45`,
# 2026-12-06) it took 8.6-35.5 s, median 13.25 s, and 6 of 230 seeds took more than 30 s; in real
# time it took 11.8-16.1 s in 5 idle runs and 38.0 s once beside eight CPU hogs with no host
# missing a step. So the bound asked here is the controller's own: the estimate must be valid
# before its creep budget runs out (invalid_estimate_creep_limit_s, read from the controller's
# parameter file), since after that the robot stops for good; and a way-point must come within
# 60 s (the first one comes ~10-14 s after the estimate is valid).
source "$(dirname "$0")/../integration/lib.sh"
timeout -k 5 150 "$ROBODDS" run "$SRC/sim/scenarios/paper1_waypoints.yaml" --realtime $(rt_priority_flag) --deploy processes --duration 60 \
  --out "$WORK/run" --domain "$DOMAIN" --no-plots >"$WORK/run.log" 2>&1 || fail "run failed: $(tail -5 "$WORK/run.log")"
python3 - "$WORK/run/summary.json" "$SRC/components/waypoint_controller/config/waypoint_controller.params.yaml" <<'PY' || fail "metrics check failed: $(tail -5 "$WORK/run.log")"
import json, sys, yaml
m = json.load(open(sys.argv[1]))["metrics"]
creep_limit_s = float(yaml.safe_load(open(sys.argv[2]))["invalid_estimate_creep_limit_s"])
valid_s = m["robots"]["1"]["time_to_valid_s"]
if not 0 <= valid_s < creep_limit_s:
    sys.exit(f"FAIL: the estimate was not valid within the controller's creep budget of {creep_limit_s} s of real time (time_to_valid_s {valid_s})")
if m["waypoints_reached"] < 1:
    sys.exit(f"FAIL: no way-point reached in 60 s of real time (estimate valid after {valid_s} s)")
# Timing in real time depends on the machine's load, so only ask that the filter beats the raw fixes.
if not m["pf_rmse_m"] < m["measurement_rmse_m"]:
    sys.exit(f"FAIL: PF RMSE {m['pf_rmse_m']} m is not below the raw fixes' {m['measurement_rmse_m']} m in real time")
print(f"ok: {m['waypoints_reached']} way-points in 60 s real time, valid after {valid_s} s, PF RMSE {m['pf_rmse_m']:.3f} m")
PY

#!/usr/bin/env bash
# Paper 1 end to end with the particle filter in the loop (sim/scenarios/paper1_waypoints.yaml):
# every way-point reached at epsilon 0.1 m, PF position RMSE at most half the raw measurement
# RMSE, the heading learned from motion (unknown initial heading), the true switch distances
# reported next to the estimated ones, and the paper's figures written next to summary.json.
source "$(dirname "$0")/../integration/lib.sh"
timeout -k 5 300 "$ROBODDS" run "$SRC/sim/scenarios/paper1_waypoints.yaml" --out "$WORK/run" --domain "$DOMAIN" \
  >"$WORK/run.log" 2>&1 || fail "run failed: $(tail -5 "$WORK/run.log")"
python3 - "$WORK/run/summary.json" <<'PY' || fail "metrics check failed"
import json, sys
m = json.load(open(sys.argv[1]))["metrics"]
def check(ok, what):
    if not ok:
        sys.exit("FAIL: " + what)
check(m["waypoints_reached"] == 18, f"reached {m['waypoints_reached']}/18")
check(m["epsilon"] == 0.1, f"epsilon {m['epsilon']}")
check(m["pf_rmse_m"] <= 0.5 * m["measurement_rmse_m"], f"PF RMSE {m['pf_rmse_m']} > half the measurement RMSE {m['measurement_rmse_m']}")
# Measurement noise is 2.28 m^2 per axis: the raw position RMSE must be near sqrt(2 * 2.28) = 2.14 m.
check(1.9 < m["measurement_rmse_m"] < 2.4, f"measurement RMSE {m['measurement_rmse_m']} does not match the sensor noise")
check(m["heading_rmse_deg"] < 10.0, f"heading RMSE {m['heading_rmse_deg']} deg")
est, true_d = m["switch_distance_estimate_m"], m["switch_distance_true_m"]
check(len(est) == 18 and len(true_d) == 18, "18 switch distances of each kind")
check(max(est) <= 0.1, f"the controller switched with the estimate beyond epsilon: {max(est)}")
check(all(t >= 0.0 for t in true_d), "true switch distances present")
check(m["final_error_true_m"] < 1.5, f"final true error {m['final_error_true_m']} m")
print(f"ok: 18/18, PF RMSE {m['pf_rmse_m']:.3f} m vs measurement {m['measurement_rmse_m']:.3f} m, "
      f"heading RMSE {m['heading_rmse_deg']:.2f} deg, true switch distance max {max(true_d):.3f} m")
PY
for figure in trajectory.png velocity.png distance.png pf_error.png; do
  [[ -s "$WORK/run/$figure" ]] || fail "figure '$figure' not written: $(ls "$WORK/run")"
done
# report.py recomputes the RMSEs of pf_error.png's legend and warns when one differs from summary.json's.
if grep -q "differs from summary.json" "$WORK/run.log"; then
  fail "the plots' RMSE is not summary.json's: $(grep "differs from summary.json" "$WORK/run.log")"
fi
echo "ok: figures written, their RMSEs those of summary.json"

# Epsilon far below the estimator's error: the paper's rule alone stalls, the confidence-aware
# switch (kappa = 0.5) completes the mission with true switch distances like epsilon = 0.1 m.
sed "s/{name: controller, type: waypoint_controller, params: {/&epsilon_m: 0.01, confidence_switch_sigmas: 0.5, /" \
  "$SRC/sim/scenarios/paper1_waypoints.yaml" >"$WORK/kappa.yaml"
grep -q "confidence_switch_sigmas: 0.5" "$WORK/kappa.yaml" || fail "scenario rewrite did not apply"
timeout -k 5 300 "$ROBODDS" run "$WORK/kappa.yaml" --out "$WORK/kappa" --domain "$DOMAIN" --no-plots \
  >"$WORK/kappa.log" 2>&1 || fail "run failed: $(tail -5 "$WORK/kappa.log")"
python3 - "$WORK/kappa/summary.json" "$WORK/run/summary.json" <<'PY' || fail "confidence-aware switch check failed"
import json, sys
m = json.load(open(sys.argv[1]))["metrics"]
base = json.load(open(sys.argv[2]))["metrics"]
if m["waypoints_reached"] != 18:
    sys.exit(f"FAIL: kappa 0.5, epsilon 0.01: reached {m['waypoints_reached']}/18")
mean = lambda v: sum(v) / len(v)
if mean(m["switch_distance_true_m"]) > 1.5 * mean(base["switch_distance_true_m"]):
    sys.exit(f"FAIL: true switch distance mean {mean(m['switch_distance_true_m'])} vs {mean(base['switch_distance_true_m'])} at epsilon 0.1")
print(f"ok: epsilon 0.01 with kappa 0.5: 18/18 in {m['time_to_final_s']} s, true switch distance mean {mean(m['switch_distance_true_m']):.3f} m")
PY

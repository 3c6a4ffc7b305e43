#!/usr/bin/env bash
# Issue 12, the actuator side: paper 1 with the particle filter in the loop on a robot with real
# actuators (sim/scenarios/paper1_waypoints.yaml: 0.3 m track, 1.5 m/s wheels, 1 m/s^2, 5 rad/s^2,
# the controller aware of them). On the paper's mission and on four missions
# the project was not tuned on (random way-points with start heading pi, way-points 0.5 m apart
# with a U-turn, a way-point at the start, a 500 m leg), every way-point is reached, and what the
# plant applied (plant/state) and what the controller commanded (plant/cmd) never exceed the
# limits: |v|, |omega|, each wheel's speed, |dv/dt| and |domega/dt| from summary.json. The limits
# are read from each scenario's robot_body fact. Each scenario over seeds 1-10 (a robodds sweep).
source "$(dirname "$0")/../integration/lib.sh"
check_sweep() {  # check_sweep SCENARIO_FILE OUT_DIR: 10 seeds (robodds sweep, 2 workers on DOMAIN, DOMAIN + 1), every run checked
  local scenario="$1" out="$2" k
  timeout -k 5 600 "$ROBODDS" sweep "$scenario" --seeds 1-10 --jobs 2 --domain "$DOMAIN" --out "$out" >"$out.log" 2>&1 \
    || fail "$(basename "$scenario"): a run failed: $(grep -h failed "$out.log" | tail -3)"
  for k in $(seq 0 9); do
    check_summary "$scenario" "$out/runs/000$k/summary.json" "$(basename "$scenario" .yaml) seed $((k + 1))"
  done
}
check_summary() {  # check_summary SCENARIO_FILE SUMMARY_JSON LABEL
  local scenario="$1" summary="$2" label="$3"
  python3 - "$scenario" "$summary" "$label" <<'PY' || fail "$label: check failed"
import json, re, sys
scenario, summary, label = sys.argv[1], sys.argv[2], sys.argv[3]
body = next(line for line in open(scenario) if re.search(r"^\s*robot_body: \{", line))  # the shared fact
param = lambda key: float(re.search(key + r": ([0-9.eE+-]+)", body).group(1))
track, wheel, accel, angular = (param(k) for k in ("wheel_base_m", "max_wheel_speed_mps", "max_accel_mps2", "max_angular_accel_radps2"))
m = json.load(open(summary))["metrics"]
def check(ok, what):
    if not ok:
        sys.exit(f"FAIL: {label}: {what}")
check(m["waypoints_total"] > 0 and m["waypoints_reached"] == m["waypoints_total"],
      f"reached {m['waypoints_reached']}/{m['waypoints_total']}")
tolerance = 1e-9  # relative: differences of doubles over a step
bounds = {"v": (wheel, "mps"), "omega": (2.0 * wheel / track, "radps"), "wheel_speed": (wheel, "mps"),
          "accel": (accel, "mps2"), "angular_accel": (angular, "radps2")}
for which in ("applied", "commanded"):
    for name, (bound, unit) in bounds.items():
        key = f"max_abs_{name}_{which}_{unit}"
        check(key in m, f"{key} missing from summary.json")
        check(m[key] <= bound * (1.0 + tolerance), f"{key} = {m[key]} exceeds the limit {bound}")
check(m["max_abs_wheel_speed_applied_mps"] >= 0.5 * wheel, "the robot never drove near its wheel limit (limits not exercised)")
print(f"ok: {label}: {m['waypoints_reached']}/{m['waypoints_total']} in {m['time_to_final_s']} s, PF RMSE {m['pf_rmse_m']:.3f} m; "
      f"applied max wheel {m['max_abs_wheel_speed_applied_mps']:.4g} m/s, |dv/dt| {m['max_abs_accel_applied_mps2']:.4g}, "
      f"|domega/dt| {m['max_abs_angular_accel_applied_radps2']:.4g} (limits {wheel}, {accel}, {angular})")
PY
}
for name in paper1_waypoints paper1_random_heading_pi paper1_close_uturn paper1_waypoint_at_start paper1_long_leg; do
  check_sweep "$SRC/sim/scenarios/$name.yaml" "$WORK/$name"
done

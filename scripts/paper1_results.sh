#!/usr/bin/env bash
# Reproduces the figures of docs/results/paper1.md: the epsilon sweep with the true pose (paper
# Table 1) and the particle filter in the loop over several seeds. Prints markdown tables on
# stdout; every run's CSVs, summary.json and plots stay under OUT (default out/paper1_results).
#   scripts/paper1_results.sh [OUT]        (needs a build: scripts/build.sh)
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
ROBODDS="${ROBODDS:-$ROOT/build/tools/robodds/robodds}"
OUT="${1:-$ROOT/out/paper1_results}"
SEEDS="${SEEDS:-1 2 3 4 5 6 7 8 9 10}"
mkdir -p "$OUT"
metric() { /usr/bin/python3 -c "import json,sys; m=json.load(open(sys.argv[1]))['metrics']; v=eval(sys.argv[2], {}, m); print(v)" "$@"; }

echo "### Ideal setting (true pose), epsilon sweep"
echo
echo "| epsilon (m) | reached | time to final (s) | switch distance min / max (m) | paper switch distance (m) | max abs omega (rad/s) |"
echo "|---:|---:|---:|---|---:|---:|"
declare -A PAPER=([0.1]=0.0996 [0.01]=0.00984 [0.001]=0.000989)
for eps in 0.1 0.01 0.001; do
  sed "s/{name: controller, type: waypoint_controller}/{name: controller, type: waypoint_controller, params: {epsilon_m: $eps}}/" \
    "$ROOT/sim/scenarios/paper1_ideal.yaml" >"$OUT/ideal_$eps.yaml"
  "$ROBODDS" run "$OUT/ideal_$eps.yaml" --duration 200 --out "$OUT/ideal_$eps" >"$OUT/ideal_$eps.log" 2>&1
  s="$OUT/ideal_$eps/summary.json"
  echo "| $eps | $(metric "$s" waypoints_reached)/18 | $(metric "$s" time_to_final_s) | $(metric "$s" "'%.6g / %.6g' % (min(switch_distance_true_m), max(switch_distance_true_m))") | ${PAPER[$eps]} | $(metric "$s" "'%.1f' % max_abs_omega_commanded_radps") |"
done
# The particle-filter tables below are on the paper's ideal robot: paper1_waypoints with the
# actuator limits of issue 12 taken off the plant and the controller (the "Actuator limits"
# table at the end is on the scenario as shipped).
IDEAL="$OUT/paper1_waypoints_ideal.yaml"
sed -e 's/  - {name: plant, type: plant, params: {[^}]*}}/  - {name: plant, type: plant}/' \
  -e 's/  - {name: controller, type: waypoint_controller, params: {[^}]*}}/  - {name: controller, type: waypoint_controller, params: {}}/' \
  -e 's/^duration_s: .*/duration_s: 150.0/' "$ROOT/sim/scenarios/paper1_waypoints.yaml" >"$IDEAL"
grep -q "{name: plant, type: plant}" "$IDEAL" || { echo "paper1_results.sh: could not take the limits off" >&2; exit 1; }
echo
echo "### Particle filter in the loop (sim/scenarios/paper1_waypoints.yaml on the ideal robot), epsilon 0.1 m, by seed"
echo
echo "| seed | reached | time to final (s) | PF RMSE (m) | fix RMSE (m) | ratio | heading RMSE (deg) | true switch distance mean / max (m) | final true error (m) |"
echo "|---:|---:|---:|---:|---:|---:|---:|---|---:|"
for seed in $SEEDS; do
  "$ROBODDS" run "$IDEAL" --seed "$seed" --out "$OUT/pf_seed$seed" --no-plots >"$OUT/pf_seed$seed.log" 2>&1 || true
  s="$OUT/pf_seed$seed/summary.json"
  echo "| $seed | $(metric "$s" waypoints_reached)/18 | $(metric "$s" time_to_final_s) | $(metric "$s" "'%.3f' % pf_rmse_m") | $(metric "$s" "'%.3f' % measurement_rmse_m") | $(metric "$s" "'%.3f' % (pf_rmse_m / measurement_rmse_m)") | $(metric "$s" "'%.2f' % heading_rmse_deg") | $(metric "$s" "'%.3f / %.3f' % (sum(switch_distance_true_m) / max(1, len(switch_distance_true_m)), max(switch_distance_true_m or [float('nan')]))") | $(metric "$s" "'%.3f' % final_error_true_m") |"
done
echo
echo "### Particle filter in the loop, epsilon 0.01 m (below the estimator's error): paper rule vs confidence-aware switch"
echo
echo "| seed | kappa | reached in 300 s | time to final (s) | true switch distance mean / max (m) | estimate switch distance max (m) |"
echo "|---:|---:|---:|---:|---|---:|"
for seed in $SEEDS; do
  for kappa in 0 0.5; do
    sed "s/{name: controller, type: waypoint_controller, params: {/&epsilon_m: 0.01, confidence_switch_sigmas: $kappa/" \
      "$IDEAL" >"$OUT/kappa_$kappa.yaml"
    grep -q "confidence_switch_sigmas: $kappa" "$OUT/kappa_$kappa.yaml" || { echo "paper1_results.sh: kappa rewrite did not apply" >&2; exit 1; }
    "$ROBODDS" run "$OUT/kappa_$kappa.yaml" --seed "$seed" --duration 300 --out "$OUT/kappa${kappa}_seed$seed" --no-plots >"$OUT/kappa${kappa}_seed$seed.log" 2>&1 || true
    s="$OUT/kappa${kappa}_seed$seed/summary.json"
    echo "| $seed | $kappa | $(metric "$s" waypoints_reached)/18 | $(metric "$s" "time_to_final_s if time_to_final_s >= 0 else 'not reached'") | $(metric "$s" "'%.3f / %.3f' % (sum(switch_distance_true_m) / max(1, len(switch_distance_true_m)), max(switch_distance_true_m or [float('nan')]))") | $(metric "$s" "'%.3f' % max(switch_distance_estimate_m or [float('nan')])") |"
  done
done
echo
echo "### Actuator limits (issue 12): sim/scenarios/paper1_waypoints.yaml as shipped and four unseen missions"
echo
echo "| run | reached | time to final (s) | PF RMSE (m) | true switch distance mean / max (m) | applied max abs v (m/s) / omega (rad/s) | max wheel (m/s) | max abs dv/dt (m/s^2) / domega/dt (rad/s^2) |"
echo "|---|---:|---:|---:|---|---|---:|---|"
limited_row() {  # limited_row SUMMARY LABEL
  echo "| $2 | $(metric "$1" waypoints_reached)/$(metric "$1" waypoints_total) | $(metric "$1" time_to_final_s) | $(metric "$1" "'%.3f' % pf_rmse_m") | $(metric "$1" "'%.3f / %.3f' % (sum(switch_distance_true_m) / max(1, len(switch_distance_true_m)), max(switch_distance_true_m or [float('nan')]))") | $(metric "$1" "'%.4g / %.4g' % (max_abs_v_applied_mps, max_abs_omega_applied_radps)") | $(metric "$1" "'%.4g' % max_abs_wheel_speed_applied_mps") | $(metric "$1" "'%.4g / %.4g' % (max_abs_accel_applied_mps2, max_abs_angular_accel_applied_radps2)") |"
}
for seed in $SEEDS; do
  "$ROBODDS" run "$ROOT/sim/scenarios/paper1_waypoints.yaml" --seed "$seed" --out "$OUT/limited_seed$seed" --no-plots >"$OUT/limited_seed$seed.log" 2>&1 || true
  limited_row "$OUT/limited_seed$seed/summary.json" "paper1_waypoints seed $seed"
done
for name in paper1_random_heading_pi paper1_close_uturn paper1_waypoint_at_start paper1_long_leg; do
  "$ROBODDS" run "$ROOT/sim/scenarios/$name.yaml" --out "$OUT/$name" --no-plots >"$OUT/$name.log" 2>&1 || true
  limited_row "$OUT/$name/summary.json" "$name"
done
"$ROBODDS" run "$ROOT/sim/scenarios/paper1_waypoints.yaml" --out "$OUT/pf_default" >"$OUT/pf_default.log" 2>&1
echo
echo "Plots of the default-seed run (limited robot): $OUT/pf_default/*.png"

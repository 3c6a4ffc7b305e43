#!/usr/bin/env bash
# A pose estimate with NaN published over DDS is rejected by the way-point controller (counted,
# logged once): the controller keeps acting on the last finite estimate, so every command it
# publishes stays finite and the mission goes on.
source "$(dirname "$0")/lib.sh"
sed 's/{name: estimator, type: truth_estimator}/{name: estimator, type: truth_estimator, params: {inject_nan_at_step: 100}}/' \
  "$SRC/sim/scenarios/paper1_ideal.yaml" >"$WORK/nan.yaml"
grep -q inject_nan_at_step "$WORK/nan.yaml" || fail "scenario rewrite did not apply"
for deploy in colocated processes; do
  run_with_nan_injected "$WORK/nan.yaml" 10 "$deploy"
  expect_rejected_once "$WORK/$deploy.log" controller estimate/pose 100 x "$WORK/$deploy/plant_cmd.csv" "$WORK/$deploy/plant_state.csv"
  grep -q '"estimate/pose": 1' "$WORK/$deploy/summary.json" || fail "evaluator did not count the rejected estimate"
  reached=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['metrics']['waypoints_reached'])" "$WORK/$deploy/summary.json")
  [[ $reached -ge 1 ]] || fail "mission did not progress after the NaN estimate (reached $reached)"
  echo "ok ($deploy): NaN estimate rejected, commands finite, $reached way-points reached in 10 s"
done

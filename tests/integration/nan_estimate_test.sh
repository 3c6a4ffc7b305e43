#!/usr/bin/env bash
# A pose estimate with NaN published over DDS is rejected by the way-point controller (counted,
# logged once): the controller keeps acting on the last finite estimate, so every command it
# publishes stays finite and the mission goes on.
source "$(dirname "$0")/lib.sh"
sed 's/{name: estimator, type: truth_estimator}/{name: estimator, type: truth_estimator, params: {inject_nan_at_step: 100}}/' \
  "$SRC/sim/scenarios/paper1_ideal.yaml" >"$WORK/nan.yaml"
grep -q inject_nan_at_step "$WORK/nan.yaml" || fail "scenario rewrite did not apply"
for deploy in colocated processes; do
  timeout -k 5 120 "$ROBODDS" run "$WORK/nan.yaml" --duration 10 --out "$WORK/$deploy" --domain "$DOMAIN" --deploy "$deploy" --no-plots \
    >"$WORK/$deploy.log" 2>&1 || fail "run failed: $(cat "$WORK/$deploy.log")"
  grep -q "\[warn\] controller: rejected a sample on estimate/pose (robot_id=1, step 100): field 'x' is not finite" "$WORK/$deploy.log" \
    || fail "controller did not report the NaN estimate: $(cat "$WORK/$deploy.log")"
  [[ $(grep -c "controller: rejected" "$WORK/$deploy.log") -eq 1 ]] || fail "rejection logged more than once"
  grep -qiE "nan|inf" "$WORK/$deploy/plant_cmd.csv" && fail "a non-finite value reached plant/cmd"
  grep -qiE "nan|inf" "$WORK/$deploy/plant_state.csv" && fail "a non-finite value reached plant/state"
  grep -q '"estimate/pose": 1' "$WORK/$deploy/summary.json" || fail "evaluator did not count the rejected estimate"
  reached=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['metrics']['waypoints_reached'])" "$WORK/$deploy/summary.json")
  [[ $reached -ge 1 ]] || fail "mission did not progress after the NaN estimate (reached $reached)"
  echo "ok ($deploy): NaN estimate rejected, commands finite, $reached way-points reached in 10 s"
done

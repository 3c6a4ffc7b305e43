#!/usr/bin/env bash
# A command with NaN published over DDS is rejected by the plant (counted, logged once) and
# never integrated: every recorded state stays finite.
source "$(dirname "$0")/lib.sh"
sed 's/{name: commander, type: open_loop_commander}/{name: commander, type: open_loop_commander, params: {inject_nan_at_step: 100}}/' \
  "$SRC/sim/scenarios/plant_smoke.yaml" >"$WORK/nan.yaml"
grep -q inject_nan_at_step "$WORK/nan.yaml" || fail "scenario rewrite did not apply"
for deploy in colocated processes; do
  run_with_nan_injected "$WORK/nan.yaml" 3 "$deploy"
  expect_rejected_once "$WORK/$deploy.log" plant plant/cmd 100 v "$WORK/$deploy/plant_state.csv"
  grep -q '"plant/cmd": 3' "$WORK/$deploy/summary.json" || fail "evaluator did not count 3 rejected commands (one per robot)"
  echo "ok ($deploy): NaN command rejected, state finite"
done

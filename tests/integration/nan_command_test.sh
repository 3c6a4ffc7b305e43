#!/usr/bin/env bash
# A command with NaN published over DDS is rejected by the plant (counted, logged once) and
# never integrated: every recorded state stays finite.
source "$(dirname "$0")/lib.sh"
sed 's/{name: commander, type: open_loop_commander}/{name: commander, type: open_loop_commander, params: {inject_nan_at_step: 100}}/' \
  "$SRC/sim/scenarios/plant_smoke.yaml" >"$WORK/nan.yaml"
for deploy in colocated processes; do
  timeout -k 5 120 "$ROBODDS" run "$WORK/nan.yaml" --duration 3 --out "$WORK/$deploy" --domain "$DOMAIN" --deploy "$deploy" --no-plots \
    >"$WORK/$deploy.log" 2>&1 || fail "run failed: $(cat "$WORK/$deploy.log")"
  grep -q "\[warn\] plant: rejected a sample on plant/cmd (robot_id=1, step 100): field 'v' is not finite" "$WORK/$deploy.log" \
    || fail "plant did not report the NaN command: $(cat "$WORK/$deploy.log")"
  [[ $(grep -c "plant: rejected" "$WORK/$deploy.log") -eq 1 ]] || fail "rejection logged more than once"
  grep -qiE "nan|inf" "$WORK/$deploy/plant_state.csv" && fail "a non-finite value reached plant/state"
  grep -q '"plant/cmd": 3' "$WORK/$deploy/summary.json" || fail "evaluator did not count 3 rejected commands (one per robot)"
  echo "ok ($deploy): NaN command rejected, state finite"
done

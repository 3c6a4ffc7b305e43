#!/usr/bin/env bash
# Paper 2 with one process per robot (each robot's range sensor, observers and controller in a
# group of their own, plus the world and the evaluator) gives byte-identical CSVs and identical
# metrics to the same scenario co-located: lockstep across a target switch, a robot leaving and
# range noise. Arguments after the domain: scenario name, event time (s), duration (s).
source "$(dirname "$0")/../integration/lib.sh"
python3 "$(dirname "$0")/paper2_per_robot.py" "$SRC/sim/scenarios/$4.yaml" "$WORK/per_robot.yaml" "$5" "$6" \
  || fail "could not write the per-robot scenario"
groups=$(grep -c '^  robot[0-9]*:' "$WORK/per_robot.yaml")
[[ $groups -eq 4 ]] || fail "expected 4 robot groups, got $groups: $(cat "$WORK/per_robot.yaml")"
timeout -k 5 300 "$ROBODDS" run "$WORK/per_robot.yaml" --out "$WORK/colocated" --domain "$DOMAIN" --no-plots >"$WORK/colocated.log" 2>&1 \
  || fail "co-located run failed: $(tail -5 "$WORK/colocated.log")"
timeout -k 5 600 "$ROBODDS" run "$WORK/per_robot.yaml" --out "$WORK/processes" --domain "$DOMAIN" --deploy processes \
  --no-plots >"$WORK/processes.log" 2>&1 || fail "processes run failed: $(tail -5 "$WORK/processes.log")"
same_outputs "$WORK/colocated" "$WORK/processes"
grep -q 'robot_id' "$WORK/colocated/plant_state.csv" || fail "no plant_state.csv rows"
echo "ok: $4 with one process per robot ($groups robots + world + evaluator): $N_CSV CSV files and the metrics identical to co-located"

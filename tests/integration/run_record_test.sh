#!/usr/bin/env bash
# `robodds run --record FILE`: the run records the topics its components publish, from inside the
# run (a run_recorder component in the evaluator's group, reading through lockstep-gated inputs).
#   - bad input: an unwritable --record path, an unknown --record-topics name, a bad
#     --record-compression, --record-foxglove-scene without --record or without plant/state in
#     --record-topics: one line, exit 2, before the run starts;
#   - lockstep determinism: plant_smoke (5 s, with --record-foxglove-scene) and paper1_waypoints
#     (20 s) each recorded co-located and with --deploy processes give byte-identical files (cmp);
#   - plant_smoke's file read by the official reader: its foxglove/robot_poses messages (JSON) hold
#     every robot's plant/state pose, exactly at the first step and then each 50 ms of the stamps
#     (scene_matches_states.py --lockstep);
#   - paper1_waypoints' file read by the official reader with Foxglove's omgidl decoder
#     (tests/npm/check_mcap.mjs): every topic the evaluator records has as many messages as CSV
#     rows, every column of each row equals the decoded message's field, log_time = the sample's
#     step x step_s (ns) and publish_time = its stamp (recording_matches_csvs.py).
# Args: ROBODDS SRC DOMAIN. Needs node and tests/npm/node_modules (scripts/npm_setup.sh). ~15 s.
source "$(dirname "$0")/lib.sh"
CHECK="$SRC/tests/npm/check_mcap.mjs"
command -v node >/dev/null || fail "node not found (scripts/setup.sh installs nodejs)"
[[ -d $SRC/tests/npm/node_modules/@mcap/core ]] || fail "tests/npm/node_modules missing: run scripts/npm_setup.sh"
SMOKE="$SRC/sim/scenarios/plant_smoke.yaml"
PAPER1="$SRC/sim/scenarios/paper1_waypoints.yaml"

expect_error 2 "--record $WORK/no/dir/x.mcap: cannot write it \(No such file or directory\)" -- \
  "$ROBODDS" run "$SMOKE" --record "$WORK/no/dir/x.mcap" --out "$WORK/bad" --no-plots --domain "$DOMAIN"
expect_error 2 "unknown topic 'plant/stat'" -- \
  "$ROBODDS" run "$SMOKE" --record "$WORK/x.mcap" --record-topics plant/state,plant/stat --out "$WORK/bad" --no-plots --domain "$DOMAIN"
expect_error 2 "unknown compression 'gzip'" -- \
  "$ROBODDS" run "$SMOKE" --record "$WORK/x.mcap" --record-compression gzip --out "$WORK/bad" --no-plots --domain "$DOMAIN"
expect_error 2 "--record-topics, --record-compression and --record-foxglove-scene go with --record FILE.mcap" -- \
  "$ROBODDS" run "$SMOKE" --record-foxglove-scene --out "$WORK/bad" --no-plots --domain "$DOMAIN"
expect_error 2 "foxglove_scene \(robodds run --record-foxglove-scene\) draws the robots from plant/state: add it to --record-topics" -- \
  "$ROBODDS" run "$SMOKE" --record "$WORK/x.mcap" --record-topics sensor/position --record-foxglove-scene --out "$WORK/bad" \
  --no-plots --domain "$DOMAIN"
[[ ! -e $WORK/bad/summary.json ]] || fail "a refused --record still ran"

record() {  # record NAME SCENARIO DEPLOY SECONDS [MORE ARGS]
  local rc=0
  timeout -k 5 120 "$ROBODDS" run "$2" --deploy "$3" --duration "$4" --domain "$DOMAIN" --out "$WORK/$1" --no-plots \
    --record "$WORK/$1.mcap" "${@:5}" >"$WORK/$1.log" 2>&1 || rc=$?
  [[ $rc -eq 0 ]] || fail "robodds run $2 --deploy $3 --record exited $rc: $(tail -20 "$WORK/$1.log")"
  grep -q '"status": "completed"' "$WORK/$1/summary.json" || fail "$1: the run did not complete"
}
for scenario in smoke paper1; do
  file=$SMOKE seconds=5 more=(--record-foxglove-scene)
  [[ $scenario == paper1 ]] && file=$PAPER1 seconds=20 more=()
  record "${scenario}_colocated" "$file" colocated "$seconds" "${more[@]}"
  record "${scenario}_processes" "$file" processes "$seconds" "${more[@]}"
  cmp "$WORK/${scenario}_colocated.mcap" "$WORK/${scenario}_processes.mcap" ||
    fail "$scenario: the recordings co-located and across processes differ (lockstep must give the same bytes)"
  echo "ok: $scenario: co-located and --deploy processes recordings byte-identical ($(stat -c %s "$WORK/${scenario}_colocated.mcap") bytes)"
done

official="$(timeout -k 5 60 node "$CHECK" "$WORK/smoke_colocated.mcap" 2>&1)" || fail "official reader on plant_smoke: $(tail -3 <<<"$official")"
echo "$official" >"$WORK/smoke.jsonl"
python3 "$SRC/tests/integration/scene_matches_states.py" "$WORK/smoke.jsonl" "$WORK/smoke_colocated/plant_state.csv" --lockstep ||
  fail "plant_smoke's foxglove/robot_poses do not hold plant/state's poses by the 50 ms rule"

info="$("$ROBODDS" info "$WORK/paper1_colocated.mcap" 2>&1)" || fail "robodds info: $info"
grep -q "^summary: *present, CRCs valid" <<<"$info" || fail "not a whole file: $info"
official="$(timeout -k 5 60 node "$CHECK" "$WORK/paper1_colocated.mcap" 2>&1)" || fail "official reader: $(tail -3 <<<"$official")"
echo "$official" >"$WORK/paper1.jsonl"
python3 "$SRC/tests/integration/recording_matches_csvs.py" "$WORK/paper1.jsonl" "$WORK/paper1_colocated" 10000000 ||
  fail "the recording does not hold what the run's CSVs hold"
echo "ok: run_record"

#!/usr/bin/env bash
# Issue 25's replay acceptance, in lockstep: paper1_waypoints (60 s of it) is recorded, then its PF
# estimator alone is re-run on the recorded sensor topics through the replay_source component
# (replay + pf_estimator + evaluator, co-located): estimate_pose.csv must be byte-identical to the
# original run's; with a changed PF parameter (num_particles) it must differ (the use case: tune an algorithm
# on recorded data). Then bad input, one line each: a scenario that runs replay_source beside the
# original producer of a replayed topic (the one-producer check refuses it), a topic the file does
# not hold, a run longer than the recording, and replay_source in real time.
# Args: ROBODDS SRC DOMAIN. Uses domains DOMAIN and DOMAIN+1. ~25 s.
source "$(dirname "$0")/lib.sh"
DOMAIN2=$((DOMAIN + 1))
DURATION=60
TOPICS=(sensor/position sensor/odometry mission/waypoints)

# The original run, recorded by `robodds record` beside it. Across processes (--deploy processes):
# a co-located lockstep run starts stepping at once and is over in < 1 s, before the recorder has
# discovered its writers (a recorder beside it lost the first ~20 samples: the re-run then waits at
# step 0 and replay_source warns that the recorder started late); the hosts' own discovery before a
# run across processes gives the recorder that time. The recorder reads best effort (the monitor
# profile); on one machine it gets every sample after that, and a recording that lost one in the
# middle is refused by replay_source's completeness check (one line naming the stream and the step).
# (`robodds run --record`, recording from inside the run, is another branch's work.)
"$ROBODDS" record "${TOPICS[@]}" --out "$WORK/rec.mcap" --domain "$DOMAIN" >"$WORK/rec.log" 2>&1 &
rec=$!
cleanup_pids+=("$rec")
for _ in $(seq 100); do grep -qE "^robodds record: [0-9]+ topics" "$WORK/rec.log" && break; sleep 0.1; done
sleep 1  # its readers matched (discovery) before the run's writers start
rc=0
timeout -k 5 120 "$ROBODDS" run "$SRC/sim/scenarios/paper1_waypoints.yaml" --duration "$DURATION" --deploy processes --domain "$DOMAIN" \
  --out "$WORK/orig" --no-plots >"$WORK/orig.log" 2>&1 || rc=$?
[[ $rc -eq 0 ]] || fail "the original run exited $rc: $(tail -20 "$WORK/orig.log")"
sleep 0.5
kill -INT "$rec"
wait "$rec" || fail "the recorder failed: $(cat "$WORK/rec.log")"
info="$("$ROBODDS" info "$WORK/rec.mcap")" || fail "robodds info on the recording: $info"
# The recording holds every sample the run's evaluator recorded (its CSV rows): else the recorder
# beside the run lost some (best effort), which is what this says rather than a re-run that differs.
for topic in sensor/position sensor/odometry; do
  csv_rows=$(($(wc -l <"$WORK/orig/${topic//\//_}.csv") - 1))
  recorded="$(awk -v t="$topic" '$2 == t {print $(NF-1)}' <<<"$info" | tr -d ,)"
  [[ $recorded == "$csv_rows" ]] || fail "the recorder beside the run got $recorded samples of $topic, the run had $csv_rows: $info"
done
echo "ok: the recording holds every sensor sample of the run ($(grep -E '^messages:' <<<"$info"))"

# The re-run: the recording's sensor topics drive the PF estimator alone.
write_scenario() {  # FILE COMPONENTS_YAML
  cat >"$1" <<EOF
name: paper1_pf_replay
description: paper1_waypoints' particle filter on recorded sensor data
step_s: 0.01
duration_s: $DURATION
seed: 7
facts:
  robot_body: {wheel_base_m: 0.3, max_wheel_speed_mps: 1.5, max_accel_mps2: 1.0, max_angular_accel_radps2: 5.0}
robots:
  - {id: 1, x: 50.0, y: 10.0, theta: 0.0}
components:
$2
EOF
}
REPLAY="  - {name: replay, type: replay_source, params: {file: $WORK/rec.mcap, topics: [sensor/position, sensor/odometry]}}"
write_scenario "$WORK/replay.yaml" "$REPLAY
  - {name: estimator, type: pf_estimator}
  - {name: evaluator, type: evaluator, params: {topics: [estimate/pose]}}"
for variant in same changed; do
  sets=()
  [[ $variant == changed ]] && sets=(--set estimator.num_particles=500 --set estimator.resample_threshold=250)
  rc=0
  timeout -k 5 120 "$ROBODDS" run "$WORK/replay.yaml" --domain "$DOMAIN2" --out "$WORK/$variant" --no-plots "${sets[@]}" \
    >"$WORK/$variant.log" 2>&1 || rc=$?
  [[ $rc -eq 0 ]] || fail "the re-run ($variant) exited $rc: $(tail -20 "$WORK/$variant.log")"
done
rows="$(wc -l <"$WORK/orig/estimate_pose.csv")"
((rows > 100 * DURATION / 2)) || fail "the original estimate_pose.csv has only $rows lines"
cmp "$WORK/orig/estimate_pose.csv" "$WORK/same/estimate_pose.csv" ||
  fail "the PF re-run on the recording does not reproduce estimate_pose.csv"
echo "ok: the PF estimator re-run on the recording: estimate_pose.csv byte-identical ($rows lines)"
cmp -s "$WORK/orig/estimate_pose.csv" "$WORK/changed/estimate_pose.csv" &&
  fail "with num_particles 500 the re-run gave the same estimate_pose.csv"
[[ $(wc -l <"$WORK/changed/estimate_pose.csv") -eq $rows ]] || fail "the changed re-run has another number of rows"
echo "ok: with num_particles 500: a different estimate_pose.csv, same rows"

# Bad input: one line each, before the run starts.
write_scenario "$WORK/two.yaml" "$REPLAY
  - {name: plant, type: plant}
  - {name: position_sensor, type: position_sensor}
  - {name: estimator, type: pf_estimator}"
expect_error 2 "sensor/position.*(replay|position_sensor).*(replay|position_sensor)" -- \
  "$ROBODDS" run "$WORK/two.yaml" --domain "$DOMAIN2" --out "$WORK/x" --no-plots
write_scenario "$WORK/missing.yaml" "  - {name: replay, type: replay_source, params: {file: $WORK/rec.mcap, topics: [sensor/range]}}"
expect_error 2 "replay\.topics: .*rec\.mcap has no topic 'sensor/range' \(its topics: .*sensor/position.*\)" -- \
  "$ROBODDS" run "$WORK/missing.yaml" --domain "$DOMAIN2" --out "$WORK/x" --no-plots
expect_error 2 "replay: .*rec\.mcap cannot drive this run: sensor/(position|odometry) \(robot_id=1\): the recording ends at step [0-9]+ but the run goes to step 7000" -- \
  "$ROBODDS" run "$WORK/replay.yaml" --duration 70 --domain "$DOMAIN2" --out "$WORK/x" --no-plots
expect_error 2 "replay: replay_source runs in lockstep only" -- \
  "$ROBODDS" run "$WORK/replay.yaml" --realtime --duration 1 --domain "$DOMAIN2" --out "$WORK/x" --no-plots
echo "ok: replay_lockstep"

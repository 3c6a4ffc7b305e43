#!/usr/bin/env bash
# `robodds run --record` of papers 2 and 3 in lockstep, checked by the official reader (issue 25):
#   - paper2_circumnavigation (20 s, its target switch and robot 4's leave moved from 1000 s to
#     10 s) and paper3_exp2 (20 s), the evaluator told to record every topic the run publishes
#     that it can write to CSV (--set evaluator.topics=[...]);
#   - each file passes tests/npm/check_mcap.mjs (@mcap/core: CRCs, footer, summary, chunk and
#     message indexes; statistics and chunk indexes against the messages; the streaming reader
#     finds the same messages) and every message decodes with Foxglove's omgidl decoder to the
#     values of the run's CSVs (recording_matches_csvs.py: counts, every column, log and publish
#     times; paper 3's evaluator serves robot 1, so a second run with an evaluator of robots 2 and
#     3 gives their rows);
#   - paper 3's pair-keyed topics are in the file: the six estimate/relative_pose* (in the CSVs)
#     and sensor/uwb (no CSV: every direction at every 50 Hz step, shape, ranges near the true
#     distance of plant_state.csv);
#   - each recorded co-located and with --deploy processes gives byte-identical files;
#   - the checks can fail: a flipped payload byte fails the official reader, a changed CSV value
#     fails the comparison;
#   - replay (issue 25, docs/record-replay.md "In lockstep"): paper 3's relative estimator alone,
#     re-run on its recording through replay_source (sensor/uwb pairs, sensor/odometry,
#     plant/state), gives byte-identical estimate_relative_pose*.csv, and other ones with another
#     window_epochs; a robot the recording lacks and a pair the scenario lacks, one line each.
# Args: ROBODDS SRC DOMAIN. Needs node and tests/npm/node_modules (scripts/npm_setup.sh). 11-18 s on
# a loaded 2-vCPU machine (the replay part: < 1.5 s of it).
source "$(dirname "$0")/lib.sh"
CHECK="$SRC/tests/npm/check_mcap.mjs"
MATCH="$SRC/tests/integration/recording_matches_csvs.py"
command -v node >/dev/null || fail "node not found (scripts/setup.sh installs nodejs)"
[[ -d $SRC/tests/npm/node_modules/@mcap/core ]] || fail "tests/npm/node_modules missing: run scripts/npm_setup.sh"

# Paper 2 with its events early enough for a 20 s run.
sed 's/time_s: 1000\.0/time_s: 10.0/' "$SRC/sim/scenarios/paper2_circumnavigation.yaml" >"$WORK/paper2.yaml"
grep -q "time_s: 10.0, robots: \[4\], leave: true" "$WORK/paper2.yaml" || fail "paper2_circumnavigation.yaml's events changed: update this test"
PAPER2_TOPICS="[plant/state, plant/cmd, estimate/pose, mission/target, sensor/range, observer/range_rate, observer/range_rate_linear, observer/range_rate_kf]"
PAPER3_TOPICS="[plant/state, plant/cmd, estimate/pose, sensor/odometry, estimate/relative_pose, estimate/relative_pose_uwb, estimate/relative_pose_window, estimate/relative_pose_pf_baseline, estimate/relative_pose_odometry, estimate/relative_pose_tc]"

record() {  # record NAME SCENARIO DEPLOY TOPICS
  local rc=0
  timeout -k 5 120 "$ROBODDS" run "$2" --deploy "$3" --duration 20 --domain "$DOMAIN" --out "$WORK/$1" --no-plots \
    --set "evaluator.topics=$4" --record "$WORK/$1.mcap" >"$WORK/$1.log" 2>&1 || rc=$?
  [[ $rc -eq 0 ]] || fail "robodds run $2 --deploy $3 --record exited $rc: $(tail -20 "$WORK/$1.log")"
  grep -q '"status": "completed"' "$WORK/$1/summary.json" || fail "$1: the run did not complete"
  ! grep -q "not recorded" "$WORK/$1.log" || fail "$1: the recorder left topics out: $(grep "not recorded" "$WORK/$1.log")"
}
official() {  # official NAME: the official reader's JSON lines in NAME.jsonl
  timeout -k 5 60 node "$CHECK" "$WORK/$1.mcap" >"$WORK/$1.jsonl" 2>"$WORK/$1.check" ||
    fail "official reader on $1.mcap: $(tail -3 "$WORK/$1.check")"
}

record paper2 "$WORK/paper2.yaml" colocated "$PAPER2_TOPICS"
record paper2_processes "$WORK/paper2.yaml" processes "$PAPER2_TOPICS"
cmp "$WORK/paper2.mcap" "$WORK/paper2_processes.mcap" ||
  fail "paper 2: the recordings co-located and across processes differ (lockstep must give the same bytes)"
echo "ok: paper2: co-located and --deploy processes recordings byte-identical ($(stat -c %s "$WORK/paper2.mcap") bytes)"
official paper2
python3 "$MATCH" "$WORK/paper2.jsonl" "$WORK/paper2" 20000000 || fail "paper 2: the recording does not hold what the CSVs hold"
grep -q '"topic":"mission/target".*"robot_id":4' "$WORK/paper2.jsonl" || fail "paper 2: no mission/target of robot 4"

record paper3 "$SRC/sim/scenarios/paper3_exp2.yaml" colocated "$PAPER3_TOPICS"
# Its evaluator serves robot 1 (the relative poses are robot 1's): the same run with an evaluator
# of robots 2 and 3 writes their rows of the robot-keyed topics (lockstep: the same samples).
python3 - "$SRC/sim/scenarios/paper3_exp2.yaml" "$WORK/paper3_robots23.yaml" <<'PY'
import sys
text = open(sys.argv[1]).read()
old = "    type: evaluator\n    robots: [1]\n"
assert old in text, "paper3_exp2.yaml's evaluator changed: update run_record_papers_test.sh"
open(sys.argv[2], "w").write(text.replace(old, "    type: evaluator\n    robots: [2, 3]\n"))
PY
timeout -k 5 120 "$ROBODDS" run "$WORK/paper3_robots23.yaml" --duration 20 --domain "$DOMAIN" --out "$WORK/paper3_robots23" \
  --no-plots --set "evaluator.topics=[plant/state, plant/cmd, estimate/pose, sensor/odometry]" >"$WORK/paper3_robots23.log" 2>&1 ||
  fail "paper 3 with the evaluator of robots 2 and 3: $(tail -5 "$WORK/paper3_robots23.log")"
record paper3_processes "$SRC/sim/scenarios/paper3_exp2.yaml" processes "$PAPER3_TOPICS"
cmp "$WORK/paper3.mcap" "$WORK/paper3_processes.mcap" ||
  fail "paper 3: the recordings co-located and across processes differ (lockstep must give the same bytes)"
echo "ok: paper3: co-located and --deploy processes recordings byte-identical ($(stat -c %s "$WORK/paper3.mcap") bytes)"
official paper3
python3 "$MATCH" "$WORK/paper3.jsonl" "$WORK/paper3:$WORK/paper3_robots23" 10000000 --no-csv sensor/uwb ||
  fail "paper 3: the recording does not hold what the CSVs hold"
python3 - "$WORK/paper3.jsonl" "$WORK/paper3/plant_state.csv" <<'PY' || fail "paper 3: sensor/uwb in the file is not what the sensors published"
import csv, json, math, sys
STEP_NS, STEPS = 10_000_000, 2000  # paper3_exp2: step_s 0.01, 20 s; UWB at 50 Hz: every 2nd step
truth = {(int(r["robot_id"]), int(r["header.step"])): (float(r["x"]), float(r["y"])) for r in csv.DictReader(open(sys.argv[2]))}
uwb = [m for m in map(json.loads, open(sys.argv[1])) if m["topic"] == "sensor/uwb"]
directions = {(1, 2), (1, 3), (2, 1), (2, 3)}  # uwb1 serves robot 1, uwb2 robot 2; every other robot is a peer
seen = {}
for m in uwb:
    v = m["value"]
    pair, step = (v["robot_id"], v["peer_id"]), v["header"]["step"]
    assert pair in directions, f"sensor/uwb of {pair}"
    assert int(m["log_time"]) == step * STEP_NS and step % 2 == 0, f"sensor/uwb {pair}: step {step}, log_time {m['log_time']}"
    seen.setdefault(pair, []).append(step)
    ranges = v["ranges"]
    assert len(ranges) == v["rows"] * v["cols"], f"sensor/uwb {pair} step {step}: {len(ranges)} ranges for {v['rows']} x {v['cols']}"
    if ranges:  # empty: out of range or a lost frame
        (ax, ay), (bx, by) = truth[(pair[0], step)], truth[(pair[1], step)]
        d = math.hypot(bx - ax, by - ay)
        mean = sum(ranges) / len(ranges)
        assert abs(mean - d) < 1.5, f"sensor/uwb {pair} step {step}: mean range {mean} m, true distance {d} m"
for pair in directions:
    assert seen.get(pair) == list(range(0, STEPS + 1, 2)), f"sensor/uwb {pair}: not every 50 Hz step, in order"
print(f"ok: sensor/uwb: {len(uwb)} messages, every direction at every 50 Hz step, ranges near the true distances")
PY
grep -q "channels: *11" <("$ROBODDS" info "$WORK/paper3.mcap") || fail "paper 3: not 11 channels: $("$ROBODDS" info "$WORK/paper3.mcap")"

# Replay (issue 25): paper 3's relative estimator alone re-run on this recording (replay_source of
# sensor/uwb, keyed by pairs of robots, sensor/odometry and plant/state for the evaluator's truth):
# the same estimate_relative_pose*.csv byte for byte; recorded itself (--record), its recorder
# waits for the sensor/uwb pairs the replay declares (every sample recorded); with another window
# the estimates differ, as many lines. Then a scenario robot the recording lacks (the estimator
# waits for its pairs) and a recorded pair of a robot the scenario lacks, one line each.
python3 - "$SRC/sim/scenarios/paper3_exp2.yaml" "$WORK" <<'PY'
import sys, yaml
scenario = yaml.safe_load(open(sys.argv[1]))
kept = [c for c in scenario["components"] if c["type"] in ("uwb_relative_estimator", "evaluator")]
assert [c["name"] for c in kept] == ["estimator1", "evaluator"], "paper3_exp2.yaml's components changed: update this test"
scenario["components"] = [{"name": "replay", "type": "replay_source",
                           "params": {"file": "paper3.mcap", "topics": ["sensor/uwb", "sensor/odometry", "plant/state"]}}] + kept
del scenario["groups"]
yaml.safe_dump(scenario, open(sys.argv[2] + "/paper3_replay.yaml", "w"), sort_keys=False)
robots = scenario["robots"]
scenario["robots"] = robots + [{"id": 4, "x": 3.0, "y": 3.0, "theta": 0.0}]
yaml.safe_dump(scenario, open(sys.argv[2] + "/paper3_replay_robot4.yaml", "w"), sort_keys=False)
scenario["robots"] = [r for r in robots if r["id"] != 3]
yaml.safe_dump(scenario, open(sys.argv[2] + "/paper3_replay_no_robot3.yaml", "w"), sort_keys=False)
PY
replayed() {  # replayed NAME [ARGS...]: the re-run in $WORK/NAME (its scenario reads paper3.mcap from $WORK)
  local name="$1" rc=0
  shift
  (cd "$WORK" && timeout -k 5 60 "$ROBODDS" run paper3_replay.yaml --duration 20 --domain "$DOMAIN" --out "$name" --no-plots "$@") \
    >"$WORK/$name.log" 2>&1 || rc=$?
  [[ $rc -eq 0 ]] || fail "the paper 3 re-run $name exited $rc: $(tail -5 "$WORK/$name.log")"
}
replayed paper3_replayed --record paper3_replayed.mcap
for f in "$WORK"/paper3/estimate_relative_pose*.csv; do
  cmp "$f" "$WORK/paper3_replayed/$(basename "$f")" || fail "paper 3 re-run on its recording: $(basename "$f") differs"
done
uwb_count() { "$ROBODDS" info "$1" | awk '$2 == "sensor/uwb" {print $(NF-1)}'; }
! grep -q "not recorded" "$WORK/paper3_replayed.log" || fail "the re-run's recorder left topics out: $(grep "not recorded" "$WORK/paper3_replayed.log")"
[[ -n $(uwb_count "$WORK/paper3.mcap") && $(uwb_count "$WORK/paper3_replayed.mcap") == "$(uwb_count "$WORK/paper3.mcap")" ]] ||
  fail "the re-run recorded $(uwb_count "$WORK/paper3_replayed.mcap") sensor/uwb samples, the original $(uwb_count "$WORK/paper3.mcap")"
replayed paper3_tuned --set estimator1.window_epochs=20
for f in "$WORK"/paper3/estimate_relative_pose*.csv; do
  [[ $(wc -l <"$f") -eq $(wc -l <"$WORK/paper3_tuned/$(basename "$f")") ]] || fail "tuned paper 3 re-run: $(basename "$f") has other lines"
done
! cmp -s "$WORK/paper3/estimate_relative_pose.csv" "$WORK/paper3_tuned/estimate_relative_pose.csv" ||
  fail "paper 3 re-run with window_epochs 20: estimate_relative_pose.csv did not change"
echo "ok: paper 3's estimator re-run on the recording: 6 estimate_relative_pose*.csv byte-identical ($(wc -l <"$WORK/paper3/estimate_relative_pose.csv") lines), $(uwb_count "$WORK/paper3_replayed.mcap") sensor/uwb recorded again; window_epochs 20 differs"
(cd "$WORK" && expect_error 2 "paper3_replay_robot4\.yaml: components: lockstep: component 'estimator1' waits at every step for sensor/uwb \(robot_id=1 peer_id=4\), an instance its producer 'replay' does not publish" -- \
  "$ROBODDS" run paper3_replay_robot4.yaml --duration 20 --domain "$DOMAIN" --out robot4 --no-plots)
(cd "$WORK" && expect_error 2 "replay: paper3\.mcap cannot drive this run: sensor/uwb \(robot_id=1 peer_id=3\): robot 3 is not a robot of the scenario \(its robots: 1, 2\)" -- \
  "$ROBODDS" run paper3_replay_no_robot3.yaml --duration 20 --domain "$DOMAIN" --out no_robot3 --no-plots)

# The checks can fail: one payload byte flipped (the last message's last byte, in the last chunk,
# uncompressed), one CSV double changed by one bit.
"$ROBODDS" run "$SRC/sim/scenarios/paper3_exp2.yaml" --duration 0.5 --domain "$DOMAIN" --out "$WORK/flip" --no-plots \
  --set "evaluator.topics=$PAPER3_TOPICS" --record "$WORK/flip.mcap" --record-compression none >"$WORK/flip.log" 2>&1 ||
  fail "the short paper 3 run failed: $(tail -5 "$WORK/flip.log")"
python3 - "$WORK/flip.mcap" <<'PY'
import struct, sys
data = bytearray(open(sys.argv[1], "rb").read())
offset, last_chunk_end = 8, None  # after the magic: opcode (1 byte), length (8), body
while data[offset] != 0x0F:  # up to Data End
    end = offset + 9 + struct.unpack_from("<Q", data, offset + 1)[0]
    if data[offset] == 0x06:  # Chunk: uncompressed here, its records end with the last message's payload
        last_chunk_end = end
    offset = end
data[last_chunk_end - 1] ^= 0x01
open(sys.argv[1], "wb").write(data)
PY
if node "$CHECK" "$WORK/flip.mcap" >/dev/null 2>"$WORK/flip.check"; then fail "the official reader accepted a flipped byte"; fi
grep -q "CRC" "$WORK/flip.check" || fail "the flipped byte was refused for another reason: $(cat "$WORK/flip.check")"
echo "ok: a flipped byte is refused by the official reader: $(head -c 200 "$WORK/flip.check")"
python3 - "$WORK/paper2/observer_range_rate.csv" <<'PY'
import math, sys
lines = open(sys.argv[1]).read().split("\n")
column = lines[0].split(",").index("range_rate")
cells = lines[5].split(",")
cells[column] = repr(math.nextafter(float(cells[column]), math.inf))  # the next double: one bit
lines[5] = ",".join(cells)
open(sys.argv[1], "w").write("\n".join(lines))
PY
if python3 "$MATCH" "$WORK/paper2.jsonl" "$WORK/paper2" 20000000 >/dev/null 2>"$WORK/changed.check"; then
  fail "a changed CSV value passed the comparison"
fi
echo "ok: a changed CSV value is found: $(cat "$WORK/changed.check")"
echo "ok: run_record_papers"

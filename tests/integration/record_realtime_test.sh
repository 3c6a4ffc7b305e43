#!/usr/bin/env bash
# `robodds record --all` as its own process beside a real-time run of plant_smoke across processes
# (4 hosts + coordinator), like `ros2 bag record` beside a running system. Two recorders at once:
#   A: stopped with SIGINT after the run: its file must be whole (`robodds info`: summary present,
#      CRCs valid), the official reader (@mcap/core with Foxglove's omgidl decoder,
#      tests/npm/check_mcap.mjs) must read and decode every message, the message counts per topic
#      must be the run's CSV row counts (plant/state, plant/cmd, sensor/position: the evaluator's
#      topics), and every CSV row of plant/state must be in the file with the same values. A also
#      has --foxglove-scene: its foxglove/robot_poses messages (JSON) must hold plant/state's poses.
#   B: 16 KB chunks, killed with SIGKILL 3 s into the run: the run must complete all the same
#      (status completed: a recorder is no host of the run), and `robodds info` must recover the
#      complete chunks of B's file (no summary).
#   C: --max-size 0.05 MB, SIGTERM: split into C_0.mcap, C_1.mcap, ..., each whole, holding A's
#      messages between them.
#   D: --duration 2: exits 0 by itself with a whole file.
# Before that, bad input (unknown topic, unwritable --out, bad --compression, --foxglove-scene
# without plant/state): one line, exit 2.
# Args: ROBODDS SRC DOMAIN. Needs node and tests/npm/node_modules (scripts/npm_setup.sh). ~15 s.
source "$(dirname "$0")/lib.sh"
CHECK="$SRC/tests/npm/check_mcap.mjs"
command -v node >/dev/null || fail "node not found (scripts/setup.sh installs nodejs)"
[[ -d $SRC/tests/npm/node_modules/@mcap/core ]] || fail "tests/npm/node_modules missing: run scripts/npm_setup.sh"

# Bad input: one line each, exit 2, before joining the domain.
expect_error 2 "unknown topic 'plant/stat'; did you mean 'plant/state'\? .*robodds record --list. lists the topics" -- \
  "$ROBODDS" record plant/state plant/stat --out "$WORK/x.mcap" --domain "$DOMAIN"
expect_error 2 "$WORK/no/dir/x.mcap: cannot create the MCAP file: No such file or directory" -- \
  "$ROBODDS" record --all --out "$WORK/no/dir/x.mcap" --domain "$DOMAIN"
expect_error 2 "unknown compression 'gzip' .accepted: none, zstd, lz4." -- \
  "$ROBODDS" record --all --out "$WORK/x.mcap" --compression gzip --domain "$DOMAIN"
expect_error 2 "name the topics to record or give --all .not both." -- "$ROBODDS" record --out "$WORK/x.mcap"
expect_error 2 "--foxglove-scene draws the robots from plant/state: add it to the topics" -- \
  "$ROBODDS" record sensor/position --foxglove-scene --out "$WORK/x.mcap" --domain "$DOMAIN"
"$ROBODDS" record --list | grep -qE "^plant/state +robodds::idl::RobotState +monitor" || fail "record --list"
echo "ok: bad input"

$(rt_chrt 10) "$ROBODDS" record --all --foxglove-scene --out "$WORK/a.mcap" --domain "$DOMAIN" >"$WORK/a.log" 2>&1 &
rec_a=$!
cleanup_pids+=("$rec_a")
$(rt_chrt 10) "$ROBODDS" record --all --out "$WORK/b.mcap" --chunk-size 16 --compression lz4 --domain "$DOMAIN" >"$WORK/b.log" 2>&1 &
rec_b=$!
cleanup_pids+=("$rec_b")
$(rt_chrt 10) "$ROBODDS" record --all --out "$WORK/c.mcap" --max-size 0.05 --chunk-size 8 --compression none --domain "$DOMAIN" \
  >"$WORK/c.log" 2>&1 &
rec_c=$!
cleanup_pids+=("$rec_c")
$(rt_chrt 10) "$ROBODDS" record plant/state --out "$WORK/d.mcap" --duration 2 --domain "$DOMAIN" >"$WORK/d.log" 2>&1 &
rec_d=$!
cleanup_pids+=("$rec_d")
for log in a b c; do  # both joined the domain (the line comes after their readers exist)
  for _ in $(seq 100); do grep -qE "^robodds record: [0-9]+ topics" "$WORK/$log.log" && break; sleep 0.1; done
  grep -qE "^robodds record: [0-9]+ topics" "$WORK/$log.log" || fail "recorder $log did not start: $(cat "$WORK/$log.log")"
done

(sleep 3; kill -KILL "$rec_b") &
cleanup_pids+=("$!")
rc=0
# --max-missed-steps: what this test checks is the recording of whatever the run published (counts
# = CSV rows), not the run's period (integration.timing_processes, overrun and the papers' real-time
# tests hold that). Its 5 s run has a default budget of 25 skipped steps, and a busy CI machine once
# stalled its sim host 0.32 s right after step 0 (32 skipped: the run failed, the recording was fine).
timeout -k 5 60 "$ROBODDS" run "$SRC/sim/scenarios/plant_smoke.yaml" --realtime $(rt_priority_flag) --deploy processes --duration 5 \
  --max-missed-steps 1000000 --domain "$DOMAIN" --out "$WORK/out" --no-plots >"$WORK/run.log" 2>&1 || rc=$?
[[ $rc -eq 0 ]] || fail "robodds run exited $rc: $(tail -20 "$WORK/run.log")"
sleep 0.5  # the last samples in flight to the recorders

grep -q '"status": "completed"' "$WORK/out/summary.json" || fail "the run did not complete beside a killed recorder: $(cat "$WORK/out/summary.json")"
wait "$rec_b" 2>/dev/null || true
# Fast DDS 2.9.1 as Debian builds it may abort a participant when a remote participant's lease
# expires (PDP.cpp:1140, docs/deployment.md "Troubleshooting"): here B's, killed on purpose.
# Only when a recorder hit that or the defect below is the test run once more, saying so; any other end of A or
# C before its signal fails at once, with its log.
# The same family: deleting a recorder's DDS readers may block in Fast DDS after a peer was killed
# (bounded: "shutdown: deleting the raw DDS readers ... did not finish", exit 3; seen 1 in 5 here);
# the recorder finishes its file before that teardown, so the file is whole either way.
retry_or_fail() {
  local known
  known=$(grep -lE "PDP.cpp:1140|shutdown: deleting the raw DDS readers .* did not finish" "$WORK/a.log" "$WORK/c.log" 2>/dev/null | head -1)
  [[ -n $known && -z ${RECORD_REALTIME_RETRY:-} ]] || fail "$1"
  echo "recorder $(basename "$known" .log) hit a known Fast DDS 2.9.1 defect ($(grep -hoE "PDP.cpp:1140|deleting the raw DDS readers" "$known" | head -1)) after B was killed: running the test once more"
  kill -KILL "$rec_a" "$rec_c" "$rec_d" 2>/dev/null || true
  wait "$rec_a" "$rec_c" "$rec_d" 2>/dev/null || true
  trap - EXIT
  cleanup
  RECORD_REALTIME_RETRY=1 exec bash "$0" "$ROBODDS" "$SRC" "$DOMAIN"
}
kill -TERM "$rec_c" 2>/dev/null || retry_or_fail "recorder C ended before its SIGTERM: $(tail -5 "$WORK/c.log")"
kill -INT "$rec_a" 2>/dev/null || retry_or_fail "recorder A ended before its SIGINT: $(tail -5 "$WORK/a.log")"
rc=0
timeout -k 2 20 tail --pid="$rec_a" -f /dev/null || fail "recorder A did not finish within 20 s of SIGINT"
wait "$rec_a" || rc=$?
[[ $rc -eq 0 ]] || retry_or_fail "recorder A exited $rc after SIGINT: $(cat "$WORK/a.log")"
cat "$WORK/a.log"

info="$("$ROBODDS" info "$WORK/a.mcap" 2>&1)" || fail "robodds info on A failed: $info"
grep -q "^summary: *present, CRCs valid" <<<"$info" || fail "A is not a whole file: $info"
official="$(timeout -k 5 60 node "$CHECK" "$WORK/a.mcap" 2>&1)" || fail "official reader on A: $(tail -3 <<<"$official")"
echo "$official" >"$WORK/a.jsonl"
python3 - "$WORK/a.jsonl" "$WORK/out" <<'PY' || fail "A does not hold what the run recorded"
import csv, json, os, sys
messages = [json.loads(line) for line in open(sys.argv[1])]
counts = {}
for m in messages:
    counts[m["topic"]] = counts.get(m["topic"], 0) + 1
for topic in ("plant/state", "plant/cmd", "sensor/position"):
    rows = list(csv.DictReader(open(os.path.join(sys.argv[2], topic.replace("/", "_") + ".csv"))))
    # The recorder reads best effort (the monitor profile, as `robodds echo`) and the evaluator
    # with the topic's own profile; on one machine both get every sample.
    assert counts.get(topic, 0) == len(rows), f"{topic}: {counts.get(topic, 0)} messages in the file, {len(rows)} CSV rows"
    print(f"ok: {topic}: {len(rows)} messages = CSV rows")
# Every plant/state row, decoded by Foxglove's decoder from our bytes, has the CSV's values.
decoded = {(m["value"]["robot_id"], m["value"]["header"]["step"]): m["value"]
           for m in messages if m["topic"] == "plant/state"}
rows = list(csv.DictReader(open(os.path.join(sys.argv[2], "plant_state.csv"))))
for r in rows:
    v = decoded.get((int(r["robot_id"]), int(r["header.step"])))
    assert v is not None, f"plant/state robot {r['robot_id']} step {r['header.step']} not in the file"
    for field in ("x", "y", "theta", "v", "omega"):
        assert float(r[field]) == float(v[field]), f"plant/state {field}: CSV {r[field]}, file {v[field]}"
    assert int(r["header.stamp_ns"]) == int(v["header"]["stamp_ns"])
print(f"ok: plant/state: all {len(rows)} CSV rows in the file with equal values (official decoder)")
# log_time is the reception time: after the source time (publish_time), within a second of it.
for m in messages:
    lag = int(m["log_time"]) - int(m["publish_time"])
    assert 0 <= lag < 1_000_000_000, f"{m['topic']}: log_time - publish_time = {lag} ns"
print("ok: log_time (reception) after publish_time (source timestamp) for all", len(messages), "messages")
PY
# --foxglove-scene: every robot's newest pose at most once per 50 ms of the stamps, each a plant/state row.
python3 "$SRC/tests/integration/scene_matches_states.py" "$WORK/a.jsonl" "$WORK/out/plant_state.csv" ||
  fail "A's foxglove/robot_poses do not hold plant/state's poses"

rc=0
info_b="$("$ROBODDS" info "$WORK/b.mcap" 2>&1)" || rc=$?
[[ $rc -eq 0 ]] || fail "robodds info on the SIGKILLed file exited $rc: $info_b"
grep -q "^summary: *missing" <<<"$info_b" || fail "B (SIGKILL) should have no summary: $info_b"
recovered="$(sed -nE 's/.* ([0-9,]+) complete chunks, ([0-9,]+) messages recovered.*/\1 \2/p' <<<"$info_b" | head -1 | tr -d ,)"
[[ -n $recovered ]] || fail "robodds info did not say what it recovered from B: $info_b"
read -r chunks_b messages_b <<<"$recovered"
total_a="$(grep -vc '"topic":"foxglove/robot_poses"' "$WORK/a.jsonl")"  # the recorded topics, not A's derived channel
# B recorded the first ~1.5 s of the run (3 s after the launch, which starts 5 processes first),
# ~480 messages/s, less its open chunk (a 16 KB chunk of these topics holds < 300 messages).
((chunks_b >= 3 && messages_b >= 200 && messages_b < total_a)) ||
  fail "B (SIGKILL): $chunks_b chunks, $messages_b messages recovered; A has $total_a: $info_b"
rc=0
wait "$rec_c" || rc=$?
[[ $rc -eq 0 ]] || retry_or_fail "recorder C exited $rc after SIGTERM: $(cat "$WORK/c.log")"
[[ ! -e $WORK/c.mcap && -e $WORK/c_0.mcap && -e $WORK/c_2.mcap ]] || fail "C not split into c_0.mcap, c_1.mcap, ...: $(ls "$WORK")"
messages_c=0
topics_c="$(sed -nE 's/^robodds record: ([0-9]+) topics.*/\1/p' "$WORK/c.log")"  # --all: every topic of the catalog
for part in "$WORK"/c_*.mcap; do
  info_c="$("$ROBODDS" info "$part" 2>&1)" || fail "robodds info $part: $info_c"
  grep -q "^summary: *present, CRCs valid" <<<"$info_c" || fail "$part is not a whole file: $info_c"
  grep -q "^channels: *$topics_c\b" <<<"$info_c" || fail "$part lacks channels (expected $topics_c): $info_c"
  n="$(sed -nE 's/^messages: *([0-9,]+).*/\1/p' <<<"$info_c" | tr -d ,)"
  messages_c=$((messages_c + n))
done
((messages_c == total_a)) || fail "C's parts hold $messages_c messages, A $total_a"
echo "ok: --max-size: $(ls "$WORK"/c_*.mcap | wc -l) whole files, $messages_c messages in all"
timeout -k 2 10 tail --pid="$rec_d" -f /dev/null || fail "recorder D did not stop by itself (--duration 2)"
rc=0
wait "$rec_d" || rc=$?
[[ $rc -eq 0 ]] || fail "recorder D (--duration 2) exited $rc: $(cat "$WORK/d.log")"
info_d="$("$ROBODDS" info "$WORK/d.mcap" 2>&1)" || fail "robodds info on D: $info_d"
grep -q "^summary: *present, CRCs valid" <<<"$info_d" && grep -q "^channels: *1$" <<<"$info_d" || fail "D: $info_d"
echo "ok: --duration 2: a whole file of one channel, $(sed -nE 's/^duration: *//p' <<<"$info_d") of log times"
echo "ok: SIGKILLed recorder: $chunks_b complete chunks, $messages_b of $total_a messages recovered"
echo "ok: record_realtime"

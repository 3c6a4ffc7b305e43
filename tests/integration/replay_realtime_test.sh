#!/usr/bin/env bash
# `robodds replay` in real time, like `ros2 bag play`: a real-time plant_smoke (co-located, domain
# DOMAIN) is recorded by `robodds record` (A), then A is replayed at --rate 2 on domain DOMAIN+1
# into a second recorder (B). B must hold every message of A, per topic, with the same values
# (decoded by the official reader, tests/npm/check_mcap.mjs) and half of A's log-time span (the
# rate, within 20 %). Bad input, one clear line each: an unknown --topics name, a channel whose
# schema is not ours (robodds-mcap-sample-writer's file), a truncated file (a warning, replays what
# was recovered, exit 0), a corrupted file, a missing file; and a replay onto a domain where a
# replayed topic already has a writer (a running plant_smoke): a warning naming the topic and the
# other participant, the replay goes on. --start 1 --end 2 replays the messages of that second.
# Args: ROBODDS SRC DOMAIN SAMPLE_WRITER. Uses domains DOMAIN and DOMAIN+1. Needs node and
# tests/npm/node_modules (scripts/npm_setup.sh). ~25 s.
source "$(dirname "$0")/lib.sh"
SAMPLE_WRITER="$4"
DOMAIN2=$((DOMAIN + 1))
CHECK="$SRC/tests/npm/check_mcap.mjs"
command -v node >/dev/null || fail "node not found (scripts/setup.sh installs nodejs)"
[[ -d $SRC/tests/npm/node_modules/@mcap/core ]] || fail "tests/npm/node_modules missing: run scripts/npm_setup.sh"
TOPICS=(plant/state plant/cmd sensor/position)
QUICK=(--wait-readers 0 --discovery-time 0 --fast)  # bad-input cases: nothing to wait for

# Recording A: 3 s of a real-time run (16 KB chunks: a cut file keeps some).
"$ROBODDS" record "${TOPICS[@]}" --out "$WORK/a.mcap" --chunk-size 16 --domain "$DOMAIN" >"$WORK/a.log" 2>&1 &
rec_a=$!
cleanup_pids+=("$rec_a")
for _ in $(seq 100); do grep -qE "^robodds record: [0-9]+ topics" "$WORK/a.log" && break; sleep 0.1; done
rc=0
timeout -k 5 60 "$ROBODDS" run "$SRC/sim/scenarios/plant_smoke.yaml" --realtime --duration 3 --domain "$DOMAIN" \
  --out "$WORK/out" --no-plots $(rt_priority_flag) >"$WORK/run.log" 2>&1 || rc=$?
[[ $rc -eq 0 ]] || fail "robodds run exited $rc: $(tail -20 "$WORK/run.log")"
sleep 0.5
kill -INT "$rec_a"
wait "$rec_a" || fail "recorder A failed: $(cat "$WORK/a.log")"

# Replay A at twice the speed into recorder B on another domain.
"$ROBODDS" record "${TOPICS[@]}" --out "$WORK/b.mcap" --domain "$DOMAIN2" >"$WORK/b.log" 2>&1 &
rec_b=$!
cleanup_pids+=("$rec_b")
for _ in $(seq 100); do grep -qE "^robodds record: [0-9]+ topics" "$WORK/b.log" && break; sleep 0.1; done
rc=0
timeout -k 5 60 "$ROBODDS" replay "$WORK/a.mcap" --rate 2 --domain "$DOMAIN2" >"$WORK/replay.log" 2>&1 || rc=$?
cat "$WORK/replay.log"
[[ $rc -eq 0 ]] || fail "robodds replay exited $rc"
grep -q "warning" "$WORK/replay.log" && fail "a replay onto a free domain with a reader warned"
sleep 0.5
kill -INT "$rec_b"
wait "$rec_b" || fail "recorder B failed: $(cat "$WORK/b.log")"
timeout -k 5 60 node "$CHECK" "$WORK/a.mcap" >"$WORK/a.jsonl" || fail "official reader on A"
timeout -k 5 60 node "$CHECK" "$WORK/b.mcap" >"$WORK/b.jsonl" || fail "official reader on B"
python3 - "$WORK/a.jsonl" "$WORK/b.jsonl" <<'PY' || fail "B is not A replayed at --rate 2"
import json, sys
a, b = ([json.loads(line) for line in open(p)] for p in sys.argv[1:3])
def by_topic(ms):
    out = {}
    for m in ms:
        out.setdefault(m["topic"], []).append(json.dumps(m["value"], sort_keys=True))
    return out
ta, tb = by_topic(a), by_topic(b)
for topic in sorted(ta):
    assert len(tb.get(topic, [])) == len(ta[topic]), f"{topic}: {len(ta[topic])} messages recorded, {len(tb.get(topic, []))} replayed"
    assert sorted(tb[topic]) == sorted(ta[topic]), f"{topic}: replayed values differ from the recorded ones"
    print(f"ok: {topic}: {len(ta[topic])} messages replayed with the recorded values")
span = lambda ms: (max(int(m["log_time"]) for m in ms) - min(int(m["log_time"]) for m in ms)) / 1e9
ratio = span(b) / span(a)
print(f"ok: log-time span {span(a):.3f} s recorded, {span(b):.3f} s replayed at --rate 2 (ratio {ratio:.3f})")
assert 0.4 <= ratio <= 0.6, f"replayed span / recorded span = {ratio:.3f}, expected 0.5 (--rate 2)"
PY

# --start/--end: the messages whose log time is 1 to 2 s after the file's first.
out="$(timeout -k 5 60 "$ROBODDS" replay "$WORK/a.mcap" --start 1 --end 2 --domain "$DOMAIN2" "${QUICK[@]}" 2>&1)" ||
  fail "replay --start 1 --end 2: $out"
expected="$(python3 -c '
import json, sys
t = [int(json.loads(line)["log_time"]) for line in open(sys.argv[1])]
print(sum(1 for x in t if min(t) + 1e9 <= x <= min(t) + 2e9))' "$WORK/a.jsonl")"
grep -qE "^robodds replay: [0-9]+ messages in .* \(recorded span (0\.9[0-9]+|1\.000) s\)" <<<"$out" &&
  grep -qE "^robodds replay: .*a\.mcap: $expected messages on 3 topics" <<<"$out" ||
  fail "--start 1 --end 2: expected $expected messages within 1 s of log time: $out"
echo "ok: --start 1 --end 2: $expected messages"

# Bad input: one line each.
expect_error 2 "--topics: unknown topic 'plant/stat': not in .*a\.mcap \(its topics: plant/cmd, plant/state, sensor/position\)" -- \
  "$ROBODDS" replay "$WORK/a.mcap" --topics plant/state,plant/stat --domain "$DOMAIN2" "${QUICK[@]}"
"$SAMPLE_WRITER" "$WORK"
expect_error 2 "sample_zstd\.mcap: channel 'test/(sample|bytes)' has schema .*, a schema that is not ours: 'test/(sample|bytes)' is no robodds topic" -- \
  "$ROBODDS" replay "$WORK/sample_zstd.mcap" --domain "$DOMAIN2" "${QUICK[@]}"
expect_error 2 "no/such\.mcap: cannot open: No such file or directory" -- \
  "$ROBODDS" replay "$WORK/no/such.mcap" --domain "$DOMAIN2" "${QUICK[@]}"
python3 - "$WORK/a.mcap" "$WORK/cut.mcap" "$WORK/flipped.mcap" <<'PY'
import sys
b = open(sys.argv[1], "rb").read()
open(sys.argv[2], "wb").write(b[: len(b) * 2 // 3])  # cut in the data section
f = bytearray(b)
f[len(b) // 3] ^= 1  # one bit inside a chunk
open(sys.argv[3], "wb").write(f)
PY
expect_error 2 "flipped\.mcap: byte [0-9]+: .*\(the file is damaged; .robodds info .*flipped\.mcap. lists every problem\)" -- \
  "$ROBODDS" replay "$WORK/flipped.mcap" --domain "$DOMAIN2" "${QUICK[@]}"
rc=0
out="$(timeout -k 5 60 "$ROBODDS" replay "$WORK/cut.mcap" --domain "$DOMAIN2" "${QUICK[@]}" 2>&1)" || rc=$?
[[ $rc -eq 0 ]] || fail "truncated file: exit $rc: $out"
[[ $(grep -c "warning" <<<"$out") -eq 1 ]] &&
  grep -qE "^robodds replay: warning: .*cut\.mcap: truncated at byte [0-9]+: [0-9]+ complete chunks?, [0-9,]+ messages recovered; summary missing; replaying what was recovered$" <<<"$out" ||
  fail "truncated file: expected one warning line: $out"
echo "ok: truncated file: one warning, replays what was recovered"

# A producer already on the domain: a run publishes plant/state; the replay names it and goes on.
# The replay starts once the run publishes (on a busy machine its start takes seconds), and waits
# for the run's reader as long as a user's replay would (--wait-readers ends when it is found).
# One process per group: a co-located real-time run has no DDS reader of the topics it produces
# (it reads them in memory), so the replay would also wait for a reader in vain.
timeout -k 5 60 "$ROBODDS" run "$SRC/sim/scenarios/plant_smoke.yaml" --realtime --deploy processes --duration 20 --domain "$DOMAIN2" \
  --out "$WORK/out2" --no-plots $(rt_priority_flag) >"$WORK/run2.log" 2>&1 &
run2=$!
cleanup_pids+=("$run2")
timeout -k 2 30 "$ROBODDS" echo plant/state --count 1 --timeout 25 --domain "$DOMAIN2" >/dev/null ||
  fail "the run on domain $DOMAIN2 published no plant/state within 25 s: $(tail -5 "$WORK/run2.log")"
rc=0
out="$(timeout -k 5 60 "$ROBODDS" replay "$WORK/a.mcap" --topics plant/state --end 0.5 --wait-readers 10 --domain "$DOMAIN2" 2>&1)" || rc=$?
[[ $rc -eq 0 ]] || fail "replay beside a producer: exit $rc: $out"
[[ $(grep -c "warning" <<<"$out") -eq 1 ]] &&
  grep -qE "^robodds replay: warning: plant/state already has a writer on domain $DOMAIN2 \(participant '[^']+'\): the run's one-producer rule will refuse one of them" <<<"$out" ||
  fail "replay beside a producer: expected one warning naming plant/state and the participant: $out"
echo "ok: a producer already on the domain: $(grep warning <<<"$out")"
kill -INT "$run2" 2>/dev/null
wait "$run2" || true
echo "ok: replay_realtime"

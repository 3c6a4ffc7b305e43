#!/usr/bin/env bash
# `robodds bridge` (Foxglove WebSocket protocol) beside a real-time plant_smoke run (3 robots,
# 100 Hz, co-located, --rt-priority where allowed) and `robodds record plant/state` on the same
# domain, checked with the official client (@foxglove/ws-protocol's FoxgloveClient on `ws`,
# tests/npm/bridge_client.mjs):
#   - A receives the advertisements (plant/state: omgidl, cdr, robodds::idl::RobotState),
#     subscribes to plant/state and decodes >= 100 messages with Foxglove's omgidl decoder from the
#     advertised schema; every one equals the recorder's sample of the same robot and stamp; after
#     its unsubscribe (and a 300 ms ack window) it gets nothing in 1 s;
#   - B subscribes to every channel and stalls (its socket paused): A's rate while B stalls stays
#     within 15 % of the run's 300 messages/s, the run completes (its missed-step limit holds) and
#     the bridge logs drops for B;
#   - C sends garbage text, a binary frame, malformed JSON, a subscribe to an unknown channel and an
#     unsubscribe of an unknown subscription: one error status each, one log line each, A served on;
#   - A gets plant/state unadvertised when the run ends (its last writer gone);
#   - D reads --foxglove-scene's foxglove/robot_poses: foxglove.PosesInFrame (JSON), the recorded
#     poses, at most one message per 50 ms of the stamps;
#   - SIGINT stops the bridge within 5 s with its receive->send latency line.
# Before that, bad command lines: one line, exit 2, and --duration 1. Args: ROBODDS SRC DOMAIN PORT
# (PORT and PORT+1). ~25 s.
source "$(dirname "$0")/lib.sh"
PORT="$4"
CLIENT="$SRC/tests/npm/bridge_client.mjs"
CHECK="$SRC/tests/npm/check_mcap.mjs"
command -v node >/dev/null || fail "node not found (scripts/setup.sh installs nodejs)"
[[ -d $SRC/tests/npm/node_modules/ws ]] || fail "tests/npm/node_modules/ws missing: run scripts/npm_setup.sh"

# Bad command lines: one line each, exit 2, before joining the domain.
expect_error 2 "--topics: unknown topic 'plant/stat'" -- "$ROBODDS" bridge --topics plant/stat --domain "$DOMAIN" --port "$PORT"
expect_error 2 "--address 'localhostt': not an IP address" -- "$ROBODDS" bridge --address localhostt --domain "$DOMAIN" --port "$PORT"
expect_error 2 "--client-queue: 0 messages is outside \[1, 1000000\]" -- "$ROBODDS" bridge --client-queue 0 --domain "$DOMAIN" --port "$PORT"
echo "ok: bad command lines"
rc=0
timeout -k 2 30 "$ROBODDS" bridge --duration 1 --domain "$DOMAIN" --port "$((PORT + 1))" >"$WORK/duration.log" 2>&1 || rc=$?
[[ $rc -eq 0 ]] && grep -q "receive->send latency" "$WORK/duration.log" || fail "bridge --duration 1 exited $rc: $(cat "$WORK/duration.log")"
echo "ok: --duration 1 stops by itself"

# A small send buffer and queue for the clients, so the stalled client's drops start within seconds.
$(rt_chrt 10) "$ROBODDS" bridge --domain "$DOMAIN" --port "$PORT" --foxglove-scene --client-queue 200 --client-send-buffer 4096 \
  --client-socket-buffer 4096 \
  >"$WORK/bridge.log" 2>&1 &
bridge=$!
cleanup_pids+=("$bridge")
$(rt_chrt 10) "$ROBODDS" record plant/state --out "$WORK/rec.mcap" --domain "$DOMAIN" >"$WORK/rec.log" 2>&1 &
rec=$!
cleanup_pids+=("$rec")
for log in bridge rec; do
  for _ in $(seq 100); do grep -qsE "^robodds (bridge|record): [0-9]+ topics" "$WORK/$log.log" && break; sleep 0.1; done
  grep -qE "^robodds (bridge|record): [0-9]+ topics" "$WORK/$log.log" || fail "$log did not start: $(cat "$WORK/$log.log")"
done
expect_error 2 "--address/--port 127.0.0.1:$PORT: cannot listen" -- "$ROBODDS" bridge --domain "$DOMAIN" --port "$PORT"
echo "ok: a second bridge on the same port is refused"

timeout -k 5 60 "$ROBODDS" run "$SRC/sim/scenarios/plant_smoke.yaml" --realtime $(rt_priority_flag) --duration 16 \
  --domain "$DOMAIN" --out "$WORK/out" --no-plots >"$WORK/run.log" 2>&1 &
run=$!
cleanup_pids+=("$run")
rc=0
$(rt_chrt 10) timeout -k 5 40 node "$CLIENT" "ws://127.0.0.1:$PORT" plant/state robodds::idl::RobotState "$WORK/a.jsonl" 6 \
  >"$WORK/client.json" 2>"$WORK/client.err" || rc=$?
[[ $rc -eq 0 ]] || fail "the official client exited $rc: $(cat "$WORK/client.err") (bridge: $(tail -5 "$WORK/bridge.log"))"
rc=0
wait "$run" || rc=$?
[[ $rc -eq 0 ]] || fail "the run exited $rc beside the bridge: $(tail -5 "$WORK/run.log")"
grep -q '"status": "completed"' "$WORK/out/summary.json" || fail "the run did not complete: $(cat "$WORK/out/summary.json")"
echo "ok: the run completed beside the bridge and a stalled client (its missed-step limit held): $(grep -o '"missed_steps": [0-9]*' "$WORK/out/summary.json" | tr '\n' ' ')"

kill -INT "$rec"
start_ns=$(date +%s%N)
kill -INT "$bridge"
timeout -k 1 5 tail --pid="$bridge" -f /dev/null || fail "the bridge did not stop within 5 s of SIGINT"
rc=0
wait "$bridge" || rc=$?
stop_ms=$((($(date +%s%N) - start_ns) / 1000000))
[[ $rc -eq 0 ]] || fail "the bridge exited $rc after SIGINT: $(tail -5 "$WORK/bridge.log")"
timeout -k 1 20 tail --pid="$rec" -f /dev/null || fail "the recorder did not stop"
cat "$WORK/bridge.log"
latency="$(grep -E "^robodds bridge: receive->send latency: [0-9]+ messages" "$WORK/bridge.log")" || fail "no latency line"
echo "ok: SIGINT stopped the bridge in $stop_ms ms; $latency"

official="$(timeout -k 5 60 node "$CHECK" "$WORK/rec.mcap" 2>&1)" || fail "official reader on the recording: $(tail -3 <<<"$official")"
echo "$official" >"$WORK/rec.jsonl"
python3 - "$WORK/client.json" "$WORK/a.jsonl" "$WORK/rec.jsonl" "$WORK/bridge.log" <<'PY' || fail "the bridge's stream does not hold what was expected"
import json, re, sys
figures = json.load(open(sys.argv[1]))
state = [c for c in figures["advertised"] if c["topic"] == "plant/state"]
assert state == [{"topic": "plant/state", "schemaName": "robodds::idl::RobotState", "schemaEncoding": "omgidl", "encoding": "cdr"}], state
topics = [c for c in figures["advertised"] if not c["topic"].startswith("foxglove/")]  # the derived one: below
assert all(c["schemaEncoding"] == "omgidl" and c["encoding"] == "cdr" and c["schemaName"].startswith("robodds::idl::")
           for c in topics), topics
print(f"ok: {len(topics)} topics advertised, omgidl/cdr: {sorted(c['topic'] for c in topics)}")

live = [json.loads(l) for l in open(sys.argv[2]) if l.strip()]
recorded = {(m["value"]["robot_id"], m["value"]["header"]["stamp_ns"]): m["value"]
            for m in map(json.loads, open(sys.argv[3])) if m["topic"] == "plant/state"}
assert len(live) >= 100, f"A decoded {len(live)} messages, expected >= 100"
# The two participants discover the run's writers at their own moments: compare the samples of
# the stamps both cover (the first recorded stamp to the last), at most 1 s of A's left out.
stamps = sorted(k[1] for k in recorded)
both = [m for m in live if stamps[0] <= m["value"]["header"]["stamp_ns"] <= stamps[-1]]
assert len(live) - len(both) <= 300, f"{len(live) - len(both)} of A's messages outside the recording's stamps {stamps[0]}..{stamps[-1]}"
missing = [m for m in both if (m["value"]["robot_id"], m["value"]["header"]["stamp_ns"]) not in recorded]
assert not missing, (f"{len(missing)} of {len(both)} live messages not in the recording ({len(recorded)} samples, stamps "
                     f"{stamps[0]}..{stamps[-1]}), e.g. {[(m['value']['robot_id'], m['value']['header']['stamp_ns']) for m in missing[:5]]}")
assert len(both) >= 100, f"only {len(both)} of A's messages within the recording's stamps"
live = both
for m in live:
    v = m["value"]
    r = recorded[(v["robot_id"], v["header"]["stamp_ns"])]
    assert v == r, f"bridge {v} != recording {r}"
    lag = int(m["receive_time"]) - int(v["header"]["stamp_ns"])  # the frame's receive time (ns) after the stamp
    assert 0 <= lag < 1_000_000_000, f"receive time - stamp = {lag} ns"
print(f"ok: A decoded {len(live)} plant/state messages, each equal to the recording's sample of the same robot and stamp")

# 3 robots at 100 Hz: 300 messages/s. Band: within 15 % while B stalls (and before it).
for key in ("rate_before_hz", "rate_during_stall_hz"):
    assert 255 <= figures[key] <= 345, f"A's {key} {figures[key]:.1f} outside [255, 345] messages/s"
print(f"ok: A's rate {figures['rate_before_hz']:.1f}/s before, {figures['rate_during_stall_hz']:.1f}/s while B stalls (band 255-345)")
assert figures["late_after_unsubscribe"] == 0, f"{figures['late_after_unsubscribe']} messages after the unsubscribe's ack window"
print("ok: nothing after A's unsubscribe (300 ms ack window, then 1 s)")
assert figures["unadvertised_when_the_run_ended"] is True, "plant/state not unadvertised when the run's writers went"
print("ok: plant/state unadvertised when the run ended (its writers gone)")

expected = ["bad message: not JSON (", "binary message of 3 bytes ignored", "bad message: not JSON (",
            "subscribe: channel 9999 is not advertised", "unsubscribe: no subscription 4242"]
statuses = figures["statuses"]
assert len(statuses) == len(expected), statuses
for s, e in zip(statuses, expected):
    assert s["level"] == 2 and s["message"].startswith(e), (s, e)
log = open(sys.argv[4]).read()
for e in sorted(set(expected) - {"bad message: not JSON ("}):
    assert len(re.findall(re.escape(e), log)) == 1, f"log lines with '{e}': {re.findall('.*' + re.escape(e) + '.*', log)}"
assert len(re.findall(r"bad message: not JSON", log)) == 2, log
print("ok: bad input: one error status and one log line each:", "; ".join(s["message"] for s in statuses))

# --foxglove-scene: foxglove.PosesInFrame in JSON; each robot's pose is one of its recorded states
# of the last 0.1 s before the message's time, heading as the quaternion (0, 0, sin, cos)(theta/2).
import math
scene = figures["scene"]
assert scene and (scene["schemaName"], scene["schemaEncoding"], scene["encoding"]) == ("foxglove.PosesInFrame", "jsonschema", "json"), scene
states = {}
for (robot, stamp), v in recorded.items():
    states.setdefault(robot, []).append((int(stamp), v))
for m in scene["messages"]:
    t = m["timestamp"]["sec"] * 1_000_000_000 + m["timestamp"]["nsec"]
    assert m["frame_id"] == "world" and len(m["poses"]) == 3, m
    for robot, pose in zip((1, 2, 3), m["poses"]):
        near = [v for stamp, v in states[robot] if t - 100_000_000 <= stamp <= t]
        match = [v for v in near if (v["x"], v["y"]) == (pose["position"]["x"], pose["position"]["y"])]
        assert match, f"robot {robot} at {t}: {pose['position']} is none of its states of the last 0.1 s"
        theta = match[0]["theta"]
        assert abs(pose["orientation"]["z"] - math.sin(theta / 2)) < 1e-12 and abs(pose["orientation"]["w"] - math.cos(theta / 2)) < 1e-12, pose
# At most one scene per 50 ms of the stamps (not one per plant/state sample: 300/s here).
times = [m["timestamp"]["sec"] * 1_000_000_000 + m["timestamp"]["nsec"] for m in scene["messages"]]
gap = min(b - a for a, b in zip(times, times[1:]))
assert gap >= 50_000_000, f"two scene messages {gap / 1e6} ms of stamps apart: at most one per 50 ms"
print(f"ok: --foxglove-scene: {len(scene['messages'])} foxglove.PosesInFrame messages (JSON) >= {gap / 1e6:.1f} ms apart, each robot's pose one of its recorded states")

port = figures["b_port"]
b = re.search(r"client 127\.0\.0\.1:%d (?:disconnected|failed|did not answer the close): (\d+) messages sent, (\d+) dropped" % port, log)
assert b, f"no line for the stalled client (port {port}) in the bridge's log"
assert int(b.group(2)) > 0, f"the stalled client dropped nothing: {b.group(0)}"
print(f"ok: the stalled client B: {b.group(0)}")
PY
echo "ok: bridge_ws"

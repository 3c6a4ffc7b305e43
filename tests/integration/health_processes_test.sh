#!/usr/bin/env bash
# Host health across processes (issue 9): every host publishes its figures and input counters on
# run/health when it finishes; the evaluator's host collects them, so summary.json lists every
# group under "hosts" and the input counters of components in other processes under "inputs",
# in lockstep and in real time. A host whose peers never report waits a bounded time, names them
# and still writes its summary.
source "$(dirname "$0")/lib.sh"
SCENARIO="$SRC/sim/scenarios/plant_smoke.yaml"
check_summary() {  # check_summary DIR MODE
  python3 - "$1/summary.json" "$2" <<'PY' || fail "$2: summary.json lacks a host or another process's input counters"
import json, sys
s = json.load(open(sys.argv[1]))
mode = sys.argv[2]
hosts = s["hosts"]
assert set(hosts) == {"control", "sim", "sensing", "evaluation"}, hosts
for member, h in hosts.items():
    assert h["ticks"] > 0 and h["missed_steps"] >= 0 and "worst_lateness_s" in h, (member, h)
inputs = s["inputs"]
if mode == "lockstep":
    assert all(h["ticks"] == 101 and h["missed_steps"] == 0 for h in hosts.values()), hosts
    # The position sensor (10 Hz, newest_only) reads plant/state at steps 0, 10, ..., 100: the
    # plant's writer sends its process only those 11 states per robot and leaves out the other
    # 90 (a content filter Fast DDS evaluates writer-side; 303 arrive without it).
    accepted = inputs["position_sensor"]["plant/state"]["accepted"]
    assert accepted == 3 * 11, f"position_sensor accepted {accepted} plant/state samples, expected 33 (3 robots x 11 read steps)"

assert inputs["plant"]["plant/cmd"]["accepted"] > 0, inputs           # in the sim process
assert inputs["position_sensor"]["plant/state"]["accepted"] > 0, inputs  # in the sensing process
assert inputs["plant"]["plant/cmd"]["rejected"] == {}, inputs
print("ok (%s): hosts %s; plant/cmd accepted by the plant: %d" % (mode, sorted(hosts), inputs["plant"]["plant/cmd"]["accepted"]))
PY
}
timeout -k 5 60 "$ROBODDS" run "$SCENARIO" --deploy processes --duration 1 --out "$WORK/lockstep" --domain "$DOMAIN" --no-plots \
  >"$WORK/lockstep.log" 2>&1 || fail "lockstep processes run failed: $(tail -5 "$WORK/lockstep.log")"
check_summary "$WORK/lockstep" lockstep
timeout -k 5 60 "$ROBODDS" run "$SCENARIO" --deploy processes --realtime $(rt_priority_flag) --duration 2 --max-missed-steps 1000000 \
  --out "$WORK/realtime" --domain "$DOMAIN" --no-plots >"$WORK/realtime.log" 2>&1 ||
  fail "real-time processes run failed: $(tail -5 "$WORK/realtime.log")"
check_summary "$WORK/realtime" realtime

# The evaluation group alone, in real time: nobody else reports. It waits (bounded), names them,
# and ends degraded (exit 3: it discovered none of the groups it exchanges topics with).
start=$(date +%s)
rc=0
timeout -k 5 40 "$ROBODDS" host --scenario "$SCENARIO" --group evaluation --realtime --duration 1 --out "$WORK/alone" --max-missed-steps 1000000 \
  --domain "$DOMAIN" --run-id 4242 >"$WORK/alone.log" 2>&1 || rc=$?
[[ $rc -eq 3 ]] || fail "evaluation host alone: exit $rc, expected 3 (degraded): $(tail -5 "$WORK/alone.log")"
grep -qE "did not discover group\(s\) 'control', 'sim', 'sensing' during its run" "$WORK/alone.log" ||
  fail "the lone host did not say which groups it never discovered: $(tail -5 "$WORK/alone.log")"
took=$(($(date +%s) - start))
[[ $took -le 20 ]] || fail "the host alone took $took s"
grep -qE "\[warn\] evaluation: no run/health report within 5 s from host\(s\) control, sim, sensing" "$WORK/alone.log" ||
  fail "no warning naming the silent hosts: $(cat "$WORK/alone.log")"
python3 - "$WORK/alone/summary.json" <<'PY' || fail "summary.json of the lone host does not list the silent hosts"
import json, sys
summary = json.load(open(sys.argv[1]))
assert summary["status"] == "degraded", summary.get("status")
hosts = summary["hosts"]
assert hosts["evaluation"]["ticks"] > 0, hosts
assert all(hosts[m] == {"reported": False} for m in ("control", "sim", "sensing")), hosts
PY
echo "ok: a lone host waited ${took} s, named the silent hosts and wrote its summary"

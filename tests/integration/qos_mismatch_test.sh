#!/usr/bin/env bash
# Lockstep with one host on a mismatched QoS file (its lockstep writers BEST_EFFORT, everyone
# else's readers RELIABLE): nothing it writes is delivered. The run must fail within the input
# timeout with one line that names the waiting component, the topic, and the incompatible
# policy with both sides' QoS and the offending group - not hang, not just "timeout".
source "$(dirname "$0")/lib.sh"
S="$SRC/sim/scenarios/plant_smoke.yaml"
QOS="$SRC/deploy/qos/robodds_qos.xml"
awk '/<data_writer profile_name="lockstep">/ { w = 1 }
     w && /<kind>RELIABLE<\/kind>/ { sub("RELIABLE", "BEST_EFFORT") }
     /<\/data_writer>/ { w = 0 }
     { print }' "$QOS" >"$WORK/best_effort_writers.xml"
[[ $(diff "$QOS" "$WORK/best_effort_writers.xml" | grep -c '^>') -eq 1 ]] || fail "expected one edited line"

# Hosts that load different QoS files are stopped at step 0 by the digest check
# (integration.scenario_digest); this test is about what gets through without it.
export ROBODDS_NO_DIGEST_CHECK=1
C=(--scenario "$S" --run-id 77 --domain "$DOMAIN" --out "$WORK/out" --input-timeout 3)
for g in sim sensing evaluation; do
  "$ROBODDS" host --group "$g" "${C[@]}" >"$WORK/$g.log" 2>&1 &
  cleanup_pids+=($!)
done
"$ROBODDS" host --group control "${C[@]}" --qos "$WORK/best_effort_writers.xml" >"$WORK/control.log" 2>&1 &
cleanup_pids+=($!)
start=$SECONDS
rc=0
out="$(timeout -k 5 60 "$ROBODDS" host --coordinate "${C[@]}" --start-timeout 20 2>&1)" || rc=$?
[[ $rc -eq 1 ]] || fail "coordinator exited $rc, expected 1: $out"
[[ $(grep -c "error:" <<<"$out") -eq 1 ]] || fail "expected one error line: $out"
grep -qE "group '(sim|evaluation)' failed at step [01]: lockstep: component '(plant|evaluator)' waited 3\.0 s at step [01] for topic plant/cmd, robot_id=1 \(nothing received yet\); DDS: [1-9] other participant\(s\) discovered; plant/cmd \(reader\): incompatible QoS RELIABILITY: this reader requests RELIABLE/TRANSIENT_LOCAL, writers offer BEST_EFFORT/TRANSIENT_LOCAL from 'control'" <<<"$out" ||
  fail "error does not name component, topic, policy and both sides: $out"
# The offending side says it too (writer listener).
grep -q "plant/cmd: incompatible QoS RELIABILITY: this writer offers BEST_EFFORT/TRANSIENT_LOCAL, readers request RELIABLE/TRANSIENT_LOCAL from" \
  "$WORK/control.log" || fail "the mismatched writer did not report it: $(cat "$WORK/control.log")"
echo "ok: failed after $((SECONDS - start)) s: $out"

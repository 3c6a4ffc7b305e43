#!/usr/bin/env bash
# Lockstep: a killed host is reported by name (the coordinator polls its children) - no hang.
source "$(dirname "$0")/lib.sh"
"$ROBODDS" run "$SRC/sim/scenarios/plant_smoke.yaml" --out "$WORK/out" --domain "$DOMAIN" --deploy processes \
  --duration 100000 >"$WORK/log" 2>&1 &
runner=$!
cleanup_pids+=("$runner")
for _ in $(seq 100); do
  victim="$(pgrep -f -- "--group sim --run-id [0-9]+ --out $WORK/out" || true)"
  [[ -n "$victim" ]] && break
  sleep 0.1
done
[[ -n "$victim" ]] || fail "sim host never started"
sleep 2
kill -9 $victim
rc=0
timeout -k 5 30 tail --pid="$runner" -f /dev/null || fail "runner hung after the kill"
wait "$runner" || rc=$?
[[ $rc -ne 0 ]] || fail "runner exited 0"
grep -q "group 'sim'" "$WORK/log" || fail "dead group not named: $(cat "$WORK/log")"
echo "ok: lockstep run failed naming group 'sim'"

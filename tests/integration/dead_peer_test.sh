#!/usr/bin/env bash
# Killing one host process makes `robodds run --deploy processes` fail fast, naming the group.
source "$(dirname "$0")/lib.sh"
"$ROBODDS" run "$SRC/sim/scenarios/plant_smoke.yaml" --out "$WORK/out" --domain "$DOMAIN" --deploy processes \
  --duration 600 --realtime $(rt_priority_flag) >"$WORK/log" 2>&1 &
runner=$!
cleanup_pids+=("$runner")
for _ in $(seq 100); do
  victim="$(pgrep -f -- "--group sensing --run-id [0-9]+ --out $WORK/out" || true)"
  [[ -n "$victim" ]] && break
  sleep 0.1
done
[[ -n "$victim" ]] || fail "sensing host never started: $(cat "$WORK/log")"
sleep 2
kill -9 $victim
start=$(date +%s.%N)
rc=0
timeout -k 5 30 tail --pid="$runner" -f /dev/null || fail "runner did not exit within 30 s after the kill"
wait "$runner" || rc=$?
elapsed=$(echo "$(date +%s.%N) - $start" | bc)
[[ $rc -ne 0 ]] || fail "runner exited 0 after a host was killed"
grep -q "group 'sensing'.*killed by signal 9" "$WORK/log" || fail "message does not name the dead group: $(cat "$WORK/log")"
sleep 0.5
pgrep -f -- "--out $WORK/out" >/dev/null && fail "orphan host processes left"
echo "ok: runner failed in ${elapsed}s naming the dead group; no orphans"

#!/usr/bin/env bash
# SIGTERM/SIGINT stop a host cleanly: it exits promptly, deletes its participant, and leaves no
# Fast DDS shared-memory segments behind.
source "$(dirname "$0")/lib.sh"
for signal in TERM INT; do
  before="$(ls /dev/shm | grep -c fastrtps || true)"
  "$ROBODDS" host --scenario "$SRC/sim/scenarios/plant_smoke.yaml" --components plant,commander --realtime \
    --duration 600 --domain "$DOMAIN" >"$WORK/host.log" 2>&1 &
  host=$!
  sleep 2
  kill -"$signal" "$host"
  rc=0
  timeout -k 2 10 tail --pid="$host" -f /dev/null || fail "host did not exit within 10 s of SIG$signal"
  wait "$host" || rc=$?
  [[ $rc -eq 130 ]] || fail "expected exit code 130 after SIG$signal, got $rc: $(cat "$WORK/host.log")"
  grep -q "interrupted by a signal" "$WORK/host.log" || fail "no interruption message: $(cat "$WORK/host.log")"
  sleep 0.5
  after="$(ls /dev/shm | grep -c fastrtps || true)"
  [[ "$after" -le "$before" ]] || fail "shared-memory segments left behind after SIG$signal ($before -> $after)"
  echo "ok: SIG$signal -> exit 130, no leftover shared memory"
done

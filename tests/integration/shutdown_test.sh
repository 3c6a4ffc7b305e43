#!/usr/bin/env bash
# SIGTERM/SIGINT stop a host cleanly: it exits promptly, deletes its participant, and leaves no
# Fast DDS shared-memory segments behind. Only the segments the host itself mapped are checked
# (from /proc/PID/maps), so tests running side by side cannot disturb the count.
source "$(dirname "$0")/lib.sh"
# Exit 128 + signal, as a shell reports it: 143 for SIGTERM (`docker stop`), 130 for SIGINT.
for signal in TERM INT; do
  expected=$((128 + $(kill -l "$signal")))
  "$ROBODDS" host --scenario "$SRC/sim/scenarios/plant_smoke.yaml" --components plant,commander --realtime \
    --duration 600 --domain "$DOMAIN" >"$WORK/host.log" 2>&1 &
  host=$!
  sleep 2
  mapped="$(grep -o '/dev/shm/fast[^ ]*' "/proc/$host/maps" | sort -u || true)"
  [[ -n "$mapped" ]] || fail "the host mapped no Fast DDS shared memory (is the SHM transport on?)"
  kill -"$signal" "$host"
  rc=0
  timeout -k 2 10 tail --pid="$host" -f /dev/null || fail "host did not exit within 10 s of SIG$signal"
  wait "$host" || rc=$?
  [[ $rc -eq $expected ]] || fail "expected exit code $expected after SIG$signal, got $rc: $(cat "$WORK/host.log")"
  grep -q "interrupted by a signal" "$WORK/host.log" || fail "no interruption message: $(cat "$WORK/host.log")"
  sleep 0.5
  for segment in $mapped; do
    [[ ! -e "$segment" ]] || fail "shared-memory segment $segment left behind after SIG$signal"
  done
  echo "ok: SIG$signal -> exit $expected, no leftover shared memory"
done

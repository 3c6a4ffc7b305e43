#!/usr/bin/env bash
# Ctrl-C (SIGINT) on `robodds run --deploy processes` stops the run promptly with exit 130 and
# leaves no host process behind (children are terminated and reaped), in lockstep and real time
# (there the second SIGINT: the first stops the run cleanly, tests/integration/realtime_stop_test.sh).
source "$(dirname "$0")/lib.sh"
children_of_run() {  # robodds host processes of this test's domain
  pgrep -f -- "robodds .*host .*--domain $DOMAIN( |\$)" || true
}
for mode in lockstep realtime; do
  extra=()
  [[ $mode == realtime ]] && extra=(--realtime)
  "$ROBODDS" run "$SRC/sim/scenarios/plant_smoke.yaml" --deploy processes "${extra[@]}" --duration 600 \
    --out "$WORK/$mode" --domain "$DOMAIN" --no-plots >"$WORK/$mode.log" 2>&1 &
  runner=$!
  cleanup_pids+=("$runner")
  for _ in $(seq 100); do  # up to 10 s for the hosts to start
    [[ $(children_of_run | wc -l) -ge 4 ]] && break
    sleep 0.1
  done
  [[ $(children_of_run | wc -l) -ge 4 ]] || fail "$mode: the 4 host processes did not start: $(cat "$WORK/$mode.log")"
  sleep 1
  kill -INT "$runner"
  if [[ $mode == realtime ]]; then  # the first stops it cleanly (realtime_stop_test.sh), a second aborts
    sleep 0.05
    kill -INT "$runner" 2>/dev/null || true
  fi
  timeout -k 2 15 tail --pid="$runner" -f /dev/null || fail "$mode: runner did not exit within 15 s of SIGINT"
  rc=0
  wait "$runner" || rc=$?
  [[ $rc -eq 130 ]] || fail "$mode: expected exit 130 after SIGINT, got $rc: $(tail -5 "$WORK/$mode.log")"
  left="$(children_of_run)"
  [[ -z "$left" ]] || fail "$mode: host processes left behind: $left"
  echo "ok ($mode): SIGINT -> exit 130, no host process left"
done

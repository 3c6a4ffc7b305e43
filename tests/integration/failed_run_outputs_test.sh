#!/usr/bin/env bash
# A run that fails keeps what it recorded and says so (issue #9, finding 8): paper1_waypoints in
# lockstep with one process per group (a duration it never reaches); a group is killed with SIGKILL once the CSVs have grown.
# robodds exits non-zero, summary.json has "status": "failed" and a reason naming the dead group,
# plant_state.csv has the rows recorded up to the failure. First the estimation host (the
# evaluator hears of the failure and writes its summary with the metrics so far), then the
# evaluation host itself (the runner writes a summary of the status and the reason alone).
source "$(dirname "$0")/lib.sh"
rows_of() { [[ -f "$1" ]] && wc -l <"$1" || echo 0; }
for victim in estimation evaluation; do
  out="$WORK/$victim"
  "$ROBODDS" run "$SRC/sim/scenarios/paper1_waypoints.yaml" --deploy processes --duration 100000 --out "$out" \
    --domain "$DOMAIN" --no-plots >"$out.log" 2>&1 &
  runner=$!
  cleanup_pids+=("$runner")
  pid=""
  for _ in $(seq 100); do  # up to 10 s for the host to start
    pid="$(pgrep -f -- "--group $victim --run-id [0-9]+ --out $out( |\$)" || true)"
    [[ -n "$pid" ]] && break
    sleep 0.1
  done
  [[ -n "$pid" ]] || fail "$victim: host never started: $(cat "$out.log")"
  for _ in $(seq 300); do  # up to 30 s for 20 s of the run's rows (the old runner wrote none)
    [[ $(rows_of "$out/plant_state.csv") -gt 2000 ]] && break
    sleep 0.1
  done
  rows_at_kill=$(rows_of "$out/plant_state.csv")
  kill -9 "$pid"
  timeout -k 5 40 tail --pid="$runner" -f /dev/null || fail "$victim: runner hung after the kill"
  rc=0
  wait "$runner" || rc=$?
  [[ $rc -ne 0 ]] || fail "$victim: runner exited 0 after a group was killed"
  [[ -f "$out/summary.json" ]] || fail "$victim: no summary.json after the failed run: $(tail -3 "$out.log")"
  python3 - "$out/summary.json" "$victim" <<'PY' || fail "$victim: summary.json: $(cat "$out/summary.json")"
import json, sys
summary, victim = json.load(open(sys.argv[1])), sys.argv[2]
assert summary.get("status") == "failed", "status is %r, not 'failed'" % summary.get("status")
reason = summary.get("reason", "")
assert "group '%s'" % victim in reason or "no acknowledgement" in reason, "reason names neither the group nor a timeout: %r" % reason
if victim != "evaluation":  # the evaluator lived to see the failure: metrics of the data so far
    assert summary["steps"] > 0 and summary["metrics"]["samples"]["plant/state"] > 0, summary
PY
  rows=$(rows_of "$out/plant_state.csv")
  [[ $rows -gt 1 ]] || fail "$victim: plant_state.csv has no rows after the failed run"
  [[ $rows -ge $rows_at_kill ]] || fail "$victim: plant_state.csv shrank from $rows_at_kill to $rows rows"
  grep -q "group '$victim'" "$out.log" || fail "$victim: dead group not named: $(tail -3 "$out.log")"
  echo "ok ($victim killed): exit $rc, status failed ($(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["reason"])' "$out/summary.json")), plant_state.csv $rows rows (>= $rows_at_kill at the kill)"
done

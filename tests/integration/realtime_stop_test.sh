#!/usr/bin/env bash
# Issue 26, finding 3: Ctrl-C ends a real-time session cleanly (plant_smoke, 60 s, domain DOMAIN):
# 1. co-located `robodds run --realtime`, one SIGINT ~2 s after the clock started: exit 0, summary.json
#    "completed" with "stopped_by": "signal", the stop time (sim s and UTC), the steps that ran and
#    their metrics; the plots drawn.
# 2. the same across processes (4 hosts + the runner): the runner has every host end after the
#    same step, so none is reported lost or missing: "completed" (not "degraded"), stopped_by.
# 3. two SIGINTs (across processes, the second while the hosts are still stopping): the run aborts
#    as before: exit 130, "failed".
# 4. lockstep + one SIGINT: "failed" as before (an interrupted deterministic run), exit 130.
source "$(dirname "$0")/lib.sh"
S="$SRC/sim/scenarios/plant_smoke.yaml"
# The run is real time: overruns on a busy machine are not what this checks.
RT=(--realtime --duration 60 --max-missed-steps 1000000 $(rt_priority_flag))

# start NAME ARGS...: `robodds run` in the background ($run: its pid).
start() {
  local name=$1
  shift
  "$ROBODDS" run "$S" --domain "$DOMAIN" --out "$WORK/$name" "$@" >"$WORK/$name.log" 2>&1 &
  run=$!
  cleanup_pids+=("$run")
}
# started NAME: waits (at most 30 s) for the evaluator's CSV files (real time: opened just before
# the clock starts; lockstep: at step 0).
started() {
  for _ in $(seq 300); do
    [[ -e "$WORK/$1/plant_state.csv" ]] && return 0
    kill -0 "$run" 2>/dev/null || fail "$1: the run ended before it started: $(tail -5 "$WORK/$1.log")"
    sleep 0.1
  done
  fail "$1: no plant_state.csv within 30 s: $(tail -5 "$WORK/$1.log")"
}
# ended NAME RC: the run exits with RC within 30 s (the stop, the health wait, the plots).
ended() {
  timeout -k 2 30 tail --pid="$run" -f /dev/null || fail "$1: still running 30 s after the signal: $(tail -5 "$WORK/$1.log")"
  local rc=0
  wait "$run" || rc=$?
  [[ $rc -eq $2 ]] || fail "$1: exit $rc, expected $2: $(tail -5 "$WORK/$1.log")"
}
# stopped NAME: summary.json of a run stopped cleanly about 2 s into its 60 s.
stopped() {
  python3 - "$WORK/$1/summary.json" <<'PY' || fail "$1: summary.json: $(head -c 600 "$WORK/$1/summary.json")"
import json, re, sys
s = json.load(open(sys.argv[1]))
assert s["status"] == "completed", (s["status"], s.get("reason"))
assert s["stopped_by"] == "signal", s.get("stopped_by")
assert 0.25 <= s["stopped_at_s"] < 30, s["stopped_at_s"]  # ~1-2 s (+ start-up on a busy machine), far from 60
assert re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d{3}Z", s["stopped_at_utc"]), s["stopped_at_utc"]
assert s["steps"] == round(s["stopped_at_s"] / s["step_s"]) + 1, (s["steps"], s["stopped_at_s"])
assert s["metrics"]["robots"]["1"]["path_length_m"] > 0, s["metrics"]["robots"]["1"]
assert s["metrics"]["samples"]["plant/state"] > 0, s["metrics"]["samples"]
print("ok: completed, stopped by a signal at t = %s s (%s), %d steps" % (s["stopped_at_s"], s["stopped_at_utc"], s["steps"]))
PY
}

start colocated "${RT[@]}"
started colocated
sleep 2
kill -INT "$run"
ended colocated 0
stopped colocated
ls "$WORK"/colocated/*.png >/dev/null 2>&1 || fail "colocated: no plots drawn: $(tail -5 "$WORK/colocated.log")"
echo "ok (colocated): one SIGINT -> exit 0, plots $(cd "$WORK/colocated" && ls ./*.png | wc -l)"

start processes "${RT[@]}" --deploy processes --no-plots
started processes
sleep 3  # the hosts open their files up to 2 s before step 0 (the runner's epoch)
kill -INT "$run"
ended processes 0
stopped processes
grep -q "stopping on a signal: every host ends cleanly after step" "$WORK/processes.log" || fail "processes: $(tail -5 "$WORK/processes.log")"
echo "ok (processes): one SIGINT -> every host ends after the same step, exit 0"

# Across processes the hosts end kGracefulStopAheadS (0.3 s) after the first signal, then exchange
# their health: a second signal 0.05 s later comes while the runner still waits for them.
start twice "${RT[@]}" --deploy processes --no-plots
started twice
sleep 1
kill -INT "$run"
sleep 0.05
kill -INT "$run" 2>/dev/null || true
ended twice 130
grep -q '"status": "failed"' "$WORK/twice/summary.json" || fail "twice: $(head -5 "$WORK/twice/summary.json")"
echo "ok (two SIGINTs): aborted, exit 130, failed"

start lockstep --duration 100000 --no-plots
started lockstep
sleep 1
kill -INT "$run"
ended lockstep 130
grep -q '"status": "failed"' "$WORK/lockstep/summary.json" || fail "lockstep: $(head -5 "$WORK/lockstep/summary.json")"
grep -q '"stopped_by"' "$WORK/lockstep/summary.json" && fail "lockstep: stopped_by in a failed run's summary"
echo "ok (lockstep): one SIGINT -> failed as before, exit 130"

#!/usr/bin/env bash
# Every host failure named (issue 24, finding 6): plant_smoke started by hand, one `robodds host`
# per group (+ `--coordinate` in lockstep), as docs/deployment.md "Multi-host by hand" does; the
# sensing host (position sensor) is killed with SIGKILL mid-run. Its participant's lease (1.5 s,
# deploy/qos) expires at every other host, which waits 0.4 s for it to come back (a stall) and then:
#   - lockstep: every surviving host and the coordinator exit non-zero within 4 s of the kill
#     (2 s + a margin for a busy machine; before: they waited 30 s for ticks), each naming
#     'sensing', and summary.json (written by the evaluation host) says "failed" naming it;
#   - real time: the others run to their end and exit 3 (degraded); each names 'sensing' and the
#     time it was dropped, within 2.5 s after the kill; summary.json says "degraded" with that;
#   - real time, the sensing host's loop frozen while its process lives (its participant stays
#     alive): the same, named by the silence of its beats on run/alive (LoopSilence).
source "$(dirname "$0")/lib.sh"
S="$SRC/sim/scenarios/plant_smoke.yaml"
now_s() { date +%s.%N; }
# start_host NAME ARGS...: a robodds process in the background; its pid in $WORK/NAME.pid, its exit
# code and exit time (s since the epoch) in $WORK/NAME.exit once it ends, its output in $WORK/NAME.log.
start_host() {
  local name="$1"
  shift
  ( "$ROBODDS" "$@" >"$WORK/$name.log" 2>&1 &
    echo $! >"$WORK/$name.pid"
    rc=0
    wait $! || rc=$?
    echo "$rc $(now_s)" >"$WORK/$name.exit" ) &
  for _ in $(seq 50); do [[ -s "$WORK/$name.pid" ]] && break; sleep 0.02; done
  cleanup_pids+=("$(cat "$WORK/$name.pid")")
}
# wait_exits LIMIT_S NAME...: waits until every NAME has ended, at most LIMIT_S s.
wait_exits() {
  local limit="$1" name deadline
  shift
  deadline=$(echo "$(now_s) + $limit" | bc)
  for name in "$@"; do
    while [[ ! -s "$WORK/$name.exit" ]]; do
      (( $(echo "$(now_s) > $deadline" | bc) )) && fail "$name still running $limit s later: $(tail -3 "$WORK/$name.log")"
      sleep 0.05
    done
  done
}

# --- lockstep ---
# lockstep_run P: the hosts as P_control, P_sim, ..., the sensing host killed mid-run; waits for
# the others to end (at most 20 s). Outputs in $WORK/P.
lockstep_run() {
  local p=$1 name
  RUN=$((RANDOM + 1000))
  L=(host --scenario "$S" --domain "$DOMAIN" --run-id "$RUN" --duration 1000)
  for g in control sim sensing; do start_host "${p}_$g" "${L[@]}" --group "$g"; done
  start_host "${p}_evaluation" "${L[@]}" --group evaluation --out "$WORK/$p"
  start_host "${p}_coordinator" "${L[@]}" --coordinate
  sleep 4  # discovery (~1 s) and a few hundred steps
  for name in control sim sensing evaluation coordinator; do
    [[ ! -e "$WORK/${p}_$name.exit" ]] || fail "${p}_$name ended before the kill: $(tail -3 "$WORK/${p}_$name.log")"
  done
  kill -9 "$(cat "$WORK/${p}_sensing.pid")"
  killed=$(now_s)
  wait_exits 20 "${p}_control" "${p}_sim" "${p}_evaluation" "${p}_coordinator"
}
lockstep_run ls
# Fast DDS 2.9.1 as Debian builds it (with assertions) may abort a host whose lease timer for a
# remote participant fires while that participant's proxy is being removed (PDP.cpp:1140,
# `GUID_t::unknown() != remote_participant->m_guid`; seen once in ~10 whole-suite runs, and once in
# robodds-fuzz): a defect of the library, not of the host's handling (docs/deployment.md,
# "Troubleshooting"). Only then is the case run once more; any other failure fails at once.
P=ls
if aborted=$(grep -l "PDP.cpp:1140" "$WORK"/ls_*.log 2>/dev/null) && [[ -n "$aborted" ]]; then
  echo "lockstep: $(basename "$aborted" .log) aborted in Fast DDS (PDP.cpp:1140, a known 2.9.1 defect): running the case again"
  lockstep_run ls2
  P=ls2
fi
for name in control sim evaluation coordinator; do
  read -r rc ended <"$WORK/${P}_$name.exit"
  took=$(echo "$ended - $killed" | bc)
  echo "lockstep: ${P}_$name exit $rc, $took s after the kill"
  [[ $rc -ne 0 && $rc -ne 3 ]] || fail "${P}_$name exited $rc after the sensing host was killed: $(tail -3 "$WORK/${P}_$name.log")"
  (( $(echo "$took < 4.0" | bc) )) || fail "${P}_$name took $took s (> 4 s) to end after the kill: $(tail -3 "$WORK/${P}_$name.log")"
  grep -qE "group 'sensing' lost at step [0-9]+: its participant 'robodds-sensing' dropped" "$WORK/${P}_$name.log" ||
    fail "${P}_$name does not name the lost group: $(tail -3 "$WORK/${P}_$name.log")"
done
python3 - "$WORK/$P/summary.json" <<'PY' || fail "lockstep summary.json does not name the lost group"
import json, re, sys
s = json.load(open(sys.argv[1]))
assert s["status"] == "failed", s["status"]
assert re.search(r"group 'sensing' lost at step [1-9][0-9]*: its participant 'robodds-sensing' dropped", s["reason"]), s["reason"]
print("ok (lockstep): summary.json failed:", s["reason"][:100])
PY

# --- real time ---
# realtime_fault NAME: a 10 s real-time run; at 4 s after step 0 the sensing host is killed
# (NAME=killed: SIGKILL, its participant's lease expires) or its loop is frozen while its process
# lives on (NAME=frozen: its main thread, which runs the host's loop, stopped by ptrace; Fast DDS's
# threads keep its participant alive, so only run/alive's silence tells). Every other host must
# name 'sensing' as lost within 2.5 s of the fault, with how it was lost (HOW, a regex).
realtime_fault() {
  local fault="$1" how="$2"
  local DURATION=10 FAULT_AT=4 epoch_s fault_s name rc ended at late freezer=""
  epoch_s=$(($(date +%s) + 3))
  local R=(host --scenario "$S" --domain "$DOMAIN" --run-id "$((RUN + RANDOM % 1000 + 1))" --realtime --epoch-ns "${epoch_s}000000000"
    --duration "$DURATION" --max-missed-steps 1000000)
  for g in control sim sensing; do start_host "${fault}_$g" "${R[@]}" --group "$g"; done
  start_host "${fault}_evaluation" "${R[@]}" --group evaluation --out "$WORK/$fault"
  sleep "$(echo "$epoch_s + $FAULT_AT - $(now_s)" | bc)"
  if [[ $fault == killed ]]; then
    kill -9 "$(cat "$WORK/${fault}_sensing.pid")"
    fault_s=$(echo "$(now_s) - $epoch_s" | bc)
  else
    python3 "$(dirname "$0")/freeze_thread.py" "$(cat "$WORK/${fault}_sensing.pid")" 30 >"$WORK/freeze.out" 2>&1 &
    freezer=$!
    cleanup_pids+=("$freezer")
    for _ in $(seq 100); do [[ -s "$WORK/freeze.out" ]] && break; sleep 0.05; done
    grep -q "^frozen " "$WORK/freeze.out" || fail "could not freeze the sensing host's loop: $(cat "$WORK/freeze.out")"
    fault_s=$(echo "$(cut -d' ' -f2 "$WORK/freeze.out") - $epoch_s" | bc)
  fi
  wait_exits $((DURATION + 20)) "${fault}_control" "${fault}_sim" "${fault}_evaluation"
  for name in "${fault}_control" "${fault}_sim" "${fault}_evaluation"; do
    read -r rc ended <"$WORK/$name.exit"
    [[ $rc -eq 3 ]] || fail "$name exited $rc, expected 3 (degraded): $(tail -3 "$WORK/$name.log")"
    (( $(echo "$ended - $epoch_s >= $DURATION" | bc) )) || fail "$name ended before the run's end"
    at=$(grep -oE "lost group 'sensing' at [0-9.]+ s after the start \($how" "$WORK/$name.log" | head -1 | grep -oE "at [0-9.]+ s" | cut -d' ' -f2)
    [[ -n "$at" ]] || fail "$name does not name the lost group 'sensing' ($how): $(grep -m1 "lost group" "$WORK/$name.log" || tail -3 "$WORK/$name.log")"
    late=$(echo "$at - $fault_s" | bc)
    echo "real time, $fault: $name lost 'sensing' at $at s, $late s after the fault (at $fault_s s); exit $rc"
    (( $(echo "$late >= 0 && $late < 2.5" | bc) )) || fail "$name named the loss $late s after the fault (bound 2.5 s)"
  done
  python3 - "$WORK/$fault/summary.json" "$fault_s" "$how" <<'PY' || fail "real-time summary.json does not name the lost group"
import json, re, sys
s = json.load(open(sys.argv[1]))
fault_s, how = float(sys.argv[2]), sys.argv[3]
assert s["status"] == "degraded", s["status"]
m = re.search(r"lost group 'sensing' at ([0-9.]+) s after the start \(" + how, s["reason"])
assert m and 0 <= float(m.group(1)) - fault_s < 2.5, s["reason"]
# Every survivor reported (each ended after the run's end: checked above from its exit time).
assert all(s["hosts"][m]["ticks"] > 0 for m in ("control", "sim", "evaluation")), s["hosts"]
assert s["hosts"]["sensing"] == {"reported": False}, s["hosts"]["sensing"]
print("ok (real time):", m.group(0))
PY
  # The tracer first: a traced process's end reaches its parent only once its tracer is gone.
  [[ $fault == frozen ]] && { kill "$freezer" 2>/dev/null || true; wait "$freezer" 2>/dev/null || true; }
  kill -9 "$(cat "$WORK/${fault}_sensing.pid")" 2>/dev/null || true
  wait_exits 10 "${fault}_sensing"  # its wrapper writes its exit file: before the cleanup removes $WORK
}
realtime_fault killed "its participant 'robodds-sensing' dropped"
realtime_fault frozen "its loop stopped: nothing on run/alive since [0-9.]+ s while its participant is alive"
echo "ok: a killed host is named by every other host, lockstep and real time, and a live host whose loop froze in real time"

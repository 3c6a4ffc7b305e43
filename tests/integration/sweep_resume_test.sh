#!/usr/bin/env bash
# Issue 26, finding 3: an interrupted sweep and --resume (plant_smoke lockstep runs of 20 s, one
# worker on domain DOMAIN):
# 1. SIGINT once the first run finished: exit 130; runs.csv and summary.md cover the runs that
#    finished, the others are "not run" (not failed), also for --aggregate (exit 0).
# 2. --resume DIR with the same command line runs exactly the runs not run (the finished ones are
#    kept), then runs.csv has every run ok.
# 3. --resume of a folder planned with other --seeds, or of a folder that does not exist: exit 2,
#    one line naming what differs / the folder.
source "$(dirname "$0")/lib.sh"
S="$SRC/sim/scenarios/plant_smoke.yaml"
SWEEP=("$ROBODDS" sweep "$S" --seeds 1-4 --duration 20 --jobs 1 --domain "$DOMAIN")
D="$WORK/sweep"

"${SWEEP[@]}" --out "$D" >"$WORK/first.log" 2>&1 &
sweep=$!
cleanup_pids+=("$sweep")
for _ in $(seq 600); do  # up to 60 s for the first run (seconds beside CPU hogs)
  [[ -e "$D/runs/0000/outcome.json" ]] && break
  kill -0 "$sweep" 2>/dev/null || fail "the sweep ended early: $(tail -5 "$WORK/first.log")"
  sleep 0.1
done
[[ -e "$D/runs/0000/outcome.json" ]] || fail "run 0 did not finish within 60 s: $(tail -5 "$WORK/first.log")"
kill -INT "$sweep"
timeout -k 2 30 tail --pid="$sweep" -f /dev/null || fail "the sweep did not exit within 30 s of SIGINT"
rc=0
wait "$sweep" || rc=$?
[[ $rc -eq 130 ]] || fail "interrupted sweep: exit $rc, expected 130: $(tail -5 "$WORK/first.log")"
grep -q "sweep interrupted by a signal after .* --resume $D" "$WORK/first.log" || fail "no resume hint: $(tail -3 "$WORK/first.log")"
[[ -f "$D/runs.csv" && -f "$D/summary.md" ]] || fail "no runs.csv/summary.md after the interruption"
ok=$(grep -c ",ok," "$D/runs.csv" || true)
not_run=$(grep -c ",not run," "$D/runs.csv" || true)
[[ $(wc -l <"$D/runs.csv") -eq 5 && $ok -ge 1 && $((ok + not_run)) -eq 4 ]] || fail "runs.csv after the interruption: $(cat "$D/runs.csv")"
grep -q "$ok runs ok, 0 failed, $not_run not run" "$D/summary.md" || fail "summary.md: $(head -3 "$D/summary.md")"
# The run the signal stopped left no folder (half a run is no result): only the finished ones stay.
[[ $(ls "$D/runs" | wc -l) -eq $ok ]] || fail "run folders after the interruption: $(ls "$D/runs")"
rc=0
"$ROBODDS" sweep --aggregate --out "$D" >"$WORK/aggregate.log" 2>&1 || rc=$?
[[ $rc -eq 0 ]] && grep -q "(4 runs, 0 failed, $not_run not run)" "$WORK/aggregate.log" ||
  fail "--aggregate counts runs never run as failed (exit $rc): $(tail -3 "$WORK/aggregate.log")"
echo "ok: interrupted after $ok run(s): exit 130, runs.csv with $not_run not run, --aggregate exit 0"

for dir in "$D"/runs/*/; do touch "$dir/kept"; done  # the finished runs must stay as they are
"${SWEEP[@]}" --resume "$D" >"$WORK/resume.log" 2>&1 || fail "--resume failed: $(tail -5 "$WORK/resume.log")"
grep -q "resuming $D: $ok of 4 runs finished, $not_run to run" "$WORK/resume.log" || fail "resume: $(head -3 "$WORK/resume.log")"
[[ $(grep -c ",ok," "$D/runs.csv") -eq 4 ]] || fail "runs.csv after --resume: $(cat "$D/runs.csv")"
[[ $(ls "$D"/runs/*/kept | wc -l) -eq $ok ]] || fail "--resume touched finished runs: $(ls "$D"/runs/*)"
echo "ok: --resume ran exactly the $not_run missing run(s), kept the $ok finished"

rc=0
out="$("$ROBODDS" sweep "$S" --seeds 1-5 --duration 20 --jobs 1 --domain "$DOMAIN" --resume "$D" 2>&1)" || rc=$?
[[ $rc -eq 2 && $(wc -l <<<"$out") -eq 1 ]] && grep -q "resume $D: not the sweep of this command line: --seeds: '1-4' in sweep.json, '1-5' on the command line" <<<"$out" ||
  fail "--resume with other seeds: exit $rc: $out"
rc=0
out="$("${SWEEP[@]}" --resume "$WORK/none" 2>&1)" || rc=$?
[[ $rc -eq 2 ]] && grep -q "resume $WORK/none: no such folder" <<<"$out" || fail "--resume of a missing folder: exit $rc: $out"
echo "ok: --resume refuses another sweep's folder and a missing one"

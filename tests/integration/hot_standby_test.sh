#!/usr/bin/env bash
# Hot standby (issue #9): paper1_waypoints in real time, one `robodds host --realtime` per group,
# with a standby PF estimator in a group of its own (standby_for: estimator). SIGKILL the
# primary's host mid-run: estimate/pose resumes from the standby within 1.1 s (DDS exclusive
# ownership, the liveliness lease of the `state` profile), no sample of the two is refused as a
# second producer, the readers log the hand-over, and the robot does not stand still for longer
# than 1.1 s (plant_state.csv v); summary.json's "standby" section (the evaluator's hand-over time)
# agrees with the CSV. A standby in lockstep or co-located is refused at start-up.
source "$(dirname "$0")/lib.sh"
S="$WORK/standby.yaml"
sed -e 's/^  - {name: estimator, type: pf_estimator}$/&\n  - {name: estimator_standby, type: pf_estimator, standby_for: estimator}/' \
  -e 's/^  estimation: \[estimator\]$/&\n  estimation_standby: [estimator_standby]/' "$SRC/sim/scenarios/paper1_waypoints.yaml" >"$S"
grep -q "estimation_standby: \[estimator_standby\]" "$S" || fail "could not add a standby to paper1_waypoints.yaml"
expect_error 2 "standby\.yaml: estimator_standby\.standby_for: a hot standby runs in real time only" -- \
  "$ROBODDS" run "$S" --duration 0.5 --domain "$DOMAIN" --out "$WORK/o1" --no-plots
expect_error 2 "standby\.yaml: estimator_standby\.standby_for: a hot standby needs one process per group" -- \
  "$ROBODDS" run "$S" --duration 0.5 --domain "$DOMAIN" --out "$WORK/o2" --no-plots --realtime

out="$WORK/run"
DURATION=14
KILL_AT=7  # s after step 0
epoch_s=$(($(date +%s) + 3))
C=(--scenario "$S" --realtime $(rt_priority_flag) --epoch-ns "${epoch_s}000000000" --duration "$DURATION" --domain "$DOMAIN" --out "$out")
declare -A pid
for g in sim sensors estimation estimation_standby control evaluation; do
  "$ROBODDS" --log info host --group "$g" "${C[@]}" >"$WORK/$g.log" 2>&1 &
  pid[$g]=$!
  cleanup_pids+=("$!")
done
sleep "$(echo "$epoch_s + $KILL_AT - $(date +%s.%N)" | bc)"
kill -9 "${pid[estimation]}"
killed_at=$(date +%s.%N)
wait "${pid[estimation]}" 2>/dev/null || true
for g in sim sensors estimation_standby control evaluation; do
  rc=0
  timeout -k 5 40 tail --pid="${pid[$g]}" -f /dev/null || fail "host $g did not end"
  wait "${pid[$g]}" || rc=$?
  [[ $rc -eq 0 ]] || fail "host $g failed (exit $rc): $(tail -n 3 "$WORK/$g.log")"
done
grep -qE "estimate/pose \(robot_id=1\): hand-over from .* to .* \(exclusive ownership\)" "$WORK/control.log" ||
  fail "the controller logged no hand-over of estimate/pose: $(cat "$WORK/control.log")"
handovers=$(grep -cE "estimate/pose \(robot_id=1\): hand-over" "$WORK/control.log")
[[ $handovers -le 3 ]] || fail "$handovers hand-overs of estimate/pose: both estimators reached the controller"
if grep -hE "rejected a sample on estimate/pose" "$WORK"/*.log; then
  fail "a reader refused samples of estimate/pose: both estimators reached it"
fi
python3 - "$out" "$killed_at" "$epoch_s" <<'PY' || fail "hand-over check failed"
import csv, sys
out, killed_at, epoch = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
def column(path, name):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return [(float(r["t_s"]), float(r[name])) for r in rows]
est = sorted(t for t, _ in column(f"{out}/estimate_pose.csv", "x"))
after_start = [t for t in est if t > epoch + 1.0]
gaps = [(b - a, a, b) for a, b in zip(after_start, after_start[1:])]
gap, last_old, first_new = max(gaps)
print(f"estimate/pose: longest gap {gap:.3f} s, from {last_old - epoch:.3f} s to {first_new - epoch:.3f} s "
      f"(primary killed at {killed_at - epoch:.3f} s); last sample at {est[-1] - epoch:.3f} s")
if not (last_old <= killed_at + 0.05 and first_new > killed_at):
    sys.exit("FAIL: the longest gap is not the hand-over after the kill")
if gap > 1.1:
    sys.exit(f"FAIL: hand-over took {gap:.3f} s > 1.1 s")
if est[-1] < killed_at + 3.0:
    sys.exit("FAIL: estimate/pose did not continue from the standby")
# The evaluator's own figure (summary.json "standby", from the same stamps as it takes them; it
# counts gaps after metrics_after_s = 5 s, before the kill) must be this one.
import json
standby = json.load(open(f"{out}/summary.json")).get("standby")
if standby is None:
    sys.exit("FAIL: summary.json has no \"standby\" section although the scenario has a hot standby")
figure = standby["robots"]["1"]
print(f"evaluator: handover_s {figure['handover_s']}, from {figure['from_s']} s to {figure['to_s']} s")
if abs(figure["handover_s"] - gap) > 1e-3 or abs(figure["from_s"] - (last_old - epoch)) > 0.05:
    sys.exit(f"FAIL: the evaluator's hand-over {figure} differs from the CSV's {gap:.6f} s from {last_old - epoch:.6f} s")
if figure["handover_s"] > 1.1:
    sys.exit(f"FAIL: the evaluator reports a hand-over of {figure['handover_s']} s > 1.1 s")
v = column(f"{out}/plant_state.csv", "v")
moving = [t for t, speed in v if abs(speed) > 1e-9]
stopped, start = 0.0, None
for t, speed in v:
    if t < moving[0]:
        continue
    if abs(speed) <= 1e-9:
        start = t if start is None else start
        stopped = max(stopped, t - start)
    else:
        start = None
print(f"plant: longest standstill after the start {stopped:.3f} s")
if stopped > 1.1:
    sys.exit(f"FAIL: the robot stood still for {stopped:.3f} s > 1.1 s")
print(f"ok: hand-over {gap:.3f} s")
PY

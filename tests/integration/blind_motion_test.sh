#!/usr/bin/env bash
# Issue 24, findings 3 and 5: the way-point controller never drives blind. paper1_waypoints in
# real time, each group in its own `robodds host --realtime` process; at speed, kill -9
#  1. the sensor host: the estimator's inputs go stale, its estimate turns invalid after its
#     input_timeout_s (0.5 s); the controller, which had a valid estimate, commands zero (before:
#     it crept on at invalid_estimate_speed_mps 0.3 m/s for 60 s, 19.2 m blind);
#  2. the estimation host: the estimate freezes; after two of the estimator's periods the controller
#     holds its last command (never raises it, before: 0.92 -> 1.32 m/s), zero at estimate_timeout_s.
# The controller's stop on an invalid estimate is braked within the robot's acceleration limits (as
# at the mission's end); on a stale one it is an instant zero (the plant brakes at its limit).
# Each time the robot must stop within v·(0.5 s + MARGIN) + v²/(2·max_accel) of where it was at the
# kill (plant/state CSV: the distance driven after the kill) and stay put. Distances, not exact
# times, are judged: a loaded 2-core machine delays processes by tens of ms.
source "$(dirname "$0")/lib.sh"
SCENARIO="$SRC/sim/scenarios/paper1_waypoints.yaml"
DURATION=14      # s of real time per round
KILL_AT=7        # s after step 0: the robot is at speed
LIMIT=0.5        # s: the estimator's input_timeout_s (round 1) and the controller's estimate_timeout_s (round 2)
MARGIN=0.3       # s of driving on at the kill speed for a loaded machine (delivery, scheduling, the evaluator)
# The start heading is given to the filter and trusted unchecked (prior_heading_tolerance_rad 0; else
# it counts only after ~4 m of creeping, issue 27): valid from the start, the robot tracks before the kill.
KNOWN_START=(--set estimator.init_theta_known=true --set estimator.init_theta_rad=0 --set estimator.prior_heading_tolerance_rad=0)
# --max-missed-steps: on a loaded machine a host may skip due steps (seen: 198 in a 14 s run beside
# three compilers); this test judges where the robot stops, the overrun rule has its own test.

# run_round VICTIM: runs every group, kills VICTIM at KILL_AT, waits for the others; outputs in $WORK/VICTIM.
run_round() {
  local victim="$1" group pid
  local epoch=$(( $(date +%s%N) + 4000000000 ))  # step 0 in 4 s: every host has started and matched
  for group in sim sensors estimation control evaluation; do
    "$ROBODDS" host --scenario "$SCENARIO" --group "$group" --realtime $(rt_priority_flag) --epoch-ns "$epoch" --duration "$DURATION" \
      --domain "$DOMAIN" --out "$WORK/$victim/out" "${KNOWN_START[@]}" --max-missed-steps 1000000 >"$WORK/$victim.$group.log" 2>&1 &
    pid=$!
    cleanup_pids+=("$pid")
    eval "pid_$group=$pid"
  done
  sleep "$(echo "($epoch + $KILL_AT * 1000000000 - $(date +%s%N)) / 1000000000" | bc -l)"
  eval "pid=\$pid_$victim"
  kill -0 "$pid" 2>/dev/null || fail "the $victim host died on its own: $(cat "$WORK/$victim.$victim.log")"
  kill -9 "$pid"
  kill_ns=$(date +%s%N)
  for group in sim sensors estimation control evaluation; do
    [[ "$group" == "$victim" ]] && continue
    eval "pid=\$pid_$group"
    timeout -k 5 60 tail --pid="$pid" -f /dev/null || fail "host $group did not finish: $(tail -5 "$WORK/$victim.$group.log")"
    # A survivor that exchanged topics with the victim ends degraded (exit 3) naming it (issue 24,
    # finding 6); the evaluation host needs every host, so it must; the others may end cleanly.
    rc=0
    wait "$pid" || rc=$?
    [[ $rc -eq 0 || $rc -eq 3 ]] || fail "host $group exited $rc after the $victim kill: $(tail -5 "$WORK/$victim.$group.log")"
    [[ $rc -eq 0 ]] || grep -q "lost group '$victim' at" "$WORK/$victim.$group.log" \
      || fail "host $group ended degraded without naming the lost group '$victim': $(tail -5 "$WORK/$victim.$group.log")"
    [[ $group != evaluation || $rc -eq 3 ]] || fail "the evaluation host did not report the lost group '$victim' (exit $rc)"
  done
  python3 - "$WORK/$victim/out" "$kill_ns" "$LIMIT" "$MARGIN" "$SCENARIO" "$victim" <<'PY' || fail "robot drove on after the $victim kill"
import csv, math, re, sys
out, kill_s, limit, margin, victim = sys.argv[1], int(sys.argv[2]) * 1e-9, float(sys.argv[3]), float(sys.argv[4]), sys.argv[6]
body = next((line for line in open(sys.argv[5]) if "robot_body:" in line), "")
accel = float(re.search(r"max_accel_mps2: ([0-9.eE+-]+)", body).group(1))
def rows(name):
    with open(f"{out}/{name}") as f:
        return [r for r in csv.DictReader(f) if r["robot_id"] == "1"]
states, cmds = rows("plant_state.csv"), rows("plant_cmd.csv")
before = [p for p in states if float(p["t_s"]) < kill_s]
after = [p for p in states if float(p["t_s"]) >= kill_s]
if not before or len(after) < 300:
    sys.exit(f"FAIL: too few plant states to judge: {len(before)} before, {len(after)} after the kill")
v_kill = abs(float(before[-1]["v"]))
if v_kill < 0.5:
    sys.exit(f"FAIL: the robot was not at speed at the kill: v = {v_kill} m/s")
path = [before[-1]] + after
driven = sum(math.hypot(float(b["x"]) - float(a["x"]), float(b["y"]) - float(a["y"])) for a, b in zip(path, path[1:]))
bound = v_kill * (limit + margin) + v_kill ** 2 / (2.0 * accel)
moving = [p for p in after if float(p["v"]) != 0.0]
stop_s = (float(moving[-1]["t_s"]) - kill_s) if moving else 0.0
end_s = float(after[-1]["t_s"]) - kill_s
print(f"{victim} killed at v = {v_kill:.3f} m/s: driven {driven:.3f} m after the kill (bound {bound:.3f} m), "
      f"standstill {stop_s:.3f} s after it (run ends {end_s:.3f} s after it)")
if driven > bound:
    sys.exit(f"FAIL: {driven:.3f} m driven after the {victim} kill, more than {bound:.3f} m")
if end_s - stop_s < 2.0:
    sys.exit(f"FAIL: still moving {stop_s:.3f} s after the {victim} kill (run ends at {end_s:.3f} s): v = {moving[-1]['v']}")
# The controller's own commands: zero once the stop is braked (the invalid estimate's stop is ramped
# within max_accel like the plant's braking; the stale one is an instant zero) -- no creeping...
zero_from = limit + margin + v_kill / accel
late = [c for c in cmds if float(c["t_s"]) >= kill_s + zero_from]
bad = [c for c in late if float(c["v"]) != 0.0 or float(c["omega"]) != 0.0]
if len(late) < 100 or bad:
    sys.exit(f"FAIL: {len(bad)} of {len(late)} commands not zero from {zero_from:.3f} s after the kill on" +
             (f", first {float(bad[0]['t_s']) - kill_s:.3f} s: v = {bad[0]['v']}" if bad else ""))
# ... and, the estimate frozen, never higher than the highest around the kill (finding 5). (After the
# sensor kill the estimator goes on publishing fresh predictions for input_timeout_s: not a frozen estimate.)
if victim != "estimation":
    sys.exit(0)
def speeds(lo, hi):
    return [abs(float(c["v"])) for c in cmds if kill_s + lo <= float(c["t_s"]) < kill_s + hi]
around, later = max(speeds(-0.1, 0.1), default=0.0), max(speeds(0.1, 1e9), default=0.0)
if later > around + 0.02:
    sys.exit(f"FAIL: the command rose to {later:.3f} m/s after the {victim} kill (at most {around:.3f} m/s around it)")
PY
}

run_round sensors
run_round estimation

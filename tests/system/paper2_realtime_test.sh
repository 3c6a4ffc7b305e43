#!/usr/bin/env bash
# Paper 2 in real time (wall-clock timers, latest-sample inputs) across processes, on a small
# mission (tests/system/paper2_realtime.yaml: 30 m orbit at 3 m/s, range noise 0.5 m): the
# formation forms before the switch at 30 s (every radius within 2 m, every gap within 15 deg of
# 90), robots 1-3 then reach target 2's circle and robot 4 stops.
source "$(dirname "$0")/../integration/lib.sh"
timeout -k 5 150 "$ROBODDS" run "$(dirname "$0")/paper2_realtime.yaml" --realtime $(rt_priority_flag) --deploy processes \
  --out "$WORK/run" --domain "$DOMAIN" --no-plots >"$WORK/run.log" 2>&1 || fail "run failed: $(tail -5 "$WORK/run.log")"
python3 - "$WORK/run/plant_state.csv" <<'PY' || fail "formation check failed: $(tail -3 "$WORK/run.log")"
import csv, math, sys
targets = {1: (0.0, 0.0), 2: (20.0, 10.0)}
radius, switch_s, end_s = 30.0, 30.0, 60.0
rows = list(csv.DictReader(open(sys.argv[1])))
t0 = float(rows[0]["t_s"])  # real time: t_s is the wall clock's; count from the first row
def window(a, b):
    """The newest state of each robot with a <= t - t0 < b."""
    last = {}
    for r in rows:
        if a <= float(r["t_s"]) - t0 < b:
            last[int(r["robot_id"])] = r
    return last
def formation(states, target, team):
    cx, cy = targets[target]
    radius_err = max(abs(math.hypot(float(states[i]["x"]) - cx, float(states[i]["y"]) - cy) - radius) for i in team)
    bearings = sorted(math.degrees(math.atan2(float(states[i]["y"]) - cy, float(states[i]["x"]) - cx)) % 360 for i in team)
    gaps = [(bearings[(k + 1) % len(team)] - bearings[k]) % 360 for k in range(len(team))]
    return radius_err, max(abs(g - 360 / len(team)) for g in gaps)
before = window(switch_s - 2, switch_s - 0.5)
r1, g1 = formation(before, 1, [1, 2, 3, 4])
after = window(end_s - 3, end_s)
r2, _ = formation(after, 2, [1, 2, 3])
v4 = abs(float(after[4]["v"]))
print(f"before the switch: radius error {r1:.2f} m, gap error {g1:.1f} deg; at the end: radius error {r2:.2f} m, robot 4 at {v4} m/s")
if not (r1 < 2.0 and g1 < 15.0):
    sys.exit("FAIL: the formation did not form around target 1 in real time")
if not r2 < 3.0:
    sys.exit("FAIL: robots 1-3 did not reach target 2's circle")
if v4 != 0.0:
    sys.exit("FAIL: robot 4 left the mission but still moves")
PY
echo "ok: paper 2 in real time across processes forms the formation"

#!/usr/bin/env python3
"""Issue 27, "missions degrade gracefully": what the way-point controller does through the gaps of
its pose estimate, per run of a `robodds sweep` of paper1_waypoints (docs/results/paper1.md,
"Controller through estimate gaps"). For each run: way-points reached, time to the last one, the
gaps (control/status state ESTIMATE_INVALID after the first TRACKING step and before the mission is
done), how many of them brought the robot to a standstill (applied |v| < 0.01 m/s in plant/state),
the time it stood in them and the distance it drove in them.

  scripts/paper1_estimate_gaps.py SWEEP_DIR [SWEEP_DIR ...]   (each from robodds sweep --out SWEEP_DIR)"""
import csv
import json
import math
import os
import sys

INVALID = "3"   # ControlState ESTIMATE_INVALID (docs/architecture.md)
TRACKING = "0"
STANDSTILL_MPS = 0.01


def gaps_of(run_dir):
    with open(os.path.join(run_dir, "summary.json")) as f:
        robot = json.load(f)["metrics"]["robots"]["1"]
    with open(os.path.join(run_dir, "control_status.csv")) as f:
        status = [r for r in csv.DictReader(f) if r["robot_id"] == "1"]
    with open(os.path.join(run_dir, "plant_state.csv")) as f:
        states = {r["t_s"]: r for r in csv.DictReader(f) if r["robot_id"] == "1"}
    first = next((float(r["t_s"]) for r in status if r["state"] == TRACKING), None)
    done_s = robot["time_to_final_s"] if robot["time_to_final_s"] >= 0 else math.inf
    gaps, gap, previous = [], None, None
    for row in status:
        t = float(row["t_s"])
        state = states.get(row["t_s"])
        if first is not None and first < t < done_s and row["state"] == INVALID:
            if gap is None:
                gap = {"start_s": t, "length_s": 0.0, "stood_s": 0.0, "standstill": False, "driven_m": 0.0}
                gaps.append(gap)
            gap["length_s"] += 0.01
            if state is not None:
                if abs(float(state["v"])) < STANDSTILL_MPS:
                    gap["stood_s"] += 0.01
                    gap["standstill"] = True
                if previous is not None:
                    gap["driven_m"] += math.hypot(float(state["x"]) - float(previous["x"]),
                                                  float(state["y"]) - float(previous["y"]))
        else:
            gap = None
        previous = state
    return robot, gaps


def main(sweeps):
    for sweep in sweeps:
        with open(os.path.join(sweep, "runs.csv")) as f:
            seeds = {int(r["run"]): r["seed"] for r in csv.DictReader(f)}
        print(sweep)
        for run in sorted(os.listdir(os.path.join(sweep, "runs"))):
            robot, gaps = gaps_of(os.path.join(sweep, "runs", run))
            lengths = sorted(round(g["length_s"], 2) for g in gaps)
            longest = f", longest {lengths[-1]:.2f} s" if lengths else ""
            print(f"  seed {seeds[int(run)]}: {robot['waypoints_reached']}/{robot['waypoints_total']}, "
                  f"time to final {robot['time_to_final_s']} s, gaps {len(gaps)}{longest}, "
                  f"standstills in them {sum(g['standstill'] for g in gaps)}, stood {sum(g['stood_s'] for g in gaps):.2f} s, "
                  f"driven in them {sum(g['driven_m'] for g in gaps):.2f} m")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])

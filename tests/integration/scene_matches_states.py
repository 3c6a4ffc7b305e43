#!/usr/bin/env python3
"""The foxglove/robot_poses channel of a recording (`robodds record --foxglove-scene`, `robodds run
--record-foxglove-scene`), as decoded by the official reader (tests/npm/check_mcap.mjs, one JSON
line per message), against the run's plant_state.csv:

  scene_matches_states.py JSONL PLANT_STATE_CSV [--lockstep]

- foxglove.PosesInFrame messages, at least one per 250 ms of the run, at least 50 ms apart
  (publish_time, the samples' stamps); frame "world", timestamp = publish_time;
- every robot's pose in robot id order, each a plant/state row of its robot stamped no later than
  the message (x, y exactly, the heading as a rotation about z);
- --lockstep (the run's recorder in lockstep): exactly the messages the rule gives, the first
  plant/state stamp and then each first one at least 50 ms after the last message's; each with
  every robot, each pose its robot's row of that stamp; log_time = that step's plant/state log_time.
Exit 1 with one line at the first disagreement.
"""
import csv
import json
import math
import sys

PERIOD_NS = 50_000_000  # foxglove::kScenePeriodNs


def fail(reason):
    print(f"scene_matches_states: {reason}", file=sys.stderr)
    sys.exit(1)


def main(args):
    lockstep = "--lockstep" in args
    args = [a for a in args if a != "--lockstep"]
    if len(args) != 2:
        fail("usage: scene_matches_states.py JSONL PLANT_STATE_CSV [--lockstep]")
    messages = [json.loads(line) for line in open(args[0])]
    rows = list(csv.DictReader(open(args[1])))
    rows_by_robot = {}
    for r in rows:
        rows_by_robot.setdefault(int(r["robot_id"]), []).append(r)
    robots = sorted(rows_by_robot)
    stamps = sorted({int(r["header.stamp_ns"]) for r in rows})
    scene = [m for m in messages if m["topic"] == "foxglove/robot_poses"]
    run_ns = stamps[-1] - stamps[0]
    if len(scene) < max(1, run_ns // 250_000_000):
        fail(f"{len(scene)} foxglove/robot_poses messages for a {run_ns / 1e9:.1f} s run")
    previous = None
    for m in scene:
        t = int(m["publish_time"])
        if previous is not None and t - previous < PERIOD_NS:
            fail(f"scene messages {t - previous} ns apart (< 50 ms)")
        previous = t
        v = m["value"]
        if v["frame_id"] != "world" or v["timestamp"]["sec"] * 10**9 + v["timestamp"]["nsec"] != t:
            fail(f"scene header {v['frame_id']} {v['timestamp']}, publish_time {t}")
        if not 1 <= len(v["poses"]) <= len(robots) or (lockstep and len(v["poses"]) != len(robots)):
            fail(f"scene at {t}: {len(v['poses'])} poses, {len(robots)} robots")
        for k, pose in enumerate(v["poses"]):
            candidates = [r for r in rows_by_robot[robots[k]] if int(r["header.stamp_ns"]) <= t]
            if lockstep:
                candidates = [r for r in candidates if int(r["header.stamp_ns"]) == t]
            match = [r for r in candidates if float(r["x"]) == pose["position"]["x"] and float(r["y"]) == pose["position"]["y"]]
            if not match:
                fail(f"scene pose {k} at {t}: no plant/state row of robot {robots[k]} with x, y = {pose['position']}")
            theta = float(match[-1]["theta"])
            q = pose["orientation"]
            if abs(q["z"] - math.sin(theta / 2)) > 1e-12 or abs(q["w"] - math.cos(theta / 2)) > 1e-12:
                fail(f"scene heading {q}, theta {theta}")
    if lockstep:
        expected = []
        for s in stamps:
            if not expected or s - expected[-1] >= PERIOD_NS:
                expected.append(s)
        got = [int(m["publish_time"]) for m in scene]
        if got != expected:
            fail(f"{len(got)} scene messages at {got[:5]}..., the rule gives {len(expected)} at {expected[:5]}...")
        log_of_stamp = {int(m["publish_time"]): int(m["log_time"]) for m in messages if m["topic"] == "plant/state"}
        for m in scene:
            if int(m["log_time"]) != log_of_stamp.get(int(m["publish_time"])):
                fail(f"scene at {m['publish_time']}: log_time {m['log_time']}, its plant/state step's {log_of_stamp.get(int(m['publish_time']))}")
    print(f"ok: foxglove/robot_poses: {len(scene)} PosesInFrame messages of {len(robots)} robots, "
          f"each pose a plant/state row of its robot{' (lockstep: exactly the 50 ms rule)' if lockstep else ''}")


if __name__ == "__main__":
    main(sys.argv[1:])

#!/usr/bin/env python3
"""Writes a per-robot deployment of a paper-2 scenario: one range sensor, observer and controller
instance per robot, each robot's three in a group of their own (robot1, robot2, ...), the world
(mission, plant, poses) and the evaluator in two more; the events scaled to a short run.
Usage: paper2_per_robot.py SCENARIO OUT EVENT_TIME_S DURATION_S"""
import copy
import sys

import yaml

PER_ROBOT = {"range_sensor", "range_rate_observer", "circumnavigation_controller"}


def main(argv):
    source, out, event_time, duration = argv[1], argv[2], float(argv[3]), float(argv[4])
    s = yaml.safe_load(open(source))
    s["name"] += "_per_robot"
    s["duration_s"] = duration
    for e in s["events"]:
        if e["time_s"] > 0:
            e["time_s"] = event_time
    components, groups = [], {"world": [], "evaluation": []}
    for c in s["components"]:
        if c["type"] in PER_ROBOT:
            for r in s["robots"]:
                one = dict(copy.deepcopy(c), name="%s_%d" % (c["name"], r["id"]), robots=[r["id"]])
                components.append(one)
                groups.setdefault("robot%d" % r["id"], []).append(one["name"])
        else:
            components.append(c)
            groups["evaluation" if c["type"] == "evaluator" else "world"].append(c["name"])
    s["components"], s["groups"] = components, groups
    yaml.safe_dump(s, open(out, "w"), sort_keys=False)


if __name__ == "__main__":
    main(sys.argv)

#!/usr/bin/env python3
"""Writes a deployment of paper 3's experiment 2 in which EVERY robot runs its own UWB array and
relative estimator (the scenario runs robot 1's only, as the paper's Table 2), each robot's route
follower, odometry, UWB sensor and estimator in a group of their own (robot1, robot2, robot3), the
world and the evaluator (recording every robot's estimates) in two more; optional UWB frame loss.
Usage: paper3_per_robot.py SCENARIO OUT DURATION_S [FRAME_LOSS]"""
import copy
import sys

import yaml


def main(argv):
    source, out, duration = argv[1], argv[2], float(argv[3])
    frame_loss = float(argv[4]) if len(argv) > 4 else 0.0
    s = yaml.safe_load(open(source))
    s["name"] += "_per_robot"
    s["duration_s"] = duration
    by_name = {c["name"]: c for c in s["components"]}
    ids = [r["id"] for r in s["robots"]]
    for kind, template in (("uwb", by_name["uwb1"]), ("estimator", by_name["estimator1"])):
        for r in ids:
            name = "%s%d" % (kind, r)
            one = dict(copy.deepcopy(template), name=name, robots=[r])
            if kind == "uwb" and frame_loss > 0:
                one["params"]["frame_loss_probability"] = frame_loss
            if name in by_name:
                by_name[name].update(one)
            else:
                s["components"].append(one)
                s["groups"]["robot%d" % r].append(name)
    by_name["evaluator"]["robots"] = ids
    yaml.safe_dump(s, open(out, "w"), sort_keys=False)


if __name__ == "__main__":
    main(sys.argv)

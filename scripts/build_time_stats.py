#!/usr/bin/env python3
"""Where a build's time went: sums the steps of BUILD_DIR/.ninja_log (end - start of each step's
last run, which is wall time per step: on a loaded machine it exceeds the step's CPU time) by kind:
unit-test compiles (the -O1 objects of robodds_unit_test(), cmake/RoboddsHelpers.cmake), the
precompiled header, other compiles, executable links, static libraries, the rest (generators).
Usage: build_time_stats.py BUILD_DIR [--top N]   (docs/performance.md, Build time)."""
import argparse
import collections
import os
import re


def unit_test_objects(build_dir):
    """Objects whose compile has the unit tests' -O1 (read from build.ninja)."""
    objects, current = set(), None
    with open(os.path.join(build_dir, "build.ninja")) as f:
        for line in f:
            m = re.match(r"build (\S+\.o): CXX_COMPILER", line)
            if m:
                current = m.group(1)
            elif current and line.startswith("  FLAGS = "):
                if " -O1" in line and "-x c++-header" not in line:
                    objects.add(current)
                current = None
    return objects


def kind(output, tests):
    name = output.rsplit("/", 1)[-1]
    if output.endswith(".gch"):
        return "precompiled header"
    if output.endswith(".o"):
        return "compile unit test" if output in tests else "compile other"
    if output.endswith(".a"):
        return "static library"
    if output.endswith(".so"):
        return "link shared"
    if "." not in name:
        return "link executable"
    return "other"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("build_dir")
    parser.add_argument("--top", type=int, default=0, help="also list the N longest steps")
    args = parser.parse_args()
    last = {}
    with open(os.path.join(args.build_dir, ".ninja_log")) as f:
        for line in f:
            if line.startswith("#"):
                continue
            start, end, _mtime, output, _hash = line.rstrip("\n").split("\t")
            last[output] = (int(start), int(end))
    tests = unit_test_objects(args.build_dir)
    sums = collections.defaultdict(lambda: [0, 0])
    for output, (start, end) in last.items():
        entry = sums[kind(output, tests)]
        entry[0] += 1
        entry[1] += end - start
    total = sum(ms for _, ms in sums.values())
    for k, (n, ms) in sorted(sums.items(), key=lambda item: -item[1][1]):
        print(f"{k:20s} {n:5d} steps {ms / 1000:8.1f} s {100 * ms / total:5.1f} %")
    print(f"{'all steps':20s} {sum(n for n, _ in sums.values()):5d} steps {total / 1000:8.1f} s")
    span = max(e for _, e in last.values()) - min(s for s, _ in last.values())
    print(f"first start to last end: {span / 1000:.1f} s")
    for output, (start, end) in sorted(last.items(), key=lambda item: item[1][0] - item[1][1])[:args.top]:
        print(f"{(end - start) / 1000:7.1f} s {output}")


if __name__ == "__main__":
    main()

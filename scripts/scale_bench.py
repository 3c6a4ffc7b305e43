#!/usr/bin/python3
"""Issue 13's scaling table: plant_smoke with N robots (open-loop commander, plant, position sensor,
evaluator; the robots on a 3 m grid), lockstep, co-located and one process per group, for each N:
ticks per second (summary.json run.ticks_per_s), microseconds per robot-tick (1e6 / (ticks/s * N))
and the largest resident set of one process. Prints a Markdown table; --plot draws the cost per
robot-tick against N (docs/performance.md, "Cost per robot-tick").

  scripts/scale_bench.py [--robots 20,50,100,200,500,1000] [--deploy colocated,processes] [--duration S]
                         [--repeat K] [--lockstep-window W] [--robodds PATH] [--qos FILE] [--domain D]
                         [--out DIR] [--plot FILE.png]

Each (N, deploy) is run --repeat times, in turn, and the median is printed (the machine is noisy:
read the figures side by side, from one invocation). --duration is simulated seconds (100 Hz)."""
import argparse
import atexit
import json
import math
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile

import yaml

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BASE_SCENARIO = os.path.join(ROOT, "sim", "scenarios", "plant_smoke.yaml")
GRID_SPACING_M = 3.0


def scenario_with_robots(n):
    """plant_smoke with n robots on a square grid, GRID_SPACING_M apart, all heading 0."""
    with open(BASE_SCENARIO) as f:
        scenario = yaml.safe_load(f)
    side = math.ceil(math.sqrt(n))
    scenario["name"] = f"plant_smoke_{n}"
    scenario["robots"] = [{"id": i + 1, "x": GRID_SPACING_M * (i % side), "y": GRID_SPACING_M * (i // side), "theta": 0.0}
                          for i in range(n)]
    return scenario


def run_once(robodds, scenario_file, deploy, duration_s, domain, out_dir, timeout_s, qos, window):
    """One run; returns (ticks per second, max RSS of one process in MB). Raises on failure."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    cmd = [robodds, "--log", "warn", "run", scenario_file, "--deploy", deploy, "--duration", str(duration_s),
           "--domain", str(domain), "--out", out_dir, "--no-plots"] + (["--qos", qos] if qos else [])
    if deploy == "processes" and window != 1:  # co-located runs have no window (one process, no coordinator)
        cmd += ["--lockstep-window", str(window)]
    done = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, timeout=timeout_s)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} exited {done.returncode}: {done.stderr.strip()[-400:]}")
    with open(os.path.join(out_dir, "summary.json")) as f:
        run = json.load(f)["run"]
    if deploy == "processes" and run.get("lockstep_window") != window:
        raise RuntimeError(f"{' '.join(cmd)}: the run says lockstep_window {run.get('lockstep_window')}, asked {window}")
    ticks_per_s = run["ticks_per_s"]
    # ru_maxrss of the children is the largest of any waited-for descendant so far (kB): exact for
    # the first run, a lower bound after a larger one, so each run is measured in a fresh process.
    return ticks_per_s, max(before, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss) / 1024.0


def measure(args, n, deploy, scenario_file, work):
    """Median ticks/s and max RSS over --repeat runs, each in its own python child (fresh rusage)."""
    rates, rss = [], []
    for k in range(args.repeat):
        out_dir = os.path.join(work, f"{deploy}_{n}_{k}")
        child = subprocess.run([sys.executable, os.path.abspath(__file__), "--one", scenario_file, deploy, str(args.duration),
                                str(args.domain), out_dir, args.robodds, str(args.timeout), args.qos or "",
                                str(args.lockstep_window)],
                               capture_output=True, text=True)
        if child.returncode != 0:
            raise RuntimeError(child.stderr.strip())
        rate, mb = json.loads(child.stdout)
        rates.append(rate)
        rss.append(mb)
        shutil.rmtree(out_dir, ignore_errors=True)
    return statistics.median(rates), max(rss)


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--one":  # internal: one run in a fresh process
        scenario_file, deploy, duration, domain, out_dir, robodds, timeout, qos, window = sys.argv[2:11]
        print(json.dumps(run_once(robodds, scenario_file, deploy, float(duration), int(domain), out_dir, float(timeout), qos,
                                  int(window))))
        return 0
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--robots", default="20,50,100,200,500,1000", help="comma-separated robot counts")
    p.add_argument("--deploy", default="colocated,processes", help="colocated, processes or both")
    p.add_argument("--duration", type=float, default=5.0, help="simulated seconds per run (100 Hz steps)")
    p.add_argument("--repeat", type=int, default=3, help="runs per (N, deploy); the median is printed")
    p.add_argument("--lockstep-window", type=int, default=1,
                   help="ticks the coordinator may run ahead across processes (robodds run --lockstep-window)")
    p.add_argument("--robodds", default=os.path.join(ROOT, "build", "tools", "robodds", "robodds"))
    p.add_argument("--qos", help="QoS profile file instead of the default (e.g. an older robodds_qos.xml, to compare)")
    p.add_argument("--domain", type=int, default=127)
    p.add_argument("--timeout", type=float, default=600.0, help="s, per run")
    p.add_argument("--out", help="keep the scenarios here (default: a temporary folder)")
    p.add_argument("--plot", help="PNG of microseconds per robot-tick against N")
    args = p.parse_args()
    try:
        robots = [int(x) for x in args.robots.split(",")]
    except ValueError:
        p.error(f"--robots: '{args.robots}' is not a comma-separated list of integers")
    if not robots or min(robots) < 1:
        p.error("--robots: each count must be >= 1")
    deploys = args.deploy.split(",")
    for d in deploys:
        if d not in ("colocated", "processes"):
            p.error(f"--deploy: '{d}' is neither colocated nor processes")
    if args.repeat < 1 or args.duration <= 0:
        p.error("--repeat must be >= 1 and --duration > 0")
    if args.lockstep_window < 1:
        p.error("--lockstep-window must be >= 1")
    if not os.access(args.robodds, os.X_OK):
        p.error(f"--robodds: {args.robodds} is not an executable (build first: scripts/build.sh)")

    work = args.out or tempfile.mkdtemp(prefix="robodds_scale_")
    os.makedirs(work, exist_ok=True)
    if not args.out:  # also when a run fails and main() raises
        atexit.register(shutil.rmtree, work, True)
    rows = []
    print(f"plant_smoke with N robots, lockstep (window {args.lockstep_window} across processes), {args.duration:g} s "
          f"simulated, median of {args.repeat}", file=sys.stderr)
    for n in robots:
        scenario_file = os.path.join(work, f"plant_smoke_{n}.yaml")
        with open(scenario_file, "w") as f:
            yaml.safe_dump(scenario_with_robots(n), f, sort_keys=False)
        row = {"n": n}
        for deploy in deploys:
            rate, mb = measure(args, n, deploy, scenario_file, work)
            row[deploy] = (rate, 1e6 / (rate * n), mb)
            print(f"  N {n} {deploy}: {rate:,.0f} ticks/s, {1e6 / (rate * n):.2f} us per robot-tick, {mb:.0f} MB",
                  file=sys.stderr)
        rows.append(row)

    header = "| N robots |" + "".join(f" {d} ticks/s | {d} us per robot-tick | {d} max RSS (MB) |" for d in deploys)
    print(header)
    print("|---:|" + "---:|---:|---:|" * len(deploys))
    for row in rows:
        cells = "".join(f" {row[d][0]:,.0f} | {row[d][1]:.2f} | {row[d][2]:.0f} |" for d in deploys)
        print(f"| {row['n']} |{cells}")

    if args.plot:
        os.environ.setdefault("MPLBACKEND", "Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 4))
        for d in deploys:
            ax.plot([r["n"] for r in rows], [r[d][1] for r in rows], marker="o", label=d)
        ax.set_xscale("log")
        ax.set_xlabel("robots")
        ax.set_ylabel("us per robot-tick (lockstep)")
        ax.set_ylim(bottom=0)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
        ax.set_title("plant_smoke: cost per robot-tick")
        fig.tight_layout()
        fig.savefig(args.plot, dpi=120)
        print(f"plot: {args.plot}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/python3
"""Issue 13 item 2: plant_smoke with N robots in REAL TIME (100 Hz wall clock), co-located and one
process per group: for each N, the plant steps each host missed (summary.json hosts.<group>.missed_steps
and late_steps) and the CPU each process used (its utime + stime from /proc, sampled every 0.2 s,
over the run's wall time). Prints a Markdown table; the largest N with no missed step is the one
that "holds 100 Hz" on this machine.

  scripts/realtime_scale.py [--robots 100,200,400] [--deploy colocated,processes] [--duration S]
                            [--robodds PATH] [--domain D] [--max-missed K] [--rt-priority P]

--duration is wall seconds (real time). --rt-priority P runs the hosts' loops at SCHED_FIFO P
(`robodds run --rt-priority`, docs/deployment.md). A run whose hosts skip more than --max-missed steps is failed
by robodds itself (--max-missed-steps); the table then says so. Run it on an otherwise idle machine."""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import yaml

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scale_bench import ROOT, scenario_with_robots  # noqa: E402  (one N-robot scenario for both benchmarks)

CLOCK_TICKS = os.sysconf("SC_CLK_TCK")


def descendants(pid):
    """pid and every process below it (from /proc/<pid>/task/<pid>/children)."""
    found, todo = [], [pid]
    while todo:
        p = todo.pop()
        found.append(p)
        try:
            with open(f"/proc/{p}/task/{p}/children") as f:
                todo.extend(int(c) for c in f.read().split())
        except OSError:
            pass
    return found


def cpu_and_name(pid):
    """(utime + stime in s, a name: the --group of a host, else 'coordinator' or the command)."""
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    cpu_s = (int(fields[11]) + int(fields[12])) / CLOCK_TICKS
    with open(f"/proc/{pid}/cmdline") as f:
        argv = f.read().split("\0")
    if "--group" in argv:
        return cpu_s, argv[argv.index("--group") + 1]
    if "run" in argv:
        return cpu_s, "run (coordinator)"
    return cpu_s, os.path.basename(argv[0]) if argv[0] else ""


def run_realtime(args, scenario_file, deploy, out_dir):
    """One real-time run; returns (exit code, {process name: CPU %}, summary dict or None, stderr tail)."""
    cmd = [args.robodds, "--log", "warn", "run", scenario_file, "--realtime", "--deploy", deploy, "--duration",
           str(args.duration), "--domain", str(args.domain), "--out", out_dir, "--no-plots", "--max-missed-steps",
           str(args.max_missed)]
    if args.rt_priority is not None:
        cmd += ["--rt-priority", str(args.rt_priority)]
    err = tempfile.TemporaryFile(mode="w+")
    started = time.monotonic()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=err)
    cpu = {}  # pid -> (name, newest utime + stime)
    while proc.poll() is None:
        for pid in descendants(proc.pid):
            try:
                cpu_s, name = cpu_and_name(pid)
            except (OSError, IndexError):
                continue
            # A process that has exited (a zombie until reaped) keeps its times but loses its
            # command line: keep the name read while it ran.
            cpu[pid] = (cpu[pid][0] if pid in cpu and cpu[pid][0] else name, cpu_s)
        if time.monotonic() - started > args.duration + 120:
            proc.kill()
            proc.wait()
            break
        time.sleep(0.2)
    wall_s = time.monotonic() - started
    err.seek(0)
    summary = None
    try:
        with open(os.path.join(out_dir, "summary.json")) as f:
            summary = json.load(f)
    except (OSError, ValueError):
        pass
    shares = {}
    for name, cpu_s in cpu.values():
        shares[name] = shares.get(name, 0.0) + 100.0 * cpu_s / wall_s
    return proc.returncode, shares, summary, err.read().strip()[-300:]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--robots", default="100,200,400", help="comma-separated robot counts")
    p.add_argument("--deploy", default="colocated,processes")
    p.add_argument("--duration", type=float, default=20.0, help="wall seconds per run")
    p.add_argument("--robodds", default=os.path.join(ROOT, "build", "tools", "robodds", "robodds"))
    p.add_argument("--domain", type=int, default=127)
    p.add_argument("--max-missed", type=int, default=1000000, help="passed as --max-missed-steps (default: never fail)")
    p.add_argument("--rt-priority", type=int, default=None, help="passed as --rt-priority (SCHED_FIFO priority)")
    args = p.parse_args()
    try:
        robots = [int(x) for x in args.robots.split(",")]
    except ValueError:
        p.error(f"--robots: '{args.robots}' is not a comma-separated list of integers")
    deploys = args.deploy.split(",")
    if any(d not in ("colocated", "processes") for d in deploys) or min(robots) < 1 or args.duration <= 0:
        p.error("--deploy takes colocated and/or processes; --robots counts >= 1; --duration > 0")
    if not os.access(args.robodds, os.X_OK):
        p.error(f"--robodds: {args.robodds} is not an executable (build first: scripts/build.sh)")

    print("| N robots | deploy | exit | missed steps (per host) | late steps | CPU % per process |")
    print("|---:|---|---:|---|---:|---|")
    with tempfile.TemporaryDirectory(prefix="robodds_rt_") as work:
        for n in robots:
            scenario_file = os.path.join(work, f"plant_smoke_{n}.yaml")
            with open(scenario_file, "w") as f:
                yaml.safe_dump(scenario_with_robots(n), f, sort_keys=False)
            for deploy in deploys:
                code, shares, summary, err = run_realtime(args, scenario_file, deploy, os.path.join(work, f"{deploy}_{n}"))
                hosts = (summary or {}).get("hosts", {})
                missed = ", ".join(f"{h} {v.get('missed_steps', '?')}" for h, v in sorted(hosts.items())) or "-"
                late = sum(v.get("late_steps", 0) for v in hosts.values())
                cpu = ", ".join(f"{name} {share:.0f}" for name, share in sorted(shares.items()))
                print(f"| {n} | {deploy} | {code} | {missed} | {late} | {cpu} |", flush=True)
                if code != 0:
                    print(f"  ({deploy}, {n} robots: {err})", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Issue 27's "every shipped scenario: over-confident fraction <= 1 % for every estimate stage",
measured: runs scenarios for the given seeds and tabulates, per scenario and estimate stage, the
fraction of valid samples the evaluator found outside their reported 3-sigma bound, the longest
such run, the worst error while valid and the mission verdict, all read from each run's
summary.json (the evaluator's `consistency` / `overconfident_*` metrics, whatever the paper).

  scripts/consistency_audit.py [--seeds 1-10] [--domains 181,182] [--out DIR] [--check FRACTION]
                               [--longest-s S] [--set KEY=VALUE ...] [--duration S] [SCENARIO ...]

SCENARIO: scenario files; default every shipped one (sim/scenarios/*.yaml and degraded/*.yaml);
a scenario whose runs report no estimate stage is listed as such. --domains: one DDS domain per
parallel run (as many runs at a time as domains). --check: exit 1 naming every (scenario, stage,
seed) above FRACTION (e.g. 0.01), or with a run longer than --longest-s in a row, or a failed run.
Prints a markdown table on stdout; every run's outputs stay under OUT/<scenario>/seed<N>, the
per-run figures in OUT/audit.json. Needs a build (ROBODDS, default build/tools/robodds/robodds)."""
import argparse
import concurrent.futures
import glob
import json
import os
import queue
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ROBODDS = os.environ.get("ROBODDS", os.path.join(ROOT, "build", "tools", "robodds", "robodds"))


def shipped_scenarios():
    scenarios = os.path.join(ROOT, "sim", "scenarios")
    return sorted(glob.glob(os.path.join(scenarios, "*.yaml"))) + sorted(glob.glob(os.path.join(scenarios, "degraded", "*.yaml")))


def parse_seeds(text):
    seeds = []
    for part in text.split(","):
        low, _, high = part.partition("-")
        seeds.extend(range(int(low), int(high or low) + 1))
    if not seeds:
        sys.exit(f"--seeds: no seed in {text!r}")
    return seeds


def stage_figures(metrics):
    """Every estimate stage's consistency figures in a summary's metrics, by stage name.

    The evaluators name them differently per paper: paper 1 `estimate_pose.overconfident_*`,
    paper 2 `observer.<kind>.consistency`, paper 3 `stages.<stage>.consistency`; per-robot copies
    (`robots.N....`) are left out, the pooled figure is the one the issue bounds."""
    found = {}

    def walk(node, path):
        if not isinstance(node, dict):
            return
        if path and path[0] == "robots":
            return
        if "overconfident_fraction" in node:
            stage = ".".join(p for p in path if p != "consistency")
            found[stage or "estimate"] = {
                "fraction": float(node["overconfident_fraction"]),
                "longest_s": float(node.get("longest_overconfident_s", 0.0)),
                "valid_samples": node.get("valid_samples", node.get("samples")),
                "worst_position_m": node.get("worst_position_error_valid_m"),
                "worst_heading_deg": node.get("worst_heading_error_valid_deg"),
                "worst_rate_mps": node.get("worst_error_valid_mps"),
            }
            return
        for key, child in node.items():
            walk(child, path + [key])

    walk(metrics, [])
    return found


def run_one(scenario, seed, domain, out_dir, extra):
    os.makedirs(out_dir, exist_ok=True)
    command = [ROBODDS, "--log", "warn", "run", scenario, "--no-plots", "--seed", str(seed), "--out", out_dir,
               "--domain", str(domain)] + extra
    with open(os.path.join(out_dir, "run.log"), "w") as log:
        # A run is bounded: the longest shipped scenario (paper 3, 600 s with every stage) takes
        # ~2 min of CPU; an hour means it hangs.
        try:
            code = subprocess.run(command, stdout=log, stderr=subprocess.STDOUT, timeout=3600).returncode
        except subprocess.TimeoutExpired:
            return {"error": "timed out after 3600 s"}
    summary_path = os.path.join(out_dir, "summary.json")
    if code != 0 or not os.path.exists(summary_path):
        with open(os.path.join(out_dir, "run.log")) as log:
            tail = log.read().strip().splitlines()[-1:] or ["(no output)"]
        return {"error": f"exit {code}: {tail[0]}"}
    with open(summary_path) as f:
        summary = json.load(f)
    return {"stages": stage_figures(summary.get("metrics", {})), "mission": summary.get("mission", ""),
            "status": summary.get("status", "")}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenarios", nargs="*")
    parser.add_argument("--seeds", default="1-10")
    parser.add_argument("--domains", default="181")
    parser.add_argument("--out", default="/tmp/consistency_audit")
    parser.add_argument("--check", type=float, help="fail above this over-confident fraction (e.g. 0.01)")
    parser.add_argument("--longest-s", type=float, help="fail on an over-confident run longer than this (s)")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="passed to every run")
    parser.add_argument("--duration", type=float, help="passed to every run (s)")
    args = parser.parse_args()

    if not os.access(ROBODDS, os.X_OK):
        sys.exit(f"no robodds binary at {ROBODDS} (build first, or set ROBODDS)")
    scenarios = [os.path.abspath(s) for s in args.scenarios] or shipped_scenarios()
    for scenario in scenarios:
        if not os.path.isfile(scenario):
            sys.exit(f"{scenario}: no such scenario file")
    seeds = parse_seeds(args.seeds)
    try:
        domains = [int(d) for d in args.domains.split(",")]
    except ValueError:
        sys.exit(f"--domains: {args.domains!r} is not a comma-separated list of integers")
    extra = [arg for kv in args.set for arg in ("--set", kv)]
    if args.duration is not None:
        extra += ["--duration", str(args.duration)]

    def name_of(scenario):
        return os.path.relpath(scenario, os.path.join(ROOT, "sim", "scenarios")) if scenario.startswith(ROOT) \
            else os.path.basename(scenario)

    free = queue.Queue()
    for domain in domains:
        free.put(domain)

    def job(scenario, seed):
        domain = free.get()
        try:
            out_dir = os.path.join(args.out, name_of(scenario).replace("/", "_").removesuffix(".yaml"), f"seed{seed}")
            return run_one(scenario, seed, domain, out_dir, extra)
        finally:
            free.put(domain)

    results = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=len(domains)) as pool:
        futures = {(name_of(s), seed): pool.submit(job, s, seed) for s in scenarios for seed in seeds}
        for (name, seed), future in futures.items():
            results.setdefault(name, {})[seed] = future.result()
            print(f"# {name} seed {seed} done", file=sys.stderr, flush=True)
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "audit.json"), "w") as f:
        json.dump(results, f, indent=1, sort_keys=True)

    failures = []
    print(f"Seeds {args.seeds}{' ' + ' '.join(extra) if extra else ''}; over-confident: valid samples outside 3 reported sigmas.\n")
    print("| scenario | stage | over-confident (min-max over seeds) | worst seed | longest run (s) | worst error while valid | missions |")
    print("|---|---|---|---|---|---|---|")
    for name in sorted(results):
        runs = results[name]
        for seed, run in sorted(runs.items()):
            if "error" in run:
                failures.append(f"{name} seed {seed}: run failed ({run['error']})")
        good = {seed: run for seed, run in runs.items() if "error" not in run}
        stages = sorted({stage for run in good.values() for stage in run["stages"]})
        missions = sorted({run["mission"] or run["status"] for run in good.values()})
        if not stages:
            print(f"| {name} | (no estimate stage) | | | | | {'; '.join(missions)} |")
            continue
        for stage in stages:
            per_seed = {seed: run["stages"][stage] for seed, run in good.items() if stage in run["stages"]}
            fractions = [f["fraction"] for f in per_seed.values()]
            worst_seed = max(per_seed, key=lambda s: per_seed[s]["fraction"])
            longest = max(f["longest_s"] for f in per_seed.values())
            worst = []
            for key, unit in (("worst_position_m", "m"), ("worst_heading_deg", "deg"), ("worst_rate_mps", "m/s")):
                values = [f[key] for f in per_seed.values() if f[key] is not None]
                if values:
                    worst.append(f"{max(values):.3g} {unit}")
            print(f"| {name} | {stage} | {100 * min(fractions):.3f}-{100 * max(fractions):.3f} % | {worst_seed} | "
                  f"{longest:.2f} | {' / '.join(worst)} | {'; '.join(missions)} |")
            for seed, figures in sorted(per_seed.items()):
                if args.check is not None and figures["fraction"] > args.check:
                    failures.append(f"{name} {stage} seed {seed}: over-confident {100 * figures['fraction']:.2f} % "
                                    f"> {100 * args.check:g} %")
                if args.longest_s is not None and figures["longest_s"] > args.longest_s:
                    failures.append(f"{name} {stage} seed {seed}: over-confident for {figures['longest_s']:.2f} s in a row "
                                    f"> {args.longest_s:g} s")
    if failures:
        # Only a failed run or a bound that was asked for puts anything here.
        print("\nFAIL:\n" + "\n".join(f"- {f}" for f in failures))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

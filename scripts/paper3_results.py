#!/usr/bin/env python3
"""Reproduces paper 3's Tables 1 and 2 (docs/results/paper3.md) on the platform and checks issue
11's acceptance figures: experiment 1-a (arrays of side 0.3 / 0.5 / 0.7 m, windows 5 / 30 / 80 /
160), experiment 2, non-line-of-sight ranges with and without the robust loss, and the ablation
"white-only vs structured range noise". Each figure is the mean over seeds with its 95 % confidence
interval (Student t); prints markdown tables on stdout, every run's CSVs and summary.json stay
under OUT, the per-run metrics in OUT/results.json.

  scripts/paper3_results.py [--out DIR] [--seeds N] [--domains 0,1] [--parts LIST] [--check] [--reuse]   (needs a build)

--parts: comma-separated subset of table1 (every side x window), sides (w 30 only, the three
sides), windows (side 0.5: w 5 and 80), table2, nlos, ablation; default all. --check: exit 1
naming every acceptance figure that is missed (among the parts run)."""
import argparse
import concurrent.futures
import csv
import json
import math
import os
import subprocess
import sys

import yaml

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ROBODDS = os.environ.get("ROBODDS", os.path.join(ROOT, "build", "tools", "robodds", "robodds"))
SCENARIOS = os.path.join(ROOT, "sim", "scenarios")
STAGES = ["odometry", "uwb", "window", "pf_baseline", "pf"]
# The paper's figures: (position m, heading deg). Table 1 per side; Table 2.
PAPER_T1 = {
    0.3: {"odometry": (0.96, 10.01), "uwb": (0.48, 7.57), "w5": (0.42, 7.02), "w30": (0.38, 4.46), "w80": (0.33, 2.99),
          "w160": (0.37, 3.49), "pf_baseline": (0.35, 5.31), "pf": (0.25, 2.91)},
    0.5: {"odometry": (0.79, 6.27), "uwb": (0.39, 5.27), "w5": (0.35, 4.77), "w30": (0.33, 3.75), "w80": (0.30, 2.55),
          "w160": (0.30, 2.91), "pf_baseline": (0.49, 6.26), "pf": (0.22, 2.70)},
    0.7: {"odometry": (0.62, 3.71), "uwb": (0.37, 5.05), "w5": (0.33, 4.69), "w30": (0.32, 3.19), "w80": (0.30, 2.35),
          "w160": (0.31, 3.09), "pf_baseline": (0.35, 4.84), "pf": (0.25, 2.02)},
}
# Experiment 1-b (text of section 4.2: only the odometry and the proposed filter are given).
PAPER_1B = {"odometry": (0.48, 8.61), "pf": (0.29, 4.39)}
PAPER_T2 = {"odometry": (1.466, 22.076), "uwb": (0.528, 7.413), "window": (0.424, 5.648), "pf_baseline": (0.534, 7.234),
            "pf": (0.312, 4.903)}
# The rows of a per-stage table (Table 2, experiment 1-b): (title, stage).
STAGE_ROWS = (("odometry", "odometry"), ("UWB only (eq. 1)", "uwb"), ("window w = 30", "window"),
              ("PF (ranges + odometry) [22]", "pf_baseline"), ("PF (window + odometry), ours", "pf"))
# Issue 27's 1 % over-confident bound is not met here (docs/results/paper3.md "Estimate consistency"):
# none since the per-node bias term (branch p3-honest2) took experiment 1-b's uwb stage under it.
CONSISTENCY_NOT_MET = set()
# Issue 27's degraded case (--parts degraded, by hand; docs/results/paper3.md "Degraded sensing"):
# experiment 2 with 0.25 m arrays and NLOS p = 0.05 on every link; each stage over-confident in at
# most 2 % of its valid samples and never for more than 2 s in a row, on every seed.
DEGRADED_FRACTION = 0.02
DEGRADED_RUN_S = 2.0
# Two-sided 95 % Student t quantiles by degrees of freedom.
T95 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365, 8: 2.306, 9: 2.262, 10: 2.228, 11: 2.201,
       12: 2.179, 13: 2.160, 14: 2.145, 19: 2.093, 29: 2.045}
# White-only range noise of the ablation: the single-epoch position error of the structured model
# (NOTES.md: white 0.13 m gives eq. 1's 0.39 m at side 0.5).
WHITE_ONLY = {"white_sigma_m": 0.13, "link_bias_sigma_m": 0.0, "common_sigma_m": 0.0}
# Experiment 2's range noise as issue 11 first put it: the base sigmas (0.04 / 0.07 / 0.30 m) all
# x 1.25; paper3_exp2.yaml grows the per-link terms only (components/uwb_sensor/README.md).
EXP2_UNIFORM = {"white_sigma_m": 0.04, "link_bias_sigma_m": 0.07, "common_sigma_m": 0.30, "sigma_scale": 1.25}


def variant(base, name, out_dir, component_params, facts=None):
    """Scenario `base` with parameter overrides {component name: {key: value}} and shared-fact
    overrides {fact: {key: value}} (the scenario's `facts:`, system/robot_facts.hpp), written to OUT."""
    s = yaml.safe_load(open(os.path.join(SCENARIOS, base + ".yaml")))
    s["name"] = name
    for c in s["components"]:
        for key, value in component_params.get(c["name"], {}).items():
            c.setdefault("params", {})[key] = value
    for fact, values in (facts or {}).items():
        s.setdefault("facts", {}).setdefault(fact, {}).update(values)
    path = os.path.join(out_dir, name + ".yaml")
    yaml.safe_dump(s, open(path, "w"), sort_keys=False)
    return path


def exp1a(name, out_dir, side=0.5, window=30, uwb=None, estimator=None):
    # The array side is the scenario's fact: the one array the sensor and the estimator both use.
    est_params = dict({"window_epochs": window}, **(estimator or {}))
    return variant("paper3_exp1a", name, out_dir, {"uwb": dict(uwb or {}), "estimator": est_params},
                   {"uwb_array": {"array_side_m": side}})


def run(job, out_dir, domain, reuse=False):
    """One `robodds run` (lockstep, co-located); returns its summary.json or None. With `reuse`, a
    run whose summary.json says completed is read, not run again."""
    label, scenario, seed = job
    out = os.path.join(out_dir, label)
    summary = os.path.join(out, "summary.json")
    if reuse and os.path.exists(summary) and json.load(open(summary)).get("status") == "completed":
        return json.load(open(summary))
    cmd = [ROBODDS, "run", scenario, "--out", out, "--domain", str(domain), "--no-plots", "--seed", str(seed)]
    with open(out + ".log", "w") as f:
        code = subprocess.call(cmd, stdout=f, stderr=subprocess.STDOUT, timeout=900)
    summary = os.path.join(out, "summary.json")
    if code != 0 or not os.path.exists(summary):
        return None
    return json.load(open(summary))


def run_all(jobs, out_dir, domains, reuse=False):
    """Runs every (label, scenario, seed) job, len(domains) at a time; returns {label: summary or None}.
    Also used by scripts/paper1_robustness.py."""
    results = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=len(domains)) as pool:
        # One chain of jobs per domain: two runs at once never share a domain.
        def chain(slot):
            for i in range(slot, len(jobs), len(domains)):
                results[jobs[i][0]] = run(jobs[i], out_dir, domains[slot], reuse)
        list(pool.map(chain, range(len(domains))))
    return results


def report_misses(failures, check):
    """The end of every results script: names each missed acceptance figure on stderr; the exit
    code is 1 when there are misses and --check was given, else 0."""
    if failures:
        print("\nMISSED:\n" + "\n".join(failures), file=sys.stderr)
        return 1 if check else 0
    return 0


def mean_ci(values):
    """(mean, half-width of the 95 % confidence interval of the mean)."""
    n = len(values)
    mean = sum(values) / n
    if n < 2:
        return mean, float("nan")
    sd = math.sqrt(sum((v - mean) ** 2 for v in values) / (n - 1))
    t = T95.get(n - 1) or T95[max(k for k in T95 if k <= n - 1)]
    return mean, t * sd / math.sqrt(n)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "paper3_results"))
    ap.add_argument("--seeds", type=int, default=10)
    ap.add_argument("--domains", default="0,1")
    ap.add_argument("--parts", default="table1,table2,nlos,ablation,exp1b")
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--reuse", action="store_true", help="read the runs already completed under OUT instead of running them again")
    args = ap.parse_args(argv[1:])
    os.makedirs(args.out, exist_ok=True)
    domains = [int(d) for d in args.domains.split(",")]
    parts = set(args.parts.split(","))
    seeds = list(range(1, args.seeds + 1))

    configs = {}  # label -> scenario path
    if "table1" in parts:
        for side in (0.3, 0.5, 0.7):
            for w in (5, 30, 80, 160):
                configs["exp1a_s%g_w%d" % (side, w)] = exp1a("exp1a_s%g_w%d" % (side, w), args.out, side, w)
    if "sides" in parts:
        for side in (0.3, 0.5, 0.7):
            configs["exp1a_s%g_w30" % side] = exp1a("exp1a_s%g_w30" % side, args.out, side, 30)
    if "windows" in parts:
        for w in (5, 30, 80):
            configs["exp1a_s0.5_w%d" % w] = exp1a("exp1a_s0.5_w%d" % w, args.out, 0.5, w)
    if "nlos" in parts:
        configs["exp1a_s0.5_w30"] = exp1a("exp1a_s0.5_w30", args.out, 0.5, 30)
        configs["nlos_plain"] = exp1a("nlos_plain", args.out, uwb={"nlos_probability": 0.02})
        configs["nlos_huber"] = exp1a("nlos_huber", args.out, uwb={"nlos_probability": 0.02},
                                      estimator={"solver": {"loss": "huber", "loss_scale_m": 0.15}})
    if "ablation" in parts:
        configs["exp1a_s0.5_w30"] = exp1a("exp1a_s0.5_w30", args.out, 0.5, 30)
        configs["white_only"] = exp1a("white_only", args.out, uwb=WHITE_ONLY)
        configs["exp2"] = os.path.join(SCENARIOS, "paper3_exp2.yaml")
        configs["exp2_uniform"] = variant("paper3_exp2", "exp2_uniform", args.out, {"uwb1": EXP2_UNIFORM, "uwb2": EXP2_UNIFORM})
    if "table2" in parts:
        configs["exp2"] = os.path.join(SCENARIOS, "paper3_exp2.yaml")
    if "exp1b" in parts:
        configs["exp1b"] = os.path.join(SCENARIOS, "paper3_exp1b.yaml")
        configs["exp1b_open"] = variant("paper3_exp1b", "exp1b_open", args.out, {"uwb": {"nlos_walls_m": []}})
    if "degraded" in parts:
        nlos = {"nlos_probability": 0.05}
        configs["degraded"] = variant("paper3_exp2", "degraded", args.out, {"uwb1": nlos, "uwb2": nlos},
                                      {"uwb_array": {"array_side_m": 0.25}})
    # Longest runs first so that the two slots end together.
    jobs = sorted([(label + "_seed%d" % s, path, s) for label, path in configs.items() for s in seeds],
                  key=lambda j: (not j[0].startswith(("exp2", "degraded")), j[0]))
    results = run_all(jobs, args.out, domains, args.reuse)
    failures = ["run %s failed (log: %s.log)" % (label, os.path.join(args.out, label)) for label, s in results.items() if s is None]
    if failures:
        print("\n".join(failures), file=sys.stderr)
        return 1
    json.dump({label: s["metrics"] for label, s in results.items()}, open(os.path.join(args.out, "results.json"), "w"),
              indent=1, sort_keys=True)

    def all_solves_error(label):
        """Mean position error (m) of every eq. (1) solve from t >= 20 s, valid or not (suspect
        solves are published with their best fit; epochs without a solve are all zeros)."""
        total, n = 0.0, 0
        with open(os.path.join(args.out, label, "estimate_relative_pose_uwb.csv")) as f:
            for row in csv.DictReader(f):
                x, y, theta = float(row["x"]), float(row["y"]), float(row["theta"])
                if float(row["t_s"]) < 20.0 or (x == 0.0 and y == 0.0 and theta == 0.0):
                    continue
                total += math.hypot(x - float(row["true_x"]), y - float(row["true_y"]))
                n += 1
        return total / n

    all_solves = {}
    for config in ("exp1a_s0.5_w30", "nlos_plain", "nlos_huber"):
        if config in configs:
            all_solves[config] = mean_ci([all_solves_error("%s_seed%d" % (config, s)) for s in seeds])

    def values(config, stage, key, subkey=None):
        got = [results["%s_seed%d" % (config, s)]["metrics"]["stages"][stage][key] for s in seeds]
        return [g[subkey] for g in got] if subkey else got

    def coverage(config, stage):
        """Share of the epochs after metrics_after_s with a valid estimate, over the seeds."""
        valid = sum(values(config, stage, "epochs"))
        invalid = sum(values(config, stage, "invalid_epochs"))
        return valid / (valid + invalid) if valid + invalid else 0.0

    def stat(config, stage, key="position_error_m_mean"):
        return mean_ci(values(config, stage, key))[0]

    def cell(config, stage):
        p, pc = mean_ci(values(config, stage, "position_error_m_mean"))
        h, hc = mean_ci(values(config, stage, "heading_error_deg_mean"))
        return "%.3f ± %.3f m / %.2f ± %.2f°" % (p, pc, h, hc)

    def paper(fig):
        return "%.2f m / %.2f°" % fig

    print("Means over %d seeds ± the half-width of their 95 %% confidence interval (Student t); the paper's "
          "figures in the next column. Errors from t >= 20 s." % len(seeds))
    sides = [s for s in (0.3, 0.5, 0.7) if "exp1a_s%g_w30" % s in configs]
    if sides:
        print()
        print("### Table 1: experiment 1-a (robot 1 around static robot 2)")
        print()
        print("| row | " + " | ".join("side %g m: ours | paper" % s for s in sides) + " |")
        print("|---|" + "---|---|" * len(sides))
        rows = [("odometry", "odometry", 30), ("UWB only (eq. 1)", "uwb", 30)]
        rows += [("window w = %d" % w, "window", w) for w in (5, 30, 80, 160)]
        rows += [("PF (ranges + odometry) [22]", "pf_baseline", 30), ("PF (window + odometry), ours", "pf", 30)]
        for title, stage, w in rows:
            key = stage if stage != "window" else "w%d" % w
            cells = []
            for s in sides:
                config = "exp1a_s%g_w%d" % (s, w)
                cells.append((cell(config, stage) if config in configs else "-") + " | " + paper(PAPER_T1[s][key]))
            print("| %s | %s |" % (title, " | ".join(cells)))
    if "exp2" in configs:
        print()
        print("### Table 2: experiment 2 (robots 2 and 3 in robot 1's frame, pooled)")
        print()
        print("| row | ours | paper |")
        print("|---|---|---|")
        for title, stage in STAGE_ROWS:
            print("| %s | %s | %s |" % (title, cell("exp2", stage), paper(PAPER_T2[stage])))
    if "nlos_plain" in configs:
        print()
        print("### Non-line-of-sight ranges (p = 0.02, excess 0.2-1.5 m), side 0.5 m, w = 30")
        print()
        print("| eq. (1) loss | UWB only, every solve | UWB only, valid solves | valid | window | PF |")
        print("|---|---|---|---:|---|---|")
        for title, config in (("clean ranges, loss none", "exp1a_s0.5_w30"), ("NLOS, loss none (the paper)", "nlos_plain"),
                              ("NLOS, Huber 0.15 m", "nlos_huber")):
            p, pc = all_solves[config]
            print("| %s | %.3f ± %.3f m | %s | %.1f %% | %s | %s |" % (title, p, pc, cell(config, "uwb"), 100 * coverage(config, "uwb"),
                                                                      cell(config, "window"), cell(config, "pf")))
    if "white_only" in configs:
        print()
        print("### Ablation: white-only vs structured range noise, side 0.5 m, w = 30")
        print()
        print("| range noise | UWB only | window | PF | window / UWB |")
        print("|---|---|---|---|---|")
        for title, config in (("structured (white 0.04 + link GM 0.07/2 s + pair GM 0.30/10 s)", "exp1a_s0.5_w30"),
                              ("white only, 0.13 m", "white_only")):
            print("| %s | %s | %s | %s | %.2f |" % (title, cell(config, "uwb"), cell(config, "window"), cell(config, "pf"),
                                                    stat(config, "window") / stat(config, "uwb")))
    if "exp1b" in configs:
        print()
        print("### Experiment 1-b: a board between the robots, an irregular path (side 0.5 m, w = 30, Huber 0.15 m)")
        print()
        print("| row | ours | paper |")
        print("|---|---|---|")
        for title, stage in STAGE_ROWS:
            print("| %s | %s | %s |" % (title, cell("exp1b", stage), paper(PAPER_1B[stage]) if stage in PAPER_1B else "-"))
        for title, stage in (("UWB only, the board taken away", "uwb"), ("PF, the board taken away", "pf")):
            print("| %s | %s | - |" % (title, cell("exp1b_open", stage)))
    if "exp2_uniform" in configs:
        print()
        print("### Experiment 2's range noise: every sigma x 1.25 vs the per-link terms grown (Table 2)")
        print()
        print("| range noise | UWB only | window | PF (ranges) [22] | PF |")
        print("|---|---|---|---|---|")
        for title, config in (("every sigma x 1.25: white 0.05, link 0.0875, common 0.375 m", "exp2_uniform"),
                              ("per link (paper3_exp2.yaml): white 0.05, link 0.105, common 0.30 m", "exp2")):
            print("| %s | %s | %s | %s | %s |" % (title, cell(config, "uwb"), cell(config, "window"), cell(config, "pf_baseline"),
                                                cell(config, "pf")))
        print("| paper | %s | %s | %s | %s |" % tuple(paper(PAPER_T2[k]) for k in ("uwb", "window", "pf_baseline", "pf")))

    # --- acceptance (issue 11) -------------------------------------------------------------------
    def need(ok, text):
        if not ok:
            failures.append(text)

    def within(config, stage, key, target, tol, what):
        v = stat(config, stage, key)
        side = "below" if v < target else "above"
        need(abs(v - target) <= tol * target,
             "%s %s.%s = %.3f is %s the band: required %.3f +- %d %%" % (what, stage, key, v, side, target, tol * 100))


    P, H = "position_error_m_mean", "heading_error_deg_mean"
    # A stage scored on few epochs could pass any band: every clean run must keep (nearly) all.
    for c in [c for c in configs if c.startswith("exp")]:
        for stage in ("uwb", "window", "pf", "pf_baseline"):
            need(coverage(c, stage) >= 0.95, "%s: %s valid in only %.1f %% of the epochs" % (c, stage, 100 * coverage(c, stage)))
    if "exp1a_s0.5_w30" in configs:
        c = "exp1a_s0.5_w30"
        within(c, "odometry", P, 0.79, 0.30, "exp 1-a")
        within(c, "odometry", H, 6.27, 0.30, "exp 1-a")
        within(c, "uwb", P, 0.39, 0.15, "exp 1-a")
        within(c, "uwb", H, 5.27, 0.15, "exp 1-a")
        within(c, "window", P, 0.33, 0.20, "exp 1-a")
        need(stat(c, "pf", P) <= 0.25, "exp 1-a pf position %.3f > 0.25 m" % stat(c, "pf", P))
        need(stat(c, "pf", H) <= 3.0, "exp 1-a pf heading %.2f > 3.0 deg" % stat(c, "pf", H))
    if "exp2" in configs:
        within("exp2", "uwb", P, 0.528, 0.20, "exp 2")
        within("exp2", "uwb", H, 7.41, 0.20, "exp 2")
        within("exp2", "window", P, 0.424, 0.25, "exp 2")
        within("exp2", "window", H, 5.65, 0.25, "exp 2")
        need(stat("exp2", "pf", P) <= 0.35, "exp 2 pf position %.3f > 0.35 m" % stat("exp2", "pf", P))
        need(stat("exp2", "pf", H) <= 5.4, "exp 2 pf heading %.2f > 5.4 deg" % stat("exp2", "pf", H))
        within("exp2", "odometry", P, 1.466, 0.30, "exp 2")
        within("exp2", "odometry", H, 22.076, 0.30, "exp 2")
        for key in (P, H):
            worst = max(STAGES, key=lambda s: stat("exp2", s, key))
            need(worst == "odometry", "exp 2: the worst row by %s is %s, not odometry" % (key, worst))
    # Experiment 1-b's ordering is ours (the issue has no figure for 1-b): behind the board the
    # stages still rank; the baseline bound is issue 11's for 1-a and 2 only.
    for c, what in (("exp1a_s0.5_w30", "exp 1-a"), ("exp2", "exp 2"), ("exp1b", "exp 1-b")):
        if c not in configs:
            continue
        for key in (P, H):
            u, w, p = stat(c, "uwb", key), stat(c, "window", key), stat(c, "pf", key)
            need(u > w > p, "%s ordering by %s: uwb %.3f > window %.3f > pf %.3f does not hold" % (what, key, u, w, p))
        if c != "exp1b":
            pf, base = stat(c, "pf", P), stat(c, "pf_baseline", P)
            need(pf <= 0.9 * base, "%s: pf position %.3f > 0.9 x pf_baseline %.3f" % (what, pf, base))
    if "exp1b" in configs:
        board, open_ = stat("exp1b", "uwb"), stat("exp1b_open", "uwb")
        need(board >= 1.1 * open_, "exp 1-b: the board does not hurt UWB only (%.3f m with, %.3f m without)" % (board, open_))
    if all("exp1a_s%g_w30" % s in configs for s in (0.3, 0.5, 0.7)):
        a, b, c = (stat("exp1a_s%g_w30" % s, "uwb") for s in (0.3, 0.5, 0.7))
        need(a > b > c, "UWB-only error by side 0.3 > 0.5 > 0.7 does not hold: %.3f, %.3f, %.3f" % (a, b, c))
    if all("exp1a_s0.5_w%d" % w in configs for w in (5, 30, 80)):
        w5, w30, w80 = (stat("exp1a_s0.5_w%d" % w, "window") for w in (5, 30, 80))
        need(w5 >= 0.98 * w30 and w30 >= 0.98 * w80, "window error w5 >= w30 >= w80 (within 2 %%) does not hold: %.3f, %.3f, %.3f"
             % (w5, w30, w80))
    # Issue 27: every stage's estimates against the covariance it reports, pooled over the seeds:
    # over-confident (outside its 3 sigma) in at most 1 % of the valid samples of every clean run.
    # Not met and not checked: CONSISTENCY_NOT_MET (none now).
    for c in [c for c in configs if c.startswith("exp")]:
        for stage in STAGES:
            if (c, stage) in CONSISTENCY_NOT_MET:
                continue
            over = sum(values(c, stage, "consistency", "overconfident_samples"))
            valid = sum(values(c, stage, "consistency", "valid_samples"))
            need(valid > 0 and over <= 0.01 * valid,
                 "%s: %s over-confident in %d of %d valid samples (> 1 %%)" % (c, stage, over, valid))
    if "degraded" in configs:
        print()
        print("### Degraded sensing: experiment 2, 0.25 m arrays, NLOS p = 0.05 (issue 27)")
        print()
        print("| stage | over-confident (per seed) | longest over-confident run | mean position error (t >= 20 s) |")
        print("|---|---|---|---|")
        for stage in STAGES + ["tc"]:  # and the tc stage beyond the paper (issue 28)
            fractions = values("degraded", stage, "consistency", "overconfident_fraction")
            runs = values("degraded", stage, "consistency", "longest_overconfident_s")
            print("| `%s` | %s %% | %.2f s | %.3f m |" % (stage, ", ".join("%.2f" % (100 * f) for f in fractions), max(runs),
                                                          stat("degraded", stage, P)))
            for seed, f, r in zip(seeds, fractions, runs):
                need(f <= DEGRADED_FRACTION, "degraded seed %d: %s over-confident in %.2f %% of its valid samples (> %g %%)"
                     % (seed, stage, 100 * f, 100 * DEGRADED_FRACTION))
                need(r <= DEGRADED_RUN_S, "degraded seed %d: %s over-confident for %.2f s in a row (> %g s)"
                     % (seed, stage, r, DEGRADED_RUN_S))
    if "nlos_plain" in configs:
        # Every solve, as the paper's plain least squares would publish it: our tracker flags the
        # epochs NLOS ranges spoil (suspect, not valid), which hides most of the damage from the
        # valid-only figure; the check is on all solves, the valid-only figures are in the table.
        clean, plain, huber = (all_solves[c][0] for c in ("exp1a_s0.5_w30", "nlos_plain", "nlos_huber"))
        need(huber <= 1.1 * clean, "NLOS: Huber %.3f > 1.1 x clean %.3f (every solve)" % (huber, clean))
        need(plain >= 1.2 * clean, "NLOS: plain %.3f < 1.2 x clean %.3f (every solve)" % (plain, clean))
    return report_misses(failures, args.check)


if __name__ == "__main__":
    sys.exit(main(sys.argv))

#!/usr/bin/env bash
# Issue 28, paper 3 beyond the paper: the tc stage (tightly coupled fixed-lag estimator) next to
# every other stage on experiment 2 and experiment 1-a (side 0.5 m), one run at a time, seeds 1-N;
# prints the mean over seeds +- the 95 % confidence half-width (Student t) of each stage's position
# and heading error and its over-confident fraction (docs/results/paper3.md "Beyond the paper: a
# tightly coupled estimator"). Needs a build (scripts/build.sh).
#   scripts/paper3_tc_results.sh [--seeds N] [--domain D] [--out DIR]   (defaults 10, 0, out/paper3_tc)
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
SEEDS=10; DOMAIN=0; OUT="$ROOT/out/paper3_tc"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --seeds) SEEDS="$2"; shift 2 ;;
    --domain) DOMAIN="$2"; shift 2 ;;
    --out) OUT="$2"; shift 2 ;;
    *) echo "paper3_tc_results.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
mkdir -p "$OUT"
for s in $(seq 1 "$SEEDS"); do
  for e in exp2 exp1a; do
    [[ -f "$OUT/${e}_seed$s/summary.json" ]] && continue
    "$ROOT/build/tools/robodds/robodds" run "$ROOT/sim/scenarios/paper3_$e.yaml" --no-plots --quiet --seed "$s" \
      --domain "$DOMAIN" --out "$OUT/${e}_seed$s" > "$OUT/${e}_seed$s.log" 2>&1
  done
done
python3 - "$OUT" "$SEEDS" <<'PY'
import json, math, statistics as st, sys
out, n = sys.argv[1], int(sys.argv[2])
T = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365, 8: 2.306, 9: 2.262}
for exp in ("exp2", "exp1a"):
    stages = {}
    for s in range(1, n + 1):
        summary = json.load(open("%s/%s_seed%d/summary.json" % (out, exp, s)))
        for stage, m in summary["metrics"]["stages"].items():
            d = stages.setdefault(stage, ([], [], []))
            d[0].append(m["position_error_m_mean"]); d[1].append(m["heading_error_deg_mean"])
            d[2].append(m["consistency"]["overconfident_fraction"])
    print("%s, seeds 1-%d" % (exp, n))
    for stage in ("odometry", "uwb", "window", "pf_baseline", "pf", "tc"):
        pos, head, over = stages[stage]
        ci = lambda v: T.get(n - 1, 1.96) * st.stdev(v) / math.sqrt(n) if n > 1 else float("nan")
        print("  %-12s %.3f +- %.3f m / %.2f +- %.2f deg, over-confident mean %.2f %%, max %.2f %%"
              % (stage, st.mean(pos), ci(pos), st.mean(head), ci(head), 100 * st.mean(over), 100 * max(over)))
PY

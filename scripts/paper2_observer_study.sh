#!/usr/bin/env bash
# The observer study of issue 10 (docs/results/paper2_observer_study.md): lag against noise floor
# of the super-twisting and linear range-rate observers over seeds, noise, sample rates and
# linear gains. Runs build/.../robodds-observer-study into OUT/study.csv, draws OUT/lag_vs_noise.png
# and OUT/total_vs_gain.png, and prints the markdown tables of the results page on stdout.
#   scripts/paper2_observer_study.sh [OUT] [-- STUDY_ARGS...]   (needs a build: scripts/build.sh,
#   or cmake --build build --target robodds-observer-study; default OUT out/paper2_observer_study)
# e.g. scripts/paper2_observer_study.sh /tmp/study -- --seeds 5 --duration short
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
STUDY="${STUDY:-$ROOT/build/components/range_rate_observer/study/robodds-observer-study}"
OUT="$ROOT/out/paper2_observer_study"
if (($# > 0)) && [[ $1 != -- ]]; then
  OUT="$1"
  shift
fi
[[ ${1:-} == -- ]] && shift
# numpy and matplotlib: Debian's python3-matplotlib (scripts/setup.sh); the first python3 on PATH
# may be another interpreter without them.
PYTHON="${PYTHON:-/usr/bin/python3}"
[[ -x $STUDY ]] || { echo "paper2_observer_study.sh: $STUDY not built (cmake --build build --target robodds-observer-study)" >&2; exit 2; }
mkdir -p "$OUT"
"$STUDY" "$@" --out "$OUT/study.csv"
MPLBACKEND=Agg "$PYTHON" "$ROOT/scripts/paper2_observer_study_plot.py" "$OUT/study.csv" "$OUT"

#!/usr/bin/env bash
# Regenerates paper 3's Tables 1 and 2 with 95 % confidence intervals over 10 seeds, the NLOS
# comparison and the white-only ablation (docs/results/paper3.md), two runs at a time, and checks
# issue 11's acceptance figures. Needs a build (scripts/build.sh). Extra arguments go to
# scripts/paper3_results.py (e.g. --seeds 3, --parts table2, --out DIR, --domains 5,6).
set -euo pipefail
cd "$(dirname "$0")/.."
exec python3 scripts/paper3_results.py --check "$@"

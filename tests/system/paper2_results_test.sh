#!/usr/bin/env bash
# Issue 10's acceptance table: scripts/paper2_results.py --check runs the noise-free scenario, the
# 0.5 m noise scenario over 10 seeds, the linear observer at an equal noise floor over 10 seeds and
# guidance on the linear observer (3 seeds), two runs at a time (domains $DOMAIN and $DOMAIN+1),
# and fails naming every figure that misses its bound.
source "$(dirname "$0")/../integration/lib.sh"
ROBODDS="$ROBODDS" timeout -k 5 900 python3 "$SRC/scripts/paper2_results.py" --out "$WORK/results" --seeds 10 \
  --domains "$DOMAIN,$((DOMAIN + 1))" --check >"$WORK/tables.md" 2>"$WORK/errors.txt" \
  || fail "paper-2 acceptance figures missed: $(cat "$WORK/errors.txt")"
grep -q "Acceptance figures" "$WORK/tables.md" || fail "no tables printed"
echo "ok: every paper-2 acceptance figure holds (noise-free and 10 noise seeds)"

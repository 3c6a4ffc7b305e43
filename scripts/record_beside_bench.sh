#!/bin/bash
# How much `robodds record --all` beside a lockstep run across processes slows it (issue 25,
# docs/performance.md "robodds record beside a run"): pairs of the same run with the recorder
# beside it and alone, alternated after a warm-up run; prints each pair's ticks/s (the run's own
# summary.json run.ticks_per_s) and the slowdown alone / with.
# usage: scripts/record_beside_bench.sh ROBODDS SCENARIO DURATION_S PAIRS [DOMAIN] [run options...]
set -euo pipefail
R=$1 S=$2 D=$3 P=$4 DOMAIN=${5:-225}
shift $(( $# < 5 ? $# : 5 ))
EXTRA=("$@")
WORK=$(mktemp -d /tmp/record_beside.XXXXXX)
trap 'kill -INT "${rp:-0}" 2>/dev/null || true; rm -rf "$WORK"' EXIT
tps() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['run']['ticks_per_s'])" "$1/summary.json"; }
run() { timeout 600 "$R" --log warn run "$S" --deploy processes --domain "$DOMAIN" --duration "$D" --no-plots --quiet --out "$1" "${EXTRA[@]}" >/dev/null; }
run "$WORK/warmup"
for i in $(seq "$P"); do
  "$R" --log warn record --all --out "$WORK/rec.mcap" --domain "$DOMAIN" >"$WORK/rec.log" 2>&1 &
  rp=$!
  sleep 1  # the recorder joins the domain before the run's hosts discover each other
  run "$WORK/with"
  kill -INT "$rp"
  wait "$rp"
  rp=
  run "$WORK/alone"
  python3 -c "import sys; a, b = float(sys.argv[1]), float(sys.argv[2]); print('pair %s: with %.1f alone %.1f ticks/s slowdown %.3f' % (sys.argv[3], a, b, b / a))" \
    "$(tps "$WORK/with")" "$(tps "$WORK/alone")" "$i"
done

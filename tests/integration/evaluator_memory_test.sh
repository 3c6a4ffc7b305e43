#!/usr/bin/env bash
# The evaluator's memory does not grow with the run's duration (issue #9, finding 9): plant_smoke
# with 20 robots, co-located lockstep, for 20 s and for 150 s of simulated time; the longer run's
# maximum resident set size is within 10 % of the shorter one's (before the evaluator streamed
# its CSVs it kept every sample: +0.45 MB per simulated second with 20 robots).
source "$(dirname "$0")/lib.sh"
[[ -x /usr/bin/time ]] || fail "/usr/bin/time missing (package 'time', see scripts/setup.sh)"
python3 - "$SRC/sim/scenarios/plant_smoke.yaml" "$WORK/plant_smoke20.yaml" <<'PY'
import sys
text = open(sys.argv[1]).read()
head, rest = text.split("robots:\n", 1)
robots = "".join("  - {id: %d, x: %.1f, y: %.1f, theta: %.1f}\n" % (i + 1, 5.0 * (i % 5), 5.0 * (i // 5), 0.3 * i)
                 for i in range(20))
open(sys.argv[2], "w").write(head + "robots:\n" + robots + rest[rest.index("components:"):])
PY
max_rss_kb() {  # DURATION_S: max RSS of a co-located run of the 20-robot plant_smoke, in KB
  timeout -k 5 120 /usr/bin/time -f "%M" -o "$WORK/rss.$1" "$ROBODDS" run "$WORK/plant_smoke20.yaml" --duration "$1" \
    --out "$WORK/out$1" --domain "$DOMAIN" --no-plots >"$WORK/log$1" 2>&1 || fail "run of $1 s failed: $(tail -3 "$WORK/log$1")"
  tail -1 "$WORK/rss.$1"
}
short=$(max_rss_kb 20)
long=$(max_rss_kb 150)
grep -q '"plant/state": 300020' "$WORK/out150/summary.json" || fail "the 150 s run did not record 20 x 15001 states"
python3 -c "import sys; s, l = int(sys.argv[1]), int(sys.argv[2]); sys.exit(0 if l < 1.1 * s else 1)" "$short" "$long" \
  || fail "max RSS grows with the duration: $short KB for 20 s, $long KB for 150 s (limit +10 %)"
echo "ok: max RSS $short KB for 20 s, $long KB for 150 s"

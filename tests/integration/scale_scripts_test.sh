#!/usr/bin/env bash
# The scaling benchmarks of issue 13 (docs/performance.md, "Cost per robot-tick") keep working:
# scripts/scale_bench.py prints one table row per robot count with ticks/s and us per robot-tick
# for each deployment, draws its plot, and its generated scenario has N robots;
# scripts/realtime_scale.py reports missed steps per host of a real-time run; both
# refuse a malformed --robots. Tiny runs: this checks the tools, not the figures.
source "$(dirname "$0")/lib.sh"
PY=/usr/bin/python3  # Debian's, with python3-yaml and python3-matplotlib (scripts/setup.sh)
"$PY" "$SRC/scripts/scale_bench.py" --robodds "$ROBODDS" --robots 2,5 --deploy colocated,processes --duration 0.5 --repeat 1 \
  --lockstep-window 2 \
  --domain "$DOMAIN" --out "$WORK/scale" --plot "$WORK/scale.png" >"$WORK/table.md" 2>"$WORK/scale.log" ||
  fail "scale_bench.py failed: $(tail -5 "$WORK/scale.log")"
cat "$WORK/table.md"
for n in 2 5; do
  grep -qE "^\| $n \| [0-9,]+ \| [0-9.]+ \| [0-9]+ \| [0-9,]+ \| [0-9.]+ \| [0-9]+ \|$" "$WORK/table.md" ||
    fail "no row for $n robots with both deployments in: $(cat "$WORK/table.md")"
done
[[ -s "$WORK/scale.png" ]] || fail "no plot written"
robots=$("$PY" -c "import yaml,sys; print(len(yaml.safe_load(open(sys.argv[1]))['robots']))" "$WORK/scale/plant_smoke_5.yaml")
[[ $robots -eq 5 ]] || fail "plant_smoke_5.yaml has $robots robots"

"$PY" "$SRC/scripts/realtime_scale.py" --robodds "$ROBODDS" --robots 2 --deploy colocated --duration 1 --domain "$DOMAIN" \
  >"$WORK/rt.md" 2>"$WORK/rt.log" || fail "realtime_scale.py failed: $(tail -5 "$WORK/rt.log")"
cat "$WORK/rt.md"
grep -qE "^\| 2 \| colocated \| 0 \| colocated [0-9]+ \| [0-9]+ \| run \(coordinator\) [0-9]+ \|$" "$WORK/rt.md" ||
  fail "no real-time row for 2 robots: $(cat "$WORK/rt.md")"

out=$("$PY" "$SRC/scripts/scale_bench.py" --robodds "$ROBODDS" --lockstep-window 0 2>&1) && fail "scale_bench.py accepted --lockstep-window 0"
grep -q "lockstep-window must be >= 1" <<<"$out" || fail "scale_bench.py: unclear error for --lockstep-window 0: $out"
for script in scale_bench.py realtime_scale.py; do
  out=$("$PY" "$SRC/scripts/$script" --robodds "$ROBODDS" --robots 2,x 2>&1) && fail "$script accepted --robots 2,x"
  grep -q "not a comma-separated list of integers" <<<"$out" || fail "$script: unclear error for --robots 2,x: $out"
done
echo "ok: scaling scripts"

#!/usr/bin/env bash
# 70 robots (plant_smoke on a grid, the scenario scripts/scale_bench.py writes): across processes
# each robot-keyed lockstep topic is published by 3 DataWriters, one per 32 robots (runtime/
# instance_spread.hpp), and the outputs stay byte-identical to the co-located run, in strict
# lockstep and with a pipelined window. The sim host must say it spread plant/state (a run with
# one writer would pass the comparison and test nothing), and some process must have sent its
# step's writes in send batches.
source "$(dirname "$0")/lib.sh"
PY=/usr/bin/python3  # Debian's, with python3-yaml (scripts/setup.sh)
SCENARIO="$WORK/plant_smoke_70.yaml"
"$PY" - "$SRC/scripts" "$SCENARIO" <<'PY' || fail "could not write the 70-robot scenario"
import sys, yaml
sys.path.insert(0, sys.argv[1])
from scale_bench import scenario_with_robots
with open(sys.argv[2], "w") as f:
    yaml.safe_dump(scenario_with_robots(70), f)
PY
timeout -k 5 300 "$ROBODDS" run "$SCENARIO" --duration 3 --out "$WORK/colocated" --domain "$DOMAIN" --no-plots >/dev/null
for window in 1 8; do
  timeout -k 5 300 "$ROBODDS" --log debug run "$SCENARIO" --duration 3 --out "$WORK/processes_$window" --domain "$DOMAIN" \
    --deploy processes --lockstep-window "$window" --no-plots >/dev/null 2>"$WORK/processes_$window.log" ||
    fail "window $window: $(grep -v '\[debug\]' "$WORK/processes_$window.log" | tail -5)"
  ! grep -q "sim/step_done: [0-9]* writers" "$WORK/processes_$window.log" ||
    fail "window $window: sim/step_done (keyed by host, not by robot) was spread"
  grep -q "plant/state: 3 writers (profile 'lockstep', 70 robots" "$WORK/processes_$window.log" ||
    fail "window $window: the sim host did not spread plant/state over 3 writers: $(grep -c . "$WORK/processes_$window.log") log lines"
  # The lockstep hosts' writes of a step leave in send batches (runtime/dds/send_batch.hpp).
  grep -q "send batches so far in this process: [1-9][0-9]* sent" "$WORK/processes_$window.log" ||
    fail "window $window: no process sent a batch of RTPS messages"
  same_outputs "$WORK/colocated" "$WORK/processes_$window"
done
echo "ok: 70 robots, plant/state on 3 writers, $N_CSV CSV files and the metrics identical co-located and across processes (window 1 and 8)"

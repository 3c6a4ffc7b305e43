#!/usr/bin/env bash
# Across processes a lockstep producer may write window + p + d - 1 samples of an instance before a
# consumer due every p steps, reading d steps late, must have them (its host acknowledges the steps
# in between, and its reader may match late at the start). A writer history shorter than that can
# drop a sample that reader never got: the run would differ silently. Each host checks the bound at
# start-up against the `lockstep` profile's writer depth (check_history_bound): with a QoS file whose
# lockstep writers keep 16 samples, plant_smoke's position sensor (10 Hz at 100 Hz: p 10, d 0) bounds
# the window: 7 runs (7 + 10 - 1 = 16), 8 is refused, naming component, topic and figures.
source "$(dirname "$0")/lib.sh"
S="$SRC/sim/scenarios/plant_smoke.yaml"
"/usr/bin/python3" - "$SRC/deploy/qos/robodds_qos.xml" "$WORK/depth16.xml" <<'PY'
import re, sys
s = open(sys.argv[1]).read()
i = s.index('<data_writer profile_name="lockstep">'); j = s.index('</data_writer>', i)
seg, n = re.subn(r'<depth>\d+</depth>', '<depth>16</depth>', s[i:j])
seg, m = re.subn(r'<max_samples_per_instance>\d+<', '<max_samples_per_instance>16<', seg)
assert n == 1 and m == 1, "lockstep writer profile not found as expected"
open(sys.argv[2], 'w').write(s[:i] + seg + s[j:])
PY
run() {  # run WINDOW: plant_smoke across processes, 1 s, with the depth-16 QoS file
  timeout -k 5 120 "$ROBODDS" run "$S" --deploy processes --duration 1 --lockstep-window "$1" --qos "$WORK/depth16.xml" \
    --domain "$DOMAIN" --out "$WORK/w$1" --no-plots >"$WORK/w$1.log" 2>&1
}
run 7 || fail "window 7 with depth 16 should run: $(tail -5 "$WORK/w7.log")"
rc=0; run 8 || rc=$?
[[ $rc -ne 0 ]] || fail "window 8 with depth 16 ran; expected the history bound to refuse it"
grep -q "component 'position_sensor' reads plant/state 0 step(s) late every 10 step(s): with --lockstep-window 8 its producers may write 17 samples of an instance before it reads them, more than the 'lockstep' QoS profile's writer history keeps (KEEP_LAST 16)" "$WORK/w8.log" ||
  fail "no clear history-bound error: $(tail -5 "$WORK/w8.log")"
echo "ok: window 7 runs, window 8 refused: $(grep -m1 -o "lockstep: component 'position_sensor'.*" "$WORK/w8.log" | cut -c1-120)..."

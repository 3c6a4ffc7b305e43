#!/usr/bin/env bash
# Across processes a lockstep producer may write window + c + d - 1 samples of an instance before a
# consumer reading d steps late must have them, c the steps between two steps at which the
# consumer's host waited for its inputs (its due steps, every p). A writer history shorter than that
# could drop a sample that reader never got (a reader that matched late at the start, a repaired
# packet). Each host keeps the bound at start-up against the `lockstep` profile's writer depth
# (history_checkpoints.hpp): where the due steps are too far apart it also waits for the inputs
# every c steps without running the component, and only when no wait can help (window + d > depth)
# it refuses to start, naming component, topic and figures. Checked on plant_smoke (position
# sensor 10 Hz at 100 Hz: p 10, d 0):
# 1. a QoS file whose lockstep writers keep 16 samples: window 7 (7 + 10 - 1 = 16) and window 8
#    (waits every 9 steps) both give the CSVs of window 1; window 17 is refused;
# 2. the shipped QoS (48): the position sensor at 1 Hz (p 100, refused before) runs across
#    processes and gives the co-located run's CSVs byte for byte.
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
run() {  # run NAME [options...]: plant_smoke, 2 s
  local name="$1"; shift
  timeout -k 5 120 "$ROBODDS" --log info run "$S" --duration 2 --domain "$DOMAIN" --out "$WORK/$name" --no-plots "$@" \
    >"$WORK/$name.log" 2>&1
}
same_csvs() {  # same_csvs A B
  local f n=0
  for f in "$WORK/$1"/*.csv; do
    cmp -s "$f" "$WORK/$2/$(basename "$f")" || fail "$1 and $2 differ in $(basename "$f")"
    n=$((n + 1))
  done
  [[ $n -gt 0 ]] || fail "$1 wrote no CSV"
}
for w in 1 7 8; do
  run "w$w" --deploy processes --lockstep-window "$w" --qos "$WORK/depth16.xml" || fail "window $w with depth 16 should run: $(tail -5 "$WORK/w$w.log")"
done
grep -q "component 'position_sensor' runs every 10 steps; its host also waits for its inputs every 9 steps" "$WORK/w8.log" ||
  fail "window 8 with depth 16: no history checkpoint announced: $(grep -m3 lockstep "$WORK/w8.log")"
! grep -q "also waits for its inputs" "$WORK/w7.log" || fail "window 7 with depth 16 needs no extra wait, yet one was announced"
same_csvs w7 w1
same_csvs w8 w1
rc=0; run w17 --deploy processes --lockstep-window 17 --qos "$WORK/depth16.xml" || rc=$?
[[ $rc -ne 0 ]] || fail "window 17 with depth 16 ran; expected the history bound to refuse it"
# Every host refuses; which one ends the run first varies (the sensors' or the evaluator's).
grep -qE "component '[a-z_]+' reads [a-z_/]+ [0-9]+ step\(s\) late: with --lockstep-window 17 its producers may write 1[7-9] samples of an instance before it reads them even if its host waits for them at every step, more than the 'lockstep' QoS profile's writer history keeps \(KEEP_LAST 16\)" "$WORK/w17.log" ||
  fail "no clear history-bound error: $(tail -5 "$WORK/w17.log")"
echo "ok: depth 16: windows 7 and 8 (waits every 9 steps) give window 1's CSVs, window 17 refused"
run slow_colocated --set position_sensor.rate_hz=1 || fail "1 Hz position sensor co-located: $(tail -5 "$WORK/slow_colocated.log")"
run slow_processes --deploy processes --set position_sensor.rate_hz=1 ||
  fail "1 Hz position sensor across processes: $(tail -5 "$WORK/slow_processes.log")"
grep -q "component 'position_sensor' runs every 100 steps; its host also waits for its inputs every 48 steps" "$WORK/slow_processes.log" ||
  fail "1 Hz sensor: no history checkpoint announced: $(grep -m3 lockstep "$WORK/slow_processes.log")"
same_csvs slow_processes slow_colocated
[[ $(wc -l <"$WORK/slow_processes/sensor_position.csv") -gt 3 ]] || fail "the 1 Hz sensor wrote no fixes"
echo "ok: a 1 Hz position sensor (p 100 > 48) runs across processes, its host waiting every 48 steps, and gives the co-located CSVs"

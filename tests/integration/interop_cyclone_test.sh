#!/usr/bin/env bash
# Interop with another DDS implementation (docs/interop.md): a real-time robodds run (a plant and
# an evaluator, no robodds commander) whose commands come from Cyclone DDS. tests/interop/
# cyclone_probe reads plant/state from the run and writes hostile plant/cmd samples (NaN, +-Inf,
# 1e300, a mode outside the enum, stamps INT64_MAX and INT64_MIN), then valid commands, then one
# command stamped INT64_MAX, then stops writing. Checks: the run exits 0; the valid Cyclone commands drive the plant (v = 0.2 recorded);
# every plant/state value (CSV and as read by Cyclone) is finite and within a box; the plant stops
# (v = omega = 0) within its command_timeout_s after the last Cyclone command; the non-finite
# samples are refused (plant log, evaluator's rejected_samples); the plant's counters in summary.json
# ("inputs"."plant"."plant/cmd") are exactly what the probe sent, per rejection reason.
# Args: ROBODDS SRC DOMAIN PROBE (PROBE "none": Cyclone DDS was not found, the test is skipped).
source "$(dirname "$0")/lib.sh"
PROBE="${4:-none}"
if [[ "$PROBE" == none || ! -x "$PROBE" ]]; then
  echo "SKIP: Cyclone DDS not found when the build was configured (Debian cyclonedds-dev and cyclonedds-tools;" \
    "scripts/setup.sh installs them), so tests/interop/cyclone_probe was not built"
  exit 77
fi

SCENARIO="$SRC/tests/interop/foreign_commander.yaml"  # plant (limits 1 m/s, 2 rad/s) + evaluator, 9 s
TIMEOUT_S=$(sed -n 's/.*command_timeout_s: \([0-9.]*\).*/\1/p' "$SCENARIO")
[[ -n "$TIMEOUT_S" ]] || fail "no command_timeout_s in $SCENARIO"
MARGIN_S=0.15   # plant period (10 ms) + delivery and scheduling slack on a loaded 2-core machine

timeout -k 5 60 "$ROBODDS" run "$SCENARIO" --realtime $(rt_priority_flag) --domain "$DOMAIN" --out "$WORK/out" --no-plots \
  >"$WORK/run.log" 2>&1 &
run_pid=$!
cleanup_pids+=("$run_pid")
timeout -k 5 30 "$PROBE" read-state --domain "$DOMAIN" --seconds 7 --robot 1 >"$WORK/state.txt" 2>"$WORK/reader.log" &
reader_pid=$!
cleanup_pids+=("$reader_pid")
timeout -k 5 40 "$PROBE" write-cmd --domain "$DOMAIN" --robot 1 --pattern hostile --linger 1 >"$WORK/cmd.txt" 2>"$WORK/writer.log" \
  || fail "cyclone_probe write-cmd failed: $(cat "$WORK/writer.log")"
wait "$reader_pid" || fail "cyclone_probe read-state failed: $(cat "$WORK/reader.log")"
rc=0
wait "$run_pid" || rc=$?
[[ $rc -eq 0 ]] || fail "robodds run exited $rc: $(cat "$WORK/run.log")"
echo "ok: robodds run exited 0; Cyclone wrote $(grep -c '^cmd ' "$WORK/cmd.txt") commands, read $(grep -c '^state ' "$WORK/state.txt") states"

grep -qE "\[warn\] plant: rejected a sample on plant/cmd from 'cyclone_probe' .*\(robot_id=1, step 0\): field 'v' is not finite" "$WORK/run.log" \
  || fail "the plant did not report the Cyclone NaN command: $(cat "$WORK/run.log")"
echo "ok: plant refused the non-finite Cyclone command (log)"

python3 - "$WORK/out/plant_state.csv" "$WORK/state.txt" "$WORK/cmd.txt" "$WORK/out/summary.json" "$TIMEOUT_S" "$MARGIN_S" <<'PY' || fail "checks on the run's outputs failed"
import csv, json, math, sys
state_csv, cyclone_states, cmd_txt, summary_json = sys.argv[1:5]
timeout_s, margin_s = float(sys.argv[5]), float(sys.argv[6])
BOX = 100.0  # m: 1 m/s for 9 s cannot leave it; 1e300 would
def check(ok, what):
    if not ok:
        print("FAIL:", what, file=sys.stderr)
        sys.exit(1)

rows = [r for r in csv.DictReader(open(state_csv)) if r["robot_id"] == "1"]
check(len(rows) > 500, f"plant_state.csv has {len(rows)} rows of robot 1, expected > 500 (9 s at 100 Hz)")
for r in rows:
    for field in ("x", "y", "theta", "v", "omega"):
        value = float(r[field])
        check(math.isfinite(value), f"plant_state.csv: {field}={r[field]} at stamp {r['header.stamp_ns']}")
    check(abs(float(r["x"])) < BOX and abs(float(r["y"])) < BOX, f"plant_state.csv: position ({r['x']}, {r['y']}) outside +-{BOX} m")
check(any(float(r["v"]) == 0.2 for r in rows), "the valid Cyclone commands (v = 0.2) never drove the plant")

n = 0
for line in open(cyclone_states):
    if not line.startswith("state "):
        continue
    fields = dict(kv.split("=") for kv in line.split()[1:])
    for field in ("x", "y", "theta", "v", "omega"):
        check(math.isfinite(float(fields[field])), f"Cyclone read {field}={fields[field]}")
    check(abs(float(fields["x"])) < BOX and abs(float(fields["y"])) < BOX, f"Cyclone read position ({fields['x']}, {fields['y']})")
    n += 1
check(n > 100, f"Cyclone read {n} plant/state samples, expected > 100")

last_write_ns = int(next(l for l in open(cmd_txt) if l.startswith("last_write_ns=")).split("=")[1])
after = [r for r in rows if int(r["header.stamp_ns"]) > last_write_ns]
check(len(after) > 100, f"only {len(after)} plant states after the last Cyclone command: the run ended too early to see the stop")
moving = [r for r in after if float(r["v"]) != 0.0 or float(r["omega"]) != 0.0]
stop_s = (int(moving[-1]["header.stamp_ns"]) - last_write_ns) * 1e-9 if moving else 0.0
check(stop_s <= timeout_s + margin_s,
      f"the plant still moved {stop_s:.3f} s after the last Cyclone command (limit {timeout_s} s + {margin_s} s)")
print(f"ok: plant_state finite and within +-{BOX} m ({len(rows)} rows, {n} read by Cyclone); "
      f"stopped {stop_s:.3f} s after the last Cyclone command (command_timeout_s {timeout_s})")

summary = json.load(open(summary_json))
rejected = summary["metrics"]["rejected_samples"]["plant/cmd"]
check(rejected >= 4, f"evaluator rejected {rejected} plant/cmd samples, expected >= 4 (NaN v, +Inf omega, -Inf v, NaN v_left)")
print(f"ok: evaluator refused {rejected} hostile Cyclone commands (>= 4 non-finite)")

# The plant's own counters (summary.json "inputs"): exactly what the probe sent, per reason. The
# probe writes RELIABLE with a history deeper than its pattern, 50 ms apart, after discovery
# settled (the log check above already requires the very first sample), and the plant's reader
# takes each sample as it arrives: every sample is delivered and counted once.
sent = {}
for line in open(cmd_txt):
    if line.startswith("cmd "):
        label = line.split()[1]
        sent[label] = sent.get(label, 0) + 1
expected = {
    "non_finite": sum(sent.get(k, 0) for k in ("nan_v", "inf_omega", "minus_inf_v", "nan_wheel")),
    "absurd_magnitude": sum(sent.get(k, 0) for k in ("absurd_v", "absurd_omega", "absurd_wheels")),
    "bad_enum": sent.get("bad_enum", 0),
    "stamp_in_future": sent.get("stamp_future", 0) + sent.get("stamp_future_last", 0),
    "negative_stamp": sent.get("stamp_negative", 0),
}
check(expected == {"non_finite": 4, "absurd_magnitude": 3, "bad_enum": 1, "stamp_in_future": 2, "negative_stamp": 1},
      f"the probe's hostile pattern is not what this test expects: {sent}")
last_label = [l for l in open(cmd_txt) if l.startswith("cmd ")][-1].split()[1]
check(last_label == "stamp_future_last", f"the probe's last command is {last_label}, not the INT64_MAX-stamped one")
counts = summary["inputs"]["plant"]["plant/cmd"]
check(counts["rejected"] == expected,
      f"plant rejected {counts['rejected']} on plant/cmd, expected exactly {expected} (what the probe sent)")
check(counts["accepted"] == sent.get("valid", 0),
      f"plant accepted {counts['accepted']} plant/cmd samples, expected {sent.get('valid', 0)} (the valid commands)")
print(f"ok: plant counted exactly what Cyclone sent: accepted {counts['accepted']}, rejected {counts['rejected']}")
PY
echo "ok: interop with Cyclone DDS"

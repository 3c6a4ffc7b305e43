#!/usr/bin/env bash
# `robodds coordinate` (issue 26, finding 6): a robot made of component executables runs in
# lockstep without a scenario file.
#   1. plant_smoke's four components as their executables (robodds-open-loop-commander, -plant,
#      -position-sensor, -evaluator; instance names, seed, robots and the evaluator's keys on
#      their command lines) and `robodds coordinate --members control,sim,sensing,evaluation`:
#      the coordinator reports the 51 steps of 0.5 s and exits 0, every member exits 0, and the
#      evaluator's CSVs and metrics are byte-identical to `robodds run plant_smoke` co-located;
#   2. a coordinator whose members are not all started names every missing one (and not the one
#      that came) at --start-timeout, exit 1;
#   3. a lone executable without a coordinator says at start that it waits for one and, after
#      --start-timeout, which coordinator (`robodds coordinate --members ...`) and that --realtime
#      needs none;
#   4. bad --members / --step / --duration: one line each naming the option, exit 2;
#   5. a member killed during a run is named by the coordinator (its participant's lease), exit 1.
# Domains DOMAIN (1), DOMAIN+1 (the reference run, then 3), DOMAIN+2 (2, then 5, beside 1).
source "$(dirname "$0")/lib.sh"
BIN="$(dirname "$ROBODDS")/../../bin"
S="$SRC/sim/scenarios/plant_smoke.yaml"
D1=$((DOMAIN + 1))
D2=$((DOMAIN + 2))

# The reference: plant_smoke co-located (its own domain, beside the runs below).
"$ROBODDS" --log warn run "$S" --duration 0.5 --domain "$D1" --out "$WORK/reference" --no-plots >"$WORK/reference.log" 2>&1 &
ref_pid=$!
cleanup_pids+=("$ref_pid")

# 1. plant_smoke from component executables: the same instance names, seed, robots (poses) and
#    evaluator keys as the scenario, one member each.
printf 'topics: [plant/state, plant/cmd, sensor/position]\nmetrics_after_s: 0.0\n' >"$WORK/evaluator.yaml"
C=(--seed 42 --domain "$DOMAIN" --start-timeout 20 --log warn)
start_member() {  # EXECUTABLE NAME MEMBER ARGS...
  local exe="$1" name="$2" member="$3"
  shift 3
  "$BIN/$exe" --name "$name" --member "$member" "${C[@]}" "$@" >"$WORK/member.$member.log" 2>&1 &
  member_pids+=("$!")
  cleanup_pids+=("$!")
}
member_pids=()
start_member robodds-open-loop-commander commander control --robot 1 --robot 2 --robot 3
start_member robodds-plant plant sim --robot 1:0,0,0 --robot 2:5,0,1.5707963267948966 --robot 3:0,5,3.141592653589793
start_member robodds-position-sensor position_sensor sensing --robot 1 --robot 2 --robot 3
start_member robodds-evaluator evaluator evaluation --robot 1 --robot 2 --robot 3 --params "$WORK/evaluator.yaml" \
  --out "$WORK/standalone"
timeout -k 5 60 "$ROBODDS" coordinate --members control,sim,sensing,evaluation --step 0.01 --duration 0.5 \
  --domain "$DOMAIN" --start-timeout 20 >"$WORK/coordinator.log" 2>&1 &
coordinator_pid=$!
cleanup_pids+=("$coordinator_pid")

# Meanwhile, on domain DOMAIN+2:
# 2. Members control (started), ghost and phantom (never started): both named, control not.
"$BIN/robodds-open-loop-commander" --log warn --name commander --member control --robot 1 --domain "$D2" --start-timeout 20 \
  >"$WORK/lonely_commander.log" 2>&1 &
lonely_pid=$!
cleanup_pids+=("$lonely_pid")
missing_rc=0
timeout -k 5 60 "$ROBODDS" coordinate --members control,ghost,phantom --duration 1 --start-timeout 3 --domain "$D2" \
  >"$WORK/missing.log" 2>&1 || missing_rc=$?
kill "$lonely_pid" 2>/dev/null || true
[[ $missing_rc -eq 1 ]] || fail "coordinate with missing members exited $missing_rc: $(cat "$WORK/missing.log")"
grep -q "no acknowledgement of step 0 within 3.0 s from groups 'ghost' (nothing received yet), 'phantom' (nothing received yet) on" \
  "$WORK/missing.log" || fail "the missing members are not both named: $(cat "$WORK/missing.log")"
grep -q "'control'" <(grep "no acknowledgement" "$WORK/missing.log") && fail "control came but is named missing: $(cat "$WORK/missing.log")"
echo "ok: the coordinator names every missing member"

# 5. A member that dies during the run (SIGKILL, once 10 % of the steps are done) is named by the
#    coordinator within its lease (1.5 s) and grace (0.4 s): exit 1. Run id 2: not the run above.
K=(--robot 1 --domain "$D2" --run-id 2 --start-timeout 20 --log warn)
"$BIN/robodds-open-loop-commander" --name commander --member control "${K[@]}" >"$WORK/death.control.log" 2>&1 &
cleanup_pids+=("$!")
"$BIN/robodds-plant" --name plant --member sim "${K[@]}" >"$WORK/death.sim.log" 2>&1 &
victim=$!
cleanup_pids+=("$victim")
"$ROBODDS" coordinate --members control,sim --duration 300 --run-id 2 --domain "$D2" --start-timeout 20 >"$WORK/death.log" 2>&1 &
death_pid=$!
cleanup_pids+=("$death_pid")
for _ in $(seq 1 400); do  # at most 20 s for the first 10 % (3,000 steps)
  grep -q "(10 %)" "$WORK/death.log" && break
  kill -0 "$death_pid" 2>/dev/null || break
  sleep 0.05
done
grep -q "(10 %)" "$WORK/death.log" || fail "the run to kill a member of did not reach 10 %: $(cat "$WORK/death.log")"
kill -KILL "$victim"
killed_at=$(date +%s.%N)
wait "$victim" 2>/dev/null || true  # reaped quietly (bash reports "Killed" otherwise)
death_rc=0
timeout -k 5 15 tail --pid="$death_pid" -f /dev/null || fail "the coordinator did not end within 15 s of the kill"
wait "$death_pid" || death_rc=$?
took=$(python3 -c "import sys; print(round($(date +%s.%N) - $killed_at, 2))")
[[ $death_rc -eq 1 ]] || fail "coordinate with a killed member exited $death_rc: $(cat "$WORK/death.log")"
grep -qE "lockstep: group 'sim' lost at step [0-9]+: its participant 'robodds-sim' dropped" "$WORK/death.log" ||
  fail "the killed member is not named: $(cat "$WORK/death.log")"
echo "ok: the killed member 'sim' is named; the coordinator exited $took s after the kill"

rc=0
wait "$coordinator_pid" || rc=$?
[[ $rc -eq 0 ]] || fail "robodds coordinate exited $rc: $(cat "$WORK/coordinator.log") $(tail -qn 2 "$WORK"/member.*.log)"
for pid in "${member_pids[@]}"; do
  wait "$pid" || fail "a member exited $?: $(tail -qn 2 "$WORK"/member.*.log)"
done
grep -q "run 1 of 'coordinate' completed: 51 steps" "$WORK/coordinator.log" ||
  fail "the coordinator did not report 51 steps: $(cat "$WORK/coordinator.log")"
wait "$ref_pid" || fail "the reference run failed: $(cat "$WORK/reference.log")"
python3 - "$WORK/reference/summary.json" "$WORK/standalone/summary.json" <<'PY' || fail "the evaluator's summary differs"
import json, sys
ref, alone = (json.load(open(path)) for path in sys.argv[1:])
assert alone["status"] == "completed" and alone["steps"] == 51, alone
for key in ("run", "hosts", "inputs", "scenario", "description"):  # deployment figures; the scenario's name and description (the evaluator's type alone)
    ref.pop(key, None)
    alone.pop(key, None)
if ref != alone:
    sys.exit("reference: %s\nstandalone: %s" % (json.dumps(ref, sort_keys=True)[:1500], json.dumps(alone, sort_keys=True)[:1500]))
PY
n=0
for f in "$WORK/reference"/*.csv; do
  cmp "$f" "$WORK/standalone/$(basename "$f")" || fail "$(basename "$f") differs from robodds run's"
  n=$((n + 1))
done
[[ $n -ge 3 ]] || fail "the reference wrote $n CSVs"
echo "ok: 4 component executables + robodds coordinate ran plant_smoke's 51 steps, byte-identical to robodds run ($n CSVs, metrics)"

# 3. A lone executable: no coordinator on its domain. It says at once what it waits for, and when
#    the first tick's wait runs out, which coordinator and that --realtime needs none.
lone_rc=0
timeout -k 5 60 "$BIN/robodds-plant" --robot 1 --domain "$D1" --start-timeout 1 >"$WORK/lone.log" 2>&1 || lone_rc=$?
[[ $lone_rc -eq 1 ]] || fail "a lone plant in lockstep exited $lone_rc: $(cat "$WORK/lone.log")"
grep -qF "[info] plant: run 1 of 'plant': components plant (lockstep: waiting for the ticks of a coordinator of member 'plant', e.g. \`robodds coordinate --members plant,... --duration S\`; --realtime needs none)" \
  "$WORK/lone.log" || fail "the lone plant does not say at start what it waits for: $(cat "$WORK/lone.log")"
grep -qF "error: plant: no tick on sim/clock for 1.0 s after start: is a lockstep coordinator alive on domain $D1 with run id 1 and waiting for member 'plant' (\`robodds coordinate --members plant,... --step 0.01 --duration S\`, or \`robodds run\`)? To run this component without one, on the wall clock, give --realtime" \
  "$WORK/lone.log" || fail "the lone plant's timeout does not name the coordinator and --realtime: $(cat "$WORK/lone.log")"
[[ $(grep -c "error:" "$WORK/lone.log") -eq 1 ]] || fail "expected one error line: $(cat "$WORK/lone.log")"
echo "ok: a lone executable says what it waits for, and at its timeout which coordinator and --realtime"

# 4. Bad input names the option.
expect_error 2 "--members 'sim,sim': 'sim' is given twice" -- "$ROBODDS" coordinate --members sim,sim --duration 1 --domain "$D1"
expect_error 2 "--members 'sim,,x': member 2 is empty" -- "$ROBODDS" coordinate --members sim,,x --duration 1 --domain "$D1"
expect_error 2 "--members: give the members to wait for" -- "$ROBODDS" coordinate --duration 1 --domain "$D1"
expect_error 2 "--duration is required" -- "$ROBODDS" coordinate --members sim --domain "$D1"
expect_error 2 "--step.*positive, finite" -- "$ROBODDS" coordinate --members sim --step nan --duration 1 --domain "$D1"
expect_error 2 "--duration.*positive, finite" -- "$ROBODDS" coordinate --members sim --duration 0 --domain "$D1"

#!/usr/bin/env bash
# `robodds topics` lists the live topics with type and QoS; `robodds echo` prints samples readably
# (enums by name), filtered by key (--robot, --key), one field (--field), as JSON or CSV.
source "$(dirname "$0")/lib.sh"
# await_topics PATTERN...: `robodds topics` (2 s of discovery each) until every PATTERN matches a
# line of one listing, within 60 s (a start-up on a loaded machine can take several seconds);
# the last listing in $topics.
await_topics() {
  local deadline=$((SECONDS + 60)) pattern missing
  while :; do
    topics="$(timeout -k 2 20 "$ROBODDS" topics --duration 2 --domain "$DOMAIN")" || fail "robodds topics failed: $topics"
    missing=""
    for pattern in "$@"; do
      grep -qE "$pattern" <<<"$topics" || missing="$pattern"
    done
    [[ -z $missing ]] && return 0
    (( SECONDS < deadline )) || fail "no listing within 60 s matched '$missing': $topics"
  done
}
"$ROBODDS" host --scenario "$SRC/sim/scenarios/plant_smoke.yaml" --components plant,commander,position_sensor --realtime $(rt_priority_flag) \
  --duration 30 --domain "$DOMAIN" >"$WORK/host.log" 2>&1 &
cleanup_pids+=("$!")
await_topics "^plant/state " "^sensor/position " "^plant/cmd +robodds::idl::VelocityCommand +1 +1 "
echo "$topics"
grep -qE "^plant/state +robodds::idl::RobotState +1 .*RELIABLE/VOLATILE" <<<"$topics" || fail "plant/state missing or wrong QoS"
grep -qE "^sensor/position +robodds::idl::PositionMeasurement +1 .*BEST_EFFORT/VOLATILE" <<<"$topics" || fail "sensor/position missing"
grep -qE "^plant/cmd +robodds::idl::VelocityCommand +1 +1 " <<<"$topics" || fail "plant/cmd should have a writer and a reader"
out="$(timeout -k 2 20 "$ROBODDS" echo plant/state --count 3 --timeout 5 --domain "$DOMAIN")" || fail "echo failed: $out"
[[ $(grep -c "^--- plant/state (robot_id=" <<<"$out") -eq 3 ]] || fail "expected 3 samples: $out"
grep -qE "^  x: -?[0-9]" <<<"$out" || fail "fields not printed: $out"
expect_error 1 "no sample on sensor/uwb within 1 s on DDS domain $DOMAIN \(.robodds topics --domain $DOMAIN. lists the topics" -- \
  "$ROBODDS" echo sensor/uwb --count 1 --timeout 1 --domain "$DOMAIN"
echo "ok: topics and echo"

# Issue 26: the commander's commands of robot 2 only, the mode enum by its IDL name.
out="$(timeout -k 2 20 "$ROBODDS" echo plant/cmd --robot 2 --count 3 --timeout 5 --domain "$DOMAIN")" || fail "echo --robot failed: $out"
[[ $(grep -c "^--- plant/cmd (robot_id=2)" <<<"$out") -eq 3 && $(grep -c "^--- " <<<"$out") -eq 3 ]] || fail "expected 3 samples of robot 2: $out"
[[ $(grep -c "^  mode: VELOCITY$" <<<"$out") -eq 3 ]] || fail "enum not printed by name: $out"
# --json: one object per line, nested header, only robot 3.
out="$(timeout -k 2 20 "$ROBODDS" echo plant/state --robot 3 --json --count 2 --timeout 5 --domain "$DOMAIN")" || fail "echo --json failed: $out"
python3 -c '
import json, sys
rows = [json.loads(line) for line in sys.stdin.read().splitlines()]
assert len(rows) == 2 and all(r["robot_id"] == 3 and r["header"]["step"] > 0 and isinstance(r["x"], float) for r in rows), rows
' <<<"$out" || fail "echo --json: not 2 JSON objects of robot 3: $out"
# --csv: a header, then rows with the enum by name; --field: the bare value.
out="$(timeout -k 2 20 "$ROBODDS" echo plant/cmd --csv --count 2 --timeout 5 --domain "$DOMAIN")" || fail "echo --csv failed: $out"
[[ $(head -1 <<<"$out") == "robot_id,header.step,header.next_step,header.stamp_ns,mode,v,omega,v_left,v_right" ]] || fail "csv header: $out"
[[ $(grep -cE "^[123],[0-9]+,[0-9]+,[0-9]+,VELOCITY," <<<"$out") -eq 2 ]] || fail "csv rows: $out"
out="$(timeout -k 2 20 "$ROBODDS" echo plant/state --robot 1 --field x --count 2 --timeout 5 --domain "$DOMAIN")" || fail "echo --field failed: $out"
[[ $(grep -cE "^-?[0-9][0-9.e+-]*$" <<<"$out") -eq 2 ]] || fail "expected 2 bare values of x: $out"
expect_error 1 "no sample of robot_id=9 on plant/state within 1 s on DDS domain $DOMAIN" -- \
  "$ROBODDS" echo plant/state --robot 9 --count 1 --timeout 1 --domain "$DOMAIN"
expect_error 2 "--field 'xx': no such field; did you mean 'x'\?" -- "$ROBODDS" echo plant/state --field xx --domain "$DOMAIN"
expect_error 2 "--key 'robotid=1': 'robotid' is no key of the topic; did you mean 'robot_id'\?" -- \
  "$ROBODDS" echo plant/state --key robotid=1 --domain "$DOMAIN"
echo "ok: echo --robot, --json, --csv, --field"
# A recording of nothing says where it listened and how to see what is there.
out="$(timeout -k 2 20 "$ROBODDS" record sensor/uwb --duration 1 --out "$WORK/empty.mcap" --domain "$DOMAIN")" || fail "record failed: $out"
grep -qF "no sample of these topics on DDS domain $DOMAIN (\`robodds topics --domain $DOMAIN\` lists the topics seen there)" <<<"$out" ||
  fail "an empty recording does not name the domain: $out"
echo "ok: an empty recording names the domain"

# Issue 29: a co-located real-time run reads the topics its components produce in memory (no DDS
# reader of them; DDS writers serve observers such as this one) and reads from DDS only what none
# of them produces: plant_smoke without its commander reads plant/cmd from DDS (an outside
# commander's topic) and has no reader of plant/state or sensor/position.
kill "${cleanup_pids[0]}" 2>/dev/null || true
wait "${cleanup_pids[0]}" 2>/dev/null || true
sed '/{name: commander, type: open_loop_commander}/d; /^  control: \[commander\]$/d' \
  "$SRC/sim/scenarios/plant_smoke.yaml" >"$WORK/no_commander.yaml"
grep -q "open_loop_commander" "$WORK/no_commander.yaml" && fail "could not remove the commander from plant_smoke.yaml: $(cat "$WORK/no_commander.yaml")"
# 60 s of run, ended by the test's cleanup once seen: a 6 s run had ended before the second listing
# on a machine at load 12 (its endpoints listed as gone: 0 writers, 0 readers).
timeout -k 5 90 "$ROBODDS" run "$WORK/no_commander.yaml" --realtime --duration 60 --domain "$DOMAIN" --out "$WORK/colocated" \
  --no-plots >"$WORK/colocated.log" 2>&1 &
cleanup_pids+=("$!")
# Once the run's endpoints are seen, one more listing: a participant's endpoints may be
# discovered one after the other, and "no reader" must not be read from a half-discovered run.
await_topics "^plant/state +robodds::idl::RobotState +1 " "^plant/cmd +robodds::idl::VelocityCommand +[0-9]+ +1 "
topics="$(timeout -k 2 20 "$ROBODDS" topics --duration 2 --domain "$DOMAIN")" || fail "robodds topics failed: $topics"
echo "$topics"
grep -qE "^plant/state +robodds::idl::RobotState +1 +0 " <<<"$topics" || fail "co-located real time: plant/state should have a writer and no reader"
grep -qE "^sensor/position +robodds::idl::PositionMeasurement +1 +0 " <<<"$topics" || fail "co-located real time: sensor/position should have a writer and no reader"
grep -qE "^plant/cmd +robodds::idl::VelocityCommand +0 +1 " <<<"$topics" || fail "co-located real time: plant/cmd (no producer in the run) should have a DDS reader"
echo "ok: a co-located real-time run reads its own topics in memory and an outside producer's from DDS"
colocated_pid="${cleanup_pids[${#cleanup_pids[@]}-1]}"
kill -TERM "$colocated_pid" 2>/dev/null || true
wait "$colocated_pid" 2>/dev/null || true

#!/usr/bin/env bash
# Every bad input exits non-zero with one line naming the file/key/element and the reason.
source "$(dirname "$0")/lib.sh"
S="$SRC/sim/scenarios/plant_smoke.yaml"
scenario_with() {  # scenario_with NAME SED-EXPR: a copy of plant_smoke edited by sed
  sed "$2" "$S" >"$WORK/$1.yaml"
  echo "$WORK/$1.yaml"
}
R=("$ROBODDS" run --domain "$DOMAIN" --out "$WORK/out")

expect_error 2 "no-such\.yaml: cannot open scenario file" -- "${R[@]}" "$WORK/no-such.yaml"
expect_error 2 "t1\.yaml: components\.plant\.type: unknown component type 'plantt'; did you mean 'plant'\?" -- "${R[@]}" "$(scenario_with t1 's/type: plant}/type: plantt}/')"
expect_error 2 "components\[1\]\.robots\[0\]: unknown robot 9" -- \
  "${R[@]}" "$(scenario_with t2 's/{name: plant, type: plant}/{name: plant, type: plant, robots: [9]}/')"
expect_error 2 "t3\.yaml: wheel_base_mm: unknown parameter" -- \
  "${R[@]}" "$(scenario_with t3 's/{name: plant, type: plant}/{name: plant, type: plant, params: {wheel_base_mm: 1}}/')"
# The robot's body is a shared fact of the scenario (system/robot_facts.hpp), not a plant parameter.
expect_error 2 "t4\.yaml: facts\.robot_body: wheel_base_m: must be > 0" -- \
  "${R[@]}" "$(scenario_with t4 's/^robots:/facts: {robot_body: {wheel_base_m: -1}}\nrobots:/')"
expect_error 2 "t5\.yaml: robots\[1\]\.facts\.robot_body: wheel_base_m: expected a number, got 'wide'" -- \
  "${R[@]}" "$(scenario_with t5 's/- {id: 2, x: 5.0/- {id: 2, facts: {robot_body: {wheel_base_m: wide}}, x: 5.0/')"
expect_error 2 "t4b\.yaml: facts\.robot_body: wheelbase_m: unknown parameter" -- \
  "${R[@]}" "$(scenario_with t4b 's/^robots:/facts: {robot_body: {wheelbase_m: 0.3}}\nrobots:/')"
expect_error 2 "t4c\.yaml: facts: robot_color: unknown fact \(known: robot_body, uwb_array, range_accel_bound_mps2\)" -- \
  "${R[@]}" "$(scenario_with t4c 's/^robots:/facts: {robot_color: red}\nrobots:/')"
# Paper 2's mission sections are read by the system layer (system/mission_plan.hpp), before the run starts.
expect_error 2 "t4e\.yaml: events\[0\]\.robots\[0\]: unknown robot 9" -- \
  "${R[@]}" "$(scenario_with t4e 's/^robots:/targets: [{id: 1, x: 0, y: 0, radius_m: 5}]\nevents: [{time_s: 0, robots: [9], target: 1}]\nrobots:/')"
expect_error 2 "t4d\.yaml: wheel_base_m: unknown parameter" -- \
  "${R[@]}" "$(scenario_with t4d 's/{name: plant, type: plant}/{name: plant, type: plant, params: {wheel_base_m: 0.3}}/')"
expect_error 2 "rate_hz: 7\.000000 Hz is not the simulation rate" -- \
  "${R[@]}" "$(scenario_with t6 's/{name: position_sensor, type: position_sensor}/{name: position_sensor, type: position_sensor, params: {rate_hz: 7}}/')"
expect_error 2 "groups\.sim: unknown component 'plnt'" -- "${R[@]}" "$(scenario_with t7 's/sim: \[plant\]/sim: [plnt]/')"
# Issue 24, finding 7: a lockstep input waiting for an instance nobody publishes is found before
# the first tick (was: a wait at step 0 until the step timeout, then "waited 10.0 s").
expect_error 2 "t8\.yaml: components: lockstep: component 'plant' waits at every step for plant/cmd of robot 3, which no component of the scenario publishes" -- \
  "${R[@]}" "$(scenario_with t8 's/{name: commander, type: open_loop_commander}/{name: commander, type: open_loop_commander, robots: [1, 2]}/')"
# The finding's own example: a UWB estimator whose window needs the link of two peers (peer_links)
# that no UWB sensor measures (paper3_exp2 without robot 2's sensor): named before the first tick.
sed -e '/name: uwb2/,+3d' -e 's/, uwb2\]/]/' "$SRC/sim/scenarios/paper3_exp2.yaml" >"$WORK/t8b.yaml"
expect_error 2 "t8b\.yaml: components: lockstep: component 'estimator1' waits at every step for sensor/uwb of robot 2, which no component of the scenario publishes" -- \
  "${R[@]}" "$WORK/t8b.yaml"
# Issue 27: a consumer's rate assumption against its producer's rate, checked before the first tick.
# The paper-2 observer's rate is the range sensor's: a 10 Hz sensor into the 50 Hz observer.
sed 's/{name: range_sensor, type: range_sensor, params: {noise_sigma_m: 0.0}}/{name: range_sensor, type: range_sensor, params: {noise_sigma_m: 0.0, rate_hz: 10}}/' \
  "$SRC/sim/scenarios/paper2_circumnavigation.yaml" >"$WORK/t9.yaml"
grep -q "rate_hz: 10}}" "$WORK/t9.yaml" || fail "t9.yaml: the range sensor's rate was not changed"
expect_error 2 "t9\.yaml: observer\.rate_hz: observer runs at 50 Hz and assumes sensor/range at that rate, but its producer 'range_sensor' samples sensor/range at 10 Hz \(range_sensor\.rate_hz\)" -- \
  "${R[@]}" "$WORK/t9.yaml"
# Paper 1 in real time with 1 Hz fixes: the filter's 0.5 s input timeout would call them stale between any two.
sed 's/{name: position_sensor, type: position_sensor}/{name: position_sensor, type: position_sensor, params: {rate_hz: 1}}/' \
  "$SRC/sim/scenarios/paper1_waypoints.yaml" >"$WORK/t10.yaml"
grep -q "rate_hz: 1}}" "$WORK/t10.yaml" || fail "t10.yaml: the position sensor's rate was not changed"
expect_error 2 "t10\.yaml: estimator\.input_timeout_s: 0\.5 s judges sensor/position stale, but its producer 'position_sensor' samples sensor/position at 1 Hz" -- \
  "${R[@]}" "$WORK/t10.yaml" --realtime --duration 1

# QoS files: missing, malformed, broken element, unknown profile.
expect_error 2 "nope\.xml: QoS profile file not found" -- "${R[@]}" "$S" --qos "$WORK/nope.xml"
printf '<dds><profiles><participant profile_name="x">' >"$WORK/truncated.xml"
expect_error 2 "truncated\.xml: rejected by Fast DDS" -- "${R[@]}" "$S" --qos "$WORK/truncated.xml"
sed 's#<kind>RELIABLE</kind>#<kind>RELIABLEISH</kind>#' "$SRC/deploy/qos/robodds_qos.xml" >"$WORK/badkind.xml"
expect_error 2 "badkind\.xml: rejected by Fast DDS" -- "${R[@]}" "$S" --qos "$WORK/badkind.xml"
expect_error 2 "participant profile 'no.such.profile'.*not found" -- "${R[@]}" "$S" --participant-profile no.such.profile
sed 's#profile_name="lockstep"#profile_name="lockstep_renamed"#g' "$SRC/deploy/qos/robodds_qos.xml" >"$WORK/noprofile.xml"
expect_error 2 "noprofile\.xml: data_writer profile 'lockstep': not found" -- "${R[@]}" "$S" --qos "$WORK/noprofile.xml"

# A second copy of the file redefines its transports and profiles: Fast DDS names the first
# duplicate it meets (a transport id since the participant profiles declare their transports).
cp "$SRC/deploy/qos/robodds_qos.xml" "$WORK/dup.xml"
expect_error 2 "dup\.xml: Fast DDS reported errors while loading it: .*(profile|transport)" -- \
  "${R[@]}" "$S" --qos "$SRC/deploy/qos/robodds_qos.xml" --qos "$WORK/dup.xml"

# Command-line mistakes are bad input too: exit 2, one line.
expect_error 2 "--scenario is required" -- "$ROBODDS" host --components plant,position_sensor --domain "$DOMAIN"
expect_error 2 "--domain: Value 300 not in range" -- "${R[@]}" "$S" --domain 300
expect_error 2 "--deploy: everywhere not in" -- "${R[@]}" "$S" --deploy everywhere

# The same errors from a host started on its own.
expect_error 2 "no group named 'nosuch'" -- "$ROBODDS" host --scenario "$S" --group nosuch --domain "$DOMAIN"
expect_error 2 "unknown topic 'plant/stat'" -- "$ROBODDS" echo plant/stat --domain "$DOMAIN"
echo "ok: all bad inputs rejected with a clear one-line error"

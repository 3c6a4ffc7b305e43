#!/usr/bin/env bash
# `robodds topics` lists the live topics with type and QoS; `robodds echo` prints samples readably.
source "$(dirname "$0")/lib.sh"
"$ROBODDS" host --scenario "$SRC/sim/scenarios/plant_smoke.yaml" --components plant,commander,position_sensor --realtime $(rt_priority_flag) \
  --duration 30 --domain "$DOMAIN" >"$WORK/host.log" 2>&1 &
cleanup_pids+=("$!")
sleep 1
topics="$(timeout -k 2 20 "$ROBODDS" topics --duration 2 --domain "$DOMAIN")" || fail "robodds topics failed: $topics"
echo "$topics"
grep -qE "^plant/state +robodds::idl::RobotState +1 .*RELIABLE/VOLATILE" <<<"$topics" || fail "plant/state missing or wrong QoS"
grep -qE "^sensor/position +robodds::idl::PositionMeasurement +1 .*BEST_EFFORT/VOLATILE" <<<"$topics" || fail "sensor/position missing"
grep -qE "^plant/cmd +robodds::idl::VelocityCommand +1 +1 " <<<"$topics" || fail "plant/cmd should have a writer and a reader"
out="$(timeout -k 2 20 "$ROBODDS" echo plant/state --count 3 --timeout 5 --domain "$DOMAIN")" || fail "echo failed: $out"
[[ $(grep -c "^--- plant/state (robot_id=" <<<"$out") -eq 3 ]] || fail "expected 3 samples: $out"
grep -qE "^  x: -?[0-9]" <<<"$out" || fail "fields not printed: $out"
expect_error 1 "no sample on sensor/uwb within 1" -- "$ROBODDS" echo sensor/uwb --count 1 --timeout 1 --domain "$DOMAIN"
echo "ok: topics and echo"

#!/usr/bin/env bash
# Multicast blocked (no multicast route, multicast off on every link): hosts cannot discover
# each other by SPDP multicast, and a Fast DDS Discovery Server in its own namespace host fixes
# that. Checks, on namespace hosts:
#   1. simple discovery fails with a timeout that names what it waited for and says no peer
#      was discovered (so multicast really is blocked);
#   2. discovery-server clients with the server down fail the same clear way;
#   3. with the server up, the paper-1 closed loop in lockstep is byte-identical to co-located;
#   4. ROS_DISCOVERY_SERVER with the SIMPLE udp_only profile reaches the server too.
# The clients use deploy/qos/discovery_client.xml; its server address (127.0.0.1) is rewritten
# in a copy, as a deployment would do for its own network.
source "$(dirname "$0")/netns_lib.sh"
command -v fastdds >/dev/null || skip "fastdds (package fastdds-tools) is not installed"
S="$SRC/sim/scenarios/paper1_waypoints.yaml"
DURATION="${4:-30}"
GROUPS_="sim sensors estimation control evaluation"
SERVER_HOST=7
COORD_HOST=6

netns_setup 7 nomulticast
SERVER_IP="$(netns_ip $SERVER_HOST)"
sed "s#<address>127.0.0.1</address>#<address>$SERVER_IP</address>#" "$SRC/deploy/qos/discovery_client.xml" >"$WORK/ds_client.xml"
grep -q "<address>$SERVER_IP</address>" "$WORK/ds_client.xml" || fail "server address not found in discovery_client.xml"
QOS=(--qos "$SRC/deploy/qos/robodds_qos.xml" --qos "$WORK/ds_client.xml")
DS=(--participant-profile robodds.participant.discovery_client "${QOS[@]}")

# expect_timeout NAME -- ARGS: a coordinator and the 'sim' host fail within their start timeout;
# the coordinator names the step, the group and the topic it waited for and says no peer matched.
expect_no_discovery() {
  local name="$1"
  shift 2
  local start=$SECONDS out
  # The sim host's own 3 s start timeout is checked too: under load it may start (and time out) later
  # than the coordinator, so give it 15 s to end by itself before it is stopped (it was once
  # "interrupted by a signal" at load 9).
  HOST_GRACE_S=15 netns_lockstep_run "$S" "$WORK/$name" 1 $COORD_HOST "sim" -- --domain "$DOMAIN" --duration 1 --start-timeout 3 --members sim "$@"
  out="$(cat "$WORK/$name.logs/coordinator.log")"
  [[ $COORD_RC -eq 1 ]] || fail "$name: coordinator exited $COORD_RC, expected 1: $out"
  grep -qE "no acknowledgement of step 0 within 3.0 s from group 'sim' \(nothing received yet\) on sim/step_done; DDS: no other participant discovered .*sim/step_done \(reader\): no writer matched" <<<"$out" ||
    fail "$name: unclear coordinator error: $out"
  [[ $(grep -c "error:" <<<"$out") -eq 1 ]] || fail "$name: expected one error line: $out"
  grep -qE "sim: no tick on sim/clock for 3.0 s after start: .*DDS: no other participant discovered .*sim/clock \(reader\): no writer matched" \
    "$WORK/$name.logs/sim.log" || fail "$name: unclear host error: $(cat "$WORK/$name.logs/sim.log")"
  echo "ok: $name: no discovery, clear errors after $((SECONDS - start)) s: $out"
}

expect_no_discovery simple_multicast_blocked -- --participant-profile robodds.participant.udp_only
expect_no_discovery server_down -- "${DS[@]}"

netns_spawn $SERVER_HOST "$WORK/server.log" fastdds discovery -i 0 -l "$SERVER_IP" -p 11811
server=$SPAWNED
for _ in $(seq 50); do
  grep -q "Server is running" "$WORK/server.log" 2>/dev/null && break
  kill -0 "$server" 2>/dev/null || fail "discovery server exited: $(cat "$WORK/server.log")"
  sleep 0.1
done
grep -q "Server is running" "$WORK/server.log" || fail "discovery server did not start: $(cat "$WORK/server.log")"

t0=$SECONDS
timeout -k 5 120 "$ROBODDS" run "$S" --duration "$DURATION" --out "$WORK/colocated" --domain "$DOMAIN" --no-plots >/dev/null
t1=$SECONDS
netns_lockstep_run "$S" "$WORK/netns" "$RANDOM$RANDOM" $COORD_HOST "$GROUPS_" -- --domain "$DOMAIN" --duration "$DURATION" \
  --start-timeout 30 "${DS[@]}"
t2=$SECONDS
[[ $COORD_RC -eq 0 ]] || fail "coordinator exited $COORD_RC: $(cat "$WORK/netns.logs/coordinator.log")"
for g in $GROUPS_; do
  [[ " $HOST_RCS" == *" $g=0 "* ]] || fail "host $g failed ($HOST_RCS): $(cat "$WORK/netns.logs/$g.log")"
done
same_outputs "$WORK/colocated" "$WORK/netns"

# The environment alternative (verified on 2.9.1): ROS_DISCOVERY_SERVER turns a SIMPLE profile
# (udp_only) into a client of that server. A short run: multicast is blocked, so finishing at all
# proves the variable took effect.
ROS_DISCOVERY_SERVER="$SERVER_IP:11811" netns_lockstep_run "$S" "$WORK/env" "$RANDOM$RANDOM" $COORD_HOST "$GROUPS_" -- \
  --domain "$DOMAIN" --duration 2 --start-timeout 15 --participant-profile robodds.participant.udp_only
[[ $COORD_RC -eq 0 ]] || fail "ROS_DISCOVERY_SERVER run: coordinator exited $COORD_RC: $(cat "$WORK/env.logs/coordinator.log")"
echo "ok: ROS_DISCOVERY_SERVER=$SERVER_IP:11811 with robodds.participant.udp_only also discovers through the server"
echo "ok: through the discovery server at $SERVER_IP:11811, $SAME_COUNT CSV files and the metrics are byte-identical" \
  "co-located ($((t1 - t0)) s) and on 5+1 namespace hosts ($((t2 - t1)) s), ${DURATION} s simulated"

#!/usr/bin/env bash
# Paper-1 closed loop in lockstep with every group on its own (network namespace) host and the
# coordinator on a sixth: its CSVs are byte-identical to the co-located run, and summary.json's
# metrics are equal. Hosts talk UDP only (robodds.participant.udp_only: shared memory does not
# exist between real machines) and discover each other by multicast across the bridge.
source "$(dirname "$0")/netns_lib.sh"
S="$SRC/sim/scenarios/paper1_waypoints.yaml"
DURATION="${4:-60}"
GROUPS_="sim sensors estimation control evaluation"

netns_setup 6
t0=$SECONDS
timeout -k 5 120 "$ROBODDS" run "$S" --duration "$DURATION" --out "$WORK/colocated" --domain "$DOMAIN" --no-plots >/dev/null
t1=$SECONDS
netns_lockstep_run "$S" "$WORK/netns" "$RANDOM$RANDOM" 6 "$GROUPS_" -- --domain "$DOMAIN" --duration "$DURATION" \
  --participant-profile robodds.participant.udp_only --start-timeout 30
t2=$SECONDS
[[ $COORD_RC -eq 0 ]] || fail "coordinator exited $COORD_RC: $(cat "$WORK/netns.logs/coordinator.log")"
for g in $GROUPS_; do
  [[ " $HOST_RCS" == *" $g=0 "* ]] || fail "host $g failed ($HOST_RCS): $(cat "$WORK/netns.logs/$g.log")"
done
for i in 1 2 3 4 5 6; do
  bytes=$(bridge_bytes "$i")
  [[ $bytes -gt 100000 ]] || fail "only $bytes bytes crossed host $i's link: the hosts did not talk over the network"
done
same_outputs "$WORK/colocated" "$WORK/netns"
echo "ok: $SAME_COUNT CSV files and the metrics are byte-identical co-located ($((t1 - t0)) s) and on 5+1 namespace hosts ($((t2 - t1)) s), ${DURATION} s simulated"

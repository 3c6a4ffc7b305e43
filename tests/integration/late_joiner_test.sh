#!/usr/bin/env bash
# A reader that starts after the mission was published still gets it (transient local).
source "$(dirname "$0")/lib.sh"
cat >"$WORK/mission.yaml" <<YAML
name: mission_only
step_s: 0.01
duration_s: 8.0
seed: 1
robots: [{id: 4}]
components:
  - {name: mission, type: mission_source, params: {waypoints: [[1, 2], [3, 4]]}}
YAML
"$ROBODDS" host --scenario "$WORK/mission.yaml" --components mission --realtime --domain "$DOMAIN" >"$WORK/host.log" 2>&1 &
cleanup_pids+=("$!")
sleep 2   # the mission is published at the first step, long before the reader exists
out="$(timeout -k 5 20 "$ROBODDS" echo mission/waypoints --count 1 --timeout 5 --domain "$DOMAIN")" \
  || fail "late reader got no mission: $out $(cat "$WORK/host.log")"
grep -q "robot_id: 4" <<<"$out" || fail "wrong sample: $out"
grep -qF "waypoints: [{x: 1, y: 2}, {x: 3, y: 4}]" <<<"$out" || fail "wrong way-points: $out"
echo "ok: late-joining reader received the transient-local mission"

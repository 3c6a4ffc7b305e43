# shellcheck shell=bash
# Helpers for multi-host tests: every "host" is a network namespace plugged into a Linux bridge
# that lives in its own namespace, so nothing (addresses, routes, links) touches the machine's
# own network. Source it instead of lib.sh; it sources lib.sh.
#
#   netns_setup N [nomulticast]   hosts 1..N at $(netns_ip i) on a bridge; 'nomulticast' leaves
#                                 out the multicast route, turns multicast off on the hosts'
#                                 links and makes the bridge drop multicast
#   netns_setup_wan N DELAY_MS [LOSS] [SEED]
#                                 hosts 1..N joined by robodds-wan-switch (tests/wan): every frame
#                                 from host to host takes DELAY_MS one way and is lost with
#                                 probability LOSS (this kernel has no netem); the switch's
#                                 per-host counters go to $WAN_STATS when it ends (wan_stop)
#   netns_teardown                ends everything in our namespaces and deletes them
#   netns_spawn I LOG CMD...      runs CMD in host I in the background (stdout+stderr -> LOG);
#                                 its pid is appended to cleanup_pids and left in $SPAWNED
#   netns_link I down|up          cuts / restores host I's cable at the bridge
#   wait_pid PID SECONDS          waits for PID to exit (fails the test on timeout); sets $RC
#
# Names are unique per test run (domain id + shell pid), so ctest -j is safe. The EXIT trap kills
# every process started here and every process left in our namespaces, then deletes them, also
# when the test fails or is interrupted. Namespaces leaked by a test that was SIGKILLed (ctest
# timeout) are removed by the next run of the same test (their owner pid is gone).
#
# Without the privilege to create namespaces the test exits with SKIP_CODE (77), which ctest
# reports as skipped (SKIP_RETURN_CODE), never as passed.
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

SKIP_CODE=77
NETNS_PREFIX="robodds-d${DOMAIN}-$$"
NETNS_BRIDGE="${NETNS_PREFIX}-br"
NETNS_SUBNET="10.$((DOMAIN % 250)).0"

skip() { echo "SKIP: $*"; exit "$SKIP_CODE"; }
netns_name() { echo "${NETNS_PREFIX}-h$1"; }
netns_ip() { echo "${NETNS_SUBNET}.$1"; }

# Kills what runs in a namespace of ours (all started by this test) and deletes it.
netns_delete() {
  local ns="$1" pids
  pids="$(ip netns pids "$ns" 2>/dev/null || true)"
  if [[ -n "$pids" ]]; then
    kill -TERM $pids 2>/dev/null || true
    for _ in $(seq 20); do
      pids="$(ip netns pids "$ns" 2>/dev/null || true)"
      [[ -z "$pids" ]] && break
      sleep 0.1
    done
    [[ -n "$pids" ]] && kill -KILL $pids 2>/dev/null || true
  fi
  ip netns del "$ns" 2>/dev/null || true
}

# Deletes every namespace of this test run (what runs in them first).
netns_delete_ours() {
  local ns
  for ns in $(ip netns list 2>/dev/null | awk '{print $1}' | grep -E "^${NETNS_PREFIX}-" || true); do
    netns_delete "$ns"
  done
}

netns_cleanup() {
  local rc=$?
  for pid in "${cleanup_pids[@]:-}"; do
    [[ -n "$pid" ]] && kill -TERM "$pid" 2>/dev/null || true
  done
  netns_delete_ours
  cleanup
  return $rc
}
trap netns_cleanup EXIT
trap 'exit 143' TERM
trap 'exit 130' INT
trap 'exit 129' HUP

# Namespaces of an earlier run of this test whose shell is gone (killed by a ctest timeout).
netns_reap_stale() {
  local ns pid
  for ns in $(ip netns list 2>/dev/null | awk '{print $1}' | grep -E "^robodds-d${DOMAIN}-[0-9]+-" || true); do
    pid="$(sed -E "s/^robodds-d${DOMAIN}-([0-9]+)-.*/\1/" <<<"$ns")"
    if ! kill -0 "$pid" 2>/dev/null; then
      echo "removing stale namespace $ns"
      netns_delete "$ns"
    fi
  done
}

netns_require() {
  command -v ip >/dev/null || skip "iproute2 ('ip') is not installed"
  [[ $(id -u) -eq 0 ]] || skip "network namespaces need root (CAP_SYS_ADMIN + CAP_NET_ADMIN); running as uid $(id -u)"
  local probe="${NETNS_PREFIX}-probe" err
  err="$(ip netns add "$probe" 2>&1)" || skip "cannot create a network namespace: $err"
  err="$(ip -n "$probe" link add probe0 type bridge 2>&1)" || { ip netns del "$probe"; skip "cannot create a bridge in a namespace: $err"; }
  err="$(ip -n "$probe" link add pa type veth peer name pb 2>&1)" || { ip netns del "$probe"; skip "cannot create veth pairs: $err"; }
  ip netns del "$probe"
}

# netns_setup N [nomulticast]
netns_setup() {
  local n="$1" multicast="${2:-multicast}" i ns
  netns_require
  netns_reap_stale
  ip netns add "$NETNS_BRIDGE"
  ip -n "$NETNS_BRIDGE" link set lo up
  # No IGMP snooping: without a querier the bridge would start filtering groups after a while.
  ip -n "$NETNS_BRIDGE" link add br0 type bridge mcast_snooping 0
  ip -n "$NETNS_BRIDGE" link set br0 up
  for i in $(seq "$n"); do
    ns="$(netns_name "$i")"
    ip netns add "$ns"
    # Both ends are created inside namespaces: no interface name can clash with another test.
    ip -n "$NETNS_BRIDGE" link add "h$i" type veth peer name eth0 netns "$ns"
    ip -n "$NETNS_BRIDGE" link set "h$i" master br0 up
    ip -n "$ns" link set lo up
    ip -n "$ns" addr add "$(netns_ip "$i")/24" dev eth0
    ip -n "$ns" link set eth0 up
    if [[ "$multicast" == multicast ]]; then
      # SPDP announces to 239.255.0.1: without a route the send fails (no default route here).
      ip -n "$ns" route add 224.0.0.0/4 dev eth0
    else
      # Like a cloud network without multicast. The interface flag alone is not enough: Fast DDS
      # picks the interface itself (IP_MULTICAST_IF) and the kernel still sends. The bridge
      # dropping all multicast towards this port is what blocks it.
      ip -n "$ns" link set dev eth0 multicast off
      bridge -n "$NETNS_BRIDGE" link set dev "h$i" mcast_flood off
    fi
  done
  # Ports of a bridge without STP forward at once, but wait for it rather than assume it.
  for _ in $(seq 50); do
    [[ $(bridge -n "$NETNS_BRIDGE" link show | grep -c "state forwarding") -eq "$n" ]] && return 0
    sleep 0.1
  done
  fail "bridge ports not forwarding: $(bridge -n "$NETNS_BRIDGE" link show)"
}

# netns_setup_wan N DELAY_MS [LOSS] [SEED]: needs $WAN_SWITCH (the robodds-wan-switch binary).
netns_setup_wan() {
  local n="$1" delay_ms="$2" loss="${3:-0}" seed="${4:-1}" i ns names=()
  [[ -x "${WAN_SWITCH:-}" ]] || fail "netns_setup_wan: WAN_SWITCH ('${WAN_SWITCH:-}') is not the robodds-wan-switch program"
  [[ -c /dev/net/tun ]] || skip "no /dev/net/tun: the WAN switch needs TAP devices"
  netns_require
  netns_reap_stale
  for i in $(seq "$n"); do
    ns="$(netns_name "$i")"
    ip netns add "$ns"
    ip -n "$ns" link set lo up
    names+=("$ns")
  done
  WAN_STATS="$WORK/wan_switch.json"
  local ready="$WORK/wan_switch.ready"
  rm -f "$ready"
  "$WAN_SWITCH" --delay-ms "$delay_ms" --loss "$loss" --seed "$seed" --ready "$ready" --stats "$WAN_STATS" \
    "${names[@]}" 2>"$WORK/wan_switch.log" &
  WAN_SWITCH_PID=$!
  cleanup_pids+=("$WAN_SWITCH_PID")
  for _ in $(seq 100); do
    [[ -f "$ready" ]] && break
    kill -0 "$WAN_SWITCH_PID" 2>/dev/null || fail "robodds-wan-switch ended: $(cat "$WORK/wan_switch.log")"
    sleep 0.05
  done
  [[ -f "$ready" ]] || fail "robodds-wan-switch did not make its TAP devices within 5 s: $(cat "$WORK/wan_switch.log")"
  for i in $(seq "$n"); do
    ns="$(netns_name "$i")"
    ip -n "$ns" addr add "$(netns_ip "$i")/24" dev eth0
    ip -n "$ns" link set eth0 up
    ip -n "$ns" route add 224.0.0.0/4 dev eth0
  done
}

# wan_stop: ends the switch (its TAP devices go with it) and waits for its counters ($WAN_STATS).
wan_stop() {
  kill -TERM "$WAN_SWITCH_PID" 2>/dev/null || true
  wait_pid "$WAN_SWITCH_PID" 10
}

# netns_teardown: kills what runs in our namespaces, ends the WAN switch if one runs, deletes the
# namespaces (a test may then set up others).
netns_teardown() {
  netns_delete_ours
  if [[ -n "${WAN_SWITCH_PID:-}" ]] && kill -0 "$WAN_SWITCH_PID" 2>/dev/null; then
    wan_stop
  fi
}

# netns_spawn I LOG CMD...
netns_spawn() {
  local i="$1" log="$2"
  shift 2
  ip netns exec "$(netns_name "$i")" "$@" >"$log" 2>&1 &
  SPAWNED=$!
  cleanup_pids+=("$SPAWNED")
}

# netns_link I down|up: the host's cable at the bridge (its own interface stays configured).
netns_link() { ip -n "$NETNS_BRIDGE" link set "h$1" "$2"; }

# wait_pid PID SECONDS: waits for a child of this shell; RC gets its exit code.
wait_pid() {
  local pid="$1" limit="$2" start=$SECONDS
  while kill -0 "$pid" 2>/dev/null; do
    if (( SECONDS - start > limit )); then
      fail "process $pid did not exit within $limit s"
    fi
    sleep 0.1
  done
  RC=0
  wait "$pid" || RC=$?
}

# now_ns: wall clock in ns (the hosts' CLOCK_REALTIME; namespaces share it).
now_ns() { date +%s%N; }

# netns_lockstep_run SCENARIO OUT RUN_ID COORD_HOST GROUPS -- HOST_ARGS...
#   Runs one lockstep run across namespace hosts: group k of the space-separated GROUPS in host
#   k, the coordinator (`robodds host --coordinate`, no component) in host COORD_HOST. HOST_ARGS
#   go to every process (domain, QoS files, participant profile, duration, timeouts). Logs go to
#   OUT.logs/<group>.log. Sets COORD_RC (the coordinator's exit code) and HOST_RCS (group=rc ...).
#   A group written GROUP@H runs in host H instead (several groups may share a host). The
#   coordinator must end within COORD_LIMIT_S (default 240 s).
netns_lockstep_run() {
  local scenario="$1" out="$2" run_id="$3" coord_host="$4" groups="$5" i=0 g
  shift 6
  local common=(--scenario "$scenario" --run-id "$run_id" --out "$out" "$@")
  local -a pids=() names=()
  mkdir -p "$out.logs"
  local host
  for g in $groups; do
    i=$((i + 1))
    host=$i
    if [[ "$g" == *@* ]]; then
      host="${g#*@}"
      g="${g%@*}"
    fi
    netns_spawn "$host" "$out.logs/$g.log" "$ROBODDS" host --group "$g" "${common[@]}"
    pids+=("$SPAWNED")
    names+=("$g")
  done
  netns_spawn "$coord_host" "$out.logs/coordinator.log" "$ROBODDS" host --coordinate "${common[@]}"
  wait_pid "$SPAWNED" "${COORD_LIMIT_S:-240}"
  COORD_RC=$RC
  HOST_RCS=""
  local grace_end=$((SECONDS + ${HOST_GRACE_S:-0}))
  for i in "${!pids[@]}"; do
    # After a failed coordinator the hosts would wait 30 s for the next tick: stop them, after
    # HOST_GRACE_S (default 0) in which a host may end on its own (a test of the hosts' own errors).
    while [[ $COORD_RC -ne 0 ]] && kill -0 "${pids[$i]}" 2>/dev/null && ((SECONDS < grace_end)); do
      sleep 0.1
    done
    if [[ $COORD_RC -ne 0 ]]; then
      kill -TERM "${pids[$i]}" 2>/dev/null || true
    fi
    wait_pid "${pids[$i]}" 60
    HOST_RCS+="${names[$i]}=$RC "
  done
}

# bridge_bytes I: bytes sent + received on host I's bridge port (proves traffic crossed the bridge).
bridge_bytes() {
  local port="h$1"
  echo $(( $(ip netns exec "$NETNS_BRIDGE" cat "/sys/class/net/$port/statistics/rx_bytes") +
           $(ip netns exec "$NETNS_BRIDGE" cat "/sys/class/net/$port/statistics/tx_bytes") ))
}

# same_outputs A B: byte-identical CSVs and identical summary.json metrics ("run", "hosts" and
# "inputs" sections aside).
same_outputs() {
  local a="$1" b="$2" n=0 f
  for f in "$a"/*.csv; do
    [[ -f "$b/$(basename "$f")" ]] || fail "$(basename "$f") missing in $b"
    cmp "$f" "$b/$(basename "$f")" || fail "$(basename "$f") differs between $a and $b"
    n=$((n + 1))
  done
  [[ $n -ge 1 ]] || fail "no CSV written in $a"
  [[ $(ls "$b"/*.csv | wc -l) -eq $n ]] || fail "$b has CSVs that $a does not"
  python3 - "$a/summary.json" "$b/summary.json" <<'PY' || fail "summary.json metrics differ"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for summary in (a, b):
    for section in ("run", "hosts", "inputs"):  # wall-clock and per-deployment figures
        summary.pop(section, None)
sys.exit(0 if a == b else 1)
PY
  # shellcheck disable=SC2034  # read by the tests that call it
  SAME_COUNT=$n
}

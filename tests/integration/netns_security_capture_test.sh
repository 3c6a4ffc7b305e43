#!/usr/bin/env bash
# DDS Security on the wire (docs/security.md): a packet capture (tcpdump) on the link of a
# namespace host shows no plaintext of a known sample value in a secure run, and shows it in the
# same run unsecured (so the check can fail). plant_smoke in two groups: 'control' (the commander)
# on host 1, 'rest' (plant, sensor, evaluator) and the coordinator on host 2; UDP only. The
# commander's v_mps is set to a value whose 8 bytes (little-endian double, as CDR carries it) are
# in every plant/cmd sample; every plant/cmd sample crosses host 1's cable, which is captured at
# the bridge. Both lockstep runs must complete (the samples did cross) with identical results.
source "$(dirname "$0")/netns_lib.sh"
command -v tcpdump >/dev/null || skip "tcpdump is not installed (scripts/setup.sh installs it)"
V_MPS=0.2718281828459045
DURATION=3
sed -e "s/^  - {name: commander, type: open_loop_commander}/  - {name: commander, type: open_loop_commander, params: {v_mps: $V_MPS}}/" \
  -e '/^  sim: \[plant\]/d; /^  sensing: \[position_sensor\]/d' \
  -e 's/^  evaluation: \[evaluator\]/  rest: [plant, position_sensor, evaluator]/' \
  "$SRC/sim/scenarios/plant_smoke.yaml" >"$WORK/capture.yaml"
grep -q "v_mps: $V_MPS" "$WORK/capture.yaml" && grep -q "^  rest: \[plant, position_sensor, evaluator\]" "$WORK/capture.yaml" ||
  fail "scenario not rewritten: $(cat "$WORK/capture.yaml")"
SEC="$WORK/sec"
"$ROBODDS" security init "$WORK/capture.yaml" --out "$SEC" >"$WORK/init.log" 2>&1 || fail "security init: $(cat "$WORK/init.log")"

netns_setup 2

# count_value PCAP: how many times the 8 bytes of V_MPS occur in the capture file.
count_value() {
  python3 - "$1" "$V_MPS" <<'PY'
import struct, sys
data = open(sys.argv[1], "rb").read()
print(data.count(struct.pack("<d", float(sys.argv[2]))))
PY
}

count_text() {  # count_text PCAP TEXT: occurrences of TEXT in the capture
  python3 - "$1" "$2" <<'PY'
import sys
print(open(sys.argv[1], "rb").read().count(sys.argv[2].encode()))
PY
}

# captured_run NAME [HOST_ARGS...]: one lockstep run across the two hosts with host 1's cable
# captured into $WORK/NAME.pcap. Sets RUN_RC (0, or 1 for the known secure-matching stall).
captured_run() {
  local name=$1 pid
  shift
  rm -rf "${WORK:?}/$name" "$WORK/$name.logs" "$WORK/$name.pcap"
  ip netns exec "$NETNS_BRIDGE" tcpdump -i h1 --immediate-mode -U -s 65535 -B 32768 -w "$WORK/$name.pcap" >"$WORK/$name.tcpdump.log" 2>&1 &
  pid=$!
  cleanup_pids+=("$pid")
  for _ in $(seq 50); do
    grep -q "listening on" "$WORK/$name.tcpdump.log" && break
    sleep 0.1
  done
  grep -q "listening on" "$WORK/$name.tcpdump.log" || fail "tcpdump did not start: $(cat "$WORK/$name.tcpdump.log")"
  netns_lockstep_run "$WORK/capture.yaml" "$WORK/$name" "$RANDOM$RANDOM" 2 "control rest" -- --domain "$DOMAIN" \
    --duration "$DURATION" --participant-profile robodds.participant.udp_only --start-timeout 20 --input-timeout 5 "$@"
  sleep 0.5  # let tcpdump write what the kernel still holds; then every packet must be in the file
  kill -INT "$pid"
  wait "$pid" || true
  local captured filtered
  captured=$(sed -nE 's/^([0-9]+) packets captured$/\1/p' "$WORK/$name.tcpdump.log")
  filtered=$(sed -nE 's/^([0-9]+) packets received by filter$/\1/p' "$WORK/$name.tcpdump.log")
  # Nothing dropped by the kernel; "received by filter" may exceed "captured" by a packet or two
  # that reached the interface as tcpdump was being stopped, 0.5 s after the run's last process
  # ended (the capture has no filter: IPv6 neighbour and multicast-listener packets come at any
  # time), so none of them can carry a sample of the run (seen once in CI: 1,308 of 1,309).
  [[ -n $captured && -n $filtered ]] && ((captured <= filtered && filtered - captured <= 3)) &&
    grep -q "^0 packets dropped by kernel" "$WORK/$name.tcpdump.log" ||
    fail "tcpdump missed packets: $(cat "$WORK/$name.tcpdump.log")"
  RUN_RC=0
  [[ $COORD_RC -eq 0 && "$HOST_RCS" == "control=0 rest=0 " ]] && return 0
  # Fast DDS 2.9.1's secure-matching stall (docs/security.md, known problem): a secure run that
  # stops at its first steps is retried by the caller; anything else fails here.
  if [[ $# -gt 0 ]] && grep -qE "waited [0-9.]+ s at step [01] for topic|no tick on sim/clock .* after step [01]|no acknowledgement of step [01] " \
    "$WORK/$name.logs/"*.log; then
    RUN_RC=1
    return 0
  fi
  fail "run $name failed (coordinator $COORD_RC, $HOST_RCS): $(tail -n 5 "$WORK/$name.logs/"*.log)"
}

t0=$SECONDS
captured_run plain
plain_count=$(count_value "$WORK/plain.pcap")
plain_bytes=$(stat -c %s "$WORK/plain.pcap")
[[ $plain_count -ge $((DURATION * 100)) ]] ||
  fail "the unsecured capture holds the value $V_MPS only $plain_count times (expected one per plant/cmd sample): the check cannot see plaintext"
t1=$SECONDS
for attempt in 1 2 3; do
  captured_run secure --security "$SEC"
  [[ $RUN_RC -eq 0 ]] && break
  echo "known Fast DDS secure-matching stall (attempt $attempt of 3): $(grep -h error: "$WORK/secure.logs/"*.log | tail -1)"
  [[ $attempt -lt 3 ]] || fail "the secure run stalled 3 times: $(tail -n 5 "$WORK/secure.logs/"*.log)"
done
secure_count=$(count_value "$WORK/secure.pcap")
secure_bytes=$(stat -c %s "$WORK/secure.pcap")
t2=$SECONDS
same_outputs "$WORK/plain" "$WORK/secure"
[[ $secure_bytes -gt $((plain_bytes / 2)) ]] || fail "the secure capture is only $secure_bytes bytes (unsecured: $plain_bytes): traffic was not captured"
[[ $secure_count -eq 0 ]] || fail "the secure capture shows the plaintext value $V_MPS $secure_count times"
# Discovery is protected too (governance discovery_protection_kind ENCRYPT): the type names that
# the endpoint announcements carry are in the unsecured capture and not in the secure one (topic
# names still are: the permissions document in the PKI-DH handshake lists them; docs/security.md).
type_plain=$(count_text "$WORK/plain.pcap" VelocityCommand)
type_secure=$(count_text "$WORK/secure.pcap" VelocityCommand)
[[ $type_plain -gt 0 ]] || fail "the unsecured capture does not show the type name VelocityCommand: the check cannot see discovery"
[[ $type_secure -eq 0 ]] || fail "the secure capture shows the type name VelocityCommand $type_secure times: discovery is not encrypted"
grep -q "ENCRYPT" "$SEC/governance.xml" || fail "governance does not encrypt"
echo "ok: v_mps=$V_MPS on host 1's cable: $plain_count times in the unsecured capture ($plain_bytes bytes, $((t1 - t0)) s)," \
  "0 times in the secure one ($secure_bytes bytes, $((t2 - t1)) s); results byte-identical ($SAME_COUNT CSVs)"

#!/usr/bin/env bash
# DDS Security (docs/security.md): an intruder with a valid identity but no right to publish
# plant/cmd cannot move a plant of a secure run. A secure lockstep run of plant_smoke on namespace
# hosts (groups control, sim, sensing, evaluation on hosts 1-4, the coordinator on 5; UDP only) and,
# started first on host 6, the intruder: a lockstep host with the `sensing` identity (authenticated,
# but its permissions do not list plant/cmd) running the commander at another speed, told the run's
# id (anyone with the sensing identity reads it on sim/clock) and acknowledging as 'intruder'.
# Checks: the plant's plant/cmd counters (summary.json "inputs", reported by the sim host over
# run/health) equal those of an unsecured co-located run without the intruder and reject nothing
# (a sample of a second producer would be counted and would fail the lockstep run), every CSV is
# byte-identical to that run's (the robots' trajectories), and the intruder was refused its writer.
# With the intruder's permissions re-signed to allow plant/cmd the run fails with two producers of
# plant/cmd: checked by hand, see the commit adding this test.
# A second intruder on host 7 tests the REMOTE side: a `control` identity of a foreign CA (its own
# `robodds security init`), whose permissions DO allow plant/cmd and whose files pass its own
# start-up checks; only the run's participants, authenticating it against their CA, can refuse it.
# Were they to accept it, the plant would see two producers of plant/cmd and the run would fail.
source "$(dirname "$0")/netns_lib.sh"
SCENARIO="$SRC/sim/scenarios/plant_smoke.yaml"
DURATION=5
SEC="$WORK/sec"
"$ROBODDS" security init "$SCENARIO" --out "$SEC" >"$WORK/init.log" 2>&1 || fail "security init: $(cat "$WORK/init.log")"
! grep -q "<topic>plant/cmd</topic>" "$SEC/sensing/permissions.xml" || fail "sensing must not name plant/cmd"
# Both intruders command at v 0.9 m/s instead of 1: the foreign one as group 'control'
# (foreign.yaml), the first one as group 'sensing', which runs the commander alone (intruder.yaml).
sed -e 's/^  - {name: commander, type: open_loop_commander}/  - {name: commander, type: open_loop_commander, params: {v_mps: 0.9}}/' \
  "$SCENARIO" >"$WORK/foreign.yaml"
sed -e 's/^  sensing: \[position_sensor\]/  sensing: [commander]/; /^  control: \[commander\]/d' \
  "$WORK/foreign.yaml" >"$WORK/intruder.yaml"
grep -q "^  sensing: \[commander\]" "$WORK/intruder.yaml" && grep -q "v_mps: 0.9" "$WORK/intruder.yaml" ||
  fail "intruder scenario not rewritten: $(cat "$WORK/intruder.yaml")"
FOREIGN="$WORK/foreign"
"$ROBODDS" security init "$SCENARIO" --out "$FOREIGN" >"$WORK/foreign_init.log" 2>&1 || fail "foreign security init: $(cat "$WORK/foreign_init.log")"
grep -q "<topic>plant/cmd</topic>" "$FOREIGN/control/permissions.xml" || fail "the foreign control identity must allow plant/cmd"
! cmp -s "$FOREIGN/ca/ca_cert.pem" "$SEC/ca/ca_cert.pem" || fail "the foreign identities share the run's CA"

# plant_cmd_counts SUMMARY: "accepted=N rejected={...}" of the plant's plant/cmd input.
plant_cmd_counts() {
  python3 - "$1" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
c = s.get("inputs", {}).get("plant", {}).get("plant/cmd")
if c is None:
    print("none reported (status %s: %s)" % (s.get("status"), s.get("reason", "")))
else:
    print("accepted=%d rejected=%s" % (c["accepted"], json.dumps(c["rejected"], sort_keys=True)))
PY
}

t0=$SECONDS
timeout -k 5 120 "$ROBODDS" run "$SCENARIO" --duration "$DURATION" --out "$WORK/plain" --domain "$DOMAIN" --no-plots \
  >"$WORK/plain.log" 2>&1 || fail "unsecured run failed: $(cat "$WORK/plain.log")"
plain_counts="$(plant_cmd_counts "$WORK/plain/summary.json")"
[[ $plain_counts == "accepted="[1-9]*" rejected={}" ]] || fail "unexpected counters of the unsecured run: $plain_counts"

netns_setup 7
t1=$SECONDS
GROUPS_="control sim sensing evaluation"
for attempt in 1 2 3; do
  run_id=$RANDOM$RANDOM
  rm -rf "${WORK:?}/secure" "$WORK/secure.logs"
  mkdir -p "$WORK/secure.logs"
  netns_spawn 6 "$WORK/secure.logs/intruder.log" "$ROBODDS" host --scenario "$WORK/intruder.yaml" --group sensing \
    --member intruder --run-id "$run_id" --duration "$DURATION" --domain "$DOMAIN" --security "$SEC" \
    --participant-profile robodds.participant.udp_only --start-timeout 20
  intruder=$SPAWNED
  netns_spawn 7 "$WORK/secure.logs/foreign.log" "$ROBODDS" host --scenario "$WORK/foreign.yaml" --group control \
    --member foreign --run-id "$run_id" --duration "$DURATION" --domain "$DOMAIN" --security "$FOREIGN" \
    --participant-profile robodds.participant.udp_only --start-timeout 20
  foreign=$SPAWNED
  sleep 1
  netns_lockstep_run "$SCENARIO" "$WORK/secure" "$run_id" 5 "$GROUPS_" -- --domain "$DOMAIN" --duration "$DURATION" \
    --participant-profile robodds.participant.udp_only --start-timeout 20 --input-timeout 5 --security "$SEC"
  kill -TERM "$intruder" "$foreign" 2>/dev/null || true
  wait_pid "$intruder" 30
  intruder_rc=$RC
  wait_pid "$foreign" 30
  # Fast DDS 2.9.1's secure-matching stall (docs/security.md, known problem) is retried; any other
  # failure is judged below.
  [[ $COORD_RC -ne 0 ]] && ! grep -q "has two producers" "$WORK/secure.logs/"*.log &&
    grep -qE "waited [0-9.]+ s at step [01] for topic|no tick on sim/clock .* after step [01]|no acknowledgement of step [01] " \
      "$WORK/secure.logs/"*.log || break
  echo "known Fast DDS secure-matching stall (attempt $attempt of 3): $(grep -h error: "$WORK/secure.logs/"*.log | tail -1)"
  [[ $attempt -lt 3 ]] || fail "the secure run stalled 3 times: $(tail -n 5 "$WORK/secure.logs/"*.log)"
done
t2=$SECONDS
[[ -f "$WORK/secure/summary.json" ]] || fail "the secure run wrote no summary.json (coordinator $COORD_RC, $HOST_RCS): $(tail -n 5 "$WORK/secure.logs/"*.log)"
secure_counts="$(plant_cmd_counts "$WORK/secure/summary.json")"
# Co-located, the plant accepts every command of the run (one per robot every 2nd step, the last
# step's included); across processes the last step's commands may arrive after the plant's last step.
plain_accepted=${plain_counts#accepted=}
plain_accepted=${plain_accepted%% *}
robots=$(grep -c "^  - {id: " "$SCENARIO")
[[ $secure_counts =~ ^accepted=([0-9]+)\ rejected=\{\}$ ]] &&
  ((BASH_REMATCH[1] <= plain_accepted && BASH_REMATCH[1] >= plain_accepted - robots)) ||
  fail "the plant's plant/cmd counters with the intruder: $secure_counts; without it: $plain_counts (at most $robots fewer accepted, none rejected); $(tail -n 5 "$WORK/secure.logs/"*.log)"
[[ $COORD_RC -eq 0 && "$HOST_RCS" == "control=0 sim=0 sensing=0 evaluation=0 " ]] ||
  fail "the secure run failed (coordinator $COORD_RC, $HOST_RCS): $(tail -n 5 "$WORK/secure.logs/"*.log)"
same_outputs "$WORK/plain" "$WORK/secure"
[[ $intruder_rc -eq 2 ]] || fail "the intruder exited $intruder_rc, expected 2 (writer refused): $(cat "$WORK/secure.logs/intruder.log")"
grep -qE "cannot create a writer on plant/cmd .*plant/cmd topic not found in allow rule" "$WORK/secure.logs/intruder.log" ||
  fail "the intruder was not refused its plant/cmd writer: $(cat "$WORK/secure.logs/intruder.log")"
# The foreign identity passed its own start-up checks and got as far as waiting for the run.
! grep -q "error: .*security" "$WORK/secure.logs/foreign.log" ||
  fail "the foreign-CA intruder was stopped by its own start-up checks, not by the run: $(cat "$WORK/secure.logs/foreign.log")"
echo "ok: the plant's plant/cmd input with the intruders: $secure_counts, without: $plain_counts; $SAME_COUNT CSVs" \
  "identical; the intruder was refused its writer, the foreign-CA one its peers (unsecured run $((t1 - t0)) s, secure run $((t2 - t1)) s)"

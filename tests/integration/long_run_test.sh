#!/usr/bin/env bash
# A long lockstep run in which instances end early (issue 22): paper 2 shortened to 180 s with
# its events at 10 % of the run (robots 1-3 switch to target 2, robot 4 leaves at 18 s), across
# processes on this machine and across five namespace hosts plus a coordinator host (UDP only).
# Both are byte-identical to the co-located run, and the steps per second of the last third are
# at least 1/1.5 of the first third's (summary.json run.ticks_per_s_by_third, the evaluator
# host's wall clock from its first tick). Before the writers forgot ended instances (Output's
# InstanceEnds, WriterHandle::end_instance) the ended instances' samples stayed the oldest in
# the writer histories and every heartbeat announced each later sample of the other robots as a
# hole: the rate fell all along the run (9,001 steps across processes: last third ~0.5 x the first).
source "$(dirname "$0")/netns_lib.sh"
PY=/usr/bin/python3  # Debian's, with python3-yaml (scripts/setup.sh)
SCENARIO="$WORK/paper2_leave_early.yaml"
"$PY" - "$SRC/sim/scenarios/paper2_circumnavigation.yaml" "$SCENARIO" <<'PY' || fail "could not write the scenario"
import sys, yaml
s = yaml.safe_load(open(sys.argv[1]))
s["name"] = "paper2_leave_early"
s["duration_s"] = 180.0
for event in s["events"][1:]:
    event["time_s"] = 18.0
yaml.safe_dump(s, open(sys.argv[2], "w"))
PY
GROUPS_="sim sensors observer control evaluation"

# check_thirds DIR LABEL: completed, and the last third's rate >= the first third's / 1.5.
check_thirds() {
  "$PY" - "$1/summary.json" "$2" <<'PY' || fail "$2: the run slowed down along its length (see above)"
import json, sys
summary = json.load(open(sys.argv[1]))
label = sys.argv[2]
if summary.get("status") != "completed":
    sys.exit(f"{label}: status {summary.get('status')}: {summary.get('reason')}")
thirds = summary["run"]["ticks_per_s_by_third"]
ratio = thirds[2] / thirds[0]
print(f"{label}: ticks/s by third {thirds}, last/first {ratio:.2f}")
if ratio < 1 / 1.5:
    sys.exit(f"{label}: the last third ran at {ratio:.2f} x the first (at least 0.67 expected)")
PY
}

timeout -k 5 120 "$ROBODDS" run "$SCENARIO" --out "$WORK/colocated" --domain "$DOMAIN" --no-plots >/dev/null 2>"$WORK/colocated.log" ||
  fail "co-located: $(tail -5 "$WORK/colocated.log")"
timeout -k 5 300 "$ROBODDS" run "$SCENARIO" --out "$WORK/processes" --domain "$DOMAIN" --deploy processes --no-plots \
  >/dev/null 2>"$WORK/processes.log" || fail "processes: $(grep -v '\[info\]' "$WORK/processes.log" | tail -5)"
same_outputs "$WORK/colocated" "$WORK/processes"
check_thirds "$WORK/processes" processes

netns_setup 6
netns_lockstep_run "$SCENARIO" "$WORK/netns" "$RANDOM$RANDOM" 6 "$GROUPS_" -- --domain "$DOMAIN" --deploy processes \
  --participant-profile robodds.participant.udp_only --start-timeout 30
[[ $COORD_RC -eq 0 ]] || fail "coordinator exited $COORD_RC: $(tail -5 "$WORK/netns.logs/coordinator.log")"
for g in $GROUPS_; do
  [[ " $HOST_RCS" == *" $g=0 "* ]] || fail "host $g failed ($HOST_RCS): $(tail -5 "$WORK/netns.logs/$g.log")"
done
same_outputs "$WORK/colocated" "$WORK/netns"
check_thirds "$WORK/netns" "namespace hosts"
echo "ok: $SAME_COUNT CSV files byte-identical co-located, across processes and on 5+1 namespace hosts; no slow-down after the instances ended"

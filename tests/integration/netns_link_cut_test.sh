#!/usr/bin/env bash
# Real time across namespace hosts, the controller's host loses its cable for 2 s:
#   - the survivors report it: the plant (and the evaluator) log that the writer of plant/cmd in
#     group 'control' lost liveliness, then that the control participant was discovered again;
#   - the plant never acts on stale commands: from command_timeout_s (0.5 s) after the cut until
#     the cable is back, the applied v and omega are exactly 0 and the robot does not move;
#   - the system resumes: after the restore the robot moves again and every host runs to its end;
#     a 2 s cut outlasts the 1.5 s participant lease, so every host sees the other side dropped
#     (issue 24, finding 6); a host that found it again within 0.4 s of the drop counts a stall
#     and exits 0, else it names the group lost and ends degraded (exit 3);
#   - the control host's real-time loop keeps its period during the cut (summary.json "hosts"):
#     at most 50 due steps skipped (the cut lasts 200; load on a shared CI machine skips some),
#     never more than 0.25 s late. Before robodds.udpv4 had non_blocking_send, sendto() blocked
#     on a send buffer full of datagrams queued behind unresolved ARP entries (the peers are
#     unreachable), inside a heartbeat that Fast DDS' event thread sends under the RTPS writer's
#     mutex, and the controller's DataWriter::write() waited on that mutex: ~170 skipped steps,
#     1.7 s late (docs/deployment.md, "A cut link must not block a real-time loop").
source "$(dirname "$0")/netns_lib.sh"
S="$SRC/sim/scenarios/paper1_waypoints.yaml"
DURATION=14      # s of real time
CUT_AT=5         # s after step 0
CUT_FOR=2        # s
GROUPS_=(sim sensors estimation control evaluation)
VICTIM=4         # host of group 'control' (controller + mission)

netns_setup 5
epoch=$(( ($(now_ns) / 1000000000 + 3) * 1000000000 ))  # step 0 in 3 s: time to discover
pids=()
for i in "${!GROUPS_[@]}"; do
  netns_spawn $((i + 1)) "$WORK/${GROUPS_[$i]}.log" "$ROBODDS" host --group "${GROUPS_[$i]}" --scenario "$S" \
    --out "$WORK/out" --domain "$DOMAIN" --participant-profile robodds.participant.udp_only --duration "$DURATION" \
    --realtime $(rt_priority_flag) --epoch-ns "$epoch"
  pids+=("$SPAWNED")
done

sleep "$(python3 -c "import time; print(max(0.0, ($epoch + $CUT_AT * 10**9 - time.time_ns()) / 1e9))")"
netns_link $VICTIM down
cut_ns=$(now_ns)          # taken after the link is down: the stale window starts no earlier
sleep "$CUT_FOR"
restore_ns=$(now_ns)      # taken before the link is up: the stale window ends no later
netns_link $VICTIM up
echo "cable of host $VICTIM (control) cut at +$(( (cut_ns - epoch) / 1000000 )) ms, restored at +$(( (restore_ns - epoch) / 1000000 )) ms"

for i in "${!pids[@]}"; do
  wait_pid "${pids[$i]}" $((DURATION + 30))
  [[ $RC -eq 0 || $RC -eq 3 ]] || fail "host ${GROUPS_[$i]} exited $RC, expected 0 or 3 (degraded by the cut): $(cat "$WORK/${GROUPS_[$i]}.log")"
  lost="control"
  [[ ${GROUPS_[$i]} == control ]] && lost="[a-z]+"
  grep -qE "participant 'robodds-$lost' dropped" "$WORK/${GROUPS_[$i]}.log" ||
    fail "host ${GROUPS_[$i]} did not see the other side of the cut dropped: $(cat "$WORK/${GROUPS_[$i]}.log")"
  if [[ $RC -eq 3 ]]; then
    grep -qE "lost group '$lost' at [0-9.]+ s after the start" "$WORK/${GROUPS_[$i]}.log" ||
      fail "host ${GROUPS_[$i]} ended degraded without naming the group lost in the cut: $(cat "$WORK/${GROUPS_[$i]}.log")"
  fi
  echo "host ${GROUPS_[$i]}: exit $RC"
done
grep -m1 -oE "lost group 'control' at [0-9.]+ s after the start|participant 'robodds-control' dropped and was discovered again [0-9.]+ s later" "$WORK/sim.log"

# Survivors report the loss and the recovery, naming topic and group. The cut outlasts the
# participant lease: the control participant is dropped (its writers unmatched, so no "regained
# liveliness") and discovered again after the restore, its writers matched as new ones.
for g in sim evaluation; do
  grep -q "plant/cmd: writer of 'control' lost liveliness" "$WORK/$g.log" ||
    fail "$g did not report the lost plant/cmd writer: $(cat "$WORK/$g.log")"
  grep -q "participant 'robodds-control' discovered again after it was lost" "$WORK/$g.log" ||
    fail "$g did not report the control host back: $(cat "$WORK/$g.log")"
done
grep -m1 "plant/cmd: writer of 'control' lost" "$WORK/sim.log"
grep -m1 "participant 'robodds-control' discovered again" "$WORK/sim.log"

# The plant's applied command, from the evaluator's records of plant/state and plant/cmd (the
# evaluator's host is not cut off). header.step is the real-time step: (wall clock - epoch) / step_s.
python3 - "$WORK/out" "$epoch" "$cut_ns" "$restore_ns" <<'PY' || fail "plant behaviour around the cut is wrong"
import bisect, csv, math, sys
out, epoch, cut, restore = sys.argv[1], *map(int, sys.argv[2:5])
step_s, timeout_s, margin_s = 0.01, 0.5, 0.1   # timeout_s: the plant's command_timeout_s
load = lambda name: [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open(f"{out}/{name}"))]
states, cmds = load("plant_state.csv"), load("plant_cmd.csv")
cmd_stamps = sorted(c["header.stamp_ns"] for c in cmds)
ok = True
def check(cond, text):
    global ok
    print(("ok: " if cond else "FAIL: ") + text)
    ok = ok and cond
# 1. Whenever the newest command is older than the timeout (+ margin), the plant applies nothing.
def stale(r):
    i = bisect.bisect_right(cmd_stamps, r["header.stamp_ns"])
    return i == 0 or (r["header.stamp_ns"] - cmd_stamps[i - 1]) * 1e-9 > timeout_s + margin_s
stale_rows = [r for r in states if stale(r) and r["header.step"] > 100]
check(len(stale_rows) >= 100, f"{len(stale_rows)} plant states while the newest command was stale")
check(all(r["v"] == 0.0 and r["omega"] == 0.0 for r in stale_rows), "v = omega = 0 whenever the newest command was stale")
# 2. The same seen from the cable: from timeout + margin after the cut until the restore.
step = lambda ns: (ns - epoch) / 1e9 / step_s
window = [r for r in states if step(cut) + (timeout_s + margin_s) / step_s <= r["header.step"] <= step(restore)]
check(len(window) >= 100 and all(r["v"] == 0.0 and r["omega"] == 0.0 for r in window),
      f"safe stop during the cut ({len(window)} states)")
check(len({(r["x"], r["y"], r["theta"]) for r in window}) == 1, "the robot stood still during the cut")
# 3. Moving before, moving again after.
before = [r for r in states if step(cut) - 200 <= r["header.step"] < step(cut)]
after = [r for r in states if r["header.step"] >= step(restore) + 100]
check(any(r["v"] != 0.0 for r in before), "the robot was moving before the cut")
check(any(r["v"] != 0.0 for r in after), "commands applied again after the restore")
moved = math.hypot(after[-1]["x"] - after[0]["x"], after[-1]["y"] - after[0]["y"]) if after else 0.0
check(moved > 0.5, f"the robot moved {moved:.2f} m after the restore")
sys.exit(0 if ok else 1)
PY
# The control host's loop kept its period while its peers were unreachable: the cut must not
# block the controller (the plant's command freshness, not the controller, covers the cut).
python3 - "$WORK/out/summary.json" <<'PY' || fail "the control host's real-time loop did not keep its period during the cut"
import json, sys
hosts = json.load(open(sys.argv[1]))["hosts"]
control = hosts.get("control", {})
print("control host:", json.dumps(control))
ok = control.get("reported", True) is not False and "missed_steps" in control
ok = ok and control["missed_steps"] <= 50 and control["worst_lateness_s"] <= 0.25
print(("ok: " if ok else "FAIL: ") + "control host skipped <= 50 due steps (the cut lasts 200) and was <= 0.25 s late (the cut lasts 2 s)")
sys.exit(0 if ok else 1)
PY
echo "ok: link cut reported by the survivors, safe stop while commands were stale, resumed after the restore, control loop kept its period"

#!/usr/bin/env bash
# SIGTERM stops a host that is already shutting down (issue #9: a coordinator blocked in Fast DDS
# while deleting its writers ignored SIGTERM, because the signal only asked a run loop that had
# already returned to stop). Host A (plant, commander) ends its real-time run while host B (the
# evaluator, which reads A's reliable plant/state and plant/cmd) is stopped (SIGSTOP: its readers
# stay matched and never acknowledge), so A's shutdown waits for acknowledgements. Once A's
# shutdown watchdog thread shows in /proc, the test sends SIGTERM: A must exit at once with 143
# and say so (before: the signal was ignored, A went on waiting and exited 0).
source "$(dirname "$0")/lib.sh"
S="$SRC/sim/scenarios/plant_smoke.yaml"
# B announces a 30 s lease: stopped, it must stay matched (not be dropped as a lost host after 1.5 s,
# issue 24 finding 6) so that A's shutdown waits for its acknowledgements. Both load the same files
# and options (finding 7's digest); B never reaches its end, it is stopped before.
write_long_lease_profile "$WORK/long_lease.xml"
export ROBODDS_QOS_FILE="$WORK/long_lease.xml"
# One epoch 3 s ahead for both (started, matched and stepping before B is stopped 2.5 s into the
# run, also with CPU hogs beside them), and SCHED_FIFO where allowed.
epoch_s=$(($(date +%s) + 3))
"$ROBODDS" --log warn host --scenario "$S" --components evaluator --realtime --duration 4 --domain "$DOMAIN" \
  --epoch-ns "${epoch_s}000000000" $(rt_priority_flag) --participant-profile test.long_lease --out "$WORK/b" >"$WORK/b.log" 2>&1 &
b=$!
cleanup_pids+=("$b")
"$ROBODDS" --log warn host --scenario "$S" --components plant,commander --realtime --duration 4 --domain "$DOMAIN" \
  --epoch-ns "${epoch_s}000000000" $(rt_priority_flag) --out "$WORK/a" >"$WORK/a.log" 2>&1 &
a=$!
cleanup_pids+=("$a")
finish() { kill -9 "$b" 2>/dev/null || true; }  # a stopped process only dies by SIGKILL
sleep "$(echo "$epoch_s + 2.5 - $(date +%s.%N)" | bc)"
kill -0 "$a" 2>/dev/null || { finish; fail "host A ended early: $(cat "$WORK/a.log")"; }
kill -STOP "$b"
in_shutdown() { grep -qx shutdown-watch /proc/"$a"/task/*/comm 2>/dev/null; }
for _ in $(seq 400); do  # A's run ends ~1.5 s later; up to 20 s
  in_shutdown && break
  kill -0 "$a" 2>/dev/null || break
  sleep 0.05
done
in_shutdown || { finish; fail "host A never reached a watched shutdown step: $(cat "$WORK/a.log")"; }
sent=$(date +%s.%N)
kill -TERM "$a"
rc=0
# tail checks the pid every -s seconds (default 1 s, as long as the whole bound: a race).
timeout 1 tail --pid="$a" -s 0.05 -f /dev/null || { finish; fail "host A ignored SIGTERM during shutdown (still running 1 s later)"; }
wait "$a" || rc=$?
took=$(echo "$(date +%s.%N) - $sent" | bc)
finish
[[ $rc -eq 143 ]] || fail "expected exit 143 after SIGTERM during shutdown, got $rc: $(cat "$WORK/a.log")"
grep -q "stopped by a signal during shutdown" "$WORK/a.log" || fail "no line says why A stopped: $(cat "$WORK/a.log")"
echo "ok: SIGTERM during shutdown (a peer stopped, acknowledgements pending) -> exit 143 after $took s"

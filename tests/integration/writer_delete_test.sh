#!/usr/bin/env bash
# Deleting reliable writers whose reader was SIGKILLed does not hang (issue #9: a coordinator hung
# in Fast DDS while deleting its writers after a failed lockstep run across processes; Fast DDS
# 2.9.1's writer deletion races with the periodic heartbeat, Fast-DDS#4076, and FastDdsBus now
# empties the histories first). robodds-writer-delete-probe runs 5 rounds of: a reader process on
# 50 topics, 16 x 256 samples per writer, SIGKILL the reader, delete the bus. Before the fix the
# first round hung (the shutdown watchdog ended the probe with code 3 after 5 s, 3 of 3 runs).
# Args: ROBODDS SRC DOMAIN PROBE (the robodds-writer-delete-probe binary).
source "$(dirname "$0")/lib.sh"
PROBE="$4"
[[ -x "$PROBE" ]] || fail "robodds-writer-delete-probe not found at '$PROBE'"
rc=0
ROBODDS_SHUTDOWN_LIMIT_S=5 timeout -k 5 120 "$PROBE" "$DOMAIN" 5 50 >"$WORK/probe.log" 2>&1 || rc=$?
[[ $rc -eq 0 ]] || fail "deleting writers whose reader died did not finish (exit $rc): $(cat "$WORK/probe.log")"
[[ $(grep -c "^round [0-9]*: deleted 50 writers" "$WORK/probe.log") -eq 5 ]] || fail "not 5 rounds: $(cat "$WORK/probe.log")"
echo "ok: 5 x 50 writers with a dead reader deleted: $(grep -o 'in [0-9.]* s' "$WORK/probe.log" | tr '\n' ' ')"

#!/usr/bin/env bash
# --rt-priority N (issue 24, finding 9): `robodds run` applies it to itself and hands it to every
# child host, which runs all its threads (Fast DDS's included) SCHED_FIFO at N with locked memory;
# a lockstep run takes it too. Without the capability (CAP_SYS_NICE, or CAP_IPC_LOCK under a small
# RLIMIT_MEMLOCK) `robodds run`, `robodds host` and a component executable refuse with one error
# line that names the option, the reason and what to do, exit 2, and start nothing.
source "$(dirname "$0")/lib.sh"
SCENARIO="$SRC/sim/scenarios/plant_smoke.yaml"
PLANT="$(dirname "$ROBODDS")/../../bin/robodds-plant"
[[ -x "$PLANT" ]] || fail "component executable $PLANT not found"
chrt -f 1 true 2>/dev/null || { echo "SKIP: this process may not use SCHED_FIFO (chrt -f 1 true refused)"; exit 77; }

# 1. Out of range: a command-line error naming the option.
expect_error 2 "--rt-priority: must be a whole number 1\.\.99 .*\(got 0\)" -- "$ROBODDS" run "$SCENARIO" --rt-priority 0
expect_error 2 "--rt-priority: must be a whole number 1\.\.99 .*\(got 100\)" -- "$PLANT" --robot 1 --rt-priority 100

# 2. Refused: no CAP_SYS_NICE (root without it in its bounding set) and RLIMIT_RTPRIO 0.
NO_NICE=(setpriv --bounding-set=-sys_nice,-ipc_lock --inh-caps=-sys_nice,-ipc_lock prlimit --rtprio=0 --)
SCHED_REFUSED="--rt-priority 50: SCHED_FIFO refused \(no CAP_SYS_NICE and RLIMIT_RTPRIO 0\): run as root, give the capability"
expect_error 2 "$SCHED_REFUSED" -- "${NO_NICE[@]}" "$ROBODDS" run "$SCENARIO" --realtime --rt-priority 50 \
  --out "$WORK/refused" --domain "$DOMAIN" --no-plots
[[ ! -e "$WORK/refused" ]] || fail "a refused run created its output directory"
expect_error 2 "$SCHED_REFUSED" -- "${NO_NICE[@]}" "$ROBODDS" host --scenario "$SCENARIO" --group sim --rt-priority 50 --domain "$DOMAIN"
expect_error 2 "$SCHED_REFUSED" -- "${NO_NICE[@]}" "$PLANT" --robot 1 --realtime --rt-priority 50 --domain "$DOMAIN"
# ... and with CAP_SYS_NICE but neither CAP_IPC_LOCK nor enough RLIMIT_MEMLOCK for mlockall.
expect_error 2 "--rt-priority 50: locking the memory \(mlockall\) refused \(.*no CAP_IPC_LOCK and RLIMIT_MEMLOCK 65536 bytes\)" -- \
  setpriv --bounding-set=-ipc_lock --inh-caps=-ipc_lock prlimit --memlock=65536 -- "$PLANT" --robot 1 --rt-priority 50 --domain "$DOMAIN"

# 3. Granted: each child host's real-time loop (its main thread) is SCHED_FIFO 10 and every other
# thread of it and of the runner (which runs no loop) SCHED_FIFO 9, above every SCHED_OTHER job
# and below the loop; memory locked.
# 6 s: the checks below take a while on a loaded machine, and every host must still be running.
timeout -k 5 60 "$ROBODDS" run "$SCENARIO" --deploy processes --realtime --duration 6 --rt-priority 10 \
  --out "$WORK/rt" --domain "$DOMAIN" --no-plots >"$WORK/rt.log" 2>&1 &
timeout_pid=$!
cleanup_pids+=("$timeout_pid")
sleep 2.5  # the hosts start at the next whole second + 1 s and have their participants by then
runner="$(pgrep -P "$timeout_pid")" || fail "the runner is not running: $(tail -5 "$WORK/rt.log")"
children=($(pgrep -P "$runner")) || true
((${#children[@]} >= 2)) || fail "expected the child hosts of the runner, found: ${children[*]:-none}"
for pid in "$runner" "${children[@]}"; do
  what="process $pid ($(tr '\0' ' ' </proc/$pid/cmdline | cut -c1-80))"
  all_threads="$(ps -L -o tid=,cls=,rtprio=,comm= -p "$pid")"
  # File writers (runtime/io/batch_writer_thread.hpp, named robodds-files: the evaluator's CSV) run
  # at the ordinary policy on purpose, below the loop and the receive threads.
  writers="$(awk '$NF == "robodds-files"' <<<"$all_threads")"
  [[ -z $writers || -z $(awk '$2 != "TS"' <<<"$writers") ]] || fail "$what: its file writer threads are not at the ordinary policy (TS): $writers"
  threads="$(awk '$NF != "robodds-files" {print $1, $2, $3}' <<<"$all_threads")"
  other="$(grep -cvE "FF +(9|10)$" <<<"$threads" || true)"
  [[ $other -eq 0 ]] || fail "$what: $other of its threads are not SCHED_FIFO 9 or 10: $threads"
  loop="$( (grep -E "FF +10$" <<<"$threads" || true) | awk '{print $1}' | tr '\n' ' ')"
  if [[ $pid == "$runner" ]]; then
    [[ -z $loop ]] || fail "$what: the runner runs no loop, yet threads $loop are at 10: $threads"
  else
    [[ $loop == "$pid " ]] || fail "$what: only its loop (main thread $pid) must be at 10, found: ${loop:-none}: $threads"
  fi
  locked_kb="$(awk '/^VmLck:/ {print $2}' "/proc/$pid/status")"
  [[ ${locked_kb:-0} -gt 0 ]] || fail "process $pid has no locked memory (VmLck ${locked_kb:-?} kB)"
  echo "ok: process $pid: $(wc -l <<<"$threads") threads SCHED_FIFO 9, the loop ${loop:-(none)}at 10, $(grep -c . <<<"$writers") file writers at the ordinary policy, VmLck $locked_kb kB"
done
wait "$timeout_pid" || fail "real-time run with --rt-priority failed: $(tail -5 "$WORK/rt.log")"
grep -q '"status": "completed"' "$WORK/rt/summary.json" || fail "summary.json: $(head -c 500 "$WORK/rt/summary.json")"

# 4. A lockstep run takes it too (harmless: lockstep does not depend on timing).
timeout -k 5 60 "$ROBODDS" run "$SCENARIO" --duration 1 --rt-priority 10 --out "$WORK/lockstep" --domain "$DOMAIN" \
  --no-plots >"$WORK/lockstep.log" 2>&1 || fail "lockstep run with --rt-priority failed: $(tail -5 "$WORK/lockstep.log")"
echo "ok: --rt-priority validated, refused with one line and exit 2 without the capability, applied to every thread of every process (the loop one above the rest)"

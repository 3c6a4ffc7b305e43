# Helpers for integration tests: real robodds processes over real DDS.

# write_long_lease_profile FILE: a QoS file with the participant profile "test.long_lease" (a 30 s
# lease): a test that stops or kills a host on purpose, and checks something else than its loss,
# gives that host this profile so that the others do not end the run 1.5 s later (issue 24,
# finding 6). Every host of the run must load the same file (finding 7's digest).
write_long_lease_profile() {
  cat >"$1" <<'XML'
<?xml version="1.0" encoding="UTF-8" ?>
<dds xmlns="http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles">
  <profiles>
    <participant profile_name="test.long_lease">
      <rtps>
        <builtin>
          <discovery_config>
            <leaseDuration><sec>30</sec><nanosec>0</nanosec></leaseDuration>
            <leaseAnnouncement><sec>0</sec><nanosec>500000000</nanosec></leaseAnnouncement>
          </discovery_config>
        </builtin>
      </rtps>
    </participant>
  </profiles>
</dds>
XML
}

# Each test gets ROBODDS (binary), SRC (repo root) and DOMAIN (its own domain id).
set -euo pipefail
ROBODDS="$1"
SRC="$2"
DOMAIN="$3"
WORK="$(mktemp -d /tmp/robodds-test.XXXXXX)"
cleanup_pids=()
cleanup() {
  for pid in "${cleanup_pids[@]:-}"; do
    [[ -n "$pid" ]] && kill "$pid" 2>/dev/null || true
  done
  # A start_host wrapper writes NAME.exit when its process ends, which may be while rm runs
  # ("Directory not empty" would fail a test that passed): try again while they finish.
  for _ in 1 2 3 4 5 6 7 8 9 10; do
    rm -rf "$WORK" 2>/dev/null && break
    sleep 0.2
  done
  [[ ! -e $WORK ]] || echo "warning: $WORK could not be removed" >&2
  # A process killed by a test (dead peers, signals) leaves its Fast DDS shared-memory segment
  # (~1 MiB with its ports, deploy/qos/robodds_qos.xml) in /dev/shm; this removes those whose
  # owner is gone (segments in use by another test's processes are kept).
  fastdds shm clean >/dev/null 2>&1 || true
}
trap cleanup EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
# rt_priority_flag: prints "--rt-priority 50" when this process may run SCHED_FIFO (`chrt -f 1
# true` works: root, CAP_SYS_NICE or rtprio in limits.conf) and lock its memory (CAP_IPC_LOCK or
# an unlimited memlock), else nothing. Real-time tests put it on their runs and hosts (unquoted:
# `$(rt_priority_flag)`) so that their loops keep the period on a busy machine where they can
# (issue 24, finding 9) and still run where they cannot.
rt_priority_flag() {
  chrt -f 1 true 2>/dev/null || return 0
  local caps
  caps="$(awk '/^CapEff:/ {print $2}' /proc/self/status)"
  if (( (0x${caps:-0} >> 14) & 1 )) || [[ $(ulimit -l) == unlimited ]]; then  # bit 14: CAP_IPC_LOCK
    echo "--rt-priority 50"
  fi
}
# rt_chrt PRIORITY: prints "chrt -f PRIORITY" when rt_priority_flag would give --rt-priority, else
# nothing: for a helper process of a real-time test that has no --rt-priority of its own (e.g.
# robodds-fuzz, the hostile writer), so that CPU hogs beside the test do not stretch its timing
# past the run it writes into. Give it a priority below the run's 50: the run still comes first.
rt_chrt() {
  [[ -n "$(rt_priority_flag)" ]] && echo "chrt -f $1"
  return 0
}
# expect_error EXPECTED_EXIT PATTERN -- command...: runs command, checks exit code and stderr.
expect_error() {
  local code="$1" pattern="$2"; shift 3
  local out rc=0
  out="$(timeout -k 5 60 "$@" 2>&1)" || rc=$?
  [[ $rc -eq $code ]] || fail "expected exit $code, got $rc from: $* -- output: $out"
  grep -qE -- "$pattern" <<<"$out" || fail "expected /$pattern/ in: $out"
  [[ $(grep -c "error:" <<<"$out") -eq 1 ]] || fail "expected exactly one error line in: $out"
  echo "ok: $pattern"
}
# same_outputs DIR_A DIR_B: every CSV of DIR_A is byte-identical in DIR_B and the two summary.json
# files are equal but for their "run", "hosts" and "inputs" sections (wall-clock and deployment
# figures). Sets $N_CSV.
same_outputs() {
  local a="$1" b="$2" f
  N_CSV=0
  for f in "$a"/*.csv; do
    [[ -e "$f" ]] || break
    cmp "$f" "$b/$(basename "$f")" || fail "$(basename "$f") differs between $(basename "$a") and $(basename "$b")"
    N_CSV=$((N_CSV + 1))
  done
  [[ $N_CSV -ge 1 ]] || fail "no CSV written in $a"
  python3 - "$a/summary.json" "$b/summary.json" <<'PY' || fail "summary.json metrics differ between $(basename "$a") and $(basename "$b")"
import json, sys
a, b = (json.load(open(path)) for path in sys.argv[1:])
for summary in (a, b):
    summary.pop("run", None)  # wall-clock figures of the runner; a host alone writes none
    summary.pop("hosts", None)  # per deployment group: differs between deployments
    summary.pop("inputs", None)  # input counters: how many samples each reader saw depends on the deployment
if a != b:
    print("first:", json.dumps(a, sort_keys=True)[:2000], "\nsecond:", json.dumps(b, sort_keys=True)[:2000], file=sys.stderr)
    sys.exit(1)
PY
}
# run_with_nan_injected SCENARIO DURATION_S DEPLOY: `robodds run` of SCENARIO (a rewrite that makes
# one producer publish NaN) into $WORK/DEPLOY, its log in $WORK/DEPLOY.log; fails if the run does.
run_with_nan_injected() {
  local scenario="$1" duration="$2" deploy="$3"
  timeout -k 5 120 "$ROBODDS" run "$scenario" --duration "$duration" --out "$WORK/$deploy" --domain "$DOMAIN" \
    --deploy "$deploy" --no-plots >"$WORK/$deploy.log" 2>&1 || fail "run failed: $(cat "$WORK/$deploy.log")"
}
# expect_rejected_once LOG CONSUMER TOPIC STEP FIELD CSV...: CONSUMER logged exactly one rejection,
# of robot 1's sample on TOPIC at STEP for FIELD, and no non-finite value reached the CSVs.
expect_rejected_once() {
  local log="$1" consumer="$2" topic="$3" step="$4" field="$5" csv
  shift 5
  grep -qE "\[warn\] $consumer: rejected a sample on $topic from .+ \(robot_id=1, step $step\): field '$field' is not finite" "$log" \
    || fail "$consumer did not report the NaN sample on $topic: $(cat "$log")"
  [[ $(grep -c "$consumer: rejected" "$log") -eq 1 ]] || fail "rejection logged more than once"
  for csv in "$@"; do
    grep -qiE "nan|inf" "$csv" && fail "a non-finite value reached $(basename "$csv")"
  done
  return 0
}

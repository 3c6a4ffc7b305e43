#!/usr/bin/env bash
# Key flood (issue 24, finding 4): robodds-fuzz publishes decodable samples of 20,000 distinct
# robots the scenario does not have (`--kinds body`, random robot ids) on plant/cmd and
# sensor/position into a real-time plant_smoke run across processes. Before the reader key filter
# (runtime/dds/key_filter.hpp) every key became an instance of the receivers' Fast DDS reader
# histories for good, with its deadline: the receivers stayed at 29-74 % CPU after the flood.
# Checks, for each receiving host (sim: plant/cmd; evaluation: plant/cmd and sensor/position):
#   - CPU back to its baseline within 1 s of the flood's end: the mean over [end + 1 s, end + 3 s]
#     at most the mean over the 3 s before the flood + KEY_FLOOD_CPU_MARGIN percentage points
#     (a margin for a busy machine: the baseline is 2-3 %, the failure 30-50 %);
#   - RSS grew by at most 1 MiB from just before the flood to after it, not counting shared
#     memory (VmRSS - RssShmem): the flooding participant's Fast DDS segment (~0.5-1 MiB, mapped by
#     every process it sends to) is counted in VmRSS as its pages are touched (seen:
#     +0.3 to +1.1 MiB of VmRSS as shared memory, +0.04 to +0.08 MiB anonymous);
#   - summary.json "inputs" counts the refused samples as unknown_key: at least half and at most
#     all of those written (best effort may drop some, robodds-fuzz does not wait for every
#     acknowledgement);
#   - the run completes (exit 0: fewer missed steps than --max-missed-steps).
# CPU is sampled from /proc/PID/stat (utime + stime) every 0.5 s, RSS from /proc/PID/status (VmRSS,
# and its anonymous and shared-memory parts for the log).
# Args: ROBODDS SRC DOMAIN FUZZ. Env: KEY_FLOOD_S (flood length, default 6 s), KEY_FLOOD_KEYS
# (default 20000), KEY_FLOOD_CPU_MARGIN (percentage points, default 8).
source "$(dirname "$0")/lib.sh"
FUZZ="$4"
[[ -x "$FUZZ" ]] || fail "robodds-fuzz not found at '$FUZZ'"
FLOOD_S="${KEY_FLOOD_S:-6}"
KEYS="${KEY_FLOOD_KEYS:-20000}"
MARGIN="${KEY_FLOOD_CPU_MARGIN:-8}"
LEAD_S=4       # s: hosts up and matched before the baseline window
BASELINE_S=3   # s before the flood
AFTER_S=3      # s after the flood: judged from end + 1 s
# The flood may take up to three times FLOOD_S: robodds-fuzz runs SCHED_OTHER beside hosts whose
# receive threads run SCHED_FIFO and take every flooded sample first (on an idle 2-core machine it
# took 12-16 s for its 6 s, and the run ended before the window after the flood).
DURATION_S=$(python3 -c "print($LEAD_S + $BASELINE_S + 3 * $FLOOD_S + 2 + $AFTER_S + 2)")
RATE=$(python3 -c "print($KEYS / $FLOOD_S)")

# --rt-priority where allowed: eight CPU hogs beside it must not starve the hosts, and the flood
# on their Fast DDS receive threads must not hold their loops off the CPU (the loop one priority
# above them: with all threads at one priority the sim host missed 51 steps during the flood).
timeout -k 5 $((DURATION_S + 60)) "$ROBODDS" run "$SRC/sim/scenarios/plant_smoke.yaml" --deploy processes --realtime $(rt_priority_flag) \
  --duration "$DURATION_S" --domain "$DOMAIN" --out "$WORK/out" --no-plots >"$WORK/run.log" 2>&1 &
run_pid=$!
cleanup_pids+=("$run_pid")

# The sampler: every 0.5 s, for every host process below the runner (`robodds host --group G`), wall time, group, CPU ticks
# and VmRSS, until the runner exits (bounded by the run's own timeout).
python3 - "$run_pid" "$WORK/samples.csv" <<'PY' &
import os, sys, time
runner, out = int(sys.argv[1]), sys.argv[2]
def children(pid):  # every descendant (the runner is below `timeout`, the hosts below the runner)
    try:
        with open(f"/proc/{pid}/task/{pid}/children") as f:
            direct = [int(c) for c in f.read().split()]
    except OSError:
        return []
    return direct + [d for c in direct for d in children(c)]
def group_of(pid):
    try:
        args = open(f"/proc/{pid}/cmdline", "rb").read().split(b"\0")
    except OSError:
        return None
    return args[args.index(b"--group") + 1].decode() if b"--group" in args else None
with open(out, "w") as f:
    f.write("t,group,ticks,rss_kb,anon_kb,shmem_kb\n")
    while os.path.exists(f"/proc/{runner}"):
        now = time.time()
        for pid in children(runner):
            group = group_of(pid)
            try:
                stat = open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()
                status = {l.split(":")[0]: l.split()[1] for l in open(f"/proc/{pid}/status") if l.startswith(("VmRSS:", "RssAnon:", "RssShmem:"))}
                rss = f"{status['VmRSS']},{status['RssAnon']},{status['RssShmem']}"
            except (OSError, IndexError, KeyError):
                continue
            if group:
                f.write(f"{now:.3f},{group},{int(stat[11]) + int(stat[12])},{rss}\n")
        f.flush()
        time.sleep(0.5 - (time.time() - now) % 0.5)
PY
sampler_pid=$!
cleanup_pids+=("$sampler_pid")

sleep $((LEAD_S + BASELINE_S))
flood_start=$(date +%s.%N)
fuzz_rc=0
timeout -k 5 $((FLOOD_S + 40)) "$FUZZ" --domain "$DOMAIN" --topics plant/cmd,sensor/position --kinds body \
  --count "$KEYS" --rate "$RATE" --seed 24 --qos "$SRC/deploy/qos/robodds_qos.xml" >"$WORK/fuzz.txt" 2>"$WORK/fuzz.log" || fuzz_rc=$?
cat "$WORK/fuzz.txt"
[[ $fuzz_rc -eq 0 ]] || fail "robodds-fuzz exited $fuzz_rc: $(cat "$WORK/fuzz.log")"
flood_end_ns=$(sed -n 's/^written_until_ns=//p' "$WORK/fuzz.txt")
rc=0
wait "$run_pid" || rc=$?
wait "$sampler_pid" || true
[[ $rc -eq 0 ]] || fail "robodds run exited $rc: $(grep -v 'deadline missed' "$WORK/run.log" | tail -20)"

python3 - "$WORK/samples.csv" "$flood_start" "$flood_end_ns" "$BASELINE_S" "$AFTER_S" "$MARGIN" <<'PY' || fail "CPU or RSS not back to its baseline after the flood"
import csv, os, sys
path, start, end = sys.argv[1], float(sys.argv[2]), int(sys.argv[3]) * 1e-9
baseline_s, after_s, margin = float(sys.argv[4]), float(sys.argv[5]), float(sys.argv[6])
hz = os.sysconf("SC_CLK_TCK")
rows = {}
for r in csv.DictReader(open(path)):
    rows.setdefault(r["group"], []).append((float(r["t"]), int(r["ticks"]), int(r["rss_kb"]), int(r["anon_kb"]), int(r["shmem_kb"])))
def cpu(samples, t0, t1):  # mean CPU % over [t0, t1] from the samples nearest its ends
    inside = [s for s in samples if t0 - 0.25 <= s[0] <= t1 + 0.25]
    if len(inside) < 2:
        return None
    (a, ta), (b, tb) = inside[0][:2], inside[-1][:2]
    return 100.0 * (tb - ta) / hz / (b - a)
ok = True
for group in ("sim", "evaluation"):
    s = rows.get(group, [])
    base = cpu(s, start - baseline_s, start)
    during = cpu(s, start, end)
    after = cpu(s, end + 1.0, end + after_s)
    before = [x for x in s if x[0] <= start][-1:]
    after_rows = [x for x in s if end + 1.0 <= x[0] <= end + after_s]
    # VmRSS - RssShmem: the process's own memory (anonymous and file pages).
    before_rss, after_rss = [x[2] - x[4] for x in before], [x[2] - x[4] for x in after_rows]
    if base is None or during is None or after is None or not before_rss or not after_rss:
        print(f"FAIL: {group}: too few samples ({len(s)})", file=sys.stderr)
        sys.exit(1)
    growth = max(after_rss) - before_rss[0]
    last = max(after_rows, key=lambda x: x[2] - x[4])
    print(f"{group}: CPU baseline {base:.1f} %, during the flood {during:.1f} %, from 1 s after it {after:.1f} % "
          f"(limit {base + margin:.1f} %); RSS without shared memory {before_rss[0]} kB before, {max(after_rss)} kB after "
          f"({growth:+d} kB, limit 1024; anonymous {last[3] - before[0][3]:+d} kB); VmRSS {before[0][2]} -> {last[2]} kB "
          f"({last[2] - before[0][2]:+d} kB, shared memory {last[4] - before[0][4]:+d} kB)")
    if after > base + margin:
        print(f"FAIL: {group}: CPU {after:.1f} % from 1 s after the flood > baseline {base:.1f} % + {margin} points", file=sys.stderr)
        ok = False
    if growth > 1024:
        print(f"FAIL: {group}: RSS without shared memory grew by {growth} kB > 1024 kB", file=sys.stderr)
        ok = False
sys.exit(0 if ok else 1)
PY
echo "ok: every receiver's CPU back to its baseline within 1 s of the flood, RSS (without shared memory) within +1 MiB"

python3 - "$WORK/out/summary.json" "$WORK/fuzz.txt" <<'PY' || fail "summary.json does not count the refused samples"
import json, sys
summary = json.load(open(sys.argv[1]))
written = {l.split()[1]: int(dict(kv.split("=") for kv in l.split()[2:])["body"]) for l in open(sys.argv[2]) if l.startswith("fuzz ")}
print("missed steps per host:", ", ".join(f"{k} {v.get('missed_steps')}" for k, v in summary["hosts"].items()))
ok = True
for component, topic in (("plant", "plant/cmd"), ("evaluator", "plant/cmd"), ("evaluator", "sensor/position")):
    c = summary["inputs"][component][topic]
    refused = c["rejected"].get("unknown_key", 0)
    # Not all need arrive: sensor/position is best effort, and robodds-fuzz leaves 1 s after its
    # last write, acknowledged or not (seen: 18,611 of 20,000 reliable plant/cmd under load 15).
    low = written[topic] // 2
    print(f"{component} {topic}: unknown_key {refused} of {written[topic]} written, accepted {c['accepted']}, rejected {c['rejected']}")
    if not low <= refused <= written[topic]:
        print(f"FAIL: {component} {topic}: unknown_key {refused}, expected {low}..{written[topic]}", file=sys.stderr)
        ok = False
sys.exit(0 if ok else 1)
PY
echo "ok: key_flood"

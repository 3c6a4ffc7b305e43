#!/usr/bin/env bash
# Runs the platform benchmarks against an existing build and prints markdown tables on stdout
# (progress and logs go to stderr and to $RESULTS). Builds nothing. See docs/performance.md.
#
#   bench/run_benchmarks.sh [BUILD_DIR]        (default: build, relative to the current directory)
#
# Environment (all optional):
#   SAMPLES=20000        latency_bench samples per run (after 1000 warm-up round trips)
#   LATENCY_RUNS=3       latency_bench runs per configuration (raw and runtime interleaved);
#                        the tables give the median over runs of each statistic
#   PROFILES="state lockstep"   QoS profiles for latency_bench
#   LOCKSTEP_RUNS=3      robodds runs of sim/scenarios/plant_smoke.yaml per deployment
#   LOCKSTEP_WINDOW=16   --lockstep-window of the pipelined multi-process variant
#   LOCKSTEP_DURATION=200  simulated seconds per lockstep run (20,001 ticks at 100 Hz): long
#                        enough that start-up (discovery, first-touch page faults) does not
#                        dominate the ticks/s figure; the scenario's own 20 s is 2,001 ticks
#   DOMAIN=150           DDS domain for latency_bench; robodds runs use DOMAIN+1
#   MIN_TIME=0.2         --benchmark_min_time for the Google Benchmark binaries
#   RESULTS=<tmp dir>    where raw outputs, logs and scenario outputs are kept
#
# Exit status: 0 if everything ran, 1 if some measurement failed (its cell says FAIL).
set -uo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=${1:-${BUILD_DIR:-build}}
if [[ ! -d $BUILD ]]; then
  echo "run_benchmarks.sh: build directory '$BUILD' not found (configure and build first)" >&2
  exit 2
fi
BUILD=$(cd "$BUILD" && pwd)
SAMPLES=${SAMPLES:-20000}
LATENCY_RUNS=${LATENCY_RUNS:-3}
PROFILES=${PROFILES:-state lockstep}
LOCKSTEP_RUNS=${LOCKSTEP_RUNS:-3}
LOCKSTEP_DURATION=${LOCKSTEP_DURATION:-200}
LOCKSTEP_WINDOW=${LOCKSTEP_WINDOW:-16}
DOMAIN=${DOMAIN:-150}
MIN_TIME=${MIN_TIME:-0.2}
RESULTS=${RESULTS:-$(mktemp -d /tmp/robodds-bench.XXXXXX)}
mkdir -p "$RESULTS"
cd "$ROOT" || exit 2

LATENCY_BENCH=$BUILD/bench/latency_bench
ROBODDS=$BUILD/tools/robodds/robodds
SCENARIO=sim/scenarios/plant_smoke.yaml
failures=0

log() { echo "[run_benchmarks] $*" >&2; }

# median of the numbers on stdin (empty if none)
median() {
  sort -g | awk '{ v[NR] = $1 } END { if (NR == 0) exit; if (NR % 2) printf "%.2f", v[(NR + 1) / 2];
                                       else printf "%.2f", (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}

# value of key=VALUE in a latency_bench output line
field() { tr ' ' '\n' <<<"$1" | sed -n "s/^$2=//p"; }

# percentage (b - a) / a ("n/a" if either is missing)
overhead() {
  if [[ -z $1 || -z $2 ]]; then echo "n/a"; return; fi
  awk -v a="$1" -v b="$2" 'BEGIN { printf "%+.1f %%", 100 * (b - a) / a }'
}

# ---------------------------------------------------------------------------------------------
echo "# robodds platform benchmarks"
echo
echo "- date: $(date -u '+%Y-%m-%d %H:%M UTC')"
echo "- commit: $(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)$(git -C "$ROOT" diff --quiet 2>/dev/null || echo ' (with uncommitted changes)')"
echo "- machine: $(nproc) CPUs, $(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1), $(uname -r)"
echo "- load average before the runs: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "- build: $BUILD ($(sed -n 's/^CMAKE_BUILD_TYPE:STRING=//p' "$BUILD/CMakeCache.txt" 2>/dev/null || echo '?'))"
echo "- raw outputs: $RESULTS"
echo

# ---------------------------------------------------------------------------------------------
# latency_table PROFILES: raw vs runtime, colocated and processes.
latency_table() {
  local profiles=$1
  echo "| deploy | QoS profile | raw median | runtime median | overhead (median) | raw p90 | runtime p90 | raw p99 | runtime p99 | overhead (p99) | raw max | runtime max |"
  echo "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
  local profile deploy r impl out line s
  for profile in $profiles; do
    for deploy in colocated processes; do
      declare -A stat=() m=()
      for ((r = 1; r <= LATENCY_RUNS; r++)); do
        for impl in raw runtime; do
          out=$RESULTS/latency-$impl-$deploy-$profile-$r.txt
          log "latency_bench $impl $deploy --profile $profile (run $r/$LATENCY_RUNS)"
          if timeout 300 "$LATENCY_BENCH" "$impl" "$deploy" --profile "$profile" \
               --samples "$SAMPLES" --domain "$DOMAIN" >"$out" 2>"$out.err"; then
            line=$(grep '^latency ' "$out" | tail -1)
            for s in median_us p90_us p99_us max_us; do
              stat[$impl.$s]+="$(field "$line" "$s") "
            done
          else
            log "latency_bench $impl $deploy $profile FAILED: $(tail -1 "$out.err")"
            failures=1
          fi
        done
      done
      for impl in raw runtime; do
        for s in median_us p90_us p99_us max_us; do
          m[$impl.$s]=$(tr ' ' '\n' <<<"${stat[$impl.$s]:-}" | grep . | median)
        done
      done
      echo "| $deploy | $profile | ${m[raw.median_us]:-FAIL} | ${m[runtime.median_us]:-FAIL} | $(overhead "${m[raw.median_us]}" "${m[runtime.median_us]}") | ${m[raw.p90_us]:-FAIL} | ${m[runtime.p90_us]:-FAIL} | ${m[raw.p99_us]:-FAIL} | ${m[runtime.p99_us]:-FAIL} | $(overhead "${m[raw.p99_us]}" "${m[runtime.p99_us]}") | ${m[raw.max_us]:-FAIL} | ${m[runtime.max_us]:-FAIL} |"
      unset stat m
    done
  done
}

# ticks_per_s of the "run" section of summary.json
ticks_per_s() {
  awk '/"run": *\{/ { inrun = 1 } inrun && /"ticks_per_s"/ { gsub(/[^0-9.]/, "", $2); print $2; exit }' "$1"
}

# lockstep_table: robodds run of the smoke scenario, co-located and across processes.
lockstep_table() {
  local no_plots=()
  if "$ROBODDS" run --help 2>&1 | grep -q -- --no-plots; then
    no_plots=(--no-plots)  # the PNGs are drawn after the timed part; skip them to save time
  fi
  local header="| deploy |" rule="|---|" r
  for ((r = 1; r <= LOCKSTEP_RUNS; r++)); do header+=" run $r |"; rule+="---:|"; done
  echo "$header median | target | met |"
  echo "$rule---:|---:|---|"
  local variant deploy extra target row values out v med met
  # Variants: co-located; one process per group with the strict lockstep (each tick waits for
  # every acknowledgement); the same with the pipelined coordinator (LOCKSTEP_WINDOW ticks
  # outstanding, byte-identical results: integration.determinism_paper1_window).
  for variant in colocated processes "processes-window$LOCKSTEP_WINDOW"; do
    deploy=${variant%%-*}
    extra=()
    [[ $variant == processes-window* ]] && extra=(--lockstep-window "$LOCKSTEP_WINDOW")
    [[ $deploy == colocated ]] && target=20000 || target=2000
    row="| $variant |"
    values=""
    for ((r = 1; r <= LOCKSTEP_RUNS; r++)); do
      out=$RESULTS/lockstep-$variant-$r
      rm -rf "$out"
      log "robodds run $SCENARIO --deploy $deploy (run $r/$LOCKSTEP_RUNS)"
      if timeout 600 "$ROBODDS" run "$SCENARIO" --out "$out" --domain $((DOMAIN + 1)) \
           --duration "$LOCKSTEP_DURATION" --deploy "$deploy" "${extra[@]}" "${no_plots[@]}" >"$out.log" 2>&1 && [[ -f $out/summary.json ]]; then
        v=$(ticks_per_s "$out/summary.json")
        row+=" ${v:-?} |"
        values+="$v "
      else
        log "robodds run --deploy $deploy FAILED: $(tail -1 "$out.log")"
        row+=" FAIL |"
        failures=1
      fi
    done
    med=$(tr ' ' '\n' <<<"$values" | grep . | median)
    if [[ -n $med ]]; then
      met=$(awk -v v="$med" -v t="$target" 'BEGIN { print (v >= t) ? "yes" : "NO" }')
      echo "$row $(printf '%.1f' "$med") | >= $target | $met |"
    else
      echo "$row FAIL | >= $target | NO |"
    fi
  done
}

echo "## One-hop latency (RobotState, half a ping-pong round trip, microseconds)"
echo
if [[ ! -x $LATENCY_BENCH ]]; then
  echo "(skipped: $LATENCY_BENCH not built)"
  failures=1
else
  echo "latency_bench --samples $SAMPLES, $LATENCY_RUNS runs per cell (raw and runtime interleaved), median over runs of each statistic."
  echo "colocated = one participant, two threads (intra-process delivery); processes = one participant per process."
  echo
  latency_table "$PROFILES"
  echo
  out=$RESULTS/latency-cv-colocated.txt
  log "latency_bench cv colocated"
  if "$LATENCY_BENCH" cv colocated --samples "$SAMPLES" >"$out" 2>"$out.err"; then
    line=$(grep '^latency ' "$out" | tail -1)
    echo "Floor without DDS (latency_bench cv colocated: the same exchange through a mutex + condition variable): median $(field "$line" median_us) us, p99 $(field "$line" p99_us) us."
  else
    echo "Floor without DDS: FAIL ($(tail -1 "$out.err"))"
    failures=1
  fi
fi
echo

# ---------------------------------------------------------------------------------------------
echo "## Lockstep throughput ($SCENARIO, ticks per second of wall time)"
echo
if [[ ! -x $ROBODDS ]]; then
  echo "(skipped: $ROBODDS not built)"
  failures=1
else
  lockstep_table
fi
echo

# ---------------------------------------------------------------------------------------------
# ---------------------------------------------------------------------------------------------
echo "## Google Benchmark binaries (--benchmark_min_time=$MIN_TIME)"
echo
mapfile -t benches < <(find "$BUILD" -type f -perm -u+x -name '*_bench' ! -name latency_bench ! -path '*/CMakeFiles/*' | sort)
if [[ ${#benches[@]} -eq 0 ]]; then
  echo "(none built under $BUILD)"
else
  echo "| binary | benchmark | time | CPU | iterations | counters |"
  echo "|---|---|---:|---:|---:|---|"
  for b in "${benches[@]}"; do
    name=${b#"$BUILD"/}
    json=$RESULTS/$(basename "$b").json
    log "$name --benchmark_min_time=$MIN_TIME"
    if ! timeout 900 "$b" --benchmark_min_time="$MIN_TIME" --benchmark_format=json >"$json" 2>"$json.err"; then
      echo "| $name | FAIL: $(tail -1 "$json.err") | | | | |"
      failures=1
      continue
    fi
    python3 - "$json" "$name" <<'PY' || { echo "| $name | (could not parse $json) | | | | |"; failures=1; }
import json, sys
data = json.load(open(sys.argv[1]))
standard = {"name", "run_name", "run_type", "repetitions", "repetition_index", "threads", "iterations",
            "real_time", "cpu_time", "time_unit", "family_index", "per_family_instance_index",
            "aggregate_name", "aggregate_unit", "error_occurred", "error_message", "label"}

def fmt(v):
    if v >= 1e9: return f"{v / 1e9:.3g} G"
    if v >= 1e6: return f"{v / 1e6:.3g} M"
    if v >= 1e3: return f"{v / 1e3:.3g} k"
    return f"{v:.3g}"

for b in data.get("benchmarks", []):
    if b.get("run_type") == "aggregate":
        continue
    if b.get("error_occurred"):
        print(f"| {sys.argv[2]} | {b['name']} | error: {b.get('error_message', '')} | | | |")
        continue
    unit = b.get("time_unit", "ns")
    counters = ", ".join(f"{k}={fmt(v)}/s" if k.endswith("_per_second") else f"{k}={fmt(v)}"
                         for k, v in b.items() if k not in standard and isinstance(v, (int, float)))
    print(f"| {sys.argv[2]} | {b['name']} | {b['real_time']:.4g} {unit} | {b['cpu_time']:.4g} {unit} | "
          f"{b['iterations']} | {counters} |")
PY
  done
fi
echo
echo "Targets (project issue): runtime hop overhead within 20 % of raw Fast DDS; lockstep >= 20,000 ticks/s co-located, >= 2,000 ticks/s across processes."
exit $failures

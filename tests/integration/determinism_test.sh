#!/usr/bin/env bash
# A scenario (default plant_smoke) co-located vs one process per group: byte-identical CSVs,
# identical metrics. Arguments after the domain: scenario name, optional duration override (s).
# $PROCESSES_ARGS (environment): extra options of the multi-process run, e.g. --lockstep-window 8.
source "$(dirname "$0")/lib.sh"
SCENARIO="$SRC/sim/scenarios/${4:-plant_smoke}.yaml"
DURATION=()
[[ -n "${5:-}" ]] && DURATION=(--duration "$5")
timeout -k 5 300 "$ROBODDS" run "$SCENARIO" "${DURATION[@]}" --out "$WORK/colocated" --domain "$DOMAIN" --no-plots >/dev/null
timeout -k 5 300 "$ROBODDS" run "$SCENARIO" "${DURATION[@]}" --out "$WORK/processes" --domain "$DOMAIN" --deploy processes ${PROCESSES_ARGS:-} --no-plots >/dev/null
same_outputs "$WORK/colocated" "$WORK/processes"
grep -q '"deploy": "processes"' "$WORK/processes/summary.json" || fail "run section missing"
echo "ok: $N_CSV CSV files and the metrics are identical co-located and across processes"

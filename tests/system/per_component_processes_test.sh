#!/usr/bin/env bash
# A paper scenario with EVERY component in its own process (one group per component) gives
# byte-identical CSVs and identical metrics to the co-located run, over the full duration, so
# the acceptance figures checked co-located hold across processes too.
# Arguments after the domain: scenario name, optional --lockstep-window for the processes run.
source "$(dirname "$0")/../integration/lib.sh"
NAME="$4"
WINDOW="${5:-1}"
SCENARIO="$SRC/sim/scenarios/$NAME.yaml"
# One group per component instance: drop the scenario's groups and list each component alone.
{
  sed '/^groups:/,$d' "$SCENARIO"
  echo "groups:"
  awk '/^components:/ { inside = 1; next } /^[a-z_]+:/ { inside = 0 }
       inside && match($0, /^  - (\{)?name: *[A-Za-z0-9_]+/) {
         name = substr($0, RSTART, RLENGTH); sub(/^  - (\{)?name: */, "", name); print "  " name ": [" name "]" }' "$SCENARIO"
} >"$WORK/per_component.yaml"
groups=$(sed -n '/^groups:/,$p' "$WORK/per_component.yaml" | grep -c ': \[')
components=$(awk '/^components:/ { inside = 1; next } /^[a-z_]+:/ { inside = 0 } inside && /^  - /' "$SCENARIO" | wc -l)
[[ $groups -eq $components && $groups -ge 4 ]] || fail "expected one group per component ($components), got $groups: $(cat "$WORK/per_component.yaml")"
timeout -k 5 300 "$ROBODDS" run "$WORK/per_component.yaml" --out "$WORK/colocated" --domain "$DOMAIN" --no-plots >"$WORK/colocated.log" 2>&1 \
  || fail "co-located run failed: $(tail -5 "$WORK/colocated.log")"
timeout -k 5 600 "$ROBODDS" run "$WORK/per_component.yaml" --out "$WORK/processes" --domain "$DOMAIN" --deploy processes \
  --lockstep-window "$WINDOW" --no-plots >"$WORK/processes.log" 2>&1 || fail "processes run failed: $(tail -5 "$WORK/processes.log")"
same_outputs "$WORK/colocated" "$WORK/processes"
echo "ok: $NAME with $groups processes (one per component, window $WINDOW): $N_CSV CSV files and the metrics identical to co-located"

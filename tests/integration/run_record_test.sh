#!/usr/bin/env bash
# `robodds run --record FILE`: the run records the topics its components publish, from inside the
# run (a run_recorder component in the evaluator's group, reading through lockstep-gated inputs).
#   - bad input: an unwritable --record path, an unknown --record-topics name, a bad
#     --record-compression: one line, exit 2, before the run starts;
#   - lockstep determinism: plant_smoke (5 s) and paper1_waypoints (20 s) each recorded co-located
#     and with --deploy processes give byte-identical files (cmp);
#   - paper1_waypoints' file read by the official reader with Foxglove's omgidl decoder
#     (tests/npm/check_mcap.mjs): every topic the evaluator records has as many messages as CSV
#     rows, each row's values equal the decoded message's, log_time = the sample's step x step_s
#     (ns) and publish_time = its stamp.
# Args: ROBODDS SRC DOMAIN. Needs node and tests/npm/node_modules (scripts/npm_setup.sh). ~15 s.
source "$(dirname "$0")/lib.sh"
CHECK="$SRC/tests/npm/check_mcap.mjs"
command -v node >/dev/null || fail "node not found (scripts/setup.sh installs nodejs)"
[[ -d $SRC/tests/npm/node_modules/@mcap/core ]] || fail "tests/npm/node_modules missing: run scripts/npm_setup.sh"
SMOKE="$SRC/sim/scenarios/plant_smoke.yaml"
PAPER1="$SRC/sim/scenarios/paper1_waypoints.yaml"

expect_error 2 "--record $WORK/no/dir/x.mcap: cannot write it \(No such file or directory\)" -- \
  "$ROBODDS" run "$SMOKE" --record "$WORK/no/dir/x.mcap" --out "$WORK/bad" --no-plots --domain "$DOMAIN"
expect_error 2 "unknown topic 'plant/stat'" -- \
  "$ROBODDS" run "$SMOKE" --record "$WORK/x.mcap" --record-topics plant/state,plant/stat --out "$WORK/bad" --no-plots --domain "$DOMAIN"
expect_error 2 "unknown compression 'gzip'" -- \
  "$ROBODDS" run "$SMOKE" --record "$WORK/x.mcap" --record-compression gzip --out "$WORK/bad" --no-plots --domain "$DOMAIN"
[[ ! -e $WORK/bad/summary.json ]] || fail "a refused --record still ran"

record() {  # record NAME SCENARIO DEPLOY SECONDS
  local rc=0
  timeout -k 5 120 "$ROBODDS" run "$2" --deploy "$3" --duration "$4" --domain "$DOMAIN" --out "$WORK/$1" --no-plots \
    --record "$WORK/$1.mcap" >"$WORK/$1.log" 2>&1 || rc=$?
  [[ $rc -eq 0 ]] || fail "robodds run $2 --deploy $3 --record exited $rc: $(tail -20 "$WORK/$1.log")"
  grep -q '"status": "completed"' "$WORK/$1/summary.json" || fail "$1: the run did not complete"
}
for scenario in smoke paper1; do
  file=$SMOKE seconds=5
  [[ $scenario == paper1 ]] && file=$PAPER1 seconds=20
  record "${scenario}_colocated" "$file" colocated "$seconds"
  record "${scenario}_processes" "$file" processes "$seconds"
  cmp "$WORK/${scenario}_colocated.mcap" "$WORK/${scenario}_processes.mcap" ||
    fail "$scenario: the recordings co-located and across processes differ (lockstep must give the same bytes)"
  echo "ok: $scenario: co-located and --deploy processes recordings byte-identical ($(stat -c %s "$WORK/${scenario}_colocated.mcap") bytes)"
done

info="$("$ROBODDS" info "$WORK/paper1_colocated.mcap" 2>&1)" || fail "robodds info: $info"
grep -q "^summary: *present, CRCs valid" <<<"$info" || fail "not a whole file: $info"
official="$(timeout -k 5 60 node "$CHECK" "$WORK/paper1_colocated.mcap" 2>&1)" || fail "official reader: $(tail -3 <<<"$official")"
echo "$official" >"$WORK/paper1.jsonl"
python3 - "$WORK/paper1.jsonl" "$WORK/paper1_colocated" <<'PY' || fail "the recording does not hold what the run's CSVs hold"
import csv, glob, json, os, sys
STEP_NS = 10_000_000  # paper1_waypoints: step_s 0.01
messages = [json.loads(line) for line in open(sys.argv[1])]
by_topic = {}
for m in messages:
    by_topic.setdefault(m["topic"], []).append(m)

def flat(value, prefix, out):
    if isinstance(value, dict):
        for k, v in value.items():
            flat(v, f"{prefix}.{k}" if prefix else k, out)
    elif isinstance(value, list):
        for i, v in enumerate(value):
            flat(v, f"{prefix}[{i}]", out)
    else:
        out[prefix] = value
    return out

csvs = sorted(glob.glob(os.path.join(sys.argv[2], "*.csv")))
assert len(csvs) == 7, csvs
for path in csvs:
    rows = list(csv.DictReader(open(path)))
    topic = next(t for t in by_topic if t.replace("/", "_") + ".csv" == os.path.basename(path))
    recorded = by_topic[topic]
    assert len(recorded) == len(rows), f"{topic}: {len(recorded)} messages in the file, {len(rows)} CSV rows"
    decoded = {(m["value"]["robot_id"], m["value"]["header"]["step"]): m for m in recorded}
    compared = 0
    for r in rows:
        m = decoded[(int(r["robot_id"]), int(r["header.step"]))]
        values = flat(m["value"], "", {})
        for column, text in r.items():
            if column in values and not isinstance(values[column], str):
                assert float(text) == float(values[column]), f"{topic} {column}: CSV {text}, file {values[column]}"
                compared += 1
        step = int(r["header.step"])
        assert int(m["log_time"]) == step * STEP_NS, f"{topic}: log_time {m['log_time']} at step {step}"
        assert int(m["publish_time"]) == int(r["header.stamp_ns"]), f"{topic}: publish_time {m['publish_time']}"
    print(f"ok: {topic}: {len(rows)} messages = CSV rows, {compared} values equal (official decoder), log_time = step x step_s")
assert len(by_topic) == len(csvs), f"{len(by_topic)} channels with messages, {len(csvs)} CSVs: {sorted(by_topic)}"
PY
echo "ok: run_record"

#!/usr/bin/env bash
# `robodds sweep` (issue 13, item 4) on real `robodds run` processes, two workers on domains
# DOMAIN and DOMAIN + 1:
# 1. plant_smoke over 3 seeds x a 2-value grid: 6 runs; every run's CSVs are byte-identical to a
#    lone `robodds run` with the same seed and --set (no cross-talk between the workers, the grid
#    really applied); runs.csv has a row per run, summary.csv a row per combination and metric,
#    and its mean is the mean of the runs' summary.json values.
# 2. A combination whose value fails at run time (position_sensor.rate_hz=7 passes the type and range
#    checks, but 7 Hz does not divide the 100 Hz simulation) is recorded as failed with the run's
#    error and the sweep goes on; the sweep exits 1. Runs past --run-timeout are killed and recorded
#    as failed, also by --aggregate (which reads outcome.json, else summary.json's status).
# 3. --plan, then the generated Slurm array script per task (--run-index K) in separate invocations,
#    then --aggregate: the same tables; the generated Kubernetes Indexed Job parses and names the runs
#    and runs as the image's user with fsGroup; --domain-offset N puts task K on domain (N + K) % 233.
# 4. Bad input: errors before anything runs.
source "$(dirname "$0")/lib.sh"
S="$SRC/sim/scenarios/plant_smoke.yaml"
SWEEP=(timeout -k 5 300 "$ROBODDS" sweep "$S" --seeds 1-3 --set position_sensor.noise_var_x_m2=0.5,4 --duration 3 --jobs 2 --domain "$DOMAIN")
"${SWEEP[@]}" --out "$WORK/a" >"$WORK/a.log" 2>&1 || fail "sweep failed: $(tail -5 "$WORK/a.log")"
grep -q "sweep: 6/6 runs done, 0 failed" "$WORK/a.log" || fail "no progress line for the last run: $(cat "$WORK/a.log")"
[[ $(wc -l <"$WORK/a/runs.csv") -eq 7 ]] || fail "runs.csv: expected 6 runs: $(cat "$WORK/a/runs.csv")"
# Run 4 is the second combination (noise 4) with seed 2.
timeout -k 5 60 "$ROBODDS" run "$S" --seed 2 --set position_sensor.noise_var_x_m2=4 --duration 3 --domain "$DOMAIN" \
  --out "$WORK/lone" --no-plots >"$WORK/lone.log" 2>&1 || fail "lone run failed: $(tail -3 "$WORK/lone.log")"
same_outputs "$WORK/lone" "$WORK/a/runs/0004"
cmp -s "$WORK/a/runs/0001/sensor_position.csv" "$WORK/a/runs/0004/sensor_position.csv" && fail "the grid value was not applied (runs 1 and 4 equal)"
python3 - "$WORK/a" <<'PY' || fail "summary.csv does not match the runs"
import csv, json, statistics, sys
d = sys.argv[1]
rows = list(csv.DictReader(open(d + "/summary.csv")))
combos = {r["position_sensor.noise_var_x_m2"] for r in rows}
assert combos == {"0.5", "4"}, combos
runs = list(csv.DictReader(open(d + "/runs.csv")))
assert all(r["status"] == "ok" for r in runs), runs
metric = "robots.1.measurement_rmse_m"  # depends on the seed and on the grid's noise
means = {}
for value in ("0.5", "4"):
    row = next(r for r in rows if r["metric"] == metric and r["position_sensor.noise_var_x_m2"] == value)
    vals = []
    for r in runs:
        if r["position_sensor.noise_var_x_m2"] == value:
            m = json.load(open("%s/runs/%04d/summary.json" % (d, int(r["run"]))))["metrics"]
            for part in metric.split("."):
                m = m[part]
            vals.append(m)
    assert int(row["n"]) == 3 and abs(float(row["mean"]) - statistics.mean(vals)) < 1e-9, (row, vals)
    assert abs(float(row["std"]) - statistics.stdev(vals)) < 1e-9, (row, vals)
    means[value] = statistics.mean(vals)
assert means["4"] > 1.5 * means["0.5"], means  # the grid value reached the sensor
print("ok: summary.csv", metric, "matches the runs' summary.json")
PY

# 2. A failing combination.
rc=0
timeout -k 5 300 "$ROBODDS" sweep "$S" --seeds 1-2 --set position_sensor.rate_hz=10,7 --duration 2 --jobs 2 --domain "$DOMAIN" \
  --out "$WORK/f" >"$WORK/f.log" 2>&1 || rc=$?
[[ $rc -eq 1 ]] || fail "a sweep with failed runs exited $rc: $(tail -5 "$WORK/f.log")"
[[ $(grep -c ",ok," "$WORK/f/runs.csv") -eq 2 && $(grep -c ",failed," "$WORK/f/runs.csv") -eq 2 ]] || fail "runs.csv: $(cat "$WORK/f/runs.csv")"
grep -q "failed,2,.*rate_hz: 7.* Hz is not the simulation rate" "$WORK/f/runs.csv" || fail "the failure reason is not recorded: $(cat "$WORK/f/runs.csv")"
grep -q "0 runs ok, 2 failed" "$WORK/f/summary.md" || fail "summary.md: $(cat "$WORK/f/summary.md")"
rc=0
timeout -k 5 120 "$ROBODDS" sweep "$S" --seeds 1-2 --duration 5000 --run-timeout 0.3 --jobs 2 --domain "$DOMAIN" --out "$WORK/t" \
  >"$WORK/t.log" 2>&1 || rc=$?
[[ $rc -eq 1 && $(grep -c ",failed," "$WORK/t/runs.csv") -eq 2 ]] || fail "runs past --run-timeout: exit $rc, $(cat "$WORK/t/runs.csv")"
grep -q "did not finish within 0.3 s (--run-timeout) and was killed" "$WORK/t/runs/0000/run.log" || fail "no timeout note in run.log"
rc=0
"$ROBODDS" sweep --aggregate --out "$WORK/t" >"$WORK/t.agg.log" 2>&1 || rc=$?
[[ $rc -eq 1 && $(grep -c ",failed," "$WORK/t/runs.csv") -eq 2 ]] || fail "--aggregate counted killed runs as ok: exit $rc, $(cat "$WORK/t/runs.csv")"
rm "$WORK"/t/runs/*/outcome.json  # as if their workers had died: summary.json's status alone decides
rc=0
"$ROBODDS" sweep --aggregate --out "$WORK/t" >"$WORK/t.agg.log" 2>&1 || rc=$?
[[ $rc -eq 1 && $(grep -c ",failed," "$WORK/t/runs.csv") -eq 2 ]] || fail "--aggregate without outcome.json: exit $rc, $(cat "$WORK/t/runs.csv")"
echo "ok: failed and timed-out runs recorded (also by --aggregate), the sweep went on"

# 3. Plan, run each index on its own (as a batch array task would), aggregate.
timeout -k 5 60 "$ROBODDS" sweep "$S" --seeds 1-3 --set position_sensor.noise_var_x_m2=0.5,4 --duration 3 --domain "$DOMAIN" \
  --out "$WORK/p" --plan >"$WORK/p.log" 2>&1 || fail "--plan failed: $(cat "$WORK/p.log")"
[[ $(grep -vc "^#" "$WORK/p/plan.txt") -eq 6 && ! -d "$WORK/p/runs" ]] || fail "--plan: $(ls "$WORK/p"; cat "$WORK/p/plan.txt")"
# The generated Slurm script runs the array tasks here as sbatch would (SLURM_ARRAY_TASK_ID set, in
# any order), on domain DOMAIN + 1 (tasks 0-5 take TASK % 233, so move them: --domain via a shim).
timeout -k 5 60 "$ROBODDS" sweep --emit slurm --out "$WORK/p" >>"$WORK/p.log" 2>&1 || fail "--emit slurm failed: $(tail -3 "$WORK/p.log")"
bash -n "$WORK/p/slurm.sbatch" || fail "slurm.sbatch is not valid bash"
grep -q "^#SBATCH --array=0-5$" "$WORK/p/slurm.sbatch" || fail "slurm.sbatch: no --array=0-5: $(cat "$WORK/p/slurm.sbatch")"
cat >"$WORK/robodds_on_test_domain" <<SHIM
#!/bin/bash
# robodds with the task's --domain K moved to $DOMAIN + 1 + K % 2 (this test's domains)
args=(); while ((\$#)); do if [[ \$1 == --domain ]]; then args+=(--domain \$(( $DOMAIN + \$2 % 2 ))); shift 2; else args+=("\$1"); shift; fi; done
exec "$ROBODDS" "\${args[@]}"
SHIM
chmod +x "$WORK/robodds_on_test_domain"
for k in 5 0 3 1 4 2; do
  SLURM_ARRAY_TASK_ID=$k ROBODDS="$WORK/robodds_on_test_domain" timeout -k 5 60 bash "$WORK/p/slurm.sbatch" >>"$WORK/p.log" 2>&1 \
    || fail "array task $k failed: $(tail -3 "$WORK/p.log")"
done
out="$(env -u SLURM_ARRAY_TASK_ID ROBODDS="$WORK/robodds_on_test_domain" bash "$WORK/p/slurm.sbatch" 2>&1)" \
  && fail "slurm.sbatch ran outside an array task: $out"
grep -q "not a Slurm array task" <<<"$out" || fail "slurm.sbatch outside an array task: $out"
timeout -k 5 60 "$ROBODDS" sweep --aggregate --out "$WORK/p" >>"$WORK/p.log" 2>&1 || fail "--aggregate failed: $(tail -3 "$WORK/p.log")"
cmp "$WORK/a/summary.csv" "$WORK/p/summary.csv" || fail "--aggregate of the separate runs differs from the sweep's summary.csv"
echo "ok: --plan, the Slurm array script (--run-index per task) and --aggregate give the sweep's table"
timeout -k 5 60 "$ROBODDS" sweep --emit k8s --out "$WORK/p" --jobs 3 --image robodds:test >>"$WORK/p.log" 2>&1 || fail "--emit k8s failed"
python3 - "$WORK/p/k8s-job.yaml" <<'PY' || fail "k8s-job.yaml: $(cat "$WORK/p/k8s-job.yaml")"
import sys, yaml
job = yaml.safe_load(open(sys.argv[1]))
assert job["apiVersion"] == "batch/v1" and job["kind"] == "Job", job
spec = job["spec"]
assert spec["completionMode"] == "Indexed" and spec["completions"] == 6 and spec["parallelism"] == 3, spec
pod = spec["template"]["spec"]
c = pod["containers"][0]
assert c["image"] == "robodds:test" and "--run-index \"$JOB_COMPLETION_INDEX\" --out /sweep" in c["args"][0], c
assert c["volumeMounts"][0]["mountPath"] == "/sweep" and pod["volumes"][0]["persistentVolumeClaim"]["claimName"] == "robodds-sweep", pod
assert pod["securityContext"] == {"runAsUser": 10001, "runAsGroup": 10001, "fsGroup": 10001}, pod  # the image's user may write the volume
print("ok: k8s-job.yaml is an Indexed Job of the 6 runs")
PY
# --domain-offset N moves every task's domain to (N + K) % 233 (two sweeps sharing nodes).
timeout -k 5 60 "$ROBODDS" sweep --emit slurm --out "$WORK/p" --domain-offset 230 >>"$WORK/p.log" 2>&1 || fail "--emit slurm --domain-offset failed"
for k in 0 5; do
  got="$(SLURM_ARRAY_TASK_ID=$k ROBODDS=echo bash "$WORK/p/slurm.sbatch")"
  [[ "$got" == *" --domain $(( (230 + k) % 233 ))" ]] || fail "--domain-offset 230, task $k: $got"
done
echo "ok: --domain-offset 230 puts tasks 0 and 5 on domains 230 and 2"

# 4. Bad input: an error naming what is wrong, nothing run.
expect_error 2 "--seeds '5-3': the range '5-3' is empty" -- "$ROBODDS" sweep "$S" --seeds 5-3 --out "$WORK/b1"
expect_error 2 "--seeds 'x': 'x' is not a seed" -- "$ROBODDS" sweep "$S" --seeds x --out "$WORK/b2"
expect_error 2 "--jobs must be at least 1" -- "$ROBODDS" sweep "$S" --seeds 1 --jobs 0 --out "$WORK/b3"
expect_error 2 "--set plant.nope: component 'plant' \(plant\) of .*plant_smoke.yaml: --set: nope: unknown parameter \(known: " -- \
  "$ROBODDS" sweep "$S" --seeds 1 --set plant.nope=1,2 --out "$WORK/b4"
expect_error 2 "--set 'plant.rate_hz': expected component.parameter=value" -- "$ROBODDS" sweep "$S" --seeds 1 --set plant.rate_hz --out "$WORK/b5"
expect_error 2 "--set plant.command_timeout_s: component 'plant' \(plant\) of .*: --set: command_timeout_s: must be > 0 and finite \(got -1\)" -- \
  "$ROBODDS" sweep "$S" --seeds 1 --set plant.command_timeout_s=0.5,-1 --out "$WORK/b6"
expect_error 2 "--set position_sensor.rate_hz: .*: --set: rate_hz: expected a number, got 'ten'" -- \
  "$ROBODDS" sweep "$S" --seeds 1 --set position_sensor.rate_hz=ten --out "$WORK/b7"
expect_error 2 "--out $WORK/a holds another sweep \(sweep.json\)" -- "$ROBODDS" sweep "$S" --seeds 1 --out "$WORK/a"
expect_error 2 "--domain-offset '233': must be 0 to 232" -- "$ROBODDS" sweep --emit slurm --out "$WORK/p" --domain-offset 233
expect_error 2 "--domain-offset 'x': not an integer" -- "$ROBODDS" sweep --emit k8s --out "$WORK/p" --domain-offset x
expect_error 2 "--domain-offset works only with --emit" -- "$ROBODDS" sweep "$S" --seeds 1 --domain-offset 3 --out "$WORK/b8"
for d in b1 b2 b3 b4 b5 b6 b7 b8; do
  [[ ! -e "$WORK/$d/runs" ]] || fail "$d: a run started despite the error"
done

#!/usr/bin/env bash
# Numbers and paths are checked before anything runs (issue #9, findings 7 and 8): a step count
# that does not fit, NaN, negative or overflowing --duration/--seed, a directory as the scenario
# and an --out that cannot be a writable directory each give exit 2, one error line naming the
# value or path, and no tick runs (no "robodds run ...: N steps" banner, no output written).
source "$(dirname "$0")/lib.sh"
S="$SRC/sim/scenarios/plant_smoke.yaml"
scenario_with() {  # scenario_with NAME SED-EXPR: a copy of plant_smoke edited by sed
  sed "$2" "$S" >"$WORK/$1.yaml"
  echo "$WORK/$1.yaml"
}
R=("$ROBODDS" run --domain "$DOMAIN" --no-plots)
H=("$ROBODDS" host --scenario "$S" --group sim --domain "$DOMAIN" --start-timeout 1)

# Step counts: 1e-25 s used to die of SIGFPE, 1e-18 s and 1e300 s overflowed the step count.
expect_error 2 "tiny\.yaml: step_s: duration 20 s at step 1e-25 s is 2e\+26 steps.*more than 1099511627776" -- \
  "${R[@]}" --out "$WORK/o1" "$(scenario_with tiny 's/^step_s: .*/step_s: 1e-25/')"
expect_error 2 "small\.yaml: step_s: duration 20 s at step 1e-18 s is 2e\+19 steps.*more than 1099511627776" -- \
  "${R[@]}" --out "$WORK/o2" "$(scenario_with small 's/^step_s: .*/step_s: 1e-18/')"
expect_error 2 "--duration: duration 1e\+300 s at step 0\.01 s is 1e\+302 steps.*more than 1099511627776" -- \
  "${R[@]}" --out "$WORK/o3" "$S" --duration 1e300
expect_error 2 "--duration: duration 1e\+300 s at step 0\.01 s is 1e\+302 steps" -- "${H[@]}" --duration 1e300
expect_error 2 "--step: duration 10 s at step 1e-25 s is 1e\+26 steps" -- \
  "$ROBODDS" host --type plant --robot 1 --step 1e-25 --duration 10 --domain "$DOMAIN" --start-timeout 1
# NaN, negative and overflowing values of --duration and --seed.
expect_error 2 "--duration: .*nan" -- "${R[@]}" --out "$WORK/o4" "$S" --duration nan
expect_error 2 "--duration: .*nan" -- "${H[@]}" --duration nan
expect_error 2 "--duration: .*-5" -- "${R[@]}" --out "$WORK/o5" "$S" --duration -5
expect_error 2 "--seed: .*-1" -- "${R[@]}" --out "$WORK/o6" "$S" --seed -1
expect_error 2 "--seed: .*-1" -- "${H[@]}" --seed -1
expect_error 2 "--seed: .*18446744073709551616" -- "${R[@]}" --out "$WORK/o7" "$S" --seed 18446744073709551616
# The scenario must be a readable file: a directory used to give a libstdc++ message naming no file.
mkdir "$WORK/adir"
expect_error 2 "adir: is a directory, not a scenario file" -- "${R[@]}" --out "$WORK/o8" "$WORK/adir"
# $ROBODDS_DOMAIN_ID must be the whole number: "7x" used to be read as domain 7.
expect_error 2 "ROBODDS_DOMAIN_ID: expected a whole number 0\.\.232, got '7x'" -- \
  env ROBODDS_DOMAIN_ID=7x "$ROBODDS" run --no-plots --duration 0.1 --out "$WORK/o9" "$S"
for out in o1 o2 o3 o4 o5 o6 o7 o8 o9; do
  [[ ! -e "$WORK/$out" ]] || fail "--out $out was created although the input was refused"
done

# --out must be a creatable, writable directory, checked before the first tick (it used to be
# found out after the run, losing the results).
touch "$WORK/afile"
expect_error 2 "afile: .*not a directory" -- "${R[@]}" "$S" --duration 0.5 --out "$WORK/afile"
expect_error 2 "afile/below: cannot create the output directory" -- "${R[@]}" "$S" --duration 0.5 --out "$WORK/afile/below"
# Unwritable: the tests run as root, for whom a mode 0555 directory is still writable, so use
# /proc: /proc/robodds-out cannot be created, /proc/self exists but takes no new files.
expect_error 2 "/proc/robodds-out: cannot create the output directory" -- "${R[@]}" "$S" --duration 0.5 --out /proc/robodds-out
expect_error 2 "/proc/self: the output directory is not writable" -- "${R[@]}" "$S" --duration 0.5 --out /proc/self
expect_error 2 "afile: .*not a directory" -- "${H[@]}" --out "$WORK/afile"
expect_error 2 "/proc/self: the output directory is not writable" -- \
  "$ROBODDS" host --type evaluator --robot 1 --out /proc/self --domain "$DOMAIN" --start-timeout 1
echo "ok: bad numbers and paths refused before the first tick"

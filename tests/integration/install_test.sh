#!/usr/bin/env bash
# The installed tree works on its own: `cmake --install BUILD --prefix P` gives P/bin/robodds and
# P/share/robodds/..., and the installed binary, started outside the source tree with
# ROBODDS_SHARE_DIR unset, finds its QoS profiles (and report.py) in P/share/robodds
# (runtime/config/share_dir.hpp) and produces byte for byte what the build-tree binary produces:
#   0. every registered component's defaults file and executable robodds-<type> is installed;
#   1. `P/bin/robodds run` of plant_smoke, co-located, is byte-identical to the build-tree run;
#   2. so is a run whose sensing group is the installed component executable
#      P/bin/robodds-position-sensor, started without the scenario file (robots, name, seed on
#      its command line), the other groups and the lockstep coordinator from the build tree;
#   3. the installed binary reads P/share/robodds, not the source tree it was built from: with an
#      installed QoS profile file broken it fails naming that file; ROBODDS_SHARE_DIR still wins.
# Extra argument: the build directory to install from.
source "$(dirname "$0")/lib.sh"
BUILD="$4"
PREFIX="$WORK/prefix"
INSTALLED="$PREFIX/bin/robodds"
SHARE="$PREFIX/share/robodds"
S="$SRC/sim/scenarios/plant_smoke.yaml"
S_INSTALLED="$SHARE/sim/scenarios/plant_smoke.yaml"
unset ROBODDS_SHARE_DIR

cmake --install "$BUILD" --prefix "$PREFIX" >"$WORK/install.log" 2>&1 || fail "cmake --install failed: $(cat "$WORK/install.log")"
for f in bin/robodds share/robodds/deploy/qos/robodds_qos.xml share/robodds/sim/report/report.py \
         share/robodds/sim/scenarios/plant_smoke.yaml share/robodds/components/pf_estimator/config/pf_estimator.params.yaml \
         share/robodds/sim/plant/config/plant.params.yaml; do
  [[ -e "$PREFIX/$f" ]] || fail "cmake --install did not install $f: $(find "$PREFIX" -type f)"
done
cmp "$S" "$S_INSTALLED" || fail "the installed scenario differs from the source one"
# Every registered component's defaults file is installed (a new component folder that forgot
# robodds_install_share fails here, not on a robot).
defaults=$("$INSTALLED" components | grep -oE '[A-Za-z0-9_./-]+\.params\.yaml' | sort -u) || fail "robodds components listed no defaults file"
for f in $defaults; do
  [[ -f "$SHARE/$f" ]] || fail "defaults file $f of a registered component is not installed (robodds_component in its folder)"
done
echo "ok: $(wc -w <<<"$defaults") defaults files of registered components installed"
# ... and so is its executable robodds-<type>.
types=$("$INSTALLED" components | grep -oE '^[a-z][a-z0-9_]*') || fail "robodds components listed no type"
for t in $types; do
  [[ -x "$PREFIX/bin/robodds-${t//_/-}" ]] || fail "component executable robodds-${t//_/-} is not installed"
done
echo "ok: $(wc -w <<<"$types") component executables installed"

"$ROBODDS" --log warn run "$S" --domain "$DOMAIN" --out "$WORK/reference" --no-plots >"$WORK/reference.log" 2>&1 ||
  fail "build-tree co-located run failed: $(cat "$WORK/reference.log")"

# 1. Co-located, from a directory outside the source tree, results relative to it.
mkdir -p "$WORK/elsewhere"
(cd "$WORK/elsewhere" && "$INSTALLED" --log warn run "$S_INSTALLED" --domain "$DOMAIN" --out out/plant_smoke --no-plots) \
  >"$WORK/installed.log" 2>&1 || fail "installed co-located run failed: $(cat "$WORK/installed.log")"
same_outputs "$WORK/reference" "$WORK/elsewhere/out/plant_smoke"
echo "ok: installed co-located run byte-identical to the build-tree run ($N_CSV CSVs)"

# 2. The sensing group from the installed binary, the rest from the build tree.
out="$WORK/groups"
C=(--run-id "$$" --domain "$DOMAIN" --start-timeout 20 --input-timeout 20)
pids=()
for g in control sim evaluation; do
  "$ROBODDS" --log warn host --scenario "$S" --group "$g" --out "$out" "${C[@]}" >"$WORK/group.$g.log" 2>&1 &
  pids+=("$!")
  cleanup_pids+=("$!")
done
# The sensing group is the installed component executable, without the scenario file: the same
# instance name, seed and robots as in plant_smoke, in the group the coordinator waits for.
SENSOR="$PREFIX/bin/robodds-position-sensor"
(cd "$WORK/elsewhere" && exec "$SENSOR" --name position_sensor --member sensing --seed 42 \
  --robot 1 --robot 2 --robot 3 "${C[@]}") >"$WORK/group.sensing.log" 2>&1 &
pids+=("$!")
cleanup_pids+=("$!")
rc=0
timeout -k 5 120 "$ROBODDS" --log warn host --scenario "$S" --coordinate "${C[@]}" >"$WORK/coordinator.log" 2>&1 || rc=$?
for pid in "${pids[@]}"; do
  wait "$pid" || rc=$((rc == 0 ? 1 : rc))
done
[[ $rc -eq 0 ]] || fail "run with an installed group host failed (exit $rc): $(tail -n 3 "$WORK"/group.*.log "$WORK/coordinator.log")"
same_outputs "$WORK/reference" "$out"
echo "ok: installed robodds-position-sensor (no scenario file) with build-tree groups and coordinator byte-identical to co-located ($N_CSV CSVs)"

# The component executable's own input handling: --help lists its parameters; a bad parameter
# file names file and key; no robot is one clear error.
sensor_help="$("$SENSOR" --help)" || fail "robodds-position-sensor --help failed"  # whole: no SIGPIPE under pipefail
grep -q "noise_var_x_m2" <<<"$sensor_help" || fail "robodds-position-sensor --help does not list its parameters"
printf 'rate_hz: -1\n' >"$WORK/bad_sensor.yaml"
expect_error 2 "$WORK/bad_sensor.yaml.*rate_hz" -- "$SENSOR" --robot 1 --params "$WORK/bad_sensor.yaml" --domain "$DOMAIN"
expect_error 2 "give the robots it serves with --robot" -- "$SENSOR" --domain "$DOMAIN"

# 3. The share dir really is the installed one: with the installed QoS profile file broken (the
#    source tree's is intact) the installed binary fails and names the installed path.
QOS="$SHARE/deploy/qos/robodds_qos.xml"
cp "$QOS" "$QOS.saved"
echo '<dds><profiles><broken' >"$QOS"
(cd "$WORK/elsewhere" && expect_error 2 "$QOS" -- \
  "$INSTALLED" run "$S_INSTALLED" --domain "$DOMAIN" --duration 0.1 --out out/missing --no-plots)
# ROBODDS_SHARE_DIR overrides the installed tree (here: back to the source tree).
ROBODDS_SHARE_DIR="$SRC" "$INSTALLED" --log warn run "$S_INSTALLED" --domain "$DOMAIN" --duration 0.1 \
  --out "$WORK/env_share" --no-plots >"$WORK/env_share.log" 2>&1 ||
  fail "installed binary with ROBODDS_SHARE_DIR=source tree failed: $(cat "$WORK/env_share.log")"
mv "$QOS.saved" "$QOS"
echo "ok: the installed binary reads $SHARE; ROBODDS_SHARE_DIR overrides it"

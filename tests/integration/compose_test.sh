#!/usr/bin/env bash
# deploy/compose/*.yml: valid for docker-compose, consistent with the repository (groups,
# profiles, image), identical to what `robodds deploy compose` generates now,
# and the commands they run complete a lockstep run that is byte-identical to the co-located
# one. No container engine is needed: `docker-compose config` validates without one, and the
# services' commands are run as local processes.
source "$(dirname "$0")/lib.sh"
COMPOSE_DIR="$SRC/deploy/compose"
CHECK=(python3 "$SRC/tests/integration/compose_check.py" "$ROBODDS" "$SRC")

# scripts/setup.sh installs docker-compose, so its absence is a broken set-up, not a skip.
command -v docker-compose >/dev/null || fail "docker-compose not found (scripts/setup.sh installs it)"
python3 -c 'import yaml' 2>/dev/null || fail "python3-yaml not found (a dependency of docker-compose)"

shopt -s nullglob
files=("$COMPOSE_DIR"/*.yml)
((${#files[@]} >= 6)) || fail "expected at least 6 compose files in $COMPOSE_DIR, found ${#files[@]}"

# 1. Every shipped file is valid and consistent with the repository.
for f in "${files[@]}"; do
  out="$(docker-compose -f "$f" config -q 2>&1)" || fail "docker-compose -f $f config -q: $out"
  echo "ok: docker-compose config -q $(basename "$f")"
  "${CHECK[@]}" "$f"
done

# 2. No drift: regenerating gives byte-identical files (and no file is missing or extra).
"$COMPOSE_DIR/regenerate.sh" "$ROBODDS" "$WORK/regenerated" >/dev/null
cp "$COMPOSE_DIR/README.md" "$COMPOSE_DIR/regenerate.sh" "$WORK/regenerated/"
diff -r "$COMPOSE_DIR" "$WORK/regenerated" >"$WORK/drift.txt" ||
  fail "deploy/compose differs from a fresh deploy/compose/regenerate.sh (run it and commit): $(head -c 2000 "$WORK/drift.txt")"
echo "ok: shipped files equal the generated ones"

# 3. The checker itself catches a broken file (unknown group, shared memory on a bridge).
sed -e "s#\.\./\.\.#$SRC#g" -e 's/--group, sim,/--group, simm,/' "$COMPOSE_DIR/plant_smoke.yml" >"$WORK/broken_group.yml"
"${CHECK[@]}" "$WORK/broken_group.yml" 2>"$WORK/broken.txt" && fail "checker accepted an unknown group"
grep -q "group 'simm' is not a group of the scenario" "$WORK/broken.txt" || fail "unexpected checker output: $(cat "$WORK/broken.txt")"
sed -e "s#\.\./\.\.#$SRC#g" -e 's/robodds.participant.udp_only/robodds.participant/' "$COMPOSE_DIR/plant_smoke.yml" >"$WORK/broken_shm.yml"
"${CHECK[@]}" "$WORK/broken_shm.yml" 2>"$WORK/broken.txt" && fail "checker accepted shared memory on a bridge network"
grep -q "bridge network with the shared-memory profile" "$WORK/broken.txt" || fail "unexpected checker output: $(cat "$WORK/broken.txt")"
echo "ok: the checker rejects an unknown group and SHM on a bridge"

# 4. Bad input: one "error:" line naming what is wrong, exit code 2.
S="$SRC/sim/scenarios/plant_smoke.yaml"
in_repo_scenario() {  # a scenario must live in the repository; edited copies go in a scratch dir there
  mkdir -p "$SRC/out/compose_test.$$"
  sed "$2" "$S" >"$SRC/out/compose_test.$$/$1.yaml"
  echo "$SRC/out/compose_test.$$/$1.yaml"
}
trap 'rm -rf "$SRC/out/compose_test.$$"; cleanup' EXIT
D=("$ROBODDS" deploy compose)
expect_error 2 "no-such\.yaml: cannot open scenario file" -- "${D[@]}" "$SRC/sim/scenarios/no-such.yaml"
expect_error 2 "components\.plant: unknown component type 'plantt'" -- \
  "${D[@]}" "$(in_repo_scenario t1 's/type: plant}/type: plantt}/')"
expect_error 2 "groups\.sim: unknown component 'plnt'" -- "${D[@]}" "$(in_repo_scenario t2 's/sim: \[plant\]/sim: [plnt]/')"
expect_error 2 "groups\.coordinator: group name 'coordinator' is reserved" -- \
  "${D[@]}" "$(in_repo_scenario t3 's/sim: \[plant\]/coordinator: [plant]/')"
expect_error 2 "groups\.discovery: group name 'discovery' is reserved" -- \
  "${D[@]}" "$(in_repo_scenario t4 's/sim: \[plant\]/discovery: [plant]/')" --discovery server
expect_error 2 "no-such-sec: DDS Security: security directory not found" -- "${D[@]}" "$S" --security "$WORK/no-such-sec"
"$ROBODDS" security init "$S" --out "$WORK/sec" >/dev/null 2>&1 || fail "robodds security init failed"
rm -r "$WORK/sec/sensing"
expect_error 2 "no identity 'sensing'" -- "${D[@]}" "$S" --security "$WORK/sec"
expect_error 2 "--security goes with --discovery multicast" -- "${D[@]}" "$S" --security "$WORK/sec" --discovery server
cp "$S" "$WORK/outside.yaml"
expect_error 2 "outside\.yaml: is outside the repository" -- "${D[@]}" "$WORK/outside.yaml"

# 5. -o writes a file whose paths fit where it is written.
mkdir -p "$SRC/out/compose_test.$$/sub"
"${D[@]}" "$S" -o "$SRC/out/compose_test.$$/sub/plant_smoke.yml" >/dev/null
grep -q "context: ../../.." "$SRC/out/compose_test.$$/sub/plant_smoke.yml" || fail "-o: build context not relative to the output file"
docker-compose -f "$SRC/out/compose_test.$$/sub/plant_smoke.yml" config -q
"${CHECK[@]}" "$SRC/out/compose_test.$$/sub/plant_smoke.yml" >/dev/null
echo "ok: -o FILE gets paths relative to FILE"

# 5b. --rt-priority N: every robodds service runs with it and gets the capabilities and limits it
#     needs; without it (the shipped files) none of them.
expect_error 2 "--rt-priority: must be a whole number 1\.\.99" -- "${D[@]}" "$S" --rt-priority 0
"${D[@]}" "$S" --rt-priority 50 -o "$SRC/out/compose_test.$$/rt.yml" >/dev/null
docker-compose -f "$SRC/out/compose_test.$$/rt.yml" config -q || fail "--rt-priority: docker-compose config -q"
"${CHECK[@]}" "$SRC/out/compose_test.$$/rt.yml" >/dev/null
python3 - "$SRC/out/compose_test.$$/rt.yml" "${files[@]}" <<'PY' || fail "--rt-priority: capabilities, limits or option wrong"
import sys, yaml
def services(path):
    return yaml.safe_load(open(path))["services"]
for name, s in services(sys.argv[1]).items():
    assert sorted(s.get("cap_add", [])) == ["IPC_LOCK", "SYS_NICE"], f"{name}: cap_add {s.get('cap_add')}"
    assert s.get("ulimits") == {"rtprio": 99, "memlock": -1}, f"{name}: ulimits {s.get('ulimits')}"
    command = s["command"]
    assert command[command.index("--rt-priority") + 1] == "50", f"{name}: command {command}"
for path in sys.argv[2:]:
    for name, s in services(path).items():
        assert "cap_add" not in s and "ulimits" not in s, f"{path}: {name} has capabilities it was not asked for"
        assert "--rt-priority" not in s.get("command", []), f"{path}: {name} runs --rt-priority unasked"
PY
echo "ok: --rt-priority 50 gives every service the option, cap_add SYS_NICE + IPC_LOCK, rtprio 99, memlock unlimited; the shipped files none"

# 6. The services' commands, run as local processes, complete the run; the outputs are
#    byte-identical to a co-located run (bridge variant: UDP only; host variant: SHM + UDP).
for scenario in plant_smoke paper1_waypoints; do
  "$ROBODDS" --log warn run "$SRC/sim/scenarios/$scenario.yaml" --domain "$DOMAIN" --out "$WORK/colocated/$scenario" --no-plots >/dev/null
done
for variant in plant_smoke.yml plant_smoke.host-network.yml paper1_waypoints.yml; do
  scenario="${variant%%.*}"
  mkdir -p "$WORK/$variant"
  ROBODDS_DOMAIN_ID="$DOMAIN" ROBODDS_RUN_ID="$RANDOM$$" timeout -k 5 700 "${CHECK[@]}" "$COMPOSE_DIR/$variant" --run "$WORK/$variant"
  for csv in "$WORK/colocated/$scenario"/*.csv; do
    cmp -s "$csv" "$WORK/$variant/$scenario/$(basename "$csv")" || fail "$variant: $(basename "$csv") differs from the co-located run"
  done
  echo "ok: $variant commands complete the run, CSVs byte-identical to co-located"
done
echo "ok: compose files valid, consistent, up to date and runnable"

#!/usr/bin/env bash
# Layering rules (docs/architecture.md), checked on the source tree by grep: no build needed.
#   1. Nothing under components/ includes sim/ or links a sim/ target: the robot and geometry
#      model the components share with the simulator lives below both, in common/model/.
#   2. Only the DDS runtime includes Fast DDS headers (fastdds/, fastrtps/).
#   3. No component (components/, sim/: their code outside test/) reads another component's
#      parameters or finds one by its type in the scenario: what several components must agree on
#      is a shared fact of the scenario (system/robot_facts.hpp).
#   4. No component's CMakeLists.txt names another component's node library.
#   5. One name per component: its folder, its namespace (robodds::<type>) and its registered type
#      agree, its node is node/<type>_node.cpp, and one folder registers one type.
#   6. The layers below never include the ones above: runtime/ includes nothing of system/,
#      components/, sim/ or tools/; system/ nothing of components/, sim/ or tools/.
#   7. The runtime is domain-free: its code (runtime/ outside test/, and outside the test and bench
#      tools runtime/dds/fuzz/ and runtime/dds/bench/, which exercise it with the robot system)
#      names no topic of the system (system/topics.cpp), no message type but its own bookkeeping
#      (RUNTIME_MESSAGE_TYPES) and no component type; comments aside.
# Usage: check_layering.sh SOURCE_ROOT. Exit 0 when clean, else 1 with one line per violation.
set -euo pipefail

# The one directory (relative to the source root) whose files may include Fast DDS headers.
FASTDDS_ALLOWED_DIR="runtime/dds/"
# Files outside it that may, and why (none today: the raw-Fast-DDS latency bench lives in
# runtime/dds/bench/).
FASTDDS_ALLOWED_FILES=()

root=${1:?usage: check_layering.sh SOURCE_ROOT}
cd "$root"

# Source files of the tree: git's view (tracked + untracked, ignoring build trees) in a checkout,
# else every file outside .git and build*/ directories.
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -t files < <(git ls-files --cached --others --exclude-standard)
else
  mapfile -t files < <(find . \( -name .git -o -type d -name 'build*' \) -prune -o -type f -print | sed 's|^\./||')
fi
sources=() cmake_lists=()
for f in "${files[@]}"; do
  [[ -f $f ]] || continue  # deleted but not yet staged
  case $f in
    *.cpp|*.hpp|*.h|*.cc|*.cxx|*.hh|*.ipp|*.inl) sources+=("$f") ;;
    */CMakeLists.txt|CMakeLists.txt) cmake_lists+=("$f") ;;
  esac
done

failed=0
violation() { echo "layering: $1"; failed=1; }
include_of() {  # include_of REGEX FILE...: "file:line:text" of every #include whose path matches REGEX
  local pattern=$1
  shift
  (($# == 0)) || grep -nHE "^[[:space:]]*#[[:space:]]*include[[:space:]]*[<\"]($pattern)" -- "$@" || true
}

# Rule 1a: no #include of sim/ from components/.
component_sources=()
for f in "${sources[@]}"; do [[ $f == components/* ]] && component_sources+=("$f"); done
while IFS= read -r hit; do
  [[ -n $hit ]] && violation "$hit: components/ must not include sim/ (shared robot model: common/model/)"
done < <(include_of '(\.\./)*sim/' "${component_sources[@]}")

# Rule 1b: no CMake target of sim/ named in a components/ CMakeLists.txt (comments stripped).
sim_targets=()
for f in "${cmake_lists[@]}"; do
  [[ $f == sim/* ]] || continue
  mapfile -t -O "${#sim_targets[@]}" sim_targets < <(sed 's/#.*//' "$f" | tr '\n' ' ' |
    grep -oE '(robodds_library|add_library|add_executable)\([[:space:]]*[A-Za-z0-9_]+' | sed -E 's/.*\([[:space:]]*//')
  # robodds_component(NAME t [LIBRARY l] ...) makes the node library (l, default robodds_t_node)
  # and the executable robodds-<t with dashes>.
  while IFS= read -r call; do
    name=$(grep -oE '[[:space:](]NAME[[:space:]]+[A-Za-z0-9_]+' <<<"$call" | awk '{print $NF}' || true)
    library=$(grep -oE '[[:space:]]LIBRARY[[:space:]]+[A-Za-z0-9_]+' <<<"$call" | awk '{print $NF}' || true)
    [[ -n $name ]] && sim_targets+=("${library:-robodds_${name}_node}" "robodds-${name//_/-}")
  done < <(sed 's/#.*//' "$f" | tr '\n' ' ' | grep -oE 'robodds_component\([^)]*\)')
done
for f in "${cmake_lists[@]}"; do
  if [[ $f != components/* ]] || ((${#sim_targets[@]} == 0)); then
    continue
  fi
  while IFS= read -r hit; do
    [[ -n $hit ]] && violation "$f:$hit: components/ must not depend on a sim/ target"
  done < <(sed 's/#.*//' "$f" | grep -nowF "${sim_targets[@]/#/-e}" || true)
done

# Rule 2: Fast DDS headers only under FASTDDS_ALLOWED_DIR (and the listed exceptions).
outside=()
for f in "${sources[@]}"; do
  [[ $f == "$FASTDDS_ALLOWED_DIR"* ]] && continue
  for allowed in "${FASTDDS_ALLOWED_FILES[@]}"; do [[ $f == "$allowed" ]] && continue 2; done
  outside+=("$f")
done
while IFS= read -r hit; do
  [[ -n $hit ]] && violation "$hit: only $FASTDDS_ALLOWED_DIR includes Fast DDS headers"
done < <(include_of 'fastdds/|fastrtps/' "${outside[@]}")

# Rule 3: no ComponentSpec type or overrides read from a component (tests aside: they build scenarios).
component_code=()
for f in "${sources[@]}"; do
  [[ ($f == components/* || $f == sim/*) && $f != */test/* ]] && component_code+=("$f")
done
if ((${#component_code[@]})); then
  while IFS= read -r hit; do
    [[ -n $hit ]] && violation "$hit: a component must not read another component's type or parameters (use a shared fact: system/robot_facts.hpp)"
  done < <(grep -nHE '\.overrides\b|\bspec\.type\b|\.type[[:space:]]*[!=]=[[:space:]]*"' -- "${component_code[@]}" || true)
fi

# Rule 4: a component folder's CMakeLists.txt names no node library but its own.
declare -A node_library_of=()  # CMakeLists.txt -> its node library
for f in "${cmake_lists[@]}"; do
  [[ $f == components/* || $f == sim/* ]] || continue
  while IFS= read -r call; do
    name=$(grep -oE '[[:space:](]NAME[[:space:]]+[A-Za-z0-9_]+' <<<"$call" | awk '{print $NF}' || true)
    library=$(grep -oE '[[:space:]]LIBRARY[[:space:]]+[A-Za-z0-9_]+' <<<"$call" | awk '{print $NF}' || true)
    [[ -n $name ]] && node_library_of[$f]="${library:-robodds_${name}_node}"
  done < <(sed 's/#.*//' "$f" | tr '\n' ' ' | grep -oE 'robodds_component\([^)]*\)')
done
for f in "${!node_library_of[@]}"; do
  for other in "${!node_library_of[@]}"; do
    [[ $other == "$f" ]] && continue
    while IFS= read -r hit; do
      [[ -n $hit ]] && violation "$f:$hit: a component must not link another component's node library (${node_library_of[$other]})"
    done < <(sed 's/#.*//' "$f" | grep -nowF -e "${node_library_of[$other]}" || true)
  done
done

# Rule 6: no include upwards from runtime/ or system/.
for layer in runtime system; do
  below=()
  for f in "${sources[@]}"; do [[ $f == $layer/* ]] && below+=("$f"); done
  above='system/|components/|sim/|tools/'
  [[ $layer == system ]] && above='components/|sim/|tools/'
  while IFS= read -r hit; do
    [[ -n $hit ]] && violation "$hit: $layer/ must not include a layer above it"
  done < <(include_of "$above" "${below[@]}")
done

# Rule 5: folder = namespace = registered type.
for f in "${cmake_lists[@]}"; do
  [[ $f == components/*/CMakeLists.txt || $f == sim/*/CMakeLists.txt ]] || continue
  folder=$(dirname "$f")
  mapfile -t names < <(sed 's/#.*//' "$f" | tr '\n' ' ' | grep -oE 'robodds_component\([[:space:]]*NAME[[:space:]]+[A-Za-z0-9_]+' |
    awk '{print $NF}')
  ((${#names[@]} == 0)) && continue
  ((${#names[@]} == 1)) || violation "$f: registers ${#names[@]} types (${names[*]}): one folder, one component"
  type=${names[0]}
  [[ $(basename "$folder") == "$type" ]] || violation "$f: the folder is '$(basename "$folder")', the registered type '$type'"
  [[ -f $folder/node/${type}_node.cpp ]] || violation "$folder: no node/${type}_node.cpp (the node file is named after the type)"
  while IFS= read -r hit; do
    [[ -n $hit ]] && violation "$hit: component '$type' declares another namespace than robodds::$type"
  done < <(grep -nHE '^[[:space:]]*namespace robodds::[a-z_]+' -- "$folder"/*.hpp "$folder"/*.cpp "$folder"/node/*.hpp "$folder"/node/*.cpp 2>/dev/null |
    grep -vE "namespace robodds::${type}([^a-z_]|$)" || true)
done

# Rule 7: runtime/ names no topic, message type or component of the system above it.
# The IDL types the runtime owns: the lockstep bookkeeping (ticks, acknowledgements, host reports)
# and the structs they are made of; run/alive beats (HostAlive).
RUNTIME_MESSAGE_TYPES=(SampleHeader SimTick StepDone HostReport HostAlive InputReport ReasonCount StageTiming)
mapfile -t system_topics < <(grep -ohE 'make_topic<[^>]+>\("[^"]+"' system/*.cpp 2>/dev/null | sed -E 's/.*\("//; s/"$//' | sort -u)
mapfile -t message_types < <(grep -ohE '^[[:space:]]*(@final[[:space:]]+)?(struct|enum)[[:space:]]+[A-Za-z0-9_]+' idl/*.idl 2>/dev/null |
  awk '{print $NF}' | grep -vxF "${RUNTIME_MESSAGE_TYPES[@]/#/-e}" | sort -u)
component_types=()
for f in "${cmake_lists[@]}"; do
  [[ $f == components/* || $f == sim/* ]] || continue
  mapfile -t -O "${#component_types[@]}" component_types < <(sed 's/#.*//' "$f" | tr '\n' ' ' |
    grep -oE 'robodds_component\([[:space:]]*NAME[[:space:]]+[A-Za-z0-9_]+' | awk '{print $NF}')
done
runtime_code=()
for f in "${sources[@]}"; do
  [[ $f == runtime/* && $f != */test/* && $f != runtime/dds/fuzz/* && $f != runtime/dds/bench/* ]] && runtime_code+=("$f")
done
if ((${#runtime_code[@]})) && ((${#system_topics[@]} + ${#message_types[@]} + ${#component_types[@]})); then
  names=()
  for t in "${system_topics[@]}"; do names+=(-e "\"$t\""); done
  for t in "${message_types[@]}" "${component_types[@]}"; do names+=(-e "$t"); done
  for f in "${runtime_code[@]}"; do
    # Comments stripped (a line's // tail), then whole words (topics: as quoted strings).
    while IFS= read -r hit; do
      [[ -n $hit ]] && violation "$f:$hit: the runtime must not name a topic, message type or component of the system above it (they belong in system/ or the component)"
    done < <(sed -E 's#//.*$##' "$f" | grep -nowF "${names[@]}" || true)
  done
fi

if ((failed == 0)); then
  echo "layering: ok (${#sources[@]} source files, ${#sim_targets[@]} sim targets)"
fi
exit "$failed"

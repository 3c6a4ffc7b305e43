#!/usr/bin/env bash
# The evaluator's core names no metrics module and a module includes no other module, so that a
# new paper adds its module (sim/evaluator/metrics/<kind>/ and one add_subdirectory line) without
# touching the core or the other modules. Checked on the source tree by grep: no build needed.
# Usage: check_module_includes.sh SOURCE_ROOT. Exit 0 when clean, else 1 with one line per violation.
set -euo pipefail
cd "${1:?usage: check_module_includes.sh SOURCE_ROOT}"

failed=0
# The core (everything of sim/evaluator outside metrics/, tests aside) includes no module.
while IFS= read -r hit; do
  echo "evaluator modules: $hit: the core must not include a metrics module"
  failed=1
done < <(grep -rnHE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"sim/evaluator/metrics/' sim/evaluator \
  --include='*.hpp' --include='*.cpp' --exclude-dir=metrics --exclude-dir=test || true)
# A module includes nothing of another module's folder.
for module in sim/evaluator/metrics/*/; do
  kind=$(basename "$module")
  while IFS= read -r hit; do
    echo "evaluator modules: $hit: module '$kind' must not include another module"
    failed=1
  done < <(grep -rnHE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"sim/evaluator/metrics/' "$module" \
    --include='*.hpp' --include='*.cpp' | grep -v "\"sim/evaluator/metrics/$kind/" || true)
done
((failed == 0)) && echo "evaluator modules: ok"
exit "$failed"

#pragma once
// Components a run adds to its scenario from the command line (e.g. `robodds run --record` adds
// its recorder to the evaluator's group): "GROUP:NAME:TYPE", given to every child host as
// `--add-component`, so each process builds the same scenario. Their parameters travel as --set.

#include <string>
#include <vector>

#include "runtime/config/scenario.hpp"

namespace robodds {

/// "GROUP:NAME:TYPE".
std::string added_component_spec(const std::string& group, const std::string& name, const std::string& type);

/// Adds each "GROUP:NAME:TYPE" of `specs` to `scenario`: component NAME of TYPE, serving every
/// robot, in group GROUP. Call before the --set overrides (they may name it). ConfigError naming
/// the spec: not three non-empty parts, no such group, or NAME already a component.
void add_components(Scenario& scenario, const std::vector<std::string>& specs);

}  // namespace robodds

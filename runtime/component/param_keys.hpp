#pragma once
// The keys of `--set component.parameter=value` checked against the scenario's components and
// their parameter tables before a run starts, with the closest names of a key that is not one.

#include <string>
#include <vector>

#include "runtime/component/registry.hpp"

namespace robodds {

/// Every key of `assignments` ("component.parameter=value", as `--set` takes them; the text after
/// '=' is not read) names a parameter of a component of `scenario`: else a ConfigError naming
/// `option`, the key and the closest "component.parameter" names (`--set epsilon=0.1`: did you
/// mean 'controller.epsilon_m'?). A text without '=' is left to parse_param_assignments().
void check_param_keys(const Scenario& scenario, const ComponentRegistry& registry,
                      const std::vector<std::string>& assignments, const std::string& option);

}  // namespace robodds

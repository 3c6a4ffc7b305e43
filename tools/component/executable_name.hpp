#pragma once
// The name of a component type's own executable, robodds-<type> with dashes: what
// robodds_component_executable() (cmake/RoboddsHelpers.cmake) builds, and what its --help and
// README.md's Layout call it.

#include <algorithm>
#include <string>

namespace robodds {

/// "pf_estimator" -> "robodds-pf-estimator".
inline std::string component_executable_name(const std::string& type) {
  std::string name = "robodds-" + type;
  std::replace(name.begin(), name.end(), '_', '-');
  return name;
}

}  // namespace robodds

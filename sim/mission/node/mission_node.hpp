#pragma once
#include <memory>

#include "common/param_doc.hpp"
#include "runtime/component.hpp"

namespace robodds::mission {
/// Publishes the way-point list from its parameters on mission/waypoints, once per robot.
std::unique_ptr<Component> make_mission_node();
/// Its parameters (keys, types, defaults, units, ranges, descriptions).
params::ParamDoc mission_source_params_doc();
}  // namespace robodds::mission

#pragma once
#include <memory>

#include "common/param_doc.hpp"
#include "runtime/component.hpp"

namespace robodds::waypoint {
/// estimate/pose + mission/waypoints in; plant/cmd and control/status out.
std::unique_ptr<Component> make_waypoint_controller_node();
/// Its parameters (keys, types, defaults, units, ranges, descriptions).
params::ParamDoc waypoint_controller_params_doc();
}  // namespace robodds::waypoint

#pragma once
#include <memory>

#include "runtime/component/component.hpp"

namespace robodds::waypoint_controller {
/// estimate/pose + mission/waypoints in; plant/cmd and control/status out.
std::unique_ptr<Component> make_waypoint_controller_node();
}  // namespace robodds::waypoint_controller

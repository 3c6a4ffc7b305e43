#pragma once
#include <memory>

#include "runtime/component/component.hpp"

namespace robodds::mission_source {
/// Publishes the way-point list from its parameters on mission/waypoints, once per robot.
std::unique_ptr<Component> make_mission_node();
}  // namespace robodds::mission_source

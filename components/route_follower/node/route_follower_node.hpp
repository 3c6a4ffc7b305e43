#pragma once
#include <memory>

#include "runtime/component/component.hpp"

namespace robodds::route_follower {
/// estimate/pose in, plant/cmd (VELOCITY) out at rate_hz for every served robot.
std::unique_ptr<Component> make_route_follower_node();
}  // namespace robodds::route_follower

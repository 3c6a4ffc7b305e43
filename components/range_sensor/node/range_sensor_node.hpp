#pragma once
#include <memory>

#include "runtime/component/component.hpp"

namespace robodds::range_sensor {
/// plant/state + mission/target in, sensor/range (robot, target) out at rate_hz, seeded per robot.
std::unique_ptr<Component> make_range_sensor_node();
}  // namespace robodds::range_sensor

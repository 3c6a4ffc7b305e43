#pragma once
#include <memory>

#include "runtime/component/component.hpp"

namespace robodds::position_sensor {
/// plant/state in, sensor/position out at rate_hz, one seeded noise stream per robot.
std::unique_ptr<Component> make_position_sensor_node();
}  // namespace robodds::position_sensor

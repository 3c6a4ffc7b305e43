#pragma once
#include <memory>

#include "runtime/component/component.hpp"

namespace robodds::odometry_sensor {
/// plant/state in (every step), sensor/odometry out at rate_hz: the mean true twist over the
/// interval since the previous reading, measured through noisy, slipping wheels.
std::unique_ptr<Component> make_odometry_sensor_node();
}  // namespace robodds::odometry_sensor

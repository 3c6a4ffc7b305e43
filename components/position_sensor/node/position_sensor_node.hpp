#pragma once
#include <memory>

#include "common/param_doc.hpp"
#include "runtime/component.hpp"

namespace robodds::position_sensor {
/// plant/state in, sensor/position out at rate_hz, one seeded noise stream per robot.
std::unique_ptr<Component> make_position_sensor_node();
/// Its parameters (keys, types, defaults, units, ranges, descriptions).
params::ParamDoc position_sensor_params_doc();
}  // namespace robodds::position_sensor

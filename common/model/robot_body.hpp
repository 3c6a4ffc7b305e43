#pragma once
// A differential-drive robot's physical description: what the plant simulates, what the
// odometry integrates with and what a controller must command within. Several components must
// agree on it, so a scenario declares it once, as a shared fact (`facts: robot_body:`, read by
// system/robot_facts.hpp), and no component carries its own copy. Pure: std only.

#include "common/model/actuator.hpp"
#include "common/model/twist.hpp"
#include "common/param_table.hpp"

namespace robodds::model {

// Units, ranges and one-line descriptions: robot_body_param_table() in robot_body.cpp (the one
// source). Defaults: the member initialisers (the paper-1 robot: 0.5 m, no limits).
struct RobotBody {
  double wheel_base_m = 0.5;  // m, distance between the wheels (D of paper 1, eq. 1)
  TwistLimits limits;         // flat keys max_speed_mps, max_turn_rate_radps (0 = unlimited)
  ActuatorLimits actuator;    // flat keys max_wheel_speed_mps, max_accel_mps2, max_angular_accel_radps2

  /// Throws std::invalid_argument("key: reason").
  void validate() const;
};

const params::ParamTable<RobotBody>& robot_body_param_table();

}  // namespace robodds::model

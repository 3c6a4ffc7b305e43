#include "common/model/robot_body.hpp"

namespace robodds::model {

const params::ParamTable<RobotBody>& robot_body_param_table() {
  static const params::ParamTable<RobotBody> table =
      params::ParamTable<RobotBody>(
          "A robot's physical description (shared fact `robot_body`): the plant simulates it, the odometry\n"
          "integrates with its wheel base, controllers command within its limits.")
          .add("wheel_base_m", &RobotBody::wheel_base_m, "m", params::positive(),
               "D in paper 1, eq. (1): distance between the wheels")
          .add("max_speed_mps", &RobotBody::limits, &TwistLimits::max_speed_mps, "m/s",
               params::non_negative("0 = unlimited"), "|v| the robot can reach (the paper: 0)")
          .add("max_turn_rate_radps", &RobotBody::limits, &TwistLimits::max_turn_rate_radps, "rad/s",
               params::non_negative("0 = unlimited"), "|omega| the robot can reach (the paper: 0)")
          .add("max_wheel_speed_mps", &RobotBody::actuator, &ActuatorLimits::max_wheel_speed_mps, "m/s",
               params::non_negative("0 = unlimited"),
               "each wheel's |rim speed|, clamped on its own as a motor driver does (the paper: 0)")
          .add("max_accel_mps2", &RobotBody::actuator, &ActuatorLimits::max_accel_mps2, "m/s^2",
               params::non_negative("0 = unlimited"), "|dv/dt| the drive can give (the paper: 0)")
          .add("max_angular_accel_radps2", &RobotBody::actuator, &ActuatorLimits::max_angular_accel_radps2,
               "rad/s^2", params::non_negative("0 = unlimited"),
               "|domega/dt| the drive can give; the change of (v, omega) is scaled as one (the paper: 0)");
  return table;
}

void RobotBody::validate() const { robot_body_param_table().check_ranges(*this); }

}  // namespace robodds::model

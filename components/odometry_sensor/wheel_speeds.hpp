#pragma once
// Body twist -> wheel rim speeds of a differential drive: the inverse of
// model::twist_from_wheel_speeds (omega = (v_right - v_left) / D, counter-clockwise positive).

#include "common/model/diff_drive_kinematics.hpp"

namespace robodds::odometry_sensor {

/// Rim speed of each wheel (m/s), positive forward.
struct WheelSpeeds {
  double left = 0.0;
  double right = 0.0;
};

/// v_left = v - omega D/2, v_right = v + omega D/2 for wheel base D = wheel_base_m (m, > 0).
WheelSpeeds wheel_speeds_from_twist(const model::Twist& twist, double wheel_base_m);

}  // namespace robodds::odometry_sensor

#include "common/model/actuator.hpp"

#include <algorithm>
#include <cmath>

namespace robodds::model {

WheelSpeeds wheel_speeds_from_twist(const Twist& twist, double wheel_base_m) {
  const double half_difference = 0.5 * twist.omega * wheel_base_m;
  return WheelSpeeds{twist.v - half_difference, twist.v + half_difference};
}

Twist clamp_wheel_speeds(const Twist& twist, double wheel_base_m, double max_wheel_speed_mps) {
  if (!(max_wheel_speed_mps > 0.0)) {
    return twist;
  }
  const WheelSpeeds w = wheel_speeds_from_twist(twist, wheel_base_m);
  if (std::abs(w.left) <= max_wheel_speed_mps && std::abs(w.right) <= max_wheel_speed_mps) {
    return twist;  // exactly as commanded (no round trip through the wheel speeds)
  }
  const double left = std::clamp(w.left, -max_wheel_speed_mps, max_wheel_speed_mps);
  const double right = std::clamp(w.right, -max_wheel_speed_mps, max_wheel_speed_mps);
  return Twist{0.5 * (left + right), (right - left) / wheel_base_m};
}

Twist scale_to_wheel_limit(const Twist& twist, double wheel_base_m, double max_wheel_speed_mps) {
  if (!(max_wheel_speed_mps > 0.0)) {
    return twist;
  }
  const WheelSpeeds w = wheel_speeds_from_twist(twist, wheel_base_m);
  const double fastest = std::max(std::abs(w.left), std::abs(w.right));
  if (fastest <= max_wheel_speed_mps) {
    return twist;
  }
  const double scale = max_wheel_speed_mps / fastest;
  return Twist{twist.v * scale, twist.omega * scale};
}

Twist limit_acceleration(const Twist& target, const Twist& previous, double dt_s, const ActuatorLimits& limits) {
  if (!(dt_s > 0.0)) {
    return previous;
  }
  const double dv = target.v - previous.v;
  const double domega = target.omega - previous.omega;
  double scale = 1.0;
  if (limits.max_accel_mps2 > 0.0 && std::abs(dv) > limits.max_accel_mps2 * dt_s) {
    scale = std::min(scale, limits.max_accel_mps2 * dt_s / std::abs(dv));
  }
  if (limits.max_angular_accel_radps2 > 0.0 && std::abs(domega) > limits.max_angular_accel_radps2 * dt_s) {
    scale = std::min(scale, limits.max_angular_accel_radps2 * dt_s / std::abs(domega));
  }
  if (scale == 1.0) {
    return target;
  }
  return Twist{previous.v + scale * dv, previous.omega + scale * domega};
}

}  // namespace robodds::model

#include "common/model/diff_drive_kinematics.hpp"

#include <cmath>

#include "common/angle.hpp"

namespace robodds::model {

Twist twist_from_wheel_speeds(double v_left, double v_right, double wheel_base_m) {
  return Twist{0.5 * (v_left + v_right), (v_right - v_left) / wheel_base_m};
}

double sinc(double x) {
  if (std::abs(x) < 0.1) {
    const double x2 = x * x;
    return 1.0 + x2 * (-1.0 / 6.0 + x2 * (1.0 / 120.0 + x2 * (-1.0 / 5040.0 + x2 * (1.0 / 362880.0 + x2 * (-1.0 / 39916800.0)))));
  }
  return std::sin(x) / x;
}

Pose2 integrate_exact(const Pose2& start, const Twist& twist, double dt_s) {
  const double dtheta = twist.omega * dt_s;
  // Chord length factor sin(dtheta/2)/(dtheta/2): exact arc, and its series near 0 avoids the
  // 0/0 of the textbook v/omega (sin(theta + omega dt) - sin(theta)) form.
  const double half = 0.5 * dtheta;
  const double chord = twist.v * dt_s * sinc(half);
  const double mid_heading = start.theta + half;
  Pose2 end;
  end.x = start.x + chord * std::cos(mid_heading);
  end.y = start.y + chord * std::sin(mid_heading);
  end.theta = wrap_angle(start.theta + dtheta);
  return end;
}

}  // namespace robodds::model

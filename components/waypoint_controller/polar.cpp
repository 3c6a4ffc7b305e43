#include "components/waypoint_controller/polar.hpp"

#include <cmath>

#include "common/angle.hpp"

namespace robodds::waypoint_controller {

PolarError polar_error(const Eigen::Vector2d& position_m, double theta_rad, const Eigen::Vector2d& waypoint_m) {
  const Eigen::Vector2d to_waypoint = waypoint_m - position_m;
  PolarError error;
  error.distance_m = std::hypot(to_waypoint.x(), to_waypoint.y());
  // On the way-point the bearing is undefined; alpha = 0 asks for no bearing correction
  // (v = kd·d is 0 there anyway) instead of the arbitrary atan2(0, 0) - theta.
  error.alpha_rad =
      error.distance_m > 0.0 ? wrap_angle(std::atan2(to_waypoint.y(), to_waypoint.x()) - theta_rad) : 0.0;
  error.sigma_rad = wrap_angle(0.5 * kPi - theta_rad);
  return error;
}

}  // namespace robodds::waypoint_controller

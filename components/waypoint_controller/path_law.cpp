#include "components/waypoint_controller/path_law.hpp"

#include <algorithm>
#include <cmath>

#include "common/angle.hpp"

namespace robodds::waypoint_controller {
namespace {
constexpr double kShortestLegM = 1e-3;  // m: below this a leg has no usable direction
}  // namespace

PathError path_error(const Eigen::Vector2d& segment_start_m, const Eigen::Vector2d& waypoint_m,
                     const Eigen::Vector2d& position_m, double theta_rad, double lookahead_m) {
  PathError error;
  const Eigen::Vector2d to_waypoint = waypoint_m - position_m;
  error.distance_m = to_waypoint.norm();
  const Eigen::Vector2d leg = waypoint_m - segment_start_m;
  const double leg_length = leg.norm();
  Eigen::Vector2d aim = waypoint_m;
  if (leg_length >= kShortestLegM) {
    const Eigen::Vector2d direction = leg / leg_length;
    const Eigen::Vector2d from_start = position_m - segment_start_m;
    error.along_track_m = direction.dot(from_start);
    error.cross_track_m = direction.x() * from_start.y() - direction.y() * from_start.x();
    const double aim_along = error.along_track_m + lookahead_m;
    if (aim_along < leg_length) {
      aim = segment_start_m + std::max(aim_along, 0.0) * direction;
    }
  }
  const Eigen::Vector2d to_aim = aim - position_m;
  error.desired_heading_rad = to_aim.squaredNorm() > 0.0 ? std::atan2(to_aim.y(), to_aim.x()) : wrap_angle(theta_rad);
  error.heading_error_rad = wrap_angle(error.desired_heading_rad - theta_rad);
  return error;
}

Command path_law(const PathError& error, const GainSet& gains) {
  Command command;
  command.v = gains.kd * error.distance_m * std::max(0.0, std::cos(error.heading_error_rad));
  command.omega = gains.ka * error.heading_error_rad;
  return command;
}

Command path_command(const PathError& error, const ControllerParams& params) {
  return within_limits(path_law(error, params.forward_gains), params.forward_gains, params);
}

}  // namespace robodds::waypoint_controller

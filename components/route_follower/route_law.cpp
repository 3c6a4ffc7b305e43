#include "components/route_follower/route_law.hpp"

#include <algorithm>
#include <cmath>

#include "common/angle.hpp"

namespace robodds::route_follower {

double turn_in_place_rate(double error_rad, double turn_rate_radps, double dt_s) {
  const double magnitude = std::min(turn_rate_radps, std::abs(error_rad) / dt_s);
  return error_rad >= 0.0 ? magnitude : -magnitude;
}

SegmentError segment_error(const Eigen::Vector2d& position, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d along = b - a;
  const double length = along.norm();
  const Eigen::Vector2d offset = position - a;
  SegmentError error;
  if (length < 1e-9) {
    error.heading_rad = std::atan2(offset.y(), offset.x());
    error.along_track_m = offset.norm();
    return error;
  }
  const Eigen::Vector2d unit = along / length;
  error.heading_rad = std::atan2(unit.y(), unit.x());
  error.cross_track_m = unit.x() * offset.y() - unit.y() * offset.x();
  error.along_track_m = unit.dot(offset);
  return error;
}

double line_following_heading(const SegmentError& error, double lookahead_m) {
  return wrap_angle(error.heading_rad - std::atan(error.cross_track_m / lookahead_m));
}

double line_following_rate(double desired_heading_rad, double heading_rad, const RouteParams& params) {
  const double error = wrap_angle(desired_heading_rad - heading_rad);
  return std::clamp(params.heading_gain * error, -params.max_correction_radps, params.max_correction_radps);
}

}  // namespace robodds::route_follower

#pragma once
// The two motions of the route follower, as free functions of the pose: the turn in place towards
// the next vertex, and line following along a segment (a bounded heading correction that brings
// the robot back onto the segment's line). Pure: SI units, world frame, angles in rad
// counter-clockwise from +x.

#include <Eigen/Core>

#include "common/model/pose2.hpp"
#include "components/route_follower/route_params.hpp"

namespace robodds::route_follower {

/// Turn rate of a turn in place for the heading error `error_rad` (desired - heading, wrapped):
/// +-turn_rate towards the desired heading, reduced on the last step so that it lands on it
/// (|omega| * dt_s <= |error|). dt_s > 0: the time until the next command.
double turn_in_place_rate(double error_rad, double turn_rate_radps, double dt_s);

/// Where a position is relative to the directed segment a -> b.
struct SegmentError {
  double heading_rad = 0.0;     // direction of a -> b
  double cross_track_m = 0.0;   // signed distance from the line through a and b, > 0 left of it
  double along_track_m = 0.0;   // projection of (p - a) on the direction, from a
};

/// For a segment shorter than 1e-9 m the direction is the bearing from a to p (cross-track 0).
SegmentError segment_error(const Eigen::Vector2d& position, const Eigen::Vector2d& a, const Eigen::Vector2d& b);

/// The heading that steers back onto the line: heading - atan(cross_track / lookahead_m).
double line_following_heading(const SegmentError& error, double lookahead_m);

/// omega = heading_gain * wrap(desired - heading), clamped to +-max_correction_radps.
double line_following_rate(double desired_heading_rad, double heading_rad, const RouteParams& params);

}  // namespace robodds::route_follower

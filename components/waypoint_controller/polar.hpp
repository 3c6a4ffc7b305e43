#pragma once
// Polar error coordinates of paper 1, eq. (8): where the way-point is, seen from the robot.
// World frame: x/y in m, heading theta in rad counter-clockwise from +x.

#include <Eigen/Core>

namespace robodds::waypoint_controller {

struct PolarError {
  /// d: Euclidean distance robot -> way-point (m), >= 0.
  double distance_m = 0.0;
  /// alpha: bearing of the way-point relative to the heading, wrap(atan2(W - p) - theta), in
  /// (-pi, pi]; 0 = straight ahead, > 0 = to the left. 0 when d = 0 (bearing undefined).
  double alpha_rad = 0.0;
  /// sigma: wrap(pi/2 - theta) in (-pi, pi], as printed in eq. (8).
  double sigma_rad = 0.0;
};

/// Eq. (8) for a robot at position_m (world, m) with heading theta_rad towards waypoint_m.
/// The bearing is measured from the robot TO the way-point (the literal atan((p - W)) of the
/// paper points away from it; see README.md). No division: d = 0 gives alpha = 0.
PolarError polar_error(const Eigen::Vector2d& position_m, double theta_rad, const Eigen::Vector2d& waypoint_m);

}  // namespace robodds::waypoint_controller

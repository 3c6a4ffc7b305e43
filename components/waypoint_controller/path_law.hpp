#pragma once
// Issue 28, "straight legs": a path-following variant of the way-point controller. The paper's
// law (eq. 10) steers on the bearing alpha to the way-point and on sigma = pi/2 - theta, whose
// ksigma term pulls the heading towards north: a 300 m eastward leg strays 32-36 m sideways even
// with the true pose. This law keeps the leg straight instead: it aims at a point a lookahead
// distance ahead along the segment from the previous way-point to the target (pure pursuit on the
// segment, clamped at the way-point), so the cross-track error decays like exp(-s / lookahead)
// over the distance s driven. The paper's switching rule (eq. 19) is unchanged (WaypointTracker).
// World frame: x/y in m, theta in rad counter-clockwise from +x.

#include <Eigen/Core>

#include "components/waypoint_controller/control_law.hpp"
#include "components/waypoint_controller/controller_params.hpp"

namespace robodds::waypoint_controller {

/// Where the robot is relative to the leg from segment_start_m to waypoint_m.
struct PathError {
  /// Signed distance from the leg's line (m): > 0 = the robot is left of the leg's direction.
  double cross_track_m = 0.0;
  /// The robot's position projected on the line, from segment_start_m towards the way-point (m);
  /// < 0 before the start, > the leg's length past the way-point.
  double along_track_m = 0.0;
  /// Distance robot -> way-point (m), >= 0.
  double distance_m = 0.0;
  /// Heading the law steers to (rad, (-pi, pi]): towards the point lookahead_m ahead of the
  /// projection on the leg, or the way-point itself once that point would lie beyond it.
  double desired_heading_rad = 0.0;
  /// wrap(desired_heading - theta) in (-pi, pi]: > 0 = turn left.
  double heading_error_rad = 0.0;
};

/// The leg's geometry and the steering target for a robot at position_m with heading theta_rad.
/// A leg shorter than 1 mm (the first leg starting on its way-point, or two equal way-points) has
/// no direction: the law then aims at the way-point directly (cross_track_m 0). `lookahead_m` > 0.
PathError path_error(const Eigen::Vector2d& segment_start_m, const Eigen::Vector2d& waypoint_m,
                     const Eigen::Vector2d& position_m, double theta_rad, double lookahead_m);

/// The raw law: v = kd·d·max(0, cos(heading error)) (the paper's distance law, slowed while the
/// robot faces away from its aim point, and turning on the spot when it faces more than 90 deg
/// away: it never backs up), omega = ka·heading error; kd and ka of the forward gain set.
Command path_law(const PathError& error, const GainSet& gains);

/// The controller output of the path law: path_law() of the forward gains made drivable by
/// within_limits(), as waypoint_command() does with eq. (10).
Command path_command(const PathError& error, const ControllerParams& params);

}  // namespace robodds::waypoint_controller

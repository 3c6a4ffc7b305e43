#pragma once
// Parameters of the way-point controller of paper 1, section 3 (control law eq. 10, gain
// conditions eq. 11 and 16, switching eq. 19).

#include "common/model/robot_body.hpp"
#include "common/param_table.hpp"

namespace robodds::waypoint_controller {

/// One set of gains of eq. (10): v = kd·d, omega = ka·alpha + sgn*·ksigma·sigma.
/// Units, ranges, descriptions: the forward_gains.* and backward_gains.* entries of
/// controller_param_table().
struct GainSet {
  double kd = 0.0;
  double ka = 0.0;      // alpha: the bearing error to the way-point
  double ksigma = 0.0;  // sigma = pi/2 - theta
};

// Units, ranges and one-line descriptions of these fields: controller_param_table() in
// controller_params.cpp (the one source; `robodds components --params waypoint_controller`
// prints it). Defaults: the member initialisers.
struct ControllerParams {
  /// Way-point ahead of the robot. Defaults: paper 1, section 4, step 2.
  GainSet forward_gains{1.0, 20.0, -2.5};
  /// Way-point behind: ka turns the robot round while it backs up. Defaults: paper 1, section 4,
  /// step 2.
  GainSet backward_gains{-1.0, 20.0, -2.5};
  double epsilon_m = 0.1;
  double max_speed_mps = 0.0;
  double max_turn_rate_radps = 0.0;
  /// The robot it drives (not a parameter of this controller: the scenario's shared fact
  /// robot_body, which the node sets; 0 = unlimited): a command whose faster wheel would exceed
  /// body.actuator.max_wheel_speed_mps is scaled down as a whole (v and omega by one factor, so
  /// the curvature is kept), and the command changes by at most max_accel_mps2 and
  /// max_angular_accel_radps2 per second (WaypointTracker, with its control period).
  model::RobotBody body;
  /// Extension. The rule: (W - p)^T P^-1 (W - p) <= kappa^2, P the estimate's position
  /// covariance. Why: with an estimated pose the true distance at a switch is bounded by the
  /// estimator's error, not by epsilon; an epsilon far below that error may never trigger (the
  /// mission stalls). This rule lets the mission go on once the estimator cannot tell the robot
  /// from the way-point any more.
  double confidence_switch_sigmas = 0.0;
  /// The paper keeps the law active (small heading corrections after t = 100 s in its Fig. 4);
  /// with an estimated pose the bearing alpha of a way-point a few cm away is pure estimate
  /// noise, and ka = 20 turns that noise into omega swings of tens of rad/s at standstill.
  bool stop_when_done = true;
  /// Extension (issue 28, path_law.hpp): 0 = the paper's law, eq. (10). > 0: follow the straight
  /// leg from the previous way-point (the first leg: from where the robot was at the mission's
  /// first step) to the target, aiming this far ahead along it; the paper's switching rule stays.
  double path_lookahead_m = 0.0;

  /// Throws std::invalid_argument "key: reason (got ...)" for the first bad field. Gain sets
  /// are checked against eq. (11) and eq. (16) as read in README.md (forward set with
  /// sgn* = +1, backward set with sgn* = -1); the message names the violated inequality.
  void validate() const;
};

const params::ParamTable<ControllerParams>& controller_param_table();

}  // namespace robodds::waypoint_controller

#pragma once
// Parameters of the way-point controller of paper 1, section 3 (control law eq. 10, gain
// conditions eq. 11 and 16, switching eq. 19). SI units: metres, seconds, radians.
// Defaults: the member initialisers; keys, units, ranges, descriptions: controller_param_table().

#include "common/param_table.hpp"

namespace robodds::waypoint {

/// One set of gains of eq. (10): v = kd·d (m/s), omega = ka·alpha + sgn*·ksigma·sigma (rad/s).
struct GainSet {
  double kd = 0.0;      // 1/s: forward speed per metre of distance; kd < 0 means backing up
  double ka = 0.0;      // 1/s: turn rate per radian of bearing error alpha
  double ksigma = 0.0;  // 1/s: turn rate per radian of sigma = pi/2 - theta
};

struct ControllerParams {
  /// Used while |alpha| <= pi/2 (way-point ahead of the robot). Paper 1, section 4, step 2.
  GainSet forward_gains{1.0, 20.0, -2.5};
  /// Used while |alpha| > pi/2 (way-point behind): kd < 0 makes the robot back up (v < 0)
  /// while ka turns it round. Paper 1, section 4, step 2.
  GainSet backward_gains{-1.0, 20.0, -2.5};
  /// Switching threshold of eq. (19) (m): way-point k counts as reached, and the tracker moves
  /// on to k+1, when the distance to it is <= epsilon_m. Must be > 0.
  double epsilon_m = 0.1;
  /// Optional limit on |v| (m/s); 0 = unlimited, as in the paper.
  double max_speed_mps = 0.0;
  /// Optional limit on |omega| (rad/s); 0 = unlimited, as in the paper.
  double max_turn_rate_radps = 0.0;
  /// Confidence-aware switching (extension, 0 = off = the paper), dimensionless kappa >= 0: the
  /// way-point also counts as reached when it lies inside the kappa-sigma ellipse of the
  /// estimate's position covariance P, i.e. (W - p)^T P^-1 (W - p) <= kappa^2. With an estimated
  /// pose the true distance at a switch is bounded by the estimator's error, not by epsilon; an
  /// epsilon far below that error may never trigger (the mission stalls). This rule lets the
  /// mission go on once the estimator cannot tell the robot from the way-point any more.
  double confidence_switch_sigmas = 0.0;
  /// Once the last way-point is reached, command zero instead of keeping the law active on it.
  /// The paper keeps it active (small heading corrections after t = 100 s in its Fig. 4); with
  /// an estimated pose the bearing alpha of a way-point a few cm away is pure estimate noise,
  /// and ka = 20 turns that noise into omega swings of tens of rad/s at standstill.
  bool stop_when_done = true;

  /// Throws std::invalid_argument "key: reason (got ...)" for the first bad field. Gain sets
  /// are checked against eq. (11) and eq. (16) as read in README.md (forward set with
  /// sgn* = +1, backward set with sgn* = -1); the message names the violated inequality.
  void validate() const;
};

const params::ParamTable<ControllerParams>& controller_param_table();

}  // namespace robodds::waypoint

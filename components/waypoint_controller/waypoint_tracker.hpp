#pragma once
// Multi-way-point tracking of paper 1, section 3: the control law eq. (10) aimed at the
// current way-point, which advances by the switching rule eq. (19). World frame, SI units.

#include <cstddef>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "components/waypoint_controller/control_law.hpp"
#include "components/waypoint_controller/controller_params.hpp"

namespace robodds::waypoint_controller {

/// What the tracker did on one step, for telemetry and tests.
struct TrackerStatus {
  /// Index (0-based) of the way-point the returned command aims at.
  std::size_t target_index = 0;
  /// Way-points reached so far (the last one counts once `done` is set).
  std::size_t reached_count = 0;
  /// Distance from the pose to the target way-point, and to the last way-point (m).
  double distance_to_target_m = 0.0;
  double distance_to_final_m = 0.0;
  /// Polar errors of eq. (8) to the target way-point (rad, (-pi, pi]).
  double alpha_rad = 0.0;
  double sigma_rad = 0.0;
  /// True once the last way-point was within epsilon; stays true (latched).
  bool done = false;
  /// True on the step at which a way-point was declared reached (eq. 19 switch, or arrival
  /// at the last one); reached_distance_m is then the distance at that moment (m), else NaN.
  bool reached_this_step = false;
  double reached_distance_m = std::numeric_limits<double>::quiet_NaN();
};

struct TrackerOutput {
  Command command;
  TrackerStatus status;
};

/// Holds a mission and turns pose estimates into commands.
///
/// Switching, eq. (19): at each step the distance to the current way-point W_k is measured
/// first; if it is <= epsilon, W_k is reached and the target becomes W_{k+1} (one switch per
/// step), and the command of that same step already aims at W_{k+1}. At the last way-point
/// the index stays (chi = n) and the control law stays active on it, as in the paper (the robot
/// converges onto it and keeps correcting its heading, v = kd·d -> 0); `done` latches when it
/// is first within epsilon. With ControllerParams::stop_when_done the command is zero from then on.
/// Every command, the stop included, changes from the previous one within the acceleration limits.
class WaypointTracker {
 public:
  /// Validates params (std::invalid_argument, see ControllerParams::validate). `period_s`: the
  /// time between two step() calls (s), which the acceleration limits need (> 0 when one is set).
  explicit WaypointTracker(const ControllerParams& params = ControllerParams{}, double period_s = 0.0);

  /// Replaces the mission (world frame, m) and restarts at its first way-point. Throws
  /// std::invalid_argument, leaving the tracker unchanged, if the list is empty or a
  /// coordinate is not finite.
  void set_mission(std::vector<Eigen::Vector2d> waypoints_m);

  /// One control step from the pose estimate (x, y in m, theta in rad, any finite angle).
  /// Throws std::invalid_argument for a non-finite pose and std::logic_error without a
  /// mission; the tracker state is then unchanged. Allocation-free.
  TrackerOutput step(double x_m, double y_m, double theta_rad);
  /// As above, with the estimate's 2x2 position covariance (m^2, world frame) for the
  /// confidence-aware switch (ControllerParams::confidence_switch_sigmas). A covariance that is
  /// not finite or not positive definite (e.g. the zero covariance of the true pose) disables
  /// that rule for this step; eq. (19) applies as usual.
  TrackerOutput step(double x_m, double y_m, double theta_rad, const Eigen::Matrix2d& position_covariance_m2);

  /// The caller sent a stop instead of step()'s command (no estimate, ...): the acceleration
  /// limits count from a standstill command again.
  void command_stopped() { last_command_ = Command{}; }
  /// A command of the caller's instead of step()'s (e.g. creeping ahead until the estimate is
  /// valid), brought within the wheel-speed and acceleration limits like step()'s; no switching.
  Command hold(const Command& wanted);
  /// The command last returned by step() or hold() (zero after command_stopped()): what the node
  /// repeats while its estimate is late (common/estimate_age.hpp).
  const Command& last_command() const { return last_command_; }

  bool has_mission() const { return !mission_.empty(); }
  const std::vector<Eigen::Vector2d>& mission() const { return mission_; }
  std::size_t target_index() const { return target_index_; }
  std::size_t reached_count() const { return reach_distances_m_.size(); }
  bool done() const { return done_; }
  /// Distance (m) at the moment each way-point was declared reached, in mission order.
  const std::vector<double>& reach_distances_m() const { return reach_distances_m_; }
  const ControllerParams& params() const { return params_; }

 private:
  TrackerOutput step_impl(double x_m, double y_m, double theta_rad, const Eigen::Matrix2d* position_covariance_m2);
  /// `wanted` changed from the previous command within the acceleration limits; remembered.
  Command ramp(const Command& wanted);
  bool inside_confidence_ellipse(const Eigen::Vector2d& offset_m, const Eigen::Matrix2d* covariance_m2) const;

  ControllerParams params_;
  double period_s_ = 0.0;
  Command last_command_;  // what the previous step() returned (the acceleration limits' start)
  std::vector<Eigen::Vector2d> mission_;
  std::size_t target_index_ = 0;
  bool done_ = false;
  /// The start of the current leg (path_lookahead_m > 0): the previous way-point, or for the first
  /// leg the position of the first step after set_mission() (has_segment_start_ false until then).
  Eigen::Vector2d segment_start_m_ = Eigen::Vector2d::Zero();
  bool has_segment_start_ = false;
  std::vector<double> reach_distances_m_;
};

}  // namespace robodds::waypoint_controller

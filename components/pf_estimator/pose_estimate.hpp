#pragma once
// State output of paper 1, eq. (7): the weighted mean of the particles, extended to heading.

#include <cstddef>

#include <Eigen/Core>

#include "components/pf_estimator/particle_set.hpp"

namespace robodds::pf_estimator {

struct PoseEstimate {
  /// [x (m), y (m), theta (rad, (-pi, pi])], world frame.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  /// Weighted covariance of [x, y, theta] about `mean` (m^2, m rad, rad^2). Heading residuals
  /// are wrapped to (-pi, pi] before use. Normalised weights, no small-sample correction.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

/// x, y: sum_i w_i x_i (eq. 7). theta: circular mean atan2(sum w_i sin theta_i, sum w_i cos theta_i),
/// since an arithmetic mean of angles near +-pi points the wrong way.
/// `normalized_weights` must sum to 1 and have the size of `particles`.
PoseEstimate weighted_pose_estimate(const ParticleSet& particles,
                                    const Eigen::ArrayXd& normalized_weights);

/// The estimate moved on from the time of the last odometry sample to a later publication time
/// (issue 27): along the exact arc of that sample's twist (v m/s, omega rad/s) for age_s s, with the
/// heading variance grown by that sample's claimed turn-rate variance omega_var ((rad/s)^2) x age_s^2.
/// Between two odometry samples the cloud is the pose at the last one; at 50 Hz odometry and 100 Hz
/// publication every other estimate was one step old, 1.8 deg behind a robot spinning at 3.2 rad/s
/// (standstill_600s seed 3: the 51 samples beyond 3 heading sigmas). age_s <= 0 returns it unchanged.
PoseEstimate extrapolate_estimate(const PoseEstimate& estimate, double v_mps, double omega_radps,
                                  double omega_var_radps2, double age_s);

/// A usable estimate: sqrt(var x + var y) < max_position_std_m and, if max_heading_std_rad > 0,
/// sqrt(var theta) < max_heading_std_rad (a position alone does not steer a robot: issue 12).
bool is_valid(const PoseEstimate& estimate, double max_position_std_m, double max_heading_std_rad);

/// Validity with hysteresis on the heading. An estimate becomes valid within the `enter` limits
/// (is_valid) and, once valid, stays valid while its heading std is below `keep_max_heading_std_rad`
/// (>= enter; the position limit is the same both ways). Why: the heading of paper 1's filter is
/// observed only while the robot moves, and on turning missions its std hovers at the enter limit;
/// without a band `valid` flickers, every flicker stops the robot (the controller never drives on an
/// invalid estimate: issue 24), and a robot standing still cannot bring its heading std down again.
/// No defaults here: the component's parameters (pf_estimator_params) hold them.
struct ValidityLimits {
  double max_position_std_m = 0.0;         ///< m, > 0: sqrt(var x + var y) below this, both ways
  double enter_max_heading_std_rad = 0.0;  ///< rad, >= 0 (0 = heading not checked): to become valid
  double keep_max_heading_std_rad = 0.0;   ///< rad, >= enter: to stay valid once valid
};
bool next_validity(const PoseEstimate& estimate, const ValidityLimits& limits, bool was_valid);

/// `valid` of one filter's estimates over time (issue 27): valid only when the filter's measurements
/// confirm it, and with the band of next_validity counted from the first valid estimate since the
/// filter's last restart, not from the last estimate. A heading spread that passed the keep limit
/// while manoeuvring, on a robot the controller then stopped (issue 24: no creeping after a valid
/// estimate), cannot come back below the enter limit standing still, where it honestly grows; below
/// the keep limit the estimate is valid again. A restart (the cloud redrawn) must enter again.
class ValidityTracker {
 public:
  explicit ValidityTracker(const ValidityLimits& limits) : limits_(limits) {}
  /// `confirmed`: ParticleFilter::confirmed(); `restarts`: its recovery count.
  bool next(const PoseEstimate& estimate, bool confirmed, std::size_t restarts);

 private:
  ValidityLimits limits_;
  bool established_ = false;  // valid at some estimate since the last restart
  std::size_t restarts_ = 0;
};

}  // namespace robodds::pf_estimator

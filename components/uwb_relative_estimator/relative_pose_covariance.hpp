#pragma once
// Covariances that the eq. (1), eq. (2) and dead-reckoning stages report with their relative poses
// (issue 27: "every estimate topic carries an uncertainty that is consistent"; "noise estimated,
// not assumed"). A UWB range of one epoch is modelled as r_kl = d_kl(x) + u_kl + c: u_kl
// independent per node pair (white noise and the per-link bias, both seen in the epoch's
// residuals: estimated), c common to all K x L ranges of the robot pair (shifts every range alike:
// it moves the fit along the line between the robots and leaves no residual, so it cannot be
// estimated from one epoch and is configured). The eq. (1) pose is the least-squares fit; its
// covariance is the linearised sandwich (J^T J)^-1 J^T Cov(r) J (J^T J)^-1 at the solution.
// Pure: Eigen + std; m, rad; covariances of (x, y, theta) in m^2, m rad, rad^2.

#include <cstddef>
#include <deque>

#include <Eigen/Core>

#include "common/model/pose2.hpp"
#include "common/model/uwb_array.hpp"
#include "common/param_table.hpp"

namespace robodds::uwb_relative_estimator {

// Units, ranges and one-line descriptions: uncertainty_param_table() in relative_pose_covariance.cpp
// (the one source). Defaults: the initialisers.
struct UncertaintyParams {
  /// Floor of the estimated independent per-range std (the configured range noise): the estimate
  /// never goes below it, so a lucky run of small residuals does not make a stage over-confident.
  double range_std_floor_m = 0.05;
  /// Std of the error common to all ranges of a robot pair (not observable in one epoch).
  double range_common_std_m = 0.30;
  /// Epochs whose residual std form the running median of the independent range std.
  int noise_window_epochs = 50;
  /// Time constant of the common-mode range error (s): how long the particle filters' measurement
  /// errors stay alike (FilterErrorCovariance). The UWB sensor's pair common mode: 10 s.
  double range_common_time_s = 10.0;
  /// Time constant of each link's independent range error (s), the white part counted as lasting
  /// as long (conservative). The UWB sensor's link bias: 2 s.
  double range_link_time_s = 2.0;
  /// A range whose leave-one-out residual exceeds this many estimated range stds is an outlier
  /// (non-line-of-sight, a blocked link): it gets its own variance, that residual squared.
  double outlier_sigma = 3.0;
  /// Std of a range bias per UWB node (every link through a node shares it: an antenna's delay
  /// error, a node shadowed by a body or a board). Its pattern lies largely along the pose's own
  /// degrees of freedom (a node biased is a node moved), so the fit absorbs it into the heading
  /// and bearing and the residuals do not show it: configured, a "consider" parameter.
  double node_bias_std_m = 0.06;
  /// pf, pf_baseline: the epochs of eq. (1) fixes their estimates are checked against
  /// (InnovationMonitor: the fixes' median innovation beyond their own covariance is added).
  int innovation_window_epochs = 50;
  /// pf, pf_baseline: a filter is lost, and restarted at its estimate plus the fixes' median
  /// innovation, when that innovation's squared Mahalanobis distance, against the fixes' mean
  /// covariance plus the filter's own error covariance, exceeds this (InnovationMonitor::lost).
  double lost_filter_d2 = 16.27;
  /// pf, pf_baseline: ... or when its mean over the last lost_window_epochs epochs exceeds this.
  double lost_mean_d2 = 4.0;
  int lost_window_epochs = 200;
  /// uwb: the fix-track check (FixTrackCheck): each fix against the fix of this long ago
  /// dead-reckoned by odometry; the fixes' error that changes over the lag, beyond what the error
  /// model says, scales the stage's covariance. 0: off.
  /// 20 s: the common mode (10 s) and the node term are mostly forgotten, so their changes show;
  /// the configured odometry noise over 20 s stays below the fixes' own spread.
  double fix_check_lag_s = 20.0;
  /// uwb: the tests (one per fix) whose mean statistics give the scales.
  int fix_check_window_epochs = 100;
  /// Throws std::invalid_argument "key: requirement (got value)".
  void validate() const;
};

const params::ParamTable<UncertaintyParams>& uncertainty_param_table();

/// Robust std of one range from one epoch's residuals r_kl - d_kl(pose): 1.4826 x the median
/// absolute residual (MAD about zero: the fit's residuals have mean ~0), times sqrt(n / (n - 3))
/// for the three fitted parameters. 0 when n <= 3 (no degree of freedom left). `ranges_m` must
/// match the arrays (require_valid_ranges).
double robust_residual_std_m(const model::UwbArray& own, const model::UwbArray& other, const Eigen::MatrixXd& ranges_m,
                             const model::Pose2& pose);

/// Plain std of one range from one epoch's residuals: sqrt(sum r_kl^2 / (n - 3)). Not robust on
/// purpose: a range far off that the fit followed (plain least squares, or Huber within its scale)
/// moved the pose, and this epoch's covariance should say so. 0 when n <= 3.
double residual_rms_std_m(const model::UwbArray& own, const model::UwbArray& other, const Eigen::MatrixXd& ranges_m,
                          const model::Pose2& pose);

/// Covariance of the least-squares eq. (1) pose at `pose` when every range has an independent error
/// of std `independent_std_m` and all share one of std `common_std_m`:
/// s_i^2 (J^T J)^-1 + s_c^2 a a^T, a = (J^T J)^-1 J^T 1, J the K L x 3 Jacobian of the predicted
/// ranges. NaN entries when J^T J is singular (a degenerate geometry: nothing to report).
Eigen::Matrix3d range_fix_covariance(const model::UwbArray& own, const model::UwbArray& other, const model::Pose2& pose,
                                     double independent_std_m, double common_std_m);

/// How one epoch's range errors reach a least-squares pose fit at `pose`: e_pose = B u + a c + N b
/// for the K L independent range errors u (variance independent_variance_m2(k) each, row-major
/// k = K index x L + L index), the common one c (std common_std_m) and the K + L per-node biases b
/// (std node_bias_std_m each: own nodes first, then the peer's); B = (J^T J)^-1 J^T (3 x K L),
/// a = B 1, N = B V with V's columns the node patterns centred per array (link kl gets b_k - mean
/// of the own nodes' b, plus b_l - mean of the peer's: the means are the common mode's).
/// With equal variances s_i^2 and no node bias, covariance() is range_fix_covariance's.
struct RangeErrorMap {
  Eigen::Matrix<double, 3, Eigen::Dynamic> independent_map;  // B
  Eigen::Vector3d common_map = Eigen::Vector3d::Zero();      // a
  Eigen::Matrix<double, 3, Eigen::Dynamic> node_map;         // N (3 x (K + L))
  Eigen::VectorXd independent_variance_m2;                    // per range
  double common_std_m = 0.0;
  double node_bias_std_m = 0.06;
  /// B diag(independent_variance_m2) B^T + s_c^2 a a^T + s_n^2 N N^T.
  Eigen::Matrix3d covariance() const;
};

/// The map at `pose` with every range's independent std `independent_std_m`; false (and `out`
/// untouched) when J^T J is singular (degenerate geometry).
bool range_error_map(const model::UwbArray& own, const model::UwbArray& other, const model::Pose2& pose,
                     double independent_std_m, double common_std_m, RangeErrorMap& out, double node_bias_std_m = 0.0);

/// Per-range variances of one epoch's independent range errors at the least-squares fit `pose`:
/// base_std_m^2, except for a range whose leave-one-out (jackknife) residual r_k / (1 - h_k)
/// (h_k its leverage, J_k (J^T J)^-1 J_k^T) exceeds outlier_sigma x detect_std_m: that residual
/// squared. A range far off moves the fit by B_k times its error, and r_k / (1 - h_k) is that
/// error when it is the only one. A vector of base_std_m^2 when J^T J is singular. `ranges_m` must
/// match the arrays (require_valid_ranges).
Eigen::VectorXd range_error_variances(const model::UwbArray& own, const model::UwbArray& other,
                                      const Eigen::MatrixXd& ranges_m, const model::Pose2& pose, double base_std_m,
                                      double detect_std_m, double outlier_sigma);

/// `covariance` of a relative pose at `pose` plus the second-order term of its bearing: ranges fix
/// the distance R and leave the bearing phi less certain, so the peer lies on an arc, not on the
/// tangent the linearised covariance draws; a bearing error phi moves it towards this robot by
/// R (1 - cos phi) ~ R phi^2 / 2. Adds E[(R phi^2 / 2)^2] = 3 R^2 sigma_phi^4 / 4 along the line of
/// sight, sigma_phi^2 = (tangential variance) / R^2 capped at 1 rad^2. Negligible while the bearing
/// is well known (0.5 m arrays at 5 m: ~1 cm next to a 0.3 m radial sigma); the 0.25 m arrays'
/// bearing sigmas of 0.3-0.6 rad give 0.1-0.6 m. Unchanged at R = 0 or with a non-finite covariance.
Eigen::Matrix3d with_bearing_curvature(const Eigen::Matrix3d& covariance, const model::Pose2& pose);

/// Jacobian of x' = inverse(m_i) x m_j (the dead reckoning of a relative pose over one epoch) with
/// respect to (x, m_i, m_j) stacked (3 x 9; central differences, heading differences wrapped).
Eigen::Matrix<double, 3, 9> relative_motion_jacobian(const model::Pose2& x, const model::Pose2& own_increment,
                                                     const model::Pose2& other_increment);

/// Dead reckoning of a relative pose x (peer j in robot i's frame) over one epoch,
/// x' = inverse(m_i) x m_j: the covariance P of x propagated to x', plus both increments' noise
/// (std `xy_std_m` on x and y, `theta_std_rad` on theta, independent per robot and epoch).
Eigen::Matrix3d propagate_relative_covariance(const Eigen::Matrix3d& covariance, const model::Pose2& x,
                                              const model::Pose2& own_increment, const model::Pose2& other_increment,
                                              double xy_std_m, double theta_std_rad);

/// The independent range std one (robot, peer) pair sees: the running median of the last
/// noise_window_epochs per-epoch robust_residual_std_m (robust over time too: an epoch with
/// a non-line-of-sight range does not move it), never below the floor.
class RangeNoiseLevel {
 public:
  explicit RangeNoiseLevel(const UncertaintyParams& params);
  /// One epoch's robust residual std (m, >= 0).
  void add(double residual_std_m);
  /// The running median, at least the floor (the floor before the first add()).
  double std_m() const;

 private:
  UncertaintyParams params_;
  std::deque<double> recent_;
};

}  // namespace robodds::uwb_relative_estimator
